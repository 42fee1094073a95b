/* The pull-off, the jumps and the lost work of an adhesive force-distance history (measure.h). */
#include "indentmap/measure.h"
#include "core/args.h"

#include "indentmap/status.h"

#include <math.h>

int im_measure_adhesion(const double *approach, const double *load, const long *contact, int count,
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
    im_adhesion_summary s = {NAN, NAN, NAN, NAN, 0};
    for (int k = 0; k < count; ++k) {
        if (load[k] < 0 && !(-load[k] <= s.pull_off_force)) {
            s.pull_off_force = -load[k];
            s.pull_off_approach = approach[k];
        }
        if (k == 0)
            continue;
        s.hysteresis_work += 0.5 * (load[k] + load[k - 1]) * (approach[k] - approach[k - 1]);
        if (isnan(s.jump_in_approach) && contact[k] > 0 && contact[k - 1] == 0 && approach[k] > approach[k - 1])
            s.jump_in_approach = approach[k];
        if (contact[k] == 0 && contact[k - 1] > 0 && approach[k] < approach[k - 1])
            s.jump_out_approach = approach[k - 1];
    }
    *out = s;
    return IM_OK;
}
