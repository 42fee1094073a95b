/* Frames of one family's indentation history, and animations made from them. */
#include "front/front.h"
#include "scene/contents.h"
#include "indentmap/figure.h"
#include "indentmap/io.h"
#include "indentmap/status.h"
#include "paper/figures.h"
#include "scene/frames.h"
#include "scene/frames3d.h"
#include "scene/labels.h"
#include "scene/manifest.h"
#include "scene/outputs.h"
#include "scene/provenance.h"
#include "scene/progress.h"
#include "scene/punch.h"
#include "scene/surfaces.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct framed_history {
    int count;
    im_field *surface;
    im_field **force, **deformed; /* per step: force per patch, heights h - u */
    double *load_star;
} framed_history;

static void history_free(framed_history *h)
{
    for (int i = 0; i < h->count; ++i) {
        if (h->force)
            im_field_free(h->force[i]);
        if (h->deformed)
            im_field_free(h->deformed[i]);
    }
    free(h->force);
    free(h->deformed);
    free(h->load_star);
    im_field_free(h->surface);
}

int scene_framed_family(const im_scene *scene)
{
    int chosen = 0;
    for (int i = 0; i < scene->family_count; ++i) {
        if (scene->frames_slope >= 0 ? fabs(scene->slopes[i] - scene->frames_slope) < 1e-12
                                     : scene->slopes[i] > scene->slopes[chosen])
            chosen = i;
    }
    return chosen;
}

/* Keeps the step's force and deformed heights h - u (u is positive into the half-space), with u on
 * the whole grid (the solver's is 0 outside its window, which drew a step at the window's edge). */
static int keep_step(im_indentation *run, framed_history *h, int index, const im_step_result *step)
{
    im_field *displacement = NULL;
    int status = im_indentation_fields_full(run, &h->force[index], NULL, &displacement);
    if (status == IM_OK)
        status = im_field_clone(h->surface, &h->deformed[index]);
    if (status == IM_OK)
        for (size_t i = 0; i < im_field_count(h->surface); ++i)
            h->deformed[index]->data[i] -= displacement->data[i];
    im_field_free(displacement);
    h->load_star[index] = step->load_star;
    return status;
}

/* Load control, frame_count loads evenly spaced up to the load at load_star. */
static int solve_history(const im_scene *scene, const im_scene_run_options *options, framed_history *h)
{
    int family = scene_framed_family(scene);
    int status = scene_surface(scene, family, scene->seeds[0], &h->surface);
    h->count = scene->frame_count;
    h->force = calloc((size_t)h->count, sizeof *h->force);
    h->deformed = calloc((size_t)h->count, sizeof *h->deformed);
    h->load_star = calloc((size_t)h->count, sizeof *h->load_star);
    if (status == IM_OK && (!h->force || !h->deformed || !h->load_star))
        status = im_fail(IM_ENOMEM, "frames: allocation failed");
    if (status != IM_OK)
        return status;
    double n = scene_load_for_load_star(scene, h->surface->delta);
    im_indenter punch = scene_punch(scene);
    im_solver_options solver = scene_solver_options(scene);
    im_indentation *run = NULL;
    status = im_indentation_create(h->surface, &punch, IM_CONTROL_LOAD, n, &solver, &run);
    scene_progress(options, "frames: %d step%s of family %d (h'rms = %g)", h->count, h->count == 1 ? "" : "s", family,
                   scene->slopes[family]);
    for (int i = 0; i < h->count && status == IM_OK; ++i) {
        if (scene_stop_signal(options)) {
            status = scene_interrupted(options, "during the frames' history (no frame is written before it ends)");
            break;
        }
        im_step_result step;
        /* the last step exactly at n: n * count / count may round above the largest load prepared */
        status = im_indentation_step(run, i + 1 == h->count ? n : n * (i + 1) / h->count, &step);
        if (status == IM_OK)
            status = keep_step(run, h, i, &step);
    }
    im_indentation_free(run);
    return status;
}

void scene_frame_load_title(const double *load_stars, int count, int index, char *text, size_t size)
{
    double largest = load_stars[0];
    for (int i = 1; i < count; ++i)
        largest = fmax(largest, load_stars[i]);
    char digits[32], widest[32];
    int pad = snprintf(widest, sizeof widest, "%.0f", largest) -
              snprintf(digits, sizeof digits, "%.0f", load_stars[index]);
    size_t used = (size_t)snprintf(text, size, "N* = ");
    for (int i = 0; i < pad && used < size; ++i)
        used += (size_t)snprintf(text + used, size - used, "\u2007");
    if (used < size)
        snprintf(text + used, size - used, "%s", digits);
}

/* The norms every step's frames share; has_tension: some step has patches under tension, and every
 * contact frame draws the tension's bar. */
typedef struct frame_norms {
    im_colormap force, tension, height;
    int has_tension;
    int force_under, force_over, height_under, height_over; /* some step's values lie beyond (frame_extends) */
} frame_norms;

/* One frame's figure, written as PNG by whichever thread takes it, with the status and message of that
 * write (another thread's last error is its own) and the frame's pixels, which the GIF reuses. */
typedef struct frame_figure {
    im_image image, frame;
    const im_colormap *norm, *tension; /* tension: the tension's bar, NULL for none */
    int extend_under, extend_over;     /* the colour bar's triangles */
    const char *label, *prefix;
    int index, keep; /* keep: the frame's pixels are wanted (the contact GIF's) */
    char title[64];
    int status;
    char error[256];
} frame_figure;

static int write_frame(const im_scene *scene, frame_figure *f)
{
    char folder[IM_SCENE_PATH], path[IM_SCENE_PATH];
    int status = scene_output_path(scene, "frames", folder, sizeof folder);
    if (status == IM_OK)
        status = im_frame_path(path, sizeof path, folder, f->prefix, f->index);
    if (status != IM_OK)
        return status;
    scene_outputs_note(scene, path);
    char norm_text[128], scale_text[16];
    run_figure_norm_text(f->norm, norm_text, sizeof norm_text);
    snprintf(scale_text, sizeof scale_text, "%d", scene->frame_scale);
    const im_png_text own[] = {{"Quantity", f->label}, /* render's four texts */
                               {"Colormap", im_colormap_name(f->norm->map)},
                               {"Norm", norm_text},
                               {"Pixels per patch", scale_text}};
    run_figure_texts texts;
    status = scene_figure_texts(scene, own, 4, &texts);
    const frame_words words = {f->title,    f->norm,     f->label,        f->tension,    "tensile force −f / (E* δ²)",
                               texts.texts, texts.count, f->extend_under, f->extend_over};
    if (status == IM_OK)
        status = frame_figure_write(&f->image, &words, path, f->keep ? &f->frame : NULL);
    run_figure_texts_free(&texts);
    return status;
}

static void write_frame_figure(const im_scene *scene, frame_figure *f)
{
    f->status = write_frame(scene, f);
    if (f->status != IM_OK)
        snprintf(f->error, sizeof f->error, "%s", im_last_error());
}

static int render_contact_frame(im_render_context *context, const framed_history *h, int i, const frame_norms *norms,
                                int pixels_per_patch, im_image *image)
{
    const frame_contact contact = {
        h->force[i],           &norms->force,        &norms->tension, pixels_per_patch, sqrt(h->load_star[i] / M_PI),
        0.5 * h->force[i]->nx, 0.5 * h->force[i]->ny};
    return frame_contact_render(context, &contact, image);
}

/* Step i's contact and height images (figures[0], figures[1]). */
static int render_step(im_render_context *context, const im_scene *scene, const framed_history *h, int i,
                       const frame_norms *norms, frame_figure *figures)
{
    figures[0] = (frame_figure){.norm = &norms->force,
                                .tension = norms->has_tension ? &norms->tension : NULL,
                                .extend_under = norms->force_under,
                                .extend_over = norms->force_over,
                                .label = "local force f / (E* δ²)",
                                .prefix = "contact",
                                .index = i,
                                .keep = (scene->animation & IM_ANIMATION_GIF) != 0};
    figures[1] = (frame_figure){.norm = &norms->height,
                                .extend_under = norms->height_under,
                                .extend_over = norms->height_over,
                                .label = "deformed height (h − u) / δ",
                                .prefix = "height",
                                .index = i};
    scene_frame_load_title(h->load_star, h->count, i, figures[0].title, sizeof figures[0].title);
    memcpy(figures[1].title, figures[0].title, sizeof figures[1].title);
    int status = render_contact_frame(context, h, i, norms, scene->frame_scale, &figures[0].image);
    im_height_style style = im_height_style_default(h->deformed[i]);
    style.colormap = norms->height;
    style.pixels_per_patch = scene->frame_scale;
    style.contact = h->force[i];
    if (status == IM_OK)
        status = im_render_height_map(context, h->deformed[i], &style, &figures[1].image);
    return status;
}

/* The norms every step's frames share: the range of all their values, [output] frames_clip percent cut at
 * each end (forces: the top), and whether some step's values lie beyond them. */
static int make_frame_norms(const im_scene *scene, const framed_history *h, frame_norms *norms)
{
    const double clip = scene->frames_clip;
    im_colormap_range forces = frame_range(h->force, h->count, IM_COLORMAP_FORCES),
                      heights = frame_range(h->deformed, h->count, IM_COLORMAP_HEIGHTS);
    const im_colormap_range tensions = frame_range(h->force, h->count, IM_COLORMAP_TENSIONS);
    int status = clip > 0.0 ? im_colormap_range_clipped(IM_COLORMAP_FORCES, h->force, h->count, clip, &forces)
                            : IM_OK;
    if (status == IM_OK && clip > 0.0)
        status = im_colormap_range_clipped(IM_COLORMAP_HEIGHTS, h->deformed, h->count, clip, &heights);
    norms->force = scene_force_norm(scene, &forces);
    norms->tension = im_colormap_range_norm(&tensions, IM_COLORMAP_TENSION, NAN, NAN, 0);
    norms->has_tension = tensions.hi > 0.0;
    norms->height = im_colormap_range_norm(&heights, IM_COLORMAP_VIRIDIS, NAN, NAN, 0);
    norms->force_under = norms->force_over = norms->height_under = norms->height_over = 0;
    for (int i = 0; i < h->count; ++i) {
        frame_extends(h->force[i], &norms->force, 1, &norms->force_under, &norms->force_over);
        frame_extends(h->deformed[i], &norms->height, 0, &norms->height_under, &norms->height_over);
    }
    return status;
}

/* Renders every step on this thread, which holds the GL context, then writes the figures side by side
 * (cairo layout and PNG encoding: a sixth of fig4's CPU time at one thread); the contact frames' pixels
 * go to gif_frames. */
static int write_frames(const im_scene *scene, im_render_context *context, const framed_history *h,
                        im_image *gif_frames, frame_norms *norms)
{
    int status = make_frame_norms(scene, h, norms);
    int count = 2 * h->count;
    frame_figure *figures = status == IM_OK ? calloc((size_t)count, sizeof *figures) : NULL;
    status = status != IM_OK || figures ? status : im_fail(IM_ENOMEM, "frames: allocation failed");
    for (int i = 0; i < h->count && status == IM_OK; ++i)
        status = render_step(context, scene, h, i, norms, &figures[2 * i]);
    if (status == IM_OK) {
#pragma omp parallel for schedule(dynamic, 1)
        for (int k = 0; k < count; ++k)
            write_frame_figure(scene, &figures[k]);
        for (int k = 0; k < count && status == IM_OK; ++k)
            if (figures[k].status != IM_OK)
                status = im_fail(figures[k].status, "%s", figures[k].error);
    }
    for (int k = 0; figures && k < count; ++k) {
        im_image_release(&figures[k].image);
        if (figures[k].keep && status == IM_OK)
            gif_frames[k / 2] = figures[k].frame;
        else
            im_image_release(&figures[k].frame);
    }
    free(figures);
    return status;
}

static int write_animations(const im_scene *scene, const im_scene_run_options *options, const im_image *frames,
                            int count)
{
    char path[IM_SCENE_PATH];
    int status = IM_OK;
    if (scene->animation & IM_ANIMATION_GIF) {
        status = scene_output_path(scene, "contact.gif", path, sizeof path);
        if (status == IM_OK)
            status = im_animation_gif(frames, count, 1.0 / scene->frame_rate, path);
    }
    if (status != IM_OK || !(scene->animation & IM_ANIMATION_MP4))
        return status;
    if (!im_ffmpeg_available()) {
        scene_progress(options, "ffmpeg is not installed: no contact.mp4 (the frames are in frames/)");
        return IM_OK;
    }
    char folder[IM_SCENE_PATH];
    status = scene_output_path(scene, "frames", folder, sizeof folder);
    if (status == IM_OK)
        status = scene_output_path(scene, "contact.mp4", path, sizeof path);
    return status == IM_OK ? im_animation_mp4(folder, "contact", count, scene->frame_rate, path) : status;
}

int scene_run_frames(const im_scene *scene, const im_scene_run_options *options, im_render_context *context,
                     im_field **last_force)
{
    *last_force = NULL;
    char folder[IM_SCENE_PATH];
    int status = scene_output_path(scene, "frames", folder, sizeof folder);
    if (status == IM_OK)
        status = im_make_directories(folder);
    framed_history history = {0};
    if (status == IM_OK)
        status = solve_history(scene, options, &history);
    im_image *gif_frames = calloc((size_t)scene->frame_count, sizeof *gif_frames);
    if (status == IM_OK && !gif_frames)
        status = im_fail(IM_ENOMEM, "frames: allocation failed");
    frame_norms norms;
    if (status == IM_OK)
        status = write_frames(scene, context, &history, gif_frames, &norms);
    if (status == IM_OK)
        status = write_animations(scene, options, gif_frames, history.count);
    if (status == IM_OK && scene->frames3d) {
        scene_frames3d_input in = {.count = history.count,
                                   .deformed = history.deformed,
                                   .force = history.force,
                                   .load_star = history.load_star,
                                   .norm = &norms.force,
                                   .extend_under = norms.force_under,
                                   .extend_over = norms.force_over,
                                   .tension = norms.has_tension ? &norms.tension : NULL};
        status = scene_write_frames3d(scene, options, context, &in);
    }
    if (status == IM_OK)
        status = im_field_clone(history.force[history.count - 1], last_force);
    for (int i = 0; gif_frames && i < scene->frame_count; ++i)
        im_image_release(&gif_frames[i]);
    free(gif_frames);
    history_free(&history);
    return status;
}
