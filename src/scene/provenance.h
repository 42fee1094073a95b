/* Internal: a scene run's provenance (provenance.c; docs/scenes.md, "Provenance"): the scene's contents
 * and its inputs' checksums as run.json records them, and the scene rebuilt from such a record. */
#ifndef INDENTMAP_SCENE_PROVENANCE_H
#define INDENTMAP_SCENE_PROVENANCE_H

#include "front/front.h"
#include "indentmap/scene.h"

#include <jansson.h>

/* Parses the scene file at path into *scene, defaults first (parse.c): im_scene_load's errors. */
int scene_load_file(const char *path, im_scene *scene);

/* Parses scene text as scene_load_file parses a file named path (parse.c): its errors name path and
 * the line of text, and paths in it resolve against path's folder. */
int scene_load_text(const char *text, const char *path, im_scene *scene);

/* Rebuilds into *scene the scene of the run record at path (provenance.c): im_scene_load_record's
 * errors. */
int scene_load_record(const char *record, im_scene *scene);

/* run.json's "scene_contents" into *record: what the scene file set ({"section": {"key": "value"}}),
 * which keys that is, and the scene file's absolute path. IM_EFORMAT for a value or path that is not
 * UTF-8 (a record holds text), *record NULL on failure. */
int scene_contents_record(const im_scene *scene, json_t **record);

/* Input i of a scene (its surface files, then its profile): its key and path; 0 past the last. A
 * profile path is resolved against the scene's folder unless the run has done it (profile_resolved).
 * What run.json's "inputs" record, and what the ranks of an MPI run compare (src/mpi/inputs.c). */
int scene_input(const im_scene *scene, int i, int profile_resolved, const char **key, char *path, size_t size);

/* run.json's "inputs" into *record: each surface and profile file of the scene as it runs (its profile
 * path already resolved: scene_prepare) with its key, absolute path and SHA-256; the error of one
 * that cannot be read, *record NULL. */
int scene_inputs_record(const im_scene *scene, json_t **record);

/* The texts every figure of a scene run carries (front.h: run_figure_texts): the version, the scene's
 * path ("Source") and contents (PAPER_SCENE_CONTENTS, when it has any), the figure's own (at most
 * four, borrowed) and the scene's inputs' SHA-256; the error of an input that cannot be read. */
int scene_figure_texts(const im_scene *scene, const im_png_text *own, int own_count, run_figure_texts *texts);

#endif
