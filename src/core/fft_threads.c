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

void fft_prepare_planner(void)
{
    pthread_once(&fftw_threads_once, init_fftw_threads);
    fftw_plan_with_nthreads(omp_get_max_threads());
    fftwf_plan_with_nthreads(omp_get_max_threads());
}
