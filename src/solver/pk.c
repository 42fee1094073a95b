/* Polonsky-Keer constrained conjugate gradients (see solver.h for the algorithm and stopping rule),
 * written once over the engines of engine.h: this file decides, the engine's passes compute. */
#include "solver/engine.h"
#include "solver/search.h"
#include "core/args.h"
#include "core/summation.h"
#include "core/team_size.h"

#include "indentmap/status.h"

#include <float.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <string.h>

static const solver_engine *engine_of(const pk_run *r) { return r->plan->engine; }

/* ---- the pressure cap (hardness): perfect plasticity at p = H_p ----
 * The elastic contact is 0 < p < cap; patches at a bound are fixed while their gap agrees: p = 0
 * needs g >= 0, p = cap needs g <= 0 (the surface has yielded: the overlap -g is its plastic
 * flattening). The conjugate gradients move the elastic patches and the capped ones whose gap says
 * they should unload (g > 0), every update projected onto [0, cap]; patches at 0 that penetrate join
 * as in Polonsky-Keer. Without a hardness the cap is +INFINITY and every line below is the plain
 * Polonsky-Keer step. */
static double pressure_cap(const im_solver_plan *plan)
{
    return plan->options.hardness > 0 ? plan->options.hardness : INFINITY;
}

/* g = u + g0 - w, with w imposed or (load control) the mean of u + g0 over I_c. */
static gap_stats compute_gaps(pk_run *r)
{
    const double cap = pressure_cap(r->plan);
    double w = r->target;
    if (r->control == IM_CONTROL_LOAD) {
        long count;
        w = engine_of(r)->contact_mean(r, r->p_factor, r->u_factor, cap, &count);
        r->p_factor = r->u_factor = 1;
        /* With a cap every contact patch may be capped for a while (none elastic to take the approach
         * from): the approach stays where it was; the capped patches whose gap opens then unload and the
         * penetrating free ones join, which restores an elastic set. */
        if (count == 0 && isfinite(cap) && isfinite(r->approach))
            w = r->approach;
        r->approach = w;
    }
    gap_stats s = engine_of(r)->gaps(r, w, cap);
    s.approach = w;
    return s;
}

static double relative_residual(const gap_stats *s)
{
    double rms = s->contact ? sqrt(s->sum_squares / s->contact) : 0;
    return fmax(rms, s->penetration) / s->approach;
}

/* u = K p */
static void convolve(pk_run *r)
{
    engine_of(r)->convolve_pressure(r);
    ++r->convolutions;
}

/* `depth` halvings of [lo, hi] towards the approach where the local guess carries the load: the
 * 2^depth - 1 midpoints they may take (in heap order, node j's halves are nodes 2j and 2j + 1), their
 * loads, then the walk down the tree, which takes the midpoints and comparisons that depth single
 * halvings take. depth 1 on an engine without winkler_loads; up to 3 (SOLVER_WINKLER_BATCH) with. */
static void bisect_levels(pk_run *r, double k0, int depth, double *lo, double *hi)
{
    double lows[SOLVER_WINKLER_BATCH + 1] = {0, *lo}, highs[SOLVER_WINKLER_BATCH + 1] = {0, *hi};
    double mids[SOLVER_WINKLER_BATCH + 1], loads[SOLVER_WINKLER_BATCH + 1];
    const int nodes = (1 << depth) - 1;
    for (int j = 1; j <= nodes; ++j) {
        mids[j] = 0.5 * (lows[j] + highs[j]);
        if (2 * j < nodes) {
            lows[2 * j] = lows[j], highs[2 * j] = mids[j];
            lows[2 * j + 1] = mids[j], highs[2 * j + 1] = highs[j];
        }
    }
    if (depth == 1)
        loads[1] = engine_of(r)->winkler(r, mids[1], k0, 0);
    else
        engine_of(r)->winkler_loads(r, mids + 1, nodes, k0, loads + 1);
    for (int j = 1, level = 0; level < depth; ++level)
        if (loads[j] < r->target)
            *lo = mids[j], j = 2 * j + 1;
        else
            *hi = mids[j], j = 2 * j;
}

/* Cold start: the Winkler guess p = max(w - g0, 0) / K(0) (the local part of the response only) at
 * the imposed approach, or (load control) at the approach where it carries the load, found by 60
 * halvings (at w = K(0) N / delta^2 the first-touch patch alone does), three at a time on an engine
 * that sums several approaches in one round trip (the GPU's: 20 waits for 60). */
static void cold_start(pk_run *r)
{
    const double k0 = r->plan->kernel[0];
    double w = r->target;
    if (r->control == IM_CONTROL_LOAD) {
        double lo = 0, hi = k0 * r->target / (r->plan->delta * r->plan->delta);
        const int batch = engine_of(r)->winkler_loads ? 3 : 1;
        for (int k = 0; k < 60; k += batch)
            bisect_levels(r, k0, batch, &lo, &hi);
        w = hi;
        r->approach = w; /* load control's approach until an elastic set forms (compute_gaps) */
    }
    engine_of(r)->winkler(r, w, k0, 1);
    const double cap = pressure_cap(r->plan);
    if (isfinite(cap)) /* a patch above the cap is neither elastic nor at the bound: it would never move */
        engine_of(r)->clip(r, cap);
}

/* With a pressure cap, under load control: rescales the elastic pressures so that delta^2 sum p = N
 * with the capped ones fixed, and recomputes u (a partial rescaling is not linear in p). */
static void impose_load_capped(pk_run *r, double cap)
{
    double elastic_load, capped_load;
    engine_of(r)->load_split(r, cap, &elastic_load, &capped_load);
    if (!(elastic_load > 0))
        return;
    const double scale = fmax(0.0, r->target - capped_load) / elastic_load;
    int clipped = engine_of(r)->scale_elastic(r, scale, cap);
    if (capped_load > 0 || clipped) { /* a partial rescaling: u by FFT */
        convolve(r);
        return;
    }
    r->u_factor = scale; /* nothing capped: all of p was scaled, and u with it by linearity (postponed) */
}

/* Under load control, rescales p (and u, by linearity) so that delta^2 sum p = N. The rescaling of
 * both fields is left to the pass that reads them next, compute_gaps's contact mean (r->p_factor,
 * r->u_factor; rescale_now where none follows): one pass over p and u saved per iteration. */
static void impose_load(pk_run *r)
{
    const double cap = pressure_cap(r->plan);
    if (isfinite(cap)) {
        impose_load_capped(r, cap);
        return;
    }
    const double load = engine_of(r)->pressure_sum(r) * r->plan->delta * r->plan->delta; /* p >= 0 */
    if (!(load > 0))
        return;
    r->p_factor = r->u_factor = r->target / load; /* postponed */
}

/* The rescaling impose_load left for the next contact mean, done now: the solve ends before one. */
static void rescale_now(pk_run *r)
{
    if (r->p_factor != 1 || r->u_factor != 1)
        engine_of(r)->scale(r, r->p_factor, r->u_factor);
    r->p_factor = r->u_factor = 1;
}

/* z = M g on I_c (0 elsewhere), M the inverse of a periodic circulant close to K (plan.c): K is
 * close to 1 / (E* |k|) in Fourier space, so M ~ E* |k| undoes most of its spread of eigenvalues,
 * which grows with the contact's size in patches and sets plain CG's rate. Centred over I_c under
 * load control (the directions keep the load). Returns <g, z> over I_c. */
static double precondition(pk_run *r)
{
    long count;
    double z_sum = engine_of(r)->precondition(r, &count);
    const double mean = r->control == IM_CONTROL_LOAD && count ? z_sum / count : 0;
    return engine_of(r)->precondition_centre(r, mean);
}

/* Step length tau = <g, t> / <K t, t> over I_c; under load control K t is centred over I_c:
 * <K t - mean, t> = <K t, t> - mean <1, t>. */
static double step_length(pk_run *r)
{
    step_terms s = engine_of(r)->step(r, pressure_cap(r->plan));
    double den = s.kt_t;
    if (r->control == IM_CONTROL_LOAD && s.count > 0)
        den -= s.kt_sum / s.count * s.t_sum;
    return s.gt / den;
}

/* Adds the changes that clipping and joining made to u (already moved by -tau K t) by direct
 * summation, or, when they are many, recomputes u = K p by FFT, which is then cheaper and exact;
 * returns 1 if u was recomputed. */
static int update_displacement(pk_run *r, long changes)
{
    if (changes > r->plan->direct_limit) {
        convolve(r);
        return 1;
    }
    if (changes > 0)
        engine_of(r)->add_point_loads(r, changes);
    return 0;
}

int solver_periodic_approach_checked(const im_solver_plan *plan, enum im_control control)
{
    return plan->options.periodic && control == IM_CONTROL_DISPLACEMENT && !(plan->options.hardness > 0);
}

int solver_check_periodic_mean_gap(double mean_gap0, double target)
{
    const double mean_gap = mean_gap0 - target;
    if (mean_gap > 0)
        return IM_OK;
    return im_fail(IM_EINVAL,
                   "approach %g on a periodic cell: its mean gap would be %g, expected > 0 (the mean "
                   "of the undeformed gap is %g; full contact needs an infinite mean pressure)",
                   target, mean_gap, mean_gap0);
}

static int check_periodic_approach(const im_solver_plan *plan, const double *gap0, enum im_control control,
                                   double target)
{
    if (!solver_periodic_approach_checked(plan, control))
        return IM_OK;
    const size_t n = (size_t)plan->nx * plan->ny;
    return solver_check_periodic_mean_gap(sum_doubles(gap0, n) / (double)n, target);
}

/* The caller's arrays checked in one pass, which also says whether any pressure is positive (a warm
 * start), so that no second pass over p looks for one. */
static int check_inputs(const im_solver_plan *plan, const double *gap0, enum im_control control, double target,
                        const double *p, int *positive)
{
    if (plan->convolution_only)
        return im_fail(IM_EINVAL, "im_solver_solve: plan is a convolution's (im_displacement_plan_create), which "
                                  "cannot solve; expected one from im_solver_plan_create");
    if (control != IM_CONTROL_DISPLACEMENT && control != IM_CONTROL_LOAD)
        return im_fail(IM_EINVAL,
                       "im_solver_solve: control = %d: expected IM_CONTROL_DISPLACEMENT or IM_CONTROL_LOAD (mean-gap "
                       "control is im_indentation_create's, periodic)",
                       (int)control);
    if (!(isfinite(target) && target >= 0))
        return im_fail(IM_EINVAL, "%s = %g: expected a finite value >= 0",
                       control == IM_CONTROL_LOAD ? "load" : "approach", target);
    const size_t n = (size_t)plan->nx * plan->ny;
    size_t bad_gap = n, bad_pressure = n; /* the first offending index of each, n if none */
    int any_positive = 0;
#pragma omp parallel for schedule(static) reduction(min : bad_gap, bad_pressure) reduction(| : any_positive)
    for (size_t i = 0; i < n; ++i) {
        if ((isnan(gap0[i]) || gap0[i] < 0) && i < bad_gap)
            bad_gap = i;
        if (!(isfinite(p[i]) && p[i] >= 0) && i < bad_pressure)
            bad_pressure = i;
        any_positive |= p[i] > 0;
    }
    *positive = any_positive;
    if (bad_gap < n)
        return im_fail(IM_ENUMERIC, "undeformed gap[%zu] = %g: expected >= 0 or +inf", bad_gap, gap0[bad_gap]);
    if (bad_pressure < n)
        return im_fail(IM_EINVAL, "warm-start pressure[%zu] = %g: expected finite and >= 0", bad_pressure,
                       p[bad_pressure]);
    return check_periodic_approach(plan, gap0, control, target);
}

static void summarise(pk_run *r, const gap_stats *s, im_solve_result *out)
{
    const double d2 = r->plan->delta * r->plan->delta;
    double sum, peak;
    long contact;
    engine_of(r)->summary(r, &sum, &contact, &peak);
    out->approach = s->approach;
    out->load = sum * d2;
    out->contact_patches = contact;
    out->mean_pressure = contact ? sum / contact : 0;
    out->max_pressure = peak;
}

/* Load control with a cap while no patch is elastic (compute_gaps kept the approach): impose_load has
 * nothing to rescale, so the load is whatever the capped patches carry, and the stopping rule, which
 * does not look at the load, must not accept it (*missed). With no capped patch that would unload and
 * no free one that would join, nothing can change: IM_ENOCONV at once, saying why. */
static int check_capped_load(pk_run *r, const gap_stats *s, int iteration, int *missed)
{
    const double cap = pressure_cap(r->plan);
    if (r->control != IM_CONTROL_LOAD || !isfinite(cap) || s->contact > 0)
        return IM_OK;
    const double load = engine_of(r)->pressure_sum(r) * r->plan->delta * r->plan->delta;
    *missed = !(fabs(load - r->target) <= r->plan->options.tol * r->target);
    if (!*missed || s->moving_squares > 0 || s->penetration_squares > 0)
        return IM_OK;
    return im_fail(IM_ENOCONV,
                   "contact iteration %d: every patch in contact is at the hardness cap H_p = %g, "
                   "carrying %g of the load %g, and no patch can join or unload at the approach %g (load control "
                   "with a cap needs an elastic patch; a smaller load step, or displacement control, avoids it)",
                   iteration, cap, load, r->target, s->approach);
}

/* How far the residual taken on a u moved by `steps` steps since its last transform (u -= tau K t, the
 * load's rescaling, up to direct_limit point loads per patch) can be from the residual on K p, in units
 * of the approach: each step rounds each patch's u a few times (the +4) and once per point load, and
 * its K t carries the transform's rounding (log2 of the transformed grid's size); the terms are taken
 * as at most 8 approaches in size (u <= w + |g| on the contact; a step moves u by less), and the residual
 * moves by twice the gaps' error under load control (w is their mean over I_c). At tol 1e-8 and 40 steps
 * it is about 1e-11: a residual below tol by more than this is below it on K p too, and the confirming
 * transform is needed only within this of tol (or at a tolerance near the rounding). */
static double drift_bound(const pk_run *r, int steps)
{
    const double transformed = (double)r->plan->px * r->plan->py;
    return 2 * 8 * steps * (4 + (double)r->plan->direct_limit + log2(transformed)) * DBL_EPSILON;
}

/* A tolerance below what double precision resolves on this problem: the residual reaches its rounding
 * (drift_bound of one step, ~5e-13 on a 512^2 grid) and from there only scatters (1e-16 to 1e-14 of the
 * approach), so the solve would run to max_iterations and fail (91 s at 512^2 for tol 1e-17). A residual
 * at that level whose least value has not halved in STALL_ITERATIONS iterations stops the solve, naming
 * the range it scattered over; converging solves halve it within a few iterations there. Armed only for a
 * tol below that rounding (a coarser tol is met before it) and on residuals that count (not a capped load
 * control's missed load, whose residual may be 0). */
enum { STALL_ITERATIONS = 100 };
typedef struct {
    double best;  /* the least residual, updated when it halves */
    double worst; /* the largest residual since */
    int since;    /* the iteration of that update */
} stall_watch;

static int residual_stalls(stall_watch *watch, double residual, double rounding, int iteration)
{
    if (residual < 0.5 * watch->best) {
        *watch = (stall_watch){residual, residual, iteration};
        return 0;
    }
    watch->worst = fmax(watch->worst, residual);
    return watch->best <= rounding && iteration - watch->since >= STALL_ITERATIONS;
}

/* How the rounding showed: the residual's scatter (step_length NaN), or a step length that rounding
 * turned non-positive (periodic load control's centred one: <K t, t> - mean(K t) sum t). */
static int fail_stalled(const stall_watch *watch, double tol, int iterations, double rounding, double step_length)
{
    char how[64];
    if (isnan(step_length))
        snprintf(how, sizeof how, "it has not halved in %d iterations", STALL_ITERATIONS);
    else
        snprintf(how, sizeof how, "the step length came out %.3g", step_length);
    return im_fail(IM_ENOCONV,
                   "contact solve: residual > tol %.3g after %d iterations: %s, at double precision's rounding of "
                   "this problem's gaps (the residual %.3g to %.3g of the approach since it last halved; the "
                   "stopping rule's bound %.3g); expected a tol above %.3g",
                   tol, iterations, how, watch->best, watch->worst, rounding, watch->worst);
}

/* The caller's stop flag: the signal's number, 0 to go on. */
static int stop_signal(pk_run *r)
{
    if (engine_of(r)->stop_signal)
        return engine_of(r)->stop_signal(r);
    const volatile sig_atomic_t *stop = r->plan->options.stop;
    return stop ? (int)*stop : 0;
}

/* Preconditioned: patches join only in a join step, a preconditioned steepest-descent step whose set
 * is I_c and the penetrating patches at p = 0 (the preconditioner, the direction and the exact step
 * length all cover both, so the joining patches get the pressure the step finds for them rather than
 * -tau g at a step length set by I_c alone); the other steps are preconditioned CG on I_c, which may
 * only shrink it (clipping). Plain PK lets patches join by the gap in every step. (No preconditioner
 * with a pressure cap: plan.c.) A join step is taken when the penetration
 * outside I_c outweighs the gap left on it, in sums (Dostal's proportioning test) or in the stopping
 * rule's own terms: its largest penetration PENETRATION_LEAD times the rms gap on I_c. A few
 * penetrating patches never win the sums against the gaps of a large I_c, and the CG steps meanwhile
 * take the rms gap far below what the stopping rule needs while the penetration, which only a join
 * step reduces, holds the residual (docs/benchmarks.md, "Joins by the stopping rule's terms"). */
static const double PENETRATION_LEAD = 4;

static int joining_pays(const gap_stats *s)
{
    const double rms = s->contact ? sqrt(s->sum_squares / s->contact) : 0;
    return s->penetration_squares > s->sum_squares || s->penetration > PENETRATION_LEAD * rms;
}

static enum solver_join step_join(const im_solver_options *o, const gap_stats *s)
{
    if (!o->precondition)
        return SOLVER_JOIN_BY_GAP;
    return joining_pays(s) ? SOLVER_JOIN_IN_DIRECTION : SOLVER_JOIN_NONE;
}

/* The CG loop proper; returns IM_OK, IM_ENOCONV, IM_ENUMERIC, IM_EINTERRUPTED or an engine's
 * failure, and leaves the last gap_stats. */
static int iterate(pk_run *r, im_solve_result *res, gap_stats *last)
{
    const im_solver_options *o = &r->plan->options;
    const solver_engine *e = engine_of(r);
    const double cap = pressure_cap(r->plan);
    int drifting = 0, restart = 1; /* drifting: the steps since u was last transformed (drift_bound) */
    double previous_squares = 1;
    stall_watch watch = {INFINITY, 0, 0};
    const double rounding = drift_bound(r, 1);
    for (;;) {
        if (r->status != IM_OK)
            return r->status;
        gap_stats s = compute_gaps(r);
        if (r->status != IM_OK)
            return r->status;
        *last = s;
        res->residual = relative_residual(&s);
        if (!isfinite(res->residual))
            return im_fail(IM_ENUMERIC, "contact iteration %d: residual is %g", res->iterations, res->residual);
        int load_missed = 0;
        int status = check_capped_load(r, &s, res->iterations, &load_missed);
        if (status != IM_OK)
            return status;
        if (res->residual <= o->tol && !load_missed) {
            if (res->residual + drift_bound(r, drifting) <= o->tol)
                return IM_OK;
            convolve(r); /* confirm on the exact displacement */
            drifting = 0;
            continue;
        }
        if (res->iterations >= o->max_iterations)
            return im_fail(IM_ENOCONV, "contact solve: residual %.3g > tol %.3g after %d iterations (cap)",
                           res->residual, o->tol, res->iterations);
        if (o->tol < rounding && !load_missed && residual_stalls(&watch, res->residual, rounding, res->iterations))
            return fail_stalled(&watch, o->tol, res->iterations, rounding, NAN);
        team_refresh();
        const int stopped_by = stop_signal(r);
        if (stopped_by) /* the caller asked to stop: p is still a valid (warm) start */
            return im_fail(IM_EINTERRUPTED, "contact solve: interrupted by signal %d after %d iterations", stopped_by,
                           res->iterations);
        if (s.contact == 0 && !e->any_positive(r)) {
            /* everything was clipped (patches at a pressure cap are not): start again from the local guess */
            cold_start(r);
            convolve(r);
            restart = 1;
            drifting = 0;
            continue;
        }
        ++res->iterations;
        r->join = step_join(o, &s);
        if (o->precondition && r->join == SOLVER_JOIN_IN_DIRECTION)
            restart = 1;
        if (!o->precondition) {
            e->direction(r, 0, restart ? 0 : s.moving_squares / previous_squares, cap);
            previous_squares = s.moving_squares;
        } else {
            double gz = precondition(r);
            e->direction(r, 1, restart ? 0 : gz / previous_squares, cap);
            previous_squares = gz;
        }
        e->convolve_direction(r); /* K t, kept by the engine */
        ++r->convolutions;
        double tau = step_length(r);
        if (!(tau > 0) && !restart) {
            /* Clipping changed the contact set and the conjugate direction no longer descends:
             * restart from steepest descent, whose step <g, g> / <K g, g> is always positive. */
            restart = 1;
            continue;
        }
        /* The direction vanishes on the step's set (under load control, one patch, or gaps already
         * equal there): only penetrating patches outside the contact set are left to join. Give
         * them the local (Winkler) step, p = -g / K(0), by the gap (t is 0 on them too). */
        if (isnan(tau) && restart) {
            tau = 1.0 / r->plan->kernel[0];
            if (r->join == SOLVER_JOIN_IN_DIRECTION)
                r->join = SOLVER_JOIN_BY_GAP;
        }
        if (!isfinite(tau) || tau <= 0) {
            if (tau <= 0 && o->tol < rounding && watch.best <= rounding)
                return fail_stalled(&watch, o->tol, res->iterations, rounding, tau);
            return im_fail(IM_ENUMERIC, "contact iteration %d: step length %g", res->iterations, tau);
        }
        long changes = e->update_pressure(r, tau, cap, &restart);
        if (o->precondition && r->join == SOLVER_JOIN_IN_DIRECTION)
            restart = 1; /* the next preconditioned step starts its own conjugate sequence */
        drifting = update_displacement(r, changes) ? 0 : drifting + 1;
        if (r->control == IM_CONTROL_LOAD)
            impose_load(r);
    }
}

static int solve_once(pk_run *r, im_solve_result *res)
{
    const solver_engine *e = engine_of(r);
    gap_stats last = {0};
    int status = e->begin(r);
    if (status != IM_OK)
        return status;
    if (!e->any_positive(r))
        cold_start(r);
    const double cap = pressure_cap(r->plan); /* a warm start above the cap */
    if (isfinite(cap))
        e->clip(r, cap);
    convolve(r);
    if (r->control == IM_CONTROL_LOAD)
        impose_load(r);
    status = iterate(r, res, &last);
    rescale_now(r);
    summarise(r, &last, res);
    int finished = e->finish(r); /* p and u back, also after a failure: p is a valid warm start */
    r->answer_kept = r->keep_answer && r->status == IM_OK;
    return status != IM_OK ? status : (r->status != IM_OK ? r->status : finished);
}

/* ---- Load control with a cap on the half-space ----
 * Polonsky-Keer's load control takes the approach from the mean gap over the elastic patches and rescales
 * them to the load; with a cap the direction also moves the capped patches that unload, so the centred
 * step denominator <Kt, t> - mean(Kt) sum t can turn negative and the iteration breaks down (a 256^2 rough
 * cone at H_p 0.12 and twice the smooth cone's load: "step length -18.8" at iteration 1). There the load is
 * found as an indentation finds it: displacement-controlled solves on the approach, each warm-started from
 * the last, bracketed from w = 0 (gap0 >= 0: no load) and narrowed by search.c. A periodic cell keeps
 * Polonsky-Keer's load control (its mean-pressure steps converge with a cap: tests/mpi/mpi_parity.c). */
static int load_is_searched(const pk_run *r)
{
    return r->control == IM_CONTROL_LOAD && isfinite(pressure_cap(r->plan)) && !r->plan->options.periodic;
}

static int displacement_trial(void *context, double w, im_solve_result *s)
{
    pk_run *r = context;
    r->control = IM_CONTROL_DISPLACEMENT;
    r->target = w;
    *s = (im_solve_result){0};
    return solve_once(r, s);
}

static double trial_load(void *context, const im_solve_result *s)
{
    (void)context;
    return s->load;
}

/* The next approach to try below the load: from N(w) > 0 as if N grew as w^2 (a cone's; a sphere's and a
 * flat punch's grow slower, so this stays short of the load there), doubled while nothing carries. */
static double next_approach(double w, double carried, double load)
{
    return carried > 0 ? w * fmax(1.1, sqrt(load / carried)) : 2 * w;
}

/* [lo, hi] with N(lo) <= load <= N(hi), from one patch spacing upwards (next_approach); IM_EEDGE once
 * the load stops growing (every patch the punch reaches has yielded). */
static int bracket_capped_load(approach_search *search, double cap, double *lo, double *e_lo, double *hi,
                               double *e_hi)
{
    const pk_run *r = search->context;
    const double load = search->target;
    *lo = 0, *e_lo = -load;
    *hi = r->plan->delta;
    int status = search_trial(search, *hi, e_hi);
    while (status == IM_OK && *e_hi < 0) {
        const int carries = *e_lo > -load;
        if ((carries && !(*e_hi > *e_lo + 1e-12 * load)) || search->trials >= SEARCH_MAX)
            return im_fail(IM_EEDGE,
                           "load %g cannot be reached under the hardness cap H_p = %g: at the approach %g the "
                           "contact carries %g, no more than at a smaller approach",
                           load, cap, *hi, load + *e_hi);
        *lo = *hi, *e_lo = *e_hi;
        *hi = next_approach(*hi, load + *e_hi, load);
        status = search_trial(search, *hi, e_hi);
    }
    return status;
}

static int solve_capped_load(pk_run *r, im_solve_result *res)
{
    const double load = r->target;
    approach_search search = {.context = r,
                              .target = load,
                              .tol = r->plan->options.tol,
                              .measure = trial_load,
                              .solve = displacement_trial};
    double lo, e_lo, hi, e_hi;
    int status = bracket_capped_load(&search, pressure_cap(r->plan), &lo, &e_lo, &hi, &e_hi);
    if (status == IM_OK)
        status = search_refine(&search, lo, e_lo, hi, e_hi, e_hi, load);
    r->control = IM_CONTROL_LOAD;
    r->target = load;
    const int coarse = res->coarse_iterations;
    *res = search.last;
    res->coarse_iterations += coarse;
    return status;
}

int solver_pk_solve(pk_run *r, im_solve_result *res)
{
    return load_is_searched(r) ? solve_capped_load(r, res) : solve_once(r, res);
}

pk_run solver_pk_run(im_solver_plan *plan, const double *gap0, enum im_control control, double target, double *p,
                     double *u)
{
    return (pk_run){.plan = plan,
                    .gap0 = gap0,
                    .control = control,
                    .target = target,
                    .p = p,
                    .u = u,
                    .status = IM_OK,
                    .approach = NAN,
                    .p_factor = 1,
                    .u_factor = 1};
}

/* A solve whose inputs were checked (positive: whether any pressure is positive), from start (its clock). */
static int solve_checked(pk_run *r, int positive, double start, im_solve_result *result)
{
    im_solver_plan *plan = r->plan;
    im_solve_result res = {0};
    int status = IM_OK;
    const size_t n = (size_t)plan->nx * plan->ny;
    if (r->target == 0) { /* no approach or no load: no contact */
        memset(r->p, 0, sizeof(double) * n);
        memset(r->u, 0, sizeof(double) * n);
    } else {
        if (!positive && plan->coarse)
            res.coarse_iterations = solver_cascade_start(plan, r->gap0, r->control, r->target, r->p,
                                                         &r->start_prolonged);
        status = solver_pk_solve(r, &res);
    }
    res.convolutions = r->convolutions;
    res.seconds = omp_get_wtime() - start;
    if (result)
        *result = res;
    return status;
}

int im_solver_solve(im_solver_plan *plan, const double *gap0, enum im_control control, double target,
                    double *pressure, double *displacement, im_solve_result *result)
{
    ARG_REQUIRE(plan, "plan");
    ARG_REQUIRE(gap0, "gap0");
    ARG_REQUIRE(pressure, "pressure");
    ARG_REQUIRE(displacement, "displacement");
    const double start = omp_get_wtime();
    int positive = 0;
    team_choose(); /* the threads the other processes leave free (core/team_size.c), for every region */
    int status = check_inputs(plan, gap0, control, target, pressure, &positive);
    if (status == IM_OK) {
        pk_run r = solver_pk_run(plan, gap0, control, target, pressure, displacement);
        status = solve_checked(&r, positive, start, result);
    }
    team_restore();
    return status;
}

int solver_solve_coarse(im_solver_plan *coarse, const double *gap0, double mean_gap0, enum im_control control,
                        double target, double *pressure, double *displacement, int keep, im_solve_result *result,
                        int *kept)
{
    const double start = omp_get_wtime();
    *kept = 0;
    int status = solver_periodic_approach_checked(coarse, control) ? solver_check_periodic_mean_gap(mean_gap0, target)
                                                                   : IM_OK;
    if (status != IM_OK)
        return status;
    pk_run r = solver_pk_run(coarse, gap0, control, target, pressure, displacement);
    r.keep_answer = keep && !load_is_searched(&r);
    status = solve_checked(&r, 0, start, result);
    *kept = r.answer_kept;
    return status;
}
