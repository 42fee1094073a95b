/* Rich text (sub/superscript markup) and tick labels with cairo. */
#include "figure/text.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void im_figure_tick_label(int logarithmic, const double *ticks, int count, int i, char *text, size_t size)
{
    double v = ticks[i];
    if (logarithmic && count >= 2 && fabs(log10(ticks[1] / ticks[0]) - 1.0) < 1e-9) {
        static const char *const superscripts[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
        int exponent = (int)lround(log10(v));
        int used = snprintf(text, size, "10%s", exponent < 0 ? "⁻" : "");
        char digits[16];
        snprintf(digits, sizeof digits, "%d", abs(exponent));
        for (const char *d = digits; *d && used < (int)size; ++d)
            used += snprintf(text + used, size - (size_t)used, "%s", superscripts[*d - '0']);
        return;
    }
    double step = count >= 2 ? ticks[1] - ticks[0] : fabs(v);
    int decimals = logarithmic ? 3 : step > 0 ? (int)fmax(0.0, -floor(log10(step) + 1e-9)) : 0;
    char number[48];
    snprintf(number, sizeof number, logarithmic ? "%.*g" : "%.*f", logarithmic ? 3 : decimals, fabs(v));
    snprintf(text, size, "%s%s", v < 0 ? "−" : "", number);
}

static double text_width(cairo_t *cr, const char *text)
{
    cairo_text_extents_t extents;
    cairo_text_extents(cr, text, &extents);
    return extents.x_advance;
}

/* Length of the plain run at text: up to the next "_{" or "^{" markup, or the end. */
static size_t plain_run(const char *text)
{
    size_t n = 0;
    while (text[n] && !((text[n] == '_' || text[n] == '^') && text[n + 1] == '{' && strchr(text + n, '}')))
        ++n;
    return n;
}

double im_figure_rich_text(cairo_t *cr, cairo_font_face_t *face, double size, double x, double y,
                           const char *text, int draw)
{
    double advance = 0.0;
    cairo_set_font_face(cr, face);
    while (*text) {
        double scale = 1.0, rise = 0.0;
        const char *start = text;
        size_t n = plain_run(text);
        if (n == 0) { /* markup */
            scale = 0.7;
            rise = text[0] == '_' ? 0.22 * size : -0.38 * size;
            start = text + 2;
            n = (size_t)(strchr(start, '}') - start);
            text = start + n + 1;
        } else {
            text += n;
        }
        char piece[256];
        snprintf(piece, sizeof piece, "%.*s", (int)(n < sizeof piece ? n : sizeof piece - 1), start);
        cairo_set_font_size(cr, size * scale);
        if (draw) {
            cairo_move_to(cr, x + advance, y + rise);
            cairo_show_text(cr, piece);
        }
        advance += text_width(cr, piece);
    }
    return advance;
}

void im_figure_show_text(cairo_t *cr, cairo_font_face_t *face, double size, double x, double y,
                         double align, const char *text)
{
    double width = im_figure_rich_text(cr, face, size, 0.0, 0.0, text, 0);
    im_figure_rich_text(cr, face, size, x - align * width, y, text, 1);
}
