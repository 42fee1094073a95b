/* Internal: FFTW's thread set-up, shared by every module that plans transforms. */
#ifndef INDENTMAP_CORE_FFT_THREADS_H
#define INDENTMAP_CORE_FFT_THREADS_H

/* Initialises FFTW's OpenMP threading once per process and makes the next plans use as many
 * threads as a parallel region started here would have: OpenMP's threads at the top level, one
 * inside a parallel region (an ensemble solving surfaces side by side), where FFTW's own region
 * could not start more. Call it with the planner lock held (below). */
void fft_prepare_planner(void);

/* FFTW's planner (plan creation and destruction, wisdom) is not thread-safe. Code that may run
 * inside a parallel region (an ensemble solving surfaces side by side) brackets every plan
 * creation and destruction with these: one process-wide mutex. */
void fft_planner_lock(void);
void fft_planner_unlock(void);

#endif
