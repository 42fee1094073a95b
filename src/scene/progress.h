/* Internal: what a running scene tells its caller: stage lines and the stop signal (progress.c). */
#ifndef INDENTMAP_SCENE_PROGRESS_H
#define INDENTMAP_SCENE_PROGRESS_H

#include "indentmap/scene.h"

#include <omp.h>

/* The caller's log and progress callbacks behind a lock of one run's own: calls from its OpenMP
 * workers come one at a time, and a callback may run another scene (a lock shared by all runs,
 * held through the callback, would make that scene's first call wait for itself forever). */
typedef struct scene_callbacks {
    omp_lock_t lock;
    im_log_fn log;
    im_progress_fn progress;
    void *user;
} scene_callbacks;

/* The options of a run whose callbacks (if any) go through *callbacks; scene_callbacks_end after
 * the run. */
im_scene_run_options scene_callbacks_begin(const im_scene_run_options *given, scene_callbacks *callbacks);
void scene_callbacks_end(scene_callbacks *callbacks);

/* A stage line (IM_LOG_INFO, dropped when quiet) and a warning (IM_LOG_WARNING, logged even when
 * quiet) to options->log, if any. */
void scene_progress(const im_scene_run_options *options, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void scene_warn(const im_scene_run_options *options, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* The number of the signal that asked the run to stop, or 0 (checked between solver steps and
 * between surfaces). */
int scene_stop_signal(const im_scene_run_options *options);

/* IM_EINTERRUPTED with a message naming the signal and where the run stopped (`where`). */
int scene_interrupted(const im_scene_run_options *options, const char *where);

#endif
