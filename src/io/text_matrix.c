#include "indentmap/io.h"
#include "core/args.h"

#include "indentmap/status.h"
#include "io/payload.h"
#include "io/readers.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

int im_text_write(const char *path, const im_field *field)
{
    ARG_REQUIRE(path, "path");
    ARG_VIEW(field, "field");
    int writable = io_check_heights_writable(field, path);
    if (writable != IM_OK)
        return writable;
    im_atomic_file file;
    int status = im_atomic_open(&file, path);
    if (status != IM_OK)
        return status;
    fprintf(file.stream, "# indentmap surface: %d columns x %d rows, row 0 (y = 0) first\n",
            field->nx, field->ny);
    fprintf(file.stream, "# Width: %.17g %s\n# Height: %.17g %s\n", field->nx * field->delta,
            field->unit, field->ny * field->delta, field->unit);
    if (field->unit[0])
        fprintf(file.stream, "# Value units: %s\n", field->unit);
    for (int iy = 0; iy < field->ny; ++iy) {
        const double *row = field->data + (size_t)iy * field->nx;
        for (int ix = 0; ix < field->nx; ++ix)
            fprintf(file.stream, ix ? " %.17g" : "%.17g", row[ix]);
        fputc('\n', file.stream);
    }
    return im_atomic_commit(&file);
}

/* A growing array of doubles. */
typedef struct value_list {
    double *values;
    size_t count, capacity;
} value_list;

/* Appends a value; growing the array is checked against the memory available, so that a text
 * file too large for this machine is refused before it is read whole. */
static int value_list_push(value_list *list, double value, const char *path, long line_number)
{
    if (list->count == list->capacity) {
        size_t capacity = list->capacity ? 2 * list->capacity : 4096;
        char what[4200];
        snprintf(what, sizeof what, "%s:%ld: room for %zu values", path, line_number, capacity);
        int status = im_memory_check((double)capacity * sizeof(double), what);
        if (status != IM_OK)
            return status;
        double *grown = realloc(list->values, capacity * sizeof *grown);
        if (!grown)
            return im_fail(IM_ENOMEM, "%s: allocation failed", what);
        list->values = grown;
        list->capacity = capacity;
    }
    list->values[list->count++] = value;
    return IM_OK;
}

/* A token for a message: at most 32 bytes, bytes outside printable ASCII as \xNN (a byte-order
 * mark or a control character would otherwise be invisible). */
static void visible_token(const char *token, char *out, size_t size)
{
    size_t used = 0;
    for (size_t i = 0; token[i] && i < 32 && used + 5 < size; ++i) {
        unsigned char c = (unsigned char)token[i];
        used += (size_t)snprintf(out + used, size - used, c >= 0x20 && c < 0x7f ? "%c" : "\\x%02x", c);
    }
    out[used] = '\0';
}

typedef struct text_header {
    double width, height;           /* Gwyddion's extents along x and y; 0 when absent */
    char width_unit[16], height_unit[16], value_unit[16];
    long columns, rows, line; /* a stated "C columns x R rows" and its line; 0 when none */
} text_header;

/* The text after "# KEY" (blanks skipped), or NULL when the header line is not about KEY. */
static const char *header_value(const char *line, const char *key)
{
    const char *at = line + 1 + strspn(line + 1, " \t");
    size_t length = strlen(key);
    return strncmp(at, key, length) == 0 ? at + length + strspn(at + length, " \t") : NULL;
}

/* A Gwyddion extent line, "# Width: 5.12 um": a finite length > 0 and an optional unit. */
static int parse_extent_header(const char *path, long line_number, const char *line, const char *key,
                               double *extent, char *unit, size_t unit_size)
{
    const char *value = header_value(line, key);
    if (!value)
        return IM_OK;
    char *end;
    double number = strtod(value, &end);
    char unit_text[64] = "";
    int words = sscanf(end, "%63s", unit_text);
    if (end == value || !isfinite(number) || !(number > 0.0) || strlen(unit_text) >= unit_size)
        return im_fail(IM_EFORMAT, "%s:%ld: %s '%.40s': expected a finite length > 0 and a unit", path,
                       line_number, key, value);
    *extent = number;
    snprintf(unit, unit_size, "%s", words == 1 ? unit_text : "");
    return IM_OK;
}

/* Gwyddion's "# Value units: m", the unit of the heights. */
static int parse_value_units(const char *path, long line_number, const char *line, text_header *header)
{
    const char *value = header_value(line, "Value units:");
    char unit[64] = "";
    if (!value)
        return IM_OK;
    if (sscanf(value, "%63s", unit) != 1 || strlen(unit) >= sizeof header->value_unit)
        return im_fail(IM_EFORMAT, "%s:%ld: Value units '%.40s': expected one unit name", path, line_number,
                       value);
    memcpy(header->value_unit, unit, sizeof header->value_unit);
    return IM_OK;
}

static int parse_header_line(const char *path, long line_number, const char *line, text_header *header)
{
    int status = parse_extent_header(path, line_number, line, "Width:", &header->width, header->width_unit,
                                     sizeof header->width_unit);
    if (status == IM_OK)
        status = parse_extent_header(path, line_number, line, "Height:", &header->height, header->height_unit,
                                     sizeof header->height_unit);
    if (status == IM_OK)
        status = parse_value_units(path, line_number, line, header);
    return status;
}

/* A header line stating the grid, "... 16 columns x 16 rows ..." (as im_text_write writes it). */
static void parse_shape_header(const char *line, long line_number, text_header *header)
{
    const char *at = strstr(line, " columns x ");
    if (!at || header->line)
        return;
    const char *start = at;
    while (start > line && start[-1] >= '0' && start[-1] <= '9')
        --start;
    long columns, rows;
    if (start < at && sscanf(start, "%ld columns x %ld rows", &columns, &rows) == 2) {
        header->columns = columns;
        header->rows = rows;
        header->line = line_number;
    }
}

/* Refuses data whose size disagrees with a grid the header states. */
static int check_stated_shape(const char *path, const text_header *header, long columns, long rows)
{
    if (!header->line || (header->columns == columns && header->rows == rows))
        return IM_OK;
    return im_fail(IM_EFORMAT, "%s:%ld: the header states %ld columns x %ld rows, but the file has %ld "
                   "columns x %ld rows of data (%s)", path, header->line, header->columns, header->rows, columns,
                   rows, rows < header->rows ? "rows are missing: truncated?" : "the size disagrees");
}

/* Parses the numbers of one data line into values, counting them in *count. */
static int parse_data_line(char *line, const char *path, long line_number, value_list *values, long *count)
{
    *count = 0;
    char shown[160];
    char *rest = NULL; /* strtok_r: surfaces are read by several threads at once (ensembles, Python) */
    for (char *token = strtok_r(line, " \t,\r\n", &rest); token; token = strtok_r(NULL, " \t,\r\n", &rest)) {
        char *end;
        errno = 0;
        double value = strtod(token, &end);
        if (end == token || *end != '\0') {
            visible_token(token, shown, sizeof shown);
            return im_fail(IM_EFORMAT, "%s:%ld: '%s' is not a number", path, line_number, shown);
        }
        if (isinf(value)) { /* NaN passes: a missing point, refused or filled once the grid is known */
            visible_token(token, shown, sizeof shown);
            return im_fail(IM_EFORMAT, "%s:%ld: value '%s' is not finite; heights must be finite numbers", path,
                           line_number, shown);
        }
        if (++*count > IM_FIELD_MAX_SIDE)
            return im_fail(IM_EFORMAT, "%s:%ld: more than %d values on one line: expected at most %d columns",
                           path, line_number, IM_FIELD_MAX_SIDE, IM_FIELD_MAX_SIDE);
        int status = value_list_push(values, value, path, line_number);
        if (status != IM_OK)
            return status;
    }
    return IM_OK;
}

/* The longest line accepted: a row of the widest grid at 64 bytes a value (%.17g needs at most 24). */
static const size_t MAX_LINE_BYTES = (size_t)IM_FIELD_MAX_SIDE * 64u;

/* A UTF-8 byte-order mark, which spreadsheet programs put before the first line, is not data. */
static char *skip_byte_order_mark(char *text, long line_number)
{
    return line_number == 1 && strncmp(text, "\xef\xbb\xbf", 3) == 0 ? text + 3 : text;
}

/* Adds one line's row of values (or header) to what was read so far. */
static int take_line(char *text, const char *path, long line_number, value_list *values, long *columns, long *rows,
                     text_header *header)
{
    if (text[0] == '#') {
        parse_shape_header(text, line_number, header);
        return parse_header_line(path, line_number, text, header);
    }
    long count;
    int status = parse_data_line(text, path, line_number, values, &count);
    if (status != IM_OK || count == 0)
        return status;
    if (*columns == 0)
        *columns = count;
    else if (count != *columns)
        return im_fail(IM_EFORMAT, "%s:%ld: %ld values, but the first data row has %ld", path, line_number, count,
                       *columns);
    if (++*rows > IM_FIELD_MAX_SIDE)
        return im_fail(IM_EFORMAT, "%s:%ld: more than %d data rows: expected at most %d rows", path, line_number,
                       IM_FIELD_MAX_SIDE, IM_FIELD_MAX_SIDE);
    return IM_OK;
}

static int read_rows(FILE *stream, const char *path, value_list *values, long *columns, long *rows,
                     text_header *header)
{
    im_text_line line = {0};
    int status = IM_OK, end = 0;
    while (status == IM_OK && (status = im_read_line(stream, path, MAX_LINE_BYTES, &line, &end)) == IM_OK && !end)
        status = take_line(skip_byte_order_mark(line.text, line.number), path, line.number, values, columns, rows,
                           header);
    free(line.text);
    return status;
}

/* What the Gwyddion headers state about units; Width and Height in different units are refused. */
static int stated_units(const char *path, const text_header *header, long columns, long rows,
                        surface_stated *stated)
{
    *stated = (surface_stated){.spacing_keys = "Width / columns and Height / rows", .lateral_key = "Width",
                               .height_key = "Value units"};
    if (header->width > 0.0 && header->height > 0.0 && strcmp(header->width_unit, header->height_unit) != 0)
        return im_fail(IM_EFORMAT, "%s: Width is in '%s' but Height in '%s': expected one lateral unit", path,
                       header->width_unit, header->height_unit);
    if (header->width > 0.0 || header->height > 0.0) { /* one extent alone states square pixels */
        stated->units.delta_y = header->height > 0.0 ? header->height / (double)rows : 0.0;
        stated->units.delta_x = header->width > 0.0 ? header->width / (double)columns : stated->units.delta_y;
        memcpy(stated->units.lateral, header->width > 0.0 ? header->width_unit : header->height_unit,
               sizeof stated->units.lateral);
    }
    memcpy(stated->units.height, header->value_unit, sizeof stated->units.height);
    return IM_OK;
}

int text_read_raw(const char *path, im_field **out, surface_stated *stated)
{
    *out = NULL;
    FILE *stream;
    int status = im_read_open(path, "r", IM_READ_OR_PIPE, &stream, NULL);
    if (status != IM_OK)
        return status;
    value_list values = {0};
    long columns = 0, rows = 0;
    text_header header = {0};
    status = read_rows(stream, path, &values, &columns, &rows, &header);
    fclose(stream);
    if (status == IM_OK && rows == 0)
        status = im_fail(IM_EFORMAT, "%s: no data rows", path);
    if (status == IM_OK)
        status = check_stated_shape(path, &header, columns, rows);
    if (status == IM_OK)
        status = stated_units(path, &header, columns, rows, stated);
    im_field *field = NULL;
    if (status == IM_OK)
        status = im_field_create((int)columns, (int)rows, 1.0, &field);
    if (status == IM_OK) {
        memcpy(field->data, values.values, values.count * sizeof *values.values);
        *out = field;
    }
    free(values.values);
    return status;
}

int im_text_read(const char *path, im_field **out)
{
    ARG_REQUIRE(path, "path");
    ARG_REQUIRE(out, "out");
    return surface_read_format(path, text_read_raw, NULL, out, NULL);
}
