#include "indentmap/surface.h"
#include "core/args.h"

#include "indentmap/io.h"
#include "indentmap/status.h"
#include "indentmap/theory.h"
#include "io/json_file.h"

#include <inttypes.h>
#include <jansson.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static double q_r_of(const im_surface_params *p) { return 2.0 * M_PI / (p->lambda_r * p->delta); }
static double zeta_of(const im_surface_params *p) { return p->lambda_r / p->lambda_s; }

double im_surface_expected_height_rms(const im_surface_params *p, double slope_rms)
{
    ARG_REQUIRE_OR(p, "params", NAN);
    double x = p->lambda_0 > p->lambda_r ? p->lambda_r / p->lambda_0 : 1.0;
    return im_theory_height_rms_moments(slope_rms, p->hurst, q_r_of(p), zeta_of(p), x);
}

double im_surface_height_rms_eq15(const im_surface_params *p, double slope_rms)
{
    ARG_REQUIRE_OR(p, "params", NAN);
    return im_theory_height_rms_eq15(slope_rms, p->hurst, q_r_of(p) * zeta_of(p), zeta_of(p));
}

/* The generator record. lambda_0 is the longest wavelength in effect: one up to lambda_r (no plateau) is
 * recorded as lambda_r, as `indentmap surface` sets it, so that the record of a surface depends on the
 * surface's parameters only, not on how a caller spelt "no plateau". The seed is written as the unsigned
 * decimal the user gave (json_unsigned: 2^63 and more too, which JSON's signed integers do not hold). */
static json_t *params_json(const im_surface_params *p)
{
    return json_pack("{s:i, s:i, s:f, s:f, s:f, s:f, s:f, s:s, s:f, s:f, s:s, s:o}", "nx", p->nx, "ny", p->ny,
                     "delta", p->delta, "hurst", p->hurst, "lambda_s", p->lambda_s, "lambda_r", p->lambda_r,
                     "lambda_0", fmax(p->lambda_0, p->lambda_r), "target",
                     p->target == IM_TARGET_HEIGHT ? "height_rms" : "slope_rms", "slope_rms", p->slope_rms,
                     "height_rms", p->height_rms, "slope_definition",
                     p->slope_definition == IM_SLOPE_SPECTRAL ? "spectral" : "finite-difference", "seed",
                     json_unsigned(p->seed));
}

int im_surface_generator_record(const im_surface_params *params, char **text)
{
    ARG_REQUIRE(params, "params");
    ARG_REQUIRE(text, "text");
    *text = NULL;
    int status = im_surface_params_check(params);
    if (status != IM_OK)
        return status;
    json_t *record = params_json(params);
    *text = record ? json_text(record, JSON_COMPACT | JSON_REAL_PRECISION(17)) : NULL;
    json_decref(record);
    return *text ? IM_OK : im_fail(IM_ENOMEM, "generator: cannot build the JSON record");
}

/* The record's string `key`, one of the two names; its index in names, or -1 with the message. */
static int choice_member(json_t *record, const char *key, const char *const names[2])
{
    const char *value = json_string_value(json_object_get(record, key));
    for (int i = 0; value && i < 2; ++i)
        if (strcmp(value, names[i]) == 0)
            return i;
    im_fail(IM_EINVAL, "generator: \"%s\": expected \"%s\" or \"%s\"", key, names[0], names[1]);
    return -1;
}

/* The record's integer `key` within [lo, hi] into *out, else IM_EINVAL naming it. */
static int integer_member(json_t *record, const char *key, json_int_t lo, json_int_t hi, json_int_t *out)
{
    json_t *value = json_object_get(record, key);
    if (!json_is_integer(value) || json_integer_value(value) < lo || json_integer_value(value) > hi)
        return im_fail(IM_EINVAL, "generator: \"%s\": expected an integer in [%lld, %lld]", key, (long long)lo,
                       (long long)hi);
    *out = json_integer_value(value);
    return IM_OK;
}

/* IM_OK when the record holds exactly the keys params_json writes (a misspelt key would otherwise be a
 * default silently taken); else IM_EINVAL naming the first unknown or missing one. */
static int check_generator_keys(json_t *record)
{
    const im_surface_params defaults = im_surface_params_default();
    json_t *keys = params_json(&defaults);
    const char *key, *missing = NULL, *unknown = NULL;
    json_t *value;
    json_object_foreach(record, key, value)
    {
        if (!unknown && !json_object_get(keys, key))
            unknown = key;
    }
    json_object_foreach(keys, key, value)
    {
        if (!missing && !json_object_get(record, key))
            missing = key;
    }
    int status = !keys     ? im_fail(IM_ENOMEM, "generator: out of memory")
                 : unknown ? im_fail(IM_EINVAL, "generator: \"%.60s\": not a key of the record", unknown)
                 : missing ? im_fail(IM_EINVAL, "generator: \"%s\" is missing", missing)
                           : IM_OK;
    json_decref(keys);
    return status;
}

/* The record's real members into p, else IM_EINVAL naming the first that is not a number. */
static int real_members(json_t *record, im_surface_params *p)
{
    struct {
        const char *key;
        double *value;
    } reals[] = {{"delta", &p->delta},          {"hurst", &p->hurst},       {"lambda_s", &p->lambda_s},
                 {"lambda_r", &p->lambda_r},    {"lambda_0", &p->lambda_0}, {"slope_rms", &p->slope_rms},
                 {"height_rms", &p->height_rms}};
    for (size_t i = 0; i < sizeof reals / sizeof reals[0]; ++i) {
        json_t *value = json_object_get(record, reals[i].key);
        if (!json_is_number(value))
            return im_fail(IM_EINVAL, "generator: \"%s\": expected a number", reals[i].key);
        *reals[i].value = json_number_value(value);
    }
    return IM_OK;
}

static int record_params(json_t *record, im_surface_params *p)
{
    static const char *const TARGETS[] = {"slope_rms", "height_rms"};
    static const char *const DEFINITIONS[] = {"spectral", "finite-difference"};
    json_int_t nx = 0, ny = 0;
    int status = check_generator_keys(record);
    if (status == IM_OK)
        status = integer_member(record, "nx", 2, IM_FIELD_MAX_SIDE, &nx);
    if (status == IM_OK)
        status = integer_member(record, "ny", 2, IM_FIELD_MAX_SIDE, &ny);
    if (status == IM_OK && json_unsigned_value(json_object_get(record, "seed"), &p->seed) != 0)
        status = im_fail(IM_EINVAL, "generator: \"seed\": expected an integer in [0, %" PRIu64 "]", UINT64_MAX);
    if (status == IM_OK)
        status = real_members(record, p);
    if (status != IM_OK)
        return status;
    const int target = choice_member(record, "target", TARGETS);
    const int definition = target < 0 ? -1 : choice_member(record, "slope_definition", DEFINITIONS);
    if (definition < 0)
        return IM_EINVAL;
    p->nx = (int)nx;
    p->ny = (int)ny;
    p->target = target == 0 ? IM_TARGET_SLOPE : IM_TARGET_HEIGHT;
    p->slope_definition = definition == 0 ? IM_SLOPE_SPECTRAL : IM_SLOPE_FINITE_DIFFERENCE;
    status = im_surface_params_check(p);
    return status == IM_OK ? IM_OK : im_fail_context(status, "generator");
}

int im_surface_generator_parse(const char *text, im_surface_params *params)
{
    ARG_REQUIRE(text, "text");
    ARG_REQUIRE(params, "params");
    json_error_t error;
    json_t *record = json_text_load(text, JSON_REJECT_DUPLICATES, &error);
    im_surface_params p = im_surface_params_default();
    int status = json_is_object(record)
                     ? record_params(record, &p)
                     : im_fail(IM_EINVAL, "generator: expected a JSON object of the generator's record (%s)",
                               record ? "another JSON value" : error.text);
    json_decref(record);
    if (status == IM_OK)
        *params = p;
    return status;
}

static json_t *stats_json(const im_surface_stats *s)
{
    return json_pack("{s:f, s:f, s:f, s:f, s:f, s:f, s:f, s:f, s:f, s:f, s:f}", "mean", s->mean, "height_rms",
                     s->height_rms, "slope_rms_spectral", s->slope_rms_spectral, "slope_rms_fd", s->slope_rms_fd,
                     "curvature_rms", s->curvature_rms, "m0", s->m0, "m2", s->m2, "m4", s->m4, "nayak",
                     isfinite(s->nayak) ? s->nayak : 0.0, "height_min", s->height_min, "height_max", s->height_max);
}

int im_surface_sidecar_write(const char *path, const im_field *surface, const im_surface_params *params,
                             const char *source, const im_surface_stats *stats)
{
    ARG_REQUIRE(path, "path");
    ARG_VIEW(surface, "surface");
    json_t *root = json_pack("{s:s, s:s, s:i, s:i, s:f, s:s}", "program", "indentmap", "version", IM_VERSION, "nx",
                             surface->nx, "ny", surface->ny, "delta", surface->delta, "unit", surface->unit);
    if (!root)
        return im_fail(IM_ENOMEM, "%s: cannot build the JSON record", path);
    if (params) {
        json_object_set_new(root, "generator", params_json(params));
        json_object_set_new(root, "height_rms_eq13",
                            json_real(im_surface_expected_height_rms(params, stats->slope_rms_spectral)));
        json_object_set_new(root, "height_rms_eq15",
                            json_real(im_surface_height_rms_eq15(params, stats->slope_rms_spectral)));
    }
    if (source) { /* a path is bytes; JSON is UTF-8: other bytes are escaped, and that is said */
        char text[4 * 4096 + 1];
        if (im_path_utf8(source, text, sizeof text))
            json_object_set_new(root, "source_encoding", json_string("escaped"));
        json_object_set_new(root, "source", json_string(text));
    }
    json_object_set_new(root, "statistics", stats_json(stats));
    int status = json_file_write(path, root);
    json_decref(root);
    return status;
}
