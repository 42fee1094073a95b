/* Internal: contact panels of every family at load_star (panels.c). */
#ifndef INDENTMAP_SCENE_PANELS_H
#define INDENTMAP_SCENE_PANELS_H

#include "indentmap/field.h"
#include "indentmap/render.h"
#include "indentmap/scene.h"

/* Panels of every family at load_star; known_force (may be NULL) is the framed family's force,
 * already solved by the frames; reuse holds what the table or the histories solved. */
struct scene_reuse;
int scene_run_panels(const im_scene *scene, const im_scene_run_options *options, im_render_context *context,
                     const struct scene_reuse *reuse, const im_field *known_force);

/* panels/force_FF.npy and force_FF.key (the key of the force of family's first seed at load_star
 * solved in two steps, and the force's checksum): written after removing the old key, so that the
 * force is read back only beside its own key; read without checking the key (for a force this run
 * wrote). */
int scene_write_panel(const im_scene *scene, int family, const im_field *force);
int scene_read_panel_force(const im_scene *scene, int family, im_field **force);

#endif
