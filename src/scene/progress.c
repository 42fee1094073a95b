/* What a running scene tells its caller: stage lines, and the signal that asked it to stop. */
#include "indentmap/status.h"
#include "scene/progress.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

int scene_stop_signal(const im_scene_run_options *options) { return options->stop ? (int)*options->stop : 0; }

int scene_interrupted(const im_scene_run_options *options, const char *where)
{
    return im_fail(IM_EINTERRUPTED,
                   "interrupted by signal %d (%s) %s; finished results are kept: "
                   "run again with --resume to continue",
                   scene_stop_signal(options), strsignal(scene_stop_signal(options)), where);
}

static void serialised_log(void *user, im_log_level level, const char *message)
{
    scene_callbacks *c = user;
    omp_set_lock(&c->lock);
    c->log(c->user, level, message);
    omp_unset_lock(&c->lock);
}

static void serialised_progress(void *user, const char *stage, int done, int total)
{
    scene_callbacks *c = user;
    omp_set_lock(&c->lock);
    c->progress(c->user, stage, done, total);
    omp_unset_lock(&c->lock);
}

im_scene_run_options scene_callbacks_begin(const im_scene_run_options *given, scene_callbacks *callbacks)
{
    *callbacks = (scene_callbacks){.log = given->log, .progress = given->progress, .user = given->user};
    omp_init_lock(&callbacks->lock);
    im_scene_run_options run = *given;
    run.log = given->log ? serialised_log : NULL;
    run.progress = given->progress ? serialised_progress : NULL;
    run.user = callbacks;
    return run;
}

void scene_callbacks_end(scene_callbacks *callbacks) { omp_destroy_lock(&callbacks->lock); }

/* One message to options->log (serialised by scene_callbacks_begin's lock), formatted here. */
static void scene_log(const im_scene_run_options *options, im_log_level level, const char *fmt, va_list args)
{
    if (!options->log || (level == IM_LOG_INFO && options->quiet))
        return;
    char message[2048];
    vsnprintf(message, sizeof message, fmt, args);
    options->log(options->user, level, message);
}

void scene_progress(const im_scene_run_options *options, const char *fmt, ...)
{
    va_list args;
    va_start(args, fmt);
    scene_log(options, IM_LOG_INFO, fmt, args);
    va_end(args);
}

void scene_warn(const im_scene_run_options *options, const char *fmt, ...)
{
    va_list args;
    va_start(args, fmt);
    scene_log(options, IM_LOG_WARNING, fmt, args);
    va_end(args);
}
