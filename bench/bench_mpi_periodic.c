/* Benchmark of nominally flat contact over ranks against the serial solver (not a test; run under
 * mpirun, bench/run_mpi_periodic.sh):
 *
 *   mpirun -n K bench_mpi_periodic N P_M CASCADE
 *
 * One periodic N x N rough cell (distributed synthesis, H = 0.8, lambda_s = 4, lambda_r = N,
 * h'rms = 0.08, seed 1) under the mean pressure P_M (units of E*), tol 1e-8, the cascade start on
 * (CASCADE 1) or off (0). Prints on rank 0 one line of key=value pairs for the distributed solve
 * (im_mpi_flat_contact): engine=mpi, ranks, threads, n, cascade, iterations (fine grid), wall_s
 * (the solve's own time, coarse levels included), approach, area_fraction; and with one rank a second line for the
 * serial solve of the same cell (im_flat_contact, engine=cpu), done after it. */
#include "indentmap/mpi.h"

#include <stdio.h>

#if IM_HAVE_MPI

#include "indentmap/status.h"

#include <omp.h>
#include <stdlib.h>

static void die(int status, const char *what)
{
    fprintf(stderr, "bench_mpi_periodic: %s: %s (%s)\n", what, im_last_error(), im_strstatus(status));
    MPI_Abort(MPI_COMM_WORLD, 1);
}

static void report(const char *engine, int ranks, int n, const im_solver_options *o, const im_flat_result *r,
                   double seconds)
{
    printf("engine=%s ranks=%d threads=%d n=%d cascade=%d iterations=%d wall_s=%.4g approach=%.12g "
           "area_fraction=%.6g\n",
           engine, ranks, omp_get_max_threads(), n, o->cascade, r->iterations, seconds, r->approach,
           r->area_fraction);
}

/* The serial solve of the whole cell (one rank: its rows are the cell). */
static void serial(int n, const double *heights, double mean_pressure, const im_solver_options *o)
{
    im_field surface = {.nx = n, .ny = n, .delta = 1.0, .data = (double *)heights};
    im_flat_contact *run;
    im_flat_result r;
    int status = im_flat_contact_create(&surface, o, &run);
    double start = omp_get_wtime();
    if (status != IM_OK || (status = im_flat_contact_solve(run, mean_pressure, &r)) != IM_OK)
        die(status, "serial solve");
    report("cpu", 1, n, o, &r, omp_get_wtime() - start);
    im_flat_contact_free(run);
}

static void run(int n, double mean_pressure, int cascade)
{
    int rank, ranks;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    im_solver_options o = im_solver_options_default();
    o.tol = 1e-8;
    o.periodic = 1;
    o.cascade = cascade;
    im_mpi_solver *solver;
    int status = im_mpi_solver_create(MPI_COMM_WORLD, n, n, 1.0, &o, &solver);
    if (status != IM_OK)
        die(status, "plan");
    int y0, rows;
    im_mpi_solver_rows(solver, &y0, &rows);
    double *heights = malloc(sizeof(double) * ((size_t)rows * n + 1));
    im_surface_params params = im_surface_params_default();
    params.nx = params.ny = n;
    params.lambda_r = n;
    if ((status = im_mpi_surface_generate(MPI_COMM_WORLD, &params, y0, rows, heights)) != IM_OK)
        die(status, "synthesis");
    im_mpi_flat_contact *run;
    if ((status = im_mpi_flat_contact_create(solver, heights, &run)) != IM_OK)
        die(status, "flat contact");
    im_flat_result r;
    MPI_Barrier(MPI_COMM_WORLD);
    double start = MPI_Wtime();
    if ((status = im_mpi_flat_contact_solve(run, mean_pressure, &r)) != IM_OK)
        die(status, "solve");
    double seconds = MPI_Wtime() - start;
    MPI_Allreduce(MPI_IN_PLACE, &seconds, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    if (rank == 0)
        report("mpi", ranks, n, &o, &r, seconds);
    im_mpi_flat_contact_free(run);
    im_mpi_solver_free(solver);
    if (ranks == 1)
        serial(n, heights, mean_pressure, &o);
    free(heights);
}

int main(int argc, char **argv)
{
    int provided;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    im_mpi_init();
    if (argc < 4) {
        fprintf(stderr, "usage: mpirun -n K bench_mpi_periodic N P_M CASCADE\n");
        MPI_Abort(MPI_COMM_WORLD, 2);
    }
    run(atoi(argv[1]), atof(argv[2]), atoi(argv[3]));
    im_mpi_cleanup();
    MPI_Finalize();
    return 0;
}

#else

int main(void)
{
    fprintf(stderr, "bench_mpi_periodic: this build has no MPI (IM_MPI=OFF)\n");
    return 77;
}

#endif
