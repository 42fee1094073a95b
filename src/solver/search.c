/* The search of an approach whose solution meets a target (search.h). */
#include "solver/search.h"

#include "indentmap/status.h"

#include <math.h>

int search_trial(approach_search *search, double w, double *excess)
{
    im_solve_result s;
    int status = search->solve(search->context, w, &s);
    s.iterations += search->last.iterations;
    s.convolutions += search->last.convolutions;
    s.coarse_iterations += search->last.coarse_iterations;
    s.seconds += search->last.seconds;
    search->last = s;
    ++search->trials;
    *excess = search->measure(search->context, &s) - search->target;
    return status;
}

int search_refine(approach_search *search, double lo, double e_lo, double hi, double e_hi, double e, double scale)
{
    const double tol = search->tol;
    int status = IM_OK, side = 0;
    while (fabs(e) > tol * scale && hi - lo > tol * fmax(fabs(hi), search->length)) {
        if (search->trials >= SEARCH_MAX)
            return im_fail(IM_ENOCONV,
                           "target %g: no approach in [%.17g, %.17g] reaches it to tol %g after %d "
                           "solves",
                           search->target, lo, hi, tol, search->trials);
        double w = (lo * e_hi - hi * e_lo) / (e_hi - e_lo);
        status = search_trial(search, w, &e);
        if (status != IM_OK)
            return status;
        if (e < 0) { /* Illinois: the end kept twice running has its value halved */
            lo = w, e_lo = e;
            e_hi *= side == -1 ? 0.5 : 1;
            side = -1;
        } else {
            hi = w, e_hi = e;
            e_lo *= side == 1 ? 0.5 : 1;
            side = 1;
        }
    }
    return status;
}

/* With mean u = 0 the approach mean g0 - target gives the mean gap target exactly (one solve) unless patches
 * yield; with a hardness their overlap opens no gap, so the approach is searched from there upwards (the mean
 * gap falls as w grows, to 0 once every patch has yielded). Without adhesion a target above mean g0 leaves the
 * flat clear of the surface: no contact, at a negative approach. */
int search_mean_gap(approach_search *search, double w, double hardness, im_solve_result *out)
{
    const double target = -search->target;
    double e_lo, e_hi;
    int status = search_trial(search, fmax(w, search->lowest), &e_lo);
    search->last.approach = w;
    if (status != IM_OK || !(hardness > 0) || !(w > search->lowest) || fabs(e_lo) <= search->tol * target) {
        *out = search->last;
        return status;
    }
    double lo = w, hi = w, step = target;
    do { /* e_lo <= 0: yielding left the gap above the target; move on until it is below */
        hi = lo + step;
        step *= 2;
        status = search_trial(search, hi, &e_hi);
        if (status == IM_OK && e_hi < 0)
            lo = hi, e_lo = e_hi;
    } while (status == IM_OK && e_hi < 0 && search->trials < SEARCH_MAX);
    if (status == IM_OK && e_hi < 0)
        status = im_fail(IM_ENOCONV, "mean gap %g: not reached up to the approach %g after %d solves", target, hi,
                         search->trials);
    if (status == IM_OK)
        status = search_refine(search, lo, e_lo, hi, e_hi, e_hi, target);
    *out = search->last;
    return status;
}
