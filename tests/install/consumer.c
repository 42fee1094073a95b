/* A program that knows indentmap only through its installed headers and library: it checks the
 * version it runs with and solves a smooth cone against Love's closed form. Exit 0 when both hold. */
#include <indentmap/indenter.h>
#include <indentmap/solver.h>
#include <indentmap/status.h>
#include <indentmap/version.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

static int solve_smooth_cone(double w, double *load)
{
    im_field *surface = NULL;
    im_indentation *run = NULL;
    im_step_result step;
    im_indenter cone = im_indenter_cone(80.0);
    im_solver_options options = im_solver_options_default();
    int status = im_field_create(64, 64, 1.0, &surface);
    if (status == IM_OK)
        status = im_indentation_create(surface, &cone, IM_CONTROL_DISPLACEMENT, w, &options, &run);
    if (status == IM_OK)
        status = im_indentation_step(run, w, &step);
    if (status == IM_OK)
        *load = step.load;
    else
        fprintf(stderr, "consumer: %s\n", im_last_error());
    im_indentation_free(run);
    im_field_free(surface);
    return status;
}

int main(void)
{
    if (strcmp(im_version(), IM_VERSION_STRING) != 0) {
        fprintf(stderr, "consumer: headers %s, library %s\n", IM_VERSION_STRING, im_version());
        return 1;
    }
    const double w = 2.0;
    double load = 0;
    if (solve_smooth_cone(w, &load) != IM_OK)
        return 1;
    im_indenter cone = im_indenter_cone(80.0);
    double love = im_indenter_load(&cone, 1.0, w);
    double error = fabs(load / love - 1.0);
    printf("indentmap %s: N = %.6g, Love %.6g, relative error %.2e\n", im_version(), load, love, error);
    return error < 0.02 ? 0 : 1;
}
