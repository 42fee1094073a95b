/* The displacement on the whole grid from a solved force field. The solver computes u only inside
 * its window (the contact and a margin); written or drawn as 0 outside, h - u showed a square step
 * at the window's edge. One convolution on the full grid gives the true u everywhere. */
#include "indentmap/solver.h"
#include "indentmap/status.h"

#include <stdio.h>
#include <stdlib.h>

int im_displacement_full(const im_field *force, const im_solver_options *options, im_field **displacement)
{
    *displacement = NULL;
    im_solver_options o = *options;
    o.fft_measure = 0; /* a one-off convolution: estimating the plan is cheaper than measuring it */
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
