/* indentmap indent: an indentation history of a surface by a punch, under displacement or load
 * control, written step by step to DIR/history.csv, with DIR/run.json and optional fields. */
#include "cli/cli.h"
#include "cli/indent_record.h"
#include "front/front.h"
#include "front/indent_run.h"
#include "front/run_folder.h"

#include "indentmap/field.h"
#include "indentmap/formats.h"
#include "indentmap/indenter.h"
#include "indentmap/io.h"
#include "indentmap/measure.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"
#include "indentmap/theory.h"
#include "indentmap/version.h"

#include <getopt.h>
#include <jansson.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void usage(FILE *stream)
{
    fprintf(stream,
            "usage: indentmap indent (SURFACE | --smooth --n N) (--approach LIST | --load LIST) [OPTIONS]\n"
            "       indentmap indent --from-record DIR/run.json [--out NEWDIR] [--wisdom FILE | --no-wisdom]\n\n"
            "Indents SURFACE (.npy, .gsf, .sdf, .nc, .x3p or text) with a rigid punch and solves each\n"
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
            "                      patch whose gap is at most D. Under --approach or --load, whose values\n"
            "                      may then be negative (the punch pulled away; a load beyond the pull-off\n"
            "                      force is refused: the contact jumps out): the force-distance curve\n"
            "                      with its jumps, pull-off and lost work (run.json \"adhesion\",\n"
            "                      force_distance.png and .pdf; docs/solver.md, \"Adhesion\")\n"
            "  --adhesion-range D  the range of the adhesive stress (length unit); with --adhesion-work\n"
            "  --adhesion-law L    maugis-dugdale (default: the stress W / D up to the gap D) or\n"
            "                      exponential (the tension (W / D) exp(-g / D) at a gap g, W / D in\n"
            "                      contact, cut beyond g = 35 D); with --adhesion-work\n"
            "  --quality Q         draft (tol 1e-5), standard (1e-6, the default, as for scenes) or\n"
            "                      publication (1e-9): the solver tolerance of a speed/accuracy preset\n"
            "                      (errors measured in solver.h)\n"
            "  --tol T             stopping tolerance on the relative gap residual (default: the\n"
            "                      quality's); overrides --quality. run.json records quality and tol\n"
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
            "At N = 0 the ratio area_ratio = n_p delta^2 / A(N) is undefined and written as nan.\n");
}

/* Runs of at least this many steps keep FFTW wisdom in the user's cache by default. */
enum { CACHED_WISDOM_STEPS = 10 };

typedef struct indent_options {
    const char *surface_path, *out, *wisdom;
    int no_wisdom;
    char wisdom_cache[4096]; /* the cache's wisdom file, when that is the one used */
    int smooth, nx, ny, m_given, fields;
    int frames;         /* --frames (sets fields) */
    int page_embed;     /* --page-embed */
    int distributions;  /* --distributions */
    indent_files files; /* what the run writes into --out (indent_run.h) */
    double gap_scale;   /* their gaps' unit: the surface's h_rms (delta when smooth) */
    double delta;
    double surface_delta;           /* the patch side as solved (the surface's, after --delta) */
    im_surface_read_options read;   /* --delta, --unit, --height-unit, --fill, --npy-order, --resample-square */
    cli_preparation preparation;    /* --crop, --detrend */
    char e_star_unit[16];           /* --e-star-unit, "" when not given */
    char force_unit[40];            /* the unit of loads and forces, from the two above */
    char length_unit[16];           /* the surface's, as solved ("" in units of delta) */
    long filled;                    /* missing points filled on reading */
    im_surface_read_info read_info; /* how SURFACE was read (its pixels, for run.json) */
    im_indenter punch;
    const char *profile_path; /* --profile */
    im_profile *profile;      /* read from it once the surface's spacing is known; the punch borrows it */
    int radius_given, x_given, y_given, punch_given, alpha_given;
    int pressures;            /* --pressure: the targets are mean pressures until the cell is known */
    double cell_area;         /* --periodic: nx ny delta^2 */
    int slope_definition;     /* --slope-definition: IM_SLOPE_*, or -1: by the surface (slope_rule) */
    const char *slope_reason; /* why the theory's h'rms is the one it is, for run.json and the k fit */
    double theory_slope;      /* that h'rms */
    enum im_control control;
    const char *targets_text;
    const char *quality; /* preset name, NULL if none given */
    int tol_given;
    int adhesion_law_given; /* --adhesion-law */
    double *targets;
    int target_count;
    im_solver_options solver;
    indent_arguments arguments;    /* as run.json records them (indent_record.h) */
    const char *from_record;       /* --from-record: the record of the run made again */
    char *command;                 /* the arguments as a command line, for the figures */
    run_figure_texts figure_texts; /* what every figure carries: the version, the command, the inputs */
} indent_options;

enum {
    OPT_SMOOTH = 256,
    OPT_N,
    OPT_M,
    OPT_DELTA,
    OPT_UNIT,
    OPT_HEIGHT_UNIT,
    OPT_CHANNEL,
    OPT_LENGTH_UNIT,
    OPT_ESTAR_UNIT,
    OPT_FILL,
    OPT_RESAMPLE,
    OPT_CROP,
    OPT_DETREND,
    OPT_ALIGN,
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
    OPT_NPY_ORDER,
    OPT_MEAN_GAP,
    OPT_FRAMES,
    OPT_PAGE_EMBED,
    OPT_FROM_RECORD,
    OPT_ADHESION_LAW
};

static const struct option LONG_OPTIONS[] = {{"smooth", no_argument, 0, OPT_SMOOTH},
                                             {"n", required_argument, 0, OPT_N},
                                             {"m", required_argument, 0, OPT_M},
                                             {"delta", required_argument, 0, OPT_DELTA},
                                             {"unit", required_argument, 0, OPT_UNIT},
                                             {"height-unit", required_argument, 0, OPT_HEIGHT_UNIT},
                                             {"channel", required_argument, 0, OPT_CHANNEL},
                                             {"fill", no_argument, 0, OPT_FILL},
                                             {"resample-square", no_argument, 0, OPT_RESAMPLE},
                                             {"crop", required_argument, 0, OPT_CROP},
                                             {"npy-order", required_argument, 0, OPT_NPY_ORDER},
                                             {"length-unit", required_argument, 0, OPT_LENGTH_UNIT},
                                             {"e-star-unit", required_argument, 0, OPT_ESTAR_UNIT},
                                             {"detrend", required_argument, 0, OPT_DETREND},
                                             {"align", required_argument, 0, OPT_ALIGN},
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
                                             {0, 0, 0, 0}};

/* --punch (indenter.h: im_punch_parse, as a scene's [punch] shape). */
static int parse_punch(const char *text, enum im_punch_kind *kind)
{
    if (im_punch_parse(text, kind) == IM_OK)
        return 0;
    fprintf(stderr, "indentmap: --punch %s\n", im_last_error());
    return -1;
}

/* --adhesion-law (solver.h: im_adhesion_law_parse). */
static int parse_adhesion_law(const char *text, int *law)
{
    if (im_adhesion_law_parse(text, law) == IM_OK)
        return 0;
    fprintf(stderr, "indentmap: --adhesion-law: %s\n", im_last_error());
    return -1;
}

/* The option that gave the targets. */
static const char *target_option(const indent_options *o)
{
    if (o->control == IM_CONTROL_MEAN_GAP)
        return "--mean-gap";
    return o->control == IM_CONTROL_DISPLACEMENT ? "--approach" : o->pressures ? "--pressure" : "--load";
}

/* What the targets are, in run.json and messages. */
static const char *target_name(enum im_control control)
{
    return control == IM_CONTROL_LOAD ? "load" : control == IM_CONTROL_MEAN_GAP ? "mean_gap" : "approach";
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
    if (steps_parse_signed(option, o->targets_text, negative, o->targets, &o->target_count, error, sizeof error) == 0)
        return 0;
    fprintf(stderr, "indentmap: %s\n", error);
    return -1;
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
    case OPT_UNIT: return cli_parse_length_unit("--unit", arg, o->read.set.lateral);
    case OPT_HEIGHT_UNIT: return cli_parse_length_unit("--height-unit", arg, o->read.set.height);
    case OPT_CHANNEL: return cli_parse_channel(arg, o->read.channel);
    case OPT_FILL: o->read.fill = 1; return 0;
    case OPT_NPY_ORDER: return cli_parse_npy_order(arg, &o->read.npy_order);
    case OPT_RESAMPLE: o->read.resample_square = 1; return 0;
    case OPT_LENGTH_UNIT: return cli_parse_length_unit("--length-unit", arg, o->read.express_in);
    case OPT_ESTAR_UNIT: return cli_parse_name("--e-star-unit", arg, o->e_star_unit, sizeof o->e_star_unit);
    case OPT_CROP: return cli_parse_crop(arg, o->preparation.crop);
    case OPT_DETREND: return cli_parse_detrend(arg, &o->preparation.detrend);
    case OPT_ALIGN: return cli_parse_align(arg, &o->preparation.align);
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
    case OPT_ADHESION_LAW: o->adhesion_law_given = 1; return parse_adhesion_law(arg, &o->solver.adhesion_law);
    case OPT_QUALITY: o->quality = arg; return 0;
    case OPT_TOL: o->tol_given = 1; return cli_parse_double("--tol", arg, 1e-300, 0.5, &o->solver.tol);
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
    default: return -1;
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

/* Adhesion's options: both or neither, displacement or load control on the half-space or mean-gap control on
 * a periodic cell, a hardness on the half-space only (a negative target is refused by the step list's parser
 * without adhesion). 0, or -1 with the message said. */
static int check_adhesion_options(const indent_options *o)
{
    const int adhesion = o->solver.adhesion_work > 0;
    const int held = o->solver.periodic ? o->control == IM_CONTROL_MEAN_GAP : o->control != IM_CONTROL_MEAN_GAP;
    if (adhesion != (o->solver.adhesion_range > 0))
        fprintf(stderr, "indentmap: --adhesion-work and --adhesion-range go together\n");
    else if (o->adhesion_law_given && !adhesion)
        fprintf(stderr,
                "indentmap: --adhesion-law goes with --adhesion-work and --adhesion-range (the law's work and "
                "range): expected both\n");
    else if (adhesion && !held)
        fprintf(stderr, "indentmap: --adhesion-work takes %s\n",
                o->solver.periodic
                    ? "--mean-gap with --periodic (a mean pressure on an adhesive cell is not available)"
                    : "--approach or --load");
    else if (adhesion && o->solver.hardness > 0 && o->solver.periodic)
        fprintf(stderr, "indentmap: --adhesion-work with --hardness and --periodic: adhesion with plasticity is "
                        "solved on the half-space only (drop --periodic or --hardness)\n");
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

static const char *slope_definition_name(int definition)
{
    return definition == IM_SLOPE_FINITE_DIFFERENCE ? "finite differences" : "spectral";
}

/* What the run writes into --out (indent_run.h: the names indent_files_claims claims). */
static run_folder_rules folder_rules(const indent_options *o)
{
    return (run_folder_rules){.dir = o->out,
                              .option = "--out",
                              .lock_advice = "give this run another --out",
                              .wisdom_advice = "give another --wisdom (or IM_FFTW_WISDOM) or another --out",
                              .claims = indent_files_claims,
                              .state = &o->files};
}

/* Refuses, before any work, an output folder whose outputs would replace the surface file, its
 * sidecar or the profile, and a wisdom file that is an input or an output. Every write is checked
 * again when it is opened (io.h: the output guard). */
static int check_outputs_apart(const indent_options *o)
{
    const char *const inputs[] = {o->surface_path, o->profile_path};
    const run_folder_rules rules = folder_rules(o);
    if (run_folder_check(&rules, inputs, 2, &o->solver) == IM_OK)
        return 0;
    fprintf(stderr, "indentmap: %s\n", im_last_error());
    return -1;
}

/* Where the tolerance came from, for run.json. */
static const char *tolerance_source(const indent_options *o)
{
    return o->tol_given ? "--tol" : o->quality ? "--quality" : "default";
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
    o->files = (indent_files){o->fields, o->solver.hardness, o->distributions, o->target_count};
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

/* The generator block of SURFACE.json (written by `indentmap surface`), or NULL. */
static json_t *surface_sidecar_generator(const char *surface_path)
{
    if (!surface_path)
        return NULL;
    char path[4096];
    if (im_path_suffix(path, sizeof path, surface_path, ".json") != IM_OK)
        return NULL; /* no sidecar can be there: the surface's own path is refused when read */
    json_t *root = json_load_file(path, 0, NULL);
    json_t *generator = root ? json_incref(json_object_get(root, "generator")) : NULL;
    json_decref(root);
    return generator;
}

/* SURFACE's pixels as read: its spacings along x and y (in the surface's unit), their relative
 * difference, and the resampling onto square pixels (method, spacing and the stored grid), or null. */
static json_t *pixels_record(const im_surface_read_info *info)
{
    json_t *resampled = info->resampled[0] ? json_pack("{s:s, s:f, s:i, s:i}", "method", info->resampled, "delta",
                                                       info->resampled_delta, "stored_nx", info->stored_nx,
                                                       "stored_ny", info->stored_ny)
                                           : json_null();
    return json_pack("{s:f, s:f, s:f, s:f, s:o}", "delta_x", info->used.delta_x, "delta_y", info->used.delta_y,
                     "relative_difference", info->spacing_difference, "tolerance", IM_SQUARE_PIXEL_TOLERANCE,
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

/* What this run was given beside the common fields (front.h: run_record_create). */
static json_t *indent_blocks(const indent_options *o, const im_field *s, const im_indentation *run)
{
    im_window w = im_indentation_window(run);
    double ax, ay;
    im_indenter_axis(&o->punch, s->nx, s->ny, s->delta, &ax, &ay);
    json_t *targets = json_array();
    for (int i = 0; i < o->target_count; ++i)
        json_array_append_new(targets, json_real(o->targets[i]));
    char source[4 * 4096 + 1];
    int escaped = im_path_utf8(o->surface_path ? o->surface_path : "smooth", source, sizeof source);
    char preparation[256];
    cli_describe_preparation(&o->preparation, o->filled, preparation, sizeof preparation);
    json_t *blocks = json_pack(
        "{s:{s:s, s:i, s:i, s:f, s:s, s:s}, s:{s:s, s:f, s:f, s:f, s:f}, s:s, s:o, s:{s:i, s:i, s:i, s:i}, s:i, "
        "s:s, s:b}",
        "surface", "source", source, "nx", s->nx, "ny", s->ny, "delta", s->delta, "unit", s->unit, "preparation",
        preparation, "punch", "kind", im_punch_name(o->punch.kind), "alpha_degrees", o->punch.alpha_degrees, "radius",
        o->punch.radius, "x", ax, "y", ay, "control", target_name(o->control), "targets", targets, "window", "x0",
        w.x0, "y0", w.y0, "nx", w.nx, "ny", w.ny, "threads", omp_get_max_threads(), "history", "history.csv",
        "fields", o->fields);
    if (blocks) {
        json_object_set_new(blocks, "periodic", json_boolean(o->solver.periodic));
        json_object_set_new(blocks, "theory_slope_rms",
                            json_pack("{s:f, s:s, s:s}", "value", o->theory_slope, "definition",
                                      slope_definition_name(o->slope_definition), "chosen_by",
                                      o->slope_reason ? o->slope_reason : "none"));
    }
    if (blocks && o->surface_path && o->read_info.used.delta_x > 0.0)
        json_object_set_new(json_object_get(blocks, "surface"), "pixels", pixels_record(&o->read_info));
    if (blocks && o->surface_path && o->read_info.conversion[0]) /* e.g. the instrument file's module and channel */
        json_object_set_new(json_object_get(blocks, "surface"), "values", json_string(o->read_info.conversion));
    if (blocks && escaped) /* the path is not UTF-8: its other bytes are written \xHH, backslashes \\ */
        json_object_set_new(json_object_get(blocks, "surface"), "source_encoding", json_string("escaped"));
    return blocks;
}

/* A number for JSON: null for NaN. */
static json_t *json_number(double value) { return isfinite(value) ? json_real(value) : json_null(); }

/* The adhesive law as run.json states it: its name, work, range, (peak) stress, the Dugdale zone's length (in
 * the length unit and in patches) and, for a sphere, Maugis's lambda and the law's Tabor mu. */
static json_t *adhesion_law_record(const indent_options *o)
{
    const double length = im_adhesion_zone_length(&o->solver),
                 lambda = im_adhesion_maugis_lambda(&o->solver, o->punch.radius);
    json_t *law = json_pack("{s:s, s:f, s:f, s:f, s:f, s:f}", "law", im_adhesion_law_name(o->solver.adhesion_law),
                            "work", o->solver.adhesion_work, "range", o->solver.adhesion_range, "stress",
                            o->solver.adhesion_work / o->solver.adhesion_range, "zone_length", length,
                            "zone_length_patches", length / o->surface_delta);
    const int sphere = o->punch.kind == IM_PUNCH_SPHERE;
    json_object_set_new(law, "maugis_lambda", sphere ? json_number(lambda) : json_null());
    json_object_set_new(law, "tabor_mu",
                        sphere ? json_number(im_adhesion_tabor_mu(&o->solver, o->punch.radius)) : json_null());
    return law;
}

/* The arguments the run is made again from (indent --from-record), and the record it was itself made
 * from (null for a command line). */
static void add_arguments(const indent_options *o, json_t *root)
{
    char from[4 * 4096 + 1];
    im_path_utf8(o->from_record ? o->from_record : "", from, sizeof from);
    json_object_set_new(root, "arguments", o->arguments.list ? json_incref(o->arguments.list) : json_array());
    if (o->arguments.escaped)
        json_object_set_new(root, "arguments_encoding", json_string("escaped"));
    json_object_set_new(root, "from_record", o->from_record ? json_string(from) : json_null());
}

/* run.json: the common record (front.h) with the surface (and the generator of its sidecar), the
 * punch, the targets, the window, the FFT plan and the units. */
static json_t *run_record(const indent_options *o, const im_field *s, const im_indentation *run)
{
    const im_solver_plan *plan = im_indentation_plan(run);
    run_record_solver solver = {.quality = o->quality     ? o->quality
                                           : o->tol_given ? "none"
                                                          : IM_QUALITY_DEFAULT,
                                .tol_from = tolerance_source(o),
                                .options = &o->solver};
    json_t *root = run_record_create("indentmap indent", o->smooth ? "smooth" : "surface", o->surface_path, &solver);
    json_t *blocks = root ? indent_blocks(o, s, run) : NULL;
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
    json_t *generator = surface_sidecar_generator(o->surface_path);
    if (generator) {
        json_object_set(json_object_get(root, "surface"), "generator", generator);
        json_t *seed = json_object_get(generator, "seed");
        if (seed)
            json_object_set(root, "seed", seed);
    }
    if (o->profile_path) { /* its shape is the file's (drop_meaningless_punch_fields: no angle or radius) */
        char profile[4 * 4096 + 1];
        im_path_utf8(o->profile_path, profile, sizeof profile);
        json_t *punch = json_object_get(root, "punch");
        json_object_set_new(punch, "profile", json_string(profile));
    }
    json_decref(generator);
    drop_meaningless_punch_fields(json_object_get(root, "punch"), o->punch.kind);
    json_object_set_new(root, "units", indent_units_record(s->unit, o->e_star_unit, o->solver.periodic));
    json_object_set_new(root, "adhesion", o->solver.adhesion_work > 0 ? adhesion_law_record(o) : json_null());
    add_arguments(o, root);
    return root;
}

/* run.json's "inputs": the surface and --profile files with their SHA-256, as a scene's record has
 * them (an empty list for a smooth run without a profile). */
static int add_inputs(const indent_options *o, json_t *record)
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

/* What every figure of the run carries (front.h: run_figure_texts): the version, the command that makes
 * it and its inputs' SHA-256. */
static int make_figure_texts(indent_options *o, const json_t *record)
{
    o->command = indent_arguments_command(&o->arguments);
    if (!o->command)
        return im_fail(IM_ENOMEM, "figure texts: out of memory");
    const im_png_text command = {"Command", o->command};
    return run_figure_texts_make(&command, 1, json_object_get(record, "inputs"), &o->figure_texts);
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

/* The same for the surface: the half-space's small-slope elasticity and the paper's theory assume
 * slopes well below 1 and, for a cone, below its flank's; a measured part can be far beyond both
 * (finding D17: a machined part with h'rms 1.15 under an 80 degree cone, flank 0.176). */
static void warn_if_rough_beyond_small_slopes(const indent_options *o)
{
    const double flank = o->punch.kind == IM_PUNCH_CONE ? 1 / tan(o->punch.alpha_degrees * M_PI / 180) : INFINITY;
    if (o->theory_slope > 1.0)
        fprintf(stderr,
                "indentmap: warning: the surface's h'rms = %.3g: slopes steeper than 45 degrees on average, "
                "where small-slope elasticity is stretched\n",
                o->theory_slope);
    if (o->theory_slope > flank)
        fprintf(stderr,
                "indentmap: warning: the surface's h'rms = %.3g is %.3g times the cone flank's slope cot(alpha) "
                "= %.3g: the roughness, not the cone, shapes the contact, beyond the paper's theory (h'rms below "
                "cot(alpha))\n",
                o->theory_slope, o->theory_slope / flank, flank);
}

static int load_surface(indent_options *o, im_field **surface)
{
    if (!o->smooth) {
        int status = im_surface_read_with(o->surface_path, &o->read, surface, &o->read_info);
        o->filled = status == IM_OK ? o->read_info.filled : 0;
        return status == IM_OK ? cli_prepare_surface(&o->preparation, surface) : status;
    }
    int status = im_field_create(o->nx, o->ny, o->delta, surface);
    if (status == IM_OK)
        memcpy((*surface)->unit, o->read.set.lateral, sizeof(*surface)->unit);
    return status;
}

/* N for Pa and m; otherwise "E*-unit length-unit²", with E* and δ standing in for what is not given. */
static void set_force_unit(indent_options *o, const im_field *surface)
{
    memcpy(o->length_unit, surface->unit, sizeof o->length_unit);
    step_force_unit(o->e_star_unit, surface->unit, o->force_unit, sizeof o->force_unit);
}

/* --x/--y must put the punch's axis on the surface (before: "the surface is too small"). */
static int check_axis_inside(const indent_options *o, const im_field *surface)
{
    double width = surface->nx * surface->delta, height = surface->ny * surface->delta;
    if (!o->x_given || (o->punch.x0 >= 0 && o->punch.x0 <= width && o->punch.y0 >= 0 && o->punch.y0 <= height))
        return IM_OK;
    return im_fail(IM_EINVAL,
                   "--x %g --y %g: the punch's axis lies outside the %d x %d surface (expected 0 <= x <= "
                   "%g and 0 <= y <= %g)",
                   o->punch.x0, o->punch.y0, surface->nx, surface->ny, width, height);
}

/* --profile, read now that the surface's spacing (a 2-D profile's) and length unit are known. */
static int load_profile(indent_options *o, const im_field *surface)
{
    if (!o->profile_path)
        return IM_OK;
    int status = im_profile_read(o->profile_path, surface->delta, &o->profile);
    if (status != IM_OK)
        return im_fail_context(status, "--profile");
    int centred = o->punch.centred;
    double x0 = o->punch.x0, y0 = o->punch.y0;
    o->punch = im_indenter_from_profile(o->profile);
    o->punch.centred = centred;
    o->punch.x0 = x0;
    o->punch.y0 = y0;
    return im_indenter_check(&o->punch);
}

/* The largest |target| (approaches below 0 pull away, with adhesion). */
static double largest(const double *v, int n)
{
    double m = 0;
    for (int i = 0; i < n; ++i)
        m = fmax(m, fabs(v[i]));
    return m;
}

/* Once per run: a contact of a few patches is below the grid's resolution (a smooth cone at 1 patch
 * carries 2.4x Love's load, at 9 patches 1.05x; issue 32), which nothing else would say. */
enum { RESOLVED_PATCHES = 10 };
static void warn_if_unresolved(const im_history_row *rows, int i)
{
    const long n = rows[i].result.contact_patches;
    for (int k = 0; k < i; ++k)
        if (rows[k].result.contact_patches > 0 && rows[k].result.contact_patches < RESOLVED_PATCHES)
            return; /* said already */
    if (n > 0 && n < RESOLVED_PATCHES)
        fprintf(stderr,
                "indentmap: warning: step %d: the contact covers %ld patch%s, too few for the grid to resolve "
                "it (a smooth cone carries 2.4x Love's load at 1 patch, 1.05x at 9): use a finer delta or a larger "
                "approach or load\n",
                i + 1, n, n == 1 ? "" : "es");
}

/* What the step line's area ratio divides by: the cell (periodic), or the smooth punch's area at the
 * load (the history's area_ratio, indenter.h). */
static const char *area_ratio_name(const indent_options *o)
{
    if (o->solver.periodic)
        return "A/A0";
    switch (o->punch.kind) {
    case IM_PUNCH_CONE: return "A/A_cone";
    case IM_PUNCH_SPHERE: return "A/A_Hertz";
    case IM_PUNCH_FLAT: return "A/A_punch";
    default: return "A/A_smooth";
    }
}

/* --periodic under a rigid flat without a hardness: k of eq. (2) fitted to the steps done (front.h:
 * periodic_fit_k, with the surface's h'rms of --slope-definition), printed and recorded in run.json
 * with its range. */
static void write_k_fit(const indent_options *o, const im_theory_interface *rough, const im_history_row *rows,
                        int done, json_t *record)
{
    periodic_k_fit k;
    if (periodic_fit_k(rows, done, o->cell_area, rough->slope_rms, rough->e_star, &k) != IM_OK) {
        fprintf(stderr, "indentmap: %s\n", im_last_error());
        return;
    }
    periodic_k_fit_print(&k, rough->slope_rms, slope_definition_name(o->slope_definition));
    json_object_set_new(record, "k_fit",
                        periodic_k_fit_record(&k, rough->slope_rms, slope_definition_name(o->slope_definition)));
}

/* Said once before the steps: a Dugdale zone shorter than a patch is not resolved. */
static void warn_if_zone_unresolved(const indent_options *o)
{
    const double patches = im_adhesion_zone_length(&o->solver) / o->surface_delta;
    if (patches < 1)
        fprintf(stderr,
                "indentmap: warning: the adhesive zone's length pi E* D^2 / (8 W) = %.3g patches is below one "
                "patch: the grid does not resolve it and the pull-off comes out too strong (a sphere: 8%% at 0.33 "
                "patches, 5 times at 0.03; 0.6%% at 3): use a finer delta or a wider --adhesion-range\n",
                patches);
}

/* The smooth punch's adhesive theory (front.h: a sphere's Maugis-Dugdale, a flat punch's Kendall) beside the
 * measured pull-off in run.json's "adhesion" block ("theory": null for the other punches, a rough surface or
 * a hardness) and adhesion_theory.csv beside the history. */
static void write_adhesion_theory(const indent_options *o, const im_history_row *rows, int done, json_t *law)
{
    const im_theory_adhesion theory = {o->solver.e_star, o->solver.adhesion_work, o->solver.adhesion_range};
    const char *model = NULL;
    im_theory_adhesive_point pull_off;
    /* (a periodic cell's flat is not a punch on a half-space, and the theories are the Maugis-Dugdale law's, on an
     * elastic body: no hardness) */
    const int smooth_punch = o->smooth && !o->solver.periodic &&
                             o->solver.adhesion_law == IM_ADHESION_MAUGIS_DUGDALE && !(o->solver.hardness > 0);
    int status = smooth_punch ? adhesion_theory_pull_off(&o->punch, &theory, &model, &pull_off) : IM_OK;
    if (status == IM_OK && model)
        status = adhesion_theory_write(o->out, &o->punch, &theory, rows, done);
    if (status != IM_OK) {
        fprintf(stderr, "indentmap: adhesion theory: %s\n", im_last_error());
        model = NULL;
    }
    if (!model) {
        json_object_set_new(law, "theory", json_null());
        return;
    }
    json_object_set_new(law, "theory",
                        json_pack("{s:s, s:f, s:f, s:f, s:s}", "model", model, "pull_off_force", -pull_off.load,
                                  "pull_off_approach", pull_off.approach, "contact_radius", pull_off.contact_radius,
                                  "file", "adhesion_theory.csv"));
    printf("adhesion theory (%s): pull-off force %.6g at w = %.6g; %s/adhesion_theory.csv\n", model, -pull_off.load,
           pull_off.approach, o->out);
}

/* With adhesion: the pull-off, the jumps and the lost work (front.h), printed and in run.json's
 * "adhesion" block beside the law, and force_distance.{png,pdf}. */
static void write_adhesion(const indent_options *o, const im_history_row *rows, int done, json_t *record)
{
    im_adhesion_summary summary = {.hysteresis_work = NAN}; /* NaN: not summarised */
    json_t *law = json_object_get(record, "adhesion");
    if (done >= 1 && analysis_write_adhesion(o->out, rows, done, o->length_unit, o->force_unit, &o->figure_texts,
                                             &summary) != IM_OK)
        fprintf(stderr, "indentmap: adhesion summary: %s\n", im_last_error());
    if (isnan(summary.hysteresis_work))
        return;
    json_object_set_new(law, "pull_off_force", json_number(summary.pull_off_force));
    json_object_set_new(law, "pull_off_approach", json_number(summary.pull_off_approach));
    json_object_set_new(law, "jump_in_approach", json_number(summary.jump_in_approach));
    json_object_set_new(law, "jump_out_approach", json_number(summary.jump_out_approach));
    json_object_set_new(law, "hysteresis_work", json_real(summary.hysteresis_work));
    json_object_set_new(law, "hysteresis_error", json_real(summary.hysteresis_error));
    json_object_set_new(law, "figure", json_string("force_distance.png"));
    printf("adhesion: pull-off force %.6g at w = %.6g; jump-in at w = %.6g, last contact retracting at w = %.6g; ",
           summary.pull_off_force, summary.pull_off_approach, summary.jump_in_approach, summary.jump_out_approach);
    if (fabs(summary.hysteresis_work) > summary.hysteresis_error)
        printf("work lost %.6g (+- %.2g, the steps' trapezoids)", summary.hysteresis_work, summary.hysteresis_error);
    else /* the loop lies between the steps: its sign and size are the trapezoids' error */
        printf("work lost not resolved by the steps: %.6g within the trapezoids' error +- %.2g (finer steps around "
               "the jumps resolve it)",
               summary.hysteresis_work, summary.hysteresis_error);
    printf("; %s/force_distance.png and .pdf\n", o->out);
    write_adhesion_theory(o, rows, done, law);
}

/* indentation.csv over the steps done (front.h), said on stdout and in run.json; a failure here is
 * reported but leaves the run's own status alone (the history is the result). */
static void write_analysis(const indent_options *o, const im_history_row *rows, int done, json_t *record)
{
    int branches = 0;
    if (o->solver.adhesion_work > 0) { /* Oliver-Pharr's analysis is of repulsive contact */
        json_object_set_new(record, "indentation", json_null());
        write_adhesion(o, rows, done, record);
        return;
    }
    if (o->solver.periodic) { /* Oliver-Pharr's areas are a punch's on a half-space */
        json_object_set_new(record, "indentation", json_null());
        return;
    }
    int status = analysis_write(o->out, &o->punch, rows, done, o->surface_delta, o->solver.e_star, o->length_unit,
                                o->force_unit, &o->figure_texts, &branches);
    if (status != IM_OK) {
        fprintf(stderr, "indentmap: indentation analysis: %s\n", im_last_error());
        return;
    }
    json_object_set_new(record, "indentation", branches > 0 ? json_string("indentation.csv") : json_null());
    if (branches == 0)
        return;
    printf("indentation analysis of %d unloading branch%s: %s/indentation.csv, load_displacement.png and .pdf\n",
           branches, branches == 1 ? "" : "es", o->out);
}

/* DIR/history.{png,pdf} (front.h: history_figure_write), with the theory where the run is elastic and
 * repulsive; a failure here is reported but leaves the run's own status alone. */
static void write_history_figure(const indent_options *o, const im_theory_interface *rough,
                                 const im_history_row *rows, int done)
{
    const int elastic = !(o->solver.hardness > 0) && !(o->solver.adhesion_work > 0);
    /* an adhesive cell's net load goes through 0: its force against the approach, as an adhesive punch's */
    const int area_plot = o->solver.periodic && !(o->solver.adhesion_work > 0);
    const history_figure figure = {rows,
                                   done,
                                   &o->punch,
                                   area_plot ? o->cell_area : 0.0,
                                   o->solver.periodic && !o->punch_given && elastic ? rough : NULL,
                                   elastic,
                                   o->length_unit,
                                   o->force_unit,
                                   o->e_star_unit,
                                   &o->figure_texts};
    if (history_figure_write(o->out, &figure) != IM_OK)
        fprintf(stderr, "indentmap: history figure: %s\n", im_last_error());
}

/* --periodic: the rigid flat when no --punch was given (a flat punch wider than the cell's diagonal
 * covers every nearest image), loads from --pressure's mean pressures, and a warning when SURFACE is
 * not periodic (the solver joins its edges, as ContactMechanics warns). */
static void prepare_periodic(indent_options *o, const im_field *surface)
{
    if (!o->solver.periodic)
        return;
    o->cell_area = periodic_cell_area(surface);
    if (!o->punch_given)
        o->punch = periodic_rigid_flat(surface);
    for (int i = 0; o->pressures && i < o->target_count; ++i)
        o->targets[i] *= o->cell_area;
    periodic_warn_if_not_periodic(surface, o->surface_path ? o->surface_path : "the surface");
}

/* --frames of the steps done, DIR/frames/contact_NNNN.png (front.h: fields_frames_write): a failure is the
 * run's error when it had none. */
static void draw_frames(const indent_options *o, const im_history_row *rows, int done, im_render_context *context,
                        int *status, char *message, size_t size)
{
    char folder[4096];
    const fields_frames frames = {
        o->out, folder, rows, done, &o->punch, o->force_unit, o->figure_texts.texts, o->figure_texts.count};
    int drawn = im_path_join(folder, sizeof folder, o->out, "frames");
    if (drawn == IM_OK)
        drawn = fields_frames_write(context, &frames);
    if (drawn != IM_OK)
        im_fail_context(drawn, "--frames");
    if (drawn != IM_OK && *status == IM_OK) {
        *status = drawn;
        snprintf(message, size, "%s", im_last_error());
    } else if (drawn != IM_OK) {
        fprintf(stderr, "indentmap: %s\n", im_last_error());
    }
}

/* The step just solved (indent_run.h's stepped): a warning for a contact too small, and its line. */
static void report_step(const im_history_row *rows, int i, const void *state)
{
    const indent_options *o = state;
    warn_if_unresolved(rows, i);
    const im_step_result *r = &rows[i].result;
    char gap[48] = "";
    if (o->solver.periodic)
        snprintf(gap, sizeof gap, "  mean gap = %.6g", r->mean_gap);
    printf("step %d: w = %.6g%s  N = %.6g  n_p = %ld  %s = %.4f  iterations %d  residual %.2e  %.3f s\n", i + 1,
           r->approach, gap, r->load, r->contact_patches, area_ratio_name(o), r->area_ratio, r->iterations,
           r->residual, r->seconds);
    fflush(stdout);
}

/* The signal that asked to stop, or 0 (indent_run.h's stop). */
static int stop_signal(const void *state)
{
    (void)state;
    return (int)cli_stop_signal;
}

/* The steps (indent_run.h: indent_run_steps), then what is drawn and analysed of those done, also
 * after a failure; run.json finished. rough: the surface's measured h'rms and the solver's E*, for
 * the theory columns. */
static int run_steps(const indent_options *o, const im_theory_interface *rough, im_indentation *run,
                     history_file *history, im_render_context *context, const run_folder *folder, json_t *record)
{
    im_history_row *rows = calloc((size_t)o->target_count, sizeof *rows);
    if (!rows)
        return im_fail(IM_ENOMEM, "history of %d steps", o->target_count);
    const indent_run_plan plan = {.dir = o->out,
                                  .punch = &o->punch,
                                  .rough = o->solver.periodic ? NULL : rough,
                                  .targets = o->targets,
                                  .count = o->target_count,
                                  .target_name = target_name(o->control),
                                  .files = o->files,
                                  .units = {o->solver.hardness, o->length_unit, o->force_unit},
                                  .gap_scale = o->gap_scale,
                                  .stop = stop_signal,
                                  .stepped = report_step,
                                  .state = o};
    int done = 0;
    int status = indent_run_steps(&plan, run, history, rows, &done);
    char message[1024];
    snprintf(message, sizeof message, "%s", im_last_error());
    if (o->frames) /* of the steps done, also when a later step failed */
        draw_frames(o, rows, done, context, &status, message, sizeof message);
    write_analysis(o, rows, done, record);
    write_history_figure(o, rough, rows, done);
    /* eq. (2) is an elastic, repulsive law for a rigid flat: no fit with a cap, adhesion or a repeated punch */
    if (o->solver.periodic && !o->punch_given && !(o->solver.hardness > 0) && !(o->solver.adhesion_work > 0))
        write_k_fit(o, rough, rows, done, record);
    if (status != IM_OK) /* what the analysis or the fit reported is not the run's error */
        im_fail(status, "%s", message);
    free(rows);
    return run_folder_record(folder, record, done, status);
}

/* Makes and locks DIR (a stale lock taken over is a warning), then removes what an earlier run left
 * there that this one would not replace (indent_run.h: indent_files_clear). */
static int prepare_folder(const indent_options *o, run_folder *folder)
{
    const run_folder_rules rules = folder_rules(o);
    int status = run_folder_open(&rules, 0, folder); /* --out may be any folder: not its subfolders */
    if (status != IM_OK)
        return status;
    cli_warn_stale_lock(&folder->lock);
    return indent_files_clear(o->out);
}

/* DIR/index.html over what the run left, even after a failure; the run's own error, if any, stays the
 * one reported. */
static int write_viewer_page(const indent_options *o, const run_folder *folder, int status)
{
    char title[1024];
    snprintf(title, sizeof title, "indentmap indent: %s", o->smooth ? "smooth surface" : o->surface_path);
    return run_folder_page(folder, title, o->page_embed, status);
}

/* The theory columns' interface: the surface's h'rms, the solver's E*, k = 2 and the PR normalisation.
 * The h'rms is --slope-definition's, else spectral for a surface known to be periodic (generated: its
 * sidecar names the generator; --smooth; solved as a periodic cell) and forward differences for a
 * measured one (the rule of scenes and of Python). */
static int measured_interface(indent_options *o, const im_field *surface, im_theory_interface *rough)
{
    json_t *generator = surface_sidecar_generator(o->surface_path);
    const int generated = o->smooth || generator;
    json_decref(generator);
    if (o->slope_definition < 0) {
        o->slope_definition = generated || o->solver.periodic ? IM_SLOPE_SPECTRAL : IM_SLOPE_FINITE_DIFFERENCE;
        o->slope_reason = generated            ? "default: a generated surface"
                          : o->solver.periodic ? "default: a periodic cell"
                                               : "default: a measured surface";
    } else {
        o->slope_reason = "--slope-definition";
    }
    double slope;
    int status = im_surface_slope_rms(surface, (enum im_slope_definition)o->slope_definition, &slope);
    if (status == IM_OK) {
        *rough = im_theory_interface_default(slope);
        rough->e_star = o->solver.e_star;
        o->theory_slope = slope;
    }
    return status;
}

/* The unit of --distributions' gaps: the surface's h_rms, its delta when it is smooth. */
static int set_gap_scale(indent_options *o, const im_field *surface)
{
    im_surface_stats stats;
    int status = im_surface_statistics(surface, &stats);
    if (status == IM_OK)
        o->gap_scale = stats.height_rms > 0.0 ? stats.height_rms : surface->delta;
    return status;
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

int cli_indent(int argc, char **argv)
{
    indent_options o;
    indent_replay replay = {0};
    int parsed = parse_command(argc, argv, &o, &replay);
    if (parsed != 0) {
        if (parsed == -1)
            fprintf(stderr, "(indentmap indent --help lists the options)\n");
        free(o.targets);
        json_decref(o.arguments.list);
        indent_replay_free(&replay);
        return parsed > 0 ? CLI_EXIT_OK : CLI_EXIT_USAGE;
    }
    im_field *surface = NULL;
    im_indentation *run = NULL;
    json_t *record = NULL;
    im_theory_interface rough;
    int status = cli_interrupt_install() != 0       ? im_fail(IM_EUNSUPPORTED, "cannot install the signal handlers")
                 : o.punch.kind == IM_PUNCH_PROFILE ? IM_OK /* checked once read, after the surface */
                                                    : im_indenter_check(&o.punch);
    if (status == IM_OK) {
        warn_if_steep(&o.punch);
        status = load_surface(&o, &surface);
    }
    if (status == IM_OK)
        status = load_profile(&o, surface);
    if (status == IM_OK) {
        prepare_periodic(&o, surface);
        status = check_axis_inside(&o, surface);
    }
    if (status == IM_OK) {
        o.surface_delta = surface->delta;
        set_force_unit(&o, surface);
        status = measured_interface(&o, surface, &rough);
    }
    if (status == IM_OK && !o.smooth) {
        warn_if_rough_beyond_small_slopes(&o);
        cli_warn_if_much_filled(o.surface_path, o.filled, im_field_count(surface));
    }
    if (status == IM_OK)
        status = set_gap_scale(&o, surface);
    im_render_context *context = NULL; /* --frames: opened before any step is solved */
    if (status == IM_OK && o.frames)
        status = cli_render_open(IM_RENDER_AUTO, &context);
    if (status == IM_OK)
        status = im_indentation_create(surface, &o.punch, o.control, largest(o.targets, o.target_count), &o.solver,
                                       &run);
    if (status == IM_OK && o.solver.adhesion_work > 0)
        warn_if_zone_unresolved(&o);
    run_folder folder = {.lock = {.fd = -1}};
    history_file history = {.fd = -1};
    if (status == IM_OK)
        status = prepare_folder(&o, &folder);
    if (status == IM_OK) {
        im_window w = im_indentation_window(run);
        printf("surface %d x %d, window [%d, %d) x [%d, %d) (%d x %d), %d threads, device %s\n", surface->nx,
               surface->ny, w.x0, w.x0 + w.nx, w.y0, w.y0 + w.ny, w.nx, w.ny, omp_get_max_threads(),
               im_solver_plan_device(im_indentation_plan(run)));
        record = run_record(&o, surface, run);
        status = record ? add_inputs(&o, record) : im_fail(IM_ENOMEM, "run record");
        if (status == IM_OK)
            status = make_figure_texts(&o, record);
        if (status == IM_OK)
            status = history_start(o.out, &history);
        if (record && status != IM_OK) /* no step solved: the record says why, not an earlier run's */
            run_folder_record(&folder, record, 0, status);
    }
    if (status == IM_OK)
        status = run_steps(&o, &rough, run, &history, context, &folder, record);
    history_close(&history);
    if (record)
        status = write_viewer_page(&o, &folder, status);
    run_folder_close(&folder);
    im_render_close(context);
    json_decref(record);
    im_indentation_free(run);
    im_profile_free(o.profile); /* after the run that borrowed it */
    im_field_free(surface);
    free(o.targets);
    json_decref(o.arguments.list);
    free(o.command);
    run_figure_texts_free(&o.figure_texts);
    indent_replay_free(&replay);
    if (status == IM_EINTERRUPTED) {
        fprintf(stderr, "indentmap: %s\n", im_last_error());
        return cli_interrupt_exit_status();
    }
    return status == IM_OK ? CLI_EXIT_OK : cli_report(status);
}
