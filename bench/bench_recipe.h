/* Shared by the solver benchmarks: the rough surface they solve on. */
#ifndef INDENTMAP_BENCH_RECIPE_H
#define INDENTMAP_BENCH_RECIPE_H

#include "indentmap/surface.h"

#include <math.h>

/* The paper's recipe on an n x n grid (H 0.8, lambda_s 4, lambda_r n, h'rms 0.08, seed 1: the
 * library's defaults with lambda_r = n) into *surface; the library's status. */
static inline int bench_paper_surface(int n, im_field **surface)
{
    im_surface_params p = im_surface_params_default();
    p.nx = p.ny = n;
    p.lambda_r = n;
    *surface = NULL;
    return im_surface_generate(&p, surface);
}

/* The undeformed gap of the periodic cell of surface: max h - h, into gap0 (im_field_count values). */
static inline void bench_cell_gap(const im_field *surface, double *gap0)
{
    const size_t count = im_field_count(surface);
    double highest = -INFINITY;
    for (size_t i = 0; i < count; ++i)
        highest = fmax(highest, surface->data[i]);
    for (size_t i = 0; i < count; ++i)
        gap0[i] = highest - surface->data[i];
}

#endif
