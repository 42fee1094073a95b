/* Files libhdf5 parses, read in a child process: libhdf5 1.10 crashes inside itself on some hostile files (a
 * memcpy into a failed allocation of a size the file states), which the caller cannot guard against. The
 * program indentmap-hdf5-read (src/formats/hdf5/) reads a plain HDF5 file with hdf5_read_into (hdf5.c), or with
 * --netcdf a NetCDF-4 file (HDF5 underneath) with netcdf_read_in_process (netcdf.c), and writes this
 * stream; the library starts it (io/child_reader.h) and parses the stream:
 *   indentmap-hdf5-read 1
 *   field NX NY                              the chosen data set
 *   units DELTA_X DELTA_Y                    the spacing the file states (0: none)
 *   lateral UNIT                             the units it states ("": none)
 *   height UNIT
 *   keys SPACING<TAB>LATERAL<TAB>HEIGHT      what stated them, for messages
 *   conversion TEXT
 *   slab X0 ROWS                             then ROWS x NY doubles (native byte order) as HDF5 stores
 *   ...                                      them ([x][y], y fastest), ROWS at most HDF5_SLAB_ROWS, the
 *                                            slabs in order up to NX; nothing after the last
 * where "error STATUS MESSAGE" (STATUS an IM_E* code, MESSAGE the reader's own refusal) may stand in place
 * of the field line or of a slab line, and ends the stream. Reading HDF5, the program holds one slab, never
 * the field (netCDF reads the whole field, sent in the same slabs).
 * Text from the file (data set names, units) is written with control bytes as '?': no file can break a line. */
#include "indentmap/formats.h"
#include "indentmap/io.h"

#include "indentmap/status.h"
#include "formats/child_reader.h"
#include "formats/hdf5.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef IM_HDF5_READER_INSTALLED
#define HDF5_READER_INSTALLED IM_HDF5_READER_INSTALLED
#else
#define HDF5_READER_INSTALLED NULL
#endif

/* The program, reading a file of HDF5 underneath in mode (NULL: plain HDF5) with parser. */
#define HDF5_READER(mode_, parser_)                                                                                  \
    {                                                                                                                \
        .name = "indentmap-hdf5-read", .mode = mode_, .environment = "INDENTMAP_HDF5_READER",                        \
        .installed = HDF5_READER_INSTALLED, .reader = "the HDF5 reader (indentmap-hdf5-read)", .parser = parser_,    \
        .damage = "the file is damaged or hostile"                                                                   \
    }

static const child_program HDF5_PROGRAM = HDF5_READER(NULL, "the HDF5 library (libhdf5)");
/* NetCDF-4 files are HDF5 files, which netCDF reads with libhdf5. */
static const child_program NETCDF4_PROGRAM = HDF5_READER("--netcdf", "netCDF's HDF5 layer (libnetcdf, libhdf5)");

/* The program's sink: the stream, and the sides of the data set being written. */
typedef struct stream_sink {
    FILE *stream;
    int ny;
} stream_sink;

static int stream_begin(void *context, const char *path, int nx, int ny, const surface_stated *stated)
{
    (void)path;
    stream_sink *sink = context;
    sink->ny = ny;
    fprintf(sink->stream, "field %d %d\nunits %.17g %.17g\n", nx, ny, stated->units.delta_x, stated->units.delta_y);
    child_stream_put_line(sink->stream, "lateral ", stated->units.lateral);
    child_stream_put_line(sink->stream, "height ", stated->units.height);
    fprintf(sink->stream, "keys %s\t%s\t%s\n", stated->spacing_keys, stated->lateral_key, stated->height_key);
    child_stream_put_line(sink->stream, "conversion ", stated->conversion);
    return IM_OK;
}

/* A stream that cannot be written (the library closed it) ends the read; the exit status says so. */
static int stream_slab(void *context, const double *values, int x0, int rows)
{
    stream_sink *sink = context;
    size_t count = (size_t)rows * (size_t)sink->ny;
    fprintf(sink->stream, "slab %d %d\n", x0, rows);
    return fwrite(values, sizeof(double), count, sink->stream) == count
               ? IM_OK
               : im_fail(IM_EIO, "the stream to the library cannot be written");
}

/* A NetCDF-4 file read here (netcdf.c), its field written in [x][y] slabs as a data set's are. */
static int write_netcdf4(stream_sink *sink, const char *path)
{
    im_field *field = NULL;
    surface_stated stated;
    int status = netcdf_read_in_process(path, &field, &stated);
    if (status == IM_OK)
        status = stream_begin(sink, path, field->nx, field->ny, &stated);
    double *values = status == IM_OK ? malloc(sizeof *values * HDF5_SLAB_ROWS * (size_t)field->ny) : NULL;
    if (status == IM_OK && !values)
        status = im_fail(IM_ENOMEM, "%s: allocation of %d x-rows of %d values failed", path, HDF5_SLAB_ROWS,
                         field->ny);
    for (int x0 = 0, rows = 0; status == IM_OK && x0 < field->nx; x0 += rows) {
        rows = field->nx - x0 < HDF5_SLAB_ROWS ? field->nx - x0 : HDF5_SLAB_ROWS;
        hdf5_gather_slab(field, values, x0, rows);
        status = stream_slab(sink, values, x0, rows);
    }
    free(values);
    im_field_free(field);
    return status;
}

int hdf5_child_write(FILE *stream, const char *path, const char *channel, int netcdf4)
{
    im_surface_read_options options = {0};
    snprintf(options.channel, sizeof options.channel, "%s", channel);
    fprintf(stream, "indentmap-hdf5-read 1\n");
    stream_sink sink = {.stream = stream};
    int status = IM_OK;
    if (!netcdf4 && hdf5_is_netcdf4(path)) {
        netcdf4 = 1;
        if (channel[0])
            status = im_fail(IM_EINVAL,
                             "%s: channel '%.63s' asked of a NetCDF-4 file, read in NetCDF's layout (one "
                             "surface, heights(x, y))",
                             path, channel);
    }
    if (status == IM_OK)
        status = netcdf4 ? write_netcdf4(&sink, path)
                         : hdf5_read_into(path, &options,
                                          &(hdf5_sink){.begin = stream_begin, .slab = stream_slab, .context = &sink});
    if (status != IM_OK) {
        char prefix[32];
        snprintf(prefix, sizeof prefix, "error %d ", status);
        child_stream_put_line(stream, prefix, im_last_error());
    }
    return fflush(stream) != 0 || ferror(stream) ? 1 : status != IM_OK ? 2 : 0;
}

/* The parent's side: where the stream goes, and the keys it names (they outlive the read: surface_finish
 * quotes them). */
typedef struct hdf5_answer {
    im_field **out;
    surface_stated *stated;
} hdf5_answer;

static __thread char stated_keys[3][96];

static int stream_error(const char *path, const char *what, const char *line)
{
    return im_fail(IM_EFORMAT, "%s: the HDF5 reader (indentmap-hdf5-read) wrote '%.60s': expected %s", path, line,
                   what);
}

/* "error STATUS MESSAGE": the reader's refusal, as it would have been made in this process. */
static int take_error(const char *path, const char *line)
{
    int status = 0, consumed = 0;
    if (sscanf(line, "error %d %n", &status, &consumed) != 1 || consumed == 0 || status <= IM_OK ||
        status > IM_EINTERRUPTED)
        return stream_error(path, "a refusal 'error STATUS MESSAGE'", line);
    return im_fail(status, "%s", line + consumed);
}

static int take_units(const char *path, const char *line, surface_stated *stated)
{
    im_surface_units *units = &stated->units;
    int consumed = 0;
    if (sscanf(line, "units %lf %lf%n", &units->delta_x, &units->delta_y, &consumed) != 2 || line[consumed] ||
        !isfinite(units->delta_x) || !isfinite(units->delta_y) || units->delta_x < 0.0 || units->delta_y < 0.0)
        return stream_error(path, "'units DELTA_X DELTA_Y', finite and >= 0", line);
    return IM_OK;
}

/* The next line, "PREFIX TEXT", its text (shorter than size) into text. */
static int take_text(FILE *stream, const char *path, const char *prefix, char *text, size_t size)
{
    char line[CHILD_STREAM_LINE];
    size_t length = strlen(prefix);
    int read = child_stream_line(stream, line);
    if (!read || strncmp(line, prefix, length) != 0 || strlen(line + length) >= size) {
        char expected[64];
        snprintf(expected, sizeof expected, "'%sTEXT' of at most %zu bytes", prefix, size - 1);
        return stream_error(path, expected, line);
    }
    memcpy(text, line + length, strlen(line + length) + 1);
    return IM_OK;
}

static int take_keys(const char *path, const char *line, surface_stated *stated)
{
    if (sscanf(line, "keys %95[^\t]\t%95[^\t]\t%95[^\t]", stated_keys[0], stated_keys[1], stated_keys[2]) != 3)
        return stream_error(path, "'keys SPACING<TAB>LATERAL<TAB>HEIGHT'", line);
    stated->spacing_keys = stated_keys[0];
    stated->lateral_key = stated_keys[1];
    stated->height_key = stated_keys[2];
    return IM_OK;
}

/* The lines after "field": units, lateral, height, keys, conversion. */
static int take_stated(FILE *stream, const char *path, surface_stated *stated)
{
    char line[CHILD_STREAM_LINE];
    *stated = (surface_stated){0};
    int status = child_stream_line(stream, line) ? take_units(path, line, stated) : stream_error(path, "units", "");
    if (status == IM_OK)
        status = take_text(stream, path, "lateral ", stated->units.lateral, sizeof stated->units.lateral);
    if (status == IM_OK)
        status = take_text(stream, path, "height ", stated->units.height, sizeof stated->units.height);
    if (status == IM_OK)
        status = child_stream_line(stream, line) ? take_keys(path, line, stated) : stream_error(path, "keys", "");
    if (status == IM_OK)
        status = take_text(stream, path, "conversion ", stated->conversion, sizeof stated->conversion);
    return status;
}

/* "slab X0 ROWS" and its values into field (*rows of them), x0 the next expected, or the reader's refusal in
 * its place. */
static int take_slab(FILE *stream, const char *path, im_field *field, int x0, double *values, int *rows)
{
    char line[CHILD_STREAM_LINE];
    if (!child_stream_line(stream, line))
        return im_fail(IM_EFORMAT, "%s: the HDF5 reader (indentmap-hdf5-read) ended before x-row %d of %d", path, x0,
                       field->nx);
    if (strncmp(line, "error ", 6) == 0)
        return take_error(path, line);
    int at = -1, consumed = 0;
    int most = field->nx - x0 < HDF5_SLAB_ROWS ? field->nx - x0 : HDF5_SLAB_ROWS;
    if (sscanf(line, "slab %d %d%n", &at, rows, &consumed) != 2 || line[consumed] || at != x0 || *rows < 1 ||
        *rows > most)
        return im_fail(IM_EFORMAT,
                       "%s: the HDF5 reader (indentmap-hdf5-read) wrote '%.60s': expected 'slab %d ROWS' "
                       "with ROWS in [1, %d]",
                       path, line, x0, most);
    size_t count = (size_t)*rows * (size_t)field->ny;
    if (fread(values, sizeof(double), count, stream) != count)
        return im_fail(IM_EFORMAT, "%s: the HDF5 reader (indentmap-hdf5-read) ended inside x-rows %d to %d", path, x0,
                       x0 + *rows - 1);
    hdf5_scatter_slab(field, values, x0, *rows);
    return IM_OK;
}

static int take_values(FILE *stream, const char *path, im_field *field)
{
    double *values = malloc(sizeof *values * HDF5_SLAB_ROWS * (size_t)field->ny);
    if (!values)
        return im_fail(IM_ENOMEM, "%s: allocation of %d x-rows of %d values failed", path, HDF5_SLAB_ROWS, field->ny);
    int status = IM_OK, rows = 0;
    for (int x0 = 0; x0 < field->nx && status == IM_OK; x0 += rows)
        status = take_slab(stream, path, field, x0, values, &rows);
    free(values);
    if (status != IM_OK)
        return status;
    return fgetc(stream) == EOF ? IM_OK
                                : im_fail(IM_EFORMAT,
                                          "%s: the HDF5 reader (indentmap-hdf5-read) wrote "
                                          "more than the field",
                                          path);
}

static int parse_stream(FILE *stream, const char *path, void *answer_, int *answered)
{
    hdf5_answer *answer = answer_;
    char line[CHILD_STREAM_LINE];
    if (!child_stream_line(stream, line) || strcmp(line, "indentmap-hdf5-read 1") != 0)
        return stream_error(path, "'indentmap-hdf5-read 1' first", line);
    if (!child_stream_line(stream, line))
        return im_fail(IM_EFORMAT, "%s: the HDF5 reader (indentmap-hdf5-read) ended before its answer", path);
    *answered = 1;
    if (strncmp(line, "error ", 6) == 0)
        return take_error(path, line);
    int nx = 0, ny = 0, consumed = 0;
    if (sscanf(line, "field %d %d%n", &nx, &ny, &consumed) != 2 || line[consumed] || nx < 1 || ny < 1 ||
        nx > IM_FIELD_MAX_SIDE || ny > IM_FIELD_MAX_SIDE)
        return im_fail(IM_EFORMAT,
                       "%s: the HDF5 reader (indentmap-hdf5-read) wrote '%.60s': expected 'field NX NY' "
                       "with sides in [1, %d]",
                       path, line, IM_FIELD_MAX_SIDE);
    int status = take_stated(stream, path, answer->stated);
    if (status == IM_OK && (status = im_field_create(nx, ny, 1.0, answer->out)) != IM_OK)
        status = im_fail_context(status, "%s", path);
    if (status == IM_OK)
        status = take_values(stream, path, *answer->out);
    return status;
}

/* files: what the program reads, for the message when it is not found. */
static int read_in_child(const child_program *program, const char *files, const char *path, const char *channel,
                         im_field **out, surface_stated *stated)
{
    *out = NULL;
    const char *executable = child_program_path(program);
    if (!executable)
        return im_fail(IM_EFORMAT,
                       "%s: %s are read by indentmap-hdf5-read, a program of this build not found beside "
                       "this program%s%s: set INDENTMAP_HDF5_READER to its path",
                       path, files, program->installed ? " nor at " : "",
                       program->installed ? program->installed : "");
    hdf5_answer answer = {.out = out, .stated = stated};
    int status = child_read(program, executable, path, channel, parse_stream, &answer);
    if (status != IM_OK && *out) {
        im_field_free(*out);
        *out = NULL;
    }
    return status;
}

int hdf5_read_raw(const char *path, const im_surface_read_options *options, im_field **out, surface_stated *stated)
{
    return read_in_child(&HDF5_PROGRAM, "HDF5 files", path, options ? options->channel : "", out, stated);
}

int netcdf4_read_raw(const char *path, im_field **out, surface_stated *stated)
{
    return read_in_child(&NETCDF4_PROGRAM, "NetCDF-4 (HDF5) files", path, "", out, stated);
}
