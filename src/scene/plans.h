/* Internal: the FFTW plans a scene's kept results were solved with (plans.c). Results depend in
 * their last bits on the plans, and measured plans on the wisdom file, which other runs rewrite: a
 * run records OUTPUT/fftw-plans.txt (how its plans were made: estimated, or measured with the wisdom
 * lines it leaves), and --resume re-solves everything when those plans can no longer be had. */
#ifndef INDENTMAP_SCENE_PLANS_H
#define INDENTMAP_SCENE_PLANS_H

#include "indentmap/scene.h"

/* 1 when the kept results' plans differ from this run's: they were estimated and this run measures,
 * or the reverse, or the wisdom file lacks a line of the recorded wisdom (removed, measured anew).
 * Says so (scene_warn). 0 when they are the same, or no record is kept (a run killed before its end,
 * or written by an earlier version). */
int scene_plans_changed(const im_scene *scene, const im_scene_run_options *options);

/* Writes OUTPUT/fftw-plans.txt for the plans this run used. */
int scene_plans_record(const im_scene *scene);

#endif
