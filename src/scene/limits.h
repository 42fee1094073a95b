/* Internal: checks before any work (limits.c). */
#ifndef INDENTMAP_SCENE_LIMITS_H
#define INDENTMAP_SCENE_LIMITS_H

#include "indentmap/scene.h"

/* Before any work (limits.c): the output folder neither is nor contains an input (IM_EINVAL); the
 * smooth contact at load_star (and at the largest N* step) stays inside the surface (IM_EINVAL);
 * the memory (IM_ENOMEM) and disk (IM_EIO; free space of the output folder's file system, and the
 * file-size limit) the outputs need, estimated from above, are there (the free space unless
 * options->no_space_check). Messages give the estimate. */
int scene_check_limits(const im_scene *scene, const im_scene_run_options *options);

#endif
