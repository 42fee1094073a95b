/* Nominally flat contact of a periodic cell, shared by the serial and the distributed forms (flat.h). */
#include "solver/flat.h"

#include "indentmap/status.h"

#include <math.h>
#include <stdlib.h>

int flat_cell_allocate(flat_cell *cell, size_t n)
{
    cell->gap0 = malloc(sizeof(double) * (n + 1)); /* + 1: a rank without rows */
    cell->pressure = calloc(n + 1, sizeof(double));
    cell->displacement = calloc(n + 1, sizeof(double));
    return cell->gap0 && cell->pressure && cell->displacement ? IM_OK : IM_ENOMEM;
}

void flat_cell_free(flat_cell *cell)
{
    free(cell->gap0);
    free(cell->pressure);
    free(cell->displacement);
}

void flat_gap(const double *heights, size_t n, double highest, double *gap0)
{
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i)
        gap0[i] = highest - heights[i];
}

static void flat_result(const flat_cell *cell, const im_solve_result *solve, im_flat_result *out)
{
    *out = (im_flat_result){.mean_pressure = solve->load / cell->cell_area,
                            .area_fraction = solve->contact_patches / cell->patches,
                            .contact_patches = solve->contact_patches,
                            .contact_pressure = solve->mean_pressure,
                            .max_pressure = solve->max_pressure,
                            .approach = solve->approach,
                            .mean_gap = cell->mean_gap0 - solve->approach,
                            .iterations = solve->iterations,
                            .residual = solve->residual};
}

static int flat_solve(flat_cell *cell, enum im_control control, double target, im_flat_result *out)
{
    im_solve_result solve = {0};
    int status = cell->solve(cell->solver, cell->gap0, control, target, cell->pressure, cell->displacement, &solve);
    cell->approach = solve.approach;
    flat_result(cell, &solve, out);
    return status;
}

int flat_solve_pressure(flat_cell *cell, double mean_pressure, im_flat_result *out)
{
    if (!(isfinite(mean_pressure) && mean_pressure >= 0.0))
        return im_fail(IM_EINVAL, "mean pressure = %g: expected a finite p_m >= 0", mean_pressure);
    int status = flat_solve(cell, IM_CONTROL_LOAD, mean_pressure * cell->cell_area, out);
    out->mean_pressure = mean_pressure; /* the imposed one, not the load's rounding */
    return status;
}

int flat_solve_gap(flat_cell *cell, double mean_gap, im_flat_result *out)
{
    if (!(isfinite(mean_gap) && mean_gap > 0.0 && mean_gap <= cell->mean_gap0))
        return im_fail(IM_EINVAL,
                       "mean gap = %g: expected 0 < mean gap <= %.17g, the undeformed cell's (at that "
                       "gap the flat just touches the highest patch; at 0 the contact is full, at an infinite "
                       "pressure)",
                       mean_gap, cell->mean_gap0);
    int status = flat_solve(cell, IM_CONTROL_DISPLACEMENT, cell->mean_gap0 - mean_gap, out);
    out->mean_gap = mean_gap; /* the imposed one */
    return status;
}

void step_result_from_solve(const im_solve_result *s, double area, double delta2, int cell, im_step_result *out)
{
    *out = (im_step_result){.approach = s->approach,
                            .load = s->load,
                            .load_star = area / delta2,
                            .contact_patches = s->contact_patches,
                            .area_ratio = s->load > 0 || (cell && s->contact_patches > 0)
                                              ? s->contact_patches * delta2 / area
                                              : NAN,
                            .mean_pressure = s->mean_pressure,
                            .max_pressure = s->max_pressure,
                            .iterations = s->iterations,
                            .convolutions = s->convolutions,
                            .residual = s->residual,
                            .seconds = s->seconds,
                            .coarse_iterations = s->coarse_iterations};
    if (cell || s->load < 0)
        out->load_star = NAN;
}
