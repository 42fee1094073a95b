/* The unit of every column of history.csv and indentation.csv, and of the tables a scene writes,
 * for run.json (front.h). */
#include "front/front.h"

#include "indentmap/history.h"
#include "indentmap/status.h"

#include <stdlib.h>
#include <string.h>

#include <stdio.h>

/* What each column is, in the run's base units; IDENTIFIER: a hexadecimal hash (a member's key, checksum). */
typedef enum column_kind {
    NUMBER,
    LENGTH,
    AREA,
    FORCE,
    PRESSURE,
    STIFFNESS,
    WORK,
    SECONDS,
    DEGREES,
    IDENTIFIER
} column_kind;

typedef struct column_unit {
    const char *name;
    column_kind kind;
} column_unit;

static const column_unit COLUMNS[] = {
    /* history.csv (history.h) */
    {"step", NUMBER},
    {"approach", LENGTH},
    {"load", FORCE},
    {"load_star", NUMBER},
    {"contact_patches", NUMBER},
    {"area_ratio", NUMBER},
    {"mean_pressure", PRESSURE},
    {"max_pressure", PRESSURE},
    {"iterations", NUMBER},
    {"residual", NUMBER},
    {"seconds", SECONDS},
    {"convolutions", NUMBER},
    {"load_smooth", FORCE},
    {"area_smooth", AREA},
    {"area_ratio_constant", NUMBER},
    {"area_ratio_gamma", NUMBER},
    {"stiffness", STIFFNESS},
    {"e_star_sneddon", PRESSURE},
    {"patches", NUMBER},
    {"patch_perimeter", LENGTH},
    {"yielding_patches", NUMBER},
    {"plastic_depth", LENGTH},
    {"plastic_work", WORK},
    {"residual_approach", LENGTH},
    {"tensile_force", FORCE},
    {"adhesive_patches", NUMBER},
    {"repulsive_patches", NUMBER},
    {"mean_gap", LENGTH},
    /* indentation.csv (ANALYSIS_COLUMNS) beside the names above */
    {"branch", NUMBER},
    {"top_step", NUMBER},
    {"last_step", NUMBER},
    {"loading_from", NUMBER},
    {"approach_max", LENGTH},
    {"load_max", FORCE},
    {"epsilon", NUMBER},
    {"contact_depth", LENGTH},
    {"area_projected", AREA},
    {"area_real", AREA},
    {"hardness_it", PRESSURE},
    {"modulus_reduced", PRESSURE},
    {"work_in", WORK},
    {"work_out", WORK},
    {"dissipated", WORK},
    {"area_real_theory", AREA},
    {"stiffness_smooth", STIFFNESS},
    /* a scene's results.csv, table1.csv, fig7.csv, sweep.csv, k_fit.csv, flat_k.csv,
       flat/flat_contact.csv and table/member_FF_SEED.csv beside the names above */
    {"family", NUMBER},
    {"height_rms", LENGTH},
    {"key", IDENTIFIER},
    {"checksum", IDENTIFIER},
    {"slope", NUMBER},
    {"seed", NUMBER},
    {"area_ratio_eq12", NUMBER},
    {"surfaces", NUMBER},
    {"height_rms_mean", LENGTH},
    {"rho_c", NUMBER},
    {"n_p_ref", NUMBER},
    {"n_p_mean", NUMBER},
    {"area_ratio_mean", NUMBER},
    {"area_ratio_sd", NUMBER},
    {"relative_error", NUMBER},
    {"n_p_sd", NUMBER},
    {"n_star", NUMBER},
    {"alpha", DEGREES},
    {"hurst", NUMBER},
    {"lambda_s", LENGTH},
    {"slope_rms", NUMBER},
    {"points", NUMBER},
    {"k", NUMBER},
    {"k_error", NUMBER},
    {"rms_residual", NUMBER},
    {"k_linear", NUMBER},
    {"linear_points", NUMBER},
    {"pressure_ratio_min", NUMBER},
    {"pressure_ratio_max", NUMBER},
    {"area_fraction_min", NUMBER},
    {"area_fraction_max", NUMBER},
    {"k_surfaces_mean", NUMBER},
    {"k_surfaces_sem", NUMBER},
    {"k_linear_to_half", NUMBER},
    {"rho_c_k2", NUMBER},
    {"area_ratio_eq12_k2", NUMBER},
    {"area_ratio_simulated", NUMBER},
    {"pressure_ratio", NUMBER},
    {"area_fraction", NUMBER}};

json_t *column_units_record(const char *length, const char *force, const char *pressure)
{
    char area[64], stiffness[96], work[96];
    snprintf(area, sizeof area, "%s²", length);
    snprintf(stiffness, sizeof stiffness, "%s / %s", force, length);
    snprintf(work, sizeof work, "%s %s", force, length);
    const char *const units[] = {"1", length, area, force, pressure, stiffness, work, "s", "°", "hex"};
    json_t *columns = json_object();
    for (size_t i = 0; columns && i < sizeof COLUMNS / sizeof *COLUMNS; ++i)
        if (json_object_set_new(columns, COLUMNS[i].name, json_string(units[COLUMNS[i].kind])) != 0) {
            json_decref(columns);
            return NULL;
        }
    return columns;
}

json_t *indent_units_record(const char *length_unit, const char *e_star_unit, int periodic)
{
    char force[40], stiffness[64], work[64];
    step_force_unit(e_star_unit, length_unit, force, sizeof force);
    const char *length = length_unit[0] ? length_unit : "delta";
    const char *stress = e_star_unit[0] ? e_star_unit : "the unit of --e-star";
    snprintf(stiffness, sizeof stiffness, "(%s) / %s", force, length);
    snprintf(work, sizeof work, "(%s) %s", force, length);
    const char *pressure = e_star_unit[0] ? e_star_unit : "E*";
    return json_pack("{s:s, s:s, s:s, s:s, s:s, s:s, s:s, s:s, s:s, s:s, s:o*}", "length", length, "approach", length,
                     "e_star", e_star_unit[0] ? e_star_unit : "as given (--e-star)", "pressure", stress, "stiffness",
                     stiffness, "work", work, "load", force, "force", force, "load_star",
                     periodic ? "none (nan): periodic" : "contact area A(N) / delta^2 (dimensionless)", "area_ratio",
                     periodic ? "A / A0 of the cell" : "n_p delta^2 / A(N)", "columns",
                     column_units_record(length_unit[0] ? length_unit : "δ", force, pressure));
}

int im_history_units_json(const char *length_unit, const char *e_star_unit, int periodic, char *text, size_t size)
{
    if (!length_unit || !e_star_unit || !text)
        return im_fail(IM_EINVAL, "im_history_units_json: %s is NULL",
                       !length_unit   ? "length_unit"
                       : !e_star_unit ? "e_star_unit"
                                      : "text");
    json_t *record = indent_units_record(length_unit, e_star_unit, periodic);
    char *json = record ? json_dumps(record, JSON_SORT_KEYS) : NULL;
    json_decref(record);
    if (!json)
        return im_fail(IM_ENOMEM, "im_history_units_json: out of memory");
    const size_t length = strlen(json);
    int status = length < size ? IM_OK
                               : im_fail(IM_EINVAL, "im_history_units_json: the text needs %zu bytes, size is %zu",
                                         length + 1, size);
    if (status == IM_OK)
        memcpy(text, json, length + 1);
    free(json);
    return status;
}
