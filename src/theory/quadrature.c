#include "theory/quadrature.h"

#include "indentmap/status.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <math.h>
#include <pthread.h>

/* Subintervals the adaptive rule may use; the theory's integrands need far fewer. */
enum { QUADRATURE_LIMIT = 1000 };

/* GSL's error handler is one process-wide pointer; its default aborts the program, and the library
 * must return statuses instead. So it is switched off while any quadrature of the library runs and
 * the application's handler, whatever it was, is put back when the last one ends: a count, under a
 * lock, since quadratures run on several threads at once. */
static pthread_mutex_t gsl_handler_lock = PTHREAD_MUTEX_INITIALIZER;
static int gsl_handler_users;
static gsl_error_handler_t *application_gsl_handler;

void theory_gsl_handler_off(void)
{
    pthread_mutex_lock(&gsl_handler_lock);
    if (gsl_handler_users++ == 0)
        application_gsl_handler = gsl_set_error_handler_off();
    pthread_mutex_unlock(&gsl_handler_lock);
}

void theory_gsl_handler_restore(void)
{
    pthread_mutex_lock(&gsl_handler_lock);
    if (--gsl_handler_users == 0)
        gsl_set_error_handler(application_gsl_handler);
    pthread_mutex_unlock(&gsl_handler_lock);
}

static int status_from_gsl(int gsl_status, const char *what, double lo, double hi)
{
    int status;
    switch (gsl_status) {
    case GSL_ENOMEM: status = IM_ENOMEM; break;
    case GSL_EMAXITER:
    case GSL_EDIVERGE:
    case GSL_ESING: status = IM_ENOCONV; break;
    default: status = IM_ENUMERIC; break;
    }
    return im_fail(status, "%s on [%g, %g]: GSL quadrature failed: %s", what, lo, hi,
                   gsl_strerror(gsl_status));
}

static int integrate(theory_integrand f, void *params, double lo, double hi, const char *what, double *result)
{
    if (!(lo < hi)) {
        *result = 0.0;
        return IM_OK;
    }
    gsl_integration_workspace *workspace = gsl_integration_workspace_alloc(QUADRATURE_LIMIT);
    if (!workspace)
        return im_fail(IM_ENOMEM, "%s: GSL integration workspace allocation failed", what);
    gsl_function function = {.function = f, .params = params};
    double value, abserr;
    int gsl_status = gsl_integration_qags(&function, lo, hi, 0.0, THEORY_QUADRATURE_EPSREL,
                                          QUADRATURE_LIMIT, workspace, &value, &abserr);
    gsl_integration_workspace_free(workspace);
    if (gsl_status != GSL_SUCCESS)
        return status_from_gsl(gsl_status, what, lo, hi);
    if (!isfinite(value))
        return im_fail(IM_ENUMERIC, "%s on [%g, %g]: the quadrature gave %g", what, lo, hi, value);
    *result = value;
    return IM_OK;
}

int theory_integrate(theory_integrand f, void *params, double lo, double hi, const char *what,
                     double *result)
{
    theory_gsl_handler_off();
    int status = integrate(f, params, lo, hi, what, result);
    theory_gsl_handler_restore();
    return status;
}
