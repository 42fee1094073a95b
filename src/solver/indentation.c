/* Indentation histories: undeformed gap, solve window, steps with plastic memory, full-grid fields
 * (see solver.h). */
#include "indentmap/solver.h"
#include "core/args.h"
#include "core/summation.h"
#include "core/team_size.h"
#include "solver/adhesion.h"
#include "solver/flat.h"
#include "solver/indentation_rows.h"
#include "solver/plan.h"
#include "solver/search.h"
#include "solver/step_window.h"

#include "indentmap/status.h"

#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct im_indentation {
    im_indenter punch;
    enum im_control control;
    double largest_target;
    double approach_bound; /* largest approach the window is exact for */
    im_solver_options options;
    int nx, ny; /* surface grid */
    double delta;
    double *gap0; /* full grid, min 0 */
    im_window window;
    double *window_gap0, *pressure, *displacement; /* window grid; window_gap0 includes the plastic depth */
    double *plastic;     /* window grid: plastic depth accumulated over the steps (>= 0, never decreases) */
    double *flow;        /* window grid, with a hardness: the last step's depth increments (their ordered sum) */
    double plastic_work; /* H_p delta^2 times the sum of the depth increments: the energy dissipated */
    im_solver_plan *plan;
    im_solver_plan *full_plan; /* made at the first im_indentation_fields_full: the whole grid's u */
    double approach;           /* last step's */
    double load;               /* last step's (net, with adhesion) */
    adhesion_state *adhesion;  /* with a work of adhesion (adhesion.h); the plan's options have none */
    /* adhesion under load control: the solution of the last accepted try and of the step's start (adhesion.h) */
    double *marked_pressure[2], *marked_displacement[2];
    step_window *steps; /* displacement control on the CPU engine: each step on the box it can touch */
    /* NULL: one process holds the surface and owns plan. Else the grid is held in rows over ranks
     * (indentation_rows.h): the window is this rank's rows, plan the ranks' (not freed here), and the solves,
     * sums, extremes and edge checks go over the ranks. */
    const adhesion_ranks *ranks;
};

/* values[0..count) combined over the ranks (one process: as they are). */
static void combine(const im_indentation *run, double *values, int count, enum adhesion_combine how)
{
    if (run->ranks)
        run->ranks->combine(run->ranks->context, values, count, how);
}

/* The sum of a window field over the grid, in a fixed order (row order over ranks). */
static double grid_sum(const im_indentation *run, const double *field)
{
    return run->ranks ? run->ranks->sum(run->ranks->context, field)
                      : sum_doubles(field, (size_t)run->window.nx * run->window.ny);
}

/* One solve of the window's problem on the plan, or over the ranks. */
static int solve_window(im_indentation *run, enum im_control control, double target, im_solve_result *s)
{
    if (run->ranks)
        return run->ranks->solve(run->ranks->context, run->window_gap0, control, target, run->pressure,
                                 run->displacement, s);
    return im_solver_solve(run->plan, run->window_gap0, control, target, run->pressure, run->displacement, s);
}

/* g0 = z(r) - h - min(z - h) over the full grid. */
static int undeformed_gap(im_indentation *run, const im_field *surface)
{
    const int nx = surface->nx, ny = surface->ny;
    const double d = surface->delta;
    double ax, ay;
    im_indenter_axis(&run->punch, nx, ny, d, &ax, &ay);
    double lowest = INFINITY;
#pragma omp parallel for schedule(static) reduction(min : lowest)
    for (int iy = 0; iy < ny; ++iy)
        for (int ix = 0; ix < nx; ++ix) {
            size_t i = (size_t)iy * nx + ix;
            double dx = (ix + 0.5) * d - ax, dy = (iy + 0.5) * d - ay;
            if (run->options.periodic) { /* the punch repeats with the cell: the nearest image */
                dx -= nx * d * round(dx / (nx * d));
                dy -= ny * d * round(dy / (ny * d));
            }
            run->gap0[i] = im_indenter_height(&run->punch, dx, dy) - surface->data[i];
            if (run->gap0[i] < lowest)
                lowest = run->gap0[i];
        }
    if (!isfinite(lowest))
        return im_fail(IM_EINVAL, "the %s punch at (%g, %g) covers no patch of the %d x %d surface",
                       im_punch_name(run->punch.kind), ax, ay, nx, ny);
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < (size_t)nx * ny; ++i)
        run->gap0[i] -= lowest;
    return IM_OK;
}

static im_window choose_window(const im_indentation *run)
{
    if (!run->options.crop || run->options.periodic) /* a periodic cell has no outside to crop */
        return (im_window){0, 0, run->nx, run->ny};
    return solver_gap_window(run->gap0, run->nx, run->ny, run->approach_bound, run->options.window_margin);
}

static double height_range(const im_field *surface)
{
    double lo = DBL_MAX, hi = -DBL_MAX;
#pragma omp parallel for schedule(static) reduction(min : lo) reduction(max : hi)
    for (size_t i = 0; i < im_field_count(surface); ++i) {
        lo = fmin(lo, surface->data[i]);
        hi = fmax(hi, surface->data[i]);
    }
    return hi - lo;
}

/* A 2-D profile is sampled on the surface's grid (indenter.h): the same delta, to rounding. */
static int check_profile_grid(const im_field *surface, const im_indenter *punch)
{
    if (punch->kind != IM_PUNCH_PROFILE_2D)
        return IM_OK;
    const double *r, *z;
    const im_field *field;
    int count;
    im_profile_samples(punch->profile, &r, &z, &count, &field);
    if (fabs(field->delta - surface->delta) <= 1e-12 * surface->delta)
        return IM_OK;
    return im_fail(IM_EINVAL,
                   "2-D profile delta = %.17g: expected the surface's delta %.17g (a 2-D profile is "
                   "sampled on the surface's grid; it is not resampled)",
                   field->delta, surface->delta);
}

/* The largest approach the window must hold: the target itself, or under load control the smooth
 * punch's approach for the largest load with a tenth to spare, plus the surface's height range.
 * With a hardness H_p a contact can sink deeper than the elastic one: to the fully plastic approach,
 * where the punch's cross-section carries the load at H_p everywhere (pi r^2 H_p = N) at its height
 * z(r) plus the half-space's sink there, the rim displacement 4 H_p r / (pi E*) of a uniform H_p on
 * that disc (without it a sphere or cone pressed deep into the plastic range was refused loads that
 * displacement control reached). A 2-D profile has no smooth estimate: its whole footprint (INFINITY). */
static double approach_bound(double height_range, const im_indenter *punch, enum im_control control,
                             double largest_target, const im_solver_options *o)
{
    if (control == IM_CONTROL_DISPLACEMENT) /* with adhesion, also its zone, and a range for its lift */
        return largest_target + adhesion_reach(o) + o->adhesion_range;
    if (o->periodic) /* no window to bound */
        return INFINITY;
    double smooth = im_indenter_approach_for_load(punch, o->e_star, largest_target);
    if (o->hardness > 0) {
        const double r = sqrt(largest_target / (M_PI * o->hardness));
        smooth = fmax(smooth, im_indenter_profile(punch, r) + 4.0 * o->hardness * r / (M_PI * o->e_star));
    }
    /* with adhesion the zone's reach too (a deeper adhesive approach is caught by the zone's check) */
    return isfinite(smooth) ? 1.1 * smooth + height_range + adhesion_reach(o) + o->adhesion_range : INFINITY;
}

static const char *control_target(enum im_control control)
{
    return control == IM_CONTROL_LOAD ? "load" : control == IM_CONTROL_MEAN_GAP ? "mean gap" : "approach";
}

/* Adhesion's passes hold the approach fixed: displacement control on the half-space, mean-gap control on a
 * periodic cell (mean u = 0 there, so a mean gap is an approach; with a hardness searched, every try from the
 * step's start: solve_adhesive_at_mean_gap), and load control on either by a walk over the approach
 * (solve_adhesive_at_load). */
static int check_adhesion_control(enum im_control control, const im_solver_options *options)
{
    const int held = control == IM_CONTROL_LOAD ||
                     control == (options->periodic ? IM_CONTROL_MEAN_GAP : IM_CONTROL_DISPLACEMENT);
    if (!held)
        return im_fail(IM_EINVAL, "adhesion work = %g: expected %s (adhesion under %s control is not available)",
                       options->adhesion_work,
                       options->periodic ? "mean-gap or load control on a periodic cell"
                                         : "displacement or load control on the half-space",
                       control_target(control));
    return IM_OK;
}

/* The punch, the options, the control and its largest target. */
static int check_run(const im_indenter *punch, enum im_control control, double largest_target,
                     const im_solver_options *options)
{
    int status = im_indenter_check(punch);
    if (status == IM_OK)
        status = im_solver_options_check(options);
    if (status != IM_OK)
        return status;
    if (control != IM_CONTROL_DISPLACEMENT && control != IM_CONTROL_LOAD && control != IM_CONTROL_MEAN_GAP)
        return im_fail(IM_EINVAL, "control %d: expected displacement, load or mean gap", (int)control);
    if (control == IM_CONTROL_MEAN_GAP && !options->periodic)
        return im_fail(IM_EINVAL, "mean-gap control: expected a periodic cell (periodic = 1; the half-space has no "
                                  "mean gap)");
    if (options->adhesion_work > 0)
        status = check_adhesion_control(control, options);
    if (status != IM_OK)
        return status;
    if (!(isfinite(largest_target) && largest_target >= 0))
        return im_fail(IM_EINVAL, "largest %s = %g: expected a finite value >= 0", control_target(control),
                       largest_target);
    return IM_OK;
}

static int check_create(const im_field *surface, const im_indenter *punch, enum im_control control,
                        double largest_target, const im_solver_options *options)
{
    int status = im_field_check_finite(surface, "surface heights");
    if (status == IM_OK)
        status = check_run(punch, control, largest_target, options);
    if (status != IM_OK)
        return status;
    if (!(isfinite(surface->delta) && surface->delta > 0))
        return im_fail(IM_EINVAL, "surface delta = %g: expected > 0", surface->delta);
    /* forces are pressures times delta^2: a square out of range made "N = inf" of a unit load */
    if (!(surface->delta >= 1e-150 && surface->delta <= 1e150))
        return im_fail(IM_EINVAL,
                       "surface delta = %g: expected 1e-150 <= delta <= 1e150 (patch areas delta^2 and "
                       "the forces on them must be finite doubles): express the lengths in another unit",
                       surface->delta);
    return check_profile_grid(surface, punch);
}

/* The cap on the repulsive part p_r of the pressure: the hardness H_p, or with adhesion H_p + sigma0, so that
 * the net pressure p_r - sigma0 of a patch in contact (whole in the zone) is at most H_p; 0 without a
 * hardness. */
static double repulsive_cap(const im_solver_options *o)
{
    if (!(o->hardness > 0))
        return 0;
    return o->adhesion_work > 0 ? o->hardness + o->adhesion_work / o->adhesion_range : o->hardness;
}

/* Whether each step is solved on the box its approach can touch (step_window.h): under displacement
 * control on a cropped half-space, without adhesion (whose zone and marks live on the whole window), on
 * the CPU engine (a GPU plan per box costs more than the box saves). */
static int steps_in_boxes(const im_indentation *run)
{
    return run->options.crop && !run->options.periodic && run->control == IM_CONTROL_DISPLACEMENT &&
           !(run->options.adhesion_work > 0) && strcmp(im_solver_plan_device(run->plan), "cpu") == 0;
}

/* The searches that mark adhesive states (solve_adhesive_at_load, solve_adhesive_at_mean_gap) get their marks
 * here, at creation: over ranks an allocation failing on one rank inside a step would leave the others waiting
 * in the step's collective solves, while the creation's failure is agreed on by every rank. */
static int reserve_adhesive_marks(im_indentation *run)
{
    const int searches = run->control == IM_CONTROL_LOAD ||
                         (run->control == IM_CONTROL_MEAN_GAP && run->options.hardness > 0);
    if (!run->adhesion || !searches)
        return IM_OK;
    const size_t n = (size_t)run->window.nx * run->window.ny + 1; /* + 1: a rank may hold no rows */
    for (int slot = ADHESION_MARK_TRY; slot <= ADHESION_MARK_STEP; ++slot) {
        run->marked_pressure[slot] = malloc(sizeof(double) * n);
        run->marked_displacement[slot] = malloc(sizeof(double) * n);
        if (!run->marked_pressure[slot] || !run->marked_displacement[slot])
            return im_fail(IM_ENOMEM, "adhesion under load control: a marked state (2 x %.1f MiB)",
                           sizeof(double) * (double)n / 1048576.0);
        int status = adhesion_reserve_mark(run->adhesion, (enum adhesion_mark_slot)slot);
        if (status != IM_OK)
            return status;
    }
    return IM_OK;
}

static int allocate_window(im_indentation *run)
{
    const im_window w = run->window;
    size_t n = (size_t)w.nx * w.ny;
    run->window_gap0 = malloc(sizeof(double) * (n + 1)); /* + 1: a rank may hold no rows */
    run->pressure = calloc(n + 1, sizeof(double));
    run->displacement = calloc(n + 1, sizeof(double));
    run->plastic = calloc(n + 1, sizeof(double));
    if (run->options.hardness > 0)
        run->flow = calloc(n + 1, sizeof(double));
    if (!run->window_gap0 || !run->pressure || !run->displacement || !run->plastic ||
        (run->options.hardness > 0 && !run->flow))
        return im_fail(IM_ENOMEM,
                       "indentation window %d x %d: allocation of %d x %.1f MiB failed (out of memory, or "
                       "of the address space ulimit -v leaves)",
                       w.nx, w.ny, run->options.hardness > 0 ? 5 : 4, sizeof(double) * (double)n / 1048576.0);
#pragma omp parallel for schedule(static)
    for (int iy = 0; iy < w.ny; ++iy)
        memcpy(run->window_gap0 + (size_t)iy * w.nx, run->gap0 + (size_t)(iy + w.y0) * run->nx + w.x0,
               sizeof(double) * w.nx);
    im_solver_options repulsive = run->options;
    repulsive.adhesion_work = repulsive.adhesion_range = repulsive.adhesion_zone = 0;
    repulsive.hardness = repulsive_cap(&run->options);
    int status = IM_OK;
    if (run->ranks) /* the ranks' plan: it solves the run's repulsive problem (indentation_rows.h) */
        run->plan->options.hardness = repulsive.hardness;
    else
        status = im_solver_plan_create(w.nx, w.ny, run->delta, &repulsive, &run->plan);
    if (status == IM_OK && run->options.adhesion_work > 0)
        status = adhesion_create(w.nx, w.ny, run->options.periodic, &run->options, &run->adhesion);
    if (status == IM_OK && run->adhesion && run->ranks)
        adhesion_over_ranks(run->adhesion, run->ranks);
    if (status == IM_OK)
        status = reserve_adhesive_marks(run);
    if (status == IM_OK && steps_in_boxes(run) && !(run->steps = step_window_create()))
        status = im_fail(IM_ENOMEM, "indentation window %d x %d: the step boxes' state", w.nx, w.ny);
    return status;
}

/* A run up to its window: checked, its undeformed gap and window chosen, nothing of the window's made. */
static int start_run(const im_field *surface, const im_indenter *punch, enum im_control control,
                     double largest_target, const im_solver_options *options, im_indentation **out)
{
    *out = NULL;
    im_solver_options o = options ? *options : im_solver_options_default();
    int status = check_create(surface, punch, control, largest_target, &o);
    if (status == IM_OK) /* from here on the law solved (a widened zone's) is the run's */
        status = im_adhesion_solved_law(&o, surface->delta, &o, NULL);
    if (status != IM_OK)
        return status;
    im_indentation *run = calloc(1, sizeof *run);
    if (!run || !(run->gap0 = malloc(sizeof(double) * im_field_count(surface)))) {
        free(run);
        return im_fail(IM_ENOMEM, "indentation of a %d x %d surface", surface->nx, surface->ny);
    }
    run->punch = *punch;
    run->control = control;
    run->largest_target = largest_target;
    run->options = o;
    run->nx = surface->nx;
    run->ny = surface->ny;
    run->delta = surface->delta;
    run->approach_bound = approach_bound(control == IM_CONTROL_LOAD ? height_range(surface) : 0, punch, control,
                                         largest_target, &o);
    status = undeformed_gap(run, surface);
    if (status == IM_OK)
        run->window = choose_window(run);
    if (status != IM_OK) {
        im_indentation_free(run);
        return status;
    }
    *out = run;
    return IM_OK;
}

int im_indentation_create(const im_field *surface, const im_indenter *punch, enum im_control control,
                          double largest_target, const im_solver_options *options, im_indentation **out)
{
    ARG_VIEW(surface, "surface");
    ARG_REQUIRE(punch, "punch");
    ARG_REQUIRE(out, "out");
    int status = start_run(surface, punch, control, largest_target, options, out);
    if (status == IM_OK && (status = allocate_window(*out)) != IM_OK) {
        im_indentation_free(*out);
        *out = NULL;
    }
    return status;
}

int im_indentation_window_for(const im_field *surface, const im_indenter *punch, enum im_control control,
                              double largest_target, const im_solver_options *options, im_window *out)
{
    ARG_REQUIRE(out, "out");
    *out = (im_window){0, 0, 0, 0};
    ARG_VIEW(surface, "surface");
    ARG_REQUIRE(punch, "punch");
    im_indentation *run = NULL;
    const int status = start_run(surface, punch, control, largest_target, options, &run);
    if (status == IM_OK)
        *out = run->window;
    im_indentation_free(run);
    return status;
}

int indentation_create_on_rows(const indentation_rows *grid, const im_indenter *punch, enum im_control control,
                               double largest_target, const im_solver_options *options, im_indentation **out)
{
    *out = NULL;
    im_solver_options o = *options;
    o.crop = 0;
    if (o.periodic)
        return im_fail(IM_EINVAL, "an indentation over ranks: periodic = 1: expected the half-space (a periodic "
                                  "cell's steps: im_mpi_flat_contact_step)");
    int status = check_run(punch, control, largest_target, &o);
    if (status == IM_OK)
        status = im_adhesion_solved_law(&o, grid->delta, &o, NULL);
    if (status != IM_OK)
        return status;
    im_indentation *run = calloc(1, sizeof *run);
    const size_t n = (size_t)grid->rows * grid->nx;
    if (!run || !(run->gap0 = malloc(sizeof(double) * (n + 1)))) {
        free(run);
        return im_fail(IM_ENOMEM, "indentation of %d rows of a %d x %d surface", grid->rows, grid->nx, grid->ny);
    }
    memcpy(run->gap0, grid->gap0, sizeof(double) * n);
    *run = (im_indentation){.punch = *punch,
                            .control = control,
                            .largest_target = largest_target,
                            .options = o,
                            .nx = grid->nx,
                            .ny = grid->ny,
                            .delta = grid->delta,
                            .approach_bound = approach_bound(grid->height_range, punch, control, largest_target, &o),
                            .gap0 = run->gap0,
                            .window = {0, 0, grid->nx, grid->rows},
                            .plan = grid->plan,
                            .ranks = grid->ranks};
    status = allocate_window(run);
    if (status != IM_OK) {
        im_indentation_free(run);
        return status;
    }
    *out = run;
    return IM_OK;
}

indentation_rows_state indentation_rows_state_of(const im_indentation *run)
{
    return (indentation_rows_state){run->pressure, run->displacement, run->window_gap0, run->adhesion, run->approach};
}

void im_indentation_free(im_indentation *run)
{
    if (!run)
        return;
    if (!run->ranks)
        im_solver_plan_free(run->plan);
    im_solver_plan_free(run->full_plan);
    free(run->gap0);
    free(run->window_gap0);
    free(run->pressure);
    free(run->displacement);
    free(run->plastic);
    free(run->flow);
    adhesion_free(run->adhesion);
    step_window_free(run->steps);
    for (int slot = 0; slot < 2; ++slot) {
        free(run->marked_pressure[slot]);
        free(run->marked_displacement[slot]);
    }
    free(run);
}

/* Whether surface row `line` (or, with column set, that column) holds a patch of the window whose value is
 * > level (or, with at_most set, <= level); sets *at to its position along the row (column). */
static int line_holds(const im_indentation *run, const double *values, double level, int at_most, int line,
                      int column, int *at)
{
    const im_window w = run->window;
    int first = column ? w.x0 : w.y0, extent = column ? w.nx : w.ny;
    if (line < first || line >= first + extent)
        return 0;
    int length = column ? w.ny : w.nx;
    for (int k = 0; k < length; ++k) {
        size_t i = column ? (size_t)k * w.nx + (line - w.x0) : (size_t)(line - w.y0) * w.nx + k;
        if (at_most ? values[i] <= level : values[i] > level) {
            *at = k + (column ? w.y0 : w.x0);
            return 1;
        }
    }
    return 0;
}

/* Over ranks: whether values > 0 on the surface's outer row or column (*x, *y: the first such patch,
 * row-major, on every rank). */
static int on_edge_over_ranks(const im_indentation *run, const double *values, int *x, int *y)
{
    const long first = run->ranks->first_on_edge(run->ranks->context, values);
    *x = first == LONG_MAX ? -1 : (int)(first % run->nx);
    *y = first == LONG_MAX ? -1 : (int)(first / run->nx);
    return first != LONG_MAX;
}

/* Whether a window patch on the surface's outer row or column has a value > level (<= level with at_most):
 * *x, *y the first such in row-major order, as over ranks (on_edge_over_ranks). One process only. */
static int edge_holds(const im_indentation *run, const double *values, double level, int at_most, int *x, int *y)
{
    const int last_row = run->ny - 1, last_column = run->nx - 1;
    int at, left, right; /* the first rows holding it in the outer columns */
    *x = *y = -1;
    if (line_holds(run, values, level, at_most, 0, 0, &at)) {
        *x = at;
        *y = 0;
    } else {
        if (!line_holds(run, values, level, at_most, 0, 1, &left))
            left = INT_MAX;
        if (!line_holds(run, values, level, at_most, last_column, 1, &right))
            right = INT_MAX;
        if ((left < right ? left : right) < last_row) {
            *x = left <= right ? 0 : last_column;
            *y = left <= right ? left : right;
        } else if (line_holds(run, values, level, at_most, last_row, 0, &at)) {
            *x = at;
            *y = last_row;
        }
    }
    return *x >= 0;
}

/* IM_EEDGE if a contact patch lies on the outer row or column of the surface. */
static int check_edge(const im_indentation *run)
{
    int sx = -1, sy = -1;
    if (run->ranks)
        on_edge_over_ranks(run, run->pressure, &sx, &sy);
    else
        edge_holds(run, run->pressure, 0, 0, &sx, &sy);
    if (sx < 0)
        return IM_OK;
    return im_fail(IM_EEDGE,
                   "contact reached the edge of the %d x %d surface at patch (%d, %d) (approach %g): the "
                   "surface is too small for this step",
                   run->nx, run->ny, sx, sy, run->approach);
}

/* IM_EEDGE when the adhesive zone reaches the window's outer row or column: the surface's edge, or a
 * window chosen from the undeformed gap that the zone outgrew. */
static int check_zone(const im_indentation *run)
{
    int x, y;
    if (!(run->ranks ? on_edge_over_ranks(run, run->adhesion->share, &x, &y)
                     : adhesion_zone_on_border(run->adhesion, &x, &y)))
        return IM_OK;
    const im_window w = run->window;
    const int whole = run->ranks || (w.nx == run->nx && w.ny == run->ny); /* the ranks' rows are the surface's */
    return im_fail(IM_EEDGE, "the adhesive zone reached the edge of the %s at patch (%d, %d) (approach %g): %s",
                   whole ? "surface" : "solve window", x + w.x0, y + w.y0, run->approach,
                   whole ? "the surface is too small for this step"
                         : "the window chosen from the undeformed gap is too small; solve the whole surface (options "
                           "crop = 0, indent --full)");
}

/* Under load control, IM_EEDGE before solving when the smooth contact at this load would already
 * reach past the surface's edge: no surface of this size can carry the load without contact
 * there (a rough contact spreads wider than the smooth one), so the solve would only end at the
 * edge, or, with a window bound broken by the edge, nowhere sensible. */
static int check_reachable(const im_indentation *run, double load)
{
    /* a flat punch's contact radius is its own; a 2-D profile has no smooth-contact estimate; a
     * periodic cell has no edge */
    if (run->control != IM_CONTROL_LOAD || run->punch.kind == IM_PUNCH_FLAT ||
        run->punch.kind == IM_PUNCH_PROFILE_2D || load <= 0 ||
        run->options.periodic) /* (under tension, with adhesion: no smooth contact either) */
        return IM_OK;
    double ax, ay;
    im_indenter_axis(&run->punch, run->nx, run->ny, run->delta, &ax, &ay);
    const double room = fmin(fmin(ax, run->nx * run->delta - ax), fmin(ay, run->ny * run->delta - ay));
    if (!(room > 0))
        return im_fail(IM_EEDGE,
                       "load %g cannot be reached: the punch axis (%g, %g) is on the edge of the %d x %d "
                       "surface or outside it, so any contact reaches the edge",
                       load, ax, ay, run->nx, run->ny);
    const double radius = sqrt(im_indenter_area_for_load(&run->punch, run->options.e_star, load) / M_PI);
    if (radius < room)
        return IM_OK;
    return im_fail(IM_EEDGE,
                   "load %g cannot be reached on the %d x %d surface: the smooth contact at this load has "
                   "radius %.4g, but the punch axis is %.4g from the surface's edge",
                   load, run->nx, run->ny, radius, room);
}

/* Plastic memory. A solved step leaves every patch at the cap with g = g0 - w + u <= 0: the overlap
 * -g is the surface's plastic flattening in this step. It is added to the patch's plastic depth and
 * to its undeformed gap, so that the state solved stays the solution (g = 0 there now) and every
 * later step sees the deformed surface: unloading is elastic from it, and reloading retraces the
 * unloading curve until a patch reaches the cap again. With adhesion the cap is on the repulsive part
 * (repulsive_cap: the net pressure there is H_p) and u the net displacement. Returns the patches that
 * yielded. */
static long accumulate_plastic_flow(im_indentation *run, double approach)
{
    const double cap = repulsive_cap(&run->options);
    const im_window w = run->window;
    double yielding = 0; /* a count, exact in a double, summed over the ranks */
#pragma omp parallel for schedule(static) reduction(+ : yielding)
    for (int iy = 0; iy < w.ny; ++iy)
        for (int ix = 0; ix < w.nx; ++ix) {
            size_t wi = (size_t)iy * w.nx + ix;
            run->flow[wi] = 0;
            if (!(run->pressure[wi] >= cap))
                continue;
            ++yielding;
            double flow = -(run->window_gap0[wi] - approach +
                            adhesion_net_displacement(run->adhesion, wi, run->displacement[wi]));
            if (!(flow > 0))
                continue;
            run->flow[wi] = flow;
            run->plastic[wi] += flow;
            run->window_gap0[wi] += flow;
            run->gap0[(size_t)(iy + w.y0) * run->nx + ix + w.x0] += flow;
        }
    combine(run, &yielding, 1, ADHESION_SUM);
    /* in a fixed order: the same bits for any thread or rank count */
    run->plastic_work += run->options.hardness * run->delta * run->delta * grid_sum(run, run->flow);
    return (long)yielding;
}

/* The largest plastic depth so far, and the least undeformed gap (g0 + plastic depth): where the
 * punch, withdrawn, would first touch the surface. */
static void plastic_extremes(const im_indentation *run, double *deepest, double *touch)
{
    double d = 0, g = INFINITY;
    const size_t n = (size_t)run->window.nx * run->window.ny;
#pragma omp parallel for schedule(static) reduction(max : d) reduction(min : g)
    for (size_t i = 0; i < n; ++i) {
        d = fmax(d, run->plastic[i]);
        g = fmin(g, run->window_gap0[i]);
    }
    double extremes[2] = {d, -g}; /* both maxima: one reduction over the ranks */
    combine(run, extremes, 2, ADHESION_MAX);
    *deepest = extremes[0];
    *touch = -extremes[1];
}

/* The largest approach at which the punch carries nothing: where it touches the (deformed) surface. */
static double withdrawn_approach(const im_indentation *run)
{
    double deepest, touch;
    plastic_extremes(run, &deepest, &touch);
    return touch;
}

/* The mean over the (periodic) cell of the gap max(g0 - w + u, 0): Persson's u-bar. A yielded patch's
 * overlap is its plastic flattening (accumulate_plastic_flow), so it counts 0. */
typedef struct gap_terms {
    const double *gap0, *u;
    const adhesion_state *adhesion; /* the zone's stress lifts the surface: u is the net displacement */
    double approach;
} gap_terms;

static double open_gap(size_t i, const void *context)
{
    const gap_terms *t = context;
    return fmax(t->gap0[i] - t->approach + adhesion_net_displacement(t->adhesion, i, t->u[i]), 0.0);
}

static double mean_open_gap(const im_indentation *run, double approach)
{
    const size_t n = (size_t)run->window.nx * run->window.ny;
    const gap_terms terms = {run->window_gap0, run->displacement, run->adhesion, approach};
    return sum_terms(n, open_gap, &terms) / (double)n;
}

static void fill_step(const im_indentation *run, const im_solve_result *s, im_step_result *out)
{
    const double d2 = run->delta * run->delta;
    /* periodic: no smooth half-space contact to compare with; the area ratio is A / A0 of the cell */
    double area = run->options.periodic ? (double)run->nx * run->ny * d2
                                        : im_indenter_area_for_load(&run->punch, run->options.e_star, s->load);
    step_result_from_solve(s, area, d2, run->options.periodic, out);
    out->plastic_work = run->plastic_work;
    out->mean_gap = run->options.periodic ? mean_open_gap(run, s->approach) : NAN;
    plastic_extremes(run, &out->plastic_depth, &out->residual_approach);
    if (run->adhesion)
        adhesion_split(run->adhesion, run->pressure, run->delta, &out->tensile_force, &out->adhesive_patches,
                       &out->repulsive_patches);
}

/* ---- searched approaches: load control with a hardness, mean-gap control with one ----
 * Polonsky-Keer's load control takes the approach from the elastic patches (0 < p < H_p); once every
 * contact patch is capped (a fully plastic start, a small load on a soft surface) there are none and
 * the approach is undefined. With a hardness the load is reached instead by displacement-controlled
 * solves on the approach, each warm-started from the last: N(w) is continuous and non-decreasing, so
 * a bracket and the Illinois variant of regula falsi find it, to |N - target| <= tol target. A
 * periodic cell's mean gap with a hardness is found the same way (it falls as w grows). The search itself
 * is search.c's, shared with the distributed cell. */
static int repulsive_solve(void *context, double w, im_solve_result *s)
{
    return solve_window(context, IM_CONTROL_DISPLACEMENT, w, s);
}

static double solved_load(void *context, const im_solve_result *s)
{
    (void)context;
    return s->load;
}

/* [lo, hi] with N(lo) <= target <= N(hi), from the last step's approach (or the smooth estimate)
 * doubled while it carries too little; IM_EEDGE when no approach within the window's bound carries
 * the load. */
static int bracket_load(approach_search *search, double *lo, double *e_lo, double *hi, double *e_hi)
{
    im_indentation *run = search->context;
    double w = run->approach > 0 ? run->approach
                                 : im_indenter_approach_for_load(&run->punch, run->options.e_star, search->target);
    if (!(isfinite(w) && w > 0 && w <= run->approach_bound))
        w = fmin(run->approach_bound, run->delta);
    *lo = 0, *e_lo = -search->target; /* no approach, no load */
    *hi = w;
    int status = search_trial(search, w, e_hi);
    while (status == IM_OK && *e_hi < 0) {
        /* the window's bound reached, or the load no longer grows: every patch the punch can reach has
         * yielded (a flat punch's or a profile's rim: the bound is then infinite) */
        const int plateau = *lo > 0 && !(*e_hi > *e_lo + 1e-12 * search->target);
        if (*hi >= run->approach_bound || plateau || search->trials >= SEARCH_MAX)
            return im_fail(IM_EEDGE,
                           "load %g cannot be reached: at the approach %g the contact carries %g%s "
                           "(a yielded contact carries at most H_p times the area the punch can reach)",
                           search->target, *hi, search->target + *e_hi,
                           plateau ? ", no more than at half that approach" : "");
        *lo = *hi, *e_lo = *e_hi;
        *hi = fmin(2 * *hi, run->approach_bound);
        status = search_trial(search, *hi, e_hi);
    }
    return status;
}

/* The approach that carries target (see above). */
static int solve_at_load(im_indentation *run, double target, im_solve_result *out)
{
    approach_search search = {.context = run,
                              .target = target,
                              .tol = run->options.tol,
                              .measure = solved_load,
                              .solve = repulsive_solve};
    double lo, e_lo, hi, e_hi;
    int status = bracket_load(&search, &lo, &e_lo, &hi, &e_hi);
    if (status == IM_OK)
        status = search_refine(&search, lo, e_lo, hi, e_hi, e_hi, target);
    *out = search.last;
    return status;
}

static double negative_mean_gap(void *context, const im_solve_result *s)
{
    const im_indentation *run = context;
    return -mean_open_gap(run, s->approach);
}

/* The approach of a periodic cell's mean gap: mean g0 - target (mean u = 0, with or without an adhesive zone,
 * whose stress moves no mean either). */
static double mean_gap_approach(const im_indentation *run, double target)
{
    const size_t n = (size_t)run->window.nx * run->window.ny;
    return grid_sum(run, run->window_gap0) / (double)n - target;
}

/* Mean-gap control, searched under a hardness (search.h). */
static int solve_at_mean_gap(im_indentation *run, double target, im_solve_result *out)
{
    approach_search search = {.context = run,
                              .target = -target,
                              .tol = run->options.tol,
                              .measure = negative_mean_gap,
                              .solve = repulsive_solve};
    return search_mean_gap(&search, mean_gap_approach(run, target), run->options.hardness, out);
}

/* ---- load control with adhesion ----
 * An adhesive contact's state depends on its history (adhesion.c: the zone grows on approach, shrinks on
 * retraction), so the search for the approach that carries a load only ever moves forward, as a quasi-static
 * loading would: from the last state it accepted (marked), each try goes on towards the target's side (larger
 * approaches for a larger load, smaller ones for a smaller load); a try that falls short becomes the new mark,
 * a try that passes the target is undone (rewound to the mark) and the next try goes less far. So the load found
 * is the first one met on the way, on the stable branch. Loading holds any load (a jump-in on the way only dips
 * the force). Unloading holds down to the least load met on the way, the pull-off force under load control: a
 * smaller target has no equilibrium (the contact jumps out), which the search says once its steps are tol short. */
static int mark_adhesive_state(im_indentation *run, enum adhesion_mark_slot slot)
{
    const size_t bytes = (size_t)run->window.nx * run->window.ny * sizeof(double);
    memcpy(run->marked_pressure[slot], run->pressure, bytes);
    memcpy(run->marked_displacement[slot], run->displacement, bytes);
    return adhesion_set_mark(run->adhesion, slot);
}

static void rewind_adhesive_state(im_indentation *run, enum adhesion_mark_slot slot)
{
    const size_t bytes = (size_t)run->window.nx * run->window.ny * sizeof(double);
    memcpy(run->pressure, run->marked_pressure[slot], bytes);
    memcpy(run->displacement, run->marked_displacement[slot], bytes);
    adhesion_rewind(run->adhesion, slot);
}

static int adhesive_solve(void *context, double w, im_solve_result *s)
{
    im_indentation *run = context;
    rewind_adhesive_state(run, ADHESION_MARK_TRY);
    return adhesion_solve(run->adhesion, run->plan, run->window_gap0, w, run->pressure, run->displacement, s);
}

/* The walk's state: the last accepted approach (the mark) and the try beyond it. */
typedef struct forward_walk {
    approach_search search;
    double direction;    /* +1: towards larger approaches (a larger load), -1: smaller */
    double near, e_near; /* the mark's approach and excess N - target (its sign: not yet passed) */
    double scale;        /* |N - target| <= tol scale ends the search */
} forward_walk;

enum forward_try { TRY_FAILED = -1, TRY_MARKED, TRY_PASSED };

/* One try at w from the mark: TRY_PASSED when its load passed the target (to be undone), else it becomes the
 * new mark (TRY_MARKED); TRY_FAILED with *status on an error. */
static enum forward_try try_forward(forward_walk *walk, double w, double *e, int *status)
{
    *status = search_trial(&walk->search, w, e);
    if (*status != IM_OK)
        return TRY_FAILED;
    if (walk->direction * *e >= 0)
        return TRY_PASSED;
    walk->near = w, walk->e_near = *e;
    *status = mark_adhesive_state(walk->search.context, ADHESION_MARK_TRY);
    return *status == IM_OK ? TRY_MARKED : TRY_FAILED;
}

/* From a passing try at far (excess e_far, the state now), the Illinois regula falsi between the mark and far,
 * the mark moving forward; ends on a try within tol scale of the target (or tol apart in the approach), its
 * state kept. */
static int narrow_forward(forward_walk *walk, double far, double e_far)
{
    const double tol = walk->search.tol, length = walk->search.length;
    int status = IM_OK, side = 0;
    double e = e_far;
    while (fabs(e) > tol * walk->scale && fabs(far - walk->near) > tol * fmax(fabs(far), length)) {
        if (walk->search.trials >= SEARCH_MAX)
            return im_fail(IM_ENOCONV,
                           "load %g: no approach between %.17g and %.17g reaches it to tol %g after %d "
                           "solves",
                           walk->search.target, walk->near, far, tol, walk->search.trials);
        const double w = (walk->near * e_far - far * walk->e_near) / (e_far - walk->e_near);
        const enum forward_try t = try_forward(walk, w, &e, &status);
        if (t == TRY_FAILED)
            return status;
        if (t == TRY_PASSED) { /* Illinois: the end kept twice running has its excess halved */
            far = w, e_far = e;
            walk->e_near *= side == 1 ? 0.5 : 1;
            side = 1;
        } else {
            e_far *= side == -1 ? 0.5 : 1;
            side = -1;
        }
    }
    return status;
}

/* The farthest approach a try may take: the window's bound, or on an elastic periodic cell half the way from the
 * mark to mean g0, where the mean gap closes (full contact at an infinite pressure: no solve there; with a
 * hardness the yielded patches take any approach). */
static double farthest_try(const im_indentation *run, double near)
{
    if (run->options.periodic && !(run->options.hardness > 0))
        return near + 0.5 * (mean_gap_approach(run, 0) - near);
    return run->approach_bound;
}

static double cell_area(const im_indentation *run) { return run->nx * run->ny * run->delta * run->delta; }

/* IM_EINVAL for a target below the least load met on retraction (at approach least_at): a cell's named by its
 * mean pressure. */
static int refuse_beyond_pull_off(const im_indentation *run, double target, double least, double least_at)
{
    if (!run->options.periodic)
        return im_fail(IM_EINVAL,
                       "load %g: below the least load the contact held on retraction, %.9g at "
                       "approach %.9g (the pull-off force under load control: the contact jumps out)",
                       target, least, least_at);
    const double area = cell_area(run);
    return im_fail(IM_EINVAL,
                   "mean pressure %g (load %g): below the least mean pressure the cell held on retraction, %.9g "
                   "at approach %.9g (the cell's pull-off under load control: it jumps out of contact)",
                   target / area, target, least / area, least_at);
}

/* Whether a patch of the last step is in repulsive contact. */
static int touching(const im_indentation *run)
{
    const size_t n = (size_t)run->window.nx * run->window.ny;
    double any = 0;
    for (size_t i = 0; i < n && !any; ++i)
        any = run->pressure[i] > 0;
    combine(run, &any, 1, ADHESION_MAX);
    return any > 0;
}

/* IM_EINVAL for a tension beyond the last step's load n0 with no patch in contact: under a load the surfaces
 * fly apart there (the tension only fades as they part), and a contact is held in tension only on retraction
 * from contact. */
static int refuse_tension_out_of_contact(const im_indentation *run, double target, double n0)
{
    char what[96];
    if (run->options.periodic)
        snprintf(what, sizeof what, "mean pressure %g (load %g)", target / cell_area(run), target);
    else
        snprintf(what, sizeof what, "load %g", target);
    return im_fail(IM_EINVAL,
                   "%s: a tension beyond the last step's load %g with no patch in contact (the surfaces would part "
                   "under it; a load-controlled contact holds tension on retraction from contact: load it into "
                   "compression first)",
                   what, n0);
}

/* Steps from the mark towards the target until a try passes it; then narrow_forward. Steps of delta_c / 8, on
 * approach doubling up to delta_c: a retraction's state depends on the steps it took (the zone's edge lets go
 * patch by patch, and a long step skips states a slow pull passes through: its pull-off comes out weaker), so
 * it keeps to short ones, through the small rises of the load where a ring of patches lets go (a
 * load-controlled contact snaps on to the next state there), until the surfaces have let go of each other:
 * then no approach held the target, and the least load met is the pull-off force under load control. */
static int walk_to_load(forward_walk *walk)
{
    im_indentation *run = walk->search.context;
    const double range = run->options.adhesion_range;
    double step = range / 8, least = walk->search.target + walk->e_near, least_at = walk->near;
    for (;;) {
        const double far = fmin(walk->near + walk->direction * step, farthest_try(run, walk->near));
        if (!(far != walk->near))
            return im_fail(IM_EEDGE,
                           "load %g cannot be reached: at the window's bound, approach %g, the contact "
                           "carries %g",
                           walk->search.target, walk->near, walk->search.target + walk->e_near);
        if (walk->search.trials >= SEARCH_MAX)
            return im_fail(IM_ENOCONV, "load %g: not passed after %d adhesive solves (last approach %g)",
                           walk->search.target, walk->search.trials, walk->near);
        double e;
        int status;
        const enum forward_try t = try_forward(walk, far, &e, &status);
        if (t == TRY_FAILED)
            return status;
        if (t == TRY_PASSED)
            return narrow_forward(walk, far, e);
        if (walk->search.target + e < least)
            least = walk->search.target + e, least_at = far;
        if (walk->direction < 0 && walk->search.last.contact_patches == 0) /* let go: the tension only fades now */
            return refuse_beyond_pull_off(run, walk->search.target, least, least_at);
        if (walk->direction > 0)
            step = fmin(2 * step, range);
    }
}

static int solve_adhesive_at_load(im_indentation *run, double target, im_solve_result *out)
{
    const int stepped = run->adhesion->stepped;
    /* unstepped: clear of the law's reach, no load */
    const double w0 = stepped ? run->approach : -(adhesion_reach(&run->options) + run->options.adhesion_range);
    const double n0 = stepped ? run->load : 0;
    if (target < fmin(n0, 0) && !touching(run)) {
        *out = (im_solve_result){.approach = w0, .load = n0};
        return refuse_tension_out_of_contact(run, target, n0);
    }
    forward_walk walk = {.search = {.context = run,
                                    .target = target,
                                    .tol = run->options.tol,
                                    .measure = solved_load,
                                    .solve = adhesive_solve,
                                    .length = run->options.adhesion_range},
                         .direction = n0 - target <= 0 ? 1 : -1,
                         .near = w0,
                         .e_near = n0 - target,
                         .scale = fmax(fabs(target), fabs(n0))};
    int status = mark_adhesive_state(run, ADHESION_MARK_STEP);
    if (status == IM_OK)
        status = mark_adhesive_state(run, ADHESION_MARK_TRY);
    if (status == IM_OK) {
        double e;
        status = n0 == target ? search_trial(&walk.search, w0, &e) : walk_to_load(&walk);
    }
    *out = walk.search.last;
    if (status != IM_OK && run->marked_pressure[ADHESION_MARK_STEP]) { /* the history stays the last step's */
        rewind_adhesive_state(run, ADHESION_MARK_STEP);
        out->approach = w0;
        out->load = n0;
    }
    return status;
}

/* An adhesive cell's mean gap under a hardness: search_mean_gap's search, each try a step from the step's start
 * (marked: the zone's history is the last step's whatever the tries before), which a failed search returns to. */
static int solve_adhesive_at_mean_gap(im_indentation *run, double target, im_solve_result *out)
{
    approach_search search = {.context = run,
                              .target = -target,
                              .tol = run->options.tol,
                              .measure = negative_mean_gap,
                              .solve = adhesive_solve,
                              .length = run->options.adhesion_range,
                              .lowest = -INFINITY};
    int status = mark_adhesive_state(run, ADHESION_MARK_TRY);
    if (status != IM_OK)
        return status;
    status = search_mean_gap(&search, mean_gap_approach(run, target), run->options.hardness, out);
    if (status != IM_OK) { /* the history stays the last step's */
        rewind_adhesive_state(run, ADHESION_MARK_TRY);
        out->approach = run->approach;
        out->load = run->load;
    }
    return status;
}

/* The approach adhesion's passes hold: the target, or on a periodic cell its mean gap's. */
static double adhesive_approach(const im_indentation *run, double target)
{
    return run->control == IM_CONTROL_MEAN_GAP ? mean_gap_approach(run, target) : target;
}

static window_grid window_grid_of(const im_indentation *run)
{
    return (window_grid){run->window.nx, run->window.ny,    run->window_gap0,
                         run->pressure,  run->displacement, run->plan};
}

/* A checked step's solve, its checks and its record; the surface keeps its state where it fails. */
static int solve_step(im_indentation *run, double target, im_step_result *out)
{
    int status;
    im_solve_result s;
    /* (a periodic cell under load control: Polonsky-Keer's own, which keeps mean u = 0) */
    if (run->adhesion && run->control == IM_CONTROL_LOAD)
        status = solve_adhesive_at_load(run, target, &s);
    else if (run->adhesion && run->control == IM_CONTROL_MEAN_GAP && run->options.hardness > 0)
        status = solve_adhesive_at_mean_gap(run, target, &s);
    else if (run->adhesion)
        status = adhesion_solve(run->adhesion, run->plan, run->window_gap0, adhesive_approach(run, target),
                                run->pressure, run->displacement, &s);
    else if (run->control == IM_CONTROL_LOAD && run->options.hardness > 0 && target > 0 && !run->options.periodic)
        status = solve_at_load(run, target, &s);
    else if (run->control == IM_CONTROL_MEAN_GAP)
        status = solve_at_mean_gap(run, target, &s);
    else if (run->steps) {
        const window_grid grid = window_grid_of(run);
        status = step_window_solve(run->steps, &grid, target, &s);
    } else
        status = solve_window(run, run->control, target, &s);
    if (status == IM_OK && run->control == IM_CONTROL_LOAD && target == 0 && !run->adhesion)
        s.approach = withdrawn_approach(run); /* N = 0 holds at any approach up to it */
    run->approach = s.approach;
    run->load = s.load;
    if (status == IM_OK && !run->options.periodic) /* a periodic cell has no edge */
        status = check_edge(run);
    if (status == IM_OK && run->adhesion)
        status = check_zone(run);
    if (status == IM_OK && s.approach > run->approach_bound) /* only if the bound were wrong: never hide it */
        status = im_fail(IM_EEDGE, "load %g needed approach %g beyond the window's bound %g", target, s.approach,
                         run->approach_bound);
    /* a step that failed leaves the surface as it was: the history stays the one reported */
    long yielding = status == IM_OK && run->options.hardness > 0 ? accumulate_plastic_flow(run, s.approach) : 0;
    fill_step(run, &s, out);
    out->yielding_patches = yielding;
    return status;
}

/* Over the ranks too: whether a window patch whose undeformed gap is `least` lies on the surface's edge (*x, *y:
 * the first, row-major). -1 where the ranks' scratch rows do not fit (on every rank). */
static int least_gap_on_edge(const im_indentation *run, double least, int *x, int *y)
{
    if (!run->ranks)
        return edge_holds(run, run->window_gap0, least, 1, x, y);
    const size_t n = (size_t)run->window.nx * run->window.ny;
    double *at_least = malloc(sizeof(double) * (n + 1)); /* + 1: a rank may hold no rows */
    double failed = at_least == NULL;
    combine(run, &failed, 1, ADHESION_MAX);
    if (failed > 0) {
        free(at_least);
        return -1;
    }
    for (size_t i = 0; i < n; ++i)
        at_least[i] = run->window_gap0[i] <= least;
    const int on_edge = on_edge_over_ranks(run, at_least, x, y);
    free(at_least);
    return on_edge;
}

/* Before solving, IM_EEDGE when the step's contact would certainly reach the surface's edge: the punch first
 * touches the surface on its outer row or column (a least undeformed gap there) and the step presses beyond
 * that touch. Such a patch, were it free, would be displaced by at least the approach beyond the touch, more
 * than any loaded patch is, which a compressive load cannot do (the half-space's displacement is largest on
 * its load: the maximum principle of the 1/r kernel). It is the smooth surface under a flat punch whose face
 * reaches the edge patches (all of the face at the least gap, U7). Other edge patches within the approach may stay
 * free (a neighbour's load lifts them), as a rough surface under a face wider than the grid often does: the
 * solve and check_edge decide those. Not with adhesion (its tension is a signed load), nor on a periodic
 * cell (no edge). */
static int check_first_touch_inside(const im_indentation *run, double target)
{
    if (run->adhesion || run->options.periodic || run->control == IM_CONTROL_MEAN_GAP)
        return IM_OK;
    const double touch = withdrawn_approach(run); /* the least gap: 0 until a hardness cap flattens it */
    if (!(run->control == IM_CONTROL_LOAD ? target > 0 : target > touch))
        return IM_OK;
    int x, y;
    const int on_edge = least_gap_on_edge(run, touch, &x, &y);
    if (on_edge < 0)
        return im_fail(IM_ENOMEM, "%s %g: the edge check's %d x %d rows", control_target(run->control), target,
                       run->window.nx, run->window.ny);
    if (!on_edge)
        return IM_OK;
    double ax, ay; /* the distance from the axis to that patch's centre, where a face's reach is judged */
    im_indenter_axis(&run->punch, run->nx, run->ny, run->delta, &ax, &ay);
    const double distance = hypot((x + 0.5) * run->delta - ax, (y + 0.5) * run->delta - ay);
    char reach[160];
    if (run->punch.kind == IM_PUNCH_FLAT)
        snprintf(reach, sizeof reach, "its face's radius %g reaches that patch's centre, %g from its axis",
                 run->punch.radius, distance);
    else
        snprintf(reach, sizeof reach, "that patch's centre is %g from its axis", distance);
    return im_fail(IM_EEDGE,
                   "%s %g cannot be reached on the %d x %d surface without contact at its edge: the %s punch first "
                   "touches the surface on the edge, at patch (%d, %d), so any step beyond that touch has contact "
                   "there (%s)",
                   control_target(run->control), target, run->nx, run->ny, im_punch_name(run->punch.kind), x, y,
                   reach);
}

int im_indentation_step(im_indentation *run, double target, im_step_result *out)
{
    ARG_REQUIRE(run, "run");
    ARG_REQUIRE(out, "out");
    const char *what = control_target(run->control);
    const double lowest = run->adhesion ? -run->largest_target : 0; /* adhesion: the punch pulled away too */
    if (!(isfinite(target) && target >= lowest && target <= run->largest_target))
        return im_fail(IM_EINVAL, "%s = %g: expected a value in [%g, %g], the largest %s the run was prepared for%s",
                       what, target, lowest, run->largest_target, what, run->adhesion ? " and its negative" : "");
    if (run->control == IM_CONTROL_MEAN_GAP && !(target > 0))
        return im_fail(IM_EINVAL, "mean gap = %g: expected > 0 (at 0 the cell is in full contact)", target);
    int status = check_reachable(run, target);
    if (status != IM_OK)
        return status;
    const double cell_capacity = run->options.hardness * cell_area(run);
    if (run->options.periodic && run->options.hardness > 0 && target >= cell_capacity)
        return im_fail(IM_EINVAL,
                       "load %g: a periodic cell at hardness %g carries less than H_p A0 = %g (at that "
                       "load every patch would have yielded: full contact, no approach to find)",
                       target, run->options.hardness, cell_capacity);
    team_choose(); /* every region of the step on the threads the other processes leave free (core/team_size.c),
                    * the first-touch check's reduction too (mpi_team) */
    status = check_first_touch_inside(run, target);
    if (status == IM_OK)
        status = solve_step(run, target, out);
    team_restore();
    return status;
}

int im_indentation_plastic(const im_indentation *run, im_field **plastic)
{
    ARG_REQUIRE(run, "run");
    ARG_REQUIRE(plastic, "plastic");
    *plastic = NULL;
    im_field *field = NULL;
    int status = im_field_create(run->nx, run->ny, run->delta, &field);
    if (status != IM_OK)
        return status;
    const im_window w = run->window;
    for (int iy = 0; iy < w.ny; ++iy)
        memcpy(field->data + (size_t)(iy + w.y0) * run->nx + w.x0, run->plastic + (size_t)iy * w.nx,
               sizeof(double) * w.nx);
    *plastic = field;
    return IM_OK;
}

im_window im_indentation_window(const im_indentation *run)
{
    ARG_REQUIRE_OR(run, "run", (im_window){0});
    return run->window;
}

const im_solver_plan *im_indentation_plan(const im_indentation *run)
{
    ARG_REQUIRE_OR(run, "run", NULL);
    return run->plan;
}

static int new_full_field(const im_indentation *run, im_field **out)
{
    return out ? im_field_create(run->nx, run->ny, run->delta, out) : IM_OK;
}

/* The fields of im_indentation_fields, with the window's u as it stands (see there). */
static int window_fields(const im_indentation *run, im_field **force, im_field **gap, im_field **displacement)
{
    im_field *f = NULL, *g = NULL, *u = NULL;
    int status = new_full_field(run, force ? &f : NULL);
    if (status == IM_OK)
        status = new_full_field(run, gap ? &g : NULL);
    if (status == IM_OK)
        status = new_full_field(run, displacement ? &u : NULL);
    if (status != IM_OK) {
        im_field_free(f);
        im_field_free(g);
        return status;
    }
    const im_window w = run->window;
    const double d2 = run->delta * run->delta, approach = run->approach;
    if (g) {
#pragma omp parallel for schedule(static)
        for (size_t i = 0; i < im_field_count(g); ++i)
            g->data[i] = run->gap0[i] - approach;
    }
#pragma omp parallel for schedule(static)
    for (int iy = 0; iy < w.ny; ++iy)
        for (int ix = 0; ix < w.nx; ++ix) {
            size_t wi = (size_t)iy * w.nx + ix, i = (size_t)(iy + w.y0) * run->nx + ix + w.x0;
            const double u_net = adhesion_net_displacement(run->adhesion, wi, run->displacement[wi]);
            if (f)
                f->data[i] = adhesion_net_pressure(run->adhesion, wi, run->pressure[wi]) * d2;
            if (u)
                u->data[i] = u_net;
            if (g)
                g->data[i] += u_net;
        }
    if (force)
        *force = f;
    if (gap)
        *gap = g;
    if (displacement)
        *displacement = u;
    return IM_OK;
}

int im_indentation_fields(const im_indentation *run, im_field **force, im_field **gap, im_field **displacement)
{
    ARG_REQUIRE(run, "run");
    team_choose();                             /* as a step's */
    if (run->steps && (gap || displacement)) { /* u outside the last step's box is not K p yet */
        const window_grid grid = window_grid_of(run);
        step_window_refresh(run->steps, &grid);
    }
    const int status = window_fields(run, force, gap, displacement);
    team_restore();
    return status;
}

/* g = g0 - w + u with the whole grid's u, from window_fields' g: corrected by u less the window's u
 * that g holds (window_fields' value, 0 outside the window), stale or not: it cancels. */
static void correct_gap(const im_indentation *run, im_field *g, const im_field *u)
{
    const im_window w = run->window;
#pragma omp parallel for schedule(static)
    for (int iy = 0; iy < run->ny; ++iy)
        for (int ix = 0; ix < run->nx; ++ix) {
            const size_t i = (size_t)iy * run->nx + ix, wi = (size_t)(iy - w.y0) * w.nx + (ix - w.x0);
            const int inside = iy >= w.y0 && iy < w.y0 + w.ny && ix >= w.x0 && ix < w.x0 + w.nx;
            const double window_u = inside ? adhesion_net_displacement(run->adhesion, wi, run->displacement[wi])
                                           : 0.0;
            g->data[i] += u->data[i] - window_u;
        }
}

/* Whether the run's solver plan convolves the whole grid as a convolution's plan would, to the bit: it
 * is the whole grid's (the window is), on the CPU and estimated (the same FFTW_ESTIMATE transforms and
 * the same spectrum; a measured plan's transforms may round differently). */
static int solver_plan_convolves_grid(const im_indentation *run)
{
    const im_solver_plan *p = run->plan;
    return p && !run->ranks && p->nx == run->nx && p->ny == run->ny && !p->measured &&
           strcmp(im_solver_plan_device(p), "cpu") == 0;
}

/* The plan the whole grid's u is convolved on: the solver's where it convolves the grid (no second plan
 * beside it), else a convolution's plan, made at the first call and kept. */
static int full_grid_plan(im_indentation *run, im_solver_plan **plan)
{
    if (solver_plan_convolves_grid(run)) {
        *plan = run->plan;
        return IM_OK;
    }
    int status = run->full_plan
                     ? IM_OK
                     : im_displacement_plan_create(run->nx, run->ny, run->delta, &run->options, &run->full_plan);
    *plan = run->full_plan;
    return status;
}

/* The fields on the whole grid: the window's, with u convolved over every patch. */
static int whole_grid_fields(im_indentation *run, im_field **force, im_field **gap, im_field **displacement)
{
    im_field *f = NULL, *g = NULL, *u = NULL;
    im_solver_plan *plan = NULL;
    int status = full_grid_plan(run, &plan);
    if (status == IM_OK)
        status = window_fields(run, &f, gap ? &g : NULL, NULL);
    if (status == IM_OK)
        status = im_displacement_full_with(plan, f, &u);
    if (status == IM_OK && g)
        correct_gap(run, g, u);
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

int im_indentation_fields_full(im_indentation *run, im_field **force, im_field **gap, im_field **displacement)
{
    ARG_REQUIRE(run, "run");
    if (run->options.periodic) /* the solve covers the whole cell with the periodic u already */
        return im_indentation_fields(run, force, gap, displacement);
    team_choose(); /* as a step's: the whole grid's convolution and its plan beside other work */
    const int status = whole_grid_fields(run, force, gap, displacement);
    team_restore();
    return status;
}
