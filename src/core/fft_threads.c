#include "core/fft_threads.h"

#include <fftw3.h>
#include <omp.h>
#include <pthread.h>

static pthread_once_t fftw_threads_once = PTHREAD_ONCE_INIT;
static pthread_mutex_t planner_mutex = PTHREAD_MUTEX_INITIALIZER;

void fft_planner_lock(void) { pthread_mutex_lock(&planner_mutex); }
void fft_planner_unlock(void) { pthread_mutex_unlock(&planner_mutex); }

static void init_fftw_threads(void)
{
    fftw_init_threads();
    fftwf_init_threads();
}

/* The threads a region started here would have: omp_get_max_threads() still says the team size inside
 * a parallel region, where a nested region (OpenMP's default: one active level) runs on one thread. */
static int threads_here(void)
{
    return omp_get_active_level() >= omp_get_max_active_levels() ? 1 : omp_get_max_threads();
}

void fft_prepare_planner(void)
{
    pthread_once(&fftw_threads_once, init_fftw_threads);
    const int threads = threads_here();
    fftw_plan_with_nthreads(threads);
    fftwf_plan_with_nthreads(threads);
}
