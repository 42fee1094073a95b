/* Shared by the solver benchmarks: the rough surface they solve on. */
#ifndef INDENTMAP_BENCH_RECIPE_H
#define INDENTMAP_BENCH_RECIPE_H

#include "indentmap/surface.h"

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

#endif
