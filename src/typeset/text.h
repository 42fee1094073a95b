/* Text for figures and plots: UTF-8 with _{subscript} and ^{superscript} markup, and the labels
 * of nice tick values. Shared by the figure module (colour bars) and the plot module (axes). */
#ifndef INDENTMAP_TYPESET_TEXT_H
#define INDENTMAP_TYPESET_TEXT_H

#include <cairo.h>
#include <stddef.h>

/* Draws (draw = 1) or only measures text at baseline (x, y) in face at size (pixels); markup runs
 * are drawn at 70 % of the size, raised or lowered. Returns the advance (width) in pixels. */
double typeset_rich_text(cairo_t *cr, cairo_font_face_t *face, double size, double x, double y, const char *text,
                         int draw);

/* Text at (x, y) baseline, aligned 0 left, 0.5 centre, 1 right. */
void typeset_show_text(cairo_t *cr, cairo_font_face_t *face, double size, double x, double y, double align,
                       const char *text);

/* Label of ticks[i] of count ticks from im_figure_ticks. Linear: as many decimals as the step
 * needs ("0.25"), or, when the step is below 0.001 or a value reaches 10^5, one common power of
 * ten ("1.5×10⁻⁶"). Log: all ticks decades: "10⁻²"; else "0.02", or "2×10⁻⁷" below 0.001 or
 * from 10^5. Minus signs are U+2212. */
void typeset_tick_label(int logarithmic, const double *ticks, int count, int i, char *text, size_t size);

/* A scale bar's length with its unit: "100 δ" without a unit; in metres with an SI prefix
 * (nm, µm, mm, m, km) so that the number lies in [1, 1000): 5e-6 m -> "5 µm"; other units as
 * "%g unit". */
void typeset_length_label(double length, const char *unit, char *text, size_t size);

#endif
