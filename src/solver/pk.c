/* Polonsky-Keer constrained conjugate gradients (see solver.h for the algorithm and stopping rule). */
#include "solver/plan.h"

#include "core/summation.h"
#include "indentmap/status.h"

#include <math.h>
#include <omp.h>
#include <string.h>

typedef struct gap_stats {
    double approach;     /* w used for these gaps */
    long contact;        /* |I_c| */
    double sum_squares;  /* G = sum over I_c of g^2 */
    double moving_squares; /* the same over the patches the CG moves (with a pressure cap, also the
                              capped ones that unload; otherwise G) */
    double penetration;  /* max over p = 0 of -g (0 if none) */
    double penetration_squares; /* sum over p = 0, g < 0 of g^2 */
} gap_stats;

typedef struct pk_run {
    im_solver_plan *plan;
    const double *gap0;
    enum im_control control;
    double target;
    double *p, *u;
    int convolutions;
} pk_run;

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

static int elastic(double p, double cap) { return p > 0 && p < cap; }

/* The patches the conjugate gradients move: elastic, or capped and unloading. */
static int moving(double p, double g, double cap) { return elastic(p, cap) || (p == cap && g > 0); }

/* The projection onto 0 <= p <= cap. */
static double project(double p, double cap) { return p < 0 ? 0 : (p > cap ? cap : p); }

/* How far a patch at a bound violates its condition: -g at p = 0, g at p = cap. */
static double bound_violation(double p, double g) { return p > 0 ? g : -g; }

/* Mean of a + b over I_c = {0 < p < cap}. */
static double mean_over_contact(const double *p, const double *a, const double *b, size_t n, double cap, long *count)
{
    double sum = 0;
    long c = 0;
#pragma omp parallel for schedule(static) reduction(+ : sum, c)
    for (size_t i = 0; i < n; ++i)
        if (elastic(p[i], cap)) {
            sum += a[i] + b[i];
            ++c;
        }
    *count = c;
    return c ? sum / c : 0;
}

/* g = u + g0 - w, with w imposed or (load control) the mean of u + g0 over I_c. */
static gap_stats compute_gaps(const pk_run *r)
{
    const size_t n = (size_t)r->plan->nx * r->plan->ny;
    const double *p = r->p, *u = r->u, *g0 = r->gap0;
    double *g = r->plan->gap;
    const double cap = pressure_cap(r->plan);
    gap_stats s = {.approach = r->target};
    if (r->control == IM_CONTROL_LOAD)
        s.approach = mean_over_contact(p, u, g0, n, cap, &s.contact);
    const double w = s.approach;
    double squares = 0, moving_squares = 0, penetration = 0, penetration_squares = 0;
    long contact = 0;
#pragma omp parallel for schedule(static) reduction(+ : squares, moving_squares, contact, penetration_squares) \
    reduction(max : penetration)
    for (size_t i = 0; i < n; ++i) {
        double gi = u[i] + g0[i] - w;
        g[i] = gi;
        if (elastic(p[i], cap)) {
            squares += gi * gi;
            ++contact;
        } else {
            if (bound_violation(p[i], gi) > penetration)
                penetration = bound_violation(p[i], gi);
            if (p[i] == 0 && gi < 0) /* would join */
                penetration_squares += gi * gi;
        }
        if (moving(p[i], gi, cap))
            moving_squares += gi * gi;
    }
    s.penetration_squares = penetration_squares;
    s.contact = contact;
    s.sum_squares = squares;
    s.moving_squares = moving_squares;
    s.penetration = penetration;
    return s;
}

static double relative_residual(const gap_stats *s)
{
    double rms = s->contact ? sqrt(s->sum_squares / s->contact) : 0;
    return fmax(rms, s->penetration) / s->approach;
}

static void convolve(pk_run *r, const double *in, double *out)
{
    im_solver_convolve(r->plan, in, out);
    ++r->convolutions;
}

/* Winkler guess p = max(w - g0, 0) / K(0): the local part of the response only. */
static double winkler_load(const pk_run *r, double w, int store)
{
    const size_t n = (size_t)r->plan->nx * r->plan->ny;
    const double k0 = r->plan->kernel[0], d2 = r->plan->delta * r->plan->delta;
    double sum = 0;
#pragma omp parallel for schedule(static) reduction(+ : sum)
    for (size_t i = 0; i < n; ++i) {
        double pi = r->gap0[i] < w ? (w - r->gap0[i]) / k0 : 0;
        if (store)
            r->p[i] = pi;
        sum += pi;
    }
    return sum * d2;
}

/* Cold start: the Winkler guess at the imposed approach, or (load control) at the approach where
 * it carries the load, found by bisection (at w = K(0) N / delta^2 the first-touch patch alone does). */
static void cold_start(pk_run *r)
{
    double w = r->target;
    if (r->control == IM_CONTROL_LOAD) {
        double lo = 0, hi = r->plan->kernel[0] * r->target / (r->plan->delta * r->plan->delta);
        for (int k = 0; k < 60; ++k) {
            double mid = 0.5 * (lo + hi);
            if (winkler_load(r, mid, 0) < r->target)
                lo = mid;
            else
                hi = mid;
        }
        w = hi;
    }
    winkler_load(r, w, 1);
}

/* With a pressure cap, under load control: rescales the elastic pressures so that delta^2 sum p = N
 * with the capped ones fixed, and recomputes u (a partial rescaling is not linear in p). */
static void impose_load_capped(pk_run *r, double cap)
{
    const size_t n = (size_t)r->plan->nx * r->plan->ny;
    const double d2 = r->plan->delta * r->plan->delta;
    double elastic_load = 0, capped_load = 0;
#pragma omp parallel for schedule(static) reduction(+ : elastic_load, capped_load)
    for (size_t i = 0; i < n; ++i) {
        if (elastic(r->p[i], cap))
            elastic_load += r->p[i] * d2;
        else
            capped_load += r->p[i] * d2;
    }
    if (!(elastic_load > 0))
        return;
    const double scale = fmax(0.0, r->target - capped_load) / elastic_load;
    int clipped = 0;
#pragma omp parallel for schedule(static) reduction(| : clipped)
    for (size_t i = 0; i < n; ++i)
        if (elastic(r->p[i], cap)) {
            r->p[i] = project(r->p[i] * scale, cap);
            clipped |= r->p[i] == cap;
        }
    if (capped_load > 0 || clipped) { /* a partial rescaling: u by FFT */
        convolve(r, r->p, r->u);
        return;
    }
    /* nothing capped: all of p was scaled, and u with it by linearity */
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i)
        r->u[i] *= scale;
}

/* Under load control, rescales p (and u, by linearity) so that delta^2 sum p = N. */
static void impose_load(pk_run *r)
{
    const double cap = pressure_cap(r->plan);
    if (isfinite(cap)) {
        impose_load_capped(r, cap);
        return;
    }
    const size_t n = (size_t)r->plan->nx * r->plan->ny;
    const double load = sum_doubles(r->p, n) * r->plan->delta * r->plan->delta; /* p >= 0 */
    if (!(load > 0))
        return;
    const double scale = r->target / load;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        r->p[i] *= scale;
        r->u[i] *= scale;
    }
}

/* New search direction t = source + beta t on the moving patches (source: the gap g, or the
 * preconditioned gap), 0 elsewhere, written also into the padded rows that the convolution
 * transforms (one pass instead of two). */
static void update_direction(const pk_run *r, const double *source, double beta)
{
    const im_solver_plan *plan = r->plan;
    const int nx = plan->nx, ny = plan->ny, px = plan->px;
    double *t = plan->direction;
    const double *g = plan->gap, *p = r->p, cap = pressure_cap(plan);
#pragma omp parallel for schedule(static)
    for (int iy = 0; iy < ny; ++iy) {
        double *padded = plan->rows_in + (size_t)iy * px;
        for (int ix = 0; ix < nx; ++ix) {
            size_t i = (size_t)iy * nx + ix;
            t[i] = moving(p[i], g[i], cap) ? source[i] + beta * t[i] : 0;
            padded[ix] = t[i];
        }
    }
}

/* z = M g on I_c (0 elsewhere), M the inverse of a periodic circulant close to K (plan.c): K is
 * close to 1 / (E* |k|) in Fourier space, so M ~ E* |k| undoes most of its spread of eigenvalues,
 * which grows with the contact's size in patches and sets plain CG's rate. Centred over I_c under
 * load control (the directions keep the load). An unpadded transform pair, a quarter of a
 * convolution's size. Returns <g, z> over I_c. */
static double precondition(pk_run *r)
{
    im_solver_plan *plan = r->plan;
    const size_t n = (size_t)plan->nx * plan->ny, modes = (size_t)plan->ny * (plan->nx / 2 + 1);
    const double *g = plan->gap, *p = r->p;
    double *z = plan->preconditioned;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i)
        z[i] = p[i] > 0 ? g[i] : 0;
    fftw_execute(plan->precondition_forward);
#pragma omp parallel for schedule(static)
    for (size_t k = 0; k < modes; ++k) {
        plan->precondition_modes[k][0] *= plan->inverse_spectrum[k];
        plan->precondition_modes[k][1] *= plan->inverse_spectrum[k];
    }
    fftw_execute(plan->precondition_backward);
    double z_sum = 0;
    long count = 0;
#pragma omp parallel for schedule(static) reduction(+ : z_sum, count)
    for (size_t i = 0; i < n; ++i) {
        if (p[i] > 0) {
            z_sum += z[i];
            ++count;
        } else
            z[i] = 0;
    }
    const double mean = r->control == IM_CONTROL_LOAD && count ? z_sum / count : 0;
    double gz = 0;
#pragma omp parallel for schedule(static) reduction(+ : gz)
    for (size_t i = 0; i < n; ++i)
        if (p[i] > 0) {
            z[i] -= mean;
            gz += g[i] * z[i];
        }
    return gz;
}

/* Step length tau = <g, t> / <K t, t> over I_c, K t read in place from the convolution's rows;
 * under load control K t is centred over I_c: <K t - mean, t> = <K t, t> - mean <1, t>. */
static double step_length(const pk_run *r)
{
    const im_solver_plan *plan = r->plan;
    const int nx = plan->nx, ny = plan->ny, px = plan->px;
    const double *t = plan->direction, *g = plan->gap, *p = r->p, cap = pressure_cap(plan);
    double num = 0, qt = 0, q_sum = 0, t_sum = 0;
    long count = 0;
#pragma omp parallel for schedule(static) reduction(+ : num, qt, q_sum, t_sum, count)
    for (int iy = 0; iy < ny; ++iy) {
        const double *q = plan->rows_out + (size_t)iy * px;
        for (int ix = 0; ix < nx; ++ix) {
            size_t i = (size_t)iy * nx + ix;
            if (moving(p[i], g[i], cap)) {
                num += g[i] * t[i];
                qt += q[ix] * t[i];
                q_sum += q[ix];
                t_sum += t[i];
                ++count;
            }
        }
    }
    double den = qt;
    if (r->control == IM_CONTROL_LOAD && count > 0)
        den -= q_sum / count * t_sum;
    return num / den;
}

/* In one pass: u -= tau K t; p -= tau t on the moving patches, projected onto [0, cap]; if
 * allow_join, patches outside I_c that penetrate (p = 0, g < 0) join with p = -tau g (at most cap).
 * Records how p differs from the plain CG step p - tau t in plan->changed_value and returns the
 * number of such patches; *joined is set when any joined. */
static long update_pressure(pk_run *r, double tau, int allow_join, int *joined)
{
    const im_solver_plan *plan = r->plan;
    const int nx = plan->nx, ny = plan->ny, px = plan->px;
    const double *t = plan->direction, *g = plan->gap, cap = pressure_cap(plan);
    double *p = r->p, *u = r->u, *change = plan->changed_value;
    long changes = 0;
    int any_joined = 0;
#pragma omp parallel for schedule(static) reduction(+ : changes) reduction(| : any_joined)
    for (int iy = 0; iy < ny; ++iy) {
        const double *q = plan->rows_out + (size_t)iy * px;
        for (int ix = 0; ix < nx; ++ix) {
            size_t i = (size_t)iy * nx + ix;
            double c = 0;
            u[i] -= tau * q[ix];
            if (moving(p[i], g[i], cap)) {
                double next = p[i] - tau * t[i];
                p[i] = project(next, cap);
                c = p[i] - next;
            } else if (allow_join && p[i] == 0 && g[i] < 0) {
                p[i] = c = project(-tau * g[i], cap);
                any_joined = 1;
            }
            change[i] = c;
            changes += c != 0;
        }
    }
    *joined = any_joined;
    return changes;
}

/* Adds the recorded changes to u (already moved by -tau K t) by direct summation, or, when they
 * are many, recomputes u = K p by FFT, which is then cheaper and exact; returns 1 if u is exact. */
static int update_displacement(pk_run *r, long changes)
{
    im_solver_plan *plan = r->plan;
    const size_t n = (size_t)plan->nx * plan->ny;
    if (changes > plan->direct_limit) {
        convolve(r, r->p, r->u);
        return 1;
    }
    if (changes > 0) {
        long k = 0;
        for (size_t i = 0; i < n && k < changes; ++i)
            if (plan->changed_value[i] != 0) {
                plan->changed[k] = (long)i;
                plan->changed_value[k++] = plan->changed_value[i];
            }
        solver_add_point_loads(plan, plan->changed, plan->changed_value, changes, r->u);
    }
    return 0;
}

static int check_inputs(const im_solver_plan *plan, const double *gap0, enum im_control control,
                        double target, const double *p)
{
    if (control != IM_CONTROL_DISPLACEMENT && control != IM_CONTROL_LOAD)
        return im_fail(IM_EINVAL, "control %d: expected displacement or load", (int)control);
    if (plan->options.periodic && control != IM_CONTROL_LOAD)
        return im_fail(IM_EINVAL, "periodic plan: expected load control (a periodic half-space's approach is "
                       "defined up to a constant)");
    if (!(isfinite(target) && target >= 0))
        return im_fail(IM_EINVAL, "%s = %g: expected a finite value >= 0",
                       control == IM_CONTROL_LOAD ? "load" : "approach", target);
    const size_t n = (size_t)plan->nx * plan->ny;
    size_t bad_gap = n, bad_pressure = n; /* the first offending index of each, n if none */
#pragma omp parallel for schedule(static) reduction(min : bad_gap, bad_pressure)
    for (size_t i = 0; i < n; ++i) {
        if ((isnan(gap0[i]) || gap0[i] < 0) && i < bad_gap)
            bad_gap = i;
        if (!(isfinite(p[i]) && p[i] >= 0) && i < bad_pressure)
            bad_pressure = i;
    }
    if (bad_gap < n)
        return im_fail(IM_ENUMERIC, "undeformed gap[%zu] = %g: expected >= 0 or +inf", bad_gap, gap0[bad_gap]);
    if (bad_pressure < n)
        return im_fail(IM_EINVAL, "warm-start pressure[%zu] = %g: expected finite and >= 0", bad_pressure,
                       p[bad_pressure]);
    return IM_OK;
}

static int any_positive(const double *p, size_t n)
{
    for (size_t i = 0; i < n; ++i)
        if (p[i] > 0)
            return 1;
    return 0;
}

static void summarise(const pk_run *r, const gap_stats *s, im_solve_result *out)
{
    const size_t n = (size_t)r->plan->nx * r->plan->ny;
    const double d2 = r->plan->delta * r->plan->delta;
    double peak = 0;
    long contact = 0;
#pragma omp parallel for schedule(static) reduction(+ : contact) reduction(max : peak)
    for (size_t i = 0; i < n; ++i)
        if (r->p[i] > 0) {
            ++contact;
            if (r->p[i] > peak)
                peak = r->p[i];
        }
    const double sum = sum_doubles(r->p, n); /* p >= 0: the sum over the contact set */
    out->approach = s->approach;
    out->load = sum * d2;
    out->contact_patches = contact;
    out->mean_pressure = contact ? sum / contact : 0;
    out->max_pressure = peak;
}

/* The CG loop proper; returns IM_OK, IM_ENOCONV, IM_ENUMERIC or IM_EINTERRUPTED and leaves the last
 * gap_stats. */
static int iterate(pk_run *r, im_solve_result *res, gap_stats *last)
{
    const im_solver_options *o = &r->plan->options;
    int exact = 1, restart = 1;
    double previous_squares = 1;
    for (;;) {
        gap_stats s = compute_gaps(r);
        *last = s;
        res->residual = relative_residual(&s);
        if (!isfinite(res->residual))
            return im_fail(IM_ENUMERIC, "contact iteration %d: residual is %g", res->iterations, res->residual);
        if (res->residual <= o->tol) {
            if (exact)
                return IM_OK;
            convolve(r, r->p, r->u); /* confirm on the exact displacement */
            exact = 1;
            continue;
        }
        if (res->iterations >= o->max_iterations)
            return im_fail(IM_ENOCONV, "contact solve: residual %.3g > tol %.3g after %d iterations (cap)",
                           res->residual, o->tol, res->iterations);
        if (o->stop && *o->stop) /* the caller asked to stop: p is still a valid (warm) start */
            return im_fail(IM_EINTERRUPTED, "contact solve: interrupted by signal %d after %d iterations",
                           (int)*o->stop, res->iterations);
        if (s.contact == 0 && !any_positive(r->p, (size_t)r->plan->nx * r->plan->ny)) {
            /* everything was clipped (patches at a pressure cap are not): start again from the local guess */
            cold_start(r);
            convolve(r, r->p, r->u);
            restart = exact = 1;
            continue;
        }
        ++res->iterations;
        /* Preconditioned: patches join only in a plain PK step (steepest descent), taken when the
         * penetration outside I_c outweighs the gap left on it (Dostal's proportioning test); the
         * other steps are preconditioned CG on I_c, which may only shrink it (clipping). Plain PK
         * lets patches join in every step. (No preconditioner with a pressure cap: plan.c.) */
        const int join = !o->precondition || s.penetration_squares > s.sum_squares;
        if (o->precondition && join)
            restart = 1;
        if (join) {
            update_direction(r, r->plan->gap, restart ? 0 : s.moving_squares / previous_squares);
            previous_squares = s.moving_squares;
        } else {
            double gz = precondition(r);
            update_direction(r, r->plan->preconditioned, restart ? 0 : gz / previous_squares);
            previous_squares = gz;
        }
        solver_convolve_rows(r->plan); /* K t, left in plan->rows_out */
        ++r->convolutions;
        double tau = step_length(r);
        if (!(tau > 0) && !restart) {
            /* Clipping changed the contact set and the conjugate direction no longer descends:
             * restart from steepest descent, whose step <g, g> / <K g, g> is always positive. */
            restart = 1;
            continue;
        }
        if (isnan(tau) && restart)
            /* The direction vanishes on the contact set (under load control, one patch, or gaps
             * already equal there): only penetrating patches outside it are left to join. Give
             * them the local (Winkler) step, p = -g / K(0). */
            tau = 1.0 / r->plan->kernel[0];
        if (!isfinite(tau) || tau <= 0)
            return im_fail(IM_ENUMERIC, "contact iteration %d: step length %g", res->iterations, tau);
        long changes = update_pressure(r, tau, join, &restart);
        if (o->precondition && join)
            restart = 1; /* the next preconditioned step starts its own conjugate sequence */
        exact = update_displacement(r, changes);
        if (r->control == IM_CONTROL_LOAD)
            impose_load(r);
    }
}

int im_solver_solve(im_solver_plan *plan, const double *gap0, enum im_control control, double target,
                    double *pressure, double *displacement, im_solve_result *result)
{
    im_solve_result res = {0};
    double start = omp_get_wtime();
    int status = check_inputs(plan, gap0, control, target, pressure);
    if (status != IM_OK)
        return status;
    const size_t n = (size_t)plan->nx * plan->ny;
    pk_run r = {.plan = plan, .gap0 = gap0, .control = control, .target = target, .p = pressure, .u = displacement};
    gap_stats last = {0};
    if (target == 0) { /* no approach or no load: no contact */
        memset(pressure, 0, sizeof(double) * n);
        memset(displacement, 0, sizeof(double) * n);
    } else {
        if (!any_positive(pressure, n) && plan->coarse)
            res.coarse_iterations = solver_cascade_start(plan, gap0, control, target, pressure);
        if (!any_positive(pressure, n))
            cold_start(&r);
        const double cap = pressure_cap(plan); /* a start above the cap (Winkler's, or a warm one) */
        for (size_t i = 0; i < n && isfinite(cap); ++i)
            pressure[i] = project(pressure[i], cap);
        convolve(&r, pressure, displacement);
        if (control == IM_CONTROL_LOAD)
            impose_load(&r);
        status = iterate(&r, &res, &last);
    }
    summarise(&r, &last, &res);
    res.convolutions = r.convolutions;
    res.seconds = omp_get_wtime() - start;
    if (result)
        *result = res;
    return status;
}
