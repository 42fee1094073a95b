#include "indentmap/io.h"

#include "indentmap/status.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

int im_text_write(const char *path, const im_field *field)
{
    im_atomic_file file;
    int status = im_atomic_open(&file, path);
    if (status != IM_OK)
        return status;
    fprintf(file.stream, "# indentmap surface: %d columns x %d rows, row 0 (y = 0) first\n",
            field->nx, field->ny);
    fprintf(file.stream, "# Width: %.17g %s\n# Height: %.17g %s\n", field->nx * field->delta,
            field->unit, field->ny * field->delta, field->unit);
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

static int value_list_push(value_list *list, double value)
{
    if (list->count == list->capacity) {
        size_t capacity = list->capacity ? 2 * list->capacity : 4096;
        double *grown = realloc(list->values, capacity * sizeof *grown);
        if (!grown)
            return IM_ENOMEM;
        list->values = grown;
        list->capacity = capacity;
    }
    list->values[list->count++] = value;
    return IM_OK;
}

/* Physical extent and unit from a Gwyddion "# Width: 5.12 um" header line. */
static void parse_extent_header(const char *line, const char *key, double *extent, char *unit, size_t unit_size)
{
    size_t key_length = strlen(key);
    if (strncmp(line + 1 + strspn(line + 1, " "), key, key_length) != 0)
        return;
    const char *value = line + 1 + strspn(line + 1, " ") + key_length;
    char unit_text[16] = "";
    if (sscanf(value, "%lf %15s", extent, unit_text) >= 1 && unit_text[0])
        snprintf(unit, unit_size, "%s", unit_text);
}

typedef struct text_header {
    double width, height;
    char unit[16];
    long columns, rows, line; /* a stated "C columns x R rows" and its line; 0 when none */
} text_header;

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

/* Parses the numbers of one data line into values and *count; IM_EFORMAT or IM_ENOMEM with a message. */
static int parse_data_line(char *line, const char *path, long line_number, value_list *values, long *count)
{
    *count = 0;
    for (char *token = strtok(line, " \t,\r\n"); token; token = strtok(NULL, " \t,\r\n")) {
        char *end;
        errno = 0;
        double value = strtod(token, &end);
        if (end == token || *end != '\0') {
            return im_fail(IM_EFORMAT, "%s:%ld: '%.32s' is not a number", path, line_number, token);
        }
        if (!isfinite(value)) {
            return im_fail(IM_EFORMAT, "%s:%ld: value '%.32s' is not finite; heights must be finite numbers",
                           path, line_number, token);
        }
        if (value_list_push(values, value) != IM_OK)
            return im_fail(IM_ENOMEM, "%s:%ld: out of memory", path, line_number);
        ++*count;
    }
    return IM_OK;
}

static int read_rows(FILE *stream, const char *path, value_list *values, long *columns, long *rows,
                     text_header *header)
{
    char *line = NULL;
    size_t capacity = 0;
    long line_number = 0;
    int status = IM_OK;
    while (status == IM_OK && getline(&line, &capacity, stream) != -1) {
        ++line_number;
        if (line[0] == '#') {
            parse_extent_header(line, "Width:", &header->width, header->unit, sizeof header->unit);
            parse_extent_header(line, "Height:", &header->height, header->unit, sizeof header->unit);
            parse_shape_header(line, line_number, header);
            continue;
        }
        long count = 0;
        status = parse_data_line(line, path, line_number, values, &count);
        if (status != IM_OK)
            break;
        if (count > 0 && *columns == 0)
            *columns = count;
        else if (count > 0 && count != *columns)
            status = im_fail(IM_EFORMAT, "%s:%ld: %ld values, but the first data row has %ld", path,
                             line_number, count, *columns);
        if (status == IM_OK && count > 0)
            ++*rows;
    }
    free(line);
    return status;
}

int im_text_read(const char *path, im_field **out)
{
    *out = NULL;
    FILE *stream = fopen(path, "r");
    if (!stream)
        return im_fail(IM_EIO, "%s: cannot open: %s", path, strerror(errno));
    value_list values = {0};
    long columns = 0, rows = 0;
    text_header header = {0};
    int status = read_rows(stream, path, &values, &columns, &rows, &header);
    fclose(stream);
    if (status == IM_OK && rows == 0)
        status = im_fail(IM_EFORMAT, "%s: no data rows", path);
    if (status == IM_OK)
        status = check_stated_shape(path, &header, columns, rows);
    im_field *field = NULL;
    if (status == IM_OK) {
        double delta = header.width > 0.0 ? header.width / (double)columns : 1.0;
        status = im_field_create((int)columns, (int)rows, delta, &field);
    }
    if (status == IM_OK) {
        memcpy(field->data, values.values, values.count * sizeof *values.values);
        if (header.width > 0.0)
            snprintf(field->unit, sizeof field->unit, "%s", header.unit);
        *out = field;
    }
    free(values.values);
    return status;
}
