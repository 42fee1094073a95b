/* indentmap indent: an indentation history of a surface by a punch, under displacement or load
 * control, written step by step to DIR/history.csv, with DIR/run.json and optional fields. */
#include "cli/cli.h"

#include "indentmap/field.h"
#include "indentmap/indenter.h"
#include "indentmap/io.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"

#include <getopt.h>
#include <jansson.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_STEPS 100000

static void usage(FILE *stream)
{
    fprintf(stream,
            "usage: indentmap indent (SURFACE | --smooth --n N) (--approach LIST | --load LIST) [OPTIONS]\n\n"
            "Indents SURFACE (.npy, .gsf or text; heights in units of its delta) with a rigid punch and\n"
            "solves each step (FFT boundary elements, Polonsky-Keer CG), warm-started from the last.\n"
            "Units: lengths in delta, stresses in E* (both settable). w counts from first touch.\n\n"
            "  --smooth            a flat surface instead of SURFACE (with --n, --m, --delta)\n"
            "  --n N, --m M        smooth grid size (default 512, M = N)\n"
            "  --delta D           smooth patch side (default 1)\n"
            "  --punch KIND        cone (default), sphere or flat\n"
            "  --alpha A           cone semi-opening angle in degrees, 0 < A < 90 (default 80); below 60\n"
            "                      a warning: small-slope elasticity is stretched (still solved)\n"
            "  --radius R          sphere radius or flat punch radius (required for those)\n"
            "  --x X --y Y         punch axis position (default: centre of patch (nx/2, ny/2))\n"
            "  --approach LIST     imposed approaches w: 'w1,w2,...' or 'a:b:count' (linear, inclusive)\n"
            "  --load LIST         imposed loads N instead (load control), same syntax\n"
            "  --e-star E          composite modulus E* (default 1)\n"
            "  --quality Q         draft (tol 1e-5), standard (1e-6) or publication (1e-9): the solver\n"
            "                      tolerance of a speed/accuracy preset (errors measured in solver.h)\n"
            "  --tol T             stopping tolerance on the relative gap residual (default 1e-8);\n"
            "                      overrides --quality. run.json records quality and tol\n"
            "  --max-iter K        iteration cap per step (default 10000)\n"
            "  --full              solve on the whole surface, not the window that can touch\n"
            "  --measure           plan the FFTs with FFTW_MEASURE (slower planning, faster steps)\n"
            "  --wisdom FILE       FFTW wisdom file (default $IM_FFTW_WISDOM); implies --measure\n"
            "  --out DIR           output folder (default output/indent)\n"
            "  --fields            also write DIR/{force,gap,displacement}_NNNN.npy for every step\n\n"
            "DIR/history.csv is rewritten atomically after every step, so the steps already solved\n"
            "survive a later failure (no convergence: exit 1; contact at the surface's edge: exit 1).\n"
            "At N = 0 the ratio area_ratio = n_p delta^2 / A(N) is undefined and written as nan.\n");
}

typedef struct indent_options {
    const char *surface_path, *out, *wisdom;
    int smooth, nx, ny, m_given, fields;
    double delta;
    im_indenter punch;
    int radius_given, x_given, y_given;
    enum im_control control;
    const char *targets_text;
    const char *quality; /* preset name, NULL if none given */
    int tol_given;
    double *targets;
    int target_count;
    im_solver_options solver;
} indent_options;

enum { OPT_SMOOTH = 256, OPT_N, OPT_M, OPT_DELTA, OPT_PUNCH, OPT_ALPHA, OPT_RADIUS, OPT_X, OPT_Y, OPT_APPROACH,
       OPT_LOAD, OPT_ESTAR, OPT_QUALITY, OPT_TOL, OPT_MAXIT, OPT_FULL, OPT_MEASURE, OPT_WISDOM, OPT_OUT, OPT_FIELDS, OPT_HELP };

static const struct option LONG_OPTIONS[] = {
    {"smooth", no_argument, 0, OPT_SMOOTH}, {"n", required_argument, 0, OPT_N},
    {"m", required_argument, 0, OPT_M}, {"delta", required_argument, 0, OPT_DELTA},
    {"punch", required_argument, 0, OPT_PUNCH}, {"alpha", required_argument, 0, OPT_ALPHA},
    {"radius", required_argument, 0, OPT_RADIUS}, {"x", required_argument, 0, OPT_X},
    {"y", required_argument, 0, OPT_Y}, {"approach", required_argument, 0, OPT_APPROACH},
    {"load", required_argument, 0, OPT_LOAD}, {"e-star", required_argument, 0, OPT_ESTAR},
    {"quality", required_argument, 0, OPT_QUALITY}, {"tol", required_argument, 0, OPT_TOL}, {"max-iter", required_argument, 0, OPT_MAXIT},
    {"full", no_argument, 0, OPT_FULL}, {"measure", no_argument, 0, OPT_MEASURE}, {"wisdom", required_argument, 0, OPT_WISDOM},
    {"out", required_argument, 0, OPT_OUT}, {"fields", no_argument, 0, OPT_FIELDS},
    {"help", no_argument, 0, OPT_HELP}, {0, 0, 0, 0}};

static int parse_punch(const char *text, enum im_punch_kind *kind)
{
    static const enum im_punch_kind KINDS[] = {IM_PUNCH_CONE, IM_PUNCH_SPHERE, IM_PUNCH_FLAT};
    for (int i = 0; i < 3; ++i)
        if (strcmp(text, im_punch_name(KINDS[i])) == 0) {
            *kind = KINDS[i];
            return 0;
        }
    fprintf(stderr, "indentmap: --punch: '%s': expected cone, sphere or flat\n", text);
    return -1;
}

/* 'a:b:count' (count >= 1 values from a to b inclusive) or 'v1,v2,...'. */
static int parse_targets(const char *option, const char *text, double **out, int *count)
{
    double a, b;
    int n;
    char tail;
    if (sscanf(text, "%lf:%lf:%d%c", &a, &b, &n, &tail) == 3) {
        if (!(isfinite(a) && isfinite(b) && a >= 0 && b >= 0) || n < 1 || n > MAX_STEPS) {
            fprintf(stderr, "indentmap: %s '%s': expected a:b:count with a, b >= 0 and 1 <= count <= %d\n",
                    option, text, MAX_STEPS);
            return -1;
        }
        if (!(*out = malloc(sizeof(double) * n)))
            return -1;
        for (int i = 0; i < n; ++i)
            (*out)[i] = n == 1 ? b : a + (b - a) * i / (n - 1);
        *count = n;
        return 0;
    }
    if (strchr(text, ':') || strstr(text, ",,") || text[0] == ',' || (text[0] && text[strlen(text) - 1] == ',')) {
        fprintf(stderr, "indentmap: %s '%s': expected a range a:b:count (three numbers) or a list v1,v2,... "
                "without empty items\n", option, text);
        return -1;
    }
    char *copy = strdup(text), *save = NULL;
    *out = malloc(sizeof(double) * (strlen(text) / 2 + 1));
    *count = 0;
    int status = copy && *out ? 0 : -1;
    for (char *item = strtok_r(copy, ",", &save); item && status == 0; item = strtok_r(NULL, ",", &save))
        status = cli_parse_double(option, item, 0, 1e300, &(*out)[(*count)++]);
    free(copy);
    if (status == 0 && *count == 0) {
        fprintf(stderr, "indentmap: %s: expected a list 'v1,v2,...' or a range 'a:b:count'\n", option);
        status = -1;
    }
    return status;
}

static int apply_option(int code, const char *arg, void *state)
{
    indent_options *o = state;
    switch (code) {
    case OPT_SMOOTH: o->smooth = 1; return 0;
    case OPT_N: return cli_parse_int("--n", arg, 2, IM_FIELD_MAX_SIDE, &o->nx);
    case OPT_M: o->m_given = 1; return cli_parse_int("--m", arg, 2, IM_FIELD_MAX_SIDE, &o->ny);
    case OPT_DELTA: return cli_parse_double("--delta", arg, 1e-300, 1e300, &o->delta);
    case OPT_PUNCH: return parse_punch(arg, &o->punch.kind);
    case OPT_ALPHA: return cli_parse_double("--alpha", arg, -1e300, 1e300, &o->punch.alpha_degrees);
    case OPT_RADIUS: o->radius_given = 1; return cli_parse_double("--radius", arg, -1e300, 1e300, &o->punch.radius);
    case OPT_X: o->x_given = 1; return cli_parse_double("--x", arg, -1e300, 1e300, &o->punch.x0);
    case OPT_Y: o->y_given = 1; return cli_parse_double("--y", arg, -1e300, 1e300, &o->punch.y0);
    case OPT_APPROACH:
    case OPT_LOAD:
        if (o->targets_text) {
            fprintf(stderr, "indentmap: give one of --approach and --load, once\n");
            return -1;
        }
        o->targets_text = arg;
        o->control = code == OPT_LOAD ? IM_CONTROL_LOAD : IM_CONTROL_DISPLACEMENT;
        return parse_targets(code == OPT_LOAD ? "--load" : "--approach", arg, &o->targets, &o->target_count);
    case OPT_ESTAR: return cli_parse_double("--e-star", arg, 1e-300, 1e300, &o->solver.e_star);
    case OPT_QUALITY: o->quality = arg; return 0;
    case OPT_TOL: o->tol_given = 1; return cli_parse_double("--tol", arg, 1e-300, 0.5, &o->solver.tol);
    case OPT_MAXIT: return cli_parse_int("--max-iter", arg, 1, 100000000, &o->solver.max_iterations);
    case OPT_FULL: o->solver.crop = 0; return 0;
    case OPT_MEASURE: o->solver.fft_measure = 1; return 0;
    case OPT_WISDOM: o->wisdom = arg; o->solver.wisdom_path = arg; return 0;
    case OPT_OUT: o->out = arg; return 0;
    case OPT_FIELDS: o->fields = 1; return 0;
    default: return -1;
    }
}

static int check_options(const indent_options *o)
{
    if (!o->targets_text)
        fprintf(stderr, "indentmap: give --approach LIST or --load LIST\n");
    else if (o->smooth == (o->surface_path != NULL))
        fprintf(stderr, "indentmap: give either a SURFACE file or --smooth\n");
    else if (o->punch.kind != IM_PUNCH_CONE && !o->radius_given)
        fprintf(stderr, "indentmap: --punch %s needs --radius\n", im_punch_name(o->punch.kind));
    else if (o->punch.kind == IM_PUNCH_CONE && o->radius_given)
        fprintf(stderr, "indentmap: --radius applies to --punch sphere or flat; a cone's shape is --alpha\n");
    else if (o->x_given != o->y_given)
        fprintf(stderr, "indentmap: give both --x and --y, or neither\n");
    else
        return 0;
    return -1;
}

/* The preset's tolerance, unless --tol was given (it wins, whatever the order). */
static int apply_quality(indent_options *o)
{
    double tol;
    if (!o->quality)
        return 0;
    if (im_quality_tolerance(o->quality, &tol) != IM_OK) {
        fprintf(stderr, "indentmap: --quality: %s\n", im_last_error());
        return -1;
    }
    if (!o->tol_given)
        o->solver.tol = tol;
    return 0;
}

/* Whether `name` is one of the files written into the output folder: history.csv, run.json and,
 * with --fields, {force,gap,displacement}_NNNN.npy for the steps 1..count. */
static int writes_into_folder(const char *name, const void *state)
{
    const indent_options *o = state;
    static const char *const FIELDS[3] = {"force_", "gap_", "displacement_"};
    if (strcmp(name, "history.csv") == 0 || strcmp(name, "run.json") == 0)
        return 1;
    for (int i = 0; o->fields && i < 3; ++i) {
        size_t length = strlen(FIELDS[i]);
        if (strncmp(name, FIELDS[i], length) != 0)
            continue;
        long step = strtol(name + length, NULL, 10);
        char expected[64];
        snprintf(expected, sizeof expected, "%s%04ld.npy", FIELDS[i], step);
        if (step >= 1 && step <= o->target_count && strcmp(name, expected) == 0)
            return 1;
    }
    return 0;
}

/* Refuses an output folder whose outputs would replace the surface file or its sidecar. */
static int check_outputs_apart(const indent_options *o)
{
    char sidecar[4200] = "";
    if (o->surface_path)
        snprintf(sidecar, sizeof sidecar, "%s.json", o->surface_path);
    const char *const inputs[] = {o->surface_path, o->surface_path ? sidecar : NULL};
    return cli_check_output_folder("--out", o->out, writes_into_folder, o, inputs, 2);
}

/* Where the tolerance came from, for run.json. */
static const char *tolerance_source(const indent_options *o)
{
    return o->tol_given ? "--tol" : o->quality ? "--quality" : "default";
}

static int parse_arguments(int argc, char **argv, indent_options *o)
{
    *o = (indent_options){.nx = 512, .ny = 512, .delta = 1, .out = "output/indent",
                          .punch = im_indenter_cone(80), .solver = im_solver_options_default()};
    int parsed = cli_parse_options(argc, argv, LONG_OPTIONS, OPT_HELP, usage, apply_option, o);
    if (parsed != 0)
        return parsed;
    if (optind < argc)
        o->surface_path = argv[optind++];
    if (optind < argc) {
        fprintf(stderr, "indentmap: unexpected argument '%s'\n", argv[optind]);
        return -1;
    }
    if (!o->m_given)
        o->ny = o->nx;
    o->punch.centred = !o->x_given;
    if (check_options(o) != 0 || check_outputs_apart(o) != 0)
        return -1;
    return apply_quality(o);
}

/* ---- outputs ---- */

static const char *HISTORY_HEADER = "step,approach,load,load_star,contact_patches,area_ratio,mean_pressure,"
                                    "max_pressure,iterations,residual,seconds,convolutions\n";

static int write_history(const char *dir, const im_step_result *rows, int count)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/history.csv", dir);
    im_atomic_file file;
    int status = im_atomic_open(&file, path);
    if (status != IM_OK)
        return status;
    fputs(HISTORY_HEADER, file.stream);
    for (int i = 0; i < count; ++i) {
        const im_step_result *r = &rows[i];
        fprintf(file.stream, "%d,%.17g,%.17g,%.17g,%ld,%.17g,%.17g,%.17g,%d,%.6e,%.6f,%d\n", i + 1, r->approach,
                r->load, r->load_star, r->contact_patches, r->area_ratio, r->mean_pressure, r->max_pressure,
                r->iterations, r->residual, r->seconds, r->convolutions);
    }
    return im_atomic_commit(&file);
}

/* Replaces the window's displacement (0 outside it) by the full grid's, and corrects the gap
 * g = g0 - w + u with it, so that no field written shows the solve window. */
static int use_full_displacement(const im_solver_options *options, im_field *force, im_field *gap,
                                 im_field **displacement)
{
    im_field *full = NULL;
    int status = im_displacement_full(force, options, &full);
    if (status != IM_OK)
        return status;
    for (size_t i = 0; i < im_field_count(gap); ++i)
        gap->data[i] += full->data[i] - (*displacement)->data[i];
    im_field_free(*displacement);
    *displacement = full;
    return IM_OK;
}

static int write_fields(const char *dir, const im_indentation *run, const im_solver_options *options, int step)
{
    im_field *f[3] = {NULL, NULL, NULL};
    static const char *const NAMES[3] = {"force", "gap", "displacement"};
    int status = im_indentation_fields(run, &f[0], &f[1], &f[2]);
    if (status == IM_OK)
        status = use_full_displacement(options, f[0], f[1], &f[2]);
    for (int i = 0; i < 3 && status == IM_OK; ++i) {
        char path[4200];
        snprintf(path, sizeof path, "%s/%s_%04d.npy", dir, NAMES[i], step);
        status = im_npy_write(path, f[i], IM_NPY_FLOAT64);
    }
    for (int i = 0; i < 3; ++i)
        im_field_free(f[i]);
    return status;
}

/* The generator block of SURFACE.json (written by `indentmap surface`), or NULL. */
static json_t *surface_sidecar_generator(const char *surface_path)
{
    if (!surface_path)
        return NULL;
    char path[4200];
    snprintf(path, sizeof path, "%s.json", surface_path);
    json_t *root = json_load_file(path, 0, NULL);
    json_t *generator = root ? json_incref(json_object_get(root, "generator")) : NULL;
    json_decref(root);
    return generator;
}

static json_t *run_record(const indent_options *o, const im_field *s, const im_indentation *run)
{
    im_window w = im_indentation_window(run);
    const im_solver_plan *plan = im_indentation_plan(run);
    double ax, ay;
    im_indenter_axis(&o->punch, s->nx, s->ny, s->delta, &ax, &ay);
    json_t *targets = json_array();
    for (int i = 0; i < o->target_count; ++i)
        json_array_append_new(targets, json_real(o->targets[i]));
    json_t *generator = surface_sidecar_generator(o->surface_path);
    json_t *seed = generator ? json_object_get(generator, "seed") : NULL;
    json_t *root = json_pack(
        "{s:s, s:s, s:{s:s, s:i, s:i, s:f, s:O?}, s:{s:s, s:f, s:f, s:f, s:f}, s:s, s:o, "
        "s:{s:s, s:f, s:s, s:f, s:i, s:b, s:f, s:b, s:i}, s:{s:i, s:i, s:i, s:i}, s:i, s:s, s:b}",
        "program", "indentmap indent", "version", IM_VERSION,
        "surface", "source", o->surface_path ? o->surface_path : "smooth", "nx", s->nx, "ny", s->ny,
        "delta", s->delta, "generator", generator,
        "punch", "kind", im_punch_name(o->punch.kind), "alpha_degrees", o->punch.alpha_degrees,
        "radius", o->punch.radius, "x", ax, "y", ay,
        "control", o->control == IM_CONTROL_LOAD ? "load" : "approach", "targets", targets,
        "solver", "quality", o->quality ? o->quality : "none", "tol", o->solver.tol, "tol_from", tolerance_source(o),
        "e_star", o->solver.e_star, "max_iterations", o->solver.max_iterations,
        "fftw_measure", im_solver_plan_measured(plan), "plan_seconds", im_solver_plan_seconds(plan),
        "crop", o->solver.crop, "window_margin", o->solver.window_margin, /* the options the run was made with */
        "window", "x0", w.x0, "y0", w.y0, "nx", w.nx, "ny", w.ny, "threads", omp_get_max_threads(),
        "history", "history.csv", "fields", o->fields);
    if (root && seed)
        json_object_set(root, "seed", seed);
    json_decref(generator);
    return root;
}

static int write_run_json(const char *dir, json_t *record, int steps_done, int status)
{
    json_object_set_new(record, "steps_completed", json_integer(steps_done));
    json_object_set_new(record, "status", json_string(status == IM_OK ? "ok" : im_strstatus(status)));
    json_object_set_new(record, "error", json_string(status == IM_OK ? "" : im_last_error()));
    char *text = json_dumps(record, JSON_INDENT(2) | JSON_REAL_PRECISION(17));
    if (!text)
        return im_fail(IM_ENOMEM, "run.json");
    char path[4200];
    snprintf(path, sizeof path, "%s/run.json", dir);
    size_t length = strlen(text);
    text[length] = '\n';
    int written = im_write_file_atomic(path, text, length + 1);
    free(text);
    return written;
}

/* ---- the run ---- */

/* Small-slope (linear) elasticity assumes the surface slopes are small; a steep cone's flank,
 * slope cot(alpha), stretches it. Warn, but still solve: the answer is the model's, not nature's. */
#define STEEP_CONE_DEGREES 60.0

static void warn_if_steep(const im_indenter *punch)
{
    if (punch->kind == IM_PUNCH_CONE && punch->alpha_degrees > 0 && punch->alpha_degrees < STEEP_CONE_DEGREES)
        fprintf(stderr,
                "indentmap: warning: alpha = %g degrees: the cone flank's slope cot(alpha) = %.3g is not small; "
                "small-slope elasticity is stretched (alpha >= %g advised)\n",
                punch->alpha_degrees, 1 / tan(punch->alpha_degrees * M_PI / 180), STEEP_CONE_DEGREES);
}

static int load_surface(const indent_options *o, im_field **surface)
{
    if (!o->smooth)
        return im_surface_read(o->surface_path, surface);
    return im_field_create(o->nx, o->ny, o->delta, surface);
}

/* --x/--y must put the punch's axis on the surface (before: "the surface is too small"). */
static int check_axis_inside(const indent_options *o, const im_field *surface)
{
    double width = surface->nx * surface->delta, height = surface->ny * surface->delta;
    if (!o->x_given || (o->punch.x0 >= 0 && o->punch.x0 <= width && o->punch.y0 >= 0 && o->punch.y0 <= height))
        return IM_OK;
    return im_fail(IM_EINVAL, "--x %g --y %g: the punch's axis lies outside the %d x %d surface (expected 0 <= x <= "
                   "%g and 0 <= y <= %g)", o->punch.x0, o->punch.y0, surface->nx, surface->ny, width, height);
}

static double largest(const double *v, int n)
{
    double m = 0;
    for (int i = 0; i < n; ++i)
        m = fmax(m, v[i]);
    return m;
}

static int run_steps(const indent_options *o, im_indentation *run, json_t *record)
{
    im_step_result *rows = calloc((size_t)o->target_count, sizeof *rows);
    if (!rows)
        return im_fail(IM_ENOMEM, "history of %d steps", o->target_count);
    int status = IM_OK, done = 0;
    for (; done < o->target_count && status == IM_OK; ++done) {
        if (cli_stop_signal) { /* checked between steps: a solve is never cut short */
            status = im_fail(IM_EINTERRUPTED, "interrupted by signal %d", (int)cli_stop_signal);
            break;
        }
        status = im_indentation_step(run, o->targets[done], &rows[done]);
        if (status != IM_OK)
            break;
        status = write_history(o->out, rows, done + 1);
        if (status == IM_OK && o->fields)
            status = write_fields(o->out, run, &o->solver, done + 1);
        const im_step_result *r = &rows[done];
        printf("step %d: w = %.6g  N = %.6g  n_p = %ld  A/A0 = %.4f  iterations %d  residual %.2e  %.3f s\n",
               done + 1, r->approach, r->load, r->contact_patches, r->area_ratio, r->iterations, r->residual,
               r->seconds);
        fflush(stdout);
    }
    if (status != IM_OK)
        im_fail_context(status, "step %d of %d (%s %g; the %d steps before are in %s/history.csv)", done + 1,
                        o->target_count, o->control == IM_CONTROL_LOAD ? "load" : "approach",
                        o->targets[done < o->target_count ? done : o->target_count - 1], done, o->out);
    char message[1024];
    snprintf(message, sizeof message, "%s", im_last_error());
    write_run_json(o->out, record, done, status);
    if (status != IM_OK)
        im_fail(status, "%s", message);
    free(rows);
    return status;
}

int cli_indent(int argc, char **argv)
{
    indent_options o;
    int parsed = parse_arguments(argc, argv, &o);
    if (parsed != 0) {
        if (parsed < 0)
            fprintf(stderr, "(indentmap indent --help lists the options)\n");
        free(o.targets);
        return parsed > 0 ? CLI_EXIT_OK : CLI_EXIT_USAGE;
    }
    im_field *surface = NULL;
    im_indentation *run = NULL;
    json_t *record = NULL;
    int status = cli_interrupt_install() == 0 ? im_indenter_check(&o.punch)
                                              : im_fail(IM_EUNSUPPORTED, "cannot install the signal handlers");
    if (status == IM_OK) {
        warn_if_steep(&o.punch);
        status = load_surface(&o, &surface);
    }
    if (status == IM_OK)
        status = check_axis_inside(&o, surface);
    if (status == IM_OK)
        status = im_indentation_create(surface, &o.punch, o.control, largest(o.targets, o.target_count), &o.solver,
                                       &run);
    if (status == IM_OK)
        status = im_make_directories(o.out);
    if (status == IM_OK) {
        im_window w = im_indentation_window(run);
        printf("surface %d x %d, window [%d, %d) x [%d, %d) (%d x %d), %d threads\n", surface->nx, surface->ny,
               w.x0, w.x0 + w.nx, w.y0, w.y0 + w.ny, w.nx, w.ny, omp_get_max_threads());
        record = run_record(&o, surface, run);
        status = record ? write_history(o.out, NULL, 0) : im_fail(IM_ENOMEM, "run record");
    }
    if (status == IM_OK)
        status = run_steps(&o, run, record);
    json_decref(record);
    im_indentation_free(run);
    im_field_free(surface);
    free(o.targets);
    if (status == IM_EINTERRUPTED) {
        fprintf(stderr, "indentmap: %s\n", im_last_error());
        return cli_interrupt_exit_status();
    }
    return status == IM_OK ? CLI_EXIT_OK : cli_report(status);
}
