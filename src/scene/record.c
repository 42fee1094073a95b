/* OUTPUT/run.json of a scene run: the common run record (front.h) and the scene's own fields. */
#include "front/front.h"
#include "scene/contents.h"
#include "scene/run_state.h"
#include "scene/outputs.h"
#include "scene/periodic.h"
#include "scene/provenance.h"
#include "scene/punch.h"
#include "scene/record.h"
#include "scene/sweep.h"

#include "indentmap/io.h"
#include "indentmap/status.h"

#include <jansson.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* What the files' h'rms are (surfaces.c: the rule). */
static const char *files_slope_definition(const im_scene *scene)
{
    return scene->run->file_slope_definition == IM_SLOPE_SPECTRAL
               ? "spectral, of each surface as solved; the ensemble's is their root mean square, the h'rms of "
                 "eq. (12)"
               : "forward differences of each surface as solved; the ensemble's is their root mean square, the "
                 "h'rms of eq. (12)";
}

/* The files of a scene over files, each with its measured h'rms and its pixels (the relative difference
 * of its spacings; resampled: the method, or null), how they were read, and what that h'rms is. */
static json_t *files_record(const im_scene *scene)
{
    static const char *const DETREND[] = {"none", "plane", "curvature"};
    static const char *const NPY_ORDER[] = {"sidecar", "yx", "xy"};
    json_t *files = json_array();
    for (int i = 0; i < scene->file_count; ++i) {
        char path[IM_SCENE_PATH];
        im_scene_file_path(scene, i, path, sizeof path);
        json_array_append_new(files,
                              json_pack("{s:s, s:f, s:f, s:o}", "path", path, "slope_rms", scene->run->file_slopes[i],
                                        "spacing_difference", scene->run->file_spacing_differences[i], "resampled",
                                        scene->run->file_resampled[i] ? json_string("bilinear") : json_null()));
    }
    static const char *const ALIGN[] = {"none", "median", "mean", "line"};
    return json_pack("{s:o, s:f, s:s, s:s, s:s, s:b, s:s, s:b, s:s, s:f, s:s}", "files", files, "slope_rms",
                     scene->slopes[0], "slope_definition", files_slope_definition(scene), "detrend",
                     DETREND[scene->detrend], "align", ALIGN[scene->align], "fill", scene->fill, "channel",
                     scene->channel[0] ? scene->channel : "first holding heights", "resample_square",
                     scene->resample_square, "npy_order", NPY_ORDER[scene->npy_order], "delta", scene->surface.delta,
                     "length_unit", scene->file_unit[0] ? scene->file_unit : "delta");
}

/* Where the scene's tolerance came from (a scene keeps the tolerance, not whether it was given:
 * one that differs from its preset's was given as [solver] tol). */
static const char *tolerance_source(const im_scene *scene)
{
    double preset = 0;
    im_quality_tolerance(scene->quality, &preset); /* validated by the parser */
    if (scene->tol != preset)
        return "[solver] tol";
    return strcmp(scene->quality, IM_QUALITY_DEFAULT) == 0 ? "default" : "[scene] quality";
}

/* A profile punch as indent records it: its kind and its file (resolved against the scene's folder;
 * escaped where it is not UTF-8). */
static json_t *profile_record(const im_scene *scene)
{
    char path[4 * IM_SCENE_PATH + 1];
    im_path_utf8(scene->profile_file, path, sizeof path);
    return json_pack("{s:s, s:s}", "kind", im_punch_name(im_profile_kind(scene_profile(scene))), "profile", path);
}

/* A sweep's lists (each given value; one value where the key is not a list) and how many points
 * they make, each a scene of its own in OUTPUT/alpha_A_hurst_H_lambda_s_L/ (sweep.h). */
static json_t *sweep_list(const double *values, int count, double scalar)
{
    json_t *list = json_array();
    for (int i = 0; i < (count > 1 ? count : 1); ++i)
        json_array_append_new(list, json_real(count > 1 ? values[i] : scalar));
    return list;
}

static json_t *sweep_record(const im_scene *scene)
{
    return json_pack("{s:o, s:o, s:o, s:i}", "alpha",
                     sweep_list(scene->alphas, scene->alpha_count, scene->alpha_degrees), "hurst",
                     sweep_list(scene->hursts, scene->hurst_count, scene->surface.hurst), "lambda_s",
                     sweep_list(scene->lambda_ss, scene->lambda_s_count, scene->surface.lambda_s), "points",
                     scene_sweep_count(scene));
}

/* [punch] periodic: the punch, what the steps are and where k of eq. (2) is (null without). */
static json_t *periodic_record(const im_scene *scene)
{
    if (!scene->periodic)
        return json_null();
    const int flat = scene->periodic == IM_SCENE_PERIODIC_FLAT;
    json_t *record = json_pack("{s:s, s:s, s:s}", "punch",
                               flat ? "rigid flat on the whole cell" : im_punch_name(scene->punch), "steps",
                               "mean pressures p_m (units of E*)", "k_fit_slope_rms",
                               "spectral, of each surface as solved");
    json_object_set_new(record, "k_fit", scene_periodic_fits_k(scene) ? json_string("k_fit.csv") : json_null());
    return record;
}

/* What the numbers of the scene's tables are in: lengths in the surfaces' unit (delta for generated
 * ones), pressures in E*, forces in E* times a length squared. */
static json_t *units_record(const im_scene *scene)
{
    const char *length = scene->file_unit[0] ? scene->file_unit : "δ";
    char force[64];
    snprintf(force, sizeof force, "E* %s\u00b2", length);
    return json_pack("{s:s, s:s, s:s, s:o*}", "length", length, "force", force, "pressure", "E*", "columns",
                     column_units_record(length, force, "E*"));
}

/* What makes the run again from its record (provenance.h): the scene's contents, its inputs' SHA-256
 * and the record it was itself rebuilt from (null for a scene file). */
static int add_provenance(const im_scene *scene, json_t *root)
{
    json_t *contents, *inputs = NULL;
    int status = scene_contents_record(scene, &contents);
    if (status == IM_OK)
        status = scene_inputs_record(scene, &inputs);
    if (status != IM_OK) {
        json_decref(contents);
        return im_fail_context(status, "run.json");
    }
    char from[4 * IM_SCENE_PATH + 1];
    im_path_utf8(scene->from_record, from, sizeof from);
    json_object_set_new(root, "scene_contents", contents);
    json_object_set_new(root, "inputs", inputs);
    json_object_set_new(root, "from_record", scene->from_record[0] ? json_string(from) : json_null());
    return IM_OK;
}

/* The h'rms of the theory beside the results: the files' as measured (surfaces.c: the rule), else the
 * generated families' target, by the definition [surfaces] slope_definition names. */
static json_t *theory_slope_record(const im_scene *scene)
{
    if (scene->file_count > 0)
        return json_pack("{s:s, s:s}", "definition", slope_definition_name(scene->run->file_slope_definition),
                         "chosen_by", scene->run->file_slope_reason);
    return json_pack("{s:s, s:s}", "definition", slope_definition_name((int)scene->surface.slope_definition),
                     "chosen_by", "generated surfaces (their target, [surfaces] slope_definition)");
}

/* OUTPUT/run.json: the common record of every front end (front.h), with the scene's path, the
 * surface files it measured, a profile punch's file and a sweep's lists. */
int scene_record_create(const im_scene *scene, json_t **record)
{
    *record = NULL;
    im_solver_options options = scene_solver_options(scene);
    run_record_solver solver = {.quality = scene->quality, .tol_from = tolerance_source(scene), .options = &options};
    json_t *root = run_record_create("indentmap run", "scene", scene->path, &solver);
    if (!root)
        return im_fail(IM_ENOMEM, "run.json: out of memory");
    json_t *input = json_object_get(root, "input");
    json_object_set(root, "scene", json_object_get(input, "path")); /* as before the common record */
    if (json_object_get(input, "path_encoding"))
        json_object_set_new(root, "scene_encoding", json_string("escaped"));
    if (scene->file_count > 0)
        json_object_set_new(root, "surface_files", files_record(scene));
    if (scene_profile(scene))
        json_object_set_new(root, "punch", profile_record(scene));
    if (scene_sweep_count(scene) > 1)
        json_object_set_new(root, "sweep", sweep_record(scene));
    json_object_set_new(root, "adhesion",
                        scene->adhesion_work > 0
                            ? json_pack("{s:s, s:f, s:f, s:f}", "law", im_adhesion_law_name(scene->adhesion_law),
                                        "work", scene->adhesion_work, "range", scene->adhesion_range, "stress",
                                        scene->adhesion_work / scene->adhesion_range)
                            : json_null());
    if (scene->adhesion_zone > 0) /* each history solves the law widened on its grid (solver.h) */
        json_object_set_new(json_object_get(root, "adhesion"), "zone", json_real(scene->adhesion_zone));
    json_object_set_new(root, "periodic", periodic_record(scene));
    json_object_set_new(root, "units", units_record(scene));
    json_object_set_new(root, "theory_slope_rms", theory_slope_record(scene));
    int status = add_provenance(scene, root);
    if (status == IM_OK)
        *record = root;
    else
        json_decref(root);
    return status;
}
