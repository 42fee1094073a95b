/* formats/text_preamble.h: the lines of text above a text file's numbers that are not an x y z header row:
 * column names ("X_(microns),y1", "index,x in µm,y in µm", "X;Y;valid"), a row of units ("µm µm",
 * "[mm];[mm];[1/0]"), a count of the rows, a profiler's report (a Bruker Dektak export's "Scan
 * Parameters"). They say what the numbers are; with the number of columns they tell a line scan (a
 * 1-D profile) from a map, which is the one thing such a file can be refused for by name. */
#ifndef INDENTMAP_FORMATS_TEXT_PREAMBLE_H
#define INDENTMAP_FORMATS_TEXT_PREAMBLE_H

typedef struct text_preamble {
    long lines; /* lines of text above the numbers; 0 when none */
    long first_line, names_line, units_line, count_line;
    char first[64], names[64], units[64]; /* the first line, the last row of names, a row of units */
    char names_refusal[400];              /* why the row of names is not an x y z header row */
    const char *vendor;                   /* the export recognised by its first line, or NULL */
    int names_fields;                     /* how many names that row holds */
    int index_column, valid_column;       /* columns (from 1) named an index or a validity flag; 0: none */
    char index_name[24], valid_name[24];
    double count; /* a lone count of the rows above them (count_line > 0) */
} text_preamble;

/* 1 when line (not a '#' comment) is text rather than numbers: its first field is not a number. */
int text_preamble_is_text(const char *line);

/* Adds a line of text above the numbers; names_refusal is the x y z header reader's refusal of it
 * ("" when the line is not a row of names). */
void text_preamble_take(text_preamble *preamble, long line_number, const char *line, const char *names_refusal);

/* Takes a lone number above rows of more values (a count of the rows) into the preamble. */
void text_preamble_take_count(text_preamble *preamble, long line_number, double count);

/* The refusal of numbers under a preamble (columns x rows of them): a line scan, named with what the
 * preamble says of it, when at most two columns are not an index or a validity flag; no numbers at
 * all; or the reason the preamble's text cannot stand above a map (always IM_EFORMAT naming path). */
int text_preamble_refuse(const char *path, const text_preamble *preamble, long columns, long rows);

#endif
