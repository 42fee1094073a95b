/* Internal: what a run makes in its output folder (manifest.c). Every output path a run names
 * (scene_output_path) is noted: a file there whose bytes are not of the kind its name says (a PNG
 * that is not a PNG, a CSV holding binary bytes) is damaged, and is removed, with a notice, before
 * it is read back or written again. OUTPUT/outputs.txt lists what the last run made; at the end of
 * a run that finished, the files it lists that this run no longer makes are removed, with a notice. */
#ifndef INDENTMAP_SCENE_MANIFEST_H
#define INDENTMAP_SCENE_MANIFEST_H

#include "indentmap/scene.h"

/* Starts noting the outputs of scene, a run's copy (run_state.h: outputs): reads the old OUTPUT/outputs.txt (a damaged one is
 * set aside with a notice) and marks the start of the run by run.json's time, so call it right after
 * run.json is written. IM_ENOMEM at worst. */
int scene_outputs_open(const im_scene *scene, const im_scene_run_options *options);

/* Notes path (under the output folder) as made or kept by this run; the first time, removes a damaged
 * file there (see above). Nothing outside a run's noting (a scene that is not a run's copy, or before
 * scene_outputs_open). Thread-safe. */
void scene_outputs_note(const im_scene *scene, const char *path);

/* Ends the run's noting: when finished, removes what outputs.txt listed and this run did not make,
 * then lists what this run made (files noted, or written since run.json); otherwise lists both, so
 * that a later run still knows them. Frees the run's outputs. Returns status, or the error of writing
 * outputs.txt when status is IM_OK. */
int scene_outputs_close(const im_scene *scene, int status);

/* Removes path when it is a regular file whose bytes are not of the kind its name's extension says
 * (damaged), unless it is a protected input, with a notice; an unknown extension is left alone. */
void scene_output_repair(const im_scene_run_options *options, const char *path);

#endif
