/* Rich text (sub/superscript markup) and tick labels with cairo. */
#include "typeset/text.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Appends "10" and the exponent in superscript digits (minus U+207B) to text at used. */
static int append_power_of_ten(int exponent, char *text, size_t size, int used)
{
    static const char *const superscripts[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
    used += snprintf(text + used, size - (size_t)used, "10%s", exponent < 0 ? "⁻" : "");
    char digits[16];
    snprintf(digits, sizeof digits, "%d", abs(exponent));
    for (const char *d = digits; *d && used < (int)size; ++d)
        used += snprintf(text + used, size - (size_t)used, "%s", superscripts[*d - '0']);
    return used;
}

static int is_power_of_ten(double v)
{
    double e = log10(v);
    return fabs(e - round(e)) < 1e-9;
}

/* Whether log ticks are all decades: 10^n labels. */
static int decade_ticks(const double *ticks, int count)
{
    for (int i = 0; i < count; ++i)
        if (!(ticks[i] > 0.0) || !is_power_of_ten(ticks[i]))
            return 0;
    return count >= 1;
}

/* v as mantissa x 10^exponent with decimals digits: "1.5×10⁻⁶", "−2×10⁷"; 0 as "0". */
static void scientific_label(double v, int exponent, int decimals, char *text, size_t size)
{
    if (v == 0.0) {
        snprintf(text, size, "0");
        return;
    }
    int used = snprintf(text, size, "%s%.*f×", v < 0 ? "−" : "", decimals, fabs(v) / pow(10.0, exponent));
    append_power_of_ten(exponent, text, size, used);
}

/* Linear ticks: plain decimals while readable (step >= 0.001, values < 10^5), else one common
 * power of ten for all labels. */
static void linear_label(const double *ticks, int count, int i, char *text, size_t size)
{
    double v = ticks[i], step = count >= 2 ? ticks[1] - ticks[0] : fabs(v), largest = 0.0;
    for (int k = 0; k < count; ++k)
        largest = fmax(largest, fabs(ticks[k]));
    if (step > 0.0 && (step < 1e-3 || largest >= 1e5)) {
        int exponent = (int)floor(log10(largest) + 1e-9);
        int decimals = (int)fmax(0.0, -floor(log10(step / pow(10.0, exponent)) + 1e-9));
        scientific_label(v, exponent, decimals, text, size);
        return;
    }
    int decimals = step > 0 ? (int)fmax(0.0, -floor(log10(step) + 1e-9)) : 0;
    snprintf(text, size, "%s%.*f", v < 0 ? "−" : "", decimals, fabs(v));
}

void typeset_tick_label(int logarithmic, const double *ticks, int count, int i, char *text, size_t size)
{
    double v = ticks[i];
    if (!logarithmic) {
        linear_label(ticks, count, i, text, size);
    } else if (decade_ticks(ticks, count)) {
        text[0] = '\0';
        append_power_of_ten((int)lround(log10(v)), text, size, 0);
    } else if (v < 1e-3 || v >= 1e5) {
        int exponent = (int)floor(log10(v) + 1e-9);
        scientific_label(v, exponent, 0, text, size); /* 1, 2 or 5 x 10^n */
    } else {
        snprintf(text, size, "%.3g", v);
    }
}

void typeset_length_label(double length, const char *unit, char *text, size_t size)
{
    static const char *const prefixes[] = {"n", "µ", "m", "", "k"};
    if (!unit || !unit[0]) {
        snprintf(text, size, "%g δ", length);
        return;
    }
    if (strcmp(unit, "m") != 0 || !(length > 0.0)) {
        snprintf(text, size, "%g %s", length, unit);
        return;
    }
    int group = (int)floor(log10(length) / 3.0 + 1e-9);
    group = group < -3 ? -3 : group > 1 ? 1 : group;
    snprintf(text, size, "%.3g %sm", length / pow(10.0, 3 * group), prefixes[group + 3]);
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

double typeset_rich_text(cairo_t *cr, cairo_font_face_t *face, double size, double x, double y, const char *text,
                         int draw)
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

void typeset_show_text(cairo_t *cr, cairo_font_face_t *face, double size, double x, double y, double align,
                       const char *text)
{
    double width = typeset_rich_text(cr, face, size, 0.0, 0.0, text, 0);
    typeset_rich_text(cr, face, size, x - align * width, y, text, 1);
}
