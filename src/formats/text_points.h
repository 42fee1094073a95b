/* formats/text_points.h: a text file of three columns, x y z, sampling a regular grid in any order
 * (as profilometers and SurfaceTopography's xyz exports write them). */
#ifndef INDENTMAP_FORMATS_TEXT_POINTS_H
#define INDENTMAP_FORMATS_TEXT_POINTS_H

#include "formats/readers.h"

/* values holds points x y z triples. When each (x, y) of a regular grid (at least 3 x 3, steps equal
 * to 1e-6 of a step; x and y finite) appears exactly once, *out is the grid of z (x along columns, y along rows, a
 * missing z stays NaN) and stated holds the steps as the spacing. Otherwise IM_EFORMAT naming path and
 * what is not a grid. */
int text_points_grid(const char *path, const double *values, long points, im_field **out, surface_stated *stated);

#endif
