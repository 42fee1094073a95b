/* The periodic half-space (solver.h, "Periodic mode"): the kernel's spectrum 2 / (E* |q|) on the
 * unpadded grid, and nominally flat contact of a periodic surface under a mean pressure. */
#include "solver/plan.h"
#include "core/args.h"
#include "core/summation.h"

#include "core/fft_threads.h"
#include "indentmap/status.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Signed mode number of index k on a grid of n (k > n / 2 stands for k - n). */
static double signed_mode(int k, int n) { return k <= n / 2 ? k : k - n; }

int solver_periodic_kernel(im_solver_plan *p)
{
    const int nx = p->nx, ny = p->ny, mx = nx / 2 + 1;
    const double e = p->options.e_star, scale = 1.0 / ((double)nx * ny);
    const double step_x = 2.0 * M_PI / (nx * p->delta), step_y = 2.0 * M_PI / (ny * p->delta);
#pragma omp parallel for schedule(static)
    for (int ky = 0; ky < ny; ++ky)
        for (int kx = 0; kx < mx; ++kx) {
            double q = hypot(kx * step_x, signed_mode(ky, ny) * step_y);
            /* the mean mode: a periodic half-space's rigid displacement is free; mean u = 0 */
            p->spectrum[(size_t)ky * mx + kx] = q > 0.0 ? 2.0 / (e * q) * scale : 0.0;
            /* the preconditioner M is K's exact inverse here (K is circulant), E* |q| / 2, but on the
             * mean mode, where K has none (plan.c applies it like the half-space's: scaled by 1 / (nx ny)) */
            p->inverse_spectrum[(size_t)ky * mx + kx] = q > 0.0 ? e * q / 2.0 * scale : 0.0;
        }
    /* The real-space kernel for direct sums (and K(0) for the Winkler start): the inverse transform
     * of the spectrum, a one-off plan. K is even, so K(|dx|, |dy|) serves every offset. */
    fft_planner_lock();
    fftw_plan inverse = fftw_plan_dft_c2r_2d(ny, nx, p->modes, p->kernel, FFTW_ESTIMATE);
    fft_planner_unlock();
    if (!inverse)
        return im_fail(IM_ENOMEM, "periodic solver plan %d x %d: kernel transform", nx, ny);
    for (size_t k = 0; k < (size_t)ny * mx; ++k) {
        p->modes[k][0] = p->spectrum[k];
        p->modes[k][1] = 0.0;
    }
    fftw_execute(inverse);
    fft_planner_lock();
    fftw_destroy_plan(inverse);
    fft_planner_unlock();
    return IM_OK;
}

struct im_flat_contact {
    im_solver_plan *plan;
    double *gap0, *pressure, *displacement;
    double cell_area;       /* nx ny delta^2: the load per unit mean pressure */
    double mean_gap0;       /* the mean of gap0: the mean gap at approach 0 (mean u = 0 always) */
};

void im_flat_contact_free(im_flat_contact *run)
{
    if (!run)
        return;
    im_solver_plan_free(run->plan);
    free(run->gap0);
    free(run->pressure);
    free(run->displacement);
    free(run);
}

/* g0 = max h - h (heights finite): the flat touches the highest patch first. */
static void flat_gap(const im_field *surface, double *gap0)
{
    const size_t n = (size_t)surface->nx * surface->ny;
    double highest = -INFINITY;
    for (size_t i = 0; i < n; ++i)
        highest = fmax(highest, surface->data[i]);
    for (size_t i = 0; i < n; ++i)
        gap0[i] = highest - surface->data[i];
}

int im_flat_contact_create(const im_field *surface, const im_solver_options *options, im_flat_contact **out)
{
    ARG_VIEW(surface, "surface");
    ARG_REQUIRE(out, "out");
    *out = NULL;
    if (!surface || !surface->data)
        return im_fail(IM_EINVAL, "flat contact: no surface");
    im_solver_options o = options ? *options : im_solver_options_default();
    o.periodic = 1;
    im_flat_contact *run = calloc(1, sizeof *run);
    if (!run)
        return im_fail(IM_ENOMEM, "flat contact %d x %d", surface->nx, surface->ny);
    const size_t n = (size_t)surface->nx * surface->ny;
    run->gap0 = malloc(sizeof(double) * n);
    run->pressure = calloc(n, sizeof(double));
    run->displacement = calloc(n, sizeof(double));
    run->cell_area = (double)n * surface->delta * surface->delta;
    int status = im_field_check_finite(surface, "surface heights");
    if (status == IM_OK && !(run->gap0 && run->pressure && run->displacement))
        status = im_fail(IM_ENOMEM, "flat contact %d x %d", surface->nx, surface->ny);
    if (status == IM_OK) {
        flat_gap(surface, run->gap0);
        run->mean_gap0 = sum_doubles(run->gap0, n) / (double)n;
        status = im_solver_plan_create(surface->nx, surface->ny, surface->delta, &o, &run->plan);
    }
    if (status != IM_OK) {
        im_flat_contact_free(run);
        return status;
    }
    *out = run;
    return IM_OK;
}

static void flat_result(const im_flat_contact *run, const im_solve_result *solve, im_flat_result *out)
{
    const double patches = (double)run->plan->nx * run->plan->ny;
    *out = (im_flat_result){.mean_pressure = solve->load / run->cell_area,
                            .area_fraction = solve->contact_patches / patches,
                            .contact_patches = solve->contact_patches, .contact_pressure = solve->mean_pressure,
                            .max_pressure = solve->max_pressure, .approach = solve->approach,
                            .mean_gap = run->mean_gap0 - solve->approach, .iterations = solve->iterations,
                            .residual = solve->residual};
}

int im_flat_contact_solve(im_flat_contact *run, double mean_pressure, im_flat_result *out)
{
    ARG_REQUIRE(run, "run");
    ARG_REQUIRE(out, "out");
    if (!(isfinite(mean_pressure) && mean_pressure >= 0.0))
        return im_fail(IM_EINVAL, "mean pressure = %g: expected a finite p_m >= 0", mean_pressure);
    im_solve_result solve;
    int status = im_solver_solve(run->plan, run->gap0, IM_CONTROL_LOAD, mean_pressure * run->cell_area,
                                 run->pressure, run->displacement, &solve);
    flat_result(run, &solve, out);
    out->mean_pressure = mean_pressure; /* the imposed one, not the load's rounding */
    return status;
}

int im_flat_contact_solve_gap(im_flat_contact *run, double mean_gap, im_flat_result *out)
{
    ARG_REQUIRE(run, "run");
    ARG_REQUIRE(out, "out");
    if (!(isfinite(mean_gap) && mean_gap > 0.0 && mean_gap <= run->mean_gap0))
        return im_fail(IM_EINVAL, "mean gap = %g: expected 0 < mean gap <= %.17g, the undeformed cell's (at that "
                       "gap the flat just touches the highest patch; at 0 the contact is full, at an infinite "
                       "pressure)", mean_gap, run->mean_gap0);
    im_solve_result solve;
    int status = im_solver_solve(run->plan, run->gap0, IM_CONTROL_DISPLACEMENT, run->mean_gap0 - mean_gap,
                                 run->pressure, run->displacement, &solve);
    flat_result(run, &solve, out);
    out->mean_gap = mean_gap; /* the imposed one */
    return status;
}

const double *im_flat_contact_pressure(const im_flat_contact *run)
{
    ARG_REQUIRE_OR(run, "run", NULL);
    return run->pressure;
}
