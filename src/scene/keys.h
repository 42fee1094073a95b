/* Internal: the keys a scene file may give (keys.c): one table of SCENE_KEY_COUNT keys, each with its
 * section, parser (values.h), destination in im_scene, range and capacity; the defaults of a scene
 * (contents.h: scene_defaults) and the settings that follow from the keys given. */
#ifndef INDENTMAP_SCENE_KEYS_H
#define INDENTMAP_SCENE_KEYS_H

#include "scene/values.h"

enum { SCENE_KEY_COUNT = 53 };

/* Key index of the table (0 <= index < SCENE_KEY_COUNT). */
const key_spec *scene_key(int index);
/* The index of [section] key in the table, -1 if a scene has no such key. */
int scene_key_index(const char *section, const char *key);
/* Whether some key of the table is in [section]. */
int scene_section_exists(const char *section);

/* The settings that follow from others unless given: the tolerance from the quality preset, rows =
 * columns, lambda_r = the box's side, the output folder (output/NAME under the working folder; a
 * given one relative to the scene file). */
void scene_complete(im_scene *scene, int tol_given, int ny_given, int lambda_r_given, int output_given);

#endif
