/* Internal: the half spectrum of a real field on its periodic box, shared by synthesis and
 * statistics. Coefficients are normalised so that h(x) = sum over all k of H_k exp(i k.x):
 * H = DFT(h) / (nx ny). Only the non-redundant half (nx/2 + 1 columns) is stored, as FFTW's
 * real-to-complex layout: entry (jx, jy) at jy * (nx/2 + 1) + jx. */
#ifndef INDENTMAP_SURFACE_SPECTRUM_H
#define INDENTMAP_SURFACE_SPECTRUM_H

#include "indentmap/field.h"

#include <complex.h>
#include <math.h>

typedef struct surface_spectrum {
    int nx, ny, half_nx;     /* half_nx = nx / 2 + 1 columns */
    double qx_step, qy_step; /* 2 pi / L_x, 2 pi / L_y */
    double complex *coefficients;
} surface_spectrum;

/* Forward transform of a field (FFTW, estimate-planned, OpenMP threads). */
int surface_spectrum_of(const im_field *field, surface_spectrum *out);

/* Allocates a zeroed half spectrum for an nx x ny box of spacing delta. */
int surface_spectrum_alloc(int nx, int ny, double delta, surface_spectrum *out);

/* Inverse transform into an existing nx x ny field (the spectrum is left unchanged). */
int surface_spectrum_to_field(const surface_spectrum *spectrum, im_field *field);

void surface_spectrum_release(surface_spectrum *spectrum);

/* Signed integer wave numbers of a stored entry. */
static inline int spectrum_kx(int jx) { return jx; }
static inline int spectrum_ky(const surface_spectrum *s, int jy) { return jy <= s->ny / 2 ? jy : jy - s->ny; }

/* How many modes of the full spectrum the stored entry (jx, .) stands for: 2 for a column whose
 * conjugate partner is not stored, 1 for column 0 and, with nx even, the Nyquist column. */
static inline double spectrum_weight(const surface_spectrum *s, int jx)
{
    return (jx == 0 || (s->nx % 2 == 0 && jx == s->nx / 2)) ? 1.0 : 2.0;
}

/* *power = the sum over the full spectrum of weight(qx, qy) |H_k|^2, in a fixed order (deterministic
 * for any thread count). IM_ENOMEM if its row sums cannot be allocated. */
int spectrum_weighted_power(const surface_spectrum *s, double (*weight)(double qx, double qy), double *power);

#endif
