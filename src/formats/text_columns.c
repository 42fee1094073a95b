/* A header row of column names above x y z points, and the units it states. */
#include "formats/text_columns.h"

#include "indentmap/status.h"
#include "core/number.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

enum { MAX_NAMES = 4 }; /* three expected; a fourth is counted to be refused */

typedef struct column_name {
    char name[24], unit[16];
} column_name;

static const char *const EXPECTED = "expected three column names, x, y and a height (z or height), each with an "
                                    "optional length unit in [] or (), e.g. 'x[um] y[um] z[nm]'";

int text_columns_is_named_row(const char *line)
{
    const char *at = line + strspn(line, " \t");
    char *end;
    (void)number_parse(at, &end); /* "nan" and "inf" are numbers */
    return *at == '"' || *at == '\'' || (isalpha((unsigned char)*at) && end == at);
}

int text_columns_names_x_first(const char *line)
{
    const char *at = line + strspn(line, " \t");
    at += *at == '"' || *at == '\'';
    return (*at == 'x' || *at == 'X') && !isalnum((unsigned char)at[1]) && at[1] != '_';
}

/* The unit in brackets at *at ("[um]", "(µm)"), into column->unit; the text after it, or NULL when the
 * brackets are not closed or hold no single word of at most 15 bytes. */
static const char *scan_unit(const char *at, column_name *column)
{
    const char *close = strchr(at, *at == '[' ? ']' : ')');
    char text[64] = "", extra[2];
    size_t length = close ? (size_t)(close - at - 1) : 0;
    if (!close || length >= sizeof text)
        return NULL;
    memcpy(text, at + 1, length);
    text[length] = '\0';
    return sscanf(text, "%15s %1s", column->unit, extra) == 1 ? close + 1 : NULL; /* a longer word: 2 */
}

/* One column's NAME, "NAME [UNIT]" or "NAME (UNIT)", quoted or not, and the separator after it; the
 * text after them, or NULL when it is none of those. */
static const char *scan_column(const char *at, column_name *column)
{
    at += strspn(at, " \t");
    char quote = *at == '"' || *at == '\'' ? *at++ : '\0';
    size_t length = 0;
    while (isalnum((unsigned char)at[length]) || at[length] == '_')
        ++length;
    if (length == 0 || length >= sizeof column->name)
        return NULL;
    memcpy(column->name, at, length);
    column->name[length] = '\0';
    column->unit[0] = '\0';
    at += length + strspn(at + length, " \t");
    if ((*at == '[' || *at == '(') && !(at = scan_unit(at, column)))
        return NULL;
    at += strspn(at, " \t");
    if (quote && *at++ != quote)
        return NULL;
    at += strspn(at, " \t");
    return *at == ',' || *at == ';' ? at + 1 : at;
}

/* The names of the row into names (at most MAX_NAMES, counted in *count); IM_EFORMAT for a row that
 * is not names. */
static int scan_row(const char *path, long line_number, const char *line, column_name names[MAX_NAMES], int *count)
{
    const char *at = line;
    for (*count = 0; at[strspn(at, " \t\r\n")] && *count < MAX_NAMES; ++*count)
        if (!(at = scan_column(at, &names[*count])))
            return im_fail(IM_EFORMAT, "%s:%ld: header row '%.60s': column %d is not a name: %s", path, line_number,
                           line, *count + 1, EXPECTED);
    if (*count != 3)
        return im_fail(IM_EFORMAT,
                       "%s:%ld: header row '%.60s' of %s%d column names: a header row is read only above "
                       "x y z points (a matrix's names state no spacing: remove them); %s",
                       path, line_number, line, *count == MAX_NAMES ? "at least " : "", *count, EXPECTED);
    return IM_OK;
}

static int names_are_x_y_height(const column_name names[3])
{
    return strcasecmp(names[0].name, "x") == 0 && strcasecmp(names[1].name, "y") == 0 &&
           (strcasecmp(names[2].name, "z") == 0 || strcasecmp(names[2].name, "height") == 0);
}

/* Each stated unit a length; units for all three columns or none; x and y in one unit. */
static int check_units(const char *path, long line_number, const column_name names[3])
{
    int stated = 0;
    for (int k = 0; k < 3; ++k) {
        stated += names[k].unit[0] != '\0';
        if (names[k].unit[0] && im_length_unit_metres(names[k].unit, NULL) == 0.0)
            return im_fail(IM_EFORMAT,
                           "%s:%ld: header row: column '%s' in '%s': expected a length unit (m, mm, "
                           "\u00b5m or um, nm, \u00c5 or A)",
                           path, line_number, names[k].name, names[k].unit);
    }
    if (stated != 0 && stated != 3)
        return im_fail(IM_EFORMAT,
                       "%s:%ld: header row states units for %d of its 3 columns (%s '%s', %s '%s', %s "
                       "'%s'): expected a unit for each of x, y and the height, or for none",
                       path, line_number, stated, names[0].name, names[0].unit, names[1].name, names[1].unit,
                       names[2].name, names[2].unit);
    if (stated && im_length_unit_metres(names[0].unit, NULL) != im_length_unit_metres(names[1].unit, NULL))
        return im_fail(IM_EFORMAT,
                       "%s:%ld: header row states x in '%s' but y in '%s': expected x and y in one unit "
                       "(their steps are the grid's spacing)",
                       path, line_number, names[0].unit, names[1].unit);
    return IM_OK;
}

int text_columns_parse(const char *path, long line_number, const char *line, text_columns *columns)
{
    column_name names[MAX_NAMES];
    int count;
    int status = scan_row(path, line_number, line, names, &count);
    if (status != IM_OK)
        return status;
    if (!names_are_x_y_height(names))
        return im_fail(IM_EFORMAT, "%s:%ld: header row names its columns '%s', '%s', '%s': %s, in that order", path,
                       line_number, names[0].name, names[1].name, names[2].name, EXPECTED);
    status = check_units(path, line_number, names);
    if (status != IM_OK)
        return status;
    columns->line = line_number;
    memcpy(columns->lateral, names[0].unit, sizeof columns->lateral);
    memcpy(columns->height, names[2].unit, sizeof columns->height);
    return IM_OK;
}

int text_columns_check(const char *path, const text_columns *columns, const text_header *header, long data_columns)
{
    if (!columns->line)
        return IM_OK;
    if (data_columns != 3 || text_header_states_a_matrix(header))
        return im_fail(IM_EFORMAT,
                       "%s:%ld: a header row of x, y and height names above %s: expected x y z points, "
                       "3 values a row, under no header stating a matrix's grid or extent",
                       path, columns->line,
                       data_columns != 3 ? "rows of another number of values" : "a header stating a matrix");
    if (header->value_unit[0] && columns->height[0] &&
        im_length_unit_metres(header->value_unit, NULL) != im_length_unit_metres(columns->height, NULL))
        return im_fail(IM_EFORMAT,
                       "%s:%ld: header row states the height in '%s' but '# Value units:' in '%s': "
                       "expected one unit",
                       path, columns->line, columns->height, header->value_unit);
    return IM_OK;
}

void text_columns_stated_units(const text_columns *columns, const text_header *header, surface_stated *stated)
{
    memcpy(stated->units.height, header->value_unit, sizeof stated->units.height);
    if (!columns->lateral[0])
        return;
    memcpy(stated->units.lateral, columns->lateral, sizeof stated->units.lateral);
    memcpy(stated->units.height, columns->height, sizeof stated->units.height);
    stated->lateral_key = "the header row's x and y unit";
    stated->height_key = "the header row's height unit";
}
