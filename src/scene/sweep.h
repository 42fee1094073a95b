/* Internal: scenes over lists of alpha, hurst and lambda_s, one sub-scene per point (sweep.c). */
#ifndef INDENTMAP_SCENE_SWEEP_H
#define INDENTMAP_SCENE_SWEEP_H

#include "scene/ensemble.h"
#include "scene/limits.h"

/* The stages of one scene (run.c): what its table solved is left in *reuse (freed by the caller). */
typedef int (*scene_stage_runner)(const im_scene *scene, const im_scene_run_options *options, scene_reuse *reuse);

/* The number of sweep points: the product of the alpha, hurst and lambda_s lists' lengths (1: no
 * sweep). */
int scene_sweep_count(const im_scene *scene);

/* Sweep point index (alpha slowest, lambda_s fastest) as a scene of its own: one alpha, hurst and
 * lambda_s (lists of one), output in OUTPUT/alpha_A_hurst_H_lambda_s_L. IM_EINVAL if that path
 * is too long. */
int scene_sweep_point(const im_scene *scene, int index, im_scene *point);

/* Every point's limits (limits.c: the smooth contact inside the surface, memory, disk) before any
 * work, so that a sweep is not refused half-way; each point's estimates in each[i] unless each is NULL. */
int scene_sweep_check_points(const im_scene *scene, const im_scene_run_options *options, scene_limits *each);

/* Before any work: IM_EINVAL when the sweep's fig2 would draw more roughnesses (rough families x H x
 * lambda_s) than it can (the run's refusal, which would otherwise come after every point is solved). */
int scene_sweep_check_fig2(const im_scene *scene);

/* Runs every sweep point with run_stages (in the output folder the caller has locked); with a
 * table, writes OUTPUT/sweep.csv (one row per point and family: A/A_cone mean and sd, rho_c,
 * eq. (12)) and, with plots = fig2, OUTPUT/fig2.{png,pdf} over all of them. */
int scene_run_sweep(const im_scene *scene, const im_scene_run_options *options, scene_stage_runner run_stages);

#endif
