/* Contact frames of the fields a run wrote step by step (front.h: fields_frames_write): `indent --frames`
 * and a periodic scene's contact panels, drawn as a scene draws its frames (frame.c). */
#include "front/front.h"

#include "indentmap/figure.h"
#include "indentmap/formats.h"
#include "indentmap/io.h"
#include "indentmap/status.h"

#include <math.h>
#include <stdio.h>

static int read_force(const char *dir, int step, im_field **force)
{
    char name[64], path[4096];
    snprintf(name, sizeof name, "force_%04d.npy", step);
    int status = im_path_join(path, sizeof path, dir, name);
    return status == IM_OK ? im_npy_read(path, force) : status;
}

/* The forces and the tensions of every step (ranges[0], ranges[1]): the frames' one force norm and their
 * one tension norm, gathered a step at a time. */
static int shared_ranges(const fields_frames *f, im_colormap_range ranges[2])
{
    ranges[0] = im_colormap_range_empty(IM_COLORMAP_FORCES);
    ranges[1] = im_colormap_range_empty(IM_COLORMAP_TENSIONS);
    int status = IM_OK;
    for (int step = 1; step <= f->count && status == IM_OK; ++step) {
        im_field *force = NULL;
        status = read_force(f->dir, step, &force);
        for (int i = 0; i < 2 && status == IM_OK; ++i)
            status = im_colormap_range_add(&ranges[i], force);
        im_field_free(force);
    }
    return status;
}

int fields_frames_pixels_per_patch(int nx, int ny)
{
    const int side = nx > ny ? nx : ny;
    const int scale = (384 + side - 1) / side;
    return scale < 1 ? 1 : scale > 8 ? 8 : scale;
}

/* Step's frame: its contact map with the smooth punch's contact circle (none where N* is not finite: a
 * periodic cell, a 2-D profile), titled with N* (else N). */
static int write_frame(im_render_context *context, const fields_frames *f, const im_colormap *norms, int tension_bar,
                       int step)
{
    const im_step_result *r = &f->rows[step - 1].result;
    im_field *force = NULL;
    im_image image = {0};
    int status = read_force(f->dir, step, &force);
    if (status != IM_OK)
        return status;
    double axis_x, axis_y;
    im_indenter_axis(f->punch, force->nx, force->ny, force->delta, &axis_x, &axis_y);
    const frame_contact contact = {force,
                                   &norms[0],
                                   &norms[1],
                                   fields_frames_pixels_per_patch(force->nx, force->ny),
                                   sqrt(r->load_star / M_PI),
                                   axis_x / force->delta,
                                   axis_y / force->delta};
    char title[96], label[96], tension_label[96], path[4096];
    if (isfinite(r->load_star))
        snprintf(title, sizeof title, "step %d: N* = %.4g", step, r->load_star);
    else
        snprintf(title, sizeof title, "step %d: N = %.4g %s", step, r->load, f->force_unit);
    im_figure_colorbar_label("force", f->force_unit, label, sizeof label); /* (96 bytes: fits any unit here) */
    im_figure_colorbar_label("tension", f->force_unit, tension_label, sizeof tension_label);
    const frame_words words = {
        title, &norms[0], label, tension_bar ? &norms[1] : NULL, tension_label, f->texts, f->text_count, 0, 0};
    status = frame_contact_render(context, &contact, &image);
    if (status == IM_OK)
        status = im_frame_path(path, sizeof path, f->frames, "contact", step - 1);
    if (status == IM_OK)
        status = frame_figure_write(&image, &words, path, NULL);
    im_image_release(&image);
    im_field_free(force);
    return status;
}

int fields_frames_write(im_render_context *context, const fields_frames *f)
{
    im_colormap_range ranges[2] = {im_colormap_range_empty(IM_COLORMAP_FORCES),
                                   im_colormap_range_empty(IM_COLORMAP_TENSIONS)};
    int status = im_make_directories(f->frames);
    if (status == IM_OK)
        status = shared_ranges(f, ranges);
    const im_colormap norms[2] = {im_colormap_range_norm(&ranges[0], IM_COLORMAP_MAGMA, NAN, NAN, 1),
                                  im_colormap_range_norm(&ranges[1], IM_COLORMAP_TENSION, NAN, NAN, 0)};
    for (int step = 1; step <= f->count && status == IM_OK; ++step)
        status = write_frame(context, f, norms, ranges[1].hi > 0.0, step);
    return status;
}
