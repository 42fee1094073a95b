/* Internal: what a periodic scene ([punch] periodic) gives beyond its histories (periodic.c). */
#ifndef INDENTMAP_SCENE_PERIODIC_H
#define INDENTMAP_SCENE_PERIODIC_H

#include "indentmap/scene.h"
#include "scene/ensemble.h"

/* Whether the scene's histories give k of eq. (2): a rigid flat on the cell without a hardness (eq. (2)
 * is an elastic law for a rigid flat), as `indent --periodic`. */
int scene_periodic_fits_k(const im_scene *scene);

/* After the histories of a periodic scene: warns for each surface that is not periodic (front.h:
 * periodic_edge_mismatch, as `indent --periodic`), and when scene_periodic_fits_k, writes OUTPUT/k_fit.csv:
 * a row per rough member, k fitted to its history (front.h: periodic_fit_k) with its surface's spectral
 * h'rms, the numbers of `indent --periodic`'s run.json "k_fit". Drawn again by every run (--resume too). */
int scene_periodic_results(const im_scene *scene, const im_scene_run_options *options, const scene_member *members,
                           int count);

#endif
