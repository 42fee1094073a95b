/* NetCDF surfaces in the layout of ContactMechanics/SurfaceTopography and contact.engineering:
 * dimensions x and y, a variable heights(x, y) (the first index is x), and variables x(x) and y(y)
 * whose attributes `length` (the physical size along that direction), `length_unit` (the unit of
 * lengths and heights alike) and `periodic` describe the grid. */
#define _DEFAULT_SOURCE /* madvise(MADV_DONTNEED): glibc ignores posix_madvise's */
#include "indentmap/formats.h"
#include "indentmap/io.h"
#include "core/args.h"

#include "indentmap/status.h"
#include "formats/payload.h"
#include "formats/hdf5.h"
#include "formats/readers.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <netcdf.h>
#include <stdint.h>
#include <netcdf_mem.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

/* IM_EFORMAT naming the file, what was being read, and netCDF's own message. */
static int nc_failure(const char *path, const char *what, int error)
{
    return im_fail(IM_EFORMAT, "%s: %s: %s", path, what, nc_strerror(error));
}

/* The length of dimension `name`; IM_EFORMAT naming it when it is missing. */
static int dimension(int ncid, const char *path, const char *name, int *id, size_t *length)
{
    int error = nc_inq_dimid(ncid, name, id);
    if (error == NC_NOERR)
        error = nc_inq_dimlen(ncid, *id, length);
    if (error != NC_NOERR)
        return im_fail(IM_EFORMAT, "%s: dimension '%s': %s (expected dimensions x and y)", path, name,
                       nc_strerror(error));
    if (*length < 1 || *length > IM_FIELD_MAX_SIDE)
        return im_fail(IM_EFORMAT, "%s: dimension %s = %zu: expected 1 to %d", path, name, *length,
                       IM_FIELD_MAX_SIDE);
    return IM_OK;
}

/* The variable heights with dimensions (x, y) or (y, x); *x_first tells which. */
static int heights_variable(int ncid, const char *path, int x_dim, int y_dim, int *var, int *x_first)
{
    int error = nc_inq_varid(ncid, "heights", var), ndims = 0, dims[NC_MAX_VAR_DIMS];
    nc_type type;
    if (error == NC_NOERR)
        error = nc_inq_var(ncid, *var, NULL, &type, &ndims, NULL, NULL);
    if (error != NC_NOERR)
        return nc_failure(path, "variable 'heights'", error);
    if (ndims != 2)
        return im_fail(IM_EFORMAT, "%s: variable heights has %d dimensions: expected heights(x, y)", path, ndims);
    nc_inq_vardimid(ncid, *var, dims);
    if (!((dims[0] == x_dim && dims[1] == y_dim) || (dims[0] == y_dim && dims[1] == x_dim)))
        return im_fail(IM_EFORMAT, "%s: variable heights: expected dimensions (x, y)", path);
    if (type == NC_CHAR || type == NC_STRING)
        return im_fail(IM_EFORMAT, "%s: variable heights holds text: expected numbers", path);
    *x_first = dims[0] == x_dim;
    return IM_OK;
}

/* A short text attribute (a unit name) of variable var into unit (16 bytes), when present; IM_EFORMAT
 * naming "NAME:ATTRIBUTE" when it is not a text of 1 to 15 bytes. */
static int unit_attribute(int ncid, int var, const char *path, const char *name, const char *attribute, char *unit)
{
    nc_type type;
    size_t count;
    if (nc_inq_att(ncid, var, attribute, &type, &count) != NC_NOERR)
        return IM_OK;
    if (type != NC_CHAR || count < 1 || count > 15 || nc_get_att_text(ncid, var, attribute, unit))
        return im_fail(IM_EFORMAT, "%s: %s:%s: expected a short text (a unit)", path, name, attribute);
    unit[count] = '\0';
    return IM_OK;
}

/* Attribute `length` of the coordinate variable `name`, when present, gives the spacing length /
 * points; its unit is `unit` (SurfaceTopography and contact.engineering today) or `length_unit` (their
 * older files). IM_EFORMAT naming the attribute when malformed. */
static int coordinate(int ncid, const char *path, const char *name, size_t points, double *spacing, char *unit)
{
    int var;
    if (nc_inq_varid(ncid, name, &var) != NC_NOERR)
        return IM_OK; /* optional: then the grid has no physical size */
    nc_type type;
    size_t count;
    if (nc_inq_att(ncid, var, "length", &type, &count) == NC_NOERR) {
        double length = NAN;
        if (count != 1 || type == NC_CHAR || type == NC_STRING || nc_get_att_double(ncid, var, "length", &length) ||
            !isfinite(length) || !(length > 0.0))
            return im_fail(IM_EFORMAT, "%s: %s:length: expected one finite number > 0", path, name);
        *spacing = length / (double)points;
    }
    int status = unit_attribute(ncid, var, path, name, "length_unit", unit);
    return status == IM_OK ? unit_attribute(ncid, var, path, name, "unit", unit) : status;
}

/* The variable's fill value as a double: its _FillValue, or netCDF's default fill for its type,
 * which is what a reader gets for values never written, e.g. past the end of a truncated file. */
static int fill_value(int ncid, int var, double *fill)
{
    nc_type type;
    union {
        signed char b;
        unsigned char ub;
        short s;
        unsigned short us;
        int i;
        unsigned int ui;
        long long ll;
        unsigned long long ull;
        float f;
        double d;
    } v;
    int no_fill = 0;
    if (nc_inq_vartype(ncid, var, &type) != NC_NOERR || nc_inq_var_fill(ncid, var, &no_fill, &v) != NC_NOERR)
        return 0;
    switch (type) {
    case NC_BYTE: *fill = v.b; break;
    case NC_UBYTE: *fill = v.ub; break;
    case NC_SHORT: *fill = v.s; break;
    case NC_USHORT: *fill = v.us; break;
    case NC_INT: *fill = v.i; break;
    case NC_UINT: *fill = v.ui; break;
    case NC_INT64: *fill = (double)v.ll; break;
    case NC_UINT64: *fill = (double)v.ull; break;
    case NC_FLOAT: *fill = v.f; break;
    default: *fill = v.d;
    }
    return 1;
}

/* Values equal to the fill value are missing points (NaN): refused, or filled on request. */
static void mark_fill_values(int ncid, int var, im_field *field)
{
    double fill;
    if (!fill_value(ncid, var, &fill))
        return;
    size_t n = im_field_count(field);
    for (size_t i = 0; i < n; ++i)
        if (field->data[i] == fill)
            field->data[i] = NAN;
}

typedef struct mapped_file {
    void *bytes; /* NULL when netCDF reads the file itself */
    size_t size;
} mapped_file;

enum { SLAB = 64 }; /* rows of the stored array read at a time */

/* Pages of the mapped file already read are clean copies of the page cache: dropping them keeps the
 * reader's resident memory near the field's own (they fault back in if netCDF needs them again). */
static void release_pages(const mapped_file *file)
{
    if (file->bytes)
        madvise(file->bytes, file->size, MADV_DONTNEED);
}

/* heights into the row-major field (row y), SLAB stored rows at a time: stored as (y, x), straight
 * into the field; stored as (x, y) (SurfaceTopography's order), through a slab transposed here. */
static int read_heights(int ncid, const char *path, int var, int x_first, im_field *field, const mapped_file *file)
{
    size_t nx = (size_t)field->nx, ny = (size_t)field->ny, rows = x_first ? nx : ny, length = x_first ? ny : nx;
    double *slab = x_first ? malloc(SLAB * length * sizeof *slab) : NULL;
    if (x_first && !slab)
        return im_fail(IM_ENOMEM, "%s: heights: allocation of a %d x %zu slab failed", path, SLAB, length);
    int error = NC_NOERR;
    for (size_t row = 0; error == NC_NOERR && row < rows; row += SLAB) {
        size_t count[2] = {rows - row < SLAB ? rows - row : SLAB, length}, start[2] = {row, 0};
        error = nc_get_vara_double(ncid, var, start, count, x_first ? slab : field->data + row * nx);
        for (size_t ix = row; error == NC_NOERR && x_first && ix < row + count[0]; ++ix)
            for (size_t iy = 0; iy < ny; ++iy)
                field->data[iy * nx + ix] = slab[(ix - row) * ny + iy];
        release_pages(file);
    }
    free(slab);
    if (error != NC_NOERR)
        return nc_failure(path, "variable heights (truncated?)", error);
    mark_fill_values(ncid, var, field);
    return IM_OK;
}

/* A classic file must hold the nx x ny values that heights declares before the field is allocated:
 * netCDF takes the data's size from the dimensions, not from the header's vsize, so a 3 KB file whose
 * dimensions claimed 63555 x 14082 made the reader allocate 7.2 GB (found with fuzz/fuzz_netcdf).
 * NetCDF-4 files compress their data, so no such bound holds for them. */
static int check_heights_fit(int ncid, const char *path, int var, size_t nx, size_t ny, const mapped_file *file)
{
    nc_type type;
    size_t value_size = 0;
    if (!file->bytes || nc_inq_vartype(ncid, var, &type) != NC_NOERR || nc_inq_type(ncid, type, NULL, &value_size))
        return IM_OK;
    /* nx and ny are at most IM_FIELD_MAX_SIDE, the value size at most 8: no overflow */
    unsigned long long needed = (unsigned long long)nx * ny * value_size;
    if (needed <= file->size)
        return IM_OK;
    return im_fail(IM_EFORMAT,
                   "%s: truncated: heights (%zu x %zu values of %zu bytes) needs %llu bytes, the file has %zu", path,
                   nx, ny, value_size, needed, file->size);
}

static int read_open(int ncid, const char *path, im_field **out, surface_stated *stated, const mapped_file *file)
{
    int x_dim, y_dim, var, x_first;
    size_t nx, ny;
    int status = dimension(ncid, path, "x", &x_dim, &nx);
    if (status == IM_OK)
        status = dimension(ncid, path, "y", &y_dim, &ny);
    if (status == IM_OK)
        status = heights_variable(ncid, path, x_dim, y_dim, &var, &x_first);
    if (status == IM_OK)
        status = check_heights_fit(ncid, path, var, nx, ny, file);
    char x_unit[16] = "", y_unit[16] = "";
    if (status == IM_OK)
        status = coordinate(ncid, path, "x", nx, &stated->units.delta_x, x_unit);
    if (status == IM_OK)
        status = coordinate(ncid, path, "y", ny, &stated->units.delta_y, y_unit);
    if (status == IM_OK && y_unit[0] && strcmp(x_unit, y_unit) != 0)
        status = im_fail(IM_EFORMAT, "%s: x's unit '%s' and y's unit '%s' differ: expected one unit", path, x_unit,
                         y_unit);
    char height_unit[16] = "";
    if (status == IM_OK)
        status = unit_attribute(ncid, var, path, "heights", "unit", height_unit);
    if (status == IM_OK && (status = im_field_create((int)nx, (int)ny, 1.0, out)) != IM_OK)
        im_fail_context(status, "%s", path);
    if (status == IM_OK && (status = read_heights(ncid, path, var, x_first, *out, file)) != IM_OK) {
        im_field_free(*out);
        *out = NULL;
    }
    memcpy(stated->units.lateral, x_unit, sizeof x_unit);
    memcpy(stated->units.height, height_unit[0] ? height_unit : x_unit, sizeof height_unit);
    if (height_unit[0])
        stated->height_key = "heights:unit";
    return status;
}

/* ---- a walk over a classic header before netCDF parses it ----
 * netCDF allocates each name, attribute and list by the counts the header states before it finds
 * the file too short for them: a hostile 88-byte header made it allocate gigabytes (found with
 * fuzz/fuzz_netcdf). The walk checks every count against the bytes that remain, and that every
 * fixed-size variable's data (begin + vsize) lies inside the file. The layout is the netCDF classic
 * format specification's (CDF1, CDF2 64-bit offset, CDF5 64-bit data). */
typedef struct header_walk {
    const unsigned char *bytes;
    size_t size, at;
    int version; /* 1, 2 or 5 */
} header_walk;

/* A big-endian unsigned integer of `width` bytes; 0 (and the walk at its end) past the end. */
static uint64_t take(header_walk *w, int width)
{
    uint64_t value = 0;
    if (w->size - w->at < (size_t)width) {
        w->at = w->size + 1; /* marks the walk as failed */
        return 0;
    }
    for (int i = 0; i < width; ++i)
        value = value << 8 | w->bytes[w->at++];
    return value;
}

static int failed(const header_walk *w) { return w->at > w->size; }
static int count_width(const header_walk *w) { return w->version == 5 ? 8 : 4; }

/* Skips count items of `item` bytes each, padded to 4, when they fit in what remains. */
static void skip(header_walk *w, uint64_t count, unsigned item)
{
    uint64_t remaining = failed(w) ? 0 : w->size - w->at;
    if (item == 0 || count > remaining / item) {
        w->at = w->size + 1;
        return;
    }
    uint64_t bytes = (count * item + 3) / 4 * 4;
    w->at = bytes > remaining ? w->size + 1 : w->at + (size_t)bytes;
}

static void skip_name(header_walk *w) { skip(w, take(w, count_width(w)), 1); }

static unsigned type_size(uint64_t type)
{
    static const unsigned SIZES[] = {0, 1, 1, 2, 4, 4, 8, 1, 2, 4, 8, 8};
    return type < sizeof SIZES / sizeof *SIZES ? SIZES[type] : 0;
}

/* A list: its tag (0 when absent) and element count; the walk fails on another tag. */
static uint64_t list_count(header_walk *w, uint64_t tag)
{
    uint64_t found = take(w, 4), count = take(w, count_width(w));
    if (found != tag && !(found == 0 && count == 0))
        w->at = w->size + 1;
    return count;
}

static void skip_attributes(header_walk *w)
{
    uint64_t count = list_count(w, 0x0C);
    for (uint64_t i = 0; i < count && !failed(w); ++i) {
        skip_name(w);
        unsigned size = type_size(take(w, 4));
        skip(w, take(w, count_width(w)), size);
    }
}

/* Dimensions, attributes and variables; each fixed-size variable's data must lie in the file and
 * each variable's type must be one of netCDF's. -1: a count or name runs past the end; 1: data
 * past the end; 2: a variable of no known type (netCDF then divided by its size 0); 0: whole. */
static int walk_header(header_walk *w, size_t *dims_out)
{
    take(w, 4);              /* magic and version */
    take(w, count_width(w)); /* numrecs */
    uint64_t dims = list_count(w, 0x0A);
    uint64_t *lengths = dims && dims < w->size ? calloc((size_t)dims, sizeof *lengths) : NULL;
    for (uint64_t i = 0; i < dims && lengths && !failed(w); ++i) {
        skip_name(w);
        lengths[i] = take(w, count_width(w));
    }
    skip_attributes(w);
    uint64_t vars = list_count(w, 0x0B);
    int outside = 0, unknown_type = 0;
    for (uint64_t i = 0; i < vars && !failed(w) && !outside; ++i) {
        skip_name(w);
        uint64_t rank = take(w, count_width(w)), record = 0;
        for (uint64_t d = 0; d < rank && !failed(w); ++d) {
            uint64_t id = take(w, count_width(w));
            record |= id >= dims || !lengths || lengths[id] == 0; /* the record dimension, or a bad id */
        }
        skip_attributes(w);
        unknown_type |= type_size(take(w, 4)) == 0; /* nc_type: netCDF divides by its size */
        uint64_t vsize = take(w, count_width(w)), begin = take(w, w->version == 1 ? 4 : 8);
        outside = !record && (begin > w->size || vsize > w->size - begin);
    }
    free(lengths);
    *dims_out = (size_t)dims;
    return failed(w) || (dims && !lengths) ? -1 : outside ? 1 : unknown_type ? 2 : 0;
}

static int check_classic_header(const char *path, const unsigned char *bytes, size_t size)
{
    header_walk w = {bytes, size, 0, size > 3 ? bytes[3] : 0};
    if (w.version != 1 && w.version != 2 && w.version != 5)
        return im_fail(IM_EFORMAT, "%s: not a netCDF classic file (version byte %d)", path, w.version);
    size_t dims = 0;
    int result = walk_header(&w, &dims);
    if (result < 0)
        return im_fail(IM_EFORMAT, "%s: netCDF header: a count or name runs past the end of the file (%zu bytes)",
                       path, size);
    if (result == 1)
        return im_fail(IM_EFORMAT, "%s: truncated: a variable's data lies past the end of the file (%zu bytes)", path,
                       size);
    if (result == 2)
        return im_fail(IM_EFORMAT, "%s: netCDF header: a variable of no known type (expected a classic nc_type)",
                       path);
    return IM_OK;
}

/* 1 when the stream starts as a classic file does ("CDF" and a version byte). */
static int starts_classic(FILE *stream)
{
    unsigned char magic[4] = {0};
    return fread(magic, 1, 4, stream) == 4 && memcmp(magic, "CDF", 3) == 0;
}

/* Opens the dataset. A classic file (CDF1, CDF2, CDF5) is mapped into memory and opened from there:
 * netCDF then refuses to read past its end, where reading the file directly would return zeros for
 * the values of a truncated file. NetCDF-4 (HDF5) files are opened directly (HDF5 checks its own
 * structure). */
static int open_dataset(const char *path, mapped_file *file, int *ncid)
{
    *file = (mapped_file){NULL, 0};
    FILE *stream;
    long long size;
    int error, status = im_read_open(path, "rb", IM_READ_REGULAR, &stream, &size); /* never a FIFO or device */
    if (status != IM_OK)
        return status;
    int classic = starts_classic(stream);
    if (classic) {
        file->size = (size_t)size;
        file->bytes = mmap(NULL, file->size, PROT_READ, MAP_PRIVATE, fileno(stream), 0);
        if (file->bytes == MAP_FAILED)
            file->bytes = NULL;
    }
    fclose(stream);
    if (classic && !file->bytes)
        return im_fail(IM_EIO, "%s: cannot map the file: %s", path, strerror(errno));
    if (classic && check_classic_header(path, file->bytes, file->size) != IM_OK) {
        munmap(file->bytes, file->size);
        return IM_EFORMAT;
    }
    error = classic ? nc_open_mem(path, NC_NOWRITE, file->size, file->bytes, ncid) : nc_open(path, NC_NOWRITE, ncid);
    if (error != NC_NOERR) {
        if (file->bytes)
            munmap(file->bytes, file->size);
        return im_fail(IM_EFORMAT, "%s: cannot open as NetCDF: %s", path, nc_strerror(error));
    }
    return IM_OK;
}

int netcdf_read_in_process(const char *path, im_field **out, surface_stated *stated)
{
    *out = NULL;
    *stated = (surface_stated){.spacing_keys = "x:length / x and y:length / y",
                               .lateral_key = "x:unit",
                               .height_key = "x:unit"};
    mapped_file file;
    int ncid, status = open_dataset(path, &file, &ncid);
    if (status != IM_OK)
        return status;
    status = read_open(ncid, path, out, stated, &file);
    nc_close(ncid);
    if (file.bytes)
        munmap(file.bytes, file.size);
    return status;
}

/* Anything not classic goes to netCDF's HDF5 layer (libhdf5, which crashes inside itself on some hostile
 * files): read in a child. */
int netcdf_read_raw(const char *path, im_field **out, surface_stated *stated)
{
    *out = NULL;
    FILE *stream;
    int status = im_read_open(path, "rb", IM_READ_REGULAR, &stream, NULL);
    if (status != IM_OK)
        return status;
    int classic = starts_classic(stream);
    fclose(stream);
    return classic ? netcdf_read_in_process(path, out, stated) : netcdf4_read_raw(path, out, stated);
}

int im_netcdf_read(const char *path, im_field **out)
{
    ARG_REQUIRE(path, "path");
    ARG_REQUIRE(out, "out");
    return surface_read_format(path, netcdf_read_raw, NULL, out, NULL);
}

/* ---- writing: classic 64-bit offset format, built in memory and written atomically ---- */

/* The unit in ASCII, as SurfaceTopography (through scipy) writes it: "um" for µm, "A" for Å. */
static const char *ascii_unit(const char *unit)
{
    return strcmp(unit, "\u00b5m") == 0 ? "um" : strcmp(unit, "\u00c5") == 0 ? "A" : unit;
}

static int define_coordinate(int ncid, const char *name, int dim, double length, const char *unit, int *var)
{
    int periodic = 0; /* a written surface makes no claim to be periodic */
    int error = nc_def_var(ncid, name, NC_DOUBLE, 1, &dim, var);
    if (!error)
        error = nc_put_att_double(ncid, *var, "length", NC_DOUBLE, 1, &length);
    if (!error)
        error = nc_put_att_int(ncid, *var, "periodic", NC_INT, 1, &periodic);
    if (!error && unit[0]) /* today's name, and the one older readers know */
        error = nc_put_att_text(ncid, *var, "unit", strlen(unit), unit);
    if (!error && unit[0])
        error = nc_put_att_text(ncid, *var, "length_unit", strlen(unit), unit);
    return error;
}

static int put_coordinate(int ncid, int var, int points, double spacing)
{
    int error = NC_NOERR;
    for (size_t i = 0; error == NC_NOERR && i < (size_t)points; ++i) {
        double centre = ((double)i + 0.5) * spacing;
        error = nc_put_var1_double(ncid, var, &i, &centre);
    }
    return error;
}

/* The heights as heights(x, y): column by column of the row-major field. */
static int put_heights(int ncid, int var, const im_field *field)
{
    int error = NC_NOERR;
    double *column = malloc((size_t)field->ny * sizeof *column);
    if (!column)
        return NC_ENOMEM;
    for (size_t ix = 0; error == NC_NOERR && ix < (size_t)field->nx; ++ix) {
        for (size_t iy = 0; iy < (size_t)field->ny; ++iy)
            column[iy] = field->data[iy * (size_t)field->nx + ix];
        size_t start[2] = {ix, 0}, count[2] = {1, (size_t)field->ny};
        error = nc_put_vara_double(ncid, var, start, count, column);
    }
    free(column);
    return error;
}

static int write_dataset(int ncid, const im_field *field)
{
    int dims[2], x_var, y_var, h_var;
    const char *unit = ascii_unit(field->unit);
    int error = nc_def_dim(ncid, "x", (size_t)field->nx, &dims[0]);
    if (!error)
        error = nc_def_dim(ncid, "y", (size_t)field->ny, &dims[1]);
    if (!error)
        error = define_coordinate(ncid, "x", dims[0], field->nx * field->delta, unit, &x_var);
    if (!error)
        error = define_coordinate(ncid, "y", dims[1], field->ny * field->delta, unit, &y_var);
    if (!error)
        error = nc_def_var(ncid, "heights", NC_DOUBLE, 2, dims, &h_var);
    if (!error && unit[0])
        error = nc_put_att_text(ncid, h_var, "unit", strlen(unit), unit);
    if (!error)
        error = nc_enddef(ncid);
    if (!error)
        error = put_coordinate(ncid, x_var, field->nx, field->delta);
    if (!error)
        error = put_coordinate(ncid, y_var, field->ny, field->delta);
    return error ? error : put_heights(ncid, h_var, field);
}

int im_netcdf_write(const char *path, const im_field *field)
{
    ARG_REQUIRE(path, "path");
    ARG_VIEW(field, "field");
    int writable = formats_check_heights_or_missing_writable(field, path);
    if (writable != IM_OK)
        return writable;
    int ncid; /* an initial size of 0 lets the buffer grow to the dataset's exact size (no padding) */
    int error = nc_create_mem(path, NC_64BIT_OFFSET, 0, &ncid);
    if (error != NC_NOERR)
        return im_fail(IM_EIO, "%s: cannot create the NetCDF dataset: %s", path, nc_strerror(error));
    error = write_dataset(ncid, field);
    NC_memio memio = {0};
    int closed = nc_close_memio(ncid, &memio);
    int status = error || closed ? im_fail(IM_EIO, "%s: NetCDF: %s", path, nc_strerror(error ? error : closed))
                                 : im_write_file_atomic(path, memio.memory, memio.size);
    free(memio.memory);
    return status;
}
