#include "indentmap/formats.h"
#include "indentmap/io.h"
#include "core/args.h"

#include "indentmap/status.h"
#include "formats/payload.h"
#include "formats/gzip_stream.h"
#include "formats/readers.h"
#include "formats/text_columns.h"
#include "formats/text_header.h"
#include "formats/text_points.h"
#include "formats/text_preamble.h"
#include "formats/utf16_text.h"
#include "core/number.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

int im_text_write(const char *path, const im_field *field)
{
    ARG_REQUIRE(path, "path");
    ARG_VIEW(field, "field");
    int writable = formats_check_heights_or_missing_writable(field, path);
    if (writable != IM_OK)
        return writable;
    im_atomic_file file;
    int status = im_atomic_open(&file, path);
    if (status != IM_OK)
        return status;
    fprintf(file.stream, "# indentmap surface: %d columns x %d rows, row 0 (y = 0) first\n", field->nx, field->ny);
    fprintf(file.stream, "# Width: %.17g %s\n# Height: %.17g %s\n", field->nx * field->delta, field->unit,
            field->ny * field->delta, field->unit);
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

/* The number of fields of line between any of separators. */
static int count_fields(const char *line, const char *separators)
{
    int count = 0;
    for (const char *at = line + strspn(line, separators); *at; at += strspn(at, separators)) {
        ++count;
        at += strcspn(at, separators);
    }
    return count;
}

/* A line written with decimal commas ("1,5 -2,25" or "1,5;-2,25": no '.', a comma between digits,
 * and blanks or semicolons between the values) has its commas turned into points, so that "1,5" is
 * read as 1.5, not split into 1 and 5; returns 1 for such a line. Commas between values (CSV) stay
 * separators. */
static int decimal_commas_to_points(char *line)
{
    if (strchr(line, '.') || count_fields(line, " \t;\r\n") < 2)
        return 0;
    int decimal = 0;
    for (char *at = strchr(line, ','); at; at = strchr(at + 1, ','))
        decimal |= at > line && isdigit((unsigned char)at[-1]) && isdigit((unsigned char)at[1]);
    for (char *at = strchr(line, ','); decimal && at; at = strchr(at + 1, ','))
        *at = '.';
    return decimal;
}

/* Parses the numbers of one data line into values, counting them in *count. */
static int parse_data_line(char *line, const char *path, long line_number, value_list *values, long *count)
{
    *count = 0;
    char shown[160];
    const char *separators = decimal_commas_to_points(line) ? " \t;\r\n" : " \t,;\r\n";
    char *rest = NULL; /* strtok_r: surfaces are read by several threads at once (ensembles, Python) */
    for (char *token = strtok_r(line, separators, &rest); token; token = strtok_r(NULL, separators, &rest)) {
        char *end;
        errno = 0;
        double value = number_parse(token, &end);
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
            return im_fail(IM_EFORMAT, "%s:%ld: more than %d values on one line: expected at most %d columns", path,
                           line_number, IM_FIELD_MAX_SIDE, IM_FIELD_MAX_SIDE);
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

/* What has been read of a text file so far. */
typedef struct text_reading {
    value_list values;
    long columns, rows, first_row_line;
    text_header header;
    text_columns names;     /* a header row naming x, y and a height */
    text_preamble preamble; /* other text above the numbers */
} text_reading;

/* A line of text above the numbers: a header row of x y z points, or what the numbers are judged with. */
static void take_text_line(const char *text, const char *path, long line_number, text_reading *reading)
{
    if (!text_columns_is_named_row(text))
        text_preamble_take(&reading->preamble, line_number, text, "");
    else if (text_columns_parse(path, line_number, text, &reading->names) != IM_OK)
        text_preamble_take(&reading->preamble, line_number, text, im_last_error());
}

/* 1 when value can count rows: a whole number, not negative. */
static int is_count(double value) { return value >= 0.0 && value == floor(value); }

/* A row of count values, the last count of reading->values. A lone whole number on the first row above
 * rows of more values is their count (a profile's point count), not a row. */
static int take_row(const char *path, long line_number, long count, text_reading *reading)
{
    double *values = reading->values.values;
    if (reading->rows == 1 && reading->columns == 1 && count > 1 && is_count(values[0])) { /* 1 + count values */
        text_preamble_take_count(&reading->preamble, reading->first_row_line, values[0]);
        memmove(values, values + 1, (size_t)count * sizeof *values);
        --reading->values.count;
        reading->rows = 0;
        reading->columns = 0;
    }
    if (reading->columns == 0) {
        reading->columns = count;
        reading->first_row_line = line_number;
    } else if (count != reading->columns)
        return im_fail(IM_EFORMAT, "%s:%ld: %ld values, but the first data row has %ld", path, line_number, count,
                       reading->columns);
    if (++reading->rows > IM_FIELD_MAX_SIDE && reading->columns != 3) /* x y z points may be many more than a side */
        return im_fail(IM_EFORMAT, "%s:%ld: more than %d data rows: expected at most %d rows", path, line_number,
                       IM_FIELD_MAX_SIDE, IM_FIELD_MAX_SIDE);
    return IM_OK;
}

/* Adds one line's row of values (or header, or text above the numbers) to what was read so far. */
static int take_line(char *text, const char *path, long line_number, text_reading *reading)
{
    if (text[0] == '#')
        return text_header_parse_comment(path, line_number, text, &reading->header);
    if (reading->rows == 0 && text_header_is_vision_line(text))
        return text_header_parse_vision(path, line_number, text, &reading->header);
    if (reading->rows == 0 && !reading->names.line && text_preamble_is_text(text)) {
        take_text_line(text, path, line_number, reading);
        return IM_OK;
    }
    long count;
    int status = parse_data_line(text, path, line_number, &reading->values, &count);
    return status != IM_OK || count == 0 ? status : take_row(path, line_number, count, reading);
}

static int read_rows(FILE *stream, const char *path, text_reading *reading)
{
    im_text_line line = {0};
    int status = IM_OK, end = 0;
    while (status == IM_OK && (status = im_read_line(stream, path, MAX_LINE_BYTES, &line, &end)) == IM_OK && !end)
        status = take_line(skip_byte_order_mark(line.text, line.number), path, line.number, reading);
    free(line.text);
    return status;
}

/* A file of one or two columns (or rows) is a profile, which a 2-D contact cannot use; reading it as
 * a 2 x N map would give a number a researcher might publish. */
static int refuse_line_scan(const char *path, long columns, long rows)
{
    return im_fail(IM_EFORMAT,
                   "%s: %ld column%s x %ld row%s of numbers: " LINE_SCAN_REFUSAL " (heights, or x and "
                   "height pairs); " LINE_SCAN_ADVICE,
                   path, columns, columns == 1 ? "" : "s", rows, rows == 1 ? "" : "s");
}

/* The numbers as a columns x rows matrix, each multiplied by factor (1: as stored). */
static int matrix_field(const value_list *values, long columns, long rows, double factor, im_field **out)
{
    int status = im_field_create((int)columns, (int)rows, 1.0, out);
    for (size_t k = 0; status == IM_OK && k < values->count; ++k)
        (*out)->data[k] = values->values[k] * factor;
    return status;
}

/* The grid the numbers and their header describe: a matrix, or x y z points placed on their grid; text
 * above them (not a header row of x y z points) says what they are, a line scan, when it is refused. */
static int numbers_to_field(const char *path, const text_reading *reading, im_field **out, surface_stated *stated)
{
    long columns = reading->columns, rows = reading->rows;
    if (reading->preamble.lines)
        return text_preamble_refuse(path, &reading->preamble, columns, rows);
    if (rows == 0)
        return im_fail(IM_EFORMAT, "%s: no data rows", path);
    const text_header *header = &reading->header;
    int status = text_header_check_shape(path, header, columns, rows);
    if (status != IM_OK)
        return status;
    if (reading->names.line || (columns == 3 && !text_header_states_a_matrix(header))) {
        status = text_columns_check(path, &reading->names, header, columns);
        if (status == IM_OK)
            status = text_points_grid(path, reading->values.values, rows, out, stated);
        if (status == IM_OK)
            text_columns_stated_units(&reading->names, header, stated);
        return status;
    }
    if (columns < 3 || rows < 3)
        return refuse_line_scan(path, columns, rows);
    double factor;
    status = text_header_stated_units(path, header, columns, rows, stated, &factor);
    return status == IM_OK ? matrix_field(&reading->values, columns, rows, factor, out) : status;
}

/* The record of how the values were read says the text was gzip-compressed. */
static void note_decompressed(surface_stated *stated)
{
    char before[sizeof stated->conversion];
    memcpy(before, stated->conversion, sizeof before);
    snprintf(stated->conversion, sizeof stated->conversion, "%s%.70s",
             before[0] ? "gzip-compressed text; " : "gzip-compressed text", before);
}

/* The record of how the values were read says the text was UTF-16 (decoded to UTF-8). */
static void note_encoding(surface_stated *stated, const char *encoding)
{
    char before[sizeof stated->conversion];
    memcpy(before, stated->conversion, sizeof before);
    snprintf(stated->conversion, sizeof stated->conversion, "%s text%s%.70s", encoding, before[0] ? "; " : "",
             before);
}

/* The file's text: decompressed when it is gzip, decoded when it is UTF-16. */
static int open_text(const char *path, FILE **stream, int *compressed, const char **encoding)
{
    *encoding = NULL;
    int status = im_read_open(path, "r", IM_READ_OR_PIPE, stream, NULL);
    if (status == IM_OK)
        status = formats_gunzip_if_compressed(stream, path, compressed);
    if (status == IM_OK && !*compressed)
        status = formats_utf16_decode_if_marked(stream, path, encoding);
    return status;
}

int text_read_raw(const char *path, im_field **out, surface_stated *stated)
{
    *out = NULL;
    FILE *stream;
    int compressed = 0;
    const char *encoding;
    int status = open_text(path, &stream, &compressed, &encoding);
    if (status != IM_OK)
        return status;
    text_reading reading = {0};
    status = read_rows(stream, path, &reading);
    if (fclose(stream) != 0 && status == IM_OK && compressed) /* zlib found the stream cut or its CRC wrong */
        status = im_fail(IM_EFORMAT, "%s: the gzip stream ends early or is damaged", path);
    im_field *field = NULL;
    if (status == IM_OK)
        status = numbers_to_field(path, &reading, &field, stated);
    if (status == IM_OK && compressed)
        note_decompressed(stated);
    if (status == IM_OK && encoding)
        note_encoding(stated, encoding);
    if (status == IM_OK)
        *out = field;
    else
        im_field_free(field);
    free(reading.values.values);
    return status;
}

int im_text_read(const char *path, im_field **out)
{
    ARG_REQUIRE(path, "path");
    ARG_REQUIRE(out, "out");
    return surface_read_format(path, text_read_raw, NULL, out, NULL);
}
