/* formats/text_header.h: the header lines of text surface files, parsed apart from their numbers.
 *
 * Two families state units in a text matrix: Gwyddion's exports ("# Width: 5.12 um", "# Height:",
 * "# Value units: m", with the German "# Breite:" and "# Höhe:" of a German Gwyddion) and
 * Wyko/Vision ASCII exports (lines "h=305 w=75", "pixel size=3.7e-007 m", "data unit=rad",
 * "height conversion factor (-> m)=2.9e-008" before the numbers). */
#ifndef INDENTMAP_FORMATS_TEXT_HEADER_H
#define INDENTMAP_FORMATS_TEXT_HEADER_H

#include "formats/readers.h"

typedef struct text_header {
    double width, height;                   /* Gwyddion's extents along x and y; 0 when absent */
    double width_rounding, height_rounding; /* half a unit of each extent's last printed digit, relative to
                                               it ("87.6": 0.05 / 87.6); 0 when absent */
    char width_unit[16], height_unit[16], value_unit[16];
    long columns, rows, line; /* a stated grid (indentmap's "C columns x R rows" or Vision's
                                       "h= w="), and its line; 0 when none */
    double pixel_size;        /* Vision's "pixel size"; 0 when absent */
    char pixel_unit[16], data_unit[16];
    double height_factor; /* Vision's "height conversion factor (-> m)"; 0 when absent */
} text_header;

/* 1 when line (before any number) is a Vision "key=value" header line rather than data. */
int text_header_is_vision_line(const char *line);

/* Parses a '#' line (Gwyddion's keys, indentmap's grid line; other comments are ignored) or a Vision
 * line into header; IM_EFORMAT naming path, line_number and the key for a value that is not what its
 * key needs, and for a Vision key this reader does not know (it could change what the numbers mean). */
int text_header_parse_comment(const char *path, long line_number, const char *line, text_header *header);
int text_header_parse_vision(const char *path, long line_number, const char *line, text_header *header);

/* Refuses data whose size disagrees with a grid the header states. */
int text_header_check_shape(const char *path, const text_header *header, long columns, long rows);

/* The units the header states for a columns x rows grid, into stated; *value_factor is what every
 * stored value must be multiplied by (Vision's conversion factor; 1 otherwise). Width and Height in
 * different length units are converted into Width's; in units that are not both lengths, refused. */
int text_header_stated_units(const char *path, const text_header *header, long columns, long rows,
                             surface_stated *stated, double *value_factor);

/* 1 when the header states a spacing or a grid, so the numbers are a matrix (not x y z points). */
int text_header_states_a_matrix(const text_header *header);

#endif
