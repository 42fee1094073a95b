/* indentmap theory --fit-k HISTORY: k of eq. (2) fitted to a periodic history written earlier, with the
 * cell, the h'rms and E* of the run.json beside it: the fit `indent --periodic` makes at its end
 * (front.h: periodic_fit_k), printed the same way. */
#include "cli/cli.h"
#include "io/json_file.h"
#include "front/front.h"

#include "indentmap/io.h"
#include "indentmap/status.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* What the fit takes from the run record beside the history. */
typedef struct periodic_run {
    double cell_area, slope_rms, e_star;
    char slope_definition[64];
} periodic_run;

/* DIR/run.json for the history DIR/NAME (./run.json for a bare NAME). */
static int record_path(const char *history, char *path, size_t size)
{
    const char *slash = strrchr(history, '/');
    char dir[4096];
    if (!slash)
        snprintf(dir, sizeof dir, ".");
    else if ((size_t)(slash - history) >= sizeof dir)
        return im_fail(IM_EINVAL, "%s: the path is too long", history);
    else
        snprintf(dir, sizeof dir, "%.*s", slash == history ? 1 : (int)(slash - history), history);
    return im_path_join(path, size, dir, "run.json");
}

/* record[block][key] as a finite number, or IM_EFORMAT naming it. */
static int record_number(const json_t *record, const char *block, const char *key, const char *path, double *value)
{
    const json_t *item = json_object_get(json_object_get(record, block), key);
    *value = json_number_value(item);
    if (json_is_number(item) && isfinite(*value))
        return IM_OK;
    return im_fail(IM_EFORMAT,
                   "%s: no number at %s.%s: expected the run.json of `indentmap indent --periodic` "
                   "(the cell's nx, ny and delta, the h'rms and E* the fit needs)",
                   path, block, key);
}

/* The cell of the record's surface block, or IM_EFORMAT naming what it lacks. */
static int read_cell(const json_t *record, const char *path, im_field *cell)
{
    double nx, ny;
    int status = record_number(record, "surface", "nx", path, &nx);
    if (status == IM_OK)
        status = record_number(record, "surface", "ny", path, &ny);
    if (status == IM_OK)
        status = record_number(record, "surface", "delta", path, &cell->delta);
    if (status == IM_OK && !(nx >= 1 && ny >= 1 && nx == floor(nx) && ny == floor(ny) && nx <= IM_FIELD_MAX_SIDE &&
                             ny <= IM_FIELD_MAX_SIDE && cell->delta > 0))
        status = im_fail(IM_EFORMAT,
                         "%s: surface.nx = %g, ny = %g, delta = %g: expected a grid (whole nx, ny from 1 "
                         "to %d, delta > 0)",
                         path, nx, ny, cell->delta, IM_FIELD_MAX_SIDE);
    if (status == IM_OK)
        cell->nx = (int)nx, cell->ny = (int)ny;
    return status;
}

/* IM_EINVAL unless the record is of a run whose history eq. (2) describes, as `indent --periodic` fits it:
 * elastic and repulsive (the rigid flat: its history's mean_gap). */
static int check_periodic_run(const json_t *record, const char *path)
{
    if (!json_is_true(json_object_get(record, "periodic")))
        return im_fail(IM_EINVAL,
                       "%s: not a periodic run (\"periodic\" is not true): k of eq. (2) is fitted to the "
                       "history of `indentmap indent SURFACE --periodic`",
                       path);
    double hardness;
    int status = record_number(record, "solver", "hardness", path, &hardness);
    if (status == IM_OK && hardness > 0)
        return im_fail(IM_EINVAL,
                       "%s: the run capped the pressure at solver.hardness = %g: eq. (2) is the elastic "
                       "law, fitted to runs without a hardness",
                       path, hardness);
    const json_t *adhesion = json_object_get(record, "adhesion");
    if (status == IM_OK && adhesion && !json_is_null(adhesion))
        return im_fail(IM_EINVAL,
                       "%s: the run was adhesive (\"adhesion\"): eq. (2) is the repulsive law, fitted "
                       "to runs without adhesion",
                       path);
    return status;
}

/* The cell's area, h'rms and E* from the run record: IM_EINVAL when there is none or it is not of a run
 * eq. (2) describes, IM_EFORMAT naming what it lacks. */
static int read_periodic_run(const char *path, periodic_run *run)
{
    if (access(path, F_OK) != 0)
        return im_fail(IM_EINVAL,
                       "%s: no run.json beside the history: the fit needs the cell (surface.nx, ny, "
                       "delta), the h'rms (theory_slope_rms.value) and E* (solver.e_star) that `indentmap indent "
                       "--periodic` records there",
                       path);
    json_error_t error;
    json_t *record = json_file_load(path, JSON_REJECT_DUPLICATES, &error);
    if (!record)
        return im_fail(IM_EFORMAT, "%s: line %d: %s", path, error.line, error.text);
    im_field cell = {.nx = 0};
    int status = check_periodic_run(record, path);
    if (status == IM_OK)
        status = read_cell(record, path, &cell);
    if (status == IM_OK)
        status = record_number(record, "theory_slope_rms", "value", path, &run->slope_rms);
    if (status == IM_OK)
        status = record_number(record, "solver", "e_star", path, &run->e_star);
    const char *definition = json_string_value(
        json_object_get(json_object_get(record, "theory_slope_rms"), "definition"));
    if (status == IM_OK && !definition)
        status = im_fail(IM_EFORMAT,
                         "%s: no text at theory_slope_rms.definition: expected the h'rms's definition "
                         "(spectral or finite differences)",
                         path);
    if (status == IM_OK) {
        run->cell_area = periodic_cell_area(&cell);
        snprintf(run->slope_definition, sizeof run->slope_definition, "%s", definition);
    }
    json_decref(record);
    return status;
}

/* The rows of a periodic history into *rows (the caller frees them): refused by name when it is of the
 * half-space or of a punch on the cell (mean_gap NaN). */
static int read_periodic_history(const char *path, im_history_row **rows, int *count)
{
    char *text = NULL;
    int status = im_read_text_file(path, 4096 + (size_t)STEPS_MAX * IM_HISTORY_LINE_MAX, &text, NULL);
    *rows = status == IM_OK ? calloc(STEPS_MAX, sizeof **rows) : NULL;
    if (status == IM_OK && !*rows)
        status = im_fail(IM_ENOMEM, "%s: %d history rows", path, STEPS_MAX);
    /* a half-space history does not parse as a cell's (load_star is finite there): read it as it is, to
     * name what makes it one */
    const int areas[] = {IM_HISTORY_AREA_CELL, IM_HISTORY_AREA_SMOOTH, IM_HISTORY_AREA_NONE};
    char why[256] = "", other[256];
    int parsed = 0;
    for (int i = 0; status == IM_OK && !parsed && i < 3; ++i)
        parsed = im_history_parse(text, areas[i], *rows, STEPS_MAX, count, i ? other : why, sizeof why);
    if (status == IM_OK && !parsed)
        status = im_fail(IM_EFORMAT, "%s: not a history of this version: %s", path, why);
    for (int i = 0; status == IM_OK && i < *count; ++i)
        if (!isfinite((*rows)[i].result.mean_gap))
            status = im_fail(IM_EINVAL,
                             "%s: row %d (line %d) has no mean_gap (not finite): not the history of a "
                             "periodic cell under the rigid flat (`indentmap indent SURFACE --periodic` without "
                             "--punch)",
                             path, i + 1, i + 2);
    if (status == IM_OK && why[0]) /* parsed, but not as a cell's */
        status = im_fail(IM_EFORMAT, "%s: not a periodic cell's history: %s", path, why);
    free(text);
    return status;
}

int cli_theory_fit_k(const char *history, int csv)
{
    char path[4096];
    periodic_run run;
    im_history_row *rows = NULL;
    int count = 0;
    periodic_k_fit k;
    int status = read_periodic_history(history, &rows, &count);
    if (status == IM_OK)
        status = record_path(history, path, sizeof path);
    if (status == IM_OK)
        status = read_periodic_run(path, &run);
    if (status == IM_OK)
        status = periodic_fit_k(rows, count, run.cell_area, run.slope_rms, run.e_star, &k);
    free(rows);
    if (status != IM_OK)
        return cli_report(status);
    if (csv) {
        printf("slope_rms,%s\n%.17g,", PERIODIC_K_COLUMNS, run.slope_rms);
        periodic_k_fit_write_row(stdout, &k);
    } else {
        char line[1024];
        periodic_k_fit_describe(&k, run.slope_rms, run.slope_definition, line, sizeof line);
        printf("%s\n", line);
    }
    return CLI_EXIT_OK;
}
