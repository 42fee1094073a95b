/* The theory beside a simulated history: per step, the smooth punch's closed forms (indenter.h) and
 * the rough-contact area ratios at the smooth mean pressure. */
#include "indentmap/status.h"
#include "core/args.h"
#include "indentmap/theory.h"

#include <math.h>

int im_theory_step_columns(const im_indenter *punch, const im_theory_interface *rough, double approach, double load,
                           im_theory_step *out)
{
    ARG_REQUIRE(punch, "punch");
    ARG_REQUIRE(rough, "rough");
    ARG_REQUIRE(out, "out");
    double p_rough, beta;
    int status = im_indenter_check(punch);
    if (status == IM_OK)
        status = im_theory_p_rough(rough, &p_rough);
    if (status == IM_OK && !(approach >= 0.0 && load >= 0.0 && isfinite(approach) && isfinite(load)))
        status = im_fail(IM_EINVAL, "w = %g, N = %g: expected finite w >= 0 and N >= 0", approach, load);
    if (status != IM_OK)
        return status;
    im_theory_step step = {.load_smooth = im_indenter_load(punch, rough->e_star, approach),
                           .area_smooth = load > 0.0 ? im_indenter_area_for_load(punch, rough->e_star, load) : 0.0,
                           .area_ratio_constant = NAN,
                           .area_ratio_gamma = NAN};
    /* the rough-contact theory is for the cone, the sphere and the flat punch: NaN for a profile */
    if (load > 0.0 && punch->kind != IM_PUNCH_PROFILE && punch->kind != IM_PUNCH_PROFILE_2D) {
        double rho = p_rough > 0.0 ? load / step.area_smooth / p_rough : INFINITY;
        status = im_theory_erf_scale(rho, rough->normalisation, rough->k, &beta);
        if (status == IM_OK)
            status = im_theory_cone_area_ratio_constant(beta, &step.area_ratio_constant);
        if (status == IM_OK)
            status = im_theory_punch_area_ratio(punch->kind, beta, &step.area_ratio_gamma);
    }
    if (status == IM_OK)
        *out = step;
    return status;
}
