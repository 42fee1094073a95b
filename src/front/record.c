/* The JSON run record of `indent` and of scenes (OUTPUT/run.json): one set of common fields, one
 * writer. */
#include "front/front.h"
#include "io/checksum.h"
#include "io/json_file.h"

#include "indentmap/io.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* The solver options a run was made with. The accelerations of issue 15 are on unless switched
 * off, and off with a hardness (solver.h). */
static json_t *solver_record(const run_record_solver *s)
{
    const im_solver_options *o = s->options;
    const int capped = o->hardness > 0;
    static const char *const devices[] = {[IM_DEVICE_CPU] = "cpu", [IM_DEVICE_GPU] = "gpu", [IM_DEVICE_AUTO] = "auto"};
    return json_pack("{s:s, s:f, s:s, s:f, s:i, s:f, s:b, s:i, s:b, s:b, s:b, s:s}", "quality", s->quality, "tol",
                     o->tol, "tol_from", s->tol_from, "e_star", o->e_star, "max_iterations", o->max_iterations,
                     "hardness", o->hardness, "crop", o->crop, "window_margin", o->window_margin, "cascade",
                     o->cascade && !capped, "precondition", o->precondition && !capped, "fftw_wisdom",
                     im_solver_wisdom_file(o) != NULL, "device", devices[o->device]);
}

/* A number for JSON: null for NaN. */
static json_t *json_number(double value) { return isfinite(value) ? json_real(value) : json_null(); }

static json_t *law_record(const im_solver_options *options, const im_indenter *punch, double delta)
{
    const double length = im_adhesion_zone_length(options),
                 lambda = im_adhesion_maugis_lambda(options, punch->radius);
    json_t *law = json_pack("{s:s, s:f, s:f, s:f, s:f, s:f}", "law", im_adhesion_law_name(options->adhesion_law),
                            "work", options->adhesion_work, "range", options->adhesion_range, "stress",
                            options->adhesion_work / options->adhesion_range, "zone_length", length,
                            "zone_length_patches", length / delta);
    const int sphere = punch->kind == IM_PUNCH_SPHERE;
    if (law) {
        json_object_set_new(law, "maugis_lambda", sphere ? json_number(lambda) : json_null());
        json_object_set_new(law, "tabor_mu",
                            sphere ? json_number(im_adhesion_tabor_mu(options, punch->radius)) : json_null());
    }
    return law;
}

json_t *run_record_adhesion_law(const im_solver_options *options, const im_indenter *punch, double delta)
{
    im_solver_options solved;
    int widened = 0;
    if (im_adhesion_solved_law(options, delta, &solved, &widened) != IM_OK)
        return NULL; /* (the run solving it checked the options) */
    json_t *law = law_record(&solved, punch, delta);
    if (law && options->adhesion_zone > 0)
        json_object_set_new(law, "zone",
                            json_pack("{s:f, s:b, s:o}", "patches", options->adhesion_zone, "widened", widened,
                                      "asked", law_record(options, punch, delta)));
    return law;
}

int run_record_adhesion_summary(json_t *law, const char *dir, const im_history_row *rows, int done,
                                enum im_control control, const char *length_unit, const char *force_unit,
                                const run_figure_texts *texts, im_adhesion_summary *summary)
{
    *summary = (im_adhesion_summary){.work_done = NAN}; /* NaN: not summarised */
    int status = done >= 1
                     ? analysis_write_adhesion(dir, rows, done, control, length_unit, force_unit, texts, summary)
                     : IM_OK;
    if (isnan(summary->work_done))
        return status;
    json_object_set_new(law, "pull_off_force", json_number(summary->pull_off_force));
    json_object_set_new(law, "pull_off_approach", json_number(summary->pull_off_approach));
    json_object_set_new(law, "most_tensile_load", json_number(summary->most_tensile_load));
    json_object_set_new(law, "most_tensile_approach", json_number(summary->most_tensile_approach));
    json_object_set_new(law, "jump_in_approach", json_number(summary->jump_in_approach));
    json_object_set_new(law, "jump_out_approach", json_number(summary->jump_out_approach));
    json_object_set_new(law, "work_done", json_real(summary->work_done));
    json_object_set_new(law, "hysteresis_work", json_number(summary->hysteresis_work));
    json_object_set_new(law, "hysteresis_error", json_real(summary->hysteresis_error));
    json_object_set_new(law, "figure", json_string("force_distance.png"));
    return status;
}

json_t *surface_sidecar_generator(const char *surface_path)
{
    if (!surface_path)
        return NULL;
    char path[PATH_MAX];
    if (im_path_suffix(path, sizeof path, surface_path, ".json") != IM_OK)
        return NULL; /* no sidecar can be there: the surface's own path is refused when read */
    json_t *root = json_file_load(path, 0, NULL);
    json_t *generator = root ? json_incref(json_object_get(root, "generator")) : NULL;
    json_decref(root);
    return generator;
}

int surface_sidecar_slope_definition(const char *surface_path)
{
    json_t *generator = surface_sidecar_generator(surface_path);
    const char *definition = json_string_value(json_object_get(generator, "slope_definition"));
    int chosen = -1; /* the names params_json writes (surface/sidecar.c) */
    if (definition && strcmp(definition, "spectral") == 0)
        chosen = IM_SLOPE_SPECTRAL;
    else if (definition && strcmp(definition, "finite-difference") == 0)
        chosen = IM_SLOPE_FINITE_DIFFERENCE;
    json_decref(generator);
    return chosen;
}

const char *slope_definition_name(int definition)
{
    return definition == IM_SLOPE_FINITE_DIFFERENCE ? "finite differences" : "spectral";
}

json_t *run_record_create(const char *program, const char *input_kind, const char *input_path,
                          const run_record_solver *solver)
{
    char path[4 * PATH_MAX + 1]; /* a path is bytes; JSON is UTF-8 */
    int escaped = input_path ? im_path_utf8(input_path, path, sizeof path) : 0;
    json_t *input = json_pack("{s:s}", "kind", input_kind);
    if (input && input_path)
        json_object_set_new(input, "path", json_string(path));
    if (input && escaped) /* the path is not UTF-8: its other bytes are written \xHH, backslashes \\ */
        json_object_set_new(input, "path_encoding", json_string("escaped"));
    return json_pack("{s:s, s:s, s:o, s:o}", "program", program, "version", IM_VERSION, "input", input, "solver",
                     solver_record(solver));
}

int run_record_write(const char *dir, const json_t *record)
{
    char path[4096];
    int status = im_path_join(path, sizeof path, dir, "run.json");
    if (status != IM_OK)
        return status;
    return json_file_write(path, record);
}

int run_record_add_input(json_t *inputs, const char *key, const char *path)
{
    char hex[IM_SHA256_HEX + 1], absolute[PATH_MAX], text[4 * PATH_MAX + 1];
    int status = im_file_sha256(path, hex);
    if (status == IM_OK)
        status = im_path_absolute(path, absolute, sizeof absolute);
    if (status != IM_OK)
        return status;
    im_path_utf8(absolute, text, sizeof text);
    return json_array_append_new(inputs, json_pack("{s:s, s:s, s:s}", "key", key, "path", text, "sha256", hex)) == 0
               ? IM_OK
               : im_fail(IM_ENOMEM, "run.json: out of memory");
}

int run_record_start(const char *dir, json_t *record)
{
    json_object_set_new(record, "status", json_string("running"));
    json_object_set_new(record, "error", json_string(""));
    return run_record_write(dir, record);
}

/* A start record (run_record_start) whose run ended without its final record is removed: "running" would be
 * false of a run that ended (a full disk: the final write fails and leaves the start record in place). */
static void remove_start_record(const char *dir)
{
    char path[4096];
    if (im_path_join(path, sizeof path, dir, "run.json") == IM_OK)
        unlink(path);
}

int run_record_finish(const char *dir, json_t *record, int steps_done, int status)
{
    const char *was = json_string_value(json_object_get(record, "status"));
    const int started = was && strcmp(was, "running") == 0;
    if (steps_done >= 0)
        json_object_set_new(record, "steps_completed", json_integer(steps_done));
    json_object_set_new(record, "status", json_string(status == IM_OK ? "ok" : im_strstatus(status)));
    char error[4 * 1024 + 1]; /* a message may quote a path that is not UTF-8 */
    im_path_utf8(status == IM_OK ? "" : im_last_error(), error, sizeof error);
    json_object_set_new(record, "error", json_string(error));
    int written = run_record_write(dir, record);
    if (written != IM_OK && started)
        remove_start_record(dir);
    return written;
}

int run_record_load(const char *record, json_t **root)
{
    json_error_t error;
    *root = json_file_load(record, JSON_REJECT_DUPLICATES, &error);
    if (!*root && error.line > 0)
        return im_fail(IM_EFORMAT, "%s:%d: %s: expected a run record (run.json)", record, error.line, error.text);
    if (!*root)
        return im_fail(IM_EFORMAT, "%s: %s: expected a run record (run.json)", record, error.text);
    return IM_OK;
}

int run_record_check_origin(const char *record, const json_t *root, const char *program, const char *kind)
{
    const char *recorded = json_string_value(json_object_get(root, "program"));
    const char *version = json_string_value(json_object_get(root, "version"));
    if (!recorded || strcmp(recorded, program) != 0)
        return im_fail(IM_EFORMAT, "%s: program '%s': expected the record of %s ('%s')", record,
                       recorded ? recorded : "(none)", kind, program);
    if (!version || strcmp(version, IM_VERSION) != 0)
        return im_fail(IM_EINVAL,
                       "%s: made by indentmap %s, this is %s: another version may solve differently in the "
                       "last bits; run it with indentmap %s",
                       record, version ? version : "(none)", IM_VERSION, version ? version : "(the record's)");
    return IM_OK;
}

int run_record_check_input(const char *record, const char *key, const char *path, const char *recorded)
{
    char hex[IM_SHA256_HEX + 1];
    int status = im_file_sha256(path, hex);
    if (status != IM_OK)
        return im_fail_context(status, "%s: the recorded input", record);
    if (strcmp(hex, recorded) != 0)
        return im_fail(IM_EINVAL, "%s: %s has changed since the run: its SHA-256 is %s, the record %s says %s", path,
                       key, hex, record, recorded);
    return IM_OK;
}

/* The inputs as sha256sum lines, "none" without. */
static char *inputs_text(const json_t *inputs)
{
    size_t size = sizeof "none", used = 0, i;
    json_t *input;
    json_array_foreach(inputs, i, input)
        size += strlen(json_string_value(json_object_get(input, "path"))) + IM_SHA256_HEX + 3;
    char *text = malloc(size);
    if (!text)
        return NULL;
    snprintf(text, size, "none");
    json_array_foreach(inputs, i, input) used += (size_t)snprintf(text + used, size - used, "%s  %s\n",
                                                                  json_string_value(json_object_get(input, "sha256")),
                                                                  json_string_value(json_object_get(input, "path")));
    return text;
}

int run_figure_texts_make(const im_png_text *given, int given_count, const json_t *inputs, run_figure_texts *out)
{
    *out = (run_figure_texts){.inputs = inputs_text(inputs)};
    if (!out->inputs)
        return im_fail(IM_ENOMEM, "figure texts: out of memory");
    out->texts[out->count++] = (im_png_text){"Software", "indentmap " IM_VERSION};
    for (int i = 0; i < given_count && out->count < RUN_FIGURE_TEXTS_MAX - 1; ++i)
        out->texts[out->count++] = given[i];
    out->texts[out->count++] = (im_png_text){"Inputs", out->inputs};
    return IM_OK;
}

void run_figure_norm_text(const im_colormap *norm, char *text, size_t size)
{
    snprintf(text, size, "%s [%.9g, %.9g]", norm->logarithmic ? "log" : "linear", norm->lo, norm->hi);
}

void run_figure_texts_free(run_figure_texts *texts)
{
    free(texts->inputs);
    texts->inputs = NULL;
}
