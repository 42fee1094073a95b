/* indentmap indent: an indentation history of a surface by a punch, under displacement or load
 * control, written step by step to DIR/history.csv, with DIR/run.json and optional fields. */
#include "cli/cli.h"

#include "indentmap/field.h"
#include "indentmap/indenter.h"
#include "indentmap/io.h"
#include "indentmap/measure.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "indentmap/viewer.h"
#include "indentmap/surface.h"
#include "indentmap/theory.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <getopt.h>
#include <jansson.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define MAX_STEPS 100000

static void usage(FILE *stream)
{
    fprintf(stream,
            "usage: indentmap indent (SURFACE | --smooth --n N) (--approach LIST | --load LIST) [OPTIONS]\n\n"
            "Indents SURFACE (.npy, .gsf, .sdf, .nc, .x3p or text) with a rigid punch and solves each\n"
            "step (FFT boundary elements, Polonsky-Keer CG), warm-started from the last. Units: lengths\n"
            "in the surface's unit (its spacing delta when it states none), stresses in E* (settable).\n"
            "w counts from first touch.\n\n"
            "  --smooth            a flat surface instead of SURFACE (with --n, --m, --delta)\n"
            "  --n N, --m M        smooth grid size (default 512, M = N)\n"
            "  --delta D           patch side: of the smooth surface (default 1), or overriding SURFACE's\n"
            "  --unit U            length unit of delta (m, mm, um, nm, ...); overrides SURFACE's\n"
            "  --height-unit U     unit of SURFACE's heights, converted to --unit (default: --unit)\n"
            "  --length-unit U     solve in this length unit (m: SI): SURFACE's spacing and heights are\n"
            "                      converted into it; approaches, gaps and displacements are in it\n"
            "  --e-star-unit U     the unit of --e-star (e.g. Pa), for the records: forces are in\n"
            "                      U x length unit^2 (N for Pa and m)\n"
            "  --fill              fill SURFACE's missing points (NaN) from their neighbours (default: refuse)\n"
            "  --crop X0,Y0,NX,NY  indent only this block of SURFACE\n"
            "  --detrend D         none (default), plane or curvature: removed from SURFACE before solving\n"
            "  --punch KIND        cone (default), sphere or flat\n"
            "  --alpha A           cone semi-opening angle in degrees, 0 < A < 90 (default 80); below 60\n"
            "                      a warning: small-slope elasticity is stretched (still solved)\n"
            "  --radius R          sphere radius or flat punch radius (required for those)\n"
            "  --x X --y Y         punch axis position (default: centre of patch (nx/2, ny/2))\n"
            "  --approach LIST     imposed approaches w: 'w1,w2,...' or 'a:b:count' (linear, inclusive)\n"
            "  --load LIST         imposed loads N instead (load control), same syntax\n"
            "  --e-star E          composite modulus E* (default 1)\n"
            "  --hardness H        perfect plasticity: no patch carries more than H (units of E*'s\n"
            "                      stress); default none\n"
            "  --quality Q         draft (tol 1e-5), standard (1e-6) or publication (1e-9): the solver\n"
            "                      tolerance of a speed/accuracy preset (errors measured in solver.h)\n"
            "  --tol T             stopping tolerance on the relative gap residual (default 1e-8);\n"
            "                      overrides --quality. run.json records quality and tol\n"
            "  --max-iter K        iteration cap per step (default 10000)\n"
            "  --full              solve on the whole surface, not the window that can touch\n"
            "  --plain-pk          plain Polonsky-Keer CG from the local guess: no cascade cold start, no\n"
            "                      preconditioner (the same answers to the tolerance, slower; docs/solver.md)\n"
            "  --measure           plan the FFTs with FFTW_MEASURE (slower planning, faster steps)\n"
            "  --wisdom FILE       FFTW wisdom file, read before planning and updated after it; implies\n"
            "                      --measure. Default: $IM_FFTW_WISDOM, else for runs of 10 steps or more\n"
            "                      the user's cache ($XDG_CACHE_HOME or ~/.cache)/indentmap/fftw-wisdom\n"
            "  --no-wisdom         no wisdom file (also IM_FFTW_WISDOM=\"\"): FFTW_ESTIMATE plans\n"
            "  --out DIR           output folder (default output/indent)\n"
            "  --fields            also write DIR/{force,gap,displacement}_NNNN.npy for every step\n\n"
            "DIR/history.csv gets one whole line per step, appended and synced as soon as the step is\n"
            "solved, so the steps already solved survive a later failure or a crash (no convergence:\n"
            "exit 1; contact at the surface's edge: exit 1). DIR is locked while the run writes there\n"
            "(DIR/.lock, as for scenes); the field files of an earlier run in DIR are removed first.\n"
            "At N = 0 the ratio area_ratio = n_p delta^2 / A(N) is undefined and written as nan.\n");
}

/* Runs of at least this many steps keep FFTW wisdom in the user's cache by default. */
enum { CACHED_WISDOM_STEPS = 10 };

typedef struct indent_options {
    const char *surface_path, *out, *wisdom;
    int no_wisdom;
    char wisdom_cache[4096];      /* the cache's wisdom file, when that is the one used */
    int smooth, nx, ny, m_given, fields;
    double delta;
    im_surface_read_options read; /* --delta, --unit, --height-unit, --fill for a surface file */
    cli_preparation preparation;  /* --crop, --detrend */
    char e_star_unit[16];         /* --e-star-unit, "" when not given */
    char force_unit[40];          /* the unit of loads and forces, from the two above */
    char length_unit[16];         /* the surface's, as solved ("" in units of delta) */
    long filled;                  /* missing points filled on reading */
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

enum { OPT_SMOOTH = 256, OPT_N, OPT_M, OPT_DELTA, OPT_UNIT, OPT_HEIGHT_UNIT, OPT_LENGTH_UNIT, OPT_ESTAR_UNIT, OPT_FILL,
       OPT_CROP, OPT_DETREND, OPT_PUNCH, OPT_ALPHA, OPT_RADIUS, OPT_X, OPT_Y, OPT_APPROACH, OPT_LOAD, OPT_ESTAR,
       OPT_HARDNESS, OPT_QUALITY, OPT_TOL, OPT_MAXIT, OPT_FULL, OPT_MEASURE, OPT_WISDOM, OPT_OUT, OPT_FIELDS,
       OPT_HELP, OPT_PLAIN_PK, OPT_NO_WISDOM };

static const struct option LONG_OPTIONS[] = {
    {"smooth", no_argument, 0, OPT_SMOOTH}, {"n", required_argument, 0, OPT_N},
    {"m", required_argument, 0, OPT_M}, {"delta", required_argument, 0, OPT_DELTA},
    {"unit", required_argument, 0, OPT_UNIT}, {"height-unit", required_argument, 0, OPT_HEIGHT_UNIT},
    {"fill", no_argument, 0, OPT_FILL}, {"crop", required_argument, 0, OPT_CROP},
    {"length-unit", required_argument, 0, OPT_LENGTH_UNIT}, {"e-star-unit", required_argument, 0, OPT_ESTAR_UNIT},
    {"detrend", required_argument, 0, OPT_DETREND}, {"punch", required_argument, 0, OPT_PUNCH}, {"alpha", required_argument, 0, OPT_ALPHA},
    {"radius", required_argument, 0, OPT_RADIUS}, {"x", required_argument, 0, OPT_X},
    {"y", required_argument, 0, OPT_Y}, {"approach", required_argument, 0, OPT_APPROACH},
    {"load", required_argument, 0, OPT_LOAD}, {"e-star", required_argument, 0, OPT_ESTAR},
    {"hardness", required_argument, 0, OPT_HARDNESS},
    {"quality", required_argument, 0, OPT_QUALITY}, {"tol", required_argument, 0, OPT_TOL}, {"max-iter", required_argument, 0, OPT_MAXIT},
    {"full", no_argument, 0, OPT_FULL}, {"measure", no_argument, 0, OPT_MEASURE}, {"wisdom", required_argument, 0, OPT_WISDOM},
    {"no-wisdom", no_argument, 0, OPT_NO_WISDOM},
    {"out", required_argument, 0, OPT_OUT}, {"fields", no_argument, 0, OPT_FIELDS},
    {"help", no_argument, 0, OPT_HELP}, {"plain-pk", no_argument, 0, OPT_PLAIN_PK}, {0, 0, 0, 0}};

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
    if (status == 0 && *count > MAX_STEPS) { /* as for a range: the step files are numbered NNNN */
        fprintf(stderr, "indentmap: %s: %d values: expected at most %d steps\n", option, *count, MAX_STEPS);
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
    case OPT_DELTA:
        if (cli_parse_double("--delta", arg, 1e-300, 1e300, &o->delta) != 0)
            return -1;
        o->read.set.delta_x = o->delta;
        return 0;
    case OPT_UNIT: return cli_parse_length_unit("--unit", arg, o->read.set.lateral);
    case OPT_HEIGHT_UNIT: return cli_parse_length_unit("--height-unit", arg, o->read.set.height);
    case OPT_FILL: o->read.fill = 1; return 0;
    case OPT_LENGTH_UNIT: return cli_parse_length_unit("--length-unit", arg, o->read.express_in);
    case OPT_ESTAR_UNIT: return cli_parse_name("--e-star-unit", arg, o->e_star_unit, sizeof o->e_star_unit);
    case OPT_CROP: return cli_parse_crop(arg, o->preparation.crop);
    case OPT_DETREND: return cli_parse_detrend(arg, &o->preparation.detrend);
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
    case OPT_HARDNESS: return cli_parse_double("--hardness", arg, 1e-300, 1e300, &o->solver.hardness);
    case OPT_QUALITY: o->quality = arg; return 0;
    case OPT_TOL: o->tol_given = 1; return cli_parse_double("--tol", arg, 1e-300, 0.5, &o->solver.tol);
    case OPT_MAXIT: return cli_parse_int("--max-iter", arg, 1, 100000000, &o->solver.max_iterations);
    case OPT_FULL: o->solver.crop = 0; return 0;
    case OPT_PLAIN_PK: o->solver.cascade = o->solver.precondition = 0; return 0;
    case OPT_MEASURE: o->solver.fft_measure = 1; return 0;
    case OPT_WISDOM: o->wisdom = arg; return 0;
    case OPT_NO_WISDOM: o->no_wisdom = 1; return 0;
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

/* Whether name is PREFIX followed by four or more digits and ".npy" (a field file of a step) or
 * ".npy.json" (its units sidecar). */
static int is_step_file(const char *name, const char *prefix)
{
    size_t length = strlen(prefix), digits = 0;
    if (strncmp(name, prefix, length) != 0)
        return 0;
    while (name[length + digits] >= '0' && name[length + digits] <= '9')
        ++digits;
    const char *suffix = name + length + digits;
    return digits >= 4 && (strcmp(suffix, ".npy") == 0 || strcmp(suffix, ".npy.json") == 0);
}

/* Whether `name` is one of the files written into the output folder: history.csv, run.json,
 * index.html and,
 * with --fields, {force,gap,displacement}_NNNN.npy and their .npy.json sidecars for the steps 1..count. */
static int writes_into_folder(const char *name, const void *state)
{
    const indent_options *o = state;
    static const char *const FIELDS[3] = {"force_", "gap_", "displacement_"};
    if (strcmp(name, "history.csv") == 0 || strcmp(name, "run.json") == 0 || strcmp(name, "index.html") == 0)
        return 1;
    for (int i = 0; o->fields && i < 3; ++i) {
        size_t length = strlen(FIELDS[i]);
        if (strncmp(name, FIELDS[i], length) != 0)
            continue;
        long step = strtol(name + length, NULL, 10);
        char field[64], sidecar[80];
        snprintf(field, sizeof field, "%s%04ld.npy", FIELDS[i], step);
        snprintf(sidecar, sizeof sidecar, "%s.json", field);
        if (step >= 1 && step <= o->target_count && (strcmp(name, field) == 0 || strcmp(name, sidecar) == 0))
            return 1;
    }
    return 0;
}

/* The wisdom file may be neither an input (checked with the inputs) nor one of the files the run
 * writes into --out: each would replace the other. */
static int check_wisdom(const indent_options *o)
{
    if (im_solver_wisdom_check(&o->solver) != IM_OK) {
        fprintf(stderr, "indentmap: %s\n", im_last_error());
        return -1;
    }
    const char *wisdom = im_solver_wisdom_file(&o->solver);
    char file[4200], folder[4200];
    if (!wisdom || im_path_absolute(wisdom, file, sizeof file) != IM_OK ||
        im_path_absolute(o->out, folder, sizeof folder) != IM_OK)
        return 0;
    size_t length = strlen(folder);
    if (strncmp(file, folder, length) != 0 || file[length] != '/' || !writes_into_folder(file + length + 1, o))
        return 0;
    fprintf(stderr, "indentmap: the FFTW wisdom file %s would be one of the run's outputs, %s/%s: give another "
            "--wisdom (or IM_FFTW_WISDOM) or another --out\n", wisdom, o->out, file + length + 1);
    return -1;
}

/* Refuses, before any work, an output folder whose outputs would replace the surface file or its
 * sidecar, and a wisdom file that is an input or an output. Every write is checked again when it
 * is opened (io.h: the output guard). */
static int check_outputs_apart(const indent_options *o)
{
    char sidecar[4200] = "";
    if (o->surface_path)
        snprintf(sidecar, sizeof sidecar, "%s.json", o->surface_path);
    const char *const inputs[] = {o->surface_path, o->surface_path ? sidecar : NULL};
    if (cli_protect_inputs(inputs, 1) != 0 || cli_check_output_folder("--out", o->out, writes_into_folder, o, inputs, 2) != 0)
        return -1;
    return check_wisdom(o);
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
    if (check_options(o) != 0)
        return -1;
    /* The cache only for histories: measuring pays within a 25-step history's first run, while a cold
     * solve needs ~15 later runs to win its planning back (docs/solver.md, "FFTW wisdom"). */
    int use_cache = o->target_count >= CACHED_WISDOM_STEPS;
    if (cli_wisdom_resolve(o->wisdom, o->no_wisdom, use_cache, &o->solver, o->wisdom_cache, sizeof o->wisdom_cache) !=
        IM_OK) {
        fprintf(stderr, "indentmap: %s\n", im_last_error());
        return -1;
    }
    if (check_outputs_apart(o) != 0)
        return -1;
    return apply_quality(o);
}

/* ---- outputs ---- */

static const char *HISTORY_HEADER = "step,approach,load,load_star,contact_patches,area_ratio,mean_pressure,"
                                    "max_pressure,iterations,residual,seconds,convolutions," IM_THEORY_STEP_COLUMNS
                                    ",stiffness,e_star_sneddon,patches,patch_perimeter\n";

/* Beside each solved step: the theory, and what an experiment would measure (measure.h). */
typedef struct step_extras {
    im_theory_step theory;
    double stiffness;       /* dN/dw from this step and the (up to) two before; NaN at the first */
    double e_star_sneddon;  /* (sqrt(pi) / 2) S / sqrt(A_smooth(N)) */
    long patches;           /* connected contact patches */
    double perimeter;       /* their perimeter */
} step_extras;

/* DIR/history.csv, appended step by step. Its header is written atomically (so the file appears
 * whole); each step is then one line, written with one write(2) and synced (fdatasync), so that a
 * finished step survives a crash and the cost per step does not grow with the steps before it. A
 * write that fails part way is cut back to the last whole line. */
typedef struct history_file {
    int fd;
    off_t size; /* bytes of whole lines */
    char path[4200];
} history_file;

static int history_start(const char *dir, history_file *h)
{
    h->fd = -1;
    snprintf(h->path, sizeof h->path, "%s/history.csv", dir);
    int status = im_write_file_atomic(h->path, HISTORY_HEADER, strlen(HISTORY_HEADER));
    if (status != IM_OK)
        return status;
    h->fd = open(h->path, O_WRONLY | O_APPEND | O_CLOEXEC);
    if (h->fd < 0)
        return im_fail(IM_EIO, "%s: cannot open for appending: %s", h->path, strerror(errno));
    h->size = (off_t)strlen(HISTORY_HEADER);
    return IM_OK;
}

static int history_append(history_file *h, int step, const im_step_result *r, const step_extras *e)
{
    char line[1024];
    const im_theory_step *t = &e->theory;
    int length = snprintf(line, sizeof line,
                          "%d,%.17g,%.17g,%.17g,%ld,%.17g,%.17g,%.17g,%d,%.6e,%.6f,%d,%.17g,%.17g,%.17g,%.17g,%.17g,"
                          "%.17g,%ld,%.17g\n",
                          step, r->approach, r->load, r->load_star, r->contact_patches, r->area_ratio,
                          r->mean_pressure, r->max_pressure, r->iterations, r->residual, r->seconds, r->convolutions,
                          t->load_smooth, t->area_smooth, t->area_ratio_constant, t->area_ratio_gamma, e->stiffness,
                          e->e_star_sneddon, e->patches, e->perimeter);
    ssize_t written = write(h->fd, line, (size_t)length);
    if (written == length && fdatasync(h->fd) == 0) {
        h->size += length;
        return IM_OK;
    }
    int saved = written < 0 || written == length ? errno : ENOSPC; /* a short write: the disk filled */
    if (ftruncate(h->fd, h->size) != 0) /* no torn last line */
        return im_fail(IM_EIO, "%s: write failed: %s; its last line is incomplete (cutting it failed: %s)",
                       h->path, strerror(saved), strerror(errno));
    return im_fail(IM_EIO, "%s: write failed: %s", h->path, strerror(saved));
}

static void history_close(history_file *h)
{
    if (h->fd >= 0)
        close(h->fd);
    h->fd = -1;
}

/* The fields of a step on the full grid, each FILE.npy with FILE.npy.json stating its units: forces in
 * force_unit, gaps and displacements in the surface's length unit. */
static int write_fields(const char *dir, im_indentation *run, int step, const char *length_unit,
                        const char *force_unit)
{
    im_field *f[3] = {NULL, NULL, NULL};
    static const char *const NAMES[3] = {"force", "gap", "displacement"};
    static const char *const QUANTITIES[3] = {"force per patch", "gap", "surface displacement"};
    int status = im_indentation_fields_full(run, &f[0], &f[1], &f[2]);
    for (int i = 0; i < 3 && status == IM_OK; ++i) {
        char path[4200];
        snprintf(path, sizeof path, "%s/%s_%04d.npy", dir, NAMES[i], step);
        snprintf(f[i]->unit, sizeof f[i]->unit, "%s", length_unit);
        if (i == 0)
            snprintf(f[i]->value_unit, sizeof f[i]->value_unit, "%s", force_unit);
        status = im_npy_write(path, f[i], IM_NPY_FLOAT64);
        if (status == IM_OK)
            status = im_field_sidecar_write(path, f[i], QUANTITIES[i]);
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

/* What the numbers of history.csv and the fields are in. */
static json_t *units_record(const indent_options *o, const im_field *s)
{
    const char *length = s->unit[0] ? s->unit : "delta";
    return json_pack("{s:s, s:s, s:s, s:s, s:s, s:s}", "length", length, "approach", length, "e_star",
                     o->e_star_unit[0] ? o->e_star_unit : "as given (--e-star)", "load", o->force_unit, "force",
                     o->force_unit, "load_star", "contact area A(N) / delta^2 (dimensionless)");
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
    char source[4 * 4200 + 1];
    int escaped = im_path_utf8(o->surface_path ? o->surface_path : "smooth", source, sizeof source);
    json_t *generator = surface_sidecar_generator(o->surface_path);
    char preparation[256];
    cli_describe_preparation(&o->preparation, o->filled, preparation, sizeof preparation);
    json_t *seed = generator ? json_object_get(generator, "seed") : NULL;
    json_t *root = json_pack(
        "{s:s, s:s, s:{s:s, s:i, s:i, s:f, s:s, s:s, s:O?}, s:{s:s, s:f, s:f, s:f, s:f}, s:s, s:o, "
        "s:{s:s, s:f, s:s, s:f, s:i, s:b, s:b, s:f, s:b, s:i, s:f}, s:{s:i, s:i, s:i, s:i}, s:i, s:s, s:b}",
        "program", "indentmap indent", "version", IM_VERSION,
        "surface", "source", source, "nx", s->nx, "ny", s->ny,
        "delta", s->delta, "unit", s->unit, "preparation", preparation, "generator", generator,
        "punch", "kind", im_punch_name(o->punch.kind), "alpha_degrees", o->punch.alpha_degrees,
        "radius", o->punch.radius, "x", ax, "y", ay,
        "control", o->control == IM_CONTROL_LOAD ? "load" : "approach", "targets", targets,
        "solver", "quality", o->quality ? o->quality : "none", "tol", o->solver.tol, "tol_from", tolerance_source(o),
        "e_star", o->solver.e_star, "max_iterations", o->solver.max_iterations,
        "fftw_measure", im_solver_plan_measured(plan), "fftw_wisdom", im_solver_wisdom_file(&o->solver) != NULL,
        "plan_seconds", im_solver_plan_seconds(plan),
        "crop", o->solver.crop, "window_margin", o->solver.window_margin, /* the options the run was made with */
        "hardness", o->solver.hardness,
        "window", "x0", w.x0, "y0", w.y0, "nx", w.nx, "ny", w.ny, "threads", omp_get_max_threads(),
        "history", "history.csv", "fields", o->fields);
    json_t *solver = root ? json_object_get(root, "solver") : NULL;
    if (solver) { /* issue 15's accelerations: on unless --plain-pk, off with a hardness (solver.h) */
        const int plain = o->solver.hardness > 0;
        json_object_set_new(solver, "cascade", json_boolean(o->solver.cascade && !plain));
        json_object_set_new(solver, "precondition", json_boolean(o->solver.precondition && !plain));
    }
    if (root && seed)
        json_object_set(root, "seed", seed);
    if (root && escaped) /* the path is not UTF-8: its other bytes are written \xHH, backslashes \\ */
        json_object_set_new(json_object_get(root, "surface"), "source_encoding", json_string("escaped"));
    if (root)
        json_object_set_new(root, "units", units_record(o, s));
    json_decref(generator);
    return root;
}

static int write_run_json(const char *dir, json_t *record, int steps_done, int status)
{
    json_object_set_new(record, "steps_completed", json_integer(steps_done));
    json_object_set_new(record, "status", json_string(status == IM_OK ? "ok" : im_strstatus(status)));
    char error[4 * 1024 + 1]; /* a message may quote a path that is not UTF-8 */
    im_path_utf8(status == IM_OK ? "" : im_last_error(), error, sizeof error);
    json_object_set_new(record, "error", json_string(error));
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

static int load_surface(indent_options *o, im_field **surface)
{
    if (!o->smooth) {
        im_surface_read_info info;
        int status = im_surface_read_with(o->surface_path, &o->read, surface, &info);
        o->filled = status == IM_OK ? info.filled : 0;
        return status == IM_OK ? cli_prepare_surface(&o->preparation, surface) : status;
    }
    int status = im_field_create(o->nx, o->ny, o->delta, surface);
    if (status == IM_OK)
        memcpy((*surface)->unit, o->read.set.lateral, sizeof (*surface)->unit);
    return status;
}

/* N for Pa and m; otherwise "E*-unit length-unit²", with E* and δ standing in for what is not given. */
static void set_force_unit(indent_options *o, const im_field *surface)
{
    memcpy(o->length_unit, surface->unit, sizeof o->length_unit);
    if (strcmp(o->e_star_unit, "Pa") == 0 && strcmp(surface->unit, "m") == 0)
        snprintf(o->force_unit, sizeof o->force_unit, "N");
    else
        snprintf(o->force_unit, sizeof o->force_unit, "%s %s\u00b2", o->e_star_unit[0] ? o->e_star_unit : "E*",
                 surface->unit[0] ? surface->unit : "\u03b4");
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

/* The extras of step i (rows 0..i solved): theory, stiffness from the last three steps (which do not
 * change as later steps come), Sneddon's modulus, contact patches. */
static int measure_step(const indent_options *o, const im_theory_interface *rough, const im_indentation *run,
                        const im_step_result *rows, int i, step_extras *e)
{
    int status = im_theory_step_columns(&o->punch, rough, rows[i].approach, rows[i].load, &e->theory);
    e->stiffness = e->e_star_sneddon = NAN;
    int first = i >= 2 ? i - 2 : 0;
    double w[3], n[3], s[3];
    for (int k = first; k <= i; ++k) {
        w[k - first] = rows[k].approach;
        n[k - first] = rows[k].load;
    }
    /* a repeated approach or a turn from loading to unloading leaves the stiffness NaN */
    if (status == IM_OK && i > 0 && im_measure_stiffness(w, n, i - first + 1, s) == IM_OK) {
        e->stiffness = s[i - first];
        e->e_star_sneddon = im_measure_sneddon_modulus(e->stiffness, e->theory.area_smooth);
    }
    im_field *force = NULL;
    im_contact_patches patches = {0};
    if (status == IM_OK)
        status = im_indentation_fields(run, &force, NULL, NULL);
    if (status == IM_OK)
        status = im_measure_contact_patches(force, &patches, NULL);
    im_field_free(force);
    e->patches = patches.patches;
    e->perimeter = patches.perimeter;
    return status;
}

/* Solves step i (0-based; rows[0..i) solved before), measures it, and writes its fields and its
 * history line. */
static int run_step(const indent_options *o, const im_theory_interface *rough, im_indentation *run,
                    history_file *history, im_step_result *rows, step_extras *extras, int i)
{
    int status = im_indentation_step(run, o->targets[i], &rows[i]);
    if (status == IM_OK)
        status = measure_step(o, rough, run, rows, i, &extras[i]);
    if (status == IM_OK && o->fields) /* first: history.csv lists only steps whose fields are written */
        status = write_fields(o->out, run, i + 1, o->length_unit, o->force_unit);
    if (status == IM_OK)
        status = history_append(history, i + 1, &rows[i], &extras[i]);
    if (status == IM_OK) {
        const im_step_result *r = &rows[i];
        printf("step %d: w = %.6g  N = %.6g  n_p = %ld  A/A0 = %.4f  iterations %d  residual %.2e  %.3f s\n", i + 1,
               r->approach, r->load, r->contact_patches, r->area_ratio, r->iterations, r->residual, r->seconds);
        fflush(stdout);
    }
    return status;
}

/* rough: the surface's measured h'rms and the solver's E*, for the theory columns. */
static int run_steps(const indent_options *o, const im_theory_interface *rough, im_indentation *run,
                     history_file *history, json_t *record)
{
    im_step_result *rows = calloc((size_t)o->target_count, sizeof *rows);
    step_extras *extras = calloc((size_t)o->target_count, sizeof *extras);
    if (!rows || !extras) {
        free(rows);
        free(extras);
        return im_fail(IM_ENOMEM, "history of %d steps", o->target_count);
    }
    int status = IM_OK, done = 0;
    for (; done < o->target_count; ++done) {
        if (cli_stop_signal) { /* checked between steps: a solve is never cut short */
            status = im_fail(IM_EINTERRUPTED, "interrupted by signal %d", (int)cli_stop_signal);
            break;
        }
        status = run_step(o, rough, run, history, rows, extras, done);
        if (status != IM_OK)
            break;
    }
    /* done counts the steps whose fields and history line are all written (< target_count here) */
    if (status != IM_OK)
        im_fail_context(status, "step %d of %d (%s %g; the %d steps before are in %s/history.csv)", done + 1,
                        o->target_count, o->control == IM_CONTROL_LOAD ? "load" : "approach", o->targets[done],
                        done, o->out);
    char message[1024];
    snprintf(message, sizeof message, "%s", im_last_error());
    int recorded = write_run_json(o->out, record, done, status);
    if (status != IM_OK)
        im_fail(status, "%s", message);
    else
        status = recorded; /* a run whose record could not be written did not finish */
    free(rows);
    free(extras);
    return status;
}

/* Takes DIR's lock, then removes what an earlier run left there that this one would not replace:
 * temporary files of a killed run, and field files (this run writes its own, or none). Inputs are
 * kept (the output guard names them). */
static int prepare_folder(const indent_options *o, im_folder_lock *lock)
{
    int status = im_folder_lock_acquire(o->out, "give this run another --out", lock);
    if (status != IM_OK)
        return status;
    im_folder_remove_temporaries(o->out, 0); /* --out may be any folder: not its subfolders */
    DIR *listing = opendir(o->out);
    if (!listing)
        return im_fail(IM_EIO, "%s: cannot list: %s", o->out, strerror(errno));
    static const char *const FIELDS[3] = {"force_", "gap_", "displacement_"};
    for (struct dirent *entry; status == IM_OK && (entry = readdir(listing)) != NULL;) {
        char path[8192];
        int field = 0;
        for (int i = 0; i < 3; ++i)
            field |= is_step_file(entry->d_name, FIELDS[i]);
        if (!field || snprintf(path, sizeof path, "%s/%s", o->out, entry->d_name) >= (int)sizeof path ||
            im_output_check(path) != IM_OK)
            continue;
        if (unlink(path) != 0 && errno != ENOENT)
            status = im_fail(IM_EIO, "%s: cannot remove the earlier run's field file: %s", path, strerror(errno));
    }
    closedir(listing);
    return status;
}

/* DIR/index.html over what the run left (viewer.h), even after a failure; the run's own error,
 * if any, stays the one reported. */
static int write_viewer_page(const indent_options *o, int status)
{
    char message[1024], title[1024];
    snprintf(message, sizeof message, "%s", im_last_error());
    snprintf(title, sizeof title, "indentmap indent: %s", o->smooth ? "smooth surface" : o->surface_path);
    int written = im_viewer_write(o->out, title);
    if (status == IM_OK)
        return written;
    im_fail(status, "%s", message);
    return status;
}

/* The theory columns' interface: the surface's h'rms (spectral, h'rms^2 = 2 m2), the solver's E*,
 * k = 2 and the PR normalisation. */
static int measured_interface(const indent_options *o, const im_field *surface, im_theory_interface *rough)
{
    im_surface_stats stats;
    int status = im_surface_statistics(surface, &stats);
    if (status == IM_OK) {
        *rough = im_theory_interface_default(stats.slope_rms_spectral);
        rough->e_star = o->solver.e_star;
    }
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
    im_theory_interface rough;
    int status = cli_interrupt_install() == 0 ? im_indenter_check(&o.punch)
                                              : im_fail(IM_EUNSUPPORTED, "cannot install the signal handlers");
    if (status == IM_OK) {
        warn_if_steep(&o.punch);
        status = load_surface(&o, &surface);
    }
    if (status == IM_OK)
        status = check_axis_inside(&o, surface);
    if (status == IM_OK) {
        set_force_unit(&o, surface);
        status = measured_interface(&o, surface, &rough);
    }
    if (status == IM_OK)
        status = im_indentation_create(surface, &o.punch, o.control, largest(o.targets, o.target_count), &o.solver,
                                       &run);
    if (status == IM_OK)
        status = im_make_directories(o.out);
    im_folder_lock lock = {.fd = -1};
    history_file history = {.fd = -1};
    if (status == IM_OK)
        status = prepare_folder(&o, &lock);
    if (status == IM_OK) {
        im_window w = im_indentation_window(run);
        printf("surface %d x %d, window [%d, %d) x [%d, %d) (%d x %d), %d threads\n", surface->nx, surface->ny,
               w.x0, w.x0 + w.nx, w.y0, w.y0 + w.ny, w.nx, w.ny, omp_get_max_threads());
        record = run_record(&o, surface, run);
        status = record ? history_start(o.out, &history) : im_fail(IM_ENOMEM, "run record");
        if (record && status != IM_OK) { /* no step solved: the record says why, not an earlier run's */
            char message[1024];
            snprintf(message, sizeof message, "%s", im_last_error());
            write_run_json(o.out, record, 0, status);
            im_fail(status, "%s", message);
        }
    }
    if (status == IM_OK)
        status = run_steps(&o, &rough, run, &history, record);
    history_close(&history);
    if (record)
        status = write_viewer_page(&o, status);
    im_folder_lock_release(&lock);
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
