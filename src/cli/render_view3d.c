/* indentmap render view3d: the deformed surface in 3-D, coloured by local force, with the punch. */
#include "cli/cli.h"
#include "cli/figure_provenance.h"
#include "front/front.h"

#include "indentmap/colormap.h"
#include "indentmap/figure.h"
#include "indentmap/formats.h"
#include "indentmap/io.h"
#include "indentmap/render.h"
#include "indentmap/status.h"

#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void usage(FILE *stream)
{
    fprintf(stream,
            "usage: indentmap render view3d HEIGHT [--force FILE] [--displacement FILE] [OPTIONS] --out FILE\n\n"
            "Draws HEIGHT (a surface or deformed surface file: " CLI_SURFACE_FORMATS ")\n"
            "as a lit 3-D mesh with the off-screen OpenGL renderer; with --displacement the drawn surface\n"
            "is HEIGHT - u (u from `indentmap indent --fields`, positive into the half-space). Patches\n"
            "with force > 0 in --force are coloured by it through the norm (as `render contact`), patches\n"
            "under tension (force < 0: adhesion) by their tension on the blue ramp of a second colour bar,\n"
            "the others light grey.\n"
            "The punch rests on the drawn heights. Output: a figure (.png, .pdf, .svg) with the colour\n"
            "bar and the vertical exaggeration stated, or with --raw the image only (PNG).\n\n"
            "  --out FILE            the figure\n"
            "  --raw                 PNG of the rendered image only\n"
            "  --force FILE          local forces (same grid) for the contact colours\n"
            "  --displacement FILE   subtract this displacement u from HEIGHT\n"
            "  --unit, --height-unit, --channel, --fill, --npy-order, --resample-square, --crop,\n"
            "  --detrend, --align    read and prepare HEIGHT as `indentmap indent` its SURFACE (the\n"
            "                        displacement of its --fields is of the surface so prepared)\n"
            "  --punch KIND          cone (default), sphere, flat or none\n"
            "  --alpha A             cone semi-opening angle in degrees (default 80)\n"
            "  --radius R            sphere or flat punch radius, in the units of delta\n"
            "  --x X --y Y           punch axis (default: centre of patch (nx/2, ny/2))\n"
            "  --punch-mode M        translucent (default), opaque, cutaway (near half removed)\n"
            "  --azimuth A           camera bearing in degrees (default 20; 0: from the map's bottom edge)\n"
            "  --elevation E         camera elevation in degrees, 1..90 (default 35)\n"
            "  --distance D          camera distance in grid sides (default: the nearest that shows\n"
            "                        the whole block and punch)\n"
            "  --fov F               vertical field of view in degrees (default 30)\n"
            "  --ortho               orthographic projection (for figures)\n"
            "  --ortho-height H      orthographic: world height of the image in patches (default: fit)\n"
            "  --exaggeration X      vertical exaggeration (default 1: true scale)\n"
            "  --width W --height H  image size in pixels (default 1920 x 1080)\n"
            "  --samples S           multisamples per pixel: 1, 2, 4 (default) or 8\n"
            "  --mesh-side N         level of detail: mesh cells along the longer side (default 384)\n"
            "  --colormap NAME       magma (default, as the contact frames), viridis, cividis, inferno\n"
            "                        or grey\n"
            "  --vmin V, --vmax V    force norm range (default: two decades below the largest force;\n"
            "                        linear: from 0)\n"
            "  --log                 logarithmic norm, the default (the contact frames' norm)\n"
            "  --linear              linear norm\n"
            "  --title TEXT          panel title (the exaggeration is appended)\n"
            "  --dpi D               resolution (default 300)\n"
            "  --backend B           auto (default), egl or osmesa\n");
}

typedef struct view3d_options {
    const char *out, *force, *displacement, *title;
    int raw, has_log, has_linear, has_vmin, has_vmax, has_distance, no_punch;
    double vmin, vmax, dpi;
    double largest_tension; /* of --force: > 0 draws the tension's colour bar */
    im_colormap_id map;
    im_indenter punch;
    int x_given, y_given, radius_given;
    im_view3d_style style;
    im_render_backend backend;
    char force_unit[40];          /* of --force (its sidecar), "" for E* δ² */
    cli_provenance provenance;    /* the command line, where it ran and the inputs: the figure's record */
    im_surface_read_options read; /* HEIGHT's reading and preparation, indent's options (cli.h) */
    cli_preparation preparation;
} view3d_options;

enum {
    OPT_OUT = 256,
    OPT_RAW,
    OPT_FORCE,
    OPT_DISPLACEMENT,
    OPT_PUNCH,
    OPT_ALPHA,
    OPT_RADIUS,
    OPT_X,
    OPT_Y,
    OPT_MODE,
    OPT_AZIMUTH,
    OPT_ELEVATION,
    OPT_DISTANCE,
    OPT_FOV,
    OPT_ORTHO,
    OPT_ORTHO_HEIGHT,
    OPT_EXAGGERATION,
    OPT_WIDTH,
    OPT_HEIGHT,
    OPT_SAMPLES,
    OPT_MESH,
    OPT_MAP,
    OPT_VMIN,
    OPT_VMAX,
    OPT_LOG,
    OPT_LINEAR,
    OPT_TITLE,
    OPT_DPI,
    OPT_BACKEND,
    OPT_HELP
};

static const struct option LONG_OPTIONS[] = {{"out", required_argument, 0, OPT_OUT},
                                             {"raw", no_argument, 0, OPT_RAW},
                                             {"force", required_argument, 0, OPT_FORCE},
                                             {"displacement", required_argument, 0, OPT_DISPLACEMENT},
                                             CLI_SURFACE_FILE_OPTIONS,
                                             {"punch", required_argument, 0, OPT_PUNCH},
                                             {"alpha", required_argument, 0, OPT_ALPHA},
                                             {"radius", required_argument, 0, OPT_RADIUS},
                                             {"x", required_argument, 0, OPT_X},
                                             {"y", required_argument, 0, OPT_Y},
                                             {"punch-mode", required_argument, 0, OPT_MODE},
                                             {"azimuth", required_argument, 0, OPT_AZIMUTH},
                                             {"elevation", required_argument, 0, OPT_ELEVATION},
                                             {"distance", required_argument, 0, OPT_DISTANCE},
                                             {"fov", required_argument, 0, OPT_FOV},
                                             {"ortho", no_argument, 0, OPT_ORTHO},
                                             {"ortho-height", required_argument, 0, OPT_ORTHO_HEIGHT},
                                             {"exaggeration", required_argument, 0, OPT_EXAGGERATION},
                                             {"width", required_argument, 0, OPT_WIDTH},
                                             {"height", required_argument, 0, OPT_HEIGHT},
                                             {"samples", required_argument, 0, OPT_SAMPLES},
                                             {"mesh-side", required_argument, 0, OPT_MESH},
                                             {"colormap", required_argument, 0, OPT_MAP},
                                             {"vmin", required_argument, 0, OPT_VMIN},
                                             {"vmax", required_argument, 0, OPT_VMAX},
                                             {"log", no_argument, 0, OPT_LOG},
                                             {"linear", no_argument, 0, OPT_LINEAR},
                                             {"title", required_argument, 0, OPT_TITLE},
                                             {"dpi", required_argument, 0, OPT_DPI},
                                             {"backend", required_argument, 0, OPT_BACKEND},
                                             {"help", no_argument, 0, OPT_HELP},
                                             {0, 0, 0, 0}};

static int named(int status, const char *option)
{
    if (status != IM_OK)
        fprintf(stderr, "indentmap: %s: %s\n", option, im_last_error());
    return status == IM_OK ? 0 : -1;
}

static int parse_choice(const char *option, const char *arg, const char *const *names, int count, int *out)
{
    for (int i = 0; i < count; ++i)
        if (strcmp(arg, names[i]) == 0) {
            *out = i;
            return 0;
        }
    fprintf(stderr, "indentmap: %s: '%s': expected", option, arg);
    for (int i = 0; i < count; ++i)
        fprintf(stderr, "%s %s", i == 0 ? "" : i == count - 1 ? " or" : ",", names[i]);
    fputc('\n', stderr);
    return -1;
}

static int apply_punch(view3d_options *o, const char *arg)
{
    static const char *const kinds[] = {"cone", "sphere", "flat", "none"};
    int kind;
    if (parse_choice("--punch", arg, kinds, 4, &kind) != 0)
        return -1;
    o->no_punch = kind == 3;
    if (kind < 3)
        o->punch.kind = (enum im_punch_kind)kind;
    return 0;
}

static int apply_option(int code, const char *arg, void *state)
{
    view3d_options *o = state;
    im_view3d_style *s = &o->style;
    static const char *const modes[] = {"translucent", "opaque", "cutaway", "none"};
    int choice;
    switch (code) {
    case OPT_OUT: return cli_parse_path("--out", arg, &o->out);
    case OPT_RAW: o->raw = 1; return 0;
    case OPT_FORCE: o->force = arg; return 0;
    case OPT_DISPLACEMENT: o->displacement = arg; return 0;
    case OPT_PUNCH: return apply_punch(o, arg);
    case OPT_ALPHA: return cli_parse_double("--alpha", arg, 1e-9, 90 - 1e-9, &o->punch.alpha_degrees);
    case OPT_RADIUS: o->radius_given = 1; return cli_parse_double("--radius", arg, 1e-300, 1e300, &o->punch.radius);
    case OPT_X: o->x_given = 1; return cli_parse_double("--x", arg, -1e300, 1e300, &o->punch.x0);
    case OPT_Y: o->y_given = 1; return cli_parse_double("--y", arg, -1e300, 1e300, &o->punch.y0);
    case OPT_MODE:
        if (parse_choice("--punch-mode", arg, modes, 4, &choice) != 0)
            return -1;
        s->punch_mode = (im_view3d_punch)choice;
        return 0;
    case OPT_AZIMUTH: return cli_parse_double("--azimuth", arg, -1e6, 1e6, &s->camera.azimuth);
    case OPT_ELEVATION: return cli_parse_double("--elevation", arg, 1, 90, &s->camera.elevation);
    case OPT_DISTANCE:
        o->has_distance = 1;
        return cli_parse_double("--distance", arg, 1e-3, 1e5, &s->camera.distance);
    case OPT_FOV: return cli_parse_double("--fov", arg, 1.001, 119.999, &s->camera.field_of_view);
    case OPT_ORTHO: s->camera.projection = IM_VIEW3D_ORTHOGRAPHIC; return 0;
    case OPT_ORTHO_HEIGHT: return cli_parse_double("--ortho-height", arg, 1e-6, 1e8, &s->camera.ortho_height);
    case OPT_EXAGGERATION: return cli_parse_double("--exaggeration", arg, 1e-6, 1e5, &s->exaggeration);
    case OPT_WIDTH: return cli_parse_int("--width", arg, 16, 16384, &s->width);
    case OPT_HEIGHT: return cli_parse_int("--height", arg, 16, 16384, &s->height);
    case OPT_SAMPLES: return cli_parse_int("--samples", arg, 1, 8, &s->samples);
    case OPT_MESH: return cli_parse_int("--mesh-side", arg, 8, 16384, &s->mesh_side);
    case OPT_MAP: return named(im_colormap_from_name(arg, &o->map), "--colormap");
    case OPT_VMIN: o->has_vmin = 1; return cli_parse_double("--vmin", arg, -1e300, 1e300, &o->vmin);
    case OPT_VMAX: o->has_vmax = 1; return cli_parse_double("--vmax", arg, -1e300, 1e300, &o->vmax);
    case OPT_LOG: o->has_log = 1; return 0;
    case OPT_LINEAR: o->has_linear = 1; return 0;
    case OPT_TITLE: o->title = arg; return 0;
    case OPT_DPI: return cli_parse_double("--dpi", arg, 1.0, 2400.0, &o->dpi);
    case OPT_BACKEND: return named(im_render_backend_from_name(arg, &o->backend), "--backend");
    default: return cli_apply_surface_file_option(code, arg, &o->read, &o->preparation, NULL);
    }
}

/* HEIGHT read and prepared as indent's SURFACE (its surface-file options), minus the displacement when one is
 * given. */
static int read_height(const char *path, const view3d_options *o, im_field **height)
{
    im_surface_read_info info;
    int status = im_surface_read_with(path, &o->read, height, &info);
    if (status == IM_OK)
        cli_warn_about_reading(path, &info, im_field_count(*height));
    if (status == IM_OK)
        status = cli_prepare_surface(&o->preparation, height);
    im_field *u = NULL;
    if (status != IM_OK || !o->displacement)
        return status;
    status = im_surface_read(o->displacement, &u);
    if (status == IM_OK && (u->nx != (*height)->nx || u->ny != (*height)->ny))
        status = im_fail(IM_EINVAL, "%s: grid %d x %d: expected the grid of %s, %d x %d", o->displacement, u->nx,
                         u->ny, path, (*height)->nx, (*height)->ny);
    for (size_t i = 0; status == IM_OK && i < im_field_count(u); ++i)
        (*height)->data[i] -= u->data[i];
    im_field_free(u);
    return status;
}

/* The contact maps' norm of the force (colormap.h: log unless --linear), with --vmin / --vmax put in. */
static void apply_norm(const view3d_options *o, const im_field *force, im_colormap *c)
{
    im_colormap_range forces = im_colormap_range_empty(IM_COLORMAP_FORCES);
    if (force)
        im_colormap_range_add(&forces, force);
    *c = im_colormap_range_norm(&forces, o->map, o->has_vmin ? o->vmin : NAN, o->has_vmax ? o->vmax : NAN,
                                !o->has_linear);
}

/* Without --distance, the nearest perspective camera that shows all that is drawn. */
static int apply_distance(const view3d_options *o, const im_field *height, im_view3d_style *s)
{
    if (o->has_distance || s->camera.projection != IM_VIEW3D_PERSPECTIVE)
        return IM_OK;
    const int status = im_view3d_fit_distance(height, o->no_punch ? NULL : &o->punch, s, &s->camera.distance);
    if (status != IM_EINVAL || o->no_punch || isnan(s->camera.distance)) /* NaN: not fitted (render.h) */
        return status;
    char key[64]; /* the punch the camera cannot frame: a needle of a cone (S12) */
    if (o->punch.kind == IM_PUNCH_CONE)
        snprintf(key, sizeof key, "--alpha %.9g", o->punch.alpha_degrees);
    else
        snprintf(key, sizeof key, "--punch %s", im_punch_name(o->punch.kind));
    return im_fail_context(status,
                           "%s: a camera that sees the punch whole stands too far (expected a blunter punch, "
                           "--punch none or --distance D)",
                           key);
}

/* The colour bars' labels in --force's unit (figure.h: im_figure_colorbar_label, as the maps'). */
typedef struct view_labels {
    char force[96], tension[96], exaggeration[96];
} view_labels;

static int write_figure(const view3d_options *o, const im_image *image, const view_labels *labels,
                        const run_figure_texts *texts)
{
    if (o->raw) {
        im_png_options options = {texts->texts, texts->count, o->dpi / 0.0254, IM_FIGURE_PNG_COMPRESSION};
        return im_png_write(o->out, image->rgba, image->width, image->height, 4, (size_t)image->width * 4, &options);
    }
    char title[256];
    snprintf(title, sizeof title, "%s%s%s", o->title ? o->title : "", o->title ? ", " : "", labels->exaggeration);
    im_figure_panel panel = {image, NULL, title};
    im_figure figure = im_figure_default();
    figure.panels = &panel;
    figure.colormap = o->force ? &o->style.colormap : NULL;
    figure.colorbar_label = labels->force;
    figure.extend_under = o->style.colormap.logarithmic;
    if (o->largest_tension > 0.0) {
        figure.tension_colormap = &o->style.tension;
        figure.tension_label = labels->tension;
    }
    figure.scale_bar = -1.0; /* a perspective view has no single scale */
    figure.dpi = o->dpi;
    figure.texts = texts->texts;
    figure.text_count = texts->count;
    return im_figure_write(&figure, o->out);
}

/* The figure (write_figure) with its texts: the record of the command (figure_provenance.h) and the
 * drawing's settings. */
static int write_view(const view3d_options *o, const im_image *image)
{
    view_labels labels;
    char norm_text[128];
    im_view3d_exaggeration_text(o->style.exaggeration, labels.exaggeration, sizeof labels.exaggeration);
    const im_colormap *norm = &o->style.colormap;
    run_figure_norm_text(norm, norm_text, sizeof norm_text);
    int status = im_figure_colorbar_label("force", o->force_unit, labels.force, sizeof labels.force);
    if (status == IM_OK)
        status = im_figure_colorbar_label("tension", o->force_unit, labels.tension, sizeof labels.tension);
    if (status != IM_OK)
        return status;
    const im_png_text given[] = {{"Quantity", labels.force},
                                 {"Colormap", im_colormap_name(norm->map)},
                                 {"Norm", norm_text},
                                 {"Vertical exaggeration", labels.exaggeration}};
    run_figure_texts texts;
    status = cli_provenance_texts(&o->provenance, given, 4, &texts);
    if (status == IM_OK)
        status = write_figure(o, image, &labels, &texts);
    run_figure_texts_free(&texts);
    return status;
}

/* The files the view is drawn from, with their SHA-256, for the figure's record. */
static int record_inputs(view3d_options *o, const char *path)
{
    int status = cli_provenance_add_input(&o->provenance, "HEIGHT", path);
    if (status == IM_OK)
        status = cli_provenance_add_input(&o->provenance, "--displacement", o->displacement);
    if (status == IM_OK)
        status = cli_provenance_add_input(&o->provenance, "--force", o->force);
    return status;
}

static int run(view3d_options *o, const char *path)
{
    im_field *height = NULL, *force = NULL;
    im_render_context *context = NULL;
    im_image image = {0};
    int status = record_inputs(o, path);
    if (status == IM_OK)
        status = read_height(path, o, &height);
    if (status == IM_OK && o->force)
        status = im_surface_read(o->force, &force);
    if (status == IM_OK && force)
        memcpy(o->force_unit, force->value_unit, sizeof o->force_unit);
    if (status == IM_OK) {
        apply_norm(o, force, &o->style.colormap);
        o->largest_tension = force ? im_contact_largest_tension(force) : 0.0;
        o->style.tension = im_contact_tension_norm(o->largest_tension);
        o->punch.centred = !(o->x_given || o->y_given);
        status = apply_distance(o, height, &o->style);
    }
    if (status == IM_OK)
        status = cli_render_open(o->backend, &context);
    if (status == IM_OK)
        status = im_render_view3d(context, height, force, o->no_punch ? NULL : &o->punch, &o->style, &image);
    if (status == IM_OK)
        status = write_view(o, &image);
    im_image_release(&image);
    im_render_close(context);
    im_field_free(force);
    im_field_free(height);
    return status == IM_OK ? CLI_EXIT_OK : cli_report(status);
}

static int view3d(view3d_options *o, int argc, char **argv)
{
    int parsed = cli_parse_options(argc, argv, LONG_OPTIONS, OPT_HELP, usage, apply_option, o);
    if (parsed != 0)
        return parsed > 0 ? CLI_EXIT_OK : CLI_EXIT_USAGE;
    if (argc - optind != 1 || !o->out) {
        fprintf(stderr, "indentmap: render view3d: expected one HEIGHT file and --out FILE\n");
        return CLI_EXIT_USAGE;
    }
    if (o->has_log && o->has_linear) {
        fprintf(stderr, "indentmap: --log and --linear: expected one norm\n");
        return CLI_EXIT_USAGE;
    }
    if (o->raw && !strstr(o->out, ".png")) {
        fprintf(stderr, "indentmap: --raw writes PNG: expected --out FILE.png\n");
        return CLI_EXIT_USAGE;
    }
    if ((o->punch.kind == IM_PUNCH_SPHERE || o->punch.kind == IM_PUNCH_FLAT) && !o->radius_given && !o->no_punch) {
        fprintf(stderr, "indentmap: --punch %s needs --radius R\n", im_punch_name(o->punch.kind));
        return CLI_EXIT_USAGE;
    }
    const char *inputs[3] = {argv[optind], o->force, o->displacement};
    if (cli_protect_inputs(inputs, 3) != 0 || cli_check_output_file("--out", o->out) != 0)
        return CLI_EXIT_USAGE;
    return run(o, argv[optind]);
}

int cli_render_view3d(int argc, char **argv)
{
    view3d_options o = {.map = IM_COLORMAP_MAGMA,
                        .dpi = 300.0,
                        .backend = IM_RENDER_AUTO,
                        .style = im_view3d_style_default(NULL)};
    o.punch = im_indenter_cone(80.0);
    int status = cli_provenance_start("indentmap render", argc, argv, &o.provenance);
    int code = status == IM_OK ? view3d(&o, argc, argv) : cli_report(status);
    cli_provenance_free(&o.provenance);
    return code;
}
