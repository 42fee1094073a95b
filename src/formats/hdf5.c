/* Plain HDF5 files read with libhdf5 in this process: what indentmap-hdf5-read runs (hdf5_child.c reads it
 * from there) and what fuzz/fuzz_hdf5.c feeds. Every 2-D numeric data set, in the order libhdf5 visits
 * them (by name, groups included), is a channel; 1-D data sets are line scans and are not. As
 * SurfaceTopography reads them, the first index of a data set runs along x and the second along y, and
 * the file states no spacing or unit: a bare matrix. */
#include "indentmap/formats.h"
#include "indentmap/io.h"

#include "indentmap/status.h"
#include "formats/hdf5.h"

#include <ctype.h>
#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

enum { MAX_DATA_SETS = 1024 };

typedef struct data_set {
    char *name;
    hsize_t nx, ny;
} data_set;

typedef struct data_sets {
    data_set maps[MAX_DATA_SETS]; /* 2-D numeric: the channels */
    int map_count;
    int line_count; /* 1-D numeric: line scans */
} data_sets;

/* Rank and sizes of a numeric data set; 0 for anything else (text, compound, empty, or numbers wider
 * than 16 bytes: a damaged type, whose conversion buffer libhdf5 would size by it). */
static int numeric_rank(hid_t file, const char *name, hsize_t dims[2])
{
    hid_t set = H5Dopen2(file, name, H5P_DEFAULT);
    if (set < 0)
        return 0;
    hid_t type = H5Dget_type(set), space = H5Dget_space(set);
    H5T_class_t kind = type >= 0 ? H5Tget_class(type) : H5T_NO_CLASS;
    int rank = space >= 0 ? H5Sget_simple_extent_ndims(space) : -1;
    size_t width = type >= 0 ? H5Tget_size(type) : 0;
    if (rank < 1 || rank > 2 || (kind != H5T_INTEGER && kind != H5T_FLOAT) || width < 1 || width > 16 ||
        H5Sget_simple_extent_dims(space, dims, NULL) != rank || dims[0] < 1 || (rank == 2 && dims[1] < 1))
        rank = 0;
    if (space >= 0)
        H5Sclose(space);
    if (type >= 0)
        H5Tclose(type);
    H5Dclose(set);
    return rank;
}

static herr_t take_data_set(hid_t file, const char *name, const H5O_info_t *about, void *sets_)
{
    data_sets *sets = sets_;
    hsize_t dims[2] = {0, 0};
    int rank = about->type == H5O_TYPE_DATASET ? numeric_rank(file, name, dims) : 0;
    if (rank == 1)
        ++sets->line_count;
    if (rank != 2 || sets->map_count == MAX_DATA_SETS)
        return 0;
    char *copy = strdup(name);
    if (!copy)
        return -1;
    sets->maps[sets->map_count++] = (data_set){.name = copy, .nx = dims[0], .ny = dims[1]};
    return 0;
}

static void free_data_sets(data_sets *sets)
{
    for (int k = 0; k < sets->map_count; ++k)
        free(sets->maps[k].name);
}

/* "0 'dataset1' (256 x 256), 1 'dataset2' (640 x 480)" for messages. */
static void list_data_sets(const data_sets *sets, char *list, size_t size)
{
    size_t used = 0;
    list[0] = '\0';
    for (int k = 0; k < sets->map_count && used + 1 < size; ++k)
        used += (size_t)snprintf(list + used, size - used, "%s%d '%.40s' (%llu x %llu)", k ? ", " : "", k,
                                 sets->maps[k].name, (unsigned long long)sets->maps[k].nx,
                                 (unsigned long long)sets->maps[k].ny);
}

static int all_digits(const char *text)
{
    for (const char *c = text; *c; ++c)
        if (!isdigit((unsigned char)*c))
            return 0;
    return *text != '\0';
}

/* The channel asked for (an index, or a name with or without its leading '/', case ignored), else the
 * first, into *k; IM_EFORMAT listing the data sets when there is none. */
static int choose(const char *path, const data_sets *sets, const char *asked, int *k)
{
    char list[1024];
    list_data_sets(sets, list, sizeof list);
    if (sets->map_count == 0)
        return im_fail(IM_EFORMAT,
                       "%s: HDF5 file without a 2-D numeric data set (%d 1-D: line scans, which a 2-D "
                       "contact solver cannot indent): expected a data set of heights (x, y)",
                       path, sets->line_count);
    for (*k = 0; asked[0] && *k < sets->map_count; ++*k) {
        const char *name = sets->maps[*k].name;
        if ((all_digits(asked) && atol(asked) == *k) || strcasecmp(asked, name) == 0 ||
            (asked[0] == '/' && strcasecmp(asked + 1, name) == 0))
            return IM_OK;
    }
    if (!asked[0])
        return IM_OK;
    return im_fail(IM_EFORMAT,
                   "%s: no channel has the index or name '%s'; its 2-D data sets: %s; choose one with "
                   "--channel",
                   path, asked, list);
}

void hdf5_scatter_slab(im_field *field, const double *values, int x0, int rows)
{
    for (int x = 0; x < rows; ++x)
        for (int y = 0; y < field->ny; ++y)
            field->data[(size_t)y * field->nx + x0 + x] = values[(size_t)x * field->ny + y];
}

void hdf5_gather_slab(const im_field *field, double *values, int x0, int rows)
{
    for (int x = 0; x < rows; ++x)
        for (int y = 0; y < field->ny; ++y)
            values[(size_t)x * field->ny + y] = field->data[(size_t)y * field->nx + x0 + x];
}

/* Reads data set [x, y] in slabs of HDF5_SLAB_ROWS x-rows, each handed to the sink as it is read. */
static int read_slabs(hid_t file, const char *path, const data_set *chosen, const hdf5_sink *sink)
{
    hid_t set = H5Dopen2(file, chosen->name, H5P_DEFAULT);
    hid_t space = set >= 0 ? H5Dget_space(set) : -1;
    double *slab = malloc(sizeof *slab * HDF5_SLAB_ROWS * chosen->ny);
    herr_t error = set < 0 || space < 0 || !slab ? -1 : 0;
    int status = IM_OK;
    for (hsize_t x0 = 0; error >= 0 && status == IM_OK && x0 < chosen->nx; x0 += HDF5_SLAB_ROWS) {
        hsize_t rows = chosen->nx - x0 < HDF5_SLAB_ROWS ? chosen->nx - x0 : HDF5_SLAB_ROWS;
        hsize_t start[2] = {x0, 0}, count[2] = {rows, chosen->ny};
        hid_t memory = H5Screate_simple(2, count, NULL);
        error = memory < 0 ? -1 : H5Sselect_hyperslab(space, H5S_SELECT_SET, start, NULL, count, NULL);
        if (error >= 0)
            error = H5Dread(set, H5T_NATIVE_DOUBLE, memory, space, H5P_DEFAULT, slab);
        if (error >= 0)
            status = sink->slab(sink->context, slab, (int)x0, (int)rows);
        if (memory >= 0)
            H5Sclose(memory);
    }
    free(slab);
    if (space >= 0)
        H5Sclose(space);
    if (set >= 0)
        H5Dclose(set);
    if (status != IM_OK)
        return status;
    return error < 0 ? im_fail(IM_EFORMAT,
                               "%s: data set '%.200s': libhdf5 cannot read its %llu x %llu values as "
                               "numbers",
                               path, chosen->name, (unsigned long long)chosen->nx, (unsigned long long)chosen->ny)
                     : IM_OK;
}

static int read_chosen(hid_t file, const char *path, const data_sets *sets, int k, const hdf5_sink *sink)
{
    const data_set *chosen = &sets->maps[k];
    if (chosen->nx > IM_FIELD_MAX_SIDE || chosen->ny > IM_FIELD_MAX_SIDE)
        return im_fail(IM_EFORMAT, "%s: data set '%.200s' is %llu x %llu: expected each side in [1, %d]", path,
                       chosen->name, (unsigned long long)chosen->nx, (unsigned long long)chosen->ny,
                       IM_FIELD_MAX_SIDE);
    surface_stated stated = {.spacing_keys = "--delta", .lateral_key = "--unit", .height_key = "--height-unit"};
    snprintf(stated.conversion, sizeof stated.conversion, "HDF5 data set '%.40s', channel %d of %d, indexed [x, y]",
             chosen->name, k, sets->map_count);
    int status = sink->begin(sink->context, path, (int)chosen->nx, (int)chosen->ny, &stated);
    return status == IM_OK ? read_slabs(file, path, chosen, sink) : status;
}

static int read_file(hid_t file, const char *path, const im_surface_read_options *options, const hdf5_sink *sink)
{
    data_sets *sets = calloc(1, sizeof *sets);
    if (!sets)
        return im_fail(IM_ENOMEM, "%s: allocation of the data set list failed", path);
    int status = IM_OK;
    if (H5Ovisit(file, H5_INDEX_NAME, H5_ITER_INC, take_data_set, sets) < 0)
        status = im_fail(IM_EFORMAT, "%s: libhdf5 cannot list the file's data sets (a damaged HDF5 file)", path);
    int k = 0;
    if (status == IM_OK)
        status = choose(path, sets, options ? options->channel : "", &k);
    if (status == IM_OK)
        status = read_chosen(file, path, sets, k, sink);
    free_data_sets(sets);
    free(sets);
    return status;
}

/* libhdf5's error stack, silenced while a file is open (it prints it otherwise: the messages say it). */
typedef struct quiet_file {
    hid_t file;
    H5E_auto2_t report;
    void *report_data;
} quiet_file;

static int open_quietly(const char *path, quiet_file *opened)
{
    FILE *stream;
    int status = im_read_open(path, "rb", IM_READ_REGULAR, &stream, NULL);
    if (status != IM_OK)
        return status;
    fclose(stream);
    H5Eget_auto2(H5E_DEFAULT, &opened->report, &opened->report_data);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    opened->file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    if (opened->file >= 0)
        return IM_OK;
    H5Eset_auto2(H5E_DEFAULT, opened->report, opened->report_data);
    return im_fail(IM_EFORMAT, "%s: libhdf5 cannot open it: expected an HDF5 file (magic 89 'HDF' 0D 0A 1A 0A)",
                   path);
}

static void close_quietly(quiet_file *opened)
{
    H5Fclose(opened->file);
    H5Eset_auto2(H5E_DEFAULT, opened->report, opened->report_data);
}

int hdf5_read_into(const char *path, const im_surface_read_options *options, const hdf5_sink *sink)
{
    quiet_file opened;
    int status = open_quietly(path, &opened);
    if (status != IM_OK)
        return status;
    status = read_file(opened.file, path, options, sink);
    close_quietly(&opened);
    return status;
}

int hdf5_is_netcdf4(const char *path)
{
    quiet_file opened;
    if (open_quietly(path, &opened) != IM_OK)
        return 0;
    int netcdf4 = H5Aexists(opened.file, "_NCProperties") > 0;
    close_quietly(&opened);
    return netcdf4;
}

/* The in-process sink: the field, and what the file states. */
typedef struct field_sink {
    im_field *field;
    surface_stated *stated;
} field_sink;

static int field_begin(void *context, const char *path, int nx, int ny, const surface_stated *stated)
{
    field_sink *sink = context;
    *sink->stated = *stated;
    int status = im_field_create(nx, ny, 1.0, &sink->field);
    return status == IM_OK ? IM_OK : im_fail_context(status, "%s", path);
}

static int field_slab(void *context, const double *values, int x0, int rows)
{
    hdf5_scatter_slab(((field_sink *)context)->field, values, x0, rows);
    return IM_OK;
}

int hdf5_read_in_process(const char *path, const im_surface_read_options *options, im_field **out,
                         surface_stated *stated)
{
    field_sink into = {.stated = stated};
    int status = hdf5_read_into(path, options,
                                &(hdf5_sink){.begin = field_begin, .slab = field_slab, .context = &into});
    if (status != IM_OK)
        im_field_free(into.field);
    *out = status == IM_OK ? into.field : NULL;
    return status;
}
