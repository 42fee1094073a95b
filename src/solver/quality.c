/* Named speed/accuracy presets of the solver tolerance (solver.h). */
#include "indentmap/solver.h"
#include "indentmap/status.h"

#include <string.h>

typedef struct quality_preset {
    const char *name;
    double tol;
} quality_preset;

/* Measured on a 256 x 256 h'rms = 0.08 surface, 80 degree cone, 16 steps (solver.h): the largest
 * relative error in N against tol 1e-11 is about tol itself; n_p is exact from 1e-7 on. */
static const quality_preset PRESETS[] = {{"draft", 1e-4}, {"standard", 1e-6}, {"publication", 1e-9}};

int im_quality_tolerance(const char *name, double *tol)
{
    for (size_t i = 0; name && i < sizeof PRESETS / sizeof PRESETS[0]; ++i)
        if (strcmp(name, PRESETS[i].name) == 0) {
            *tol = PRESETS[i].tol;
            return IM_OK;
        }
    return im_fail(IM_EINVAL, "quality = '%s': expected draft, standard or publication", name ? name : "(null)");
}
