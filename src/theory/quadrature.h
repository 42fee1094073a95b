/* Internal: GSL adaptive quadrature for the theory module, with GSL's error handler switched off
 * during each call (and the application's put back after it) and GSL's status codes turned into
 * the project's. */
#ifndef INDENTMAP_THEORY_QUADRATURE_H
#define INDENTMAP_THEORY_QUADRATURE_H

/* GSL's error handler switched off (its default aborts; the library returns statuses) for the
 * length of a GSL call, and the application's put back once no such call of the library runs (a
 * count under a lock: callers on several threads at once). Every off is paired with a restore. */
void theory_gsl_handler_off(void);
void theory_gsl_handler_restore(void);

/* Relative accuracy asked of every theory quadrature. */
#define THEORY_QUADRATURE_EPSREL 1e-12

/* An integrand of one variable with its parameters. */
typedef double (*theory_integrand)(double x, void *params);

/* int_lo^hi f(x) dx by GSL's qags (adaptive Gauss-Kronrod with Wynn extrapolation, which copes
 * with integrable endpoint singularities) to THEORY_QUADRATURE_EPSREL. `what` names the integral
 * in error messages; lo >= hi gives 0. IM_OK, IM_ENOMEM, IM_ENUMERIC or IM_ENOCONV. */
int theory_integrate(theory_integrand f, void *params, double lo, double hi, const char *what,
                     double *result);

#endif
