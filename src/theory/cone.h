/* Internal helpers of the theory of the cone and the other punches, shared by contact.c,
 * cone_area.c and punch_area.c. */
#ifndef INDENTMAP_THEORY_CONE_H
#define INDENTMAP_THEORY_CONE_H

/* IM_EINVAL unless beta >= 0 (+INFINITY allowed), with a message naming beta. */
int theory_check_erf_scale(double beta);

/* acosh(1 / s), the smooth cone's p(r) / p_m,c, for 0 <= s = r/a <= 1; +INFINITY at s = 0. */
double theory_acosh_inverse(double s);

/* The same as a function of the distance from the rim t = 1 - s, 0 <= t <= 1, accurate to a few
 * ulps where t is tiny (there acosh(1/s) ~ sqrt(2 t), and 1 / s - 1 would have lost t's digits). */
double theory_acosh_inverse_from_rim(double t);

/* erf(beta x) / beta, which stays accurate (no underflow) as beta -> 0. */
double theory_erf_over_beta(double beta, double x);

#endif
