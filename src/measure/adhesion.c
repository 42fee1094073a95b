/* The pull-off, the jumps and the lost work of an adhesive force-distance history (measure.h). */
#include "indentmap/measure.h"
#include "core/args.h"

#include "indentmap/status.h"

#include <math.h>

/* |N''| at step i from the second difference of steps i - 1, i, i + 1, or NaN where they are not on one
 * branch (the approach turns at i) or i is the first or last step. */
static double curvature_at(const double *approach, const double *load, int count, int i)
{
    if (i < 1 || i > count - 2)
        return NAN;
    const double before = approach[i] - approach[i - 1], after = approach[i + 1] - approach[i];
    if (!(before * after > 0))
        return NAN;
    const double slopes = (load[i + 1] - load[i]) / after - (load[i] - load[i - 1]) / before;
    return fabs(2 * slopes / (before + after));
}

/* The trapezoid's error estimate over the step from k - 1 to k (measure.h, hysteresis_error). */
static double trapezoid_error(const double *approach, const double *load, int count, int k)
{
    const double h = fabs(approach[k] - approach[k - 1]), monotone = 0.5 * h * fabs(load[k] - load[k - 1]);
    const double curvature = fmax(curvature_at(approach, load, count, k - 1), curvature_at(approach, load, count, k));
    return isnan(curvature) ? monotone : fmin(monotone, h * h * h * curvature / 12);
}

/* Whether the least load, at step least, is a pull-off the steps passed (measure.h, pull_off_force): the
 * approaches or mean gaps given, a later step's load above it (the contact let go past it). */
static int passed_pull_off(const double *load, int count, int least, int loads_given)
{
    if (loads_given)
        return 0;
    for (int k = least + 1; k < count; ++k)
        if (load[k] > load[least])
            return 1;
    return 0;
}

/* Whether sum N dw is a loss (measure.h, hysteresis_work): the last step back at the first approach, or from no
 * force to no force. */
static int closes_a_loop(const double *approach, const double *load, int count)
{
    return approach[count - 1] == approach[0] || (load[0] == 0 && load[count - 1] == 0);
}

int im_measure_adhesion(const double *approach, const double *load, const long *contact, int count, int loads_given,
                        im_adhesion_summary *out)
{
    ARG_REQUIRE(approach, "approach");
    ARG_REQUIRE(load, "load");
    ARG_REQUIRE(contact, "contact");
    ARG_REQUIRE(out, "out");
    if (count < 1)
        return im_fail(IM_EINVAL, "adhesion summary of %d steps: expected at least 1", count);
    for (int k = 0; k < count; ++k)
        if (!(isfinite(approach[k]) && isfinite(load[k])))
            return im_fail(IM_EINVAL, "adhesion summary: step %d has w = %g, N = %g: expected finite values", k + 1,
                           approach[k], load[k]);
    im_adhesion_summary s = {NAN, NAN, NAN, NAN, 0, NAN, 0, NAN, NAN};
    int least = -1;
    for (int k = 0; k < count; ++k) {
        if (load[k] < 0 && !(-load[k] <= s.most_tensile_load)) {
            s.most_tensile_load = -load[k];
            s.most_tensile_approach = approach[k];
            least = k;
        }
        if (k == 0)
            continue;
        s.work_done += 0.5 * (load[k] + load[k - 1]) * (approach[k] - approach[k - 1]);
        s.hysteresis_error += trapezoid_error(approach, load, count, k);
        if (isnan(s.jump_in_approach) && contact[k] > 0 && contact[k - 1] == 0 && approach[k] > approach[k - 1])
            s.jump_in_approach = approach[k];
        if (contact[k] == 0 && contact[k - 1] > 0 && approach[k] < approach[k - 1])
            s.jump_out_approach = approach[k - 1];
    }
    if (closes_a_loop(approach, load, count))
        s.hysteresis_work = s.work_done;
    if (least >= 0 && passed_pull_off(load, count, least, loads_given)) {
        s.pull_off_force = s.most_tensile_load;
        s.pull_off_approach = s.most_tensile_approach;
    }
    *out = s;
    return IM_OK;
}
