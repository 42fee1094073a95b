/* The cascade start over ranks (solver.h, "Cascade"): the coarse levels are small, so every rank
 * holds them whole and solves them alike on the serial CPU engine; only the restriction of the fine
 * gap and the prolongation of the coarse pressure touch the ranks' rows. The coarse grid sees the
 * serial plan's numbers to the bit (solver/cascade.c's pair sums and block means; each block's upper
 * and lower pair sums are summed over ranks with zeros from every rank but the row's owner, which
 * is exact), and the coarse solves run on one thread (the CPU engine's OpenMP reductions depend on
 * the thread count): the start is the same for any rank or thread count, and the fine iteration
 * then takes the serial solver's path. */
#include "mpi/mpi_internal.h"

#include "indentmap/status.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

/* The coarse plan's options: the serial cascade's, on the CPU, without wisdom or a stop flag (each
 * rank would read its own flag mid-way: the fine solve reads it for all, right after). */
static im_solver_options coarse_options(const im_mpi_solver *s)
{
    im_solver_options o = solver_cascade_options(&s->plan.options);
    o.device = IM_DEVICE_CPU;
    o.wisdom_path = NULL;
    o.stop = NULL;
    return o;
}

static int create_level(im_mpi_solver *s, int cx, int cy)
{
    const size_t n = (size_t)cx * cy;
    s->coarse_gap0 = malloc(sizeof(double) * n);
    s->coarse_pressure = malloc(sizeof(double) * n);
    s->coarse_displacement = malloc(sizeof(double) * n);
    s->coarse_sums = malloc(sizeof(double) * 4 * n);
    if (!s->coarse_gap0 || !s->coarse_pressure || !s->coarse_displacement || !s->coarse_sums)
        return im_fail(IM_ENOMEM, "distributed solver %d x %d: rank %d's cascade level %d x %d", s->nx, s->ny,
                       s->rank, cx, cy);
    const im_solver_options o = coarse_options(s);
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1); /* the coarse plans' FFTW threads too */
    int status = solver_plan_create_level(cx, cy, 2 * s->delta, &o, NULL, &s->coarse);
    omp_set_num_threads(threads);
    return status;
}

int mpi_cascade_create(im_mpi_solver *s)
{
    int cx, cy;
    if (!s->plan.options.cascade || !solver_cascade_sides(s->nx, s->ny, s->plan.options.periodic, &cx, &cy))
        return IM_OK;
    return mpi_collective_status(s->comm, create_level(s, cx, cy));
}

void mpi_cascade_free(im_mpi_solver *s)
{
    im_solver_plan_free(s->coarse);
    free(s->coarse_gap0);
    free(s->coarse_pressure);
    free(s->coarse_displacement);
    free(s->coarse_sums);
}

/* The solver and whether the coarse gaps are summed. */
typedef struct coarse_means {
    const im_mpi_solver *solver;
    int summed;
} coarse_means;

/* The coarse gaps of [lo, hi) from their blocks' sums (restrict_gap's layout), and when summed their sum,
 * taken while they are in cache (summation.h: sum_ranges; else 0). */
static double block_means(size_t lo, size_t hi, const void *context)
{
    const coarse_means *means = context;
    const im_mpi_solver *s = means->solver;
    const size_t m = (size_t)s->coarse->nx * s->coarse->ny;
    const double *sums = s->coarse_sums;
    for (size_t k = lo; k < hi; ++k)
        s->coarse_gap0[k] = solver_cascade_block_mean(sums[k], sums[m + k], (int)(sums[2 * m + k] + sums[3 * m + k]));
    return means->summed ? sum_doubles_range(s->coarse_gap0, lo, hi) : 0;
}

/* The coarse gap on every rank: each block's upper and lower pair sums and counts (layout: 4 arrays
 * of cx cy), from the rows' owners, summed over ranks; its mean where the coarse level's periodic
 * approach is checked (else NaN), summed as the serial cascade sums it. */
static double restrict_gap(im_mpi_solver *s, const double *gap0, enum im_control control)
{
    const int cx = s->coarse->nx;
    const size_t m = (size_t)cx * s->coarse->ny;
    double *sums = s->coarse_sums;
    memset(sums, 0, sizeof(double) * 4 * m);
#pragma omp parallel for schedule(static)
    for (int row = 0; row < s->rows; ++row) {
        const int y = s->y0 + row, lower = y % 2;
        for (int c = 0; c < cx; ++c) {
            const size_t k = (size_t)(y / 2) * cx + c;
            int count;
            solver_cascade_pair_sum(gap0 + (size_t)row * s->nx, s->nx, c, &sums[lower * m + k], &count);
            sums[(2 + lower) * m + k] = count;
        }
    }
    MPI_Allreduce(MPI_IN_PLACE, sums, (int)(4 * m), MPI_DOUBLE, MPI_SUM, s->comm);
    const coarse_means means = {s, solver_periodic_approach_checked(s->coarse, control)};
    const double sum = sum_ranges(m, block_means, &means);
    return means.summed ? sum / (double)m : NAN;
}

/* This rank's rows of the fine start; whether any rank's is loaded. */
static int prolong_pressure(const im_mpi_solver *s, const double *gap0, double *pressure)
{
    int loaded = 0;
#pragma omp parallel for schedule(static) reduction(| : loaded)
    for (int row = 0; row < s->rows; ++row)
        loaded |= solver_cascade_prolong_row(s->coarse_pressure + (size_t)((s->y0 + row) / 2) * s->coarse->nx,
                                             gap0 + (size_t)row * s->nx, s->nx, pressure + (size_t)row * s->nx);
    MPI_Allreduce(MPI_IN_PLACE, &loaded, 1, MPI_INT, MPI_LOR, s->comm);
    return loaded;
}

int mpi_cascade_start(im_mpi_solver *s, const double *gap0, enum im_control control, double target, double *pressure)
{
    const double mean_gap0 = restrict_gap(s, gap0, control);
    int usable;
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    int iterations = solver_cascade_solve(s->coarse, s->coarse_gap0, mean_gap0, control, target, s->coarse_pressure,
                                          s->coarse_displacement, &usable);
    omp_set_num_threads(threads);
    if (!usable || !prolong_pressure(s, gap0, pressure))
        memset(pressure, 0, sizeof(double) * (size_t)s->rows * s->nx);
    return iterations;
}
