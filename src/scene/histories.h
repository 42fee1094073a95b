/* Internal: histories of every member over [loading] steps (histories.c). */
#ifndef INDENTMAP_SCENE_HISTORIES_H
#define INDENTMAP_SCENE_HISTORIES_H

#include "scene/ensemble.h"

/* The member solver of the histories (the table's is scene_table_member): reads back a member an
 * earlier run kept (options->resume) or solves it, and writes it under the output folder. */
int scene_history_member(const im_scene *scene, const im_scene_run_options *options, scene_member *m);

/* Reads a history an earlier run kept into m (its rows allocated here when m->history is NULL) where
 * --resume reuses it: 0 where a periodic member writes its steps' files (solved again), or there is none,
 * or it is damaged or made from other inputs (solved again, with a notice: scene_warn). */
int scene_history_member_kept(const im_scene *scene, const im_scene_run_options *options, scene_member *m);

/* Whether the histories unload (steps that go down, with a hardness's memory, not periodic): then each
 * member's indentation analysis is written (indentation/member_FF_SEED.csv). */
int scene_histories_unload(const im_scene *scene);

/* Points each history member at the table's member of the same surface (reuse->table), whose
 * state at load_star a load-controlled history takes instead of solving it again. */
void scene_link_table(const im_scene *scene, const scene_reuse *reuse, scene_member *members, int count);

/* The largest |target| of the [loading] steps on surface: a history's largest target
 * (im_indentation_create's), which bounds its window. */
double scene_largest_step(const im_scene *scene, const im_field *surface);

/* Histories of every member over [loading] steps, for plots fig5, fig6, fig7. A load-controlled
 * step at load_star takes the table's state (reuse->table) instead of solving it again; without a
 * table, that step's force is kept in reuse->force for the panels. */
int scene_run_histories(const im_scene *scene, const im_scene_run_options *options, scene_reuse *reuse);

#endif
