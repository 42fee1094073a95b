/* Maugis-Dugdale adhesion in an indentation (solver.h, "Adhesion").
 *
 * The net pressure is p = p_r - sigma0 s: a repulsive part p_r >= 0 with p_r g = 0, and the adhesive
 * stress sigma0 on the share s in [0, 1] of each patch that lies on the zone Z = {g <= delta_c} (1 in
 * contact). Given the shares the problem is the repulsive one with the undeformed gap g0 - sigma0 K s
 * (the zone's stress lifts the surface), solved by the plan's Polonsky-Keer; the shares are then
 * taken from the new gaps, and so on to a fixed point.
 *
 * The shares. The zone's edge runs through patches; with all-or-nothing patches the discrete problem
 * has many fixed points (the edge pinned at patch boundaries: "lattice trapping"), so approach and
 * retraction stopped at different edges and a sphere's pull-off came out 9% too strong at 8 patches
 * per reduced radius, 5% at 16. The share of a patch is the part of it whose gap is at most delta_c,
 * the gap taken linear across the patch (its central differences): 0.6% and 0.07% (lambda = 1).
 *
 * The passes are monotone as a rule. Adding stress to the zone lowers every gap of the constrained
 * half-space (a comparison principle of the obstacle problem), so from a state below the solution the zone
 * only grows, and from one above it only shrinks (exactly so for all-or-nothing patches). An approach step
 * (w at least the last step's) starts from the last shares and raises them; a retraction step lowers them
 * (a patch in repulsive contact is whole in the zone either way). The passes end when no share would move
 * by more than tol / 100, on the state the history leads to: the least zone on approach, the largest on
 * retraction. That is the hysteresis of adhesive contact (jump-in late on approach, pull-off late on
 * retraction) without a rule of its own.
 *
 * Against the step's direction. The shares also follow the gap's local slope, which an early pass of a long
 * step can steepen and a later one flatten: held to one direction, a share so raised stayed although the
 * final gaps called for less, and a state reached in one step was no equilibrium (a rough cell's load 2.5%
 * below the one reached in 80 steps, whose shares were off by less). So a share also moves against the
 * step's direction, to the law's share of the new gaps, where that is off by more than a band of SHARE_BAND
 * tol: the passes end on an equilibrium of the discrete problem to within the band, whatever the steps that
 * led to it. Within the band a share keeps to the step's direction, as the solves' own error moves the
 * shares both ways (about 10 tol: 1e-7 at tol 1e-8 on a rough cone), and unheld those passes never settled.
 *
 * The exponential law. The tension sigma(g) = (w / rho) exp(-g / rho) depends on the gap everywhere: a
 * patch's share is the mean of sigma / sigma0 over it (sigma0 = w / rho, the gap linear across it as above,
 * sigma0 where that gap is below 0), and the passes are the same fixed point on the shares. Its map is
 * monotone too (more tension, lower gaps, more tension), and its Jacobian D K' (D = diag(sigma / rho),
 * K' the compliance of the patches out of contact) has real eigenvalues >= 0, below 1 exactly where the
 * state is stable (the energy's Hessian K'^-1 - D positive definite): so the plain pass, undamped,
 * converges wherever the state is stable, at the rate of the largest eigenvalue, which tends to 1 at the
 * jumps. A damped pass would only be slower (the eigenvalues are not negative); an over-relaxed one would
 * lose the monotone passes that choose the branch. */
#include "solver/adhesion.h"
#include "solver/plan.h"

#include "core/args.h"
#include "core/summation.h"
#include "indentmap/status.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

/* A share moves against the step's direction only where the law's share is off by more than this many tol
 * (the passes' noise, from solves to tol, is about 10 tol). From tol 1e-3 the band is a whole share: the
 * passes are then one-way (docs/solver.md says so), rather than held by a band near the noise. */
static const double SHARE_BAND = 1000;

/* A zone still changing after this many passes is reported (a retraction through pull-off on a
 * 196^2 window took 300). */
enum { ADHESION_PASSES_MAX = 20000 };

/* The exponential law's tension is cut to 0 beyond this many ranges rho: exp(-35) < 1e-15 of its peak. */
static const double EXPONENTIAL_CUT = 35;

double adhesion_reach(const im_solver_options *options)
{
    const double range = options->adhesion_range;
    return options->adhesion_law == IM_ADHESION_EXPONENTIAL ? EXPONENTIAL_CUT * range : range;
}

int adhesion_create(int nx, int ny, int periodic, const im_solver_options *options, adhesion_state **out)
{
    const size_t n = (size_t)nx * ny;
    adhesion_state *a = calloc(1, sizeof *a);
    *out = NULL;
    if (a) {
        a->share = calloc(n, sizeof(double));
        a->gap_rows = malloc((n + 2 * (size_t)nx) * sizeof(double));
        a->proposal = malloc(n * sizeof(double));
        a->lift = calloc(n, sizeof(double));
        a->gap0 = malloc(n * sizeof(double));
    }
    if (!a || !a->share || !a->gap_rows || !a->proposal || !a->lift || !a->gap0) {
        adhesion_free(a);
        return im_fail(IM_ENOMEM, "adhesion on a %d x %d window", nx, ny);
    }
    a->law = options->adhesion_law;
    a->stress = options->adhesion_work / options->adhesion_range;
    a->range = options->adhesion_range;
    a->nx = nx;
    a->ny = ny;
    a->periodic = periodic;
    a->gaps = a->gap_rows + nx;
    *out = a;
    return IM_OK;
}

struct adhesion_mark {
    double *share, *lift;
    double approach, zone_area;
    long zone_patches;
    int stepped;
};

static void free_mark(struct adhesion_mark *m)
{
    if (m) {
        free(m->share);
        free(m->lift);
        free(m);
    }
}

void adhesion_free(adhesion_state *a)
{
    if (!a)
        return;
    free_mark(a->marks[ADHESION_MARK_TRY]);
    free_mark(a->marks[ADHESION_MARK_STEP]);
    free(a->share);
    free(a->gap_rows);
    free(a->proposal);
    free(a->lift);
    free(a->gap0);
    free(a);
}

void adhesion_over_ranks(adhesion_state *a, const adhesion_ranks *ranks) { a->ranks = ranks; }

/* values[0..count) combined over the ranks (one process: as they are). */
static void combine(const adhesion_state *a, double *values, int count, enum adhesion_combine how)
{
    if (a->ranks)
        a->ranks->combine(a->ranks->context, values, count, how);
}

/* The sum of a field over the grid, in a fixed order. */
static double grid_sum(const adhesion_state *a, const double *field)
{
    return a->ranks ? a->ranks->sum(a->ranks->context, field) : sum_doubles(field, (size_t)a->nx * a->ny);
}

/* The repulsive solve's gap: g0 - sigma0 lift, shifted so that its least finite value is 0 (the
 * solver's convention: first touch at approach 0). */
static void lifted_gap(adhesion_state *a, const double *gap0)
{
    const size_t n = (size_t)a->nx * a->ny;
    double lowest = INFINITY;
#pragma omp parallel for schedule(static) reduction(min : lowest)
    for (size_t i = 0; i < n; ++i) {
        a->gap0[i] = gap0[i] - a->stress * a->lift[i];
        lowest = fmin(lowest, a->gap0[i]);
    }
    combine(a, &lowest, 1, ADHESION_MIN);
    a->shift = isfinite(lowest) ? -lowest : 0;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i)
        a->gap0[i] += a->shift;
}

/* The gaps' rows just outside the grid's (or, over ranks, this rank's): a periodic cell's wrap around, the
 * window's are off it (NaN). */
static void fill_outer_rows(adhesion_state *a)
{
    double *above = a->gaps - a->nx, *below = a->gaps + (size_t)a->ny * a->nx;
    if (a->ranks) {
        a->ranks->outer_rows(a->ranks->context, a->gaps, above, below);
        return;
    }
    for (int x = 0; x < a->nx; ++x) {
        above[x] = a->periodic ? a->gaps[(size_t)(a->ny - 1) * a->nx + x] : NAN;
        below[x] = a->periodic ? a->gaps[x] : NAN;
    }
}

/* The gap at patch (x, y), y from -1 to ny (the outer rows), or NaN off the window (a periodic cell's
 * neighbours wrap around) or where the punch cannot reach. */
static double gap_at(const adhesion_state *a, const double *gaps, int x, int y)
{
    if (a->periodic)
        x = (x + a->nx) % a->nx;
    if (x < 0 || x >= a->nx)
        return NAN;
    double g = gaps[(ptrdiff_t)y * a->nx + x];
    return isfinite(g) ? g : NAN;
}

/* The gap's change across patch (x, y) along one axis (half the difference of its neighbours: the change
 * over one patch side), or one-sided at a missing side. */
static double patch_change(const adhesion_state *a, const double *gaps, int x, int y, int dx, int dy)
{
    double before = gap_at(a, gaps, x - dx, y - dy), after = gap_at(a, gaps, x + dx, y + dy);
    double here = gaps[(size_t)y * a->nx + x];
    if (!isnan(before) && !isnan(after))
        return 0.5 * (after - before);
    if (!isnan(after))
        return after - here;
    return isnan(before) ? 0 : here - before;
}

/* The share of a patch whose gap is at most delta_c, the gap running linearly from g - change / 2 to
 * g + change / 2 across it: the zone's edge cuts patches, and a share rather than all or nothing keeps the
 * discrete problem from holding the edge at a patch boundary (lattice trapping: approach and retraction
 * would stop at different edges, and the pull-off would be overestimated by the edge's pinning). */
static double dugdale_share(double range, double g, double change)
{
    if (!(change > 0))
        return g <= range;
    return fmin(1, fmax(0, 0.5 + (range - g) / change));
}

/* The mean over such a patch of exp(-max(gap, 0) / rho): the exponential law's tension in units of its
 * peak, 0 where the whole patch lies beyond the cut. */
static double exponential_share(double rho, double g, double change)
{
    const double lowest = g - 0.5 * change, highest = g + 0.5 * change;
    if (lowest >= EXPONENTIAL_CUT * rho)
        return 0;
    if (highest <= 0)
        return 1;
    if (lowest < 0) /* the part below 0 pulls at the peak */
        return (-lowest - rho * expm1(-highest / rho)) / change;
    const double half = 0.5 * change / rho; /* the mean is exp(-g / rho) sinh(half) / half */
    if (half < 1)
        return half > 0 ? exp(-g / rho) * sinh(half) / half : exp(-g / rho);
    return rho * (exp(-lowest / rho) - exp(-highest / rho)) / change;
}

/* The share of patch (x, y) the law calls for, the gap taken linear across the patch. */
static double zone_share(const adhesion_state *a, const double *gaps, int x, int y)
{
    const double g = gaps[(size_t)y * a->nx + x];
    if (!isfinite(g))
        return 0;
    const double change = hypot(patch_change(a, gaps, x, y, 1, 0), patch_change(a, gaps, x, y, 0, 1));
    return a->law == IM_ADHESION_EXPONENTIAL ? exponential_share(a->range, g, change)
                                             : dugdale_share(a->range, g, change);
}

/* The share a pass takes: the law's (target) where it lies in the step's direction (grow: above the old share),
 * or beyond the band against it; else the old one. */
static double next_share(double old, double target, int grow, double band)
{
    const double along = grow ? target - old : old - target;
    return along > 0 || -along > band ? target : old;
}

/* The shares the gaps of the repulsive solution at approach w_lifted call for, into a->proposal (next_share; 1 in
 * repulsive contact). Returns the largest change. */
static double propose_shares(adhesion_state *a, double w_lifted, const double *pressure, const double *displacement,
                             int grow, double band)
{
    const size_t n = (size_t)a->nx * a->ny;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i)
        a->gaps[i] = a->gap0[i] - w_lifted + displacement[i];
    fill_outer_rows(a);
    double largest = 0;
#pragma omp parallel for schedule(static) reduction(max : largest)
    for (int y = 0; y < a->ny; ++y)
        for (int x = 0; x < a->nx; ++x) {
            const size_t i = (size_t)y * a->nx + x;
            const double old = a->share[i];
            const double share = pressure[i] > 0 ? 1 : next_share(old, zone_share(a, a->gaps, x, y), grow, band);
            largest = fmax(largest, fabs(share - old));
            a->proposal[i] = share;
        }
    combine(a, &largest, 1, ADHESION_MAX);
    return largest;
}

/* Takes the proposed shares, and counts the zone's patches and area (summed as the solver sums loads:
 * the same bits for any thread count). */
static void apply_shares(adhesion_state *a)
{
    const size_t n = (size_t)a->nx * a->ny;
    long count = 0;
#pragma omp parallel for schedule(static) reduction(+ : count)
    for (size_t i = 0; i < n; ++i) {
        a->share[i] = a->proposal[i];
        count += a->share[i] > 0;
    }
    double patches = (double)count;
    combine(a, &patches, 1, ADHESION_SUM);
    a->zone_patches = (long)patches;
    a->zone_area = grid_sum(a, a->share);
}

/* The repulsive solve at approach w > 0 on the plan, or over the ranks. */
static int repulsive_solve(const adhesion_state *a, im_solver_plan *plan, double w, double *pressure,
                           double *displacement, im_solve_result *result)
{
    if (a->ranks)
        return a->ranks->solve(a->ranks->context, a->gap0, IM_CONTROL_DISPLACEMENT, w, pressure, displacement,
                               result);
    return im_solver_solve(plan, a->gap0, IM_CONTROL_DISPLACEMENT, w, pressure, displacement, result);
}

/* out = K in on the plan, or over the ranks. */
static void convolve(const adhesion_state *a, im_solver_plan *plan, const double *in, double *out)
{
    if (a->ranks)
        a->ranks->convolve(a->ranks->context, in, out);
    else
        im_solver_convolve(plan, in, out);
}

/* Adds a pass's counts to the step's. */
static void add_counts(im_solve_result *total, const im_solve_result *pass)
{
    total->iterations += pass->iterations;
    total->convolutions += pass->convolutions;
    total->coarse_iterations += pass->coarse_iterations;
    total->seconds += pass->seconds;
}

/* The step's result: the last pass's solution with the net load. */
static void net_result(const adhesion_state *a, const im_solver_plan *plan, double w, const im_solve_result *last,
                       im_solve_result *out)
{
    const double d2 = plan->delta * plan->delta;
    out->approach = w;
    out->load = last->load - a->stress * d2 * a->zone_area;
    out->contact_patches = last->contact_patches;
    out->mean_pressure = last->contact_patches ? out->load / (last->contact_patches * d2) : 0;
    /* the patches outside the zone carry 0 (the window always has some: its margin) */
    out->max_pressure = last->contact_patches ? fmax(last->max_pressure - a->stress, 0) : 0;
    out->residual = last->residual;
}

int adhesion_solve(adhesion_state *a, im_solver_plan *plan, const double *gap0, double w, double *pressure,
                   double *displacement, im_solve_result *result)
{
    const int grow = !a->stepped || w >= a->approach;
    const size_t n = (size_t)a->nx * a->ny;
    im_solve_result total = {0}, pass = {0};
    int status = IM_OK;
    /* The shares settle to a hundredth of the gaps' tolerance: the passes converge linearly, slowly near the
     * jumps, where stopping at tol would leave about tol / (1 - rate) (tol 1e-6 -> 1e-8: 6% more iterations). */
    const double settle = 0.01 * plan->options.tol, band = SHARE_BAND * plan->options.tol;
    for (int passes = 1;; ++passes) {
        lifted_gap(a, gap0);
        const double w_lifted = w + a->shift;
        if (w_lifted > 0) {
            status = repulsive_solve(a, plan, w_lifted, pressure, displacement, &pass);
        } else { /* the lifted surface does not reach the punch: no repulsive contact */
            memset(pressure, 0, n * sizeof(double));
            memset(displacement, 0, n * sizeof(double));
            pass = (im_solve_result){.approach = w_lifted};
        }
        add_counts(&total, &pass);
        /* a change below settle is not taken: the shares stay those the lift and the solve were made with */
        if (status != IM_OK || propose_shares(a, w_lifted, pressure, displacement, grow, band) <= settle)
            break;
        apply_shares(a);
        if (passes >= ADHESION_PASSES_MAX) {
            status = im_fail(IM_ENOCONV, "adhesive zone at approach %g: still changing after %d passes (%ld patches)",
                             w, passes, a->zone_patches);
            break;
        }
        convolve(a, plan, a->share, a->lift);
        ++total.convolutions;
    }
    if (status == IM_OK) { /* a failed step does not become the history the next one grows or shrinks from */
        a->approach = w;
        a->stepped = 1;
    }
    net_result(a, plan, w, &pass, &total);
    *result = total;
    return status;
}

void adhesion_split(adhesion_state *a, const double *pressure, double delta, double *tensile, long *adhesive_patches,
                    long *repulsive_patches)
{
    const size_t n = (size_t)a->nx * a->ny;
    long adhesive = 0, repulsive = 0;
    double *pull = a->proposal; /* free between steps: the tension of each patch, summed as loads are */
#pragma omp parallel for schedule(static) reduction(+ : adhesive, repulsive)
    for (size_t i = 0; i < n; ++i) {
        const double p = adhesion_net_pressure(a, i, pressure[i]);
        pull[i] = p < 0 ? -p : 0;
        adhesive += p < 0;
        repulsive += p > 0;
    }
    double counts[2] = {(double)adhesive, (double)repulsive};
    combine(a, counts, 2, ADHESION_SUM);
    *tensile = grid_sum(a, pull) * delta * delta;
    *adhesive_patches = (long)counts[0];
    *repulsive_patches = (long)counts[1];
}

int adhesion_zone_on_border(const adhesion_state *a, int *x, int *y)
{
    if (a->periodic)
        return 0;
    for (int iy = 0; iy < a->ny; ++iy)
        for (int ix = 0; ix < a->nx; ix += (iy == 0 || iy == a->ny - 1) ? 1 : a->nx - 1) {
            if (a->share[(size_t)iy * a->nx + ix] > 0) {
                *x = ix;
                *y = iy;
                return 1;
            }
            if (a->nx == 1)
                break;
        }
    return 0;
}

int im_adhesion_law_parse(const char *word, int *law)
{
    ARG_REQUIRE(word, "word");
    ARG_REQUIRE(law, "law");
    static const char *const words[] =
        {[IM_ADHESION_MAUGIS_DUGDALE] = "maugis-dugdale", [IM_ADHESION_EXPONENTIAL] = "exponential"};
    for (int k = 0; k < 2; ++k)
        if (strcmp(word, words[k]) == 0) {
            *law = k;
            return IM_OK;
        }
    return im_fail(IM_EINVAL, "adhesion law '%s': expected maugis-dugdale or exponential", word);
}

const char *im_adhesion_law_name(int law)
{
    return law == IM_ADHESION_MAUGIS_DUGDALE ? "Maugis-Dugdale"
           : law == IM_ADHESION_EXPONENTIAL  ? "exponential"
                                             : NULL;
}

/* Whether the options hold a valid adhesion (no message left: the getters' misuse is a NaN). */
static int has_adhesion(const im_solver_options *o)
{
    return o && o->adhesion_work > 0 && o->adhesion_range > 0 && isfinite(o->adhesion_work) &&
           isfinite(o->adhesion_range) && isfinite(o->e_star) && o->e_star > 0 &&
           im_adhesion_law_name(o->adhesion_law);
}

double im_adhesion_zone_length(const im_solver_options *options)
{
    ARG_REQUIRE_OR(options, "options", NAN);
    if (!has_adhesion(options))
        return NAN;
    return M_PI * options->e_star * options->adhesion_range * options->adhesion_range / (8 * options->adhesion_work);
}

int im_adhesion_solved_law(const im_solver_options *options, double delta, im_solver_options *solved, int *widened)
{
    ARG_REQUIRE(options, "options");
    ARG_REQUIRE(solved, "solved");
    int status = im_solver_options_check(options);
    if (status != IM_OK)
        return status;
    if (!(isfinite(delta) && delta > 0))
        return im_fail(IM_EINVAL, "adhesion zone: patch side delta = %g: expected a finite length > 0", delta);
    const double span = options->adhesion_zone * delta; /* 0 without a zone to widen */
    const int widen = span > 0 && im_adhesion_zone_length(options) < span;
    *solved = *options;
    solved->adhesion_zone = 0;
    if (widen) /* l = pi E* delta_c^2 / (8 w) = span at the same w */
        solved->adhesion_range = sqrt(8 * options->adhesion_work * span / (M_PI * options->e_star));
    if (widened)
        *widened = widen;
    return IM_OK;
}

double im_adhesion_maugis_lambda(const im_solver_options *options, double radius)
{
    ARG_REQUIRE_OR(options, "options", NAN);
    if (!has_adhesion(options) || !(isfinite(radius) && radius > 0))
        return NAN;
    const double k = 4.0 / 3.0 * options->e_star, w = options->adhesion_work;
    return 2 * (w / options->adhesion_range) * cbrt(radius / (M_PI * w * k * k));
}

int adhesion_reserve_mark(adhesion_state *a, enum adhesion_mark_slot slot)
{
    if (a->marks[slot])
        return IM_OK;
    const size_t n = (size_t)a->nx * a->ny + 1; /* + 1: a rank may hold no rows */
    struct adhesion_mark *m = calloc(1, sizeof *m);
    if (m && (!(m->share = malloc(n * sizeof(double))) || !(m->lift = malloc(n * sizeof(double))))) {
        free_mark(m);
        m = NULL;
    }
    if (!m)
        return im_fail(IM_ENOMEM, "adhesion: the state of a %d x %d window for a load search", a->nx, a->ny);
    a->marks[slot] = m;
    return IM_OK;
}

int adhesion_set_mark(adhesion_state *a, enum adhesion_mark_slot slot)
{
    const size_t n = (size_t)a->nx * a->ny;
    int status = adhesion_reserve_mark(a, slot);
    if (status != IM_OK)
        return status;
    struct adhesion_mark *m = a->marks[slot];
    memcpy(m->share, a->share, n * sizeof(double));
    memcpy(m->lift, a->lift, n * sizeof(double));
    m->approach = a->approach;
    m->zone_area = a->zone_area;
    m->zone_patches = a->zone_patches;
    m->stepped = a->stepped;
    return IM_OK;
}

void adhesion_rewind(adhesion_state *a, enum adhesion_mark_slot slot)
{
    const size_t n = (size_t)a->nx * a->ny;
    const struct adhesion_mark *m = a->marks[slot];
    memcpy(a->share, m->share, n * sizeof(double));
    memcpy(a->lift, m->lift, n * sizeof(double));
    a->approach = m->approach;
    a->zone_area = m->zone_area;
    a->zone_patches = m->zone_patches;
    a->stepped = m->stepped;
}

double im_adhesion_tabor_mu(const im_solver_options *options, double radius)
{
    ARG_REQUIRE_OR(options, "options", NAN);
    const double lambda = im_adhesion_maugis_lambda(options, radius);
    if (isnan(lambda) || options->adhesion_law == IM_ADHESION_MAUGIS_DUGDALE)
        return lambda / 1.157;
    const double e = options->e_star, rho = options->adhesion_range;
    return cbrt(radius * options->adhesion_work * options->adhesion_work / (e * e * rho * rho * rho));
}
