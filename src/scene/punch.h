/* Internal: the punch of a scene, the loads that give its N*, its solver options and eq. (12) (punch.c). */
#ifndef INDENTMAP_SCENE_PUNCH_H
#define INDENTMAP_SCENE_PUNCH_H

#include "indentmap/indenter.h"
#include "indentmap/scene.h"
#include "indentmap/solver.h"

/* The punch a scene describes. */
im_indenter scene_punch(const im_scene *scene);

/* The punch that presses a member's surface: scene_punch, or with [punch] periodic and no shape the
 * rigid flat on the whole cell (front.h: periodic_rigid_flat, as `indent --periodic`). */
im_indenter scene_member_punch(const im_scene *scene, const im_field *surface);

/* The load N whose smooth contact area is load_star delta^2 (N* of the paper for a cone). */
double scene_load_for_load_star(const im_scene *scene, double delta);

/* The load N whose smooth contact area is n_star delta^2; NaN for a punch without a smooth-contact
 * area (a 2-D profile: run.c refuses what would ask, and the solver refuses a NaN target). */
double scene_load_for_n_star(const im_scene *scene, double n_star, double delta);

/* Whether the scene's [loading] steps are loads N (`indent --load`'s), not N*: under load control with
 * [adhesion], whose pulled (negative) loads have no smooth-contact area to give an N*. */
int scene_steps_are_loads(const im_scene *scene);

/* Solver options of a scene (its tolerance; everything else default). */
im_solver_options scene_solver_options(const im_scene *scene);

/* Eq. (12)'s A/A_cone for a cone scene and a roughness (NaN for other punches); *rho_c (may be
 * NULL) receives rho_c of eq. (7). */
double scene_eq12(const im_scene *scene, double slope, double *rho_c);

#endif
