/* run.json of an indentation run (indent_run.h: indent_run_record): the common record (front.h) with
 * the surface, the punch, the targets, the window, the FFT plan, the units, adhesion's law and the
 * arguments it is made again from. */
#include "front/indent_run.h"

#include "indentmap/io.h"
#include "indentmap/status.h"
#include "indentmap/version.h"

#include <limits.h>
#include <omp.h>
#include <string.h>

/* The surface's pixels as read: its spacings along x and y (in the surface's unit), their relative
 * difference, and the resampling onto square pixels (method, spacing and the stored grid), or null. */
static json_t *pixels_record(const im_surface_read_info *info)
{
    json_t *resampled = info->resampled[0] ? json_pack("{s:s, s:f, s:i, s:i}", "method", info->resampled, "delta",
                                                       info->resampled_delta, "stored_nx", info->stored_nx,
                                                       "stored_ny", info->stored_ny)
                                           : json_null();
    return json_pack("{s:f, s:f, s:f, s:f, s:o}", "delta_x", info->used.delta_x, "delta_y", info->used.delta_y,
                     "relative_difference", info->spacing_difference, "tolerance", info->square_tolerance,
                     "resampled", resampled);
}

/* A cone has no radius, a sphere or flat punch no angle, a profile neither (its shape is the file's):
 * their defaults are not the run's (D14). */
static void drop_meaningless_punch_fields(json_t *punch, enum im_punch_kind kind)
{
    if (kind != IM_PUNCH_SPHERE && kind != IM_PUNCH_FLAT)
        json_object_del(punch, "radius");
    if (kind != IM_PUNCH_CONE)
        json_object_del(punch, "alpha_degrees");
}

/* The surface block's additions: its pixels, how its values were converted, its path's encoding. */
static void add_surface_details(const indent_run_state *s, json_t *surface, int escaped)
{
    if (!s->smooth && s->read_info.used.delta_x > 0.0)
        json_object_set_new(surface, "pixels", pixels_record(&s->read_info));
    if (!s->smooth && s->read_info.conversion[0]) /* e.g. the instrument file's module and channel */
        json_object_set_new(surface, "values", json_string(s->read_info.conversion));
    if (escaped) /* the path is not UTF-8: its other bytes are written \xHH, backslashes \\ */
        json_object_set_new(surface, "source_encoding", json_string("escaped"));
}

/* What this run was given beside the common fields (front.h: run_record_create). */
static json_t *indent_blocks(const indent_run_state *s, const im_field *surface, const im_indentation *run)
{
    const im_indent_options *o = s->options;
    im_window w = im_indentation_window(run);
    double ax, ay;
    im_indenter_axis(&s->punch, surface->nx, surface->ny, surface->delta, &ax, &ay);
    json_t *targets = json_array();
    for (int i = 0; i < o->target_count; ++i)
        json_array_append_new(targets, json_real(s->targets[i]));
    char source[4 * PATH_MAX + 1];
    int escaped = im_path_utf8(s->smooth ? "smooth" : o->surface_path, source, sizeof source);
    char preparation[256];
    const surface_preparation prepared = {{o->crop[0], o->crop[1], o->crop[2], o->crop[3]}, o->detrend, o->align};
    surface_preparation_describe(&prepared, s->filled, preparation, sizeof preparation);
    json_t *blocks = json_pack(
        "{s:{s:s, s:i, s:i, s:f, s:s, s:s}, s:{s:s, s:f, s:f, s:f, s:f}, s:s, s:o, s:{s:i, s:i, s:i, s:i}, s:i, "
        "s:s, s:b}",
        "surface", "source", source, "nx", surface->nx, "ny", surface->ny, "delta", surface->delta, "unit",
        surface->unit, "preparation", preparation, "punch", "kind", im_punch_name(s->punch.kind), "alpha_degrees",
        s->punch.alpha_degrees, "radius", s->punch.radius, "x", ax, "y", ay, "control",
        indent_target_name(o->control), "targets", targets, "window", "x0", w.x0, "y0", w.y0, "nx", w.nx, "ny", w.ny,
        "threads", omp_get_max_threads(), "history", "history.csv", "fields", s->files.fields);
    if (!blocks)
        return NULL;
    json_object_set_new(blocks, "periodic", json_boolean(o->solver.periodic));
    json_object_set_new(blocks, "theory_slope_rms",
                        json_pack("{s:f, s:s, s:s}", "value", s->theory_slope, "definition",
                                  slope_definition_name(s->slope_definition), "chosen_by",
                                  s->slope_reason ? s->slope_reason : "none"));
    add_surface_details(s, json_object_get(blocks, "surface"), escaped);
    return blocks;
}

/* The arguments the run is made again from (indent --from-record), and the record it was itself made
 * from (null for a command line). */
static void add_arguments(const im_indent_options *o, json_t *root)
{
    char from[4 * PATH_MAX + 1];
    im_path_utf8(o->from_record ? o->from_record : "", from, sizeof from);
    json_t *arguments = json_array();
    for (int i = 0; i < o->argument_count; ++i)
        json_array_append_new(arguments, json_string(o->arguments[i]));
    json_object_set_new(root, "arguments", arguments);
    if (o->arguments_escaped)
        json_object_set_new(root, "arguments_encoding", json_string("escaped"));
    json_object_set_new(root, "from_record", o->from_record ? json_string(from) : json_null());
}

/* Where the tolerance came from. */
static const char *tolerance_source(const im_indent_options *o)
{
    return o->tol_given ? "--tol" : o->quality ? "--quality" : "default";
}

/* The surface's generator (its sidecar's, written by `indentmap surface`) and seed, and the profile's path
 * (its shape is the file's: drop_meaningless_punch_fields leaves no angle or radius). */
static void add_sources(const indent_run_state *s, json_t *root)
{
    const im_indent_options *o = s->options;
    json_t *generator = surface_sidecar_generator(o->surface_path);
    if (generator) {
        json_object_set(json_object_get(root, "surface"), "generator", generator);
        json_t *seed = json_object_get(generator, "seed");
        if (seed)
            json_object_set(root, "seed", seed);
    }
    if (o->profile_path) {
        char profile[4 * PATH_MAX + 1];
        im_path_utf8(o->profile_path, profile, sizeof profile);
        json_object_set_new(json_object_get(root, "punch"), "profile", json_string(profile));
    }
    json_decref(generator);
}

int indent_run_record_inputs(const im_indent_options *o, json_t *record)
{
    json_t *inputs = json_array();
    int status = inputs ? IM_OK : im_fail(IM_ENOMEM, "run.json: out of memory");
    if (status == IM_OK && o->surface_path)
        status = run_record_add_input(inputs, "surface", o->surface_path);
    if (status == IM_OK && o->profile_path)
        status = run_record_add_input(inputs, "--profile", o->profile_path);
    if (status == IM_OK)
        json_object_set_new(record, "inputs", inputs);
    else
        json_decref(inputs);
    return status;
}

json_t *indent_run_record(const indent_run_state *s, const im_field *surface, const im_indentation *run)
{
    const im_indent_options *o = s->options;
    const im_solver_plan *plan = im_indentation_plan(run);
    run_record_solver solver = {.quality = o->quality     ? o->quality
                                           : o->tol_given ? "none"
                                                          : IM_QUALITY_DEFAULT,
                                .tol_from = tolerance_source(o),
                                .options = &o->solver};
    json_t *root = run_record_create("indentmap indent", s->smooth ? "smooth" : "surface", o->surface_path, &solver);
    json_t *blocks = root ? indent_blocks(s, surface, run) : NULL;
    if (!blocks) {
        json_decref(root);
        return NULL;
    }
    json_object_update(root, blocks);
    json_decref(blocks);
    json_t *solver_block = json_object_get(root, "solver");
    json_object_set_new(solver_block, "fftw_measure", json_boolean(im_solver_plan_measured(plan)));
    json_object_set_new(solver_block, "plan_seconds", json_real(im_solver_plan_seconds(plan)));
    json_object_set_new(root, "device_name", json_string(im_solver_plan_device(plan))); /* beside threads */
    add_sources(s, root);
    drop_meaningless_punch_fields(json_object_get(root, "punch"), s->punch.kind);
    json_object_set_new(root, "units",
                        indent_units_record(surface->unit, o->e_star_unit ? o->e_star_unit : "", o->solver.periodic));
    json_object_set_new(root, "adhesion",
                        o->solver.adhesion_work > 0 ? run_record_adhesion_law(&o->solver, &s->punch, s->surface_delta)
                                                    : json_null());
    add_arguments(o, root);
    return root;
}
