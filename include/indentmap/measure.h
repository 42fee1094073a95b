/* indentmap/measure.h: what an indentation experiment measures, from simulated histories and
 * fields: the contact stiffness S = dN/dw, the effective modulus Sneddon's relation infers from
 * it (the Oliver-Pharr analysis), the contact patches (number, sizes, perimeter) and the gap
 * distribution.
 *
 * Sneddon: for any axisymmetric punch in elastic contact, S = dN/dw = 2 E* a with a the contact
 * radius, so an experiment that knows the projected area A = pi a^2 infers
 *     E*_eff = (sqrt(pi) / 2) S / sqrt(A),
 * which is E* for a smooth surface. Units: loads N in E* (length)^2, approaches and lengths in the
 * field's units, stiffness in E* length.
 * Errors: IM_EINVAL naming the argument; IM_ENOMEM. Outputs are written only on success.
 */
#ifndef INDENTMAP_MEASURE_H
#define INDENTMAP_MEASURE_H

#include "indentmap/field.h"

#ifdef __cplusplus
extern "C" {
#endif

/* S_i = dN/dw at each of count >= 2 steps with strictly increasing (loading) or strictly decreasing
 * (unloading) approaches: the three-point
 * derivative for unequal steps inside (exact for a quadratic N(w), Love's cone), one-sided
 * three-point formulas at both ends (two-point when count = 2). stiffness: count values. */
int im_measure_stiffness(const double *approach, const double *load, int count, double *stiffness);

/* Sneddon / Oliver-Pharr: E*_eff = (sqrt(pi) / 2) S / sqrt(A) for S >= 0 and A > 0 (NaN otherwise). */
double im_measure_sneddon_modulus(double stiffness, double area);

/* Connected contact patches (force > 0; 4-neighbour connectivity, not periodic). */
typedef struct im_contact_patches {
    long patches;        /* number of connected patches (clusters of contacting grid cells) */
    long cells;          /* contacting cells in all, n_p */
    long largest;        /* cells of the largest patch */
    double mean_area;    /* cells / patches * delta^2 (0 without contact) */
    double perimeter;    /* length of the edges between contact and no contact (including the grid's
                            border next to a contacting cell), delta per edge */
} im_contact_patches;

/* Patch statistics of a force (or pressure) field; sizes, when not NULL, receives a new array of the
 * patches' cell counts in order of first appearance (row by row; the caller frees it; NULL without
 * contact). */
int im_measure_contact_patches(const im_field *force, im_contact_patches *out, long **sizes);

/* Histogram of the finite gaps of a gap field on bins equal bins over [0, gap_max) (gap_max > 0,
 * bins >= 1): counts[bins] (contact, g <= 0, falls in the first bin; gaps >= gap_max and +INFINITY
 * are not counted). */
int im_measure_gap_histogram(const im_field *gap, double gap_max, int bins, long *counts);

#ifdef __cplusplus
}
#endif

#endif
