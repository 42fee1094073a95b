/* SIGINT and SIGTERM during long subcommands (run, indent): the first signal asks the work to
 * stop at its next check (between solver steps and between surfaces), so that finished results
 * are kept and no file is left half-written; a second one ends the process at once (its
 * temporary file, PATH.tmp.PID, may then remain). */
#include "cli/cli.h"

#include "indentmap/status.h"

#include <signal.h>
#include <string.h>
#include <unistd.h>

volatile sig_atomic_t cli_stop_signal = 0;

/* Async-signal-safe: stores the number and says so at once (a step may take minutes, and a
 * silent Ctrl-C reads as ignored), or restores the default action and re-raises it when the user
 * insists (a second signal while the first is being honoured). */
static void on_signal(int signal_number)
{
    static const char notice[] = "indentmap: stopping at the next safe point (finished results are kept); "
                                 "signal again to stop at once\n";
    if (cli_stop_signal) {
        signal(signal_number, SIG_DFL);
        raise(signal_number);
        return;
    }
    cli_stop_signal = signal_number;
    ssize_t written = write(STDERR_FILENO, notice, sizeof notice - 1);
    (void)written; /* nothing to do in a handler if stderr is gone */
}

int cli_interrupt_install(void)
{
    struct sigaction action;
    memset(&action, 0, sizeof action);
    action.sa_handler = on_signal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART; /* file writes in progress complete rather than fail with EINTR */
    cli_stop_signal = 0;
    im_set_stop_flag(&cli_stop_signal); /* file reads poll it too */
    /* A write past the file-size limit (ulimit -f) then fails with EFBIG and is reported, its
     * temporary file removed, instead of SIGXFSZ killing the process mid-write. */
    signal(SIGXFSZ, SIG_IGN);
    return sigaction(SIGINT, &action, NULL) == 0 && sigaction(SIGTERM, &action, NULL) == 0 ? 0 : -1;
}

int cli_interrupt_exit_status(void)
{
    return 128 + (int)cli_stop_signal;
}
