/* The OpenMP team beside a busy process (core/team_size.c), through every entry that solves: a solve
 * (im_solver_solve, and im_mpi_solver_solve on one rank under mpirun) and an indentation's steps and
 * fields (im_indentation_step twice, so that the second solves on its step box, im_indentation_fields,
 * im_indentation_fields_full; im_mpi_indentation_step). Each must leave the busy process a core: no parallel region of the library
 * runs with more threads than the free cpus. Before, the distributed solve chose no team, and a step's
 * own regions (its box, its window's passes) ran on all the cpus around the solve's choice, spinning in
 * libgomp's barriers for a thread that shared its core with the neighbour: `mpi-indent --n 256 --m 512` took
 * 4.3-6.4 s against 0.9-1.5 s on one thread, `indent` a 40-step history 0.24-0.40 s of CPU against one thread's 0.11-0.15 s
 * (docs/benchmarks.md, "Two threads against one").
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

static const double DEPTH = 3.0; /* touches the rough cone over many patches */

/* A rough cone on 128^2: its undeformed gap (the distributed solver's, on one rank the serial gap). */
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

enum entry { SERIAL_SOLVE, DISTRIBUTED_SOLVE, SERIAL_STEPS, DISTRIBUTED_STEPS, ENTRIES };
static const char *const ENTRY_NAMES[ENTRIES] = {"serial solve", "distributed solve", "serial steps and fields",
                                                 "distributed steps"};

/* What an entry needs made before the busy process starts: planning is not watched. */
typedef struct prepared {
    im_solver_plan *plan;
    im_indentation *steps;
    im_mpi_indentation *distributed_steps;
} prepared;

static prepared prepare(problem *p, enum entry e)
{
    im_solver_options o = im_solver_options_default();
    const im_indenter cone = im_indenter_cone(80);
    prepared made = {0};
    memset(p->pressure, 0, sizeof(double) * im_field_count(p->surface));
    if (e == SERIAL_SOLVE)
        check_status(im_solver_plan_create(p->surface->nx, p->surface->ny, 1.0, &o, &made.plan), "serial plan");
    if (e == SERIAL_STEPS)
        check_status(im_indentation_create(p->surface, &cone, IM_CONTROL_DISPLACEMENT, DEPTH, &o, &made.steps),
                     "serial indentation");
    if (e == DISTRIBUTED_STEPS)
        check_status(im_mpi_indentation_create(p->solver, p->surface->data, &cone, IM_CONTROL_DISPLACEMENT, DEPTH,
                                               NULL, &made.distributed_steps),
                     "distributed indentation");
    return made;
}

static int run_entry(problem *p, enum entry e, prepared *made)
{
    im_step_result step;
    im_field *force = NULL;
    int status = IM_OK;
    switch (e) {
    case SERIAL_SOLVE:
        return im_solver_solve(made->plan, p->gap0, IM_CONTROL_DISPLACEMENT, DEPTH, p->pressure, p->displacement,
                               NULL);
    case DISTRIBUTED_SOLVE:
        return im_mpi_solver_solve(p->solver, p->gap0, IM_CONTROL_DISPLACEMENT, DEPTH, p->pressure, p->displacement,
                                   NULL);
    case SERIAL_STEPS:
        for (double w = DEPTH / 2; w <= DEPTH && status == IM_OK; w += DEPTH / 2)
            status = im_indentation_step(made->steps, w, &step);
        if (status == IM_OK)
            status = im_indentation_fields(made->steps, &force, NULL, NULL);
        im_field_free(force);
        force = NULL;
        if (status == IM_OK) /* the whole grid's u: its own plan and convolution (frames, step files) */
            status = im_indentation_fields_full(made->steps, &force, NULL, NULL);
        im_field_free(force);
        return status;
    case DISTRIBUTED_STEPS:
        for (double w = DEPTH / 2; w <= DEPTH && status == IM_OK; w += DEPTH / 2)
            status = im_mpi_indentation_step(made->distributed_steps, w, &step);
        return status;
    default: return IM_EINVAL;
    }
}

/* The largest team of the regions an entry ran beside a busy process. */
static int team_of(problem *p, enum entry e)
{
    prepared made = prepare(p, e);
    const pid_t busy = start_busy_process();
    largest_team = 0;
    const int status = run_entry(p, e, &made);
    const int team = largest_team;
    stop_busy_process(busy);
    check_status(status, ENTRY_NAMES[e]);
    im_solver_plan_free(made.plan);
    im_indentation_free(made.steps);
    im_mpi_indentation_free(made.distributed_steps);
    return team;
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
    printf("largest team beside a busy process on %d cpus:", cpus);
    for (enum entry e = 0; e < ENTRIES; ++e) {
        const int team = team_of(&p, e);
        char detail[160];
        snprintf(detail, sizeof detail, "a region ran %d threads beside a busy process on %d cpus", team, cpus);
        check(team >= 1 && team <= cpus - 1, ENTRY_NAMES[e], detail);
        printf(" %s %d%s", ENTRY_NAMES[e], team, e + 1 < ENTRIES ? "," : "\n");
    }
    free_problem(&p);
    im_mpi_cleanup();
    MPI_Finalize();
    return 0;
}
