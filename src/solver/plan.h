/* Internal: the solver plan's layout, shared by plan.c (set-up, convolution) and pk.c (iteration). */
#ifndef INDENTMAP_SOLVER_PLAN_H
#define INDENTMAP_SOLVER_PLAN_H

#include "indentmap/solver.h"

#include <fftw3.h>

struct im_solver_plan {
    int nx, ny;              /* problem grid */
    int px, py;              /* padded grid: 2nx x 2ny (periodic: nx x ny, no padding) */
    double delta;
    im_solver_options options;
    double *kernel;          /* nx * ny: K at offset (|dx|, |dy|) delta, for direct summation */
    double *spectrum;        /* py * (px/2 + 1): real spectrum of K, divided by px * py */
    double *rows_in;         /* ny * px: the grid's rows, zero-padded to px (right halves stay 0) */
    double *rows_out;        /* ny * px */
    fftw_complex *modes;     /* py * (px/2 + 1): the row transforms, then the 2-D transform */
    /* The 2-D transform of the padded grid, pruned: the x transforms of the py - ny zero rows are
     * skipped going forward, and those of the rows outside the result coming back. The column
     * transforms run in place: out of place, FFTW_ESTIMATE's strided column plans were up to 3x
     * slower on large grids (a 3584^2 convolution cost 1.26 full 2-D pairs at 2 threads; in place 0.85). */
    fftw_plan rows_forward, columns_forward, columns_backward, rows_backward;
    double *direction, *gap; /* nx * ny work arrays of the iteration; K t is read from rows_out */
    long *changed;           /* nx * ny: indices of patches changed outside the CG step */
    double *changed_value;   /* their pressure changes */
    long direct_limit;       /* most changes added by direct summation rather than by FFT */
    double plan_seconds;
    int measured;
};

/* Transforms rows_in (filled by the caller: the grid's rows, stride px) and leaves the
 * convolution with K in rows_out (stride px, the first nx values of each of the ny rows). */
void solver_convolve_rows(im_solver_plan *plan);

/* displacement += sum_k value[k] K(x - x_index[k]) over the grid (direct summation). */
void solver_add_point_loads(const im_solver_plan *plan, const long *index, const double *value, long count,
                            double *displacement);

/* The periodic half-space's kernel (periodic.c): spectrum 2 / (E* |q|) with a zero mean mode, and
 * its real-space values for direct sums (options.periodic). IM_OK or IM_ENOMEM. */
int solver_periodic_kernel(im_solver_plan *plan);

#endif
