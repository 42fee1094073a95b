/* Internal: frames of the framed family's history (frames.c). */
#ifndef INDENTMAP_SCENE_FRAMES_H
#define INDENTMAP_SCENE_FRAMES_H

#include "indentmap/field.h"
#include "indentmap/render.h"
#include "indentmap/scene.h"

/* The family whose history is framed: the one whose slope is frames_slope, else the roughest. */
int scene_framed_family(const im_scene *scene);

/* Frames of the framed family's history; *last_force receives its last step's force field (the
 * state at load_star), which the panels reuse instead of solving it again. */
int scene_run_frames(const im_scene *scene, const im_scene_run_options *options, im_render_context *context,
                     im_field **last_force);

#endif
