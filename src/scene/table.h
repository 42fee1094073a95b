/* Internal: the ensemble table at load_star (table.c). */
#ifndef INDENTMAP_SCENE_TABLE_H
#define INDENTMAP_SCENE_TABLE_H

#include "scene/ensemble.h"

/* The member solver of the table (the histories' is scene_history_member): reads back a member an
 * earlier run kept (options->resume) or solves it, and writes it under the output folder. */
int scene_table_member(const im_scene *scene, const im_scene_run_options *options, scene_member *m);

/* Reads a member written by an earlier, interrupted run (what --resume reuses); 0 if there is none, if
 * it is damaged, or if it was made from other inputs (its key differs): then it is solved again, with a
 * notice (scene_warn). */
int scene_table_member_kept(const im_scene *scene, const im_scene_run_options *options, scene_member *m);

/* The ensemble table at load_star (the paper's Table 1): table/member_FF_SEED.csv for each
 * surface as soon as it is solved, then table1.csv and table1.md. Its members (and the first
 * seeds' forces, for panels) are left in *reuse. */
int scene_run_table(const im_scene *scene, const im_scene_run_options *options, scene_reuse *reuse);

#endif
