/* Surface synthesis: time and peak memory for one size, as a CSV row.
 *   bench_surface N [REPEATS]     (threads from OMP_NUM_THREADS)
 * Floor: one c2r transform of the same size, the least a spectral synthesis can cost.
 * bench/run_surface.sh runs it from 512^2 to 8192^2 at 1 and 2 threads, one process per size so
 * that the peak memory is that size's own. */
#include "bench_common.h"

#include "indentmap/status.h"
#include "indentmap/surface.h"

#include <fftw3.h>
#include <omp.h>
#include <stdio.h>

static double time_c2r_floor(int n)
{
    fftw_complex *in = fftw_alloc_complex((size_t)n * (size_t)(n / 2 + 1));
    double *out = fftw_alloc_real((size_t)n * (size_t)n);
    fftw_plan_with_nthreads(omp_get_max_threads());
    fftw_plan plan = fftw_plan_dft_c2r_2d(n, n, in, out, FFTW_ESTIMATE);
    for (size_t i = 0; i < (size_t)n * (size_t)(n / 2 + 1); ++i)
        in[i][0] = in[i][1] = 0.0;
    double times[3];
    for (int r = 0; r < 3; ++r) {
        double start = bench_now();
        fftw_execute(plan);
        times[r] = bench_now() - start;
    }
    fftw_destroy_plan(plan);
    fftw_free(in);
    fftw_free(out);
    return bench_median(times, 3);
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: bench_surface N [REPEATS]\n");
        return 2;
    }
    int n = atoi(argv[1]), repeats = argc > 2 ? atoi(argv[2]) : 5;
    if (n < 8 || repeats < 1 || repeats > 100) {
        fprintf(stderr, "bench_surface: N >= 8 and 1 <= REPEATS <= 100 expected\n");
        return 2;
    }
    im_surface_params p = im_surface_params_default();
    p.nx = p.ny = n;
    p.lambda_r = p.lambda_0 = n;
    double times[100];
    for (int r = 0; r < repeats; ++r) {
        im_field *s = NULL;
        p.seed = (uint64_t)r + 1;
        double start = bench_now();
        if (im_surface_generate(&p, &s) != IM_OK) {
            fprintf(stderr, "bench_surface: %s\n", im_last_error());
            return 1;
        }
        times[r] = bench_now() - start;
        im_field_free(s);
    }
    double peak = bench_peak_rss_mib();
    fftw_init_threads();
    double floor_s = time_c2r_floor(n);
    double median = bench_median(times, repeats);
    printf("%d,%d,%d,%.4f,%.4f,%.2f,%.1f,%.1f\n", n, omp_get_max_threads(), repeats, median, floor_s,
           median / floor_s, peak, im_surface_generate_bytes(n, n) / 1048576.0);
    return 0;
}
