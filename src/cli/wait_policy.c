/* The OpenMP wait policy of the command line (see cli.h). */
#include "cli/cli.h"

#include <stdlib.h>
#include <unistd.h>

/* libgomp reads OMP_WAIT_POLICY once, when it is loaded, and by default spins at every barrier
 * for a while before sleeping. On a machine whose cores are shared (other jobs, a laptop's
 * desktop), a spinning thread holds a core that the thread it waits for needs: measured on 2 cores
 * with one competing busy process, the paper's fig4 scene took 43 s spinning against 17.7 s with
 * passive waiting (docs/benchmarks.md). The solver's parallel regions are long (whole-grid passes
 * and FFTs), so sleeping at their ends costs little on an idle machine. The policy can only be set
 * before libgomp loads, hence the one re-execution. */
void cli_prefer_passive_waiting(char **argv)
{
    if (getenv("OMP_WAIT_POLICY") || getenv("GOMP_SPINCOUNT"))
        return; /* the user's choice */
    if (setenv("OMP_WAIT_POLICY", "passive", 1) != 0)
        return;
    execv("/proc/self/exe", argv);
    /* exec failed (no /proc, say): carry on with the default policy; the variable set above only
     * tells libgomp's children, which read their environment afresh */
    unsetenv("OMP_WAIT_POLICY");
}
