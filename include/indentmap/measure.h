/* indentmap/measure.h: what an indentation experiment measures, from simulated histories and
 * fields: the contact stiffness S = dN/dw, the effective modulus Sneddon's relation infers from
 * it (the Oliver-Pharr analysis), the contact patches (number, sizes, perimeter) and the gap
 * distribution.
 *
 * Entry points:
 *   im_measure_stiffness, im_measure_sneddon_modulus       S = dN/dw and the modulus it gives
 *   im_measure_unloading, im_measure_epsilon, im_measure_projected_area   Oliver-Pharr's analysis
 *   im_measure_contact_patches, im_measure_patch_list, im_measure_patch_histogram   contact patches
 *   im_measure_gap_histogram, im_measure_gap_distribution, im_measure_write_distributions   gaps
 *   im_measure_adhesion                                     pull-off and hysteresis of a history
 *
 * Sneddon: for any axisymmetric punch in elastic contact, S = dN/dw = 2 E* a with a the contact
 * radius, so an experiment that knows the projected area A = pi a^2 infers
 *     E*_eff = (sqrt(pi) / 2) S / sqrt(A),
 * which is E* for a smooth surface. Units: loads N in E* (length)^2, approaches and lengths in the
 * field's units, stiffness in E* length.
 * Errors: IM_EINVAL naming the argument; IM_ENOMEM. Outputs are written only on success.
 * Misuse (status.h): NULL arrays, outputs or invalid field views give IM_EINVAL naming the function
 * and the argument.
 * Threads: thread-safe: each call reads its inputs, writes its outputs and keeps nothing.
 */
#ifndef INDENTMAP_MEASURE_H
#define INDENTMAP_MEASURE_H

#include "indentmap/field.h"
#include "indentmap/indenter.h"

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

/* ---- The indentation analysis of unloading branches (Oliver & Pharr, J. Mater. Res. 7, 1564 (1992)) ----
 * A history whose approach rises to a top and then falls holds an unloading branch: from the top step
 * (the last of a top held over several steps) while the approach decreases; approaches within 1e-6 of
 * each other (relative) count as one (a repeated target, or load control finding one load twice).
 * For each, with h the approach (counted from first touch) and P the load:
 *   S     = dP/dh at the top: the slope there of the parabola through the top and the next two
 *           unloading steps (im_measure_stiffness's one-sided formula; NaN with fewer than 3 points,
 *           or when the second or third has P = 0 short of the touch, below its residual approach
 *           where those are given: a parabola across the touch is no slope of the curve);
 *   h_c   = h_max - epsilon P_max / S, epsilon the punch's geometry factor: 0.72 cone, 0.75 sphere and
 *           axisymmetric profiles (Oliver-Pharr's paraboloid), 1 flat punch;
 *   A_p   = pi r^2 with z(r) = h_c on the punch's profile (the projected area at the contact depth;
 *           the flat punch's pi a^2); NaN for a 2-D profile;
 *   H_IT  = P_max / A_p;   E_r = (sqrt(pi) / 2) S / sqrt(A_p) (Sneddon, beta = 1);
 *   h_r   = the residual approach: where the withdrawn punch touches the impression it left (the
 *           state's min of g0 + plastic depth, im_step_result.residual_approach, at the branch's last
 *           step), when that step's load is 0; NaN otherwise (the curve alone cannot give it: P = 0
 *           below h_r, and extrapolating the last unloading steps is no measurement);
 *   W_in  = the trapezoid integral of P dh over the loading steps before the top (from h = 0, P = 0
 *           for the first branch, else from the step the approach last turned up at);
 *   W_out = the same over the unloading branch (the elastic work given back); with a full unload
 *           W_in - W_out is the loop's area, the dissipated energy.
 * h_c within 1e-9 h_max below 0 (a flat punch, h = P / S, to rounding) is 0. */
typedef struct im_unloading_branch {
    int top_step, last_step; /* 1-based steps of the history: the top, the branch's last */
    int loading_from;        /* 1-based step the loading before the top started at (0: the origin) */
    double approach_max, load_max, stiffness, epsilon, contact_depth, area_projected;
    double hardness, modulus, residual_approach, work_in, work_out;
    int withdrawn_step; /* 1-based step of S's second or third point when it is past the touch (S NaN), else 0 */
} im_unloading_branch;

/* The unloading branches of a history of count steps (approach, load and, may be NULL, the residual
 * approach of each step's state), for punch: at most capacity of them into branches (*found says how
 * many there are). IM_EINVAL naming the argument for NULL arrays, count < 1, non-finite approaches or
 * loads, an invalid punch. */
int im_measure_unloading(const im_indenter *punch, const double *approach, const double *load, const double *residual,
                         int count, im_unloading_branch *branches, int capacity, int *found);

/* Why branch's S (and h_c, A_p, H_IT, E_r after it) is NaN and what to do, the sentence every front end says
 * (findings R3): its fit's second or third point is past the touch (withdrawn_step); unload in smaller
 * steps that keep at least three points in contact. "" where S is measured or NaN for another reason (fewer
 * than three unloading steps). IM_EINVAL for NULL branch or text, or size 0. */
int im_measure_unloading_note(const im_unloading_branch *branch, char *text, size_t size);

/* Oliver-Pharr's epsilon for the punch (see above); NaN for a 2-D profile. */
double im_measure_epsilon(const im_indenter *punch);
/* The punch's cross-section area pi r^2 at height h_c above its lowest point; NaN for a 2-D profile
 * or h_c < 0. */
double im_measure_projected_area(const im_indenter *punch, double contact_depth);

/* Connected contact patches (force > 0; 4-neighbour connectivity, not periodic). */
typedef struct im_contact_patches {
    long patches;     /* number of connected patches (clusters of contacting grid cells) */
    long cells;       /* contacting cells in all, n_p */
    long largest;     /* cells of the largest patch */
    double mean_area; /* cells / patches * delta^2 (0 without contact) */
    double perimeter; /* length of the edges between contact and no contact (including the grid's
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

/* ---- Distributions at one state (docs/theory.md, "Gap and patch-size distributions") ---- */

/* One contact patch: its cells (area cells delta^2) and the edges between it and no contact,
 * including the grid's border next to it (perimeter edges delta). */
typedef struct im_patch {
    long cells;
    long edges;
} im_patch;

/* The patches of a force field (force > 0; 4-neighbour connectivity, not periodic) in order of
 * first appearance (row by row): *patches is a new array of *count entries (NULL when there is no
 * contact; the caller frees it). Their cells add up to im_contact_patches' cells and their edges to
 * its perimeter / delta. */
int im_measure_patch_list(const im_field *force, im_patch **patches, long *count);

enum { IM_PATCH_BINS = 40 }; /* octaves of patch size: 1 to 2^40 cells */

/* Histogram of patch sizes by octave: bin b holds the patches of 2^b <= cells < 2^(b+1) (so b = 0
 * is single cells); patches[b], cells[b] and edges[b] (IM_PATCH_BINS each) receive their number,
 * their cells and their edges. Every patch falls in one bin: the sums are count, the contact's cells
 * and its edges. IM_EINVAL for NULL arrays with count > 0 or a patch of fewer than 1 cell. */
int im_measure_patch_histogram(const im_patch *list, long count, long *patches, long *cells, long *edges);

/* The gap outside contact (cells whose force is not > 0) in units of scale > 0 (h_rms, say): bins >= 1
 * equal bins over [0, g_max / scale], g_max the largest finite gap outside contact (the last bin
 * includes it; a negative gap, within the solver's tolerance, counts as 0). counts[bins] the cells of
 * each bin; *bin_width its width in units of scale (0 when no finite gap lies outside contact);
 * *infinite the cells outside contact whose gap is +Inf (a flat punch's far field). So the counts
 * and *infinite add up to the cells outside contact, and sum density * bin_width over the bins, with
 * density = counts / (nx ny bin_width), is the non-contact fraction of finite gap. force and gap
 * share one grid (IM_EINVAL otherwise, or for a NaN gap outside contact). */
int im_measure_gap_distribution(const im_field *gap, const im_field *force, double scale, int bins, long *counts,
                                double *bin_width, long *infinite);

/* The gap bins of the distributions `indentmap indent --distributions`, periodic scenes and Python's
 * Indentation.write_distributions write. */
enum { IM_MEASURE_GAP_BINS = 50 };

/* Writes the distributions of one state as CSV files (atomically): PREFIX_gaps.csv, the gap outside
 * contact normalised by height_rms (> 0; the caller passes delta for a smooth surface) in `bins`
 * bins, columns gap_low,gap_high,cells,density (density per unit gap / height_rms, over all cells:
 * its integral is the non-contact fraction), and a last row `inf,inf,CELLS,0` for infinite gaps;
 * PREFIX_patches.csv, the patch-size histogram by octave (non-empty bins), columns
 * cells_low,cells_high,patches,cells,area,perimeter (area in delta^2 x cells, perimeter in delta x
 * edges, both in the field's length units); PREFIX_patch_list.csv, one row per patch:
 * patch,cells,area,perimeter. IM_EIO naming the file. */
int im_measure_write_distributions(const im_field *force, const im_field *gap, double height_rms, int bins,
                                   const char *prefix);

/* ---- adhesion: a force-distance history's pull-off, jumps and lost work (solver.h, "Adhesion") ---- */
typedef struct im_adhesion_summary {
    double pull_off_force;        /* the pull-off, -min N (> 0), where the steps passed it: the approaches (or
                                 mean gaps) were given and a later step's load rises above it; NaN
                                 otherwise (a load-controlled contact holds every load it is given, and the
                                 least load it can hold lies below them: a step past it is refused naming it) */
    double pull_off_approach;     /* the approach of that step; NaN with pull_off_force */
    double jump_in_approach;      /* the first step in contact right after one out of contact, the approach
                                 rising (the surface snapped up to the punch); NaN when none */
    double jump_out_approach;     /* the last step in contact right before one out of contact, the approach
                                 falling (separation lies between it and the next); NaN when none */
    double work_done;             /* sum of N dw over the history (trapezoids): the work the punch did */
    double hysteresis_work;       /* work_done where the history closes a loop, the work lost in its jumps: its
                                 last step at the first approach, or both without force (the path between
                                 at N = 0 does no work); NaN otherwise (a retraction alone is no loss) */
    double hysteresis_error;      /* an estimate of the trapezoids' error in work_done: over each step the smaller of
                                 h^3 |N''| / 12 (N'' from the neighbouring second differences on the same
                                 branch) and h |dN| / 2 (the bound where N is monotone between the steps, as
                                 across a jump); a work within it is not resolved by the steps */
    double most_tensile_load;     /* -min N (> 0), pull-off or not; NaN when no step pulls */
    double most_tensile_approach; /* the approach of that step */
} im_adhesion_summary;

/* Summarises count >= 1 steps of approaches, net loads and contact patches (p_r > 0), solved at the loads given
 * (loads_given != 0, load control: their least load is never a pull-off) or at approaches or mean gaps (0).
 * IM_EINVAL for NULL arrays, count < 1 or a non-finite approach or load (naming the step). */
int im_measure_adhesion(const double *approach, const double *load, const long *contact, int count, int loads_given,
                        im_adhesion_summary *out);

#ifdef __cplusplus
}
#endif

#endif
