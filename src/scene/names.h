/* Internal: the names a scene's words are checked against (names.c): the plots' names (scene.h:
 * im_scene_plot_name, im_scene_plot_parse) and, for a word that is none of a set of names, the
 * nearest of them. */
#ifndef INDENTMAP_SCENE_NAMES_H
#define INDENTMAP_SCENE_NAMES_H

#include <stddef.h>

/* Levenshtein distance between a and b; (size_t)-1 when b has 64 characters or more. */
size_t scene_edit_distance(const char *a, const char *b);

/* The plot name nearest to an unknown one (fewer edits than half its length), NULL if none is close. */
const char *scene_suggest_plot(const char *word);

#endif
