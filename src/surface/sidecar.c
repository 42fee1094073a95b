#include "indentmap/surface.h"
#include "core/args.h"

#include "indentmap/io.h"
#include "indentmap/status.h"
#include "indentmap/theory.h"
#include "io/json_file.h"

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

static json_t *params_json(const im_surface_params *p)
{
    return json_pack("{s:i, s:i, s:f, s:f, s:f, s:f, s:f, s:s, s:f, s:f, s:s, s:I}", "nx", p->nx, "ny", p->ny,
                     "delta", p->delta, "hurst", p->hurst, "lambda_s", p->lambda_s, "lambda_r", p->lambda_r,
                     "lambda_0", p->lambda_0, "target", p->target == IM_TARGET_HEIGHT ? "height_rms" : "slope_rms",
                     "slope_rms", p->slope_rms, "height_rms", p->height_rms, "slope_definition",
                     p->slope_definition == IM_SLOPE_SPECTRAL ? "spectral" : "finite-difference", "seed",
                     (json_int_t)p->seed);
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
