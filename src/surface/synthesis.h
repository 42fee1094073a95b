/* Internal: the mode-keyed generator of im_surface_generate, one mode at a time, for code that
 * builds a surface's spectrum in pieces (the distributed synthesis, src/mpi/synthesis.c). */
#ifndef INDENTMAP_SURFACE_SYNTHESIS_H
#define INDENTMAP_SURFACE_SYNTHESIS_H

#include "indentmap/surface.h"

#include <complex.h>

/* The unscaled coefficient of mode (kx, ky) of the nx x ny surface params describes (qx_step,
 * qy_step = 2 pi / L_x, 2 pi / L_y): the square root of the cell-averaged PSD times the mode's
 * Gaussian keyed by (seed, kx, ky); 0 for the mean, Nyquist modes and modes outside the band. It
 * depends on the mode only, not on how or where the rest of the spectrum is computed. */
double complex surface_mode_coefficient(const im_surface_params *params, int kx, int ky, double qx_step,
                                        double qy_step);

#endif
