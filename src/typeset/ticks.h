/* Nice tick values on any range, for colour bars and plot axes. */
#ifndef INDENTMAP_TYPESET_TICKS_H
#define INDENTMAP_TYPESET_TICKS_H

/* Ticks on [lo, hi] for a plot axis: about `target` linear intervals (a 1-2-5 step at least
 * span / target), or, when logarithmic, the decades, and 1-2-5 multiples only when fewer than
 * two decades fall inside (colour bars switch below three). Returns how many
 * were written (0 for an empty or, when logarithmic, non-positive range). */
int typeset_ticks_between(double lo, double hi, int logarithmic, double target, double *ticks, int capacity);

/* The ticks of a colour bar on [lo, hi] (im_figure_ticks, figure.h): linear, about 5 intervals; log,
 * the decades inside, or 1-2-5 multiples when fewer than three decades fall inside. */
int typeset_colour_bar_ticks(double lo, double hi, int logarithmic, double *ticks, int capacity);

#endif
