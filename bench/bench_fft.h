/* Shared by the solver benchmarks: process CPU time and the FFT-pair floor that a solver iteration is
 * measured against. */
#ifndef INDENTMAP_BENCH_FFT_H
#define INDENTMAP_BENCH_FFT_H

#include "bench_common.h"
#include "core/fft_threads.h"

#include <fftw3.h>
#include <omp.h>
#include <time.h>

static inline double bench_cpu_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* One forward r2c + inverse c2r FFTW_ESTIMATE transform pair of a px x py grid at the process's thread
 * count (the solver's floor): its CPU and wall seconds, medians of BENCH_PAIR_REPEATS. */
enum { BENCH_PAIR_REPEATS = 21 };
typedef struct bench_pair_time {
    double cpu, wall;
} bench_pair_time;

static inline bench_pair_time bench_fft_pair_time(int px, int py)
{
    double *real = fftw_malloc(sizeof(double) * (size_t)px * py);
    fftw_complex *modes = fftw_malloc(sizeof(fftw_complex) * (size_t)py * (px / 2 + 1));
    fft_prepare_planner();
    fftw_plan f = fftw_plan_dft_r2c_2d(py, px, real, modes, FFTW_ESTIMATE);
    fftw_plan b = fftw_plan_dft_c2r_2d(py, px, modes, real, FFTW_ESTIMATE);
    for (size_t i = 0; i < (size_t)px * py; ++i)
        real[i] = (double)(i % 7) * 0.1;
    double cpu[BENCH_PAIR_REPEATS], wall[BENCH_PAIR_REPEATS];
    for (int r = 0; r < BENCH_PAIR_REPEATS; ++r) {
        double start = bench_cpu_now(), start_wall = omp_get_wtime();
        fftw_execute(f);
        fftw_execute(b);
        cpu[r] = bench_cpu_now() - start;
        wall[r] = omp_get_wtime() - start_wall;
    }
    fftw_destroy_plan(f);
    fftw_destroy_plan(b);
    fftw_free(real);
    fftw_free(modes);
    return (bench_pair_time){bench_median(cpu, BENCH_PAIR_REPEATS), bench_median(wall, BENCH_PAIR_REPEATS)};
}

#endif
