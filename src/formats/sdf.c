/* ISO 25178-71 surface data files (.sdf), ASCII ("aISO-1.0", or the older "aBCR-1.0") and binary
 * ("bISO-1.0", "bBCR-1.0"): a header stating NumPoints (columns) by NumProfiles (rows), the spacings
 * Xscale and Yscale and the height unit Zscale, all in metres, then the values row by row, each a
 * height in units of Zscale. Missing points: NaN, or "BAD" in the ASCII form. Gwyddion writes the
 * version "aBCR-0.0" (or "bBCR-0.0") and two more ASCII keys: NumDataSet (the data sets that follow:
 * one is read) and NanPresent (0 or 1: whether values are NaN). */
#include "indentmap/formats.h"
#include "indentmap/io.h"
#include "core/args.h"

#include "indentmap/status.h"
#include "formats/payload.h"
#include "formats/readers.h"
#include "core/number.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

enum { SDF_BINARY_HEADER = 8 + 10 + 12 + 12 + 2 + 2 + 4 * 8 + 3 }; /* 81 bytes, packed, little-endian */

/* DataType codes of the standard, with their sizes in bytes (0: none). */
enum { SDF_UINT8, SDF_UINT16, SDF_UINT32, SDF_FLOAT, SDF_SINT8, SDF_SINT16, SDF_SINT32, SDF_DOUBLE, SDF_TYPES };
static const int SDF_SIZES[SDF_TYPES] = {1, 2, 4, 4, 1, 2, 4, 8};

typedef struct sdf_header {
    long points, profiles;         /* NumPoints (columns, along x), NumProfiles (rows, along y) */
    double xscale, yscale, zscale; /* metres per step and per unit of a value */
    long compression, data_type;
    long data_sets, nan_present; /* Gwyddion's NumDataSet and NanPresent (1 and 0 when absent) */
} sdf_header;

/* The versions read: the standard's, the older BCR ones and Gwyddion's (after 'a' or 'b'). */
static const char *const SDF_VERSIONS[] = {"ISO-1.0", "BCR-1.0", "BCR-0.0"};

/* A header value that must be finite and > 0. */
static int check_scale(const char *path, const char *key, double value)
{
    if (!isfinite(value) || !(value > 0.0))
        return im_fail(IM_EFORMAT, "%s: %s = %g: expected a finite length in metres > 0", path, key, value);
    return IM_OK;
}

static int check_header(const char *path, const sdf_header *h)
{
    if (h->points < 1 || h->profiles < 1)
        return im_fail(IM_EFORMAT, "%s: NumPoints = %ld, NumProfiles = %ld: expected both >= 1", path, h->points,
                       h->profiles);
    if (h->compression != 0)
        return im_fail(IM_EFORMAT, "%s: Compression = %ld: only uncompressed data (0) is read", path, h->compression);
    if (h->data_type < 0 || h->data_type >= SDF_TYPES)
        return im_fail(IM_EFORMAT, "%s: DataType = %ld: expected 0 to 7", path, h->data_type);
    if (h->data_sets != 1)
        return im_fail(IM_EFORMAT, "%s: NumDataSet = %ld: only files of one data set (1) are read", path,
                       h->data_sets);
    if (h->nan_present != 0 && h->nan_present != 1)
        return im_fail(IM_EFORMAT, "%s: NanPresent = %ld: expected 0 or 1", path, h->nan_present);
    int status = check_scale(path, "Xscale", h->xscale);
    if (status == IM_OK)
        status = check_scale(path, "Yscale", h->yscale);
    return status == IM_OK ? check_scale(path, "Zscale", h->zscale) : status;
}

/* ---- ASCII ---- */

/* The header keys read: integers first, then lengths. */
enum { SDF_LONG_KEYS = 6, SDF_KEYS = 9 };
static const char *const SDF_KEY_NAMES[SDF_KEYS] = {"NumPoints", "NumProfiles", "Compression",
                                                    "DataType",  "NumDataSet",  "NanPresent",
                                                    "Xscale",    "Yscale",      "Zscale"};

/* "Key = value" into the header; IM_EFORMAT naming the key for a value that is not a number. */
static int parse_ascii_line(const char *path, long line_number, const char *line, sdf_header *h, int *seen)
{
    long *long_fields[SDF_LONG_KEYS] = {&h->points,    &h->profiles,  &h->compression,
                                        &h->data_type, &h->data_sets, &h->nan_present};
    double *double_fields[SDF_KEYS - SDF_LONG_KEYS] = {&h->xscale, &h->yscale, &h->zscale};
    char key[32], value[64], *end;
    if (sscanf(line, " %31[A-Za-z] = %63s", key, value) != 2)
        return IM_OK; /* dates, manufacturer and the like: not needed */
    for (int i = 0; i < SDF_LONG_KEYS; ++i)
        if (strcmp(key, SDF_KEY_NAMES[i]) == 0) {
            errno = 0;
            *long_fields[i] = strtol(value, &end, 10);
            if (*end != '\0' || errno == ERANGE)
                return im_fail(IM_EFORMAT, "%s:%ld: %s = '%s': expected a decimal integer", path, line_number, key,
                               value);
            seen[i] = 1;
        }
    for (int i = SDF_LONG_KEYS; i < SDF_KEYS; ++i)
        if (strcmp(key, SDF_KEY_NAMES[i]) == 0) {
            *double_fields[i - SDF_LONG_KEYS] = number_parse(value, &end);
            if (*end != '\0')
                return im_fail(IM_EFORMAT, "%s:%ld: %s = '%s': expected a number", path, line_number, key, value);
            seen[i] = 1;
        }
    return IM_OK;
}

static int read_ascii_header(FILE *stream, const char *path, sdf_header *h, long *line_number)
{
    /* Compression and DataType may be absent (0, and text values), NumDataSet and NanPresent too */
    int seen[SDF_KEYS] = {0, 0, 1, 1, 1, 1, 0, 0, 0};
    char line[256];
    int status = IM_OK;
    while (status == IM_OK && fgets(line, sizeof line, stream)) {
        ++*line_number;
        if (line[0] == '*')
            break;
        status = parse_ascii_line(path, *line_number, line, h, seen);
    }
    if (status != IM_OK)
        return status;
    if (feof(stream))
        return im_fail(IM_EFORMAT, "%s: truncated: no '*' line ends the header", path);
    for (int i = 0; i < SDF_KEYS; ++i)
        if (!seen[i])
            return im_fail(IM_EFORMAT, "%s: the header lacks %s", path, SDF_KEY_NAMES[i]);
    return check_header(path, h);
}

/* The values after the header: NumPoints x NumProfiles numbers ("BAD": missing), then '*' or the end. */
static int read_ascii_values(FILE *stream, const char *path, const sdf_header *h, im_field *field)
{
    size_t count = im_field_count(field), got = 0;
    char token[64];
    while (got < count && fscanf(stream, "%63s", token) == 1) {
        char *end;
        double value = strcmp(token, "BAD") == 0 ? NAN : number_parse(token, &end);
        if (token[0] == '*')
            break;
        if (strcmp(token, "BAD") != 0 && *end != '\0')
            return im_fail(IM_EFORMAT, "%s: value %zu (x=%zu, y=%zu): '%s' is not a number", path, got + 1,
                           got % (size_t)field->nx, got / (size_t)field->nx, token);
        field->data[got++] = value * h->zscale;
    }
    if (got != count)
        return im_fail(IM_EFORMAT, "%s: truncated data: %zu of NumPoints x NumProfiles = %zu values", path, got,
                       count);
    if (fscanf(stream, "%63s", token) == 1 && token[0] != '*')
        return im_fail(IM_EFORMAT, "%s: more values than NumPoints x NumProfiles = %zu ('%s' follows)", path, count,
                       token);
    return IM_OK;
}

/* ---- binary ---- */

static double load_le(const uint8_t *bytes, int size, int type)
{
    uint64_t bits = 0;
    for (int i = size - 1; i >= 0; --i)
        bits = bits << 8 | bytes[i];
    union {
        uint64_t u;
        double d;
    } d8 = {bits};
    union {
        uint32_t u;
        float f;
    } f4 = {(uint32_t)bits};
    switch (type) {
    case SDF_UINT8:
    case SDF_UINT16:
    case SDF_UINT32: return (double)bits;
    case SDF_SINT8: return (int8_t)bits;
    case SDF_SINT16: return (int16_t)bits;
    case SDF_SINT32: return (int32_t)bits;
    case SDF_FLOAT: return f4.f;
    default: return d8.d;
    }
}

static int read_binary_header(FILE *stream, const char *path, sdf_header *h)
{
    uint8_t b[SDF_BINARY_HEADER]; /* the 8-byte version is read already */
    if (fread(b + 8, 1, sizeof b - 8, stream) != sizeof b - 8)
        return im_fail(IM_EFORMAT, "%s: truncated header: expected %d bytes", path, SDF_BINARY_HEADER);
    const uint8_t *p = b + 8 + 10 + 12 + 12;
    h->points = (long)load_le(p, 2, SDF_UINT16);
    h->profiles = (long)load_le(p + 2, 2, SDF_UINT16);
    h->xscale = load_le(p + 4, 8, SDF_DOUBLE);
    h->yscale = load_le(p + 12, 8, SDF_DOUBLE);
    h->zscale = load_le(p + 20, 8, SDF_DOUBLE);
    h->compression = p[36];
    h->data_type = p[37];
    return check_header(path, h);
}

static int read_binary_values(FILE *stream, const char *path, const sdf_header *h, im_field *field)
{
    size_t count = im_field_count(field);
    int size = SDF_SIZES[h->data_type];
    uint8_t value[8];
    for (size_t i = 0; i < count; ++i) {
        if (fread(value, 1, (size_t)size, stream) != (size_t)size)
            return im_fail(IM_EFORMAT, "%s: truncated data: %zu of NumPoints x NumProfiles = %zu values", path, i,
                           count);
        field->data[i] = load_le(value, size, (int)h->data_type) * h->zscale;
    }
    int next = fgetc(stream);
    if (next != EOF && next != '*')
        return im_fail(IM_EFORMAT, "%s: more data than NumPoints x NumProfiles = %zu values, and no '*' trailer",
                       path, count);
    return IM_OK;
}

/* ---- reading ---- */

/* Whether the 7 bytes after the version's 'a' or 'b' are one of SDF_VERSIONS. */
static int known_version(const char *version)
{
    for (size_t i = 0; i < sizeof SDF_VERSIONS / sizeof *SDF_VERSIONS; ++i)
        if (memcmp(version, SDF_VERSIONS[i], 7) == 0)
            return 1;
    return 0;
}

static int read_header(FILE *stream, const char *path, sdf_header *h, int *ascii)
{
    char magic[8];
    long line = 1;
    if (fread(magic, 1, 8, stream) != 8 || (magic[0] != 'a' && magic[0] != 'b') || !known_version(magic + 1))
        return im_fail(IM_EFORMAT,
                       "%s: not an ISO 25178-71 surface data file (no aISO-1.0, bISO-1.0, aBCR-1.0, "
                       "bBCR-1.0, aBCR-0.0 or bBCR-0.0 first)",
                       path);
    *ascii = magic[0] == 'a';
    if (!*ascii)
        return read_binary_header(stream, path, h);
    int c = fgetc(stream); /* the rest of the version line */
    while (c != EOF && c != '\n')
        c = fgetc(stream);
    return read_ascii_header(stream, path, h, &line);
}

/* Before allocating: a regular file must hold at least the values the header claims (a binary value
 * takes its size in bytes, an ASCII one at least two: a digit and a separator), so that a header
 * claiming a huge grid over a few bytes is refused at once. Trailers may follow, so more is allowed. */
static int check_enough_data(FILE *stream, const char *path, const sdf_header *h, int ascii)
{
    struct stat info;
    long position = ftell(stream);
    if (position < 0 || fstat(fileno(stream), &info) != 0 || !S_ISREG(info.st_mode))
        return IM_OK;
    double needed = (double)h->points * (double)h->profiles * (ascii ? 2.0 : SDF_SIZES[h->data_type]);
    double present = (double)info.st_size - (double)position;
    if (present + (ascii ? 1.0 : 0.0) < needed) /* the last ASCII value needs no separator */
        return im_fail(IM_EFORMAT,
                       "%s: truncated data: NumPoints x NumProfiles = %ld x %ld values need at least %.0f "
                       "bytes, the file has %.0f after the header",
                       path, h->points, h->profiles, needed, present);
    return IM_OK;
}

int sdf_read_raw(const char *path, im_field **out, surface_stated *stated)
{
    *out = NULL;
    FILE *stream = fopen(path, "rb");
    if (!stream)
        return im_fail(IM_EIO, "%s: cannot open: %s", path, strerror(errno));
    sdf_header h = {.data_sets = 1};
    int ascii = 0;
    im_field *field = NULL;
    int status = read_header(stream, path, &h, &ascii);
    if (status == IM_OK)
        status = check_enough_data(stream, path, &h, ascii);
    if (status == IM_OK && (status = im_field_create((int)h.points, (int)h.profiles, 1.0, &field)) != IM_OK)
        im_fail_context(status, "%s", path);
    if (status == IM_OK)
        status = ascii ? read_ascii_values(stream, path, &h, field) : read_binary_values(stream, path, &h, field);
    fclose(stream);
    if (status != IM_OK) {
        im_field_free(field);
        return status;
    }
    *stated = (surface_stated){.units = {h.xscale, h.yscale, "m", "m"},
                               .spacing_keys = "Xscale and Yscale",
                               .lateral_key = "Xscale",
                               .height_key = "Zscale"};
    *out = field;
    return IM_OK;
}

int im_sdf_read(const char *path, im_field **out)
{
    ARG_REQUIRE(path, "path");
    ARG_REQUIRE(out, "out");
    return surface_read_format(path, sdf_read_raw, NULL, out, NULL);
}

/* ---- writing: binary, DataType double, heights and spacing in metres (Zscale 1) ---- */

static void store_le(uint8_t *p, uint64_t bits, int size)
{
    for (int i = 0; i < size; ++i)
        p[i] = (uint8_t)(bits >> (8 * i));
}

static void store_double(uint8_t *p, double value)
{
    union {
        double d;
        uint64_t u;
    } v = {value};
    store_le(p, v.u, 8);
}

int im_sdf_write(const char *path, const im_field *field)
{
    ARG_REQUIRE(path, "path");
    ARG_VIEW(field, "field");
    int writable = formats_check_heights_or_missing_writable(field, path);
    if (writable != IM_OK)
        return writable;
    double metres = im_length_unit_metres(field->unit, NULL);
    if (metres == 0.0)
        return im_fail(IM_EINVAL, "%s: an .sdf states metres: the surface needs a length unit (it has '%s')", path,
                       field->unit);
    if (field->nx > 65535 || field->ny > 65535)
        return im_fail(IM_EINVAL, "%s: %d x %d: an .sdf holds at most 65535 x 65535 points", path, field->nx,
                       field->ny);
    uint8_t header[SDF_BINARY_HEADER];
    memset(header, ' ', 8 + 10 + 12 + 12);
    memcpy(header, "bISO-1.0", 8);
    memcpy(header + 8, "indentmap", 9);
    uint8_t *p = header + 8 + 10 + 12 + 12;
    store_le(p, (uint64_t)field->nx, 2);
    store_le(p + 2, (uint64_t)field->ny, 2);
    store_double(p + 4, field->delta * metres);
    store_double(p + 12, field->delta * metres);
    store_double(p + 20, 1.0);
    store_double(p + 28, -1.0); /* Zresolution: unknown */
    p[36] = 0;                  /* no compression */
    p[37] = SDF_DOUBLE;
    p[38] = 0; /* no checksum */
    im_atomic_file file;
    int status = im_atomic_open(&file, path);
    if (status != IM_OK)
        return status;
    int ok = fwrite(header, 1, sizeof header, file.stream) == sizeof header;
    size_t count = im_field_count(field);
    for (size_t i = 0; ok && i < count; ++i) {
        uint8_t value[8];
        store_double(value, field->data[i] * metres);
        ok = fwrite(value, 1, 8, file.stream) == 8;
    }
    if (!ok) {
        im_atomic_abort(&file);
        return im_fail(IM_EIO, "%s: write failed: %s", path, strerror(errno));
    }
    return im_atomic_commit(&file);
}
