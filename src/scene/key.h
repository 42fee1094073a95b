/* Internal: keys of kept results (key.c). */
#ifndef INDENTMAP_SCENE_KEY_H
#define INDENTMAP_SCENE_KEY_H

#include "indentmap/scene.h"

#include <stddef.h>
#include <stdint.h>

/* What a kept result is: the state at load_star solved in two steps (a table member, a panel), a
 * history, or the last of the frames' steps (the framed family's panel). */
enum scene_result_kind { SCENE_RESULT_AT_LOAD_STAR, SCENE_RESULT_HISTORY, SCENE_RESULT_FRAMED };

/* A hash of every input that determines the result of family's surface with this seed: the
 * surface (generator parameters, slope, seed, grid; or the file's path, size and time), punch,
 * material, solver options (tolerance, window), and load_star or the loading control and steps. */
uint64_t scene_result_key(const im_scene *scene, int family, uint64_t seed, enum scene_result_kind kind);

/* The index of the load-controlled step at load_star, -1 if none: there a history takes the
 * table's state instead of solving it again. */
int scene_load_star_step(const im_scene *scene);

/* Whether a result kept at path (with key kept; 0 when it could not be read) may be reused; if
 * not, warns (scene_warn) why it is solved again. */
int scene_key_matches(const im_scene_run_options *options, const char *path, uint64_t kept, uint64_t wanted);

/* FNV-1a (64 bits) of length bytes: the checksum a kept history carries of its rows, so that one
 * cut short or edited is solved again rather than drawn. */
uint64_t scene_checksum(const char *bytes, size_t length);

/* Warns (scene_warn) that the kept result at path is damaged (why) and is solved again; returns 0,
 * for `return scene_kept_damaged(...)` in a reader. */
int scene_kept_damaged(const im_scene_run_options *options, const char *path, const char *why);

#endif
