/* Benchmark of the distributed solver (not a test); run under mpirun (bench/run_mpi.sh):
 *
 *   mpirun -n K bench_mpi NX NY [REPEATS]
 *
 * For one NX x NY rough surface (distributed synthesis, H = 0.8, lambda_s = 4, lambda_r = min
 * side, h'rms = 0.08, seed 1) and an 80 degree cone pressed to a contact radius of about NX/4
 * (displacement control, tol 1e-8), prints on rank 0 one line of key=value pairs:
 *   ranks, threads, nx, ny;
 *   model_mib: im_mpi_solver_bytes for the largest rank; rss_mib: the largest rank's peak RSS
 *     growth over its RSS before planning (ru_maxrss, which includes FFTW-MPI's transpose
 *     buffers and MPI's own); rss_total_mib: the largest peak RSS itself;
 *   convolution_s: median over REPEATS (default 5) of one distributed convolution (2 FFTs and
 *     2 all-to-all transposes), alltoall_s: median of an MPI_Alltoall moving the same volume as
 *     one transpose of the padded spectrum (16 (nx + 1) 2 ny bytes in all), fft_s: median of the
 *     same pair of transforms on one rank's share done serially, without communication (the
 *     local compute rate: a (2nx x 2ny/K) r2c then c2r pair, FFTW_ESTIMATE); the _cpu_s values
 *     are the same medians in CPU seconds of the slowest rank (process user + system time);
 *   iterations, convolutions, solve_wall_s, solve_cpu_s (user + system time summed over ranks),
 *     load, contact (the same for every K).
 * Wall times on a shared machine are noisy: CPU times are printed beside them. */
#include "indentmap/mpi.h"

#include <stdio.h>

#if IM_HAVE_MPI

#include "indentmap/status.h"

#include <fftw3.h>
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#define MAX_REPEATS 31

static void die(int status, const char *what)
{
    fprintf(stderr, "bench_mpi: %s: %s (%s)\n", what, im_last_error(), im_strstatus(status));
    MPI_Abort(MPI_COMM_WORLD, 1);
}

static double peak_rss_mib(void)
{
    struct rusage usage;
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_maxrss / 1024.0;
}

static double cpu_seconds(void)
{
    struct rusage usage;
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_utime.tv_sec + usage.ru_stime.tv_sec + 1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, compare_doubles);
    return v[n / 2];
}

static double max_over_ranks(double v)
{
    MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    return v;
}

/* Median seconds (slowest rank) of one distributed convolution; *cpu: its median CPU seconds. */
static double time_convolution(im_mpi_solver *solver, const double *p, double *u, int repeats, double *cpu)
{
    double t[MAX_REPEATS], c[MAX_REPEATS];
    for (int k = 0; k < repeats; ++k) {
        MPI_Barrier(MPI_COMM_WORLD);
        double start = MPI_Wtime(), cpu_start = cpu_seconds();
        im_mpi_convolve(solver, p, u);
        t[k] = max_over_ranks(MPI_Wtime() - start);
        c[k] = max_over_ranks(cpu_seconds() - cpu_start);
    }
    *cpu = median(c, repeats);
    return median(t, repeats);
}

/* Median seconds of an all-to-all moving one transpose's volume: 16 (nx + 1) 2ny bytes in all. */
static double time_alltoall(int nx, int ny, int ranks, int repeats)
{
    size_t total = 2 * ((size_t)nx + 1) * 2 * (size_t)ny; /* doubles */
    size_t block = total / ((size_t)ranks * ranks) + 1;   /* per pair of ranks */
    double *send = calloc(block * ranks, sizeof(double)), *recv = calloc(block * ranks, sizeof(double));
    double t[MAX_REPEATS];
    for (int k = 0; k < repeats; ++k) {
        MPI_Barrier(MPI_COMM_WORLD);
        double start = MPI_Wtime();
        MPI_Alltoall(send, (int)block, MPI_DOUBLE, recv, (int)block, MPI_DOUBLE, MPI_COMM_WORLD);
        t[k] = max_over_ranks(MPI_Wtime() - start);
    }
    free(send);
    free(recv);
    return median(t, repeats);
}

/* Median seconds of one rank's share of the padded transforms done locally: a 2nx x (2ny / K)
 * r2c then c2r pair (the row and column work of a convolution without its exchanges). */
static double time_local_fft(int nx, int ny, int ranks, int repeats, double *cpu)
{
    int rows = (2 * ny + ranks - 1) / ranks;
    double *real = fftw_alloc_real((size_t)rows * 2 * ((size_t)nx + 1));
    fftw_complex *modes = fftw_alloc_complex((size_t)rows * ((size_t)nx + 1));
    fftw_plan_with_nthreads(omp_get_max_threads());
    fftw_plan forward = fftw_plan_dft_r2c_2d(rows, 2 * nx, real, modes, FFTW_ESTIMATE);
    fftw_plan backward = fftw_plan_dft_c2r_2d(rows, 2 * nx, modes, real, FFTW_ESTIMATE);
    memset(real, 0, sizeof(double) * (size_t)rows * 2 * ((size_t)nx + 1));
    double t[MAX_REPEATS], c[MAX_REPEATS];
    for (int k = 0; k < repeats; ++k) {
        MPI_Barrier(MPI_COMM_WORLD);
        double start = MPI_Wtime(), cpu_start = cpu_seconds();
        fftw_execute(forward);
        fftw_execute(backward);
        t[k] = max_over_ranks(MPI_Wtime() - start);
        c[k] = max_over_ranks(cpu_seconds() - cpu_start);
    }
    *cpu = median(c, repeats);
    fftw_destroy_plan(forward);
    fftw_destroy_plan(backward);
    fftw_free(real);
    fftw_free(modes);
    return median(t, repeats);
}

static void run(int nx, int ny, int repeats)
{
    int rank, ranks;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    const double rss_before = peak_rss_mib();
    im_solver_options options = im_solver_options_default();
    options.tol = 1e-8; /* the tolerance these figures were measured at (the default is 1e-6) */
    im_mpi_solver *solver;
    int status = im_mpi_solver_create(MPI_COMM_WORLD, nx, ny, 1.0, &options, &solver);
    if (status != IM_OK)
        die(status, "plan");
    int y0, rows;
    im_mpi_solver_rows(solver, &y0, &rows);
    size_t n = (size_t)rows * nx + 1;
    double *heights = malloc(sizeof(double) * n), *gap0 = malloc(sizeof(double) * n);
    double *p = calloc(n, sizeof(double)), *u = malloc(sizeof(double) * n);
    im_surface_params params = im_surface_params_default();
    params.nx = nx;
    params.ny = ny;
    params.lambda_r = nx < ny ? nx : ny;
    im_indenter cone = im_indenter_cone(80);
    if ((status = im_mpi_surface_generate(MPI_COMM_WORLD, &params, y0, rows, heights)) != IM_OK)
        die(status, "synthesis");
    if ((status = im_mpi_undeformed_gap(solver, heights, &cone, gap0)) != IM_OK)
        die(status, "gap");
    const double w = 0.25 * nx * M_PI / tan(80 * M_PI / 180) / 2; /* smooth contact radius nx/4 */
    double cpu_start = cpu_seconds();
    im_solve_result result;
    if ((status = im_mpi_solver_solve(solver, gap0, IM_CONTROL_DISPLACEMENT, w, p, u, &result)) != IM_OK)
        die(status, "solve");
    double cpu = cpu_seconds() - cpu_start;
    MPI_Allreduce(MPI_IN_PLACE, &cpu, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
    double convolution_cpu, fft_cpu;
    double convolution = time_convolution(solver, p, u, repeats, &convolution_cpu);
    double rss_peak = max_over_ranks(peak_rss_mib()), rss_growth = max_over_ranks(peak_rss_mib() - rss_before);
    double alltoall = time_alltoall(nx, ny, ranks, repeats), fft = time_local_fft(nx, ny, ranks, repeats, &fft_cpu);
    if (rank == 0)
        printf("ranks=%d threads=%d nx=%d ny=%d model_mib=%.1f rss_mib=%.1f rss_total_mib=%.1f convolution_s=%.4g "
               "convolution_cpu_s=%.4g alltoall_s=%.4g fft_s=%.4g fft_cpu_s=%.4g iterations=%d convolutions=%d "
               "solve_wall_s=%.4g solve_cpu_s=%.4g "
               "load=%.10g contact=%ld\n",
               ranks, omp_get_max_threads(), nx, ny, im_mpi_solver_bytes(nx, ny, ranks) / 1048576.0, rss_growth,
               rss_peak, convolution, convolution_cpu, alltoall, fft, fft_cpu, result.iterations, result.convolutions,
               result.seconds, cpu, result.load, result.contact_patches);
    im_mpi_solver_free(solver);
    free(heights);
    free(gap0);
    free(p);
    free(u);
}

int main(int argc, char **argv)
{
    int provided;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    im_mpi_init();
    if (argc < 3) {
        fprintf(stderr, "usage: mpirun -n K bench_mpi NX NY [REPEATS]\n");
        MPI_Abort(MPI_COMM_WORLD, 2);
    }
    int repeats = argc > 3 ? atoi(argv[3]) : 5;
    repeats = repeats < 1 ? 1 : repeats > MAX_REPEATS ? MAX_REPEATS : repeats;
    run(atoi(argv[1]), atoi(argv[2]), repeats);
    im_mpi_cleanup();
    MPI_Finalize();
    return 0;
}

#else

int main(void)
{
    fprintf(stderr, "bench_mpi: this build has no MPI (configure with IM_MPI=ON)\n");
    return 77;
}

#endif
