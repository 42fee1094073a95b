/* 3-D frames of the framed history (frames3d = yes): one view per step with one colour norm, one
 * exaggeration and one camera, and their animations. */
#include "indentmap/figure.h"
#include "scene/contents.h"
#include "indentmap/io.h"
#include "indentmap/render.h"
#include "indentmap/status.h"
#include "front/front.h"
#include "paper/figures.h"
#include "scene/frames.h"
#include "scene/frames3d.h"
#include "scene/manifest.h"
#include "scene/outputs.h"
#include "scene/provenance.h"
#include "scene/progress.h"
#include "scene/punch.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The largest 1, 2 or 5 times a power of ten that is at most x (x >= 1), else 1. */
static double nice_at_most(double x)
{
    if (!(x > 1.0))
        return 1.0;
    double magnitude = pow(10.0, floor(log10(x))), nice = magnitude;
    if (5.0 * magnitude <= x)
        nice = 5.0 * magnitude;
    else if (2.0 * magnitude <= x)
        nice = 2.0 * magnitude;
    return nice;
}

static void height_range(const im_field *h, double *lo, double *hi)
{
    for (size_t i = 0; i < im_field_count(h); ++i) {
        *lo = fmin(*lo, h->data[i] / h->delta);
        *hi = fmax(*hi, h->data[i] / h->delta);
    }
}

/* The camera's distance: the nearest at which every step is seen whole (the block's front edge
 * included: the deepest step's block reaches lowest, the first step's punch highest). */
static int fit_camera(im_field *const *deformed, int count, const im_indenter *punch, im_view3d_style *s)
{
    double farthest = 0.0;
    for (int i = 0; i < count; ++i) {
        double distance;
        int status = im_view3d_fit_distance(deformed[i], punch, s, &distance);
        if (status != IM_OK)
            return status;
        farthest = fmax(farthest, distance);
    }
    s->camera.distance = farthest;
    return IM_OK;
}

/* The frames' view before the fields shape it: their size, the punch cut away. */
static im_view3d_style view_of(const im_scene *scene)
{
    im_view3d_style s = im_view3d_style_default(NULL);
    s.width = scene->frame3d_width;
    s.height = scene->frame3d_height;
    s.punch_mode = IM_VIEW3D_PUNCH_CUTAWAY; /* the contact under the punch stays in sight */
    return s;
}

/* One style for every frame (the punch cut away, the camera as near as shows every step whole):
 * the relief of the last (deepest) step exaggerated to about an eighth
 * of the grid's longer side (a 1-2-5 factor, never below true scale), the camera's target fixed at
 * the middle of all frames' heights. */
static int frames_style(const im_scene *scene, const scene_frames3d_input *in, const im_indenter *punch,
                        im_view3d_style *style)
{
    im_field *const *deformed = in->deformed;
    const int count = in->count;
    im_view3d_style s = view_of(scene);
    s.colormap = *in->norm;
    if (in->tension)
        s.tension = *in->tension;
    double lo = INFINITY, hi = -INFINITY;
    height_range(deformed[count - 1], &lo, &hi);
    int longer = deformed[0]->nx > deformed[0]->ny ? deformed[0]->nx : deformed[0]->ny;
    s.exaggeration = hi > lo ? nice_at_most(longer / 8.0 / (hi - lo)) : 1.0;
    for (int i = 0; i < count; ++i)
        height_range(deformed[i], &lo, &hi);
    s.camera.target_z = s.exaggeration * 0.5 * (lo + hi);
    *style = s;
    return fit_camera(deformed, count, punch, style);
}

/* Step index's annotated frame as frames/view3d_NNNN.png, its pixels in *frame when frame is not NULL. */
static int write_frame(const im_scene *scene, const scene_frames3d_input *in, const im_image *image,
                       const im_view3d_style *s, int index, im_image *frame)
{
    char folder[IM_SCENE_PATH], path[IM_SCENE_PATH], title[192], load[64], scale[96], norm[128];
    int status = scene_output_path(scene, "frames", folder, sizeof folder);
    if (status == IM_OK)
        status = im_frame_path(path, sizeof path, folder, "view3d", index);
    if (status == IM_OK)
        scene_outputs_note(scene, path);
    im_view3d_exaggeration_text(s->exaggeration, scale, sizeof scale);
    scene_frame_load_title(in->load_star, in->count, index, load, sizeof load);
    snprintf(title, sizeof title, "%s, %s", load, scale);
    char range[96];
    run_figure_norm_text(&s->colormap, range, sizeof range);
    snprintf(norm, sizeof norm, "%s %s", im_colormap_name(s->colormap.map), range); /* the map named in it */
    im_figure_panel panel = {image, NULL, title};
    const im_png_text own[] = {{"Title", title}, {"Quantity", "local force f / (E* δ²)"}, {"Norm", norm}};
    run_figure_texts texts;
    if (status == IM_OK)
        status = scene_figure_texts(scene, own, 3, &texts);
    if (status != IM_OK)
        return status;
    im_figure figure = im_figure_default();
    figure.texts = texts.texts;
    figure.text_count = texts.count;
    figure.panels = &panel;
    figure.colormap = &s->colormap;
    figure.colorbar_label = "local force f / (E* δ²)";
    figure.extend_under = in->extend_under; /* the contact frames' triangles: one norm, one bar */
    figure.extend_over = in->extend_over;
    if (in->tension) {
        figure.tension_colormap = &s->tension;
        figure.tension_label = "tensile force −f / (E* δ²)";
    }
    figure.scale_bar = -1.0; /* a perspective view has no single scale */
    figure.dpi = 150;
    status = frame ? im_figure_write_frame(&figure, path, frame) : im_figure_write(&figure, path);
    run_figure_texts_free(&texts);
    return status;
}

static int write_animations(const im_scene *scene, const im_scene_run_options *options, const im_image *frames,
                            int count)
{
    char path[IM_SCENE_PATH], folder[IM_SCENE_PATH];
    int status = IM_OK;
    if (scene->animation & IM_ANIMATION_GIF) {
        status = scene_output_path(scene, "view3d.gif", path, sizeof path);
        if (status == IM_OK)
            status = im_animation_gif(frames, count, 1.0 / scene->frame_rate, path);
    }
    if (status != IM_OK || !(scene->animation & IM_ANIMATION_MP4))
        return status;
    if (!im_ffmpeg_available()) {
        scene_progress(options, "ffmpeg is not installed: no view3d.mp4 (the 3-D frames are in frames/)");
        return IM_OK;
    }
    status = scene_output_path(scene, "frames", folder, sizeof folder);
    if (status == IM_OK)
        status = scene_output_path(scene, "view3d.mp4", path, sizeof path);
    return status == IM_OK ? im_animation_mp4(folder, "view3d", count, scene->frame_rate, path) : status;
}

/* The punch's key as the scene gives it, with its value, for a message. */
static void punch_key(const im_scene *scene, char *key, size_t size)
{
    if (scene->punch == IM_PUNCH_CONE)
        snprintf(key, size, "[punch] alpha = %.9g", scene->alpha_degrees);
    else if (scene->punch == IM_PUNCH_SPHERE || scene->punch == IM_PUNCH_FLAT)
        snprintf(key, size, "[punch] radius = %.9g", scene->radius);
    else
        snprintf(key, size, "[punch] profile");
}

int scene_check_frames3d(const im_scene *scene)
{
    if (!scene->frames3d)
        return IM_OK;
    im_field *flat = NULL;
    int status = im_field_create(scene->surface.nx, scene->surface.ny, scene->surface.delta, &flat);
    if (status != IM_OK)
        return status;
    const im_view3d_style style = view_of(scene);
    const im_indenter punch = scene_punch(scene);
    double distance;
    status = im_view3d_fit_distance(flat, &punch, &style, &distance);
    im_field_free(flat);
    if (status != IM_EINVAL || isnan(distance)) /* NaN: not fitted (render.h) */
        return status;
    char key[96];
    punch_key(scene, key, sizeof key);
    return im_fail_context(status,
                           "%s: %s with [output] frames3d: the 3-D frames show the punch over the %d x %d grid,"
                           " and a camera that sees it whole stands too far (expected a punch the 3-D view can"
                           " frame: a blunter one, or frames3d = no)",
                           scene->path, key, scene->surface.nx, scene->surface.ny);
}

int scene_write_frames3d(const im_scene *scene, const im_scene_run_options *options, im_render_context *context,
                         const scene_frames3d_input *in)
{
    im_view3d_style style;
    im_indenter punch = scene_punch(scene);
    int status = frames_style(scene, in, &punch, &style);
    if (status != IM_OK)
        return status;
    int gif = (scene->animation & IM_ANIMATION_GIF) != 0;
    im_image *frames = calloc((size_t)in->count, sizeof *frames);
    if (!frames)
        return im_fail(IM_ENOMEM, "3-D frames: allocation failed");
    scene_progress(options, "frames3d: %d 3-D view%s (%s, vertical exaggeration %g)", in->count,
                   in->count == 1 ? "" : "s", im_render_gl_renderer(context), style.exaggeration);
    for (int i = 0; i < in->count && status == IM_OK; ++i) {
        im_image view = {0};
        status = im_render_view3d(context, in->deformed[i], in->force[i], &punch, &style, &view);
        if (status == IM_OK)
            status = write_frame(scene, in, &view, &style, i, gif ? &frames[i] : NULL);
        im_image_release(&view);
    }
    if (status == IM_OK)
        status = write_animations(scene, options, frames, in->count);
    for (int i = 0; i < in->count; ++i)
        im_image_release(&frames[i]);
    free(frames);
    return status;
}
