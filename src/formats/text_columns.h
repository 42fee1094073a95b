/* formats/text_columns.h: a header row of column names above x y z points ("x y z", "x[um] y[um] z[nm]",
 * "X (µm)\tY (µm)\tHeight (nm)", "\"x\",\"y\",\"height\""), with the units it states. */
#ifndef INDENTMAP_FORMATS_TEXT_COLUMNS_H
#define INDENTMAP_FORMATS_TEXT_COLUMNS_H

#include "formats/readers.h"
#include "formats/text_header.h"

typedef struct text_columns {
    long line;                    /* the header row's line; 0 when none */
    char lateral[16], height[16]; /* the units it states for x and y, and for the height ("" none) */
} text_columns;

/* 1 when line, the first data line, begins with a name (a letter or a quote) rather than a number. */
int text_columns_is_named_row(const char *line);

/* 1 when line begins with a column named x, as a header row of x y z points does (surface_file's
 * look at a file sends it to the text reader, which accepts the row or says what it expected). */
int text_columns_names_x_first(const char *line);

/* Parses a header row: three names, x, y and a height (z or height; case ignored), each with an
 * optional length unit in [] or () and optionally quoted, between blanks, tabs, commas or semicolons.
 * IM_EFORMAT naming path, line_number and what was expected for anything else, a unit that is not a
 * length, units stated for some columns only, and x and y in different units. */
int text_columns_parse(const char *path, long line_number, const char *line, text_columns *columns);

/* Refuses a header row above anything but 3 columns of points (a matrix's row of names says nothing
 * of its spacing) or above a header stating a matrix's grid or extent, and a '# Value units:' line of
 * header that the row's height unit contradicts. */
int text_columns_check(const char *path, const text_columns *columns, const text_header *header, long data_columns);

/* The units of x y z points under a header row (if any: columns->line > 0) and a '# Value units:' line
 * of header, into stated, whose keys then name the row when it states them. */
void text_columns_stated_units(const text_columns *columns, const text_header *header, surface_stated *stated);

#endif
