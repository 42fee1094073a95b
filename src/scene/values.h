/* Internal: the parsers of a scene's values (values.c), one per kind of value, and what a key tells
 * its parser (key_spec; the keys themselves are keys.c's table). Each parser stores the value into
 * the im_scene field the spec names and returns IM_OK, or IM_EFORMAT with a message naming the key
 * and what was expected (parse.c puts the file and line before it). */
#ifndef INDENTMAP_SCENE_VALUES_H
#define INDENTMAP_SCENE_VALUES_H

#include "indentmap/scene.h"

#include <stddef.h>

typedef struct key_spec key_spec;
typedef int (*value_parser)(const key_spec *spec, const char *value, im_scene *scene);

struct key_spec {
    const char *section, *key;
    value_parser parse;
    size_t offset;       /* of the destination in im_scene */
    double min, max;     /* numeric range (inclusive) */
    const char *choices; /* "a|b|c" for enumerations */
    size_t capacity;     /* string size or list capacity */
    size_t count_offset; /* of the list's count */
};

int scene_parse_double(const key_spec *spec, const char *value, im_scene *scene);
int scene_parse_int(const key_spec *spec, const char *value, im_scene *scene);
int scene_parse_string(const key_spec *spec, const char *value, im_scene *scene);
int scene_parse_name(const key_spec *spec, const char *value, im_scene *scene);
int scene_parse_choice(const key_spec *spec, const char *value, im_scene *scene); /* one of spec->choices */
int scene_parse_bool(const key_spec *spec, const char *value, im_scene *scene);
int scene_parse_double_list(const key_spec *spec, const char *value, im_scene *scene);
int scene_parse_sweep_list(const key_spec *spec, const char *value, im_scene *scene);
int scene_parse_seeds(const key_spec *spec, const char *value, im_scene *scene);
int scene_parse_adhesion_law(const key_spec *spec, const char *value, im_scene *scene);
int scene_parse_punch(const key_spec *spec, const char *value, im_scene *scene);
int scene_parse_plots(const key_spec *spec, const char *value, im_scene *scene);
int scene_parse_quality(const key_spec *spec, const char *value, im_scene *scene);
/* Stores nothing: a value whose meaning depends on other keys ([loading] steps, below 0 with
 * [adhesion] only), which parse.c keeps as written and check.c parses once every key is known. */
int scene_parse_later(const key_spec *spec, const char *value, im_scene *scene);

#endif
