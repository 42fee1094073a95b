#include "indentmap/formats.h"
#include "indentmap/io.h"
#include "core/args.h"

#include "indentmap/status.h"
#include "formats/payload.h"
#include "formats/readers.h"
#include "core/number.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char GSF_MAGIC[] = "Gwyddion Simple Field 1.0\n";

/* The header (its length in *length), in base SI units when the field's unit is a known length:
 * Gwyddion writes and reads metres and keeps no prefix ("XYUnits = um" reads as metres). *metres
 * scales the lengths (1 for a field without units). */
static int write_header(char *header, size_t size, const im_field *field, const char *path, double *metres,
                        int *length)
{
    *metres = field->unit[0] ? im_length_unit_metres(field->unit, NULL) : 1.0;
    if (*metres == 0.0)
        return im_fail(IM_EINVAL,
                       "%s: unit '%.15s' is not a length unit (m, cm, mm, \u00b5m or um, nm, pm, "
                       "\u00c5): a .gsf states its lengths in metres",
                       path, field->unit);
    *length = snprintf(header, size, "%sXRes = %d\nYRes = %d\nXReal = %.17g\nYReal = %.17g\n%s", GSF_MAGIC, field->nx,
                       field->ny, field->nx * field->delta * *metres, field->ny * field->delta * *metres,
                       field->unit[0] ? "XYUnits = m\nZUnits = m\n" : "");
    return IM_OK;
}

/* A missing point is written as NaN: Gwyddion's own GSF reader masks NaN as an invalid point (2.62's gsffile
 * module, checked by reading such a file back through it), and this one reads it back as missing. */
int im_gsf_write(const char *path, const im_field *field)
{
    ARG_REQUIRE(path, "path");
    ARG_VIEW(field, "field");
    int writable = formats_check_heights_or_missing_writable(field, path);
    if (writable != IM_OK)
        return writable;
    char header[512];
    double metres;
    int length = 0;
    int status = write_header(header, sizeof header, field, path, &metres, &length);
    if (status != IM_OK)
        return status;
    size_t padding = 4 - (size_t)length % 4; /* at least one NUL ends the header */
    im_atomic_file file;
    if ((status = im_atomic_open(&file, path)) != IM_OK)
        return status;
    int ok = fwrite(header, 1, (size_t)length, file.stream) == (size_t)length;
    for (size_t i = 0; ok && i < padding; ++i)
        ok = fputc('\0', file.stream) != EOF;
    size_t count = im_field_count(field);
    for (size_t i = 0; ok && i < count; ++i) {
        float value = (float)(field->data[i] * metres);
        ok = fwrite(&value, sizeof value, 1, file.stream) == 1;
    }
    if (!ok) {
        im_atomic_abort(&file);
        return im_fail(IM_EIO, "%s: write failed: %s", path, strerror(errno));
    }
    return im_atomic_commit(&file);
}

typedef struct gsf_header {
    long xres, yres;
    double xreal, yreal; /* 0 when absent */
    char xy_units[16], z_units[16];
    int refused; /* 1 once a value was refused (the message is recorded) */
} gsf_header;

/* A decimal integer and nothing else but blanks: "16abc" and "1.6e1" are not pixel counts. */
static int parse_count(const char *path, const char *key, const char *value, long *out)
{
    char *end;
    errno = 0;
    long number = strtol(value, &end, 10);
    if (end == value || end[strspn(end, " \t\r")] != '\0' || errno == ERANGE)
        return im_fail(IM_EFORMAT, "%s: %s = '%.32s': expected a decimal integer", path, key, value);
    *out = number;
    return IM_OK;
}

/* A finite length > 0 and nothing else but blanks. */
static int parse_extent(const char *path, const char *key, const char *value, double *out)
{
    char *end;
    double number = number_parse(value, &end);
    if (end == value || end[strspn(end, " \t\r")] != '\0' || !isfinite(number) || !(number > 0.0))
        return im_fail(IM_EFORMAT, "%s: %s = '%.32s': expected a finite length > 0", path, key, value);
    *out = number;
    return IM_OK;
}

static int parse_units(const char *path, const char *key, const char *value, char *out, size_t size)
{
    size_t length = strcspn(value, " \t\r");
    if (length == 0 || length >= size || value[length + strspn(value + length, " \t\r")] != '\0')
        return im_fail(IM_EFORMAT, "%s: %s = '%.32s': expected one unit name of at most %zu bytes", path, key, value,
                       size - 1);
    snprintf(out, size, "%.*s", (int)length, value);
    return IM_OK;
}

/* One KEY = VALUE line; keys other than these six are Gwyddion metadata and ignored. */
static void parse_header_line(const char *path, const char *line, gsf_header *h)
{
    char key[64], value[128];
    if (h->refused || sscanf(line, " %63[^= ] = %127[^\n]", key, value) != 2)
        return;
    int status = IM_OK;
    if (strcmp(key, "XRes") == 0)
        status = parse_count(path, key, value, &h->xres);
    else if (strcmp(key, "YRes") == 0)
        status = parse_count(path, key, value, &h->yres);
    else if (strcmp(key, "XReal") == 0)
        status = parse_extent(path, key, value, &h->xreal);
    else if (strcmp(key, "YReal") == 0)
        status = parse_extent(path, key, value, &h->yreal);
    else if (strcmp(key, "XYUnits") == 0)
        status = parse_units(path, key, value, h->xy_units, sizeof h->xy_units);
    else if (strcmp(key, "ZUnits") == 0)
        status = parse_units(path, key, value, h->z_units, sizeof h->z_units);
    h->refused = status != IM_OK;
}

/* Reads the text header up to its terminating NUL and skips the padding to a multiple of 4. */
static int read_header(FILE *stream, const char *path, gsf_header *h)
{
    char line[256];
    size_t offset = 0, used = 0;
    int c;
    if (fread(line, 1, sizeof GSF_MAGIC - 1, stream) != sizeof GSF_MAGIC - 1 ||
        memcmp(line, GSF_MAGIC, sizeof GSF_MAGIC - 1) != 0)
        return im_fail(IM_EFORMAT, "%s: not a Gwyddion Simple Field (no '%.25s' line)", path, GSF_MAGIC);
    offset = sizeof GSF_MAGIC - 1;
    while ((c = fgetc(stream)) != EOF && c != '\0') {
        ++offset;
        if (c == '\n' || used + 1 == sizeof line) {
            line[used] = '\0';
            parse_header_line(path, line, h);
            used = 0;
        } else {
            line[used++] = (char)c;
        }
        if (h->refused)
            return IM_EFORMAT;
        if (offset > 1 << 20)
            return im_fail(IM_EFORMAT, "%s: header has no terminating NUL in its first MiB", path);
    }
    if (c == EOF)
        return im_fail(IM_EFORMAT, "%s: truncated header (no NUL padding before the data)", path);
    ++offset;
    while (offset % 4 != 0 && (c = fgetc(stream)) == '\0')
        ++offset;
    if (offset % 4 != 0)
        return im_fail(IM_EFORMAT, "%s: header padding is not NUL bytes up to a multiple of 4", path);
    if (h->xres < 1 || h->yres < 1) /* the upper bound is formats_check_grid's */
        return im_fail(IM_EFORMAT, "%s: XRes = %ld, YRes = %ld: expected both >= 1", path, h->xres, h->yres);
    return IM_OK;
}

static int read_values(FILE *stream, const char *path, im_field *field)
{
    size_t count = im_field_count(field), got = 0;
    float value;
    while (got < count && fread(&value, sizeof value, 1, stream) == 1)
        field->data[got++] = value;
    if (got != count)
        return im_fail(IM_EFORMAT, "%s: truncated data: %zu of %zu values (XRes %d x YRes %d)", path, got, count,
                       field->nx, field->ny);
    if (fgetc(stream) != EOF)
        return im_fail(IM_EFORMAT, "%s: more data than XRes x YRes = %d x %d holds", path, field->nx, field->ny);
    return IM_OK;
}

/* The spacing keys, naming the GSF specification's default for an absent XReal (bit 0) or YReal (bit 1). */
static const char *const SPACING_KEYS[4] = {
    "XReal / XRes and YReal / YRes", "XReal / XRes and YReal / YRes (no XReal: 1.0, the GSF default)",
    "XReal / XRes and YReal / YRes (no YReal: 1.0, the GSF default)",
    "XReal / XRes and YReal / YRes (no XReal, no YReal: 1.0 each, the GSF default)"};

/* What the header states about units: pixel spacing XReal / XRes and YReal / YRes, each extent 1.0
 * when absent (the specification's default); heights without ZUnits have an unknown unit. */
static void stated_units(const gsf_header *h, surface_stated *stated)
{
    int absent = (h->xreal > 0.0 ? 0 : 1) | (h->yreal > 0.0 ? 0 : 2);
    *stated = (surface_stated){.spacing_keys = SPACING_KEYS[absent],
                               .lateral_key = "XYUnits",
                               .height_key = "ZUnits",
                               .height_unit_unknown = 1};
    stated->units.delta_x = (h->xreal > 0.0 ? h->xreal : 1.0) / (double)h->xres;
    stated->units.delta_y = (h->yreal > 0.0 ? h->yreal : 1.0) / (double)h->yres;
    memcpy(stated->units.lateral, h->xy_units, sizeof h->xy_units);
    memcpy(stated->units.height, h->z_units, sizeof h->z_units);
}

int gsf_read_raw(const char *path, im_field **out, surface_stated *stated)
{
    *out = NULL;
    FILE *stream;
    int opened = im_read_open(path, "rb", IM_READ_OR_PIPE, &stream, NULL);
    if (opened != IM_OK)
        return opened;
    gsf_header header = {0};
    im_field *field = NULL;
    int status = read_header(stream, path, &header);
    if (status == IM_OK) {
        char claim[64];
        snprintf(claim, sizeof claim, "XRes %ld x YRes %ld float32", header.xres, header.yres);
        status = formats_check_grid(stream, path, header.xres, header.yres, 4u, claim);
    }
    if (status == IM_OK) {
        status = im_field_create((int)header.xres, (int)header.yres, 1.0, &field);
        if (status != IM_OK)
            im_fail_context(status, "%s", path);
    }
    if (status == IM_OK)
        status = read_values(stream, path, field);
    fclose(stream);
    if (status != IM_OK) {
        im_field_free(field);
        return status;
    }
    stated_units(&header, stated);
    *out = field;
    return IM_OK;
}

int im_gsf_read(const char *path, im_field **out)
{
    ARG_REQUIRE(path, "path");
    ARG_REQUIRE(out, "out");
    return surface_read_format(path, gsf_read_raw, NULL, out, NULL);
}
