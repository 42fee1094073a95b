/* The punch of a scene, the loads that give its N*, its solver options and eq. (12) at its angle. */
#include "indentmap/scene.h"
#include "scene/contents.h"
#include "scene/run_state.h"

#include "indentmap/status.h"
#include "indentmap/theory.h"
#include "front/front.h"
#include "scene/punch.h"

#include <math.h>

im_indenter scene_punch(const im_scene *scene)
{
    switch (scene->punch) {
    case IM_PUNCH_SPHERE: return im_indenter_sphere(scene->radius);
    case IM_PUNCH_FLAT: return im_indenter_flat(scene->radius);
    case IM_PUNCH_PROFILE: return im_indenter_from_profile(scene_profile(scene)); /* or a 2-D one, as read */
    default: return im_indenter_cone(scene->alpha_degrees);
    }
}

im_indenter scene_member_punch(const im_scene *scene, const im_field *surface)
{
    return scene->periodic == IM_SCENE_PERIODIC_FLAT ? periodic_rigid_flat(surface) : scene_punch(scene);
}

double scene_load_for_load_star(const im_scene *scene, double delta)
{
    return scene_load_for_n_star(scene, scene->load_star, delta);
}

double scene_load_for_n_star(const im_scene *scene, double n_star, double delta)
{
    /* A(N) increases with N for every punch: bisect A(N) = n_star delta^2 in log N. */
    im_indenter punch = scene_punch(scene);
    if (!isfinite(im_indenter_area_for_load(&punch, scene->modulus, 1.0)))
        return NAN; /* no smooth-contact area (a 2-D profile): no load has this N* */
    double area = n_star * delta * delta, lo = 1e-300, hi = 1.0;
    while (im_indenter_area_for_load(&punch, scene->modulus, hi) < area && hi < 1e300)
        hi *= 2.0;
    for (int i = 0; i < 200 && hi / lo > 1.0 + 1e-15; ++i) {
        double mid = sqrt(lo * hi);
        if (im_indenter_area_for_load(&punch, scene->modulus, mid) < area)
            lo = mid;
        else
            hi = mid;
    }
    return hi;
}

int scene_steps_are_loads(const im_scene *scene)
{
    return scene->control == IM_CONTROL_LOAD && scene->adhesion_work > 0 && !scene->periodic;
}

im_solver_options scene_solver_options(const im_scene *scene)
{
    im_solver_options options = im_solver_options_default();
    options.e_star = scene->modulus;
    options.tol = scene->tol;
    options.hardness = scene->hardness;
    options.adhesion_work = scene->adhesion_work;
    options.adhesion_range = scene->adhesion_range;
    options.adhesion_law = scene->adhesion_law;
    options.adhesion_zone = scene->adhesion_zone;
    options.device = scene->device;
    options.wisdom_path = scene->wisdom_path;
    options.periodic = scene->periodic != 0;
    return options;
}

double scene_eq12(const im_scene *scene, double slope, double *rho_c)
{
    im_theory_interface rough = im_theory_interface_default(slope);
    double rho = NAN, beta, ratio;
    int ok = scene->punch == IM_PUNCH_CONE && im_theory_cone_rho(&rough, scene->alpha_degrees, &rho) == IM_OK &&
             im_theory_erf_scale(rho, rough.normalisation, rough.k, &beta) == IM_OK &&
             im_theory_cone_area_ratio_variable(beta, &ratio) == IM_OK;
    if (rho_c)
        *rho_c = rho;
    return ok ? ratio : NAN;
}
