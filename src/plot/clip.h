/* Clipping in double precision, before coordinates reach cairo's fixed-point range. */
#ifndef INDENTMAP_PLOT_CLIP_H
#define INDENTMAP_PLOT_CLIP_H

typedef struct plot_rect {
    double left, top, right, bottom;
} plot_rect;

/* Sutherland-Hodgman: clips the closed polygon xy[0..2n) (x, y pairs, finite) to the rectangle.
 * *out receives a malloc'ed array of the clipped polygon's pairs (the caller frees it; NULL when
 * the result is empty). Returns the number of vertices, or -1 when memory runs out. */
int plot_clip_polygon(const double *xy, int n, plot_rect r, double **out);

#endif
