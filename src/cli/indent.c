/* indentmap indent: an indentation history of a surface by a punch, under displacement or load
 * control, written step by step to DIR/history.csv, with DIR/run.json and optional fields. This file
 * is its options, their checks and the exit code; the run is the library's (indent.h: im_indent_run). */
#include "cli/cli.h"
#include "cli/indent_record.h"
#include "front/front.h"
#include "front/indent_run.h"

#include "indentmap/field.h"
#include "indentmap/formats.h"
#include "indentmap/indent.h"
#include "indentmap/indenter.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"

#include <getopt.h>
#include <jansson.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void usage(FILE *stream)
{
    fprintf(stream,
            "usage: indentmap indent (SURFACE | --smooth --n N) (--approach LIST | --load LIST) [OPTIONS]\n"
            "       indentmap indent --from-record DIR/run.json [--out NEWDIR] [--wisdom FILE | --no-wisdom]\n\n"
            "Indents SURFACE (" CLI_SURFACE_FORMATS ") with a rigid punch and solves each\n"
            "step (FFT boundary elements, Polonsky-Keer CG), warm-started from the last. Units: lengths\n"
            "in the surface's unit (its spacing delta when it states none), stresses in E* (settable).\n"
            "w counts from first touch.\n\n"
            "  --smooth            a flat surface instead of SURFACE (with --n, --m, --delta)\n"
            "  --n N, --m M        smooth grid size (default 512, M = N)\n"
            "  --delta D           patch side: of the smooth surface (default 1), or overriding SURFACE's\n"
            "  --unit U            length unit of delta (m, mm, um, nm, ...); SURFACE stating its unit is\n"
            "                      converted into U (with --delta, both are restated)\n"
            "  --height-unit U     unit of SURFACE's heights, converted to --unit (default: --unit)\n"
            "  --channel C         SURFACE's channel (index or title), for an instrument file read through\n"
            "                      Gwyddion (default: the first holding heights)\n"
            "  --length-unit U     solve in this length unit (m: SI): SURFACE's spacing and heights are\n"
            "                      converted into it; approaches, gaps and displacements are in it\n"
            "  --e-star-unit U     the unit of --e-star (e.g. Pa), for the records: forces are in\n"
            "                      U x length unit^2 (N for Pa and m)\n"
            "  --fill              fill SURFACE's missing points (NaN) from their neighbours (default: refuse)\n"
            "  --npy-order O       yx (rows are y) or xy (the first index is x, as SurfaceTopography's\n"
            "                      heights()) for a .npy SURFACE (default: its sidecar's, else yx)\n"
            "  --resample-square   resample SURFACE's pixels when they are not square (x and y spacings\n"
            "                      differing by more than 2^-16 of their mean) bilinearly onto square pixels\n"
            "                      of the finer spacing (default: refuse them); run.json records it\n"
            "  --crop X0,Y0,NX,NY  indent only this block of SURFACE\n"
            "  --detrend D         none (default), plane or curvature: removed from SURFACE before solving\n"
            "  --align A           scan-line alignment of SURFACE's rows before detrending: none (default),\n"
            "                      median, mean or line (each row's offset or tilt removed, as AFM images need)\n"
            "  --punch KIND        cone (default), sphere, flat or profile (with --profile)\n"
            "  --profile FILE      the punch's shape for --punch profile: a text file of samples 'r z' or\n"
            "                      'r,z' per line (axisymmetric: r from 0 increasing, z from 0 non-\n"
            "                      decreasing; '#' comments; interpolated by a monotone cubic; no contact\n"
            "                      beyond the last r), or a .npy height field on the surface's grid whose\n"
            "                      centre patch (nx/2, ny/2) lies on the axis (a 2-D profile); lengths in\n"
            "                      the surface's length unit (docs/solver.md, \"User-given profiles\")\n"
            "  --alpha A           cone semi-opening angle in degrees, 0 < A < 90 (default 80); below 60\n"
            "                      a warning: small-slope elasticity is stretched (still solved)\n"
            "  --radius R          sphere radius or flat punch radius (required for those)\n"
            "  --x X --y Y         punch axis position (default: centre of patch (nx/2, ny/2))\n"
            "  --approach LIST     imposed approaches w: 'w1,w2,...' or 'first:last:count' (linear,\n"
            "                      inclusive); at most 4096 steps, as a scene's [loading] steps\n"
            "  --load LIST         imposed loads N instead (load control), same syntax\n"
            "  --periodic          SURFACE is one period of a periodic surface (nominally flat contact):\n"
            "                      the periodic half-space (mean u = 0), under --load, --pressure,\n"
            "                      --mean-gap or --approach; the punch is a\n"
            "                      rigid flat on the whole cell unless --punch gives one, which then\n"
            "                      repeats with the cell. area_ratio is A / A0; load_star and the\n"
            "                      theory columns are nan (docs/solver.md, \"Periodic indentation\")\n"
            "  --pressure LIST     with --periodic: mean pressures p_m (units of E*) instead of --load\n"
            "                      (N = p_m times the cell's area), same syntax\n"
            "  --mean-gap LIST     with --periodic: mean gaps over the cell (Persson's u-bar, the mean of\n"
            "                      max(g, 0); length unit of SURFACE), each > 0, same syntax\n"
            "  --slope-definition D  the h'rms of the theory columns and the k fit: spectral (the\n"
            "                      band-limited interpolant's) or fd (forward differences). Default: spectral\n"
            "                      for a surface known to be periodic (generated, --smooth, --periodic), fd\n"
            "                      for a measured one (its edges would count in the spectrum), as scenes\n"
            "                      and Python do; run.json states which\n"
            "  --e-star E          composite modulus E* (default 1)\n"
            "  --hardness H        perfect plasticity: no patch carries more than H (units of E*'s\n"
            "                      stress); default none\n"
            "  --adhesion-work W   adhesion (Maugis-Dugdale): the work of adhesion W (E*'s stress times\n"
            "                      the length unit), with --adhesion-range: the stress W / D pulls every\n"
            "                      patch whose gap is at most D. Under --approach or --load (--periodic:\n"
            "                      --mean-gap, --pressure or --load), whose loads, pressures and approaches\n"
            "                      may then be negative (the punch pulled away; a load beyond the pull-off\n"
            "                      force is refused: the contact jumps out): the force-distance curve\n"
            "                      with its jumps, pull-off and lost work (run.json \"adhesion\",\n"
            "                      force_distance.png and .pdf; docs/solver.md, \"Adhesion\")\n"
            "  --adhesion-range D  the range of the adhesive stress (length unit); with --adhesion-work\n"
            "  --adhesion-law L    maugis-dugdale (default: the stress W / D up to the gap D) or\n"
            "                      exponential (the tension (W / D) exp(-g / D) at a gap g, W / D in\n"
            "                      contact, cut beyond g = 35 D); with --adhesion-work\n"
            "  --adhesion-zone P   solve instead the Maugis-Dugdale law of the same work W whose Dugdale\n"
            "                      zone pi E* D^2 / (8 W) spans at least P patches (D raised, W / D\n"
            "                      lowered) where it is narrower: a smoother law than the one asked, whose\n"
            "                      pull-off coarse grids resolve (a JKR-like sphere, Tabor mu 10: 0.075\n"
            "                      pi W R off at 8 patches per reduced radius, 1.37 without); stdout and\n"
            "                      run.json \"adhesion\" state the law solved and the law asked\n"
            "                      (docs/solver.md, \"Across Tabor's mu\"); with --adhesion-work\n"
            "  --quality Q         draft (tol 1e-5), standard (1e-6, the default, as for scenes) or\n"
            "                      publication (1e-9): the solver tolerance of a speed/accuracy preset\n"
            "                      (errors measured in solver.h)\n"
            "  --tol T             stopping tolerance on the relative gap residual, 1e-15 to 0.5\n"
            "                      (default: the quality's; below about 1e-13 double precision's\n"
            "                      rounding may hold the residual: the solve then stops, naming a tol\n"
            "                      that works); overrides --quality. run.json records both\n"
            "  --max-iter K        iteration cap per step (default 10000)\n"
            "  --full              solve on the whole surface, not the window that can touch\n"
            "  --plain-pk          plain Polonsky-Keer CG from the local guess: no cascade cold start, no\n"
            "                      preconditioner (the same answers to the tolerance, slower; docs/solver.md)\n"
            "  --device D          cpu (default): OpenMP and FFTW; gpu: the Vulkan compute engine (VkFFT,\n"
            "                      double precision; a CPU Vulkan device such as lavapipe when there is no\n"
            "                      GPU); auto: a hardware GPU when there is one, else the CPU. The same\n"
            "                      answers to the tolerance (docs/solver.md, \"Engines\"); indentmap info\n"
            "                      lists the Vulkan devices\n"
            "  --measure           plan the FFTs with FFTW_MEASURE (slower planning, faster steps)\n"
            "  --wisdom FILE       FFTW wisdom file, read before planning and updated after it; implies\n"
            "                      --measure. Default: $IM_FFTW_WISDOM, else for runs of 10 steps or more\n"
            "                      the user's cache ($XDG_CACHE_HOME or ~/.cache)/indentmap/fftw-wisdom\n"
            "  --no-wisdom         no wisdom file (also IM_FFTW_WISDOM=\"\"): FFTW_ESTIMATE plans\n"
            "  --out DIR           output folder (default output/indent)\n"
            "  --from-record R     the run recorded in its run.json R made again: its options as recorded\n"
            "                      (run.json \"arguments\"), into --out (default: R's folder); refused when\n"
            "                      an input file's SHA-256 is no longer the recorded one or R was made by\n"
            "                      another version; its FFTW plans estimated as recorded unless --wisdom\n"
            "                      is given (docs/scenes.md, \"Provenance\")\n"
            "  --fields            also write DIR/{force,gap,displacement}_NNNN.npy for every step\n"
            "  --frames            also draw DIR/frames/contact_NNNN.png for every step (the step's contact\n"
            "                      map, one log force norm over all steps; implies --fields, needs OpenGL),\n"
            "                      which index.html shows under a slider\n"
            "  --page-embed        index.html carries its images as data URIs: one file that travels alone\n"
            "  --distributions     also write DIR/distributions_NNNN_{gaps,patches,patch_list}.csv for every\n"
            "                      step: the gap outside contact in units of h_rms, the patch sizes by\n"
            "                      octave and each patch's area and perimeter (docs/theory.md)\n\n"
            "DIR/history.csv gets one whole line per step, appended and synced as soon as the step is\n"
            "solved, so the steps already solved survive a later failure or a crash (no convergence:\n"
            "exit 1; contact at the surface's edge: exit 1). DIR is locked while the run writes there\n"
            "(DIR/.lock, as for scenes); the field files of an earlier run in DIR are removed first.\n"
            "Before any step, --fields, --frames and --distributions are checked against the memory their\n"
            "whole-grid convolution needs (exit 2) and the fields' and frames' files of every step against\n"
            "the free disk (an upper bound, exit 1; IM_NO_SPACE_CHECK=1 skips it).\n"
            "Where N is not positive beyond the solver's tolerance (N <= tol max |N| of the steps so far)\n"
            "the ratio area_ratio = n_p delta^2 / A(N) is undefined and written as nan.\n");
}

/* Runs of at least this many steps keep FFTW wisdom in the user's cache by default. */
enum { CACHED_WISDOM_STEPS = 10 };

typedef struct indent_options {
    const char *surface_path, *out, *wisdom;
    int no_wisdom;
    char wisdom_cache[4096]; /* the cache's wisdom file, when that is the one used */
    int smooth, nx, ny, m_given, fields;
    int frames;        /* --frames (sets fields) */
    int page_embed;    /* --page-embed */
    int distributions; /* --distributions */
    double delta;
    im_surface_read_options read; /* --delta, --unit, --height-unit, --fill, --npy-order, --resample-square */
    cli_preparation preparation;  /* --crop, --detrend */
    char e_star_unit[16];         /* --e-star-unit, "" when not given */
    im_indenter punch;
    const char *profile_path; /* --profile */
    int radius_given, x_given, y_given, punch_given, alpha_given;
    int pressures;        /* --pressure: the targets are mean pressures until the cell is known */
    int slope_definition; /* --slope-definition: IM_SLOPE_*, or -1: by the surface (the library's rule) */
    enum im_control control;
    const char *targets_text;
    const char *quality; /* preset name, NULL if none given */
    int tol_given;
    int adhesion_law_given; /* --adhesion-law */
    double *targets;
    int target_count;
    im_solver_options solver;
    indent_arguments arguments; /* as run.json records them (indent_record.h) */
    const char *from_record;    /* --from-record: the record of the run made again */
} indent_options;

enum {
    OPT_SMOOTH = 256,
    OPT_N,
    OPT_M,
    OPT_DELTA,
    OPT_LENGTH_UNIT,
    OPT_ESTAR_UNIT,
    OPT_PUNCH,
    OPT_ALPHA,
    OPT_RADIUS,
    OPT_X,
    OPT_Y,
    OPT_APPROACH,
    OPT_LOAD,
    OPT_ESTAR,
    OPT_HARDNESS,
    OPT_QUALITY,
    OPT_TOL,
    OPT_MAXIT,
    OPT_FULL,
    OPT_MEASURE,
    OPT_WISDOM,
    OPT_OUT,
    OPT_FIELDS,
    OPT_HELP,
    OPT_PLAIN_PK,
    OPT_DISTRIBUTIONS,
    OPT_PROFILE,
    OPT_NO_WISDOM,
    OPT_DEVICE,
    OPT_PERIODIC,
    OPT_PRESSURE,
    OPT_SLOPE_DEFINITION,
    OPT_ADHESION_WORK,
    OPT_ADHESION_RANGE,
    OPT_MEAN_GAP,
    OPT_FRAMES,
    OPT_PAGE_EMBED,
    OPT_FROM_RECORD,
    OPT_ADHESION_LAW,
    OPT_ADHESION_ZONE
};

static const struct option LONG_OPTIONS[] = {{"smooth", no_argument, 0, OPT_SMOOTH},
                                             {"n", required_argument, 0, OPT_N},
                                             {"m", required_argument, 0, OPT_M},
                                             {"delta", required_argument, 0, OPT_DELTA},
                                             CLI_SURFACE_FILE_OPTIONS,
                                             {"length-unit", required_argument, 0, OPT_LENGTH_UNIT},
                                             {"e-star-unit", required_argument, 0, OPT_ESTAR_UNIT},
                                             {"punch", required_argument, 0, OPT_PUNCH},
                                             {"alpha", required_argument, 0, OPT_ALPHA},
                                             {"radius", required_argument, 0, OPT_RADIUS},
                                             {"x", required_argument, 0, OPT_X},
                                             {"y", required_argument, 0, OPT_Y},
                                             {"approach", required_argument, 0, OPT_APPROACH},
                                             {"load", required_argument, 0, OPT_LOAD},
                                             {"e-star", required_argument, 0, OPT_ESTAR},
                                             {"hardness", required_argument, 0, OPT_HARDNESS},
                                             {"quality", required_argument, 0, OPT_QUALITY},
                                             {"tol", required_argument, 0, OPT_TOL},
                                             {"max-iter", required_argument, 0, OPT_MAXIT},
                                             {"full", no_argument, 0, OPT_FULL},
                                             {"measure", no_argument, 0, OPT_MEASURE},
                                             {"wisdom", required_argument, 0, OPT_WISDOM},
                                             {"no-wisdom", no_argument, 0, OPT_NO_WISDOM},
                                             {"out", required_argument, 0, OPT_OUT},
                                             {"fields", no_argument, 0, OPT_FIELDS},
                                             {"frames", no_argument, 0, OPT_FRAMES},
                                             {"page-embed", no_argument, 0, OPT_PAGE_EMBED},
                                             {"distributions", no_argument, 0, OPT_DISTRIBUTIONS},
                                             {"help", no_argument, 0, OPT_HELP},
                                             {"plain-pk", no_argument, 0, OPT_PLAIN_PK},
                                             {"profile", required_argument, 0, OPT_PROFILE},
                                             {"device", required_argument, 0, OPT_DEVICE},
                                             {"periodic", no_argument, 0, OPT_PERIODIC},
                                             {"pressure", required_argument, 0, OPT_PRESSURE},
                                             {"mean-gap", required_argument, 0, OPT_MEAN_GAP},
                                             {"slope-definition", required_argument, 0, OPT_SLOPE_DEFINITION},
                                             {"adhesion-work", required_argument, 0, OPT_ADHESION_WORK},
                                             {"adhesion-range", required_argument, 0, OPT_ADHESION_RANGE},
                                             {"from-record", required_argument, 0, OPT_FROM_RECORD},
                                             {"adhesion-law", required_argument, 0, OPT_ADHESION_LAW},
                                             {"adhesion-zone", required_argument, 0, OPT_ADHESION_ZONE},
                                             {0, 0, 0, 0}};

/* --punch (indenter.h: im_punch_parse, as a scene's [punch] shape). */
static int parse_punch(const char *text, enum im_punch_kind *kind)
{
    if (im_punch_parse(text, kind) == IM_OK)
        return 0;
    fprintf(stderr, "indentmap: --punch %s\n", im_last_error());
    return -1;
}

/* The option that gave the targets. */
static const char *target_option(const indent_options *o)
{
    if (o->control == IM_CONTROL_MEAN_GAP)
        return "--mean-gap";
    return o->control == IM_CONTROL_DISPLACEMENT ? "--approach" : o->pressures ? "--pressure" : "--load";
}

/* --approach, --load, --pressure or --mean-gap, once all options are read: a step list (front.h:
 * steps_parse, as a scene's [loading] steps, with its messages); approaches may be negative with
 * adhesion (approaches and loads: the punch pulled away, the contact under tension). */
static int parse_targets(indent_options *o)
{
    char error[512];
    const char *option = target_option(o);
    const int negative = o->control != IM_CONTROL_MEAN_GAP && o->solver.adhesion_work > 0;
    if (!(o->targets = malloc(sizeof(double) * STEPS_MAX)))
        return -1;
    if (steps_parse_signed(option, o->targets_text, negative, o->targets, &o->target_count, error, sizeof error) !=
            0 ||
        (o->control == IM_CONTROL_MEAN_GAP && /* refused now, not at its step after the steps before it */
         steps_check_mean_gaps(option, o->targets_text, o->targets, o->target_count, error, sizeof error) != 0)) {
        fprintf(stderr, "indentmap: %s\n", error);
        return -1;
    }
    return 0;
}

static int apply_one_option(int code, const char *arg, indent_options *o)
{
    switch (code) {
    case OPT_SMOOTH: o->smooth = 1; return 0;
    case OPT_N: return cli_parse_int("--n", arg, 2, IM_FIELD_MAX_SIDE, &o->nx);
    case OPT_M: o->m_given = 1; return cli_parse_int("--m", arg, 2, IM_FIELD_MAX_SIDE, &o->ny);
    case OPT_DELTA:
        if (cli_parse_double("--delta", arg, 1e-300, 1e300, &o->delta) != 0)
            return -1;
        o->read.set.delta_x = o->delta;
        return 0;
    case OPT_LENGTH_UNIT: return cli_parse_length_unit("--length-unit", arg, o->read.express_in);
    case OPT_ESTAR_UNIT: return cli_parse_name("--e-star-unit", arg, o->e_star_unit, sizeof o->e_star_unit);
    case OPT_PUNCH: o->punch_given = 1; return parse_punch(arg, &o->punch.kind);
    case OPT_PERIODIC: o->solver.periodic = 1; return 0;
    case OPT_SLOPE_DEFINITION:
        if (strcmp(arg, "spectral") == 0 || strcmp(arg, "fd") == 0) {
            o->slope_definition = strcmp(arg, "fd") == 0 ? IM_SLOPE_FINITE_DIFFERENCE : IM_SLOPE_SPECTRAL;
            return 0;
        }
        fprintf(stderr, "indentmap: --slope-definition %s: expected spectral or fd\n", arg);
        return -1;
    case OPT_PROFILE: o->profile_path = arg; return 0;
    case OPT_ALPHA:
        o->alpha_given = 1;
        return cli_parse_double("--alpha", arg, -1e300, 1e300, &o->punch.alpha_degrees);
    case OPT_RADIUS: o->radius_given = 1; return cli_parse_double("--radius", arg, -1e300, 1e300, &o->punch.radius);
    case OPT_X: o->x_given = 1; return cli_parse_double("--x", arg, -1e300, 1e300, &o->punch.x0);
    case OPT_Y: o->y_given = 1; return cli_parse_double("--y", arg, -1e300, 1e300, &o->punch.y0);
    case OPT_APPROACH:
    case OPT_LOAD:
    case OPT_PRESSURE:
    case OPT_MEAN_GAP:
        if (o->targets_text) {
            fprintf(stderr, "indentmap: give one of --approach, --load, --pressure and --mean-gap, once\n");
            return -1;
        }
        o->targets_text = arg;
        o->control = code == OPT_APPROACH   ? IM_CONTROL_DISPLACEMENT
                     : code == OPT_MEAN_GAP ? IM_CONTROL_MEAN_GAP
                                            : IM_CONTROL_LOAD;
        o->pressures = code == OPT_PRESSURE;
        return 0;
    case OPT_ESTAR: return cli_parse_double("--e-star", arg, 1e-300, 1e300, &o->solver.e_star);
    case OPT_HARDNESS: return cli_parse_double("--hardness", arg, 1e-300, 1e300, &o->solver.hardness);
    case OPT_ADHESION_WORK: return cli_parse_double("--adhesion-work", arg, 1e-300, 1e300, &o->solver.adhesion_work);
    case OPT_ADHESION_RANGE:
        return cli_parse_double("--adhesion-range", arg, 1e-300, 1e300, &o->solver.adhesion_range);
    case OPT_ADHESION_LAW: o->adhesion_law_given = 1; return cli_parse_adhesion_law(arg, &o->solver.adhesion_law);
    case OPT_ADHESION_ZONE: return cli_parse_double("--adhesion-zone", arg, 1e-300, 1e300, &o->solver.adhesion_zone);
    case OPT_QUALITY: o->quality = arg; return 0;
    case OPT_TOL:
        o->tol_given = 1;
        return cli_parse_double("--tol", arg, IM_SOLVER_TOL_MIN, IM_SOLVER_TOL_MAX, &o->solver.tol);
    case OPT_MAXIT: return cli_parse_int("--max-iter", arg, 1, 100000000, &o->solver.max_iterations);
    case OPT_FULL: o->solver.crop = 0; return 0;
    case OPT_PLAIN_PK: o->solver.cascade = o->solver.precondition = 0; return 0;
    case OPT_MEASURE: o->solver.fft_measure = 1; return 0;
    case OPT_DEVICE: return cli_parse_device(arg, &o->solver.device);
    case OPT_WISDOM: return cli_parse_path("--wisdom", arg, &o->wisdom);
    case OPT_NO_WISDOM: o->no_wisdom = 1; return 0;
    case OPT_OUT: return cli_parse_path("--out", arg, &o->out);
    case OPT_FIELDS: o->fields = 1; return 0;
    case OPT_FRAMES: o->frames = o->fields = 1; return 0; /* drawn from the force fields */
    case OPT_PAGE_EMBED: o->page_embed = 1; return 0;
    case OPT_DISTRIBUTIONS: o->distributions = 1; return 0;
    case OPT_FROM_RECORD: return cli_parse_path("--from-record", arg, &o->from_record);
    default: return cli_apply_surface_file_option(code, arg, &o->read, &o->preparation, NULL);
    }
}

static const char *option_name(int code)
{
    for (const struct option *option = LONG_OPTIONS; option->name; ++option)
        if (option->val == code)
            return option->name;
    return NULL;
}

/* Applies an option and notes it in the run's arguments, but for where the run writes and plans (a run
 * made again from its record writes and plans where it is told). */
static int apply_option(int code, const char *arg, void *state)
{
    indent_options *o = state;
    if (apply_one_option(code, arg, o) != 0)
        return -1;
    if (code == OPT_OUT || code == OPT_WISDOM || code == OPT_NO_WISDOM || code == OPT_FROM_RECORD)
        return 0;
    if (indent_arguments_add(&o->arguments, option_name(code), arg, code == OPT_PROFILE) == IM_OK)
        return 0;
    fprintf(stderr, "indentmap: --%s: %s\n", option_name(code), im_last_error());
    return -1;
}

/* Adhesion's options: both or neither, displacement or load control on the half-space or mean-gap and load
 * control (mean pressures) on a periodic cell (a negative target is refused by the step list's parser without
 * adhesion). 0, or -1 with the message said. */
static int check_adhesion_options(const indent_options *o)
{
    const int adhesion = o->solver.adhesion_work > 0;
    const int held = o->solver.periodic ? o->control != IM_CONTROL_DISPLACEMENT : o->control != IM_CONTROL_MEAN_GAP;
    if (adhesion != (o->solver.adhesion_range > 0))
        fprintf(stderr, "indentmap: --adhesion-work and --adhesion-range go together\n");
    else if (o->adhesion_law_given && !adhesion)
        fprintf(stderr,
                "indentmap: --adhesion-law goes with --adhesion-work and --adhesion-range (the law's work and "
                "range): expected both\n");
    else if (o->solver.adhesion_zone > 0 && !adhesion)
        fprintf(stderr,
                "indentmap: --adhesion-zone widens the zone of --adhesion-work and --adhesion-range: expected "
                "both\n");
    else if (o->solver.adhesion_zone > 0 && o->solver.adhesion_law != IM_ADHESION_MAUGIS_DUGDALE)
        fprintf(stderr, "indentmap: --adhesion-zone widens the Maugis-Dugdale law's zone: expected --adhesion-law "
                        "maugis-dugdale (the exponential law has no Dugdale zone)\n");
    else if (adhesion && !held)
        fprintf(stderr, "indentmap: --adhesion-work takes %s\n",
                o->solver.periodic
                    ? "--mean-gap, --pressure or --load with --periodic (an approach on a cell is its mean gap)"
                    : "--approach or --load");
    else
        return 0;
    return -1;
}

static int check_options(const indent_options *o)
{
    if (!o->targets_text)
        fprintf(stderr,
                "indentmap: give --approach LIST or --load LIST (with --periodic also --pressure or --mean-gap)\n");
    else if (o->control == IM_CONTROL_MEAN_GAP && !o->solver.periodic)
        fprintf(stderr,
                "indentmap: --mean-gap (a mean gap over the cell) needs --periodic; the half-space has none\n");
    else if (o->solver.periodic && !o->punch_given && (o->alpha_given || o->x_given))
        fprintf(stderr,
                "indentmap: --periodic without --punch presses a rigid flat on the cell: --alpha, --x and --y "
                "apply to a punch (give --punch cone to repeat a cone with the cell)\n");
    else if (o->pressures && !o->solver.periodic)
        fprintf(stderr, "indentmap: --pressure (a mean pressure over the cell) needs --periodic; a punch on the "
                        "half-space takes --load\n");
    else if (o->smooth == (o->surface_path != NULL))
        fprintf(stderr, "indentmap: give either a SURFACE file or --smooth\n");
    else if ((o->punch.kind == IM_PUNCH_PROFILE) != (o->profile_path != NULL))
        fprintf(stderr, "indentmap: --punch profile and --profile FILE go together\n");
    else if (o->punch.kind != IM_PUNCH_CONE && o->punch.kind != IM_PUNCH_PROFILE && !o->radius_given)
        fprintf(stderr, "indentmap: --punch %s needs --radius\n", im_punch_name(o->punch.kind));
    else if ((o->punch.kind == IM_PUNCH_CONE || o->punch.kind == IM_PUNCH_PROFILE) && o->radius_given)
        fprintf(stderr, "indentmap: --radius applies to --punch sphere or flat; a cone's shape is --alpha, a "
                        "profile's its --profile\n");
    else if (o->x_given != o->y_given)
        fprintf(stderr, "indentmap: give both --x and --y, or neither\n");
    else
        return check_adhesion_options(o);
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

/* The run's lines (indent.h): what it has to say on stdout, warnings and failures after the steps on
 * stderr. */
static void indent_log(void *user, im_log_level level, const char *message)
{
    (void)user;
    if (level == IM_LOG_WARNING) {
        fprintf(stderr, "indentmap: %s\n", message);
        return;
    }
    printf("%s\n", message);
    fflush(stdout);
}

/* What the library runs (indent.h), the arguments borrowed from o->arguments into the array *recorded (NULL
 * when there are none; the caller frees it). */
static int run_options(const indent_options *o, const char ***recorded, char *command, im_indent_options *run)
{
    const size_t count = json_array_size(o->arguments.list);
    *recorded = count ? malloc(sizeof **recorded * count) : NULL;
    if (count && !*recorded)
        return im_fail(IM_ENOMEM, "run.json's arguments: out of memory");
    for (size_t i = 0; i < count; ++i)
        (*recorded)[i] = json_string_value(json_array_get(o->arguments.list, i));
    const cli_preparation *p = &o->preparation;
    *run = (im_indent_options){.surface_path = o->surface_path,
                               .nx = o->nx,
                               .ny = o->ny,
                               .delta = o->delta,
                               .read = o->read,
                               .crop = {p->crop[0], p->crop[1], p->crop[2], p->crop[3]},
                               .align = p->align,
                               .detrend = p->detrend,
                               .slope_definition = o->slope_definition,
                               .punch = o->punch,
                               .profile_path = o->profile_path,
                               .punch_given = o->punch_given,
                               .control = o->control,
                               .targets = o->targets,
                               .target_count = o->target_count,
                               .pressures = o->pressures,
                               .solver = o->solver,
                               .quality = o->quality,
                               .tol_given = o->tol_given,
                               .e_star_unit = o->e_star_unit,
                               .out = o->out,
                               .fields = o->fields,
                               .frames = o->frames,
                               .page_embed = o->page_embed,
                               .distributions = o->distributions,
                               .no_space_check = cli_space_check_off(),
                               .arguments = *recorded,
                               .argument_count = (int)count,
                               .arguments_escaped = o->arguments.escaped,
                               .from_record = o->from_record,
                               .command = command,
                               .stop = &cli_stop_signal,
                               .log = indent_log};
    return IM_OK;
}

/* Refuses, before any work, an output folder whose outputs would replace the surface file, its
 * sidecar or the profile, and a wisdom file that is an input or an output (the library checks it
 * again, indent.h). Every write is checked again when it is opened (io.h: the output guard). */
static int check_outputs_apart(const indent_options *o)
{
    const char **recorded = NULL;
    im_indent_options run;
    int status = run_options(o, &recorded, NULL, &run);
    if (status == IM_OK)
        status = indent_run_check(&run);
    free(recorded);
    if (status == IM_OK)
        return 0;
    fprintf(stderr, "indentmap: %s\n", im_last_error());
    return -1;
}

/* The operand SURFACE, noted in the arguments; with --from-record none may be given beside it. */
static int parse_operands(int argc, char **argv, indent_options *o)
{
    if (optind < argc)
        o->surface_path = argv[optind++];
    if (optind < argc) {
        fprintf(stderr, "indentmap: unexpected argument '%s'\n", argv[optind]);
        return -1;
    }
    if (o->from_record && (o->surface_path || o->arguments.list)) {
        fprintf(stderr, "indentmap: --from-record runs the recorded options: give only --out, --wisdom or "
                        "--no-wisdom beside it\n");
        return -1;
    }
    if (o->surface_path && indent_arguments_add(&o->arguments, NULL, o->surface_path, 1) != IM_OK) {
        fprintf(stderr, "indentmap: SURFACE: %s\n", im_last_error());
        return -1;
    }
    return 0;
}

static int parse_arguments(int argc, char **argv, indent_options *o)
{
    *o = (indent_options){.nx = 512,
                          .ny = 512,
                          .delta = 1,
                          .slope_definition = -1,
                          .punch = im_indenter_cone(80),
                          .solver = im_solver_options_default()};
    int parsed = cli_parse_options(argc, argv, LONG_OPTIONS, OPT_HELP, usage, apply_option, o);
    if (parsed != 0)
        return parsed;
    if (parse_operands(argc, argv, o) != 0)
        return -1;
    if (o->from_record) /* the record's options are parsed next (parse_command) */
        return 0;
    if (!o->out)
        o->out = "output/indent";
    if (!o->m_given)
        o->ny = o->nx;
    o->punch.centred = !o->x_given;
    if (check_options(o) != 0 || parse_targets(o) != 0)
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

/* What parse_command returns for a record it refuses (its message said): no hint at the options. */
enum { REFUSED_RECORD = -2 };

/* The command line's options or, with --from-record, those of the run the record names, with --out and
 * the wisdom options of the command line (indent_record.h). */
static int parse_command(int argc, char **argv, indent_options *o, indent_replay *replay)
{
    int parsed = parse_arguments(argc, argv, o);
    if (parsed != 0 || !o->from_record)
        return parsed;
    const char *record = o->from_record;
    const indent_replay_options given = {o->out, o->wisdom, o->no_wisdom};
    if (indent_replay_load(record, &given, replay) != IM_OK) {
        fprintf(stderr, "indentmap: --from-record: %s\n", im_last_error());
        return REFUSED_RECORD;
    }
    parsed = parse_arguments(replay->argc, replay->argv, o);
    o->from_record = record;
    return parsed;
}

/* The run (indent.h: im_indent_run) with the options parsed: its lines said, the renderer of --frames
 * chosen as the program chooses it (IM_RENDER_BACKEND). */
static int run_indentation(const indent_options *o)
{
    im_render_backend backend = IM_RENDER_AUTO;
    if (cli_interrupt_install() != 0)
        return im_fail(IM_EUNSUPPORTED, "cannot install the signal handlers");
    int status = o->frames ? cli_render_backend(&backend) : IM_OK;
    if (status != IM_OK)
        return status;
    char *command = indent_arguments_command(&o->arguments);
    const char **recorded = NULL;
    im_indent_options run;
    status = command ? run_options(o, &recorded, command, &run) : im_fail(IM_ENOMEM, "figure texts: out of memory");
    run.backend = (int)backend;
    if (status == IM_OK)
        status = im_indent_run(&run);
    free(recorded);
    free(command);
    return status;
}

int cli_indent(int argc, char **argv)
{
    indent_options o;
    indent_replay replay = {0};
    int parsed = parse_command(argc, argv, &o, &replay);
    int status = parsed == 0 ? run_indentation(&o) : IM_OK;
    free(o.targets);
    json_decref(o.arguments.list);
    indent_replay_free(&replay);
    if (parsed != 0) {
        if (parsed == -1)
            fprintf(stderr, "(indentmap indent --help lists the options)\n");
        return parsed > 0 ? CLI_EXIT_OK : CLI_EXIT_USAGE;
    }
    if (status == IM_EINTERRUPTED)
        return cli_interrupt_report(1);
    return status == IM_OK ? CLI_EXIT_OK : cli_report(status);
}
