/* indentation.csv: the indentation analysis of the unloading branches of a history, written by every
 * front end that runs histories (front.h). */
#include "front/front.h"

#include "indentmap/io.h"
#include "indentmap/measure.h"
#include "indentmap/status.h"

#include <stdio.h>
#include <stdlib.h>

const char ANALYSIS_COLUMNS[] = "branch,top_step,last_step,loading_from,approach_max,load_max,stiffness,epsilon,"
                                "contact_depth,area_projected,area_real,hardness_it,modulus_reduced,"
                                "residual_approach,work_in,work_out,dissipated";

enum { ANALYSIS_LINE_MAX = 640 };

static int format_branch(int index, const im_unloading_branch *b, const history_row *rows, double delta, char *line,
                         size_t size)
{
    const im_step_result *top = &rows[b->top_step - 1].result, *last = &rows[b->last_step - 1].result;
    return snprintf(line, size,
                    "%d,%d,%d,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n",
                    index + 1, b->top_step, b->last_step, b->loading_from, b->approach_max, b->load_max,
                    b->stiffness, b->epsilon, b->contact_depth, b->area_projected,
                    (double)top->contact_patches * delta * delta, b->hardness, b->modulus, b->residual_approach,
                    b->work_in, b->work_out, last->plastic_work);
}

static int write_branches(const char *dir, const im_unloading_branch *b, int found, const history_row *rows,
                          double delta)
{
    size_t size = sizeof ANALYSIS_COLUMNS + 1 + (size_t)found * ANALYSIS_LINE_MAX, used = 0;
    char *text = malloc(size), path[4096];
    if (!text)
        return im_fail(IM_ENOMEM, "indentation.csv of %d branches", found);
    used += (size_t)snprintf(text, size, "%s\n", ANALYSIS_COLUMNS);
    for (int k = 0; k < found; ++k)
        used += (size_t)format_branch(k, &b[k], rows, delta, text + used, size - used);
    int status = im_path_join(path, sizeof path, dir, "indentation.csv");
    if (status == IM_OK)
        status = im_write_file_atomic(path, text, used);
    free(text);
    return status;
}

int analysis_write(const char *dir, const im_indenter *punch, const history_row *rows, int count, double delta,
                   int *branches)
{
    *branches = 0;
    if (count < 2)
        return IM_OK;
    double *columns = malloc(sizeof(double) * 3 * (size_t)count);
    im_unloading_branch *found = malloc(sizeof *found * (size_t)count);
    int status = columns && found ? IM_OK : im_fail(IM_ENOMEM, "indentation analysis of %d steps", count);
    for (int k = 0; status == IM_OK && k < count; ++k) {
        columns[k] = rows[k].result.approach;
        columns[count + k] = rows[k].result.load;
        columns[2 * count + k] = rows[k].result.residual_approach;
    }
    if (status == IM_OK)
        status = im_measure_unloading(punch, columns, columns + count, columns + 2 * count, count, found, count,
                                      branches);
    if (status == IM_OK && *branches > 0)
        status = write_branches(dir, found, *branches, rows, delta);
    free(columns);
    free(found);
    return status;
}
