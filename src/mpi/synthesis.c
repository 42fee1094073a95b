/* Surface synthesis over ranks: each rank fills its columns of the transposed half spectrum with
 * the mode-keyed generator, one FFTW-MPI c2r transform makes the rows, which then move to the
 * rows each rank asked for. */
#include "mpi/mpi_internal.h"
#include "core/args.h"

#include "core/fft_threads.h"
#include "indentmap/status.h"
#include "surface/synthesis.h"

#include <stdlib.h>

typedef struct spectral_slab {
    MPI_Comm comm;
    int nx, ny, half_nx;
    ptrdiff_t local_n0, local_0_start, local_n1, local_1_start;
    fftw_complex *modes; /* local_n1 x ny (transposed); in place, the real rows afterwards */
} spectral_slab;

/* How many modes of the full spectrum the stored column kx stands for (its conjugate partner). */
static double column_weight(int kx, int nx) { return kx == 0 || (nx % 2 == 0 && kx == nx / 2) ? 1.0 : 2.0; }

/* Fills this rank's columns; returns the sum over the full spectrum of weight |H|^2 (weight q^2
 * for a slope target, 1 for a height target), in column order whatever the ranks. */
static double fill_columns(const im_surface_params *p, const spectral_slab *slab, double *column_sums)
{
    const double qx_step = 2.0 * M_PI / (p->nx * p->delta), qy_step = 2.0 * M_PI / (p->ny * p->delta);
    const int slope = p->target == IM_TARGET_SLOPE;
#pragma omp parallel for schedule(static)
    for (ptrdiff_t c = 0; c < slab->local_n1; ++c) {
        int kx = (int)(slab->local_1_start + c);
        compensated sum = {0, 0};
        for (int jy = 0; jy < p->ny; ++jy) {
            int ky = jy <= p->ny / 2 ? jy : jy - p->ny;
            double complex h = surface_mode_coefficient(p, kx, ky, qx_step, qy_step);
            slab->modes[(size_t)c * p->ny + jy][0] = creal(h);
            slab->modes[(size_t)c * p->ny + jy][1] = cimag(h);
            double qx = kx * qx_step, qy = ky * qy_step;
            double weight = column_weight(kx, p->nx) * (slope ? qx * qx + qy * qy : 1.0);
            compensated_add(&sum, weight * (creal(h) * creal(h) + cimag(h) * cimag(h)));
        }
        column_sums[c] = compensated_total(&sum);
    }
    int ranks;
    MPI_Comm_size(slab->comm, &ranks);
    int mine[2] = {(int)slab->local_n1, (int)slab->local_1_start};
    int *counts = malloc(sizeof(int) * 2 * (size_t)ranks), *starts = counts + ranks;
    int *pairs = malloc(sizeof(int) * 2 * (size_t)ranks);
    double *all = malloc(sizeof(double) * (size_t)slab->half_nx);
    MPI_Allgather(mine, 2, MPI_INT, pairs, 2, MPI_INT, slab->comm);
    for (int r = 0; r < ranks; ++r) {
        counts[r] = pairs[2 * r];
        starts[r] = pairs[2 * r + 1];
    }
    MPI_Allgatherv(column_sums, (int)slab->local_n1, MPI_DOUBLE, all, counts, starts, MPI_DOUBLE, slab->comm);
    compensated total = {0, 0};
    for (int kx = 0; kx < slab->half_nx; ++kx)
        compensated_add(&total, all[kx]);
    free(counts);
    free(pairs);
    free(all);
    return compensated_total(&total);
}

static int check_request(const im_surface_params *p, int y0, int rows)
{
    int status = im_surface_params_check(p);
    if (status != IM_OK)
        return status;
    if (p->target == IM_TARGET_SLOPE && p->slope_definition == IM_SLOPE_FINITE_DIFFERENCE)
        return im_fail(IM_EINVAL, "slope definition: the distributed synthesis supports the spectral definition "
                                  "only (finite-difference slopes need the whole surface)");
    if (y0 < 0 || rows < 0 || y0 + rows > p->ny)
        return im_fail(IM_EINVAL, "rows [%d, %d): expected a range inside [0, %d)", y0, y0 + rows, p->ny);
    return IM_OK;
}

/* Transforms the filled slab and moves its rows, scaled by `scale`, to [y0, y0 + rows). */
static int transform_and_move(spectral_slab *slab, fftw_plan plan, double scale, int y0, int rows, double *heights)
{
    fftw_execute(plan);
    const double *real_rows = (const double *)slab->modes;
    const size_t stride = 2 * (size_t)slab->half_nx;
    int status = mpi_redistribute_rows(slab->comm, slab->nx, (int)slab->local_0_start, (int)slab->local_n0, real_rows,
                                       stride, y0, rows, heights);
    if (status == IM_OK) {
#pragma omp parallel for schedule(static)
        for (size_t i = 0; i < (size_t)rows * slab->nx; ++i)
            heights[i] *= scale;
    }
    return status;
}

int im_mpi_surface_generate(MPI_Comm comm, const im_surface_params *p, int y0, int rows, double *heights)
{
    ARG_REQUIRE(p, "params");
    ARG_REQUIRE(heights || rows == 0, "heights"); /* a rank may ask for no rows */
    int status = mpi_collective_status(comm, check_request(p, y0, rows));
    if (status != IM_OK)
        return status;
    spectral_slab slab = {.comm = comm, .nx = p->nx, .ny = p->ny, .half_nx = p->nx / 2 + 1};
    ptrdiff_t alloc_local = fftw_mpi_local_size_2d_transposed(p->ny, slab.half_nx, comm, &slab.local_n0,
                                                              &slab.local_0_start, &slab.local_n1,
                                                              &slab.local_1_start);
    slab.modes = fftw_alloc_complex((size_t)alloc_local + 1);
    double *column_sums = malloc(sizeof(double) * ((size_t)slab.local_n1 + 1));
    status = slab.modes && column_sums
                 ? IM_OK
                 : im_fail(IM_ENOMEM, "distributed synthesis of a %d x %d surface", p->nx, p->ny);
    status = mpi_collective_status(comm, status);
    fftw_plan plan = NULL;
    if (status == IM_OK) {
        fft_planner_lock();
        fft_prepare_planner();
        plan = fftw_mpi_plan_dft_c2r_2d(p->ny, p->nx, slab.modes, (double *)slab.modes, comm,
                                        FFTW_ESTIMATE | FFTW_MPI_TRANSPOSED_IN);
        fft_planner_unlock();
        status = mpi_collective_status(comm,
                                       plan ? IM_OK : im_fail(IM_ENOMEM, "FFTW-MPI could not plan the synthesis"));
    }
    if (status == IM_OK) {
        double current = sqrt(fill_columns(p, &slab, column_sums));
        double wanted = p->target == IM_TARGET_HEIGHT ? p->height_rms * p->delta : p->slope_rms;
        if (current > 0)
            status = transform_and_move(&slab, plan, wanted / current, y0, rows, heights);
        else
            status = im_fail(IM_EINVAL,
                             "no Fourier mode lies between lambda_s = %g and lambda_0 = %g on a %d x %d "
                             "grid: the surface would be flat",
                             p->lambda_s, fmax(p->lambda_0, p->lambda_r), p->nx, p->ny);
    }
    fft_planner_lock();
    if (plan)
        fftw_destroy_plan(plan);
    fft_planner_unlock();
    fftw_free(slab.modes);
    free(column_sums);
    return status;
}
