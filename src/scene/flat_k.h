/* Internal: eq. (2)'s k measured on surfaces pressed flat (flat_k.c). */
#ifndef INDENTMAP_SCENE_FLAT_K_H
#define INDENTMAP_SCENE_FLAT_K_H

#include "scene/ensemble.h"

/* plots = flat_k (flat_k.c): eq. (2)'s k measured on every rough surface in the periodic half-space,
 * fed into eq. (12) beside k = 2 and the table's simulated A/A_cone (reuse, when the table ran). */
int scene_run_flat_k(const im_scene *scene, const im_scene_run_options *options, const scene_reuse *reuse);

#endif
