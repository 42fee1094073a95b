/* Internal: checks before any work (limits.c). */
#ifndef INDENTMAP_SCENE_LIMITS_H
#define INDENTMAP_SCENE_LIMITS_H

#include "indentmap/scene.h"

/* What scene_check_limits estimated, as far as it got: `run --check` prints the run's own numbers. */
typedef struct scene_limits {
    int nx, ny, window_nx, window_ny; /* the grid; the window the solves are planned on (the grid where not known) */
    int at_once, gpu;                 /* the most solves at once; whether their plans are the GPU engine's */
    double solve_bytes;               /* one solve's plan and fields */
    double memory_needed, memory_available;     /* available: 0 when the machine does not say */
    double address_reserved, address_space;     /* reserved by threads and the renderer; the limit, 0 for none */
    double disk_total, disk_largest, disk_free; /* disk_free: -1 when the file system does not say */
    const char *disk_largest_name;
    char disk_folder[IM_SCENE_PATH]; /* the existing folder whose file system holds the outputs */
} scene_limits;

/* Before any work (limits.c): the output folder neither is nor contains an input (IM_EINVAL); the
 * smooth contact at load_star (and at the largest N* step) stays inside the surface (IM_EINVAL);
 * the memory (IM_ENOMEM) and disk (IM_EIO; free space of the output folder's file system, and the
 * file-size limit) the outputs need, estimated from above, are there (the free space unless
 * options->no_space_check). Messages give the estimate; *limits (zeroed first) keeps it. */
int scene_check_limits(const im_scene *scene, const im_scene_run_options *options, scene_limits *limits);

#endif
