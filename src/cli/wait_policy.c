/* The OpenMP wait policy of the command line (see cli.h). */
#include "cli/cli.h"

#include <stdlib.h>
#include <unistd.h>

/* libgomp reads its wait policy once, when it is loaded, and by default spins 300000 times at
 * every barrier before sleeping. On a machine whose cores are shared (other jobs, a laptop's
 * desktop), a spinning thread holds a core that the thread it waits for needs: measured on 2 cores
 * with one competing busy process, the paper's fig4 scene took 43 s spinning against 17.7 s with
 * passive waiting (spin count 0). But sleeping at once makes every barrier a futex wake-up, and a
 * solver iteration has about twenty: a 512 x 512 solve on two threads took 0.36 s passive against
 * 0.27 s on one. A short spin (3000) keeps most wake-ups off the kernel on an idle machine (0.21 s
 * on two threads) and costs little beside a busy process (fig4 1.11x the passive time); the
 * figures are in docs/benchmarks.md. The count can only be set before libgomp loads, hence the one
 * re-execution. */
void cli_prefer_short_spinning(char **argv)
{
    if (getenv("OMP_WAIT_POLICY") || getenv("GOMP_SPINCOUNT"))
        return; /* the user's choice */
    if (setenv("GOMP_SPINCOUNT", CLI_SPIN_COUNT, 1) != 0)
        return;
    execv("/proc/self/exe", argv);
    /* exec failed (no /proc, say): carry on with the default spin count; the variable set above only
     * tells libgomp's children, which read their environment afresh */
    unsetenv("GOMP_SPINCOUNT");
}
