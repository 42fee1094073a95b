/* Internal: frames of the framed family's history (frames.c). */
#ifndef INDENTMAP_SCENE_FRAMES_H
#define INDENTMAP_SCENE_FRAMES_H

#include "indentmap/field.h"
#include "indentmap/render.h"
#include "indentmap/scene.h"

#include <stddef.h>

/* The family whose history is framed: the one whose slope is frames_slope, else the roughest. */
int scene_framed_family(const im_scene *scene);

/* Frames of the framed family's history; *last_force receives its last step's force field (the
 * state at load_star), which the panels reuse instead of solving it again. */
int scene_run_frames(const im_scene *scene, const im_scene_run_options *options, im_render_context *context,
                     im_field **last_force);

/* "N* = LOAD", the title of step index's frames: LOAD, rounded, right-aligned with figure spaces
 * (U+2007, a digit's width) to the digits of the history's largest N*, so that every frame of a history
 * has one title width, hence one layout and size, as its animations need (a title wider than a small
 * map widened the frame it headed). */
void scene_frame_load_title(const double *load_stars, int count, int index, char *text, size_t size);

#endif
