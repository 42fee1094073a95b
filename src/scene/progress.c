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

void scene_progress(const im_scene_run_options *options, const char *fmt, ...)
{
    if (options->quiet)
        return;
    va_list args;
    va_start(args, fmt);
    fputs("indentmap: ", stderr);
    vfprintf(stderr, fmt, args);
    fputc('\n', stderr);
    va_end(args);
}
