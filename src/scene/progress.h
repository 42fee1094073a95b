/* Internal: what a running scene tells its caller: stage lines and the stop signal (progress.c). */
#ifndef INDENTMAP_SCENE_PROGRESS_H
#define INDENTMAP_SCENE_PROGRESS_H

#include "indentmap/scene.h"

/* A stage line (IM_LOG_INFO, dropped when quiet) and a warning (IM_LOG_WARNING, logged even when
 * quiet) to options->log, if any. */
void scene_progress(const im_scene_run_options *options, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
void scene_warn(const im_scene_run_options *options, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* The number of the signal that asked the run to stop, or 0 (checked between solver steps and
 * between surfaces). */
int scene_stop_signal(const im_scene_run_options *options);

/* IM_EINTERRUPTED with a message naming the signal and where the run stopped (`where`). */
int scene_interrupted(const im_scene_run_options *options, const char *where);

#endif
