/* The library's log lines and progress, printed on stderr as the indentmap program shows them. */
#include "cli/cli.h"

#include "indentmap/io.h"

#include <stdio.h>
#include <unistd.h>

void cli_log(void *user, im_log_level level, const char *message)
{
    (void)user;
    (void)level; /* quiet runs get no IM_LOG_INFO lines from the library: what comes is printed */
    fprintf(stderr, "indentmap: %s\n", message);
}

void cli_progress(void *user, const char *stage, int done, int total)
{
    (void)user;
    (void)stage; /* the stage's own line follows the bar */
    if (!isatty(STDERR_FILENO))
        return;
    enum { WIDTH = 40 };
    char bar[WIDTH + 1];
    int filled = done * WIDTH / total;
    for (int i = 0; i < WIDTH; ++i)
        bar[i] = i < filled ? '#' : '.';
    bar[WIDTH] = '\0';
    fprintf(stderr, "\r[%s] %d/%d surfaces", bar, done, total);
    if (done == total)
        fputc('\n', stderr);
    fflush(stderr);
}

void cli_warn_stale_lock(const im_folder_lock *lock)
{
    if (lock->stale_pid > 0) /* a warning, shown even with --quiet */
        fprintf(stderr, "indentmap: taking over the stale lock %s of pid %ld, which no longer runs\n", lock->path,
                lock->stale_pid);
}
