/* A solve's OpenMP team beside a busy process (core/team_size.c), through every solve entry: the serial
 * im_solver_solve and the distributed im_mpi_solver_solve (one rank, under mpirun). Each must leave the
 * busy process a core: no parallel region of the library runs with more threads than the free cpus.
 * Before the distributed solve chose its team it ran on all the cpus, spinning in libgomp's barriers
 * for a thread that shared its core with the neighbour: `mpi-indent --n 256` took 4.5 s against 1.1 s
 * on one thread beside two busy processes on 2 cores (docs/benchmarks.md, "Two threads against one").
 *
 * The regions are watched by wrapping libgomp's entry (the link's --wrap=GOMP_parallel, which reaches
 * the static library's objects): a region asked for no particular count runs the calling thread's
 * nthreads-var, which is what team_size.c sets. Prints one line for tests/mpi/mpi_solver.sh. */
#include "mpi_check.h"

#include "indentmap/solver.h"
#include "indentmap/surface.h"

#include <omp.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

void __real_GOMP_parallel(void (*fn)(void *), void *data, unsigned threads, unsigned flags);

static int largest_team; /* over the regions since the last reset */

void __wrap_GOMP_parallel(void (*fn)(void *), void *data, unsigned threads, unsigned flags)
{
    const int asked = omp_get_max_threads();
    const int team = threads == 0 || (int)threads > asked ? asked : (int)threads;
    if (team > largest_team)
        largest_team = team;
    __real_GOMP_parallel(fn, data, threads, flags);
}

/* A child process that spins until it is killed. */
static pid_t start_busy_process(void)
{
    pid_t child = fork();
    check(child >= 0, "fork", "a busy process");
    if (child == 0)
        for (volatile unsigned long spin = 0;; ++spin)
            ;
    nanosleep(&(struct timespec){0, 150000000}, NULL); /* until it runs, and any look is older than 0.1 s */
    return child;
}

static void stop_busy_process(pid_t child)
{
    kill(child, SIGKILL);
    waitpid(child, NULL, 0);
}

typedef struct problem {
    im_field *surface;
    im_mpi_solver *solver; /* one rank: all the rows */
    double *gap0, *pressure, *displacement;
} problem;

/* A rough cone's undeformed gap on 128^2 (the distributed solver's, the same on one rank as the serial
 * gap); a depth of 3 touches over many patches. */
static problem rough_cone(void)
{
    im_surface_params params = im_surface_params_default();
    params.nx = params.ny = 128;
    params.lambda_r = 128;
    params.seed = 7;
    problem p = {0};
    check_status(im_surface_generate(&params, &p.surface), "synthesis");
    im_solver_options o = im_solver_options_default();
    check_status(im_mpi_solver_create(MPI_COMM_WORLD, params.nx, params.ny, 1.0, &o, &p.solver), "distributed plan");
    const size_t n = im_field_count(p.surface);
    p.gap0 = malloc(sizeof(double) * n);
    p.pressure = malloc(sizeof(double) * n);
    p.displacement = malloc(sizeof(double) * n);
    check(p.gap0 && p.pressure && p.displacement, "memory", "the problem's fields");
    const im_indenter cone = im_indenter_cone(80);
    check_status(im_mpi_undeformed_gap(p.solver, p.surface->data, &cone, p.gap0), "undeformed gap");
    return p;
}

static void free_problem(problem *p)
{
    im_mpi_solver_free(p->solver);
    im_field_free(p->surface);
    free(p->gap0);
    free(p->pressure);
    free(p->displacement);
}

/* The largest team of the regions a cold solve ran beside a busy process, serially or over the rank. */
static int team_of_solve(problem *p, int distributed)
{
    im_solver_options o = im_solver_options_default();
    im_solver_plan *plan = NULL;
    if (!distributed)
        check_status(im_solver_plan_create(p->surface->nx, p->surface->ny, 1.0, &o, &plan), "serial plan");
    memset(p->pressure, 0, sizeof(double) * im_field_count(p->surface));
    const pid_t busy = start_busy_process();
    largest_team = 0;
    const int status = distributed ? im_mpi_solver_solve(p->solver, p->gap0, IM_CONTROL_DISPLACEMENT, 3.0,
                                                         p->pressure, p->displacement, NULL)
                                   : im_solver_solve(plan, p->gap0, IM_CONTROL_DISPLACEMENT, 3.0, p->pressure,
                                                     p->displacement, NULL);
    const int team = largest_team;
    stop_busy_process(busy);
    check_status(status, distributed ? "distributed solve" : "serial solve");
    im_solver_plan_free(plan);
    return team;
}

static void check_team(const char *entry, int team, int cpus)
{
    char detail[160];
    snprintf(detail, sizeof detail, "a region ran %d threads beside a busy process on %d cpus", team, cpus);
    check(team >= 1 && team <= cpus - 1, entry, detail);
}

int main(int argc, char **argv)
{
    mpi_test_start(&argc, &argv);
    int ranks;
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    check(ranks == 1, "one rank", "run with mpirun -n 1 (the busy process must be the only other)");
    const int cpus = (int)sysconf(_SC_NPROCESSORS_ONLN);
    if (cpus < 2 || omp_get_num_procs() < cpus) { /* bound to some cpus: the rule keeps the count */
        printf("team skipped: %d cpus, %d usable\n", cpus, omp_get_num_procs());
        im_mpi_cleanup();
        MPI_Finalize();
        return 77; /* ctest's skip */
    }
    unsetenv("OMP_NUM_THREADS"); /* the user's choice, which the team would keep: none here */
    unsetenv("OMP_WAIT_POLICY");
    omp_set_num_threads(cpus);
    problem p = rough_cone();
    const int serial = team_of_solve(&p, 0), distributed = team_of_solve(&p, 1);
    check_team("serial solve", serial, cpus);
    check_team("distributed solve", distributed, cpus);
    printf("team beside a busy process: serial %d, distributed %d, of %d cpus\n", serial, distributed, cpus);
    free_problem(&p);
    im_mpi_cleanup();
    MPI_Finalize();
    return 0;
}
