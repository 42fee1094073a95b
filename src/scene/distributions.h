/* Internal: the gap and contact-patch size distributions a scene writes (distributions.c). */
#ifndef INDENTMAP_SCENE_DISTRIBUTIONS_H
#define INDENTMAP_SCENE_DISTRIBUTIONS_H

#include "indentmap/scene.h"

/* [output] distributions (distributions.c): distributions/family_FF_{gaps,patches,patch_list}.csv,
 * the gap (in h_rms of the surface, delta for a smooth one) and contact-patch size distributions of
 * each family's first surface at load_star, solved for them. */
int scene_run_distributions(const im_scene *scene, const im_scene_run_options *options);

#endif
