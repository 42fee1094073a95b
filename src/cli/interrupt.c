/* SIGINT and SIGTERM. During long subcommands (run, indent) the first signal asks the work to stop
 * at its next check (between solver steps and between surfaces), so that finished results are kept
 * and no file is left half-written; a second one ends the process at once. Elsewhere (render,
 * surface) the first one ends it. Either way the temporary files being written are removed first
 * (io.h: im_atomic_remove_temporaries), so no "*.im.tmp.*" file is left behind. */
#include "cli/cli.h"

#include "indentmap/io.h"
#include "indentmap/status.h"

#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

volatile sig_atomic_t cli_stop_signal = 0;

/* Async-signal-safe: removes the files being written, then dies of the signal. */
static void end_by_signal(int signal_number)
{
    im_atomic_remove_temporaries();
    signal(signal_number, SIG_DFL);
    raise(signal_number);
}

/* Async-signal-safe: stores the number and says so at once (a step may take minutes, and a
 * silent Ctrl-C reads as ignored), or ends the process when the user insists (a second signal while
 * the first is being honoured). */
static void on_signal(int signal_number)
{
    static const char notice[] = "indentmap: stopping at the next safe point (finished results are kept); "
                                 "signal again to stop at once\n";
    if (cli_stop_signal) {
        end_by_signal(signal_number);
        return;
    }
    cli_stop_signal = signal_number;
    ssize_t written = write(STDERR_FILENO, notice, sizeof notice - 1);
    (void)written; /* nothing to do in a handler if stderr is gone */
}

static int install(void (*handler)(int), int flags)
{
    struct sigaction action;
    memset(&action, 0, sizeof action);
    action.sa_handler = handler;
    sigemptyset(&action.sa_mask);
    action.sa_flags = flags;
    cli_stop_signal = 0;
    im_set_stop_flag(&cli_stop_signal); /* file reads poll it too */
    /* A write past the file-size limit (ulimit -f) then fails with EFBIG and is reported, its
     * temporary file removed, instead of SIGXFSZ killing the process mid-write. */
    signal(SIGXFSZ, SIG_IGN);
    return sigaction(SIGINT, &action, NULL) == 0 && sigaction(SIGTERM, &action, NULL) == 0 &&
                   sigaction(SIGHUP, &action, NULL) == 0
               ? 0
               : -1;
}

/* SA_RESTART: a read or write of a pipe or terminal in progress completes rather than fails with EINTR. */
int cli_interrupt_install(void) { return install(on_signal, SA_RESTART); }

/* Without SA_RESTART: mpirun signalled itself stops reading its ranks' output and kills them a timeout after
 * passing the signal on; a write blocked on that full pipe must return EINTR for the work to stop and be
 * recorded in time (docs/mpi.md). Writes to regular files are not interrupted by a caught signal on Linux. */
int cli_interrupt_install_unrestarted(void) { return install(on_signal, 0); }

int cli_interrupt_install_cleanup(void) { return install(end_by_signal, SA_RESTART); }

int cli_interrupt_report(int reporting)
{
    if (reporting)
        fprintf(stderr, "indentmap: %s\n", im_last_error());
    return 128 + (int)cli_stop_signal;
}
