#include "theory/quadrature.h"
#include "core/gsl_handler.h"

#include "indentmap/status.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <math.h>

/* Subintervals the adaptive rule may use; the theory's integrands need far fewer. */
enum { QUADRATURE_LIMIT = 1000 };

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
    return im_fail(status, "%s on [%g, %g]: GSL quadrature failed: %s", what, lo, hi, gsl_strerror(gsl_status));
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
    int gsl_status = gsl_integration_qags(&function, lo, hi, 0.0, THEORY_QUADRATURE_EPSREL, QUADRATURE_LIMIT,
                                          workspace, &value, &abserr);
    gsl_integration_workspace_free(workspace);
    if (gsl_status != GSL_SUCCESS)
        return status_from_gsl(gsl_status, what, lo, hi);
    if (!isfinite(value))
        return im_fail(IM_ENUMERIC, "%s on [%g, %g]: the quadrature gave %g", what, lo, hi, value);
    *result = value;
    return IM_OK;
}

int theory_integrate(theory_integrand f, void *params, double lo, double hi, const char *what, double *result)
{
    core_gsl_handler_off();
    int status = integrate(f, params, lo, hi, what, result);
    core_gsl_handler_restore();
    return status;
}
