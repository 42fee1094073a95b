/* Internal: how a scene's figures name its families and colour their forces (labels.c). */
#ifndef INDENTMAP_SCENE_LABELS_H
#define INDENTMAP_SCENE_LABELS_H

#include "indentmap/colormap.h"
#include "indentmap/scene.h"

#include <stddef.h>

/* A label for a family: "smooth" or "h'rms = 0.08". */
void scene_family_title(const im_scene *scene, int family, char *buffer, size_t size);

/* The colour norm of the local forces gathered in `forces` (colormap.h: im_colormap_range_norm): the
 * scene's colour map, linear from 0 or log over the two decades below the largest. */
im_colormap scene_force_norm(const im_scene *scene, const im_colormap_range *forces);

#endif
