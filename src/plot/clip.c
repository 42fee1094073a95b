/* Polygon clipping against a rectangle (Sutherland-Hodgman), one side at a time. */
#include "plot/clip.h"

#include <stdlib.h>
#include <string.h>

/* A side of the rectangle: points with sign * coordinate[axis] <= sign * bound are inside. */
typedef struct side {
    int axis; /* 0: x, 1: y */
    double bound;
    double sign; /* +1: keep below the bound, -1: keep above it */
} side;

static int inside(const double *p, side s) { return s.sign * p[s.axis] <= s.sign * s.bound; }

/* The point where segment a-b crosses the side's line. */
static void crossing(const double *a, const double *b, side s, double *out)
{
    int other = 1 - s.axis;
    double t = (s.bound - a[s.axis]) / (b[s.axis] - a[s.axis]);
    out[s.axis] = s.bound;
    out[other] = a[other] + t * (b[other] - a[other]);
}

/* One pass: in[0..n) to out (capacity 2n); returns the output count. */
static int clip_side(const double *in, int n, side s, double *out)
{
    int count = 0;
    for (int i = 0; i < n; ++i) {
        const double *current = in + 2 * i, *previous = in + 2 * ((i + n - 1) % n);
        int current_in = inside(current, s), previous_in = inside(previous, s);
        if (current_in != previous_in)
            crossing(previous, current, s, out + 2 * count++);
        if (current_in) {
            memcpy(out + 2 * count++, current, 2 * sizeof *out);
        }
    }
    return count;
}

int plot_clip_polygon(const double *xy, int n, plot_rect r, double **out)
{
    const side sides[4] = {{0, r.left, -1.0}, {0, r.right, 1.0}, {1, r.top, -1.0}, {1, r.bottom, 1.0}};
    *out = NULL;
    double *current = malloc(2 * sizeof(double) * (size_t)(n > 0 ? n : 1));
    if (!current)
        return -1;
    memcpy(current, xy, 2 * sizeof(double) * (size_t)n);
    for (int k = 0; k < 4 && n > 0; ++k) {
        /* Each pass adds at most one crossing per input edge. */
        double *next = malloc(4 * sizeof(double) * (size_t)n);
        if (!next) {
            free(current);
            return -1;
        }
        n = clip_side(current, n, sides[k], next);
        free(current);
        current = next;
    }
    if (n == 0) {
        free(current);
        return 0;
    }
    *out = current;
    return n;
}
