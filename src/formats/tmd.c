/* TrueMap / GelSight .tmd: "Binary TrueMap Data File v2.0\r\n\0" (32 bytes), a comment ending in a NUL,
 * then little-endian uint32 columns and rows, float32 lengths along x and y and offsets along x and y,
 * then columns x rows float32 heights, row by row (x fastest). Lengths and heights are in millimetres
 * (GelSight's readtmd/writetmd, SurfaceTopography's TMD reader). */
#include "indentmap/formats.h"
#include "indentmap/io.h"

#include "indentmap/status.h"
#include "formats/payload.h"
#include "formats/readers.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

static const char TMD_MAGIC[32] = "Binary TrueMap Data File v2.0\r\n";
enum { TMD_COMMENT_MAX = 4096 };

typedef struct tmd_header {
    uint32_t columns, rows;
    float length_x, length_y;
} tmd_header;

static uint32_t little_u32(const unsigned char *b)
{
    return (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
}

static float little_f32(const unsigned char *b)
{
    uint32_t bits = little_u32(b);
    float value;
    memcpy(&value, &bits, sizeof value);
    return value;
}

/* Skips the comment up to and including its NUL, at most TMD_COMMENT_MAX bytes. */
static int skip_comment(FILE *stream, const char *path)
{
    for (int length = 0; length <= TMD_COMMENT_MAX; ++length) {
        int c = fgetc(stream);
        if (c == EOF)
            return im_fail(IM_EFORMAT,
                           "%s: truncated header: the comment after the magic line has no "
                           "terminating NUL",
                           path);
        if (c == '\0')
            return IM_OK;
    }
    return im_fail(IM_EFORMAT,
                   "%s: the comment after the magic line has no terminating NUL in its first %d "
                   "bytes",
                   path, TMD_COMMENT_MAX);
}

static int check_length(const char *path, const char *name, float length)
{
    if (!isfinite(length) || length <= 0.0f)
        return im_fail(IM_EFORMAT, "%s: %s = %g: expected a positive length (mm)", path, name, (double)length);
    return IM_OK;
}

static int read_header(FILE *stream, const char *path, tmd_header *h)
{
    unsigned char magic[sizeof TMD_MAGIC], sizes[24];
    if (fread(magic, 1, sizeof magic, stream) != sizeof magic || memcmp(magic, TMD_MAGIC, sizeof magic) != 0)
        return im_fail(IM_EFORMAT,
                       "%s: not a TrueMap file: expected the 32-byte magic 'Binary TrueMap Data "
                       "File v2.0' + CR LF NUL",
                       path);
    int status = skip_comment(stream, path);
    if (status != IM_OK)
        return status;
    if (fread(sizes, 1, sizeof sizes, stream) != sizeof sizes)
        return im_fail(IM_EFORMAT,
                       "%s: truncated header: expected columns, rows (uint32), lengths and offsets "
                       "(float32) after the comment",
                       path);
    *h = (tmd_header){.columns = little_u32(sizes),
                      .rows = little_u32(sizes + 4),
                      .length_x = little_f32(sizes + 8),
                      .length_y = little_f32(sizes + 12)};
    if (h->columns < 1 || h->rows < 1 || h->columns > IM_FIELD_MAX_SIDE || h->rows > IM_FIELD_MAX_SIDE)
        return im_fail(IM_EFORMAT, "%s: columns = %lu, rows = %lu: expected each in [1, %d]", path,
                       (unsigned long)h->columns, (unsigned long)h->rows, IM_FIELD_MAX_SIDE);
    status = check_length(path, "length x", h->length_x);
    return status == IM_OK ? check_length(path, "length y", h->length_y) : status;
}

static int read_heights(FILE *stream, const char *path, im_field *field)
{
    size_t count = im_field_count(field), got = 0;
    unsigned char value[4];
    while (got < count && fread(value, 1, sizeof value, stream) == sizeof value)
        field->data[got++] = little_f32(value);
    if (got != count)
        return im_fail(IM_EFORMAT, "%s: truncated data: %zu of %zu float32 heights (columns %d x rows %d)", path, got,
                       count, field->nx, field->ny);
    return IM_OK;
}

int tmd_read_raw(const char *path, im_field **out, surface_stated *stated)
{
    *out = NULL;
    FILE *stream;
    int status = im_read_open(path, "rb", IM_READ_REGULAR, &stream, NULL);
    if (status != IM_OK)
        return status;
    tmd_header header = {0};
    im_field *field = NULL;
    status = read_header(stream, path, &header);
    if (status == IM_OK) {
        char claim[64];
        snprintf(claim, sizeof claim, "columns %lu x rows %lu float32", (unsigned long)header.columns,
                 (unsigned long)header.rows);
        status = formats_check_grid(stream, path, header.columns, header.rows, 4u, claim);
    }
    if (status == IM_OK && (status = im_field_create((int)header.columns, (int)header.rows, 1.0, &field)) != IM_OK)
        im_fail_context(status, "%s", path);
    if (status == IM_OK)
        status = read_heights(stream, path, field);
    fclose(stream);
    if (status != IM_OK) {
        im_field_free(field);
        return status;
    }
    *stated = (surface_stated){.spacing_keys = "length x / columns and length y / rows",
                               .lateral_key = "TrueMap lengths (mm)",
                               .height_key = "TrueMap heights (mm)"};
    stated->units.delta_x = header.length_x / (double)header.columns;
    stated->units.delta_y = header.length_y / (double)header.rows;
    snprintf(stated->units.lateral, sizeof stated->units.lateral, "mm");
    snprintf(stated->units.height, sizeof stated->units.height, "mm");
    snprintf(stated->conversion, sizeof stated->conversion, "TrueMap float32 heights in mm");
    *out = field;
    return IM_OK;
}
