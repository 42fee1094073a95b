/* The periodic half-space (solver.h, "Periodic mode"): the kernel's spectrum 2 / (E* |q|) on the
 * unpadded grid, and nominally flat contact of a periodic surface under a mean pressure. */
#include "solver/plan.h"
#include "solver/flat.h"
#include "core/args.h"
#include "core/summation.h"

#include "core/fft_threads.h"
#include "indentmap/status.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Signed mode number of index k on a grid of n (k > n / 2 stands for k - n). */
static double signed_mode(int k, int n) { return k <= n / 2 ? k : k - n; }

void solver_periodic_mode(const im_solver_plan *p, int kx, int ky, double *spectrum, double *inverse)
{
    const int nx = p->nx, ny = p->ny;
    const double e = p->options.e_star, scale = 1.0 / ((double)nx * ny);
    const double step_x = 2.0 * M_PI / (nx * p->delta), step_y = 2.0 * M_PI / (ny * p->delta);
    const double q = hypot(kx * step_x, signed_mode(ky, ny) * step_y);
    /* the mean mode: a periodic half-space's rigid displacement is free; mean u = 0 */
    *spectrum = q > 0.0 ? 2.0 / (e * q) * scale : 0.0;
    /* the preconditioner M is K's exact inverse here (K is circulant), E* |q| / 2, but on the mean
     * mode, where K has none (applied like the half-space's M: scaled by 1 / (nx ny)) */
    *inverse = q > 0.0 ? e * q / 2.0 * scale : 0.0;
}

int solver_periodic_kernel(im_solver_plan *p)
{
    const int nx = p->nx, ny = p->ny, mx = nx / 2 + 1;
#pragma omp parallel for schedule(static)
    for (int ky = 0; ky < ny; ++ky)
        for (int kx = 0; kx < mx; ++kx) {
            const size_t k = (size_t)ky * mx + kx;
            solver_periodic_mode(p, kx, ky, &p->spectrum[k], &p->inverse_spectrum[k]);
        }
    /* The real-space kernel for direct sums (and K(0) for the Winkler start): the inverse transform
     * of the spectrum, a one-off plan on a temporary. K is even, so K(|dx|, |dy|) serves every offset. */
    fftw_complex *modes = fftw_malloc(sizeof(fftw_complex) * (size_t)ny * mx);
    fft_planner_lock();
    fftw_plan inverse = modes ? fftw_plan_dft_c2r_2d(ny, nx, modes, p->kernel, FFTW_ESTIMATE) : NULL;
    fft_planner_unlock();
    if (!inverse) {
        fftw_free(modes);
        return im_fail(IM_ENOMEM, "periodic solver plan %d x %d: kernel transform", nx, ny);
    }
    for (size_t k = 0; k < (size_t)ny * mx; ++k) {
        modes[k][0] = p->spectrum[k];
        modes[k][1] = 0.0;
    }
    solver_execute_once(inverse);
    fftw_free(modes);
    return IM_OK;
}

struct im_flat_contact {
    im_solver_plan *plan;
    flat_cell cell;
};

void im_flat_contact_free(im_flat_contact *run)
{
    if (!run)
        return;
    im_solver_plan_free(run->plan);
    flat_cell_free(&run->cell);
    free(run);
}

static int solve_on_plan(void *plan, const double *gap0, enum im_control control, double target, double *pressure,
                         double *displacement, im_solve_result *result)
{
    return im_solver_solve(plan, gap0, control, target, pressure, displacement, result);
}

/* The cell's gap and totals from the surface (heights finite), and its plan. */
static int prepare(im_flat_contact *run, const im_field *surface, const im_solver_options *o)
{
    const size_t n = im_field_count(surface);
    double highest = -INFINITY;
    for (size_t i = 0; i < n; ++i)
        highest = fmax(highest, surface->data[i]);
    flat_gap(surface->data, n, highest, run->cell.gap0);
    run->cell.mean_gap0 = sum_doubles(run->cell.gap0, n) / (double)n;
    int status = im_solver_plan_create(surface->nx, surface->ny, surface->delta, o, &run->plan);
    run->cell.solver = run->plan;
    return status;
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
    const size_t n = im_field_count(surface);
    run->cell = (flat_cell){.solve = solve_on_plan,
                            .patches = (double)n,
                            .cell_area = (double)n * surface->delta * surface->delta};
    int status = im_field_check_finite(surface, "surface heights");
    if (status == IM_OK && flat_cell_allocate(&run->cell, n) != IM_OK)
        status = im_fail(IM_ENOMEM, "flat contact %d x %d", surface->nx, surface->ny);
    if (status == IM_OK)
        status = prepare(run, surface, &o);
    if (status != IM_OK) {
        im_flat_contact_free(run);
        return status;
    }
    *out = run;
    return IM_OK;
}

int im_flat_contact_solve(im_flat_contact *run, double mean_pressure, im_flat_result *out)
{
    ARG_REQUIRE(run, "run");
    ARG_REQUIRE(out, "out");
    return flat_solve_pressure(&run->cell, mean_pressure, out);
}

int im_flat_contact_solve_gap(im_flat_contact *run, double mean_gap, im_flat_result *out)
{
    ARG_REQUIRE(run, "run");
    ARG_REQUIRE(out, "out");
    return flat_solve_gap(&run->cell, mean_gap, out);
}

const im_solver_plan *flat_contact_plan(const im_flat_contact *run) { return run->plan; }

const double *im_flat_contact_pressure(const im_flat_contact *run)
{
    ARG_REQUIRE_OR(run, "run", NULL);
    return run->cell.pressure;
}
