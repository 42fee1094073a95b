/* The indentation analysis of a history's unloading branches (measure.h: Oliver-Pharr with the
 * punch's own area function, the residual approach and the works of each branch). */
#include "indentmap/measure.h"
#include "core/args.h"

#include "indentmap/status.h"

#include <math.h>
#include <stdio.h>

double im_measure_epsilon(const im_indenter *punch)
{
    ARG_REQUIRE_OR(punch, "punch", NAN);
    switch (punch->kind) {
    case IM_PUNCH_CONE: return 0.72;
    case IM_PUNCH_FLAT: return 1.0;
    case IM_PUNCH_SPHERE:
    case IM_PUNCH_PROFILE: return 0.75;
    default: return NAN;
    }
}

/* The largest r with z(r) <= depth, by bisection on the monotone profile (60 halvings: to the last
 * bits of r); the flat punch and a profile end at their rim (z is +infinity beyond it). */
static double radius_at_depth(const im_indenter *punch, double depth)
{
    double lo = 0, hi = 1;
    for (int k = 0; k < 200 && im_indenter_profile(punch, hi) <= depth; ++k)
        lo = hi, hi *= 2;
    for (int k = 0; k < 60; ++k) {
        double mid = 0.5 * (lo + hi);
        if (im_indenter_profile(punch, mid) <= depth)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

double im_measure_projected_area(const im_indenter *punch, double contact_depth)
{
    ARG_REQUIRE_OR(punch, "punch", NAN);
    if (punch->kind == IM_PUNCH_PROFILE_2D || !(contact_depth >= 0) || im_indenter_check(punch) != IM_OK)
        return NAN;
    double r = radius_at_depth(punch, contact_depth);
    return M_PI * r * r;
}

/* The trapezoid integral of P dh over steps [first, last] (0-based), from the origin when from_origin. */
static double work_over(const double *h, const double *p, int first, int last, int from_origin)
{
    double work = from_origin ? 0.5 * p[first] * h[first] : 0;
    for (int k = first + 1; k <= last; ++k)
        work += 0.5 * (p[k] + p[k - 1]) * (h[k] - h[k - 1]);
    return work;
}

/* Step k unloaded short of the touch, its residual approach (when given): N is 0 there, not on the curve
 * whose slope is sought. At the touch itself N is on it (an elastic cone's apex at h = 0). */
static int withdrawn(const double *h, const double *p, const double *residual, int k)
{
    return residual && p[k] == 0 && h[k] < residual[k];
}

/* S at the top from the first three points of the branch; NaN with fewer, or when the branch is
 * withdrawn by its third point: a parabola across the touch is no slope of the unloading curve (Oliver
 * and Pharr fit its upper part). A rough cone unloaded from 16 to 12 and 8 nm, withdrawn at 9.15, gave
 * S = 167 against 141 from steps of 0.5 nm. */
static double top_stiffness(const double *h, const double *p, const double *residual, int top, int last,
                            int *withdrawn_step)
{
    double s[3];
    *withdrawn_step = 0;
    if (last - top < 2)
        return NAN;
    for (int k = top + 1; k <= top + 2; ++k)
        if (withdrawn(h, p, residual, k)) {
            *withdrawn_step = k + 1;
            return NAN;
        }
    return im_measure_stiffness(h + top, p + top, 3, s) == IM_OK ? s[0] : NAN;
}

static im_unloading_branch analyse_branch(const im_indenter *punch, const double *h, const double *p,
                                          const double *residual, int from, int top, int last)
{
    im_unloading_branch b = {.top_step = top + 1,
                             .last_step = last + 1,
                             .loading_from = from < 0 ? 0 : from + 1,
                             .approach_max = h[top],
                             .load_max = p[top],
                             .epsilon = im_measure_epsilon(punch)};
    b.stiffness = top_stiffness(h, p, residual, top, last, &b.withdrawn_step);
    b.contact_depth = h[top] - b.epsilon * p[top] / b.stiffness;
    if (b.contact_depth < 0 && b.contact_depth > -1e-9 * h[top]) /* 0 but for rounding (a flat punch: h = P / S) */
        b.contact_depth = 0;
    b.area_projected = im_measure_projected_area(punch, b.contact_depth);
    b.hardness = b.area_projected > 0 ? p[top] / b.area_projected : NAN;
    b.modulus = im_measure_sneddon_modulus(b.stiffness, b.area_projected);
    b.residual_approach = residual && p[last] == 0 ? residual[last] : NAN;
    b.work_in = work_over(h, p, from < 0 ? 0 : from, top, from < 0);
    b.work_out = -work_over(h, p, top, last, 0);
    return b;
}

/* Approaches within APPROACH_TIE of each other (relative) are one: a repeated target, or the approach
 * load control finds twice for one load (its solves are exact to the tolerance, 1e-6 by default). */
#define APPROACH_TIE 1e-6

static int below(double a, double b) { return a < b - APPROACH_TIE * fabs(b); }

static int check_unloading_arguments(const im_indenter *punch, const double *approach, const double *load, int count)
{
    if (count < 1)
        return im_fail(IM_EINVAL, "unloading analysis: count %d: expected at least 1 step", count);
    for (int k = 0; k < count; ++k)
        if (!(isfinite(approach[k]) && isfinite(load[k])))
            return im_fail(IM_EINVAL, "unloading analysis: step %d: approach %g, load %g: expected finite values",
                           k + 1, approach[k], load[k]);
    return im_indenter_check(punch);
}

int im_measure_unloading_note(const im_unloading_branch *branch, char *text, size_t size)
{
    ARG_REQUIRE(branch, "branch");
    ARG_REQUIRE(text, "text");
    if (size == 0)
        return im_fail(IM_EINVAL, "im_measure_unloading_note: size 0: expected room for the text");
    text[0] = '\0';
    if (branch->withdrawn_step > 0)
        snprintf(text, size,
                 "the unloading from step %d: S, and h_c, A_p, H_IT and E_r after it, are NaN: the stiffness fit's "
                 "%s point (step %d) is past the touch (no load, the punch withdrawn short of the residual "
                 "approach): unload in smaller steps that keep at least three points in contact",
                 branch->top_step, branch->withdrawn_step - branch->top_step == 1 ? "second" : "third",
                 branch->withdrawn_step);
    return IM_OK;
}

int im_measure_unloading(const im_indenter *punch, const double *approach, const double *load, const double *residual,
                         int count, im_unloading_branch *branches, int capacity, int *found)
{
    ARG_REQUIRE(punch, "punch");
    ARG_REQUIRE(approach, "approach");
    ARG_REQUIRE(load, "load");
    ARG_REQUIRE(found, "found");
    ARG_REQUIRE(branches || capacity == 0, "branches");
    *found = 0;
    int status = check_unloading_arguments(punch, approach, load, count);
    if (status != IM_OK)
        return status;
    for (int k = 0; k + 1 < count; ++k) {
        if (!below(approach[k + 1], approach[k]))
            continue;
        int plateau = k; /* a top held over several steps (a repeated target, or load control's noise) */
        while (plateau > 0 && !below(approach[plateau - 1], approach[k]) &&
               !below(approach[k], approach[plateau - 1]))
            --plateau;
        if (!(plateau == 0 ? approach[0] > 0 : below(approach[plateau - 1], approach[k])))
            continue;       /* reached by unloading: no top */
        int from = plateau; /* back along the loading to where it started: step `from`, or -1 for the origin */
        while (from > 0 && below(approach[from - 1], approach[from]))
            --from;
        if (from == 0 && approach[0] > 0)
            from = -1;
        int last = k + 1;
        while (last + 1 < count && below(approach[last + 1], approach[last]))
            ++last;
        if (*found < capacity)
            branches[*found] = analyse_branch(punch, approach, load, residual, from, k, last);
        ++*found;
    }
    return IM_OK;
}
