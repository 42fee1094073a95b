/* indentmap render: draw a field file as a contact map or a height field, or animate frames. */
#include "cli/cli.h"
#include "io/json_file.h"
#include "cli/figure_provenance.h"
#include "front/front.h"

#include "indentmap/colormap.h"
#include "indentmap/figure.h"
#include "indentmap/formats.h"
#include "indentmap/io.h"
#include "indentmap/render.h"
#include "indentmap/status.h"

#include <getopt.h>
#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void usage(FILE *stream)
{
    fprintf(stream,
            "usage: indentmap render contact FORCE... [OPTIONS] --out FILE\n"
            "       indentmap render height SURFACE... [OPTIONS] --out FILE\n"
            "       indentmap render animate FORCE... --frames DIR [--out FILE.gif|FILE.mp4] [OPTIONS]\n"
            "       indentmap render view3d HEIGHT [--force FILE] [OPTIONS] --out FILE   (see render view3d "
            "--help)\n\n"
            "Draws a field file (" CLI_SURFACE_FORMATS " matrix)\n"
            "with the off-screen OpenGL renderer.\n"
            "contact: local compressive forces, none grey (the paper's Fig. 4), patches under tension\n"
            "(adhesion) on a blue ramp of their tension -f with a second colour bar beside the force's,\n"
            "from 0 to the largest tension of all the files; height: heights with hill-shading;\n"
            "animate: one contact map per FORCE file, written as DIR/contact_NNNN.png, then a GIF or\n"
            "an MP4 (ffmpeg) of those same annotated frames (the GIF with one 256-colour palette built\n"
            "from all of them).\n"
            "Several files make one figure of panels (a), (b), ... with one shared norm and colour\n"
            "bar, e.g. the paper's Fig. 4: six force files --columns 3 --circle A.\n"
            "Output format from the extension: .png, .pdf or .svg.\n\n"
            "  --out FILE          the figure (or the animation for 'animate')\n"
            "  --raw               PNG of the data image only, without annotations\n"
            "  --colormap NAME     magma (default for forces: contact, animate, as scenes, indent --frames\n"
            "                      and render view3d), viridis (default for heights), cividis, inferno\n"
            "                      or grey\n"
            "  --vmin V, --vmax V  norm range (default: the two decades below the largest force, log; 0 ..\n"
            "                      largest force with --linear; min .. max height)\n"
            "  --clip P            cut P percent of the values (P in [0, 50); default 0) at each end of the\n"
            "                      default range: heights from the P to the 100 - P percentile, forces up to\n"
            "                      the 100 - P percentile of those > 0 (a scan's spikes and dropouts, a\n"
            "                      needle asperity's force); the values beyond take the ends' colours, the\n"
            "                      colour bar's triangles; --vmin/--vmax replace its ends\n"
            "  --log               logarithmic norm (vmin > 0; default vmin: vmax / 100): the default for\n"
            "                      forces (contact, animate)\n"
            "  --linear            linear norm of forces (contact, animate; heights are linear)\n"
            "  --scale N           pixels per patch (default 2)\n"
            "  --circle R          contact circle of radius R patches (contact, animate)\n"
            "  --circle-x X, --circle-y Y   its centre in patches (default: the grid's middle)\n"
            "  --contact FILE      outline the patches with value > 0 of FILE (height)\n"
            "  --label TEXT        panel label, e.g. '(a)'\n"
            "  --title TEXT        panel title\n"
            "  --titles LIST       comma-separated panel titles, one per file\n"
            "  --columns C         panels per row (default: all in one row)\n"
            "  --quantity TEXT     colour bar label (default: 'local force f / (E* δ²)' or 'height h / δ' (gap g,\n"
            "                      displacement u or plastic depth d when FILE.json says so), in\n"
            "                      the units the input's sidecar FILE.json states, e.g. 'local force f / N')\n"
            "  --dpi D             resolution (default 300)\n"
            "  --fps F             animation frames per second (default 5)\n"
            "  --frames DIR        directory for the frames of 'animate'\n"
            "  --backend B         auto (default), egl or osmesa; IM_RENDER_BACKEND sets the default\n");
}

typedef struct render_options {
    const char *mode, *out, *contact, *label, *title, *titles, *quantity, *frames;
    im_colormap_id map;
    double vmin, vmax, clip, circle, circle_x, circle_y, dpi, fps;
    int has_vmin, has_vmax, has_clip, has_circle_x, has_circle_y, logarithmic, scale, raw, columns;
    int map_given, linear;         /* --colormap, --linear: else forces take the frames' magma, log */
    im_colormap_range shared;      /* default norm: the union of the fields' values */
    im_colormap_range tensions;    /* the tension -f of all the fields: one tension norm, its bar where hi > 0 */
    char value_unit[40];           /* the first field's value unit (its .npy sidecar), "" if none */
    int extend_under, extend_over; /* some drawn values lie below / above the norm */
    im_render_backend backend;
    cli_provenance provenance; /* the command line, where it ran and the inputs: every figure's record */
} render_options;

enum {
    OPT_OUT = 256,
    OPT_RAW,
    OPT_MAP,
    OPT_VMIN,
    OPT_VMAX,
    OPT_LOG,
    OPT_SCALE,
    OPT_CIRCLE,
    OPT_CX,
    OPT_CY,
    OPT_CONTACT,
    OPT_LABEL,
    OPT_TITLE,
    OPT_QUANTITY,
    OPT_DPI,
    OPT_FPS,
    OPT_FRAMES,
    OPT_BACKEND,
    OPT_TITLES,
    OPT_COLUMNS,
    OPT_LINEAR,
    OPT_CLIP,
    OPT_HELP
};

static const struct option LONG_OPTIONS[] = {{"out", required_argument, 0, OPT_OUT},
                                             {"raw", no_argument, 0, OPT_RAW},
                                             {"colormap", required_argument, 0, OPT_MAP},
                                             {"vmin", required_argument, 0, OPT_VMIN},
                                             {"vmax", required_argument, 0, OPT_VMAX},
                                             {"log", no_argument, 0, OPT_LOG},
                                             {"linear", no_argument, 0, OPT_LINEAR},
                                             {"clip", required_argument, 0, OPT_CLIP},
                                             {"scale", required_argument, 0, OPT_SCALE},
                                             {"circle", required_argument, 0, OPT_CIRCLE},
                                             {"circle-x", required_argument, 0, OPT_CX},
                                             {"circle-y", required_argument, 0, OPT_CY},
                                             {"contact", required_argument, 0, OPT_CONTACT},
                                             {"label", required_argument, 0, OPT_LABEL},
                                             {"title", required_argument, 0, OPT_TITLE},
                                             {"quantity", required_argument, 0, OPT_QUANTITY},
                                             {"dpi", required_argument, 0, OPT_DPI},
                                             {"fps", required_argument, 0, OPT_FPS},
                                             {"frames", required_argument, 0, OPT_FRAMES},
                                             {"backend", required_argument, 0, OPT_BACKEND},
                                             {"titles", required_argument, 0, OPT_TITLES},
                                             {"columns", required_argument, 0, OPT_COLUMNS},
                                             {"help", no_argument, 0, OPT_HELP},
                                             {0, 0, 0, 0}};

static int named(int status, const char *option)
{
    if (status != IM_OK)
        fprintf(stderr, "indentmap: %s: %s\n", option, im_last_error());
    return status == IM_OK ? 0 : -1;
}

static int apply_option(int code, const char *arg, void *state)
{
    render_options *o = state;
    switch (code) {
    case OPT_OUT: return cli_parse_path("--out", arg, &o->out);
    case OPT_RAW: o->raw = 1; return 0;
    case OPT_MAP: o->map_given = 1; return named(im_colormap_from_name(arg, &o->map), "--colormap");
    case OPT_VMIN: o->has_vmin = 1; return cli_parse_double("--vmin", arg, -1e300, 1e300, &o->vmin);
    case OPT_VMAX: o->has_vmax = 1; return cli_parse_double("--vmax", arg, -1e300, 1e300, &o->vmax);
    case OPT_LOG: o->logarithmic = 1; return 0;
    case OPT_LINEAR: o->linear = 1; return 0;
    case OPT_CLIP: o->has_clip = 1; return cli_parse_double("--clip", arg, 0.0, 50.0, &o->clip);
    case OPT_SCALE: return cli_parse_int("--scale", arg, 1, 64, &o->scale);
    case OPT_CIRCLE: return cli_parse_double("--circle", arg, 0.0, 1e9, &o->circle);
    case OPT_CX: o->has_circle_x = 1; return cli_parse_double("--circle-x", arg, -1e9, 1e9, &o->circle_x);
    case OPT_CY: o->has_circle_y = 1; return cli_parse_double("--circle-y", arg, -1e9, 1e9, &o->circle_y);
    case OPT_CONTACT: o->contact = arg; return 0;
    case OPT_LABEL: o->label = arg; return 0;
    case OPT_TITLE: o->title = arg; return 0;
    case OPT_TITLES: o->titles = arg; return 0;
    case OPT_COLUMNS: return cli_parse_int("--columns", arg, 1, 64, &o->columns);
    case OPT_QUANTITY: o->quantity = arg; return 0;
    case OPT_DPI: return cli_parse_double("--dpi", arg, 1.0, 2400.0, &o->dpi);
    case OPT_FPS: return cli_parse_double("--fps", arg, 0.01, 100.0, &o->fps);
    case OPT_FRAMES: return cli_parse_path("--frames", arg, &o->frames);
    case OPT_BACKEND: return named(im_render_backend_from_name(arg, &o->backend), "--backend");
    default: return -1;
    }
}

/* The norm: the fields' shared range, overridden by --vmin/--vmax/--log/--colormap. */
static void apply_norm(const render_options *o, im_colormap *c)
{
    *c = im_colormap_range_norm(&o->shared, o->map, o->has_vmin ? o->vmin : NAN, o->has_vmax ? o->vmax : NAN,
                                o->logarithmic);
}

/* The contact map of the force read from input (named in an error: an infinite force, say). */
static int render_contact(im_render_context *context, const im_field *force, const char *input, render_options *o,
                          im_image *image, im_colormap *norm)
{
    im_contact_style style = im_contact_style_default(force);
    apply_norm(o, &style.colormap);
    frame_extends(force, &style.colormap, 1, &o->extend_under, &o->extend_over);
    style.tension = im_colormap_range_norm(&o->tensions, IM_COLORMAP_TENSION, NAN, NAN, 0);
    style.pixels_per_patch = o->scale;
    style.circle_radius = o->circle;
    if (o->has_circle_x)
        style.circle_x = o->circle_x;
    if (o->has_circle_y)
        style.circle_y = o->circle_y;
    *norm = style.colormap;
    const int status = im_render_contact_map(context, force, &style, image);
    return status == IM_OK ? IM_OK : im_fail_context(status, "%s", input);
}

static int render_height(im_render_context *context, const im_field *height, render_options *o, im_image *image,
                         im_colormap *norm)
{
    im_field *contact = NULL;
    int status = o->contact ? im_surface_read(o->contact, &contact) : IM_OK;
    if (status != IM_OK)
        return status;
    im_height_style style = im_height_style_default(height);
    apply_norm(o, &style.colormap);
    frame_extends(height, &style.colormap, 0, &o->extend_under, &o->extend_over);
    style.pixels_per_patch = o->scale;
    style.contact = contact;
    *norm = style.colormap;
    status = im_render_height_map(context, height, &style, image);
    im_field_free(contact);
    return status;
}

/* The i-th comma-separated item of list into buffer; "" when missing. */
/* The number of comma-separated items in list (0 for NULL). */
static int list_length(const char *list)
{
    int n = list ? 1 : 0;
    for (; list && (list = strchr(list, ',')) != NULL; ++list)
        ++n;
    return n;
}

static void list_item(const char *list, int i, char *buffer, size_t size)
{
    buffer[0] = '\0';
    for (; list && i > 0; --i)
        list = strchr(list, ',') ? strchr(list, ',') + 1 : NULL;
    if (list)
        snprintf(buffer, size, "%.*s", (int)strcspn(list, ","), list);
}

/* The quantity of a height-mode field for its colour bar (figure.h: im_figure_colorbar_label): what its
 * sidecar FILE.json says it is (indent --fields writes gaps, displacements and plastic depths beside the
 * forces), "height" for a surface or a file without one. */
static const char *height_quantity(const char *path)
{
    static const char *const KNOWN[][2] = {{"gap", "gap"},
                                           {"surface displacement", "displacement"},
                                           {"plastic depth", "plastic"}};
    char sidecar[4096];
    snprintf(sidecar, sizeof sidecar, "%s.json", path);
    json_t *record = json_file_load(sidecar, 0, NULL);
    const char *stated = json_string_value(json_object_get(record, "quantity")), *quantity = "height";
    for (size_t i = 0; stated && i < sizeof KNOWN / sizeof *KNOWN; ++i)
        if (strncmp(stated, KNOWN[i][0], strlen(KNOWN[i][0])) == 0)
            quantity = KNOWN[i][1];
    json_decref(record);
    return quantity;
}

/* The figure (or, with --raw, the data image of a single panel) with the texts; when frame is not NULL, the
 * figure's pixels too (im_figure_write_frame). */
static int write_figure(const render_options *o, const im_image *images, int count, const im_colormap *norm,
                        const char *quantity, const char *tension_name, const run_figure_texts *texts,
                        im_image *frame)
{
    if (o->raw) {
        im_png_options options = {texts->texts, texts->count, o->dpi / 0.0254, IM_FIGURE_PNG_COMPRESSION};
        return im_png_write(o->out, images[0].rgba, images[0].width, images[0].height, 4, (size_t)images[0].width * 4,
                            &options);
    }
    int columns = o->columns > 0 ? o->columns : count;
    if (count % columns != 0)
        return im_fail(IM_EINVAL, "--columns %d: %d panels do not fill whole rows", columns, count);
    im_figure_panel panels[64];
    char labels[64][8], titles[64][128];
    for (int i = 0; i < count; ++i) {
        snprintf(labels[i], sizeof labels[i], "(%c)", 'a' + i);
        list_item(o->titles, i, titles[i], sizeof titles[i]);
        panels[i] = (im_figure_panel){&images[i], count > 1 ? labels[i] : o->label,
                                      count > 1 ? (titles[i][0] ? titles[i] : NULL) : o->title};
    }
    im_figure figure = im_figure_default();
    figure.rows = count / columns;
    figure.columns = columns;
    figure.panels = panels;
    figure.colormap = norm;
    figure.colorbar_label = quantity;
    figure.extend_under = o->extend_under;
    figure.extend_over = o->extend_over;
    const im_colormap tension = im_colormap_range_norm(&o->tensions, IM_COLORMAP_TENSION, NAN, NAN, 0);
    if (strcmp(o->mode, "height") != 0 && o->tensions.hi > 0.0) {
        figure.tension_colormap = &tension;
        figure.tension_label = tension_name;
    }
    figure.dpi = o->dpi;
    figure.texts = texts->texts;
    figure.text_count = texts->count;
    return frame ? im_figure_write_frame(&figure, o->out, frame) : im_figure_write(&figure, o->out);
}

/* The figure (write_figure) with its texts: the record of the command (figure_provenance.h) and the
 * drawing's settings. */
static int write_output(const render_options *o, char **inputs, const im_image *images, int count,
                        const im_colormap *norm, im_image *frame)
{
    char norm_text[128], scale_text[16];
    run_figure_norm_text(norm, norm_text, sizeof norm_text);
    snprintf(scale_text, sizeof scale_text, "%d", o->scale);
    int contact = strcmp(o->mode, "height") != 0;
    char label[96], tension_name[96];
    int status = im_figure_colorbar_label("tension", o->value_unit, tension_name, sizeof tension_name);
    if (status == IM_OK)
        status = im_figure_colorbar_label(contact ? "force" : height_quantity(inputs[0]),
                                          contact ? o->value_unit : images[0].unit, label, sizeof label);
    if (status != IM_OK)
        return status;
    const char *quantity = o->quantity ? o->quantity : label;
    const im_png_text given[] = {{"Quantity", quantity},
                                 {"Colormap", im_colormap_name(norm->map)},
                                 {"Norm", norm_text},
                                 {"Pixels per patch", scale_text}};
    run_figure_texts texts;
    status = cli_provenance_texts(&o->provenance, given, 4, &texts);
    if (status == IM_OK)
        status = write_figure(o, images, count, norm, quantity, tension_name, &texts, frame);
    run_figure_texts_free(&texts);
    return status;
}

/* Where a few outliers set the default linear range (colormap.h: im_colormap_outlier_note), one notice on
 * stderr naming the file that holds the farthest and suggesting --clip; the picture is drawn as without it. */
static int note_outliers(char **inputs, im_field **fields, int count)
{
    char note[512];
    int farthest;
    int status = im_colormap_outlier_note(fields, count, note, sizeof note, &farthest);
    if (status == IM_OK && note[0])
        fprintf(stderr, "indentmap: %s: %s; --clip %g cuts %g%% of the values at each end (or set --vmin/--vmax)\n",
                inputs[farthest], note, IM_COLORMAP_OUTLIER_PERCENT, IM_COLORMAP_OUTLIER_PERCENT);
    return status;
}

/* The default norm of several fields: the union of their finite values (colormap.h: forces 0 .. the
 * largest; heights min .. max), its defaults only when that union is empty or a single value, with --clip
 * percent cut at each end. Taking the union of each field's default range instead let one all-zero force
 * field widen the norm of every frame to its default [0, 1]. */
static int set_shared_range(render_options *o, char **inputs, im_field **fields, int count)
{
    int height = strcmp(o->mode, "height") == 0;
    const im_colormap_values values = height ? IM_COLORMAP_HEIGHTS : IM_COLORMAP_FORCES;
    o->shared = frame_range(fields, count, values);
    o->tensions = frame_range(fields, height ? 0 : count, IM_COLORMAP_TENSIONS); /* heights: none */
    if (o->clip > 0.0)
        return im_colormap_range_clipped(values, fields, count, o->clip, &o->shared);
    return height && !o->has_clip && !o->has_vmin && !o->has_vmax ? note_outliers(inputs, fields, count) : IM_OK;
}

/* Reads the fields and sets the default norm. */
static int read_fields(render_options *o, char **inputs, int count, im_field **fields)
{
    const im_surface_read_options fields_to_draw = {.field_values = 1}; /* NaN, +Inf gaps: drawn as such */
    for (int i = 0; i < count; ++i) {
        int status = im_surface_read_with(inputs[i], &fields_to_draw, &fields[i], NULL);
        if (status != IM_OK)
            return status;
        if (i == 0)
            memcpy(o->value_unit, fields[i]->value_unit, sizeof o->value_unit);
    }
    return set_shared_range(o, inputs, fields, count);
}

/* Frame i: its contact map into DIR/contact_NNNN.png, as a figure or (--raw) the map alone; for a GIF,
 * the frame's pixels as written stay in *frame. */
static int write_animation_frame(im_render_context *context, im_field *field, char **input, int i, render_options *o,
                                 int gif, im_image *frame)
{
    im_colormap norm;
    im_image image = {0};
    char path[4096];
    int status = render_contact(context, field, input[0], o, &image, &norm);
    if (status == IM_OK)
        status = im_frame_path(path, sizeof path, o->frames, "contact", i);
    if (status == IM_OK) {
        render_options frame_options = *o;
        frame_options.out = path;
        status = write_output(&frame_options, input, &image, 1, &norm, gif && !o->raw ? frame : NULL);
    }
    if (status == IM_OK && gif && o->raw)
        *frame = image; /* the PNG frame is the map itself */
    else
        im_image_release(&image);
    return status;
}

/* The fields of an animation share one grid: frames of different sizes cannot make one animation. */
static int check_one_grid(char **inputs, im_field **fields, int count)
{
    for (int i = 1; i < count; ++i)
        if (fields[i]->nx != fields[0]->nx || fields[i]->ny != fields[0]->ny)
            return im_fail(IM_EINVAL,
                           "render animate: %s (frame %d) is %d x %d but %s (frame 0) is %d x %d: the frames of an "
                           "animation are fields of one grid",
                           inputs[i], i, fields[i]->nx, fields[i]->ny, inputs[0], fields[0]->nx, fields[0]->ny);
    return IM_OK;
}

/* One contact map per force file, all with one norm, into DIR/contact_NNNN.png, then the GIF or MP4 of
 * those frames. */
static int animate(im_render_context *context, char **inputs, int count, render_options *o)
{
    int status = im_make_directories(o->frames);
    im_field **fields = calloc((size_t)count, sizeof *fields);
    im_image *frames = calloc((size_t)count, sizeof *frames);
    if (!fields || !frames) {
        free(fields);
        free(frames);
        return im_fail(IM_ENOMEM, "animation: out of memory");
    }
    if (status == IM_OK)
        status = read_fields(o, inputs, count, fields);
    if (status == IM_OK)
        status = check_one_grid(inputs, fields, count);
    const char *dot = o->out ? strrchr(o->out, '.') : NULL;
    int gif = dot && strcmp(dot, ".gif") == 0;
    for (int i = 0; status == IM_OK && i < count; ++i)
        status = write_animation_frame(context, fields[i], inputs + i, i, o, gif, &frames[i]);
    if (status == IM_OK && gif)
        status = im_animation_gif(frames, count, 1.0 / o->fps, o->out);
    else if (status == IM_OK && dot && strcmp(dot, ".mp4") == 0)
        status = im_animation_mp4(o->frames, "contact", count, o->fps, o->out);
    else if (status == IM_OK && o->out)
        status = im_fail(IM_EINVAL, "%s: expected an animation ending in .gif or .mp4", o->out);
    for (int i = 0; i < count; ++i) {
        im_image_release(&frames[i]);
        im_field_free(fields[i]);
    }
    free(frames);
    free(fields);
    return status;
}

/* One panel per input with the shared norm, then the figure. */
static int draw_panels(im_render_context *context, char **inputs, int count, render_options *o)
{
    im_field **fields = calloc((size_t)count, sizeof *fields);
    im_image *images = calloc((size_t)count, sizeof *images);
    im_colormap norm;
    int status = fields && images ? read_fields(o, inputs, count, fields)
                                  : im_fail(IM_ENOMEM, "render: out of memory");
    for (int i = 0; status == IM_OK && i < count; ++i)
        status = strcmp(o->mode, "contact") == 0 ? render_contact(context, fields[i], inputs[i], o, &images[i], &norm)
                                                 : render_height(context, fields[i], o, &images[i], &norm);
    if (status == IM_OK)
        status = write_output(o, inputs, images, count, &norm, NULL);
    for (int i = 0; fields && images && i < count; ++i) {
        im_image_release(&images[i]);
        im_field_free(fields[i]);
    }
    free(images);
    free(fields);
    return status;
}

static int check_usage(const render_options *o, int inputs)
{
    int animation = strcmp(o->mode, "animate") == 0;
    if (strcmp(o->mode, "contact") != 0 && strcmp(o->mode, "height") != 0 && !animation)
        fprintf(stderr, "indentmap: render: '%s': expected contact, height or animate\n", o->mode);
    else if (inputs < 1 || inputs > 64)
        fprintf(stderr, "indentmap: render %s: expected 1 to 64 input files\n", o->mode);
    else if (o->raw && inputs > 1 && !animation)
        fprintf(stderr, "indentmap: --raw draws one file\n");
    else if (list_length(o->titles) > inputs)
        fprintf(stderr, "indentmap: --titles '%s': %d titles for %d file%s: expected at most one per file\n",
                o->titles, list_length(o->titles), inputs, inputs == 1 ? "" : "s");
    else if (animation ? !o->frames : !o->out)
        fprintf(stderr, "indentmap: render %s: %s is required\n", o->mode, animation ? "--frames" : "--out");
    else if (o->raw && !animation && strstr(o->out, ".png") == NULL)
        fprintf(stderr, "indentmap: --raw writes PNG: expected --out FILE.png\n");
    else if (!(o->clip < 50.0))
        fprintf(stderr, "indentmap: --clip %g: expected a percentage in [0, 50) cut at each end\n", o->clip);
    else if (o->logarithmic && o->linear)
        fprintf(stderr, "indentmap: --log and --linear: expected one norm\n");
    else if (o->linear && strcmp(o->mode, "height") == 0)
        fprintf(stderr, "indentmap: --linear is for forces (contact, animate): heights are drawn linear\n");
    else if (o->has_vmin && !(o->vmin > 0) && !o->linear && (o->logarithmic || strcmp(o->mode, "height") != 0))
        fprintf(stderr, "indentmap: --vmin %g: a logarithmic norm needs --vmin > 0 (or %s)\n", o->vmin,
                strcmp(o->mode, "height") == 0 ? "no --log: heights are linear by default" : "--linear");
    else
        return 0;
    return -1;
}

/* Registers the inputs (the fields and --contact) and refuses, before any work, an output that is
 * one of them: --out, or a frame DIR/contact_NNNN.png of --frames. */
static int check_outputs_apart(const render_options *o, char **inputs, int count)
{
    if (cli_protect_inputs((const char *const *)inputs, count) != 0 || cli_protect_inputs(&o->contact, 1) != 0 ||
        cli_check_output_file("--out", o->out) != 0)
        return -1;
    for (int i = 0; o->frames && strcmp(o->mode, "animate") == 0 && i < count; ++i) {
        char path[4096];
        if (im_frame_path(path, sizeof path, o->frames, "contact", i) != IM_OK) {
            cli_report(IM_EINVAL);
            return -1;
        }
        if (cli_check_output_file("--frames", path) != 0)
            return -1;
    }
    return 0;
}

/* The files the figures are drawn from, with their SHA-256, for the figures' record. */
static int record_inputs(render_options *o, char **inputs, int count)
{
    int status = cli_provenance_add_input(&o->provenance, "--contact", o->contact);
    for (int i = 0; status == IM_OK && i < count; ++i)
        status = cli_provenance_add_input(&o->provenance, "input", inputs[i]);
    return status;
}

static int run(render_options *o, char **inputs, int count)
{
    im_render_context *context = NULL;
    int status = record_inputs(o, inputs, count);
    if (status == IM_OK)
        status = cli_render_open(o->backend, &context);
    if (status != IM_OK)
        return cli_report(status);
    if (strcmp(o->mode, "animate") == 0) {
        status = animate(context, inputs, count, o);
    } else {
        status = draw_panels(context, inputs, count, o);
    }
    im_render_close(context);
    if (status == IM_EUNSUPPORTED && strstr(im_last_error(), "ffmpeg not found")) {
        fprintf(stderr, "indentmap: %s\n", im_last_error());
        return CLI_EXIT_FAILURE;
    }
    return status == IM_OK ? CLI_EXIT_OK : cli_report(status);
}

/* Forces (contact, animate) default to the colour map and norm of every other front end's force maps:
 * magma on a log norm over two decades (scenes, indent --frames, render view3d). */
static void apply_force_defaults(render_options *o)
{
    if (strcmp(o->mode, "height") == 0)
        return;
    if (!o->map_given)
        o->map = IM_COLORMAP_MAGMA;
    if (!o->linear)
        o->logarithmic = 1;
}

static int render(render_options *o, int argc, char **argv)
{
    int parsed = cli_parse_options(argc, argv, LONG_OPTIONS, OPT_HELP, usage, apply_option, o);
    if (parsed != 0)
        return parsed > 0 ? CLI_EXIT_OK : CLI_EXIT_USAGE;
    if (optind >= argc) {
        usage(stderr);
        return CLI_EXIT_USAGE;
    }
    o->mode = argv[optind];
    if (check_usage(o, argc - optind - 1) != 0 || check_outputs_apart(o, argv + optind + 1, argc - optind - 1) != 0)
        return CLI_EXIT_USAGE;
    if (cli_interrupt_install_cleanup() != 0)
        return cli_report(im_fail(IM_EUNSUPPORTED, "cannot install the SIGINT/SIGTERM handlers"));
    apply_force_defaults(o);
    return run(o, argv + optind + 1, argc - optind - 1);
}

int cli_render(int argc, char **argv)
{
    if (argc > 1 && strcmp(argv[1], "view3d") == 0)
        return cli_render_view3d(argc - 1, argv + 1);
    render_options o = {.map = IM_COLORMAP_VIRIDIS, .scale = 2, .dpi = 300.0, .fps = 5.0, .backend = IM_RENDER_AUTO};
    int status = cli_provenance_start("indentmap", argc, argv, &o.provenance);
    int code = status == IM_OK ? render(&o, argc, argv) : cli_report(status);
    cli_provenance_free(&o.provenance);
    return code;
}
