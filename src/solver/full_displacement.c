/* The displacement on the whole grid from a solved force field. The solver computes u only inside
 * its window (the contact and a margin); written or drawn as 0 outside, h - u showed a square step
 * at the window's edge. One convolution on the full grid gives the true u everywhere. */
#include "indentmap/solver.h"
#include "core/args.h"
#include "indentmap/status.h"
#include "solver/plan.h"

#include <stdio.h>

/* A convolution's options from a solve's (NULL: the defaults). */
static im_solver_options convolution_options(const im_solver_options *options)
{
    im_solver_options o = options ? *options : im_solver_options_default();
    o.fft_measure = 0;              /* a few convolutions: estimating the plan is cheaper than measuring it */
    o.wisdom_path = NULL;           /* nor read or written wisdom */
    o.cascade = o.precondition = 0; /* no solve: no coarse levels, no preconditioner */
    o.adhesion_work = o.adhesion_range = o.adhesion_zone = 0; /* u = K p whatever the interaction that made p */
    return o;
}

int im_displacement_plan_create(int nx, int ny, double delta, const im_solver_options *options, im_solver_plan **plan)
{
    ARG_REQUIRE(plan, "plan");
    ARG_SIDES(nx, ny);
    const im_solver_options o = convolution_options(options);
    return solver_convolution_plan_create(nx, ny, delta, &o, plan);
}

int im_displacement_memory_needed(int nx, int ny, const im_solver_options *options, im_solver_memory *out)
{
    ARG_REQUIRE(out, "out");
    ARG_SIDES(nx, ny);
    const im_solver_options o = convolution_options(options);
    return solver_convolution_memory_needed(nx, ny, &o, out);
}

int im_displacement_full_with(im_solver_plan *plan, const im_field *force, im_field **displacement)
{
    ARG_REQUIRE(plan, "plan");
    ARG_VIEW(force, "force");
    ARG_REQUIRE(displacement, "displacement");
    *displacement = NULL;
    size_t count = im_field_count(force);
    if (plan->nx != force->nx || plan->ny != force->ny)
        return im_fail(IM_EINVAL, "full-grid displacement: a %d x %d force field on a %d x %d plan", force->nx,
                       force->ny, plan->nx, plan->ny);
    im_field *u = NULL;
    int status = im_field_create(force->nx, force->ny, force->delta, &u);
    if (status == IM_OK) { /* the pressure in u's array, convolved in place: no grid beside it */
        double area = force->delta * force->delta;
        for (size_t i = 0; i < count; ++i)
            u->data[i] = force->data[i] / area;
        im_solver_convolve(plan, u->data, u->data);
        snprintf(u->unit, sizeof u->unit, "%s", force->unit);
        *displacement = u;
    }
    return status;
}

int im_displacement_full(const im_field *force, const im_solver_options *options, im_field **displacement)
{
    ARG_VIEW(force, "force");
    ARG_REQUIRE(displacement, "displacement");
    *displacement = NULL;
    im_solver_plan *plan = NULL;
    int status = im_displacement_plan_create(force->nx, force->ny, force->delta, options, &plan);
    if (status == IM_OK)
        status = im_displacement_full_with(plan, force, displacement);
    im_solver_plan_free(plan);
    return status;
}
