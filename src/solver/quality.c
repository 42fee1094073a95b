/* Named speed/accuracy presets of the solver tolerance (solver.h). */
#include "indentmap/solver.h"
#include "core/args.h"
#include "indentmap/status.h"

#include <string.h>

typedef struct quality_preset {
    const char *name;
    double tol;
} quality_preset;

/* Measured on the paper's 512 x 512 history (solver.h): the largest relative error in N against
 * tol 1e-11 is within 2 tol; n_p is exact from 1e-8 on. draft is the loosest tolerance whose n_p
 * error (0.19%) stays below the grid's own area error (0.9% at lambda_s = 4 delta): at 1e-4 the
 * solver, not the grid, decided the area (2.0%). */
static const quality_preset PRESETS[] = {{"draft", 1e-5}, {"standard", 1e-6}, {"publication", 1e-9}};

int im_quality_tolerance(const char *name, double *tol)
{
    ARG_REQUIRE(name, "name");
    ARG_REQUIRE(tol, "tol");
    for (size_t i = 0; name && i < sizeof PRESETS / sizeof PRESETS[0]; ++i)
        if (strcmp(name, PRESETS[i].name) == 0) {
            *tol = PRESETS[i].tol;
            return IM_OK;
        }
    return im_fail(IM_EINVAL, "quality = '%s': expected draft, standard or publication", name ? name : "(null)");
}

double im_quality_default_tolerance(void)
{
    double tol = 0;
    im_quality_tolerance(IM_QUALITY_DEFAULT, &tol); /* a preset of the table above */
    return tol;
}
