/* A program that uses indentmap's distributed-memory solver knowing it only through its installed headers
 * and library (indentmap/mpi.h includes <mpi.h>): a smooth cone indented over the ranks of MPI_COMM_WORLD
 * against Love's closed form. Exit 0 on every rank when the load is within 2% of it. */
#include <indentmap/indenter.h>
#include <indentmap/mpi.h>
#include <indentmap/solver.h>
#include <indentmap/status.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#if !IM_HAVE_MPI
#error "indentmap/mpi.h of a library built without MPI"
#endif

/* The load of a smooth 64 x 64 surface under the cone at approach w, over the ranks (the same on each). */
static int solve_smooth_cone(const im_indenter *cone, double w, double *load)
{
    const int n = 64;
    im_solver_options options = im_solver_options_default();
    im_mpi_solver *solver = NULL;
    im_mpi_indentation *run = NULL;
    int y0 = 0, rows = 0, status = im_mpi_solver_create(MPI_COMM_WORLD, n, n, 1.0, &options, &solver);
    if (status == IM_OK)
        im_mpi_solver_rows(solver, &y0, &rows);
    /* + 1: a rank may hold no rows; the cast: this file is also compiled as C++ (tests/install/cxx) */
    double *heights = (double *)calloc((size_t)rows * n + 1, sizeof *heights);
    if (status == IM_OK)
        status = heights ? im_mpi_indentation_create(solver, heights, cone, IM_CONTROL_DISPLACEMENT, w, NULL, &run)
                         : IM_ENOMEM;
    im_step_result step;
    if (status == IM_OK)
        status = im_mpi_indentation_step(run, w, &step);
    if (status == IM_OK)
        *load = step.load;
    else
        fprintf(stderr, "consumer_mpi: %s\n", im_last_error());
    im_mpi_indentation_free(run);
    im_mpi_solver_free(solver);
    free(heights);
    return status;
}

int main(int argc, char **argv)
{
    int provided = 0, rank = 0, ranks = 0;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    im_mpi_init();
    const double w = 2.0;
    im_indenter cone = im_indenter_cone(80.0);
    double load = NAN;
    int ok = provided >= MPI_THREAD_FUNNELED && solve_smooth_cone(&cone, w, &load) == IM_OK;
    const double love = im_indenter_load(&cone, 1.0, w), error = fabs(load / love - 1.0);
    ok = ok && error < 0.02;
    if (rank == 0)
        printf("indentmap over %d ranks: N = %.6g, Love %.6g, relative error %.2e\n", ranks, load, love, error);
    im_mpi_cleanup();
    MPI_Finalize();
    return ok ? 0 : 1;
}
