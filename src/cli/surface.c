/* indentmap surface: generate a rough surface, or measure an existing one. */
#include "cli/cli.h"
#include "front/front.h"

#include "indentmap/colormap.h"
#include "indentmap/formats.h"
#include "indentmap/io.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"

#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void usage(FILE *stream)
{
    fprintf(stream,
            "usage: indentmap surface [OPTIONS] [--out FILE]\n"
            "       indentmap surface --stats FILE [--png FILE] [--psd FILE] [--histograms FILE]\n\n"
            "Generates an isotropic self-affine Gaussian surface by spectral synthesis (the paper's\n"
            "section 2.2) and prints its statistics; lengths are in grid spacings delta.\n\n"
            "  --n N              grid columns (default 512)\n"
            "  --m M              grid rows (default: N)\n"
            "  --delta D          patch side in physical units (default 1); with --stats, overrides the file's\n"
            "  --unit U           length unit of delta (m, mm, um, nm, ...); with --stats, a file stating its\n"
            "                     unit is converted into U (with --delta, both are restated)\n"
            "  --height-unit U    with --stats: unit of the file's heights, converted to --unit\n"
            "  --channel C        with --stats: the channel (index or title) of an instrument file read\n"
            "                     through Gwyddion (default: the first holding heights)\n"
            "  --fill             with --stats: fill missing points (NaN) from their neighbours (default:\n"
            "                     refuse them, naming the first)\n"
            "  --npy-order O      with --stats: yx (rows are y) or xy (the first index is x, as\n"
            "                     SurfaceTopography's heights()) for a .npy (default: its sidecar's, else yx)\n"
            "  --resample-square  with --stats: resample pixels that are not square (x and y spacings differing\n"
            "                     by more than 2^-16 of their mean) bilinearly onto square pixels of the finer\n"
            "                     spacing (default: refuse them; closer spacings are read as square, their mean)\n"
            "  --crop X0,Y0,NX,NY with --stats: measure only this block of the file\n"
            "  --detrend D        with --stats: none, plane (default) or curvature: removed before measuring\n"
            "  --align A          with --stats: scan-line alignment of the rows before detrending: none\n"
            "                     (default), median, mean or line (each row's offset or tilt removed)\n"
            "  --window W         with --stats: taper for the spectral quantities and the PSD of non-periodic\n"
            "                     data: hann (default), tukey[:ALPHA] (ALPHA 0.5) or none\n"
            "  --hurst H          Hurst exponent, 0 < H < 1 (default 0.8)\n"
            "  --slope S          target h'rms = sqrt(<|grad h|^2>) (default 0.08)\n"
            "  --height-rms R     target h_rms instead of h'rms, in units of delta\n"
            "  --slope-def DEF    'spectral' (default) or 'fd' (forward differences): how h'rms is measured\n"
            "  --lambda-s L       short-wavelength cutoff 2 pi / q_s (default 4)\n"
            "  --lambda-r L       roll-off wavelength 2 pi / q_r (default: max(N, M), the longer side)\n"
            "  --lambda-0 L       longest wavelength, > lambda-r adds a roll-off plateau (default: none)\n"
            "  --seed S           random seed (default 1); the same seed gives the same surface\n"
            "  --out FILE         write the surface (" CLI_SURFACE_WRITE_FORMATS ") and FILE.json beside it\n"
            "  --stats FILE       measure FILE (" CLI_SURFACE_FORMATS " matrix) instead of generating\n"
            "  --png FILE         write a height-field image (viridis, one pixel per patch)\n"
            "  --psd FILE         write the radially averaged PSD C_iso(q) as CSV\n"
            "  --histograms FILE  write height, slope and curvature histograms as CSV\n");
}

typedef struct surface_options {
    im_surface_params params;
    im_surface_read_options read; /* --delta, --unit, --height-unit, --fill, --npy-order, --resample-square */
    cli_preparation preparation;  /* --crop, --detrend, --window (files only) */
    int preparation_given;
    int generated_file; /* --stats of a file whose sidecar records its generator: measured as made */
    int m_given, lambda_r_given;
    const char *out, *stats, *png, *psd, *histograms;
} surface_options;

enum {
    OPT_N = 256,
    OPT_M,
    OPT_DELTA,
    OPT_WINDOW,
    OPT_HURST,
    OPT_SLOPE,
    OPT_HEIGHT,
    OPT_SLOPE_DEF,
    OPT_LS,
    OPT_LR,
    OPT_L0,
    OPT_SEED,
    OPT_OUT,
    OPT_STATS,
    OPT_PNG,
    OPT_PSD,
    OPT_HIST,
    OPT_HELP
};

static const struct option LONG_OPTIONS[] = {{"n", required_argument, 0, OPT_N},
                                             {"m", required_argument, 0, OPT_M},
                                             {"delta", required_argument, 0, OPT_DELTA},
                                             {"hurst", required_argument, 0, OPT_HURST},
                                             CLI_SURFACE_FILE_OPTIONS,
                                             {"window", required_argument, 0, OPT_WINDOW},
                                             {"slope", required_argument, 0, OPT_SLOPE},
                                             {"height-rms", required_argument, 0, OPT_HEIGHT},
                                             {"slope-def", required_argument, 0, OPT_SLOPE_DEF},
                                             {"lambda-s", required_argument, 0, OPT_LS},
                                             {"lambda-r", required_argument, 0, OPT_LR},
                                             {"lambda-0", required_argument, 0, OPT_L0},
                                             {"seed", required_argument, 0, OPT_SEED},
                                             {"out", required_argument, 0, OPT_OUT},
                                             {"stats", required_argument, 0, OPT_STATS},
                                             {"png", required_argument, 0, OPT_PNG},
                                             {"psd", required_argument, 0, OPT_PSD},
                                             {"histograms", required_argument, 0, OPT_HIST},
                                             {"help", no_argument, 0, OPT_HELP},
                                             {0, 0, 0, 0}};

static int parse_slope_definition(const char *text, enum im_slope_definition *out)
{
    if (strcmp(text, "spectral") == 0)
        *out = IM_SLOPE_SPECTRAL;
    else if (strcmp(text, "fd") == 0)
        *out = IM_SLOPE_FINITE_DIFFERENCE;
    else {
        fprintf(stderr, "indentmap: --slope-def: '%s': expected 'spectral' or 'fd'\n", text);
        return -1;
    }
    return 0;
}

/* Applies one option; 0 on success, -1 after printing an error. */
static int apply_option(int code, const char *arg, void *state)
{
    surface_options *o = state;
    im_surface_params *p = &o->params;
    switch (code) {
    case OPT_N: return cli_parse_int("--n", arg, 2, IM_FIELD_MAX_SIDE, &p->nx);
    case OPT_M: o->m_given = 1; return cli_parse_int("--m", arg, 2, IM_FIELD_MAX_SIDE, &p->ny);
    case OPT_DELTA:
        if (cli_parse_double("--delta", arg, 1e-300, 1e300, &p->delta) != 0)
            return -1;
        o->read.set.delta_x = p->delta;
        return 0;
    case OPT_WINDOW: o->preparation_given = 1; return cli_parse_taper(arg, &o->preparation.taper);
    case OPT_HURST: return cli_parse_double("--hurst", arg, 1e-6, 1 - 1e-6, &p->hurst);
    case OPT_SLOPE: p->target = IM_TARGET_SLOPE; return cli_parse_double("--slope", arg, 0, 1e6, &p->slope_rms);
    case OPT_HEIGHT:
        p->target = IM_TARGET_HEIGHT;
        return cli_parse_double("--height-rms", arg, 0, 1e12, &p->height_rms);
    case OPT_SLOPE_DEF: return parse_slope_definition(arg, &p->slope_definition);
    case OPT_LS: return cli_parse_double("--lambda-s", arg, 2, 1e9, &p->lambda_s);
    case OPT_LR: o->lambda_r_given = 1; return cli_parse_double("--lambda-r", arg, 2, 1e9, &p->lambda_r);
    case OPT_L0: return cli_parse_double("--lambda-0", arg, 2, 1e9, &p->lambda_0);
    case OPT_SEED: return cli_parse_u64("--seed", arg, &p->seed);
    case OPT_OUT: return cli_parse_path("--out", arg, &o->out);
    case OPT_STATS: o->stats = arg; return 0;
    case OPT_PNG: o->png = arg; return 0;
    case OPT_PSD: return cli_parse_path("--psd", arg, &o->psd);
    case OPT_HIST: o->histograms = arg; return 0;
    default: return cli_apply_surface_file_option(code, arg, &o->read, &o->preparation, &o->preparation_given);
    }
}

/* Where the spacing and the heights' unit came from, for a surface read from a file. */
static void print_units(const im_field *s, const im_surface_read_info *info, const im_surface_read_options *read)
{
    const im_surface_units *file = &info->file;
    printf("spacing          %s", read->set.delta_x > 0.0 ? "set by --delta"
                                  : file->delta_x > 0.0   ? "stated by the file"
                                                          : "none stated: lengths in delta");
    if (!(read->set.delta_x > 0.0) && file->delta_x > 0.0 && strcmp(file->lateral, s->unit) != 0 && file->lateral[0])
        printf(", %.9g %s, converted into %s", file->delta_x, file->lateral, s->unit);
    printf("\n");
    if (info->height_factor != 1.0)
        printf("heights          in %s, converted from %s (x %.6g)\n", s->unit, info->used.height,
               info->height_factor);
    else
        printf("heights          in %s\n", s->unit[0]        ? s->unit
                                           : s->delta == 1.0 ? "delta"
                                                             : "the spacing's unit (not named; --unit names it)");
    if (info->conversion[0])
        printf("values           %s\n", info->conversion);
}

/* Pixels that were not square: resampled onto square ones, or read as square within the tolerance. */
static void print_pixels(const im_surface_read_info *info)
{
    const im_surface_units *u = &info->used;
    const char *space = u->lateral[0] ? " " : "";
    if (info->resampled[0])
        printf("pixels           %d x %d of %.9g x %.9g%s%s, resampled (%s) onto square pixels of %.9g%s%s\n",
               info->stored_nx, info->stored_ny, u->delta_x, u->delta_y, space, u->lateral, info->resampled,
               info->resampled_delta, space, u->lateral);
    else if (info->spacing_difference > 0.0)
        printf("pixels           x spacing %.9g and y spacing %.9g%s%s differ by %.3g of their mean, within the %.3g "
               "%sthat rounding explains: read as square, of their mean\n",
               u->delta_x, u->delta_y, space, u->lateral, info->spacing_difference, info->square_tolerance,
               info->square_tolerance > IM_SQUARE_PIXEL_TOLERANCE ? "(the extents' printed digits) " : "");
}

static const char *taper_name(const im_taper *taper)
{
    return taper->kind == IM_TAPER_HANN ? "Hann" : taper->kind == IM_TAPER_TUKEY ? "Tukey" : NULL;
}

/* How a file was prepared, and so what its spectral h'rms means. */
static void print_preparation(const surface_options *o, const im_surface_read_info *info)
{
    char text[256];
    cli_describe_preparation(&o->preparation, info->filled, text, sizeof text);
    const char *taper = taper_name(&o->preparation.taper);
    printf("preparation      %s; spectral quantities and PSD %s%s%s%s\n", text,
           taper ? "of the " : "of the data as is", taper ? taper : "",
           taper ? "-tapered surface" : " (periodic box)",
           o->generated_file ? " (its sidecar records its generator: a synthesised periodic surface, measured as "
                               "made; --detrend, --window prepare it as measured data)"
                             : "");
}

static void print_statistics(const surface_options *o, const im_field *s, const im_surface_stats *st,
                             const im_surface_read_info *info)
{
    const im_surface_params *p = o->stats ? NULL : &o->params;
    printf("grid             %d x %d, delta = %g %s\n", s->nx, s->ny, s->delta, s->unit);
    if (info) {
        print_units(s, info, &o->read);
        print_pixels(info);
        print_preparation(o, info);
    }
    printf("mean             %.6g\n", st->mean);
    printf("h_rms            %.6g\n", st->height_rms);
    if (p) {
        printf("h_rms eq. (13)   %.6g   (exact moments of the spectrum)\n",
               im_surface_expected_height_rms(p, st->slope_rms_spectral));
        printf("h_rms eq. (15)   %.6g   (the paper's large-zeta approximation)\n",
               im_surface_height_rms_eq15(p, st->slope_rms_spectral));
    }
    if (info)
        printf("h'rms spectral   %.6g   (sqrt(sum q^2 |h_q|^2)%s)\n", st->slope_rms_spectral,
               o->preparation.taper.kind != IM_TAPER_NONE ? " of the tapered surface" : ", periodic box");
    else
        printf("h'rms spectral   %.6g\n", st->slope_rms_spectral);
    printf("h'rms fd         %.6g   (forward differences%s)\n", st->slope_rms_fd,
           info ? " of the prepared surface: what scenes compare with theory" : "");
    printf("curvature rms    %.6g   (mean curvature, spectral)\n", st->curvature_rms);
    printf("m0 m2 m4         %.6g %.6g %.6g\n", st->m0, st->m2, st->m4);
    printf("Nayak alpha      %.6g\n", st->nayak);
    printf("height range     [%.6g, %.6g]\n", st->height_min, st->height_max);
}

static int write_psd_csv(const char *path, const im_field *surface, const im_taper *taper)
{
    im_psd *psd = NULL;
    im_field *tapered = NULL;
    int status = im_surface_tapered(surface, taper, &tapered);
    if (status == IM_OK)
        status = im_surface_psd(tapered, 64, &psd);
    im_field_free(tapered);
    if (status != IM_OK)
        return status;
    im_atomic_file file;
    status = im_atomic_open(&file, path);
    if (status == IM_OK) {
        fprintf(file.stream, "q,c_iso,modes\n");
        for (int i = 0; i < psd->bins; ++i)
            if (psd->counts[i])
                fprintf(file.stream, "%.10g,%.10g,%ld\n", psd->q[i], psd->c[i], psd->counts[i]);
        status = im_atomic_commit(&file);
    }
    im_psd_free(psd);
    return status;
}

static int write_histograms_csv(const char *path, const im_field *surface)
{
    static const char *const NAMES[] = {"height", "slope", "curvature"};
    im_atomic_file file;
    int status = im_atomic_open(&file, path);
    if (status != IM_OK)
        return status;
    fprintf(file.stream, "quantity,centre,density\n");
    for (int q = 0; q < 3 && status == IM_OK; ++q) {
        im_histogram *h = NULL;
        status = im_surface_histogram(surface, (enum im_histogram_quantity)q, 101, &h);
        for (int b = 0; status == IM_OK && b < h->bins; ++b)
            fprintf(file.stream, "%s,%.10g,%.10g\n", NAMES[q], h->centre[b], h->density[b]);
        im_histogram_free(h);
    }
    if (status != IM_OK) {
        im_atomic_abort(&file);
        return status;
    }
    return im_atomic_commit(&file);
}

static int write_height_png(const char *path, const im_field *surface, const im_surface_stats *st)
{
    double half_range = fmax(fabs(st->height_min - st->mean), fabs(st->height_max - st->mean));
    im_colormap colormap = im_colormap_make(IM_COLORMAP_VIRIDIS, st->mean - half_range,
                                            st->mean + fmax(half_range, 1e-300));
    uint8_t *rgb = malloc(im_field_count(surface) * 3);
    if (!rgb)
        return im_fail(IM_ENOMEM, "%s: image allocation failed", path);
    im_colormap_field_image(&colormap, surface, rgb);
    char range[96];
    snprintf(range, sizeof range, "[%.6g, %.6g]", colormap.lo, colormap.hi);
    im_png_text texts[] = {{"Software", "indentmap " IM_VERSION},
                           {"Title", "height field"},
                           {"Colour map", "viridis"},
                           {"Height range", range}};
    im_png_options options = {texts, 4, 0.0, 6};
    int status = im_png_write(path, rgb, surface->nx, surface->ny, 3, (size_t)surface->nx * 3, &options);
    free(rgb);
    return status;
}

static int write_outputs(const surface_options *o, const im_field *surface, const im_surface_stats *st,
                         const im_surface_params *params)
{
    int status = IM_OK;
    if (o->out)
        status = im_surface_write_with_sidecar(o->out, surface, params, o->stats, st);
    if (status == IM_OK && o->png)
        status = write_height_png(o->png, surface, st);
    if (status == IM_OK && o->psd)
        status = write_psd_csv(o->psd, surface, &o->preparation.taper);
    if (status == IM_OK && o->histograms)
        status = write_histograms_csv(o->histograms, surface);
    return status;
}

/* Refuses, before any work, an output that is the measured file (--stats) or its sidecar:
 * `--psd s.npy` or `--png s.npy.json` would replace it. The writes are checked again when opened. */
static int check_outputs_apart(const surface_options *o)
{
    char sidecar[4096] = "";
    if (o->out && im_path_suffix(sidecar, sizeof sidecar, o->out, ".json") != IM_OK) {
        fprintf(stderr, "indentmap: --out: %s\n", im_last_error());
        return -1;
    }
    const char *const inputs[] = {o->stats};
    const char *const options[] = {"--out", "--out (its sidecar)", "--png", "--psd", "--histograms"};
    const char *const outputs[] = {o->out, o->out ? sidecar : NULL, o->png, o->psd, o->histograms};
    if (cli_protect_inputs(inputs, 1) != 0)
        return -1;
    for (int i = 0; i < 5; ++i)
        if (cli_check_output_file(options[i], outputs[i]) != 0)
            return -1;
    return 0;
}

static int parse_options(int argc, char **argv, surface_options *o)
{
    int parsed = cli_parse_options(argc, argv, LONG_OPTIONS, OPT_HELP, usage, apply_option, o);
    if (parsed != 0)
        return parsed;
    if (optind < argc) {
        fprintf(stderr, "indentmap: surface: unexpected argument '%s'\n", argv[optind]);
        return -1;
    }
    if (!o->stats && (o->read.set.height[0] || o->read.channel[0] || o->preparation_given)) {
        fprintf(stderr,
                "indentmap: surface: --height-unit, --channel, --fill, --resample-square, --crop, --align, --detrend "
                "and --window read a file: "
                "use them with --stats\n");
        return -1;
    }
    if (!o->stats) /* a synthesised surface is periodic and measured exactly */
        o->preparation = (cli_preparation){.detrend = IM_DETREND_NONE, .taper = {IM_TAPER_NONE, 0.0}};
    if (!o->m_given)
        o->params.ny = o->params.nx;
    if (!o->lambda_r_given)
        o->params.lambda_r = o->params.nx > o->params.ny ? o->params.nx : o->params.ny;
    if (!o->stats && !o->lambda_r_given && !(o->params.lambda_r > o->params.lambda_s)) {
        fprintf(stderr,
                "indentmap: --n %d: the box's side is the default lambda_r, which must exceed lambda_s = %g: "
                "expected a larger --n (or --lambda-s, --lambda-r)\n",
                o->params.nx, o->params.lambda_s);
        return -1;
    }
    if (o->params.lambda_0 != 0.0 && o->params.lambda_0 < o->params.lambda_r) {
        fprintf(stderr,
                "indentmap: --lambda-0 %g: expected >= lambda_r = %g (lambda_0 > lambda_r adds a roll-off "
                "plateau; without --lambda-0 there is none)\n",
                o->params.lambda_0, o->params.lambda_r);
        return -1;
    }
    if (o->params.lambda_0 < o->params.lambda_r)
        o->params.lambda_0 = o->params.lambda_r;
    return check_outputs_apart(o);
}

/* A file this program synthesised (its sidecar records the generator) is periodic: measured as made, it gives
 * the h'rms it was made with, as indent and scenes take it; the plane and Hann taper of measured data gave
 * 0.0728 for a requested 0.08 (redteam3 R6). A preparation asked for is kept. */
static void measure_generated_as_made(surface_options *o)
{
    json_t *generator = o->stats && !o->preparation_given ? surface_sidecar_generator(o->stats) : NULL;
    if (!generator)
        return;
    json_decref(generator);
    o->generated_file = 1;
    o->preparation = (cli_preparation){.detrend = IM_DETREND_NONE, .taper = {IM_TAPER_NONE, 0.0}};
}

int cli_surface(int argc, char **argv)
{
    /* A file is measured as non-periodic data: plane removed, Hann taper (both can be turned off). */
    surface_options o = {.params = im_surface_params_default(),
                         .preparation = {.detrend = IM_DETREND_PLANE, .taper = {IM_TAPER_HANN, 0.0}}};
    int parsed = parse_options(argc, argv, &o);
    if (parsed != 0)
        return parsed > 0 ? CLI_EXIT_OK : CLI_EXIT_USAGE;
    measure_generated_as_made(&o);
    if (cli_interrupt_install_cleanup() != 0)
        return cli_report(im_fail(IM_EUNSUPPORTED, "cannot install the SIGINT/SIGTERM handlers"));
    im_field *surface = NULL;
    im_surface_read_info info;
    int status = o.stats ? im_surface_read_with(o.stats, &o.read, &surface, &info)
                         : im_surface_generate(&o.params, &surface);
    if (status == IM_OK && !o.stats)
        memcpy(surface->unit, o.read.set.lateral, sizeof surface->unit);
    if (status == IM_OK && o.stats) {
        cli_warn_about_reading(o.stats, &info, im_field_count(surface));
        status = cli_prepare_surface(&o.preparation, &surface);
        if (status != IM_OK)
            im_fail_context(status, "%s", o.stats);
    }
    im_surface_stats stats;
    if (status == IM_OK)
        status = im_surface_statistics_tapered(surface, &o.preparation.taper, &stats);
    if (status == IM_OK) {
        print_statistics(&o, surface, &stats, o.stats ? &info : NULL);
        status = write_outputs(&o, surface, &stats, o.stats ? NULL : &o.params);
    }
    im_field_free(surface);
    return status == IM_OK ? CLI_EXIT_OK : cli_report(status);
}
