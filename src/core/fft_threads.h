/* Internal: FFTW's thread set-up, shared by every module that plans transforms. */
#ifndef INDENTMAP_CORE_FFT_THREADS_H
#define INDENTMAP_CORE_FFT_THREADS_H

/* Initialises FFTW's OpenMP threading once per process and makes the next plans use as many
 * threads as OpenMP would now. FFTW's planner is not thread-safe: call this, and plan, from
 * serial code only. */
void im_fft_prepare_planner(void);

#endif
