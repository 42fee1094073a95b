/* Instrument formats through Gwyddion's file modules: the program that runs them, and its stream. */
#include "formats/gwyddion.h"

#include "indentmap/formats.h"
#include "indentmap/io.h"
#include "indentmap/status.h"
#include "formats/child_reader.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static const child_program GWYDDION_PROGRAM = {
    .name = "indentmap-gwyddion-read",
    .environment = "INDENTMAP_GWYDDION_READER",
#ifdef IM_GWYDDION_READER_INSTALLED
    .installed = IM_GWYDDION_READER_INSTALLED,
#endif
    .reader = "Gwyddion's reader",
    .parser = "Gwyddion's file module",
    .damage = "a damaged file?",
};

const char *im_gwyddion_reader(void) { return child_program_path(&GWYDDION_PROGRAM); }

enum { MAX_LISTED = 8 };

typedef struct stream_header {
    char module[64];
    char channels[512]; /* "0 'Height' [m], 1 'Phase' [deg], ..." for messages */
    int channel_count;
    int id, nx, ny, masked;
    double x_extent, y_extent;
    char lateral[16], height[16];
    char title[64]; /* the chosen channel's */
} stream_header;

/* "channel ID<TAB>XRES<TAB>YRES<TAB>ZUNIT<TAB>TITLE": appended to the list for messages. */
static void take_channel_line(const char *line, stream_header *header)
{
    int id = -1, consumed = 0;
    char unit[32] = "";
    sscanf(line, "channel %d\t%*d\t%*d\t%31[^\t]\t%n", &id, unit, &consumed);
    const char *title = consumed ? line + consumed : "";
    size_t used = strlen(header->channels);
    if (header->channel_count < MAX_LISTED)
        snprintf(header->channels + used, sizeof header->channels - used, "%s%d '%.40s' [%s]",
                 header->channel_count ? ", " : "", id, title, unit);
    else if (header->channel_count == MAX_LISTED)
        snprintf(header->channels + used, sizeof header->channels - used, ", ...");
    ++header->channel_count;
}

static int take_field_line(const char *path, const char *line, stream_header *header)
{
    char lateral[32], height[32];
    int consumed = 0;
    if (sscanf(line, "field %d %d %d %lf %lf %31s %31s %d %n", &header->id, &header->nx, &header->ny,
               &header->x_extent, &header->y_extent, lateral, height, &header->masked, &consumed) != 8 ||
        header->nx < 1 || header->ny < 1 || header->nx > IM_FIELD_MAX_SIDE || header->ny > IM_FIELD_MAX_SIDE ||
        !isfinite(header->x_extent) || !(header->x_extent > 0.0) || !isfinite(header->y_extent) ||
        !(header->y_extent > 0.0) || (header->masked != 0 && header->masked != 1))
        return im_fail(IM_EFORMAT,
                       "%s: Gwyddion's reader described the field as '%.80s': expected sides 1 to %d "
                       "and extents > 0",
                       path, line, IM_FIELD_MAX_SIDE);
    snprintf(header->lateral, sizeof header->lateral, "%.15s", strcmp(lateral, "-") ? lateral : "");
    snprintf(header->height, sizeof header->height, "%.15s", strcmp(height, "-") ? height : "");
    snprintf(header->title, sizeof header->title, "%.63s", consumed ? line + consumed : "");
    return IM_OK;
}

static int read_stream_header(FILE *stream, const char *path, stream_header *header, int *answered)
{
    char line[CHILD_STREAM_LINE];
    if (!child_stream_line(stream, line) || strcmp(line, "indentmap-gwyddion-read 1") != 0)
        return im_fail(IM_EFORMAT, "%s: Gwyddion's reader gave no answer one can read (first line '%.40s')", path,
                       line);
    while (child_stream_line(stream, line)) {
        *answered = strncmp(line, "error ", 6) == 0 || strncmp(line, "field ", 6) == 0;
        if (strncmp(line, "error unknown-format ", 21) == 0)
            return im_fail(IM_EFORMAT, "%s: " GWYDDION_UNKNOWN_FORMAT ": %.200s", path, line + 21);
        if (strncmp(line, "error line-scan ", 16) == 0)
            return im_fail(IM_EFORMAT,
                           "%s: " LINE_SCAN_REFUSAL ": Gwyddion's module '%s' reads it as %.200s; " LINE_SCAN_ADVICE,
                           path, header->module, line + 16);
        if (strncmp(line, "error failed ", 13) == 0)
            return im_fail(IM_EFORMAT, "%s: Gwyddion's file modules cannot read it: %.200s", path, line + 13);
        if (sscanf(line, "module %63s", header->module) == 1)
            continue;
        if (strncmp(line, "channel ", 8) == 0) {
            take_channel_line(line, header);
            continue;
        }
        if (strncmp(line, "field ", 6) != 0)
            return im_fail(IM_EFORMAT, "%s: Gwyddion's reader wrote '%.40s': expected a field", path, line);
        return take_field_line(path, line, header);
    }
    return im_fail(IM_EFORMAT, "%s: Gwyddion's reader ended before the field", path);
}

/* The heights, and NaN where the mask marks a point invalid; nothing may follow. */
static int read_stream_values(FILE *stream, const char *path, const stream_header *header, im_field *field)
{
    size_t count = im_field_count(field);
    if (fread(field->data, sizeof(double), count, stream) != count)
        return im_fail(IM_EFORMAT, "%s: Gwyddion's reader ended inside the heights (%zu expected)", path, count);
    for (size_t k = 0; header->masked && k < count; ++k) {
        int invalid = fgetc(stream);
        if (invalid == EOF)
            return im_fail(IM_EFORMAT, "%s: Gwyddion's reader ended inside the mask", path);
        if (invalid)
            field->data[k] = NAN;
    }
    return fgetc(stream) == EOF ? IM_OK
                                : im_fail(IM_EFORMAT, "%s: Gwyddion's reader wrote more than the field", path);
}

/* Gwyddion keeps values in base SI units: heights in "m", and any other unit is not a height. */
static int state_units(const char *path, const stream_header *header, surface_stated *stated)
{
    if (header->height[0] && strcmp(header->height, "m") != 0)
        return im_fail(IM_EFORMAT,
                       "%s: channel %d '%.40s' holds values in '%s', not heights (a length); its "
                       "channels: %s; choose one with --channel",
                       path, header->id, header->title, header->height, header->channels);
    *stated = (surface_stated){.spacing_keys = "Gwyddion's xreal / xres and yreal / yres",
                               .lateral_key = "Gwyddion's lateral unit",
                               .height_key = "Gwyddion's value unit"};
    stated->units.delta_x = header->x_extent / header->nx;
    stated->units.delta_y = header->y_extent / header->ny;
    snprintf(stated->units.lateral, sizeof stated->units.lateral, "%s", header->lateral);
    snprintf(stated->units.height, sizeof stated->units.height, "%s", header->height);
    snprintf(stated->conversion, sizeof stated->conversion, "Gwyddion '%.16s': channel %d '%.24s' of %d",
             header->module, header->id, header->title, header->channel_count);
    return IM_OK;
}

/* A stream in a regular file (the fuzz harness's) must hold the values its field line claims before
 * they are allocated; from the program's pipe they come from a field Gwyddion already holds. */
static int check_values_present(FILE *stream, const char *path, const stream_header *header)
{
    struct stat about;
    long at = ftell(stream);
    double needed = (double)header->nx * header->ny * (sizeof(double) + (header->masked ? 1 : 0));
    if (fstat(fileno(stream), &about) != 0 || !S_ISREG(about.st_mode) || at < 0 ||
        (double)(about.st_size - at) >= needed)
        return IM_OK;
    return im_fail(IM_EFORMAT, "%s: Gwyddion's reader ended inside the heights (%d x %d claimed, %lld bytes left)",
                   path, header->nx, header->ny, (long long)(about.st_size - at));
}

/* The stream parsed; *answered says whether it held an error line or a field (else the program's exit
 * status and errors explain it better). */
static int stream_parse(FILE *stream, const char *path, im_field **out, surface_stated *stated, int *answered)
{
    *out = NULL;
    stream_header header = {0};
    int status = read_stream_header(stream, path, &header, answered);
    if (status == IM_OK)
        status = state_units(path, &header, stated);
    if (status == IM_OK)
        status = check_values_present(stream, path, &header);
    im_field *field = NULL;
    if (status == IM_OK)
        status = im_field_create(header.nx, header.ny, 1.0, &field);
    if (status == IM_OK)
        status = read_stream_values(stream, path, &header, field);
    if (status == IM_OK)
        *out = field;
    else
        im_field_free(field);
    return status;
}

int gwyddion_stream_file_read(const char *path, im_field **out)
{
    *out = NULL;
    FILE *stream = fopen(path, "rb");
    if (!stream)
        return im_fail(IM_EIO, "%s: cannot open: %s", path, strerror(errno));
    surface_stated stated;
    im_field *field = NULL;
    int answered = 0;
    int status = stream_parse(stream, path, &field, &stated, &answered);
    fclose(stream);
    if (status == IM_OK)
        status = surface_finish(path, field, &stated, NULL, NULL);
    if (status == IM_OK)
        *out = field;
    else
        im_field_free(field);
    return status;
}

/* Values without a unit beside lateral sizes in a unit are counts or volts as often as lengths: their
 * unit is not guessed (a file with no units at all is read as a bare matrix). */
static int check_height_unit(const char *path, const surface_stated *stated, const im_surface_read_options *options)
{
    if (stated->units.height[0] || !stated->units.lateral[0] || (options && options->set.height[0]))
        return IM_OK;
    return im_fail(IM_EFORMAT,
                   "%s: %s: its values have no unit beside lateral sizes in %s: give their unit "
                   "(--height-unit) if they are heights",
                   path, stated->conversion, stated->units.lateral);
}

/* Where the program's stream goes: child_read hands the parser one pointer. */
typedef struct stream_result {
    im_field **out;
    surface_stated *stated;
} stream_result;

static int parse_from_program(FILE *stream, const char *path, void *result_, int *answered)
{
    stream_result *result = result_;
    return stream_parse(stream, path, result->out, result->stated, answered);
}

int gwyddion_read_raw(const char *path, const im_surface_read_options *options, im_field **out,
                      surface_stated *stated)
{
    *out = NULL;
    const char *program = im_gwyddion_reader();
    if (!program)
        return im_fail(IM_EFORMAT,
                       "%s: a format read through Gwyddion's file modules, which this build lacks "
                       "(install libgwyddion20-dev and gwyddion, then rebuild)",
                       path);
    stream_result result = {.out = out, .stated = stated};
    int status = child_read(&GWYDDION_PROGRAM, program, path, options ? options->channel : "", parse_from_program,
                            &result);
    if (status == IM_OK)
        status = check_height_unit(path, stated, options);
    if (status != IM_OK && *out) {
        im_field_free(*out);
        *out = NULL;
    }
    return status;
}
