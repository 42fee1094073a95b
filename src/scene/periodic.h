/* Internal: what a periodic scene ([punch] periodic) gives beyond its histories (periodic.c). */
#ifndef INDENTMAP_SCENE_PERIODIC_H
#define INDENTMAP_SCENE_PERIODIC_H

#include "indentmap/render.h"
#include "indentmap/scene.h"
#include "indentmap/solver.h"
#include "scene/ensemble.h"

/* Whether the scene's histories give k of eq. (2): a rigid flat on the cell without a hardness (eq. (2)
 * is an elastic law for a rigid flat), as `indent --periodic`. */
int scene_periodic_fits_k(const im_scene *scene);

/* Warns (scene_warn, naming the file of a scene over files) when the surface of family, seed is not
 * periodic (front.h: periodic_edge_mismatch): a periodic cell joins its edges as if they met. */
void scene_warn_if_not_periodic(const im_scene *scene, const im_scene_run_options *options, int family, uint64_t seed,
                                const im_field *surface);

/* After the histories of a periodic scene: warns for each surface that is not periodic (front.h:
 * periodic_edge_mismatch, as `indent --periodic`), and when scene_periodic_fits_k, writes OUTPUT/k_fit.csv:
 * a row per rough member, k fitted to its history (front.h: periodic_fit_k) with its surface's spectral
 * h'rms, the numbers of `indent --periodic`'s run.json "k_fit". Drawn again by every run (--resume too). */
int scene_periodic_results(const im_scene *scene, const im_scene_run_options *options, const scene_member *members,
                           int count);

/* ---- contact panels and distributions of a periodic scene (periodic_maps.c) ---- */

/* Whether member m writes files at every step: the first surface of its family in a periodic scene with
 * [output] contact_panels or distributions. Such a member is solved by every run (its history is not read
 * back: the files need the solver's state of each step). */
int scene_periodic_writes_steps(const im_scene *scene, const scene_member *m);

/* After step `step` (from 1) of such a member, the run at that step: with contact_panels its fields
 * panels/family_FF/{force,gap,displacement[,plastic]}_NNNN.npy (+ .npy.json; the plastic depth with a
 * hardness), as `indent --fields` writes them; with distributions distributions/family_FF_NNNN_{gaps,
 * patches,patch_list}.csv (gaps in the surface's h_rms), as `indent --distributions`. */
int scene_periodic_step_files(const im_scene *scene, const scene_member *m, im_indentation *run, int step,
                              const im_field *surface);

/* With contact_panels: moves the history rows of those members into reuse->rows for the drawing. */
void scene_periodic_keep_rows(const im_scene *scene, scene_reuse *reuse, scene_member *members, int count);

/* Draws panels/family_FF/contact_MMMM.png (MMMM = step - 1) of every family kept in reuse->rows, from its
 * fields, as `indent --frames` (front.h: fields_frames_write; one log force norm over a family's steps). */
int scene_periodic_draw_panels(const im_scene *scene, const scene_reuse *reuse, im_render_context *context);

#endif
