/* Internal: the surfaces of a scene, generated or read from its files (surfaces.c). */
#ifndef INDENTMAP_SCENE_SURFACES_H
#define INDENTMAP_SCENE_SURFACES_H

#include "indentmap/field.h"
#include "indentmap/scene.h"

#include <stdint.h>

/* The surface of one family and seed: flat for slope 0, the file when the scene names one, else
 * generated. */
int scene_surface(const im_scene *scene, int family, uint64_t seed, im_field **out);

/* The h'rms of one member: its file's measured one in a scene over files, else its family's. */
double scene_member_slope(const im_scene *scene, int family, uint64_t seed);

#endif
