/* Internal: the theory beside a history's steps (history_theory.c). */
#ifndef INDENTMAP_SCENE_HISTORY_THEORY_H
#define INDENTMAP_SCENE_HISTORY_THEORY_H

#include "indentmap/scene.h"
#include "indentmap/theory.h"

/* The rough interface of the theory columns of a history on a surface of this h'rms: the scene's
 * E*, k = 2 and the PR normalisation (history_theory.c). */
im_theory_interface scene_theory_interface(const im_scene *scene, double slope);
/* The theory columns (theory.h's im_theory_step) of a step at approach w and load N on it. */
int scene_history_theory_row(const im_scene *scene, double slope, double approach, double load, im_theory_step *row);

#endif
