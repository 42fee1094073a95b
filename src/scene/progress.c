/* What a running scene tells its caller: stage lines, and the signal that asked it to stop. */
#include "indentmap/status.h"
#include "scene/progress.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

int scene_stop_signal(const im_scene_run_options *options)
{
    return options->stop ? (int)*options->stop : 0;
}

int scene_interrupted(const im_scene_run_options *options, const char *where)
{
    return im_fail(IM_EINTERRUPTED, "interrupted by signal %d (%s) %s; finished results are kept: "
                   "run again with --resume to continue", scene_stop_signal(options),
                   strsignal(scene_stop_signal(options)), where);
}

/* One message to options->log, formatted here; calls from OpenMP workers are serialised, with the
 * progress calls too (the same critical section as ensemble.c's). */
static void scene_log(const im_scene_run_options *options, im_log_level level, const char *fmt, va_list args)
{
    if (!options->log || (level == IM_LOG_INFO && options->quiet))
        return;
    char message[2048];
    vsnprintf(message, sizeof message, fmt, args);
#pragma omp critical(scene_progress)
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
