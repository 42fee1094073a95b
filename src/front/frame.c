/* One annotated frame of a history (front.h, "Frames"): the contact map a scene's frames and
 * `indent --frames` draw, and the figure every frame is written as. */
#include "front/front.h"

#include "indentmap/figure.h"
#include "indentmap/status.h"

#include <math.h>

im_colormap_range frame_range(im_field *const *fields, int count, im_colormap_values values)
{
    im_colormap_range range = im_colormap_range_empty(values);
    for (int i = 0; i < count; ++i)
        im_colormap_range_add(&range, fields[i]);
    return range;
}

void frame_extends(const im_field *field, const im_colormap *norm, int forces, int *under, int *over)
{
    for (size_t i = 0; i < im_field_count(field); ++i) {
        const double v = field->data[i];
        if (isnan(v) || (forces && !(v > 0.0)))
            continue;
        const int index = im_colormap_index(norm, v);
        *under |= index == -1;
        *over |= index == 256;
    }
}

int frame_contact_render(im_render_context *context, const frame_contact *contact, im_image *image)
{
    im_contact_style style = im_contact_style_default(contact->force);
    style.colormap = *contact->norm;
    style.tension = *contact->tension;
    style.pixels_per_patch = contact->pixels_per_patch;
    if (contact->circle_radius > 0.0) { /* NaN or 0: no smooth contact to outline */
        style.circle_radius = contact->circle_radius;
        style.circle_x = contact->circle_x;
        style.circle_y = contact->circle_y;
    }
    return im_render_contact_map(context, contact->force, &style, image);
}

int frame_figure_write(const im_image *image, const frame_words *words, const char *path, im_image *kept)
{
    im_figure_panel panel = {image, NULL, words->title};
    im_figure figure = im_figure_default();
    figure.panels = &panel;
    figure.colormap = words->norm;
    figure.colorbar_label = words->colorbar_label;
    figure.tension_colormap = words->tension;
    figure.tension_label = words->tension_label;
    figure.dpi = 150;
    figure.extend_under = words->norm->logarithmic || words->extend_under;
    figure.extend_over = words->extend_over;
    figure.texts = words->texts;
    figure.text_count = words->text_count;
    return kept ? im_figure_write_frame(&figure, path, kept) : im_figure_write(&figure, path);
}
