/* Internal: whether a scene's keys agree with each other (check.c), once parse.c has parsed each. */
#ifndef INDENTMAP_SCENE_CHECK_H
#define INDENTMAP_SCENE_CHECK_H

#include "indentmap/scene.h"

/* What parse.c saw of a scene. */
typedef struct scene_given {
    im_scene *scene;      /* every key given parsed into it, completed (keys.h: scene_complete) */
    const int *key_lines; /* the line of each key of keys.h's table, 0 for a key not given */
    const char *steps;    /* [loading] steps as written (values.h: scene_parse_later) */
} scene_given;

/* Parses [loading] steps and checks the settings that contradict each other (adhesion, periodic,
 * sweeps, the punch's keys, fig7's steps, lambda_r, surface files, mean gaps, steps that unload),
 * completing the scene where one key decides another (a periodic scene's control, the files'
 * ensemble). 0 if consistent, else the line of the key at fault (the later of two; 1 if no key
 * was given) with IM_EFORMAT's message (im_fail). */
int scene_check_keys(const scene_given *given);

#endif
