/* The theory beside every simulated history of a scene (the history files' theory columns). */
#include "indentmap/theory.h"
#include "scene/contents.h"
#include "scene/history_theory.h"
#include "scene/punch.h"

im_theory_interface scene_theory_interface(const im_scene *scene, double slope)
{
    im_theory_interface rough = im_theory_interface_default(slope);
    rough.e_star = scene->modulus;
    return rough;
}

int scene_history_theory_row(const im_scene *scene, double slope, double approach, double load, im_theory_step *row)
{
    im_indenter punch = scene_punch(scene);
    im_theory_interface rough = scene_theory_interface(scene, slope);
    return im_theory_step_columns(&punch, &rough, approach, load, row);
}
