/* The smooth adhesive theory beside an adhesive history (front.h): Maugis-Dugdale for a sphere, Kendall for
 * a flat punch. */
#include "front/front.h"
#include "indentmap/io.h"
#include "indentmap/status.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

int adhesion_theory_pull_off(const im_indenter *punch, const im_theory_adhesion *law, const char **model,
                             im_theory_adhesive_point *pull_off)
{
    *model = NULL;
    if (punch->kind == IM_PUNCH_SPHERE) {
        *model = "Maugis-Dugdale sphere";
        return im_theory_md_sphere_pull_off(law, punch->radius, pull_off);
    }
    if (punch->kind == IM_PUNCH_FLAT) {
        *model = "Kendall flat punch";
        return im_theory_kendall_pull_off(law, punch->radius, pull_off);
    }
    return IM_OK;
}

static int theory_load(const im_indenter *punch, const im_theory_adhesion *law, double approach, double *load)
{
    if (punch->kind == IM_PUNCH_SPHERE)
        return im_theory_md_sphere_load_at_approach(law, punch->radius, approach, load);
    if (punch->kind == IM_PUNCH_FLAT)
        return im_theory_kendall_load_at_approach(law, punch->radius, approach, load);
    return im_fail(IM_EINVAL, "adhesion_theory.csv: no adhesive theory for a %s", im_punch_name(punch->kind));
}

enum { THEORY_LINE_MAX = 128 };

int adhesion_theory_write(const char *dir, const im_indenter *punch, const im_theory_adhesion *law,
                          const im_history_row *rows, int count)
{
    static const char header[] = "step,approach,load,load_theory\n";
    const size_t size = sizeof header + (size_t)count * THEORY_LINE_MAX;
    char *text = malloc(size), path[4096];
    if (!text)
        return im_fail(IM_ENOMEM, "adhesion_theory.csv of %d steps", count);
    size_t used = (size_t)snprintf(text, size, "%s", header);
    int status = IM_OK;
    for (int k = 0; k < count && status == IM_OK; ++k) {
        double load;
        status = theory_load(punch, law, rows[k].result.approach, &load);
        used += (size_t)snprintf(text + used, size - used, "%d,%.17g,%.17g,%.17g\n", rows[k].step,
                                 rows[k].result.approach, rows[k].result.load, load);
    }
    if (status == IM_OK)
        status = im_path_join(path, sizeof path, dir, "adhesion_theory.csv");
    if (status == IM_OK)
        status = im_write_file_atomic(path, text, used);
    free(text);
    return status;
}
