/* indentmap/history.h: the one history schema of every front end — `indent`'s history.csv, a scene's
 * histories/member_FF_SEED.csv and Python's history arrays: its columns, the measurement beside each
 * solved step, one row writer and one reader.
 *
 * Entry points:
 *   im_history_columns                     the schema: its column names, in order
 *   im_history_integer_columns             those of its columns that hold integers
 *   im_history_measure                     a solved step's row (the theory and measures beside it)
 *   im_history_format, im_history_parse    a row as CSV text and back
 *   im_history_row_values, im_history_row_from_values   a row as its columns' numbers and back
 *   im_history_write_analysis              the indentation analysis `indent` writes beside a history
 *   im_history_units_json                  run.json's "units" block
 *
 * Columns, in order: step, the solver's results (approach, load, load_star, contact_patches,
 * area_ratio, mean_pressure, max_pressure, iterations, residual, seconds, convolutions), the theory
 * beside them (load_smooth, area_smooth, area_ratio_constant, area_ratio_gamma; theory.h), what an
 * experiment measures (stiffness, e_star_sneddon, patches, patch_perimeter; measure.h) and the plastic
 * memory (yielding_patches, plastic_depth, plastic_work, residual_approach; solver.h) and adhesion
 * (tensile_force, adhesive_patches, repulsive_patches; solver.h, 0 without) and a periodic cell's mean
 * gap (mean_gap; solver.h, NaN on the half-space). Numbers are
 * written with 17 significant digits (residual and seconds with 7), so a history read back is the one
 * written.
 *
 * Misuse (status.h): NULL arrays or outputs give IM_EINVAL naming the function and the argument.
 * Threads: thread-safe on distinct rows and files. */
#ifndef INDENTMAP_HISTORY_H
#define INDENTMAP_HISTORY_H

#include "indentmap/indenter.h"
#include "indentmap/solver.h"
#include "indentmap/theory.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* One step of a history. A value the writer did not have (a scene's step taken from its table) is -1
 * for the counts (iterations, convolutions, patches) and NaN for the others. */
typedef struct im_history_row {
    int step; /* 1-based */
    im_step_result result;
    im_theory_step theory;
    double stiffness;      /* dN/dw from this step and the two before on one branch; NaN otherwise */
    double e_star_sneddon; /* (sqrt(pi) / 2) S / sqrt(A_smooth(N)) */
    long patches;          /* connected contact patches */
    double perimeter;      /* their perimeter */
} im_history_row;

/* The column line (without its newline), the same for every history this version writes. */
const char *im_history_columns(void);
/* The columns written as integers (the others are floating point), in the same order and form: what
 * a reader needs to type the columns (Python's history arrays: int64 and float64). */
const char *im_history_integer_columns(void);

/* Fills rows[i] (rows[0..i) filled before; rows[i].result set by the caller, e.g. by
 * im_indentation_step): its step number, the theory for punch on the interface rough at its approach
 * and load (NaN when rough is NULL: a periodic cell), the stiffness and Sneddon modulus, and (run not
 * NULL: the state of this step) the contact patches. On the half-space (rough not NULL) it also settles
 * area_ratio, A / A_smooth(N): NaN where the load is not positive beyond the solver's tolerance tol (the
 * steps' options.tol), N <= tol max |N| over rows[0..i]. The smooth area vanishes as N -> 0 while an
 * adhesive contact keeps its area, so a load the solver holds at zero only to tol (load control's 0,
 * 1e-6 of the loads before it) gave any ratio at all (52665). IM_EINVAL for i < 0 or tol not in [0, 1]. */
int im_history_measure(const im_indenter *punch, const im_theory_interface *rough, const im_indentation *run,
                       double tol, im_history_row *rows, int i);

/* The most steps of one history (IM_SCENE_MAX_STEPS of a scene, and indent's). */
enum { IM_HISTORY_MAX_STEPS = 4096 };

/* The row as one CSV line with its newline, into line (IM_HISTORY_LINE_MAX bytes suffice). Returns its
 * length; -1 (IM_EINVAL) for a NULL row or line. */
enum { IM_HISTORY_LINE_MAX = 1024 };
int im_history_format(const im_history_row *row, char *line, size_t size);

/* The row's values in the columns' order, IM_HISTORY_COLUMN_COUNT of them (the integer columns' as
 * doubles, exactly), into values; and a row from such values: how a reader that keeps the columns apart
 * (Python's history arrays) writes and reads rows with this schema, not a listing of its own.
 * IM_EINVAL for a NULL row or values, and from values for an integer column holding a value that is not
 * an integer of its type (naming the column). */
enum { IM_HISTORY_COLUMN_COUNT = 28 };
int im_history_row_values(const im_history_row *row, double *values);
int im_history_row_from_values(const double *values, im_history_row *row);

/* What area_ratio and load_star are measured against, im_history_parse's area: no area (a 2-D
 * profile: both NaN), the smooth punch's (load_star = A(N) / delta^2), the periodic cell's (area_ratio
 * = A / A0, load_star NaN; solver.h, "Periodic mode"), or any of them (a reader that does not know the
 * punch: load_star and area_ratio are not checked). */
enum { IM_HISTORY_AREA_NONE = 0, IM_HISTORY_AREA_SMOOTH = 1, IM_HISTORY_AREA_CELL = 2, IM_HISTORY_AREA_ANY = 3 };

/* Parses the text of a history from its column line: the line must be im_history_columns() (else a
 * history of another version), then each row whole, with the right number of values, numbers finite
 * where they must be (approach, load; with IM_HISTORY_AREA_SMOOTH, load_star unless the load is
 * tensile; with it or IM_HISTORY_AREA_CELL, area_ratio unless the load is not compressive, and with the
 * first also where it may be zero to the solver's tolerance: not above every load before it,
 * im_history_measure) and NaN where the solver writes NaN (area_ratio at no load; load_star but with a
 * smooth-contact area, area_ratio without any area). Fills rows[0..*count) (capacity at most). Returns 1, or 0 with a reason in why at
 * the first fault (also for NULL arguments). */
int im_history_parse(const char *text, int area, im_history_row *rows, int capacity, int *count, char *why,
                     size_t why_size);

/* The indentation analysis of rows[0..count) as `indent` writes it beside its history (docs/solver.md,
 * "Indentation analysis"): when the history holds an unloading branch for punch (measure.h:
 * im_measure_unloading), DIR/indentation.csv (a row per branch) and the load-displacement figure
 * DIR/load_displacement.{png,pdf} (N against w, loading and unloading segments in two colours, each
 * branch's tangent at its top), atomically. delta: the grid's spacing (the real area n_p delta^2); e_star:
 * E* (the smooth punch's stiffness beside each branch); length_unit and force_unit: the axes' units ("" for
 * delta and E* delta^2). *branches says how many branches there are (0: nothing written, as for count < 2).
 * IM_EINVAL for a NULL pointer or count < 0; the measurement's and the writers' errors otherwise. */
int im_history_write_analysis(const char *dir, const im_indenter *punch, const im_history_row *rows, int count,
                              double delta, double e_star, const char *length_unit, const char *force_unit,
                              int *branches);

/* The units of a history's numbers as `indent` states them in run.json's "units" block: JSON text (keys
 * sorted) with "length", "approach", "e_star", "pressure", "stiffness", "work", "load", "force",
 * "load_star", "area_ratio" and "columns" (each column of history.csv and indentation.csv with its unit),
 * for the surface's length_unit ("": units of delta) and e_star_unit ("": E* as given; "Pa" with "m"
 * gives forces in N), periodic or not. IM_EINVAL for NULL pointers or a text of fewer than size bytes;
 * IM_ENOMEM. */
int im_history_units_json(const char *length_unit, const char *e_star_unit, int periodic, char *text, size_t size);

#ifdef __cplusplus
}
#endif

#endif
