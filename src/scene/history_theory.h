/* Internal: the theory beside a history's steps (history_theory.c). */
#ifndef INDENTMAP_SCENE_HISTORY_THEORY_H
#define INDENTMAP_SCENE_HISTORY_THEORY_H

#include "indentmap/scene.h"

/* The theory columns (theory.h's im_theory_step) of a step at approach w and load N on a surface
 * of this h'rms: the scene's punch and E*, k = 2 and the PR normalisation (history_theory.c). */
struct im_theory_step;
int scene_history_theory_row(const im_scene *scene, double slope, double approach, double load,
                             struct im_theory_step *row);

#endif
