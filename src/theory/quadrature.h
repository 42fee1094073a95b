/* Internal: GSL adaptive quadrature for the theory module, with GSL's error handler switched off
 * during each call (core/gsl_handler.h) and GSL's status codes turned into
 * the project's. */
#ifndef INDENTMAP_THEORY_QUADRATURE_H
#define INDENTMAP_THEORY_QUADRATURE_H

/* Relative accuracy asked of every theory quadrature. */
#define THEORY_QUADRATURE_EPSREL 1e-12

/* An integrand of one variable with its parameters. */
typedef double (*theory_integrand)(double x, void *params);

/* int_lo^hi f(x) dx by GSL's qags (adaptive Gauss-Kronrod with Wynn extrapolation, which copes
 * with integrable endpoint singularities) to THEORY_QUADRATURE_EPSREL. `what` names the integral
 * in error messages; lo >= hi gives 0. IM_OK, IM_ENOMEM, IM_ENUMERIC or IM_ENOCONV. */
int theory_integrate(theory_integrand f, void *params, double lo, double hi, const char *what, double *result);

#endif
