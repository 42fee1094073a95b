/* indentmap/theory.h: the paper's theory.
 *
 * Roughness relations (eqs. 13-15): spectral moments of an isotropic power-law PSD
 * C(q) = A |q|^(-2(1+H)) on q_r < q < q_s with a roll-off plateau C(q_r) on q_0 < q < q_r, with
 * the magnification zeta = q_s / q_r and x = q_0 / q_r (x = 1: no plateau).
 */
#ifndef INDENTMAP_THEORY_H
#define INDENTMAP_THEORY_H

/* Eq. (13) divided by the prefactor A: m_n / A = T(n) q_r^(n - 2H) ((1 - x^(n+2)) / (n + 2)
 * + (zeta^(n - 2H) - 1) / (n - 2H)), T(0) = 2 pi, T(2) = pi, T(4) = 3 pi / 4; n in {0, 2, 4}.
 * Returns NaN for any other n or for parameters outside 0 < H < 1, q_r > 0, zeta >= 1,
 * 0 <= x <= 1. */
double im_theory_moment(int n, double hurst, double q_r, double zeta, double x);

/* h_rms of a surface with the given h'rms from the exact moments of eq. (13):
 * h_rms = h'rms sqrt(m0 / (2 m2)). */
double im_theory_height_rms_moments(double slope_rms, double hurst, double q_r, double zeta, double x);

/* The paper's eq. (15), the large-zeta approximation of eq. (14) without roll-off:
 * h_rms ~ h'rms sqrt((1 - H) / H) zeta^H / q_s. It drops zeta^(2H - 2) against 1, which for the
 * paper's surfaces (H = 0.8, zeta = 128) makes it 7.5% lower than the exact moments. */
double im_theory_height_rms_eq15(double slope_rms, double hurst, double q_s, double zeta);

#endif
