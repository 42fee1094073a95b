/* The displacement on the whole grid from a solved force field. The solver computes u only inside
 * its window (the contact and a margin); written or drawn as 0 outside, h - u showed a square step
 * at the window's edge. One convolution on the full grid gives the true u everywhere. */
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "solver/plan.h"

#include <stdio.h>
#include <stdlib.h>

int im_displacement_full(const im_field *force, const im_solver_options *options, im_field **displacement)
{
    *displacement = NULL;
    im_solver_options o = *options;
    o.fft_measure = 0; /* a one-off convolution: estimating the plan is cheaper than measuring it */
    o.cascade = o.precondition = 0; /* no solve: no coarse levels, no preconditioner */
    im_solver_plan *plan = NULL;
    im_field *u = NULL;
    size_t count = im_field_count(force);
    double *pressure = malloc(count * sizeof *pressure);
    int status = pressure ? im_solver_plan_create(force->nx, force->ny, force->delta, &o, &plan)
                          : im_fail(IM_ENOMEM, "full-grid displacement %d x %d: allocation failed", force->nx,
                                    force->ny);
    if (status == IM_OK)
        status = im_field_create(force->nx, force->ny, force->delta, &u);
    if (status == IM_OK) {
        double area = force->delta * force->delta;
        for (size_t i = 0; i < count; ++i)
            pressure[i] = force->data[i] / area;
        im_solver_convolve(plan, pressure, u->data);
        snprintf(u->unit, sizeof u->unit, "%s", force->unit);
        *displacement = u;
    }
    im_solver_plan_free(plan);
    free(pressure);
    return status;
}

int im_indentation_fields_full(const im_indentation *run, im_field **force, im_field **gap, im_field **displacement)
{
    im_field *f = NULL, *g = NULL, *window_u = NULL, *u = NULL;
    int status = im_indentation_fields(run, &f, gap ? &g : NULL, &window_u);
    if (status == IM_OK)
        status = im_displacement_full(f, &im_indentation_plan(run)->options, &u);
    if (status == IM_OK && g) /* g = g0 - w + u: the same gap with the true u */
        for (size_t i = 0; i < im_field_count(g); ++i)
            g->data[i] += u->data[i] - window_u->data[i];
    im_field_free(window_u);
    if (status != IM_OK) {
        im_field_free(f);
        im_field_free(g);
        im_field_free(u);
        return status;
    }
    if (force)
        *force = f;
    else
        im_field_free(f);
    if (gap)
        *gap = g;
    if (displacement)
        *displacement = u;
    else
        im_field_free(u);
    return IM_OK;
}
