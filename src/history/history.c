/* The one history schema (history.h): the columns, the measurement beside each solved step, one row
 * writer, one reader. */
#include "indentmap/history.h"
#include "core/args.h"

#include "indentmap/field.h"
#include "indentmap/io.h"
#include "indentmap/measure.h"
#include "indentmap/status.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char HISTORY_COLUMNS[] = "step,approach,load,load_star,contact_patches,area_ratio,mean_pressure,"
                                      "max_pressure,iterations,residual,seconds,convolutions," IM_THEORY_STEP_COLUMNS
                                      ",stiffness,e_star_sneddon,patches,patch_perimeter,"
                                      "yielding_patches,plastic_depth,plastic_work,residual_approach,"
                                      "tensile_force,adhesive_patches,repulsive_patches,mean_gap";

enum { HISTORY_VALUES = IM_HISTORY_COLUMN_COUNT }; /* the columns above */

/* Those im_history_format writes with %d or %ld. */
static const char HISTORY_INTEGER_COLUMNS[] = "step,contact_patches,iterations,convolutions,patches,yielding_patches,"
                                              "adhesive_patches,repulsive_patches";

const char *im_history_columns(void) { return HISTORY_COLUMNS; }

/* Where each column's value is in a row, in the columns' order, and its type. */
typedef enum { COLUMN_INT, COLUMN_LONG, COLUMN_DOUBLE } column_type;
typedef struct column_member {
    size_t offset;
    column_type type;
} column_member;
#define MEMBER(member, type)                                                                                         \
    {                                                                                                                \
        offsetof(im_history_row, member), type                                                                       \
    }
static const column_member COLUMN_MEMBERS[HISTORY_VALUES] = {
    MEMBER(step, COLUMN_INT),
    MEMBER(result.approach, COLUMN_DOUBLE),
    MEMBER(result.load, COLUMN_DOUBLE),
    MEMBER(result.load_star, COLUMN_DOUBLE),
    MEMBER(result.contact_patches, COLUMN_LONG),
    MEMBER(result.area_ratio, COLUMN_DOUBLE),
    MEMBER(result.mean_pressure, COLUMN_DOUBLE),
    MEMBER(result.max_pressure, COLUMN_DOUBLE),
    MEMBER(result.iterations, COLUMN_INT),
    MEMBER(result.residual, COLUMN_DOUBLE),
    MEMBER(result.seconds, COLUMN_DOUBLE),
    MEMBER(result.convolutions, COLUMN_INT),
    MEMBER(theory.load_smooth, COLUMN_DOUBLE),
    MEMBER(theory.area_smooth, COLUMN_DOUBLE),
    MEMBER(theory.area_ratio_constant, COLUMN_DOUBLE),
    MEMBER(theory.area_ratio_gamma, COLUMN_DOUBLE),
    MEMBER(stiffness, COLUMN_DOUBLE),
    MEMBER(e_star_sneddon, COLUMN_DOUBLE),
    MEMBER(patches, COLUMN_LONG),
    MEMBER(perimeter, COLUMN_DOUBLE),
    MEMBER(result.yielding_patches, COLUMN_LONG),
    MEMBER(result.plastic_depth, COLUMN_DOUBLE),
    MEMBER(result.plastic_work, COLUMN_DOUBLE),
    MEMBER(result.residual_approach, COLUMN_DOUBLE),
    MEMBER(result.tensile_force, COLUMN_DOUBLE),
    MEMBER(result.adhesive_patches, COLUMN_LONG),
    MEMBER(result.repulsive_patches, COLUMN_LONG),
    MEMBER(result.mean_gap, COLUMN_DOUBLE),
};

int im_history_row_values(const im_history_row *row, double *values)
{
    ARG_REQUIRE(row, "row");
    ARG_REQUIRE(values, "values");
    for (int i = 0; i < HISTORY_VALUES; ++i) {
        const char *member = (const char *)row + COLUMN_MEMBERS[i].offset;
        switch (COLUMN_MEMBERS[i].type) {
        case COLUMN_INT: values[i] = *(const int *)member; break;
        case COLUMN_LONG: values[i] = (double)*(const long *)member; break;
        default: values[i] = *(const double *)member;
        }
    }
    return IM_OK;
}

/* The name of column i (0-based) into name. */
static void column_name(int i, char *name, size_t size)
{
    const char *start = HISTORY_COLUMNS;
    for (int k = 0; k < i; ++k)
        start = strchr(start, ',') + 1;
    snprintf(name, size, "%.*s", (int)strcspn(start, ","), start);
}

/* values[i] into its integer member; IM_EINVAL naming the column when it is not such an integer. */
static int set_integer(const double *values, int i, char *member)
{
    const int is_int = COLUMN_MEMBERS[i].type == COLUMN_INT;
    const double v = values[i], bound = is_int ? 2147483648.0 : 9007199254740992.0; /* 2^31; 2^53: exact */
    if (!(v == floor(v) && fabs(v) < bound)) {
        char name[64];
        column_name(i, name, sizeof name);
        return im_fail(IM_EINVAL, "im_history_row_from_values: %s = %g: expected an integer", name, v);
    }
    if (is_int)
        *(int *)member = (int)v;
    else
        *(long *)member = (long)v;
    return IM_OK;
}

int im_history_row_from_values(const double *values, im_history_row *row)
{
    ARG_REQUIRE(values, "values");
    ARG_REQUIRE(row, "row");
    int status = IM_OK;
    for (int i = 0; i < HISTORY_VALUES && status == IM_OK; ++i) {
        char *member = (char *)row + COLUMN_MEMBERS[i].offset;
        if (COLUMN_MEMBERS[i].type == COLUMN_DOUBLE)
            *(double *)member = values[i];
        else
            status = set_integer(values, i, member);
    }
    return status;
}

const char *im_history_integer_columns(void) { return HISTORY_INTEGER_COLUMNS; }

/* Contact patches of the run's current state. */
static int measure_patches(const im_indentation *run, im_history_row *row)
{
    im_field *force = NULL;
    im_contact_patches patches = {0};
    int status = im_indentation_fields(run, &force, NULL, NULL);
    if (status == IM_OK)
        status = im_measure_contact_patches(force, &patches, NULL);
    im_field_free(force);
    row->patches = patches.patches;
    row->perimeter = patches.perimeter;
    return status;
}

/* A / A_smooth(N) is a number only where the load is positive beyond the solver's tolerance (history.h):
 * the loads of a history are solved to tol of the largest of them (load control's search, to tol of the
 * target's and the last step's), so a smaller one is zero, where the smooth area is 0. */
static void settle_area_ratio(im_history_row *rows, int i, double tol)
{
    double largest = 0.0;
    for (int k = 0; k <= i; ++k)
        largest = fmax(largest, fabs(rows[k].result.load));
    if (!(rows[i].result.load > tol * largest))
        rows[i].result.area_ratio = NAN;
}

/* The punch short of where it touches (the surface, or the impression a hardness left: the residual
 * approach, 0 without one) and nothing pulls it: N is 0 about the step, so S = dN/dw is exactly 0. The
 * three points would span the touch (N turns from 0 to its unloading curve there) and gave
 * -1.28 E* delta after a plastic sphere's unloading (redteam3 R2). */
static int punch_withdrawn(const im_step_result *r)
{
    return r->contact_patches == 0 && r->adhesive_patches == 0 && r->approach < r->residual_approach;
}

int im_history_measure(const im_indenter *punch, const im_theory_interface *rough, const im_indentation *run,
                       double tol, im_history_row *rows, int i)
{
    ARG_REQUIRE(punch, "punch");
    ARG_REQUIRE(rows, "rows");
    if (i < 0)
        return im_fail(IM_EINVAL, "history row %d: expected >= 0", i);
    if (!(tol >= 0.0 && tol <= 1.0))
        return im_fail(IM_EINVAL, "im_history_measure: tol = %g: expected the solver's tolerance, in [0, 1]", tol);
    im_history_row *row = &rows[i];
    row->step = i + 1;
    if (rough)
        settle_area_ratio(rows, i, tol);
    int status = IM_OK;
    /* none for a periodic cell (the theory is the half-space's), nor for an adhesive step pulled below
     * first touch or into tension (the theory is of repulsive contact) */
    if (rough && row->result.approach >= 0 && row->result.load >= 0)
        status = im_theory_step_columns(punch, rough, row->result.approach, row->result.load, &row->theory);
    else
        row->theory = (im_theory_step){NAN, NAN, NAN, NAN};
    row->stiffness = row->e_star_sneddon = NAN;
    /* Three steps on one branch (the parabola's slope: exact for Love's quadratic N(w)); at the first
     * two steps, a repeated approach or a turn from loading to unloading the stiffness stays NaN. Two
     * steps would give only their secant, 25% low on a cone when w doubles (issue 26). Nor across the
     * touch: a reload from a withdrawn step (N = 0 there, rising steeply past the touch) gave 18.6
     * where the same state unloading gives 23.7. */
    if (status == IM_OK && punch_withdrawn(&row->result)) {
        row->stiffness = 0.0;
    } else if (status == IM_OK && i >= 2 && !punch_withdrawn(&rows[i - 2].result) &&
               !punch_withdrawn(&rows[i - 1].result)) {
        double w[3], n[3], s[3];
        for (int k = 0; k < 3; ++k) {
            w[k] = rows[i - 2 + k].result.approach;
            n[k] = rows[i - 2 + k].result.load;
        }
        if (im_measure_stiffness(w, n, 3, s) == IM_OK) {
            row->stiffness = s[2];
            row->e_star_sneddon = im_measure_sneddon_modulus(row->stiffness, row->theory.area_smooth);
        }
    }
    row->patches = -1;
    row->perimeter = NAN;
    return status == IM_OK && run ? measure_patches(run, row) : status;
}

int im_history_format(const im_history_row *row, char *line, size_t size)
{
    ARG_REQUIRE_OR(row, "row", -1);
    ARG_REQUIRE_OR(line, "line", -1);
    const im_step_result *r = &row->result;
    const im_theory_step *t = &row->theory;
    return snprintf(line, size,
                    "%d,%.17g,%.17g,%.17g,%ld,%.17g,%.17g,%.17g,%d,%.6e,%.6f,%d,%.17g,%.17g,%.17g,%.17g,%.17g,"
                    "%.17g,%ld,%.17g,%ld,%.17g,%.17g,%.17g,%.17g,%ld,%ld,%.17g\n",
                    row->step, r->approach, r->load, r->load_star, r->contact_patches, r->area_ratio,
                    r->mean_pressure, r->max_pressure, r->iterations, r->residual, r->seconds, r->convolutions,
                    t->load_smooth, t->area_smooth, t->area_ratio_constant, t->area_ratio_gamma, row->stiffness,
                    row->e_star_sneddon, row->patches, row->perimeter, r->yielding_patches, r->plastic_depth,
                    r->plastic_work, r->residual_approach, r->tensile_force, r->adhesive_patches,
                    r->repulsive_patches, r->mean_gap);
}

/* One row on a whole line [line, end); 0 when it is not HISTORY_VALUES numbers. */
static int scan_row(const char *line, const char *end, im_history_row *row)
{
    im_step_result *r = &row->result;
    im_theory_step *t = &row->theory;
    int used = 0;
    return sscanf(line,
                  "%d,%lf,%lf,%lf,%ld,%lf,%lf,%lf,%d,%lf,%lf,%d,%lf,%lf,%lf,%lf,%lf,%lf,%ld,%lf,%ld,%lf,%lf,%lf,%lf,%"
                  "ld,%ld,%lf%n",
                  &row->step, &r->approach, &r->load, &r->load_star, &r->contact_patches, &r->area_ratio,
                  &r->mean_pressure, &r->max_pressure, &r->iterations, &r->residual, &r->seconds, &r->convolutions,
                  &t->load_smooth, &t->area_smooth, &t->area_ratio_constant, &t->area_ratio_gamma, &row->stiffness,
                  &row->e_star_sneddon, &row->patches, &row->perimeter, &r->yielding_patches, &r->plastic_depth,
                  &r->plastic_work, &r->residual_approach, &r->tensile_force, &r->adhesive_patches,
                  &r->repulsive_patches, &r->mean_gap, &used) == HISTORY_VALUES &&
           line + used == end;
}

/* Whether A / A_cone may be NaN at a positive load: with a smooth-contact area, where the load is zero to the
 * solver's tolerance (settle_area_ratio), which is at most 1, so never above every load before it. */
static int ratio_may_be_undefined(const im_step_result *r, int area, double largest_before)
{
    return area == IM_HISTORY_AREA_SMOOTH && r->load <= largest_before;
}

/* Whether the solution's values are what the solver reports: approach and load finite; with a
 * smooth-contact area, N* finite unless the load is tensile (adhesion) and A / A_cone NaN only where
 * there is no compressive load, or one zero to the solver's tolerance; without one (a 2-D profile), both
 * NaN; on a periodic cell, N* NaN and A / A0 as A / A_cone. largest_before: the largest |load| of the rows
 * before. */
static int row_is_finite(const im_history_row *row, int area, double largest_before)
{
    const im_step_result *r = &row->result;
    if (area == IM_HISTORY_AREA_ANY)
        return isfinite(r->approach) && isfinite(r->load);
    int ratio_ok = r->load > 0 && area != IM_HISTORY_AREA_NONE
                       ? isfinite(r->area_ratio) ||
                             (isnan(r->area_ratio) && ratio_may_be_undefined(r, area, largest_before))
                       : isnan(r->area_ratio);
    int n_star_ok = area == IM_HISTORY_AREA_SMOOTH && r->load >= 0 ? isfinite(r->load_star) : isnan(r->load_star);
    return isfinite(r->approach) && isfinite(r->load) && n_star_ok && ratio_ok;
}

int im_history_parse(const char *text, int area, im_history_row *rows, int capacity, int *count, char *why,
                     size_t why_size)
{
    ARG_REQUIRE_OR(text, "text", 0);
    ARG_REQUIRE_OR(rows, "rows", 0);
    ARG_REQUIRE_OR(count, "count", 0);
    ARG_REQUIRE_OR(why, "why", 0);
    size_t columns = strlen(HISTORY_COLUMNS);
    *count = 0;
    if (!text[0]) {
        snprintf(why, why_size, "it is empty: expected the history columns' line, then a row per step");
        return 0;
    }
    if (strncmp(text, HISTORY_COLUMNS, columns) != 0 || text[columns] != '\n') {
        snprintf(why, why_size, "its columns are not this version's history columns (an older version wrote it)");
        return 0;
    }
    double largest = 0.0; /* |load| over the rows read */
    for (const char *line = text + columns + 1; *line; ++*count) {
        const char *next = strchr(line, '\n');
        if (!next || *count >= capacity || !scan_row(line, next, &rows[*count])) {
            snprintf(why, why_size, "row %d is not %d numbers on a whole line", *count + 1, HISTORY_VALUES);
            return 0;
        }
        if (rows[*count].step != *count + 1 || !row_is_finite(&rows[*count], area, largest)) {
            snprintf(why, why_size, "row %d holds a value that is not finite or a step out of order", *count + 1);
            return 0;
        }
        largest = fmax(largest, fabs(rows[*count].result.load));
        line = next + 1;
    }
    return 1;
}
