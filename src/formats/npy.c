#include "indentmap/formats.h"
#include "indentmap/io.h"
#include "core/args.h"

#include "indentmap/status.h"
#include "formats/payload.h"
#include "formats/readers.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char NPY_MAGIC[6] = {'\x93', 'N', 'U', 'M', 'P', 'Y'};

static void store_le16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
}

/* Little-endian host assumed for the payload (x86-64, aarch64); checked at compile time. */
_Static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "npy payload code assumes little-endian");

static int write_payload(FILE *stream, const im_field *field, enum im_npy_dtype dtype)
{
    size_t count = im_field_count(field);
    if (dtype == IM_NPY_FLOAT64)
        return fwrite(field->data, sizeof(double), count, stream) == count ? IM_OK : IM_EIO;
    for (size_t i = 0; i < count; ++i) {
        float value = (float)field->data[i];
        if (fwrite(&value, sizeof value, 1, stream) != 1)
            return IM_EIO;
    }
    return IM_OK;
}

int im_npy_write(const char *path, const im_field *field, enum im_npy_dtype dtype)
{
    ARG_REQUIRE(path, "path");
    ARG_VIEW(field, "field");
    char dict[128];
    int dict_length = snprintf(dict, sizeof dict, "{'descr': '%s', 'fortran_order': False, 'shape': (%d, %d), }",
                               dtype == IM_NPY_FLOAT64 ? "<f8" : "<f4", field->ny, field->nx);
    /* magic(6) + version(2) + length(2) + dict + padding + '\n' is a multiple of 64 bytes */
    size_t header_length = (size_t)dict_length + 1;
    size_t total = 10 + header_length;
    size_t padding = (64 - total % 64) % 64;
    header_length += padding;
    uint8_t prefix[10];
    memcpy(prefix, NPY_MAGIC, 6);
    prefix[6] = 1;
    prefix[7] = 0;
    store_le16(prefix + 8, (uint16_t)header_length);
    im_atomic_file file;
    int status = im_atomic_open(&file, path);
    if (status != IM_OK)
        return status;
    int ok = fwrite(prefix, 1, sizeof prefix, file.stream) == sizeof prefix &&
             fwrite(dict, 1, (size_t)dict_length, file.stream) == (size_t)dict_length;
    for (size_t i = 0; ok && i < padding; ++i)
        ok = fputc(' ', file.stream) != EOF;
    ok = ok && fputc('\n', file.stream) != EOF && write_payload(file.stream, field, dtype) == IM_OK;
    if (!ok) {
        im_atomic_abort(&file);
        return im_fail(IM_EIO, "%s: write failed: %s", path, strerror(errno));
    }
    return im_atomic_commit(&file);
}

/* Finds the value text after 'key': in a NumPy header dictionary. */
static const char *dict_value(const char *dict, const char *key)
{
    char pattern[32];
    snprintf(pattern, sizeof pattern, "'%s'", key);
    const char *at = strstr(dict, pattern);
    if (!at)
        return NULL;
    at += strlen(pattern);
    while (*at == ' ' || *at == ':')
        ++at;
    return at;
}

static const char *skip_blanks(const char *p)
{
    while (*p == ' ')
        ++p;
    return p;
}

/* Parses "(rows, cols)" with an optional trailing comma; 0 for any other shape. */
static int parse_shape(const char *text, long *rows, long *cols)
{
    char *end;
    const char *p = skip_blanks(text);
    if (*p++ != '(')
        return 0;
    *rows = strtol(p, &end, 10);
    if (end == p)
        return 0;
    p = skip_blanks(end);
    if (*p++ != ',')
        return 0;
    *cols = strtol(p, &end, 10);
    if (end == p)
        return 0;
    p = skip_blanks(end);
    if (*p == ',')
        p = skip_blanks(p + 1);
    return *p == ')';
}

/* Length of a quoted value "'<i8'" including both quotes (at most 24), else of its first word. */
static int quoted_length(const char *text)
{
    const char *close = text[0] == '\'' ? strchr(text + 1, '\'') : NULL;
    size_t length = close ? (size_t)(close - text) + 1 : strcspn(text, ",} ");
    return length < 24 ? (int)length : 24;
}

/* The element type of a .npy: its descr ("'>i2'"), kind ('f' float, 'i' signed, 'u' unsigned), size
 * in bytes and byte order. */
typedef struct npy_type {
    char descr[8];
    char kind;
    int size, big_endian, fortran_order;
} npy_type;

/* Parses "'<f8'"-style descr: byte order '<' (little), '>' (big), '=' (native, little here) or '|'
 * (not applicable: one byte), kind f (4 or 8 bytes), i or u (1, 2, 4 or 8). 0 for anything else. */
static int parse_descr(const char *text, npy_type *type)
{
    char order, kind, tail;
    int size;
    if (sscanf(text, "'%c%c%d%c", &order, &kind, &size, &tail) != 4 || tail != '\'' || !strchr("<>=|", order))
        return 0;
    int integer = (kind == 'i' || kind == 'u') && (size == 1 || size == 2 || size == 4 || size == 8);
    int floating = kind == 'f' && (size == 4 || size == 8);
    if (!(integer || floating) || (order == '|') != (size == 1))
        return 0;
    snprintf(type->descr, sizeof type->descr, "%c%c%d", order, kind, size);
    type->kind = kind;
    type->size = size;
    type->big_endian = order == '>';
    return 1;
}

/* Length of a "(...)" tuple up to its closing parenthesis (at most 48), so that a message quotes
 * the shape and not the header's padding after it. */
static int tuple_length(const char *text)
{
    size_t length = strcspn(text, ")");
    length += text[length] == ')';
    return length < 48 ? (int)length : 48;
}

static int parse_header(const char *path, const char *dict, npy_type *type, long *rows, long *cols)
{
    const char *descr = dict_value(dict, "descr");
    const char *order = dict_value(dict, "fortran_order");
    const char *shape = dict_value(dict, "shape");
    if (!descr || !order || !shape)
        return im_fail(IM_EFORMAT, "%s: header lacks 'descr', 'fortran_order' or 'shape'", path);
    if (!parse_descr(descr, type))
        return im_fail(IM_EFORMAT,
                       "%s: dtype %.*s is not supported; expected a float ('<f8', '>f4', ...) or an "
                       "integer ('<i2', '>u4', '|u1', ...) of either byte order",
                       path, quoted_length(descr), descr);
    if (strncmp(order, "False", 5) != 0 && strncmp(order, "True", 4) != 0)
        return im_fail(IM_EFORMAT, "%s: fortran_order %.8s: expected True or False", path, order);
    type->fortran_order = order[0] == 'T';
    if (!parse_shape(shape, rows, cols))
        return im_fail(IM_EFORMAT, "%s: shape %.*s: expected a 2-D shape (rows, columns)", path, tuple_length(shape),
                       shape);
    if (*rows < 1 || *cols < 1)
        return im_fail(IM_EFORMAT, "%s: shape (%ld, %ld): expected each side >= 1", path, *rows, *cols);
    return IM_OK; /* the upper bound on the sides is formats_check_grid's, after the memory check */
}

static int read_header(FILE *stream, const char *path, npy_type *type, long *rows, long *cols)
{
    uint8_t prefix[12];
    if (fread(prefix, 1, 8, stream) != 8 || memcmp(prefix, NPY_MAGIC, 6) != 0)
        return im_fail(IM_EFORMAT, "%s: not a .npy file (no \\x93NUMPY magic)", path);
    int major = prefix[6];
    size_t length_bytes = major == 1 ? 2 : 4;
    if (major < 1 || major > 3 || fread(prefix + 8, 1, length_bytes, stream) != length_bytes)
        return im_fail(IM_EFORMAT, "%s: unsupported .npy version %d or truncated header", path, major);
    size_t header_length = prefix[8] | (size_t)prefix[9] << 8;
    if (length_bytes == 4)
        header_length |= (size_t)prefix[10] << 16 | (size_t)prefix[11] << 24;
    if (header_length > 65536)
        return im_fail(IM_EFORMAT, "%s: header length %zu is implausible", path, header_length);
    char *dict = calloc(header_length + 1, 1);
    if (!dict)
        return im_fail(IM_ENOMEM, "%s: header allocation failed", path);
    int status = fread(dict, 1, header_length, stream) == header_length
                     ? parse_header(path, dict, type, rows, cols)
                     : im_fail(IM_EFORMAT, "%s: truncated header", path);
    free(dict);
    return status;
}

/* One element of the payload as a double. */
static double decode(const uint8_t *bytes, const npy_type *type)
{
    uint8_t ordered[8];
    for (int i = 0; i < type->size; ++i) /* into the host's (little-endian) order */
        ordered[i] = bytes[type->big_endian ? type->size - 1 - i : i];
    union {
        uint8_t b[8];
        double f8;
        float f4;
        int8_t i1;
        int16_t i2;
        int32_t i4;
        int64_t i8;
        uint8_t u1;
        uint16_t u2;
        uint32_t u4;
        uint64_t u8;
    } v;
    memcpy(v.b, ordered, (size_t)type->size);
    switch (type->kind * 16 + type->size) {
    case 'f' * 16 + 8: return v.f8;
    case 'f' * 16 + 4: return v.f4;
    case 'i' * 16 + 1: return v.i1;
    case 'i' * 16 + 2: return v.i2;
    case 'i' * 16 + 4: return v.i4;
    case 'i' * 16 + 8: return (double)v.i8;
    case 'u' * 16 + 1: return v.u1;
    case 'u' * 16 + 2: return v.u2;
    case 'u' * 16 + 4: return v.u4;
    default: return (double)v.u8;
    }
}

/* Reads the payload element by element (in blocks), converting each to double and placing it in
 * row-major order whatever the file's order. */
static int read_payload(FILE *stream, const char *path, const npy_type *type, im_field *field)
{
    size_t count = im_field_count(field), got = 0, rows = (size_t)field->ny, cols = (size_t)field->nx;
    uint8_t block[8 * 4096];
    size_t per_block = sizeof block / (size_t)type->size;
    while (got < count) {
        size_t want = count - got < per_block ? count - got : per_block;
        size_t read = fread(block, (size_t)type->size, want, stream);
        for (size_t k = 0; k < read; ++k, ++got) {
            size_t index = type->fortran_order ? (got % rows) * cols + got / rows : got;
            field->data[index] = decode(block + k * (size_t)type->size, type);
        }
        if (read < want)
            break;
    }
    if (got != count)
        return im_fail(IM_EFORMAT, "%s: truncated data: %zu of %zu values (header shape %d x %d)", path, got, count,
                       field->ny, field->nx);
    if (fgetc(stream) != EOF)
        return im_fail(IM_EFORMAT, "%s: more data than the header shape (%d, %d) holds", path, field->ny, field->nx);
    return IM_OK;
}

/* What was converted to reach float64 in C order, for the read info; "" for '<f8' in C order. */
static void describe_conversion(const npy_type *type, char *text, size_t size)
{
    static const char *const KINDS[] = {"float", "int", "uint"};
    int kind = type->kind == 'f' ? 0 : type->kind == 'i' ? 1 : 2;
    int converted = strcmp(type->descr, "<f8") != 0 && strcmp(type->descr, "=f8") != 0;
    snprintf(text, size, "%s%s%s%s%d%s", converted ? "'" : "", converted ? type->descr : "", converted ? "' (" : "",
             converted ? KINDS[kind] : "", converted ? 8 * type->size : 0, converted ? ") converted to float64" : "");
    if (!converted)
        text[0] = '\0';
    if (type->fortran_order)
        snprintf(text + strlen(text), size - strlen(text), "%sFortran order transposed to C order",
                 converted ? "; " : "");
}

int npy_read_raw(const char *path, im_field **out, surface_stated *stated)
{
    *stated = (surface_stated){.spacing_keys = "--delta",
                               .lateral_key = "--unit",
                               .height_key = "--height-unit",
                               .npy_order = IM_NPY_ORDER_YX};
    *out = NULL;
    FILE *stream;
    int opened = im_read_open(path, "rb", IM_READ_OR_PIPE, &stream, NULL);
    if (opened != IM_OK)
        return opened;
    npy_type type = {0};
    long rows = 0, cols = 0;
    im_field *field = NULL;
    int status = read_header(stream, path, &type, &rows, &cols);
    if (status == IM_OK) {
        char claim[96];
        snprintf(claim, sizeof claim, "shape (%ld, %ld) of %s", rows, cols, type.descr);
        status = formats_check_grid(stream, path, cols, rows, (unsigned)type.size, claim);
    }
    if (status == IM_OK) {
        status = im_field_create((int)cols, (int)rows, 1.0, &field);
        if (status != IM_OK)
            im_fail_context(status, "%s", path);
    }
    if (status == IM_OK)
        status = read_payload(stream, path, &type, field);
    if (status == IM_OK)
        status = npy_sidecar_read(path, stated, field->value_unit, sizeof field->value_unit);
    fclose(stream);
    if (status != IM_OK) {
        im_field_free(field);
        return status;
    }
    describe_conversion(&type, stated->conversion, sizeof stated->conversion);
    *out = field;
    return IM_OK;
}

/* The field of an array indexed [x, y] (field->nx is its second extent, ny its first), rows along y. */
static int transpose(const char *path, im_field *field)
{
    im_field *rows_y = NULL;
    int status = im_field_create(field->ny, field->nx, field->delta, &rows_y);
    if (status != IM_OK)
        return im_fail_context(status, "%s: indexed [x, y], transposed", path);
    for (size_t x = 0; x < (size_t)rows_y->nx; ++x)
        for (size_t y = 0; y < (size_t)rows_y->ny; ++y)
            rows_y->data[y * (size_t)rows_y->nx + x] = field->data[x * (size_t)field->nx + y];
    double *stored = field->data;
    field->data = rows_y->data;
    rows_y->data = stored;
    field->nx = rows_y->nx;
    field->ny = rows_y->ny;
    im_field_free(rows_y);
    return IM_OK;
}

int npy_apply_order(const char *path, im_field *field, surface_stated *stated, const im_surface_read_options *options)
{
    enum im_npy_order order = options && options->npy_order ? options->npy_order : stated->npy_order;
    if (stated->npy_order == IM_NPY_ORDER_SIDECAR || order != IM_NPY_ORDER_XY)
        return IM_OK; /* not a .npy, or rows along y */
    size_t used = strlen(stated->conversion);
    snprintf(stated->conversion + used, sizeof stated->conversion - used, "%sindexed [x, y]", used ? "; " : "");
    return transpose(path, field);
}

int im_npy_read(const char *path, im_field **out)
{
    ARG_REQUIRE(path, "path");
    ARG_REQUIRE(out, "out");
    return surface_read_format(path, npy_read_raw, NULL, out, NULL);
}
