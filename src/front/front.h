/* Internal: what the two front ends, `indentmap indent` (src/cli/indent.c) and scenes (src/scene/),
 * share, so that each exists once: the history file appended step by step (history_file.c; its
 * schema is the public history.h), the step-list parser (steps.c), the indentation analysis'
 * files (analysis.c) and the JSON run record (record.c). */
#ifndef INDENTMAP_FRONT_H
#define INDENTMAP_FRONT_H

#include "indentmap/formats.h"
#include "indentmap/history.h"
#include "indentmap/indenter.h"
#include "indentmap/io.h"
#include "indentmap/measure.h"
#include "indentmap/render.h"
#include "indentmap/solver.h"
#include "indentmap/surface.h"
#include "indentmap/theory.h"

#include <jansson.h>
#include <stddef.h>
#include <stdio.h>
#include <sys/types.h>

/* The texts a run's figures carry as PNG text chunks and PDF metadata: "Software" (the version), the
 * given texts (what makes the run again: a scene's path and contents, indent's command), and "Inputs",
 * the record's inputs (run_record_add_input) as sha256sum writes them, one "SHA256  PATH\n" line each
 * ("none" without). */
enum { RUN_FIGURE_TEXTS_MAX = 10 };
typedef struct run_figure_texts {
    im_png_text texts[RUN_FIGURE_TEXTS_MAX];
    int count;
    char *inputs; /* the Inputs text (owned) */
} run_figure_texts;

/* At most RUN_FIGURE_TEXTS_MAX - 2 given texts (borrowed); IM_ENOMEM. Free with run_figure_texts_free. */
int run_figure_texts_make(const im_png_text *given, int given_count, const json_t *inputs, run_figure_texts *out);
void run_figure_texts_free(run_figure_texts *texts);
/* The "Norm" text of a colour-mapped figure: "log [lo, hi]" or "linear [lo, hi]", nine digits (the
 * "Colormap" text names the map). */
void run_figure_norm_text(const im_colormap *norm, char *text, size_t size);

/* ---- step lists (steps.c) ---- */

/* The most steps of one history. A scene holds its steps inline (im_scene.steps, 32 KiB for
 * 4096 doubles, copied by value) and a run keeps a row of about 200 bytes per step; at the
 * 0.05-1 s a step of a 512 x 512 solve takes, 4096 steps are already minutes to an hour. The
 * field files of `indent --fields` are numbered with four digits, which 4096 keeps. */
enum { STEPS_MAX = IM_HISTORY_MAX_STEPS };

/* Parses a step list: items separated by commas (blanks around them allowed), each a value or a range
 * "first:last:count" (count values evenly spaced from first to last, both included; last may be below
 * first), of finite values >= 0, into values[STEPS_MAX]: "2:8:4, 7:2:6" loads to 8 and unloads to 2.
 * 0, or -1 with a message "NAME 'TEXT': expected ..." in error (name is the option or key:
 * "--approach", "steps"). */
int steps_parse(const char *name, const char *text, double *values, int *count, char *error, size_t error_size);
/* The largest |value| of a step list: a history's largest target (im_indentation_create's; approaches and loads
 * below 0 pull away, with adhesion). */
double steps_largest(const double *values, int count);
/* The same, with negative values too when negative is nonzero (approaches pulling away, with adhesion). */
int steps_parse_signed(const char *name, const char *text, int negative, double *values, int *count, char *error,
                       size_t error_size);
/* 0 when every mean gap of a parsed list is > 0, else -1 with the message (naming name, text and the step):
 * at a mean gap of 0 a periodic cell is in full contact. Checked before any step is solved. */
int steps_check_mean_gaps(const char *name, const char *text, const double *values, int count, char *error,
                          size_t error_size);

/* ---- history.csv appended step by step (history_file.c; the schema is history.h's) ---- */

/* A history file appended step by step (indent): its column line is written atomically, then each
 * row with one write(2) and synced (fdatasync), so that a finished step survives a crash and the
 * cost per step does not grow with the steps before it. A write that fails part way is cut back to
 * the last whole line. */
typedef struct history_file {
    int fd;
    off_t size; /* bytes of whole lines */
    char path[4096];
} history_file;
int history_start(const char *dir, history_file *h);
int history_append(history_file *h, const im_history_row *row);
void history_close(history_file *h);

/* ---- the indentation analysis of a history's unloading branches (analysis.c) ---- */

/* The columns of DIR/indentation.csv: one row per unloading branch (measure.h, im_measure_unloading),
 * with the real contact area n_p delta^2 at the top and the dissipation the solver reports over the
 * cycle (from the step the loading started at to the branch's last step), then the theory beside it
 * at the top load where the top is elastic and repulsive (NaN otherwise): eq. (12)'s real area and the
 * smooth punch's stiffness 2 E* sqrt(A_smooth / pi) (E* = e_star). */
extern const char ANALYSIS_COLUMNS[];

/* Analyses rows[0..count) (measure.h) and, when they hold an unloading branch, writes
 * DIR/indentation.csv and DIR/load_displacement.{png,pdf} atomically: the history's N(w), loading and
 * unloading segments in two colours, with each branch's tangent at its top (slope S, to N = 0:
 * Oliver-Pharr's construction), its axes in length_unit and force_unit ("" for delta and
 * E* delta^2), the figure carrying texts (NULL: none). *branches says how many branches (0: nothing
 * written). */
int analysis_write(const char *dir, const im_indenter *punch, const im_history_row *rows, int count, double delta,
                   double e_star, const char *length_unit, const char *force_unit, const run_figure_texts *texts,
                   int *branches);

/* Why a branch of rows[0..count)'s S is NaN and what to do (measure.h: im_measure_unloading_note), handed to
 * say(user, note) for each such branch: what the front ends say beside the table (findings R3). */
typedef void analysis_say(void *user, const char *note);
int analysis_notes(const im_indenter *punch, const im_history_row *rows, int count, analysis_say *say, void *user);

/* The same table alone at path (a scene's per-member file), atomically, when rows[0..count) hold an
 * unloading branch; *branches says how many (0: nothing written). */
int analysis_write_table(const char *path, const im_indenter *punch, const im_history_row *rows, int count,
                         double delta, double e_star, int *branches);

/* With adhesion: the summary of rows[0..count) (measure.h, im_measure_adhesion) into *summary, under the
 * steps' control. IM_EINVAL for count < 1. */
int analysis_measure_adhesion(const im_history_row *rows, int count, enum im_control control,
                              im_adhesion_summary *summary);

/* The line every front end says of that summary of rows[0..done) (`indent` on stdout, `mpi-indent` on stderr
 * beside its CSV): the pull-off force (or the most tensile load held, and why it is not the pull-off), the
 * jumps, the work lost (or done, or not resolved), and DIR/force_distance.{png,pdf} where dir is not NULL. */
void analysis_describe_adhesion(const im_adhesion_summary *summary, const im_history_row *rows, int done,
                                enum im_control control, const char *dir, char *line, size_t size);

/* With adhesion: the summary of rows[0..count) (analysis_measure_adhesion) into *summary, then
 * DIR/force_distance.{png,pdf}: the approach and retraction segments of N(w) in two colours, the
 * least load marked (as the pull-off, or as the most tensile load held: measure.h, pull_off_force, with
 * the steps' control), carrying texts (NULL: none). IM_EINVAL for count < 1; a figure that cannot be
 * written leaves the summary set. */
int analysis_write_adhesion(const char *dir, const im_history_row *rows, int count, enum im_control control,
                            const char *length_unit, const char *force_unit, const run_figure_texts *texts,
                            im_adhesion_summary *summary);

/* The smooth adhesive theory of punch under law (theory.h, "Adhesion"; adhesion_theory.c): "Maugis-Dugdale
 * sphere" or "Kendall flat punch" into *model and the pull-off point into *pull_off; NULL *model (IM_OK)
 * for the other punches, which have none verified. A theory's status otherwise. */
int adhesion_theory_pull_off(const im_indenter *punch, const im_theory_adhesion *law, const char **model,
                             im_theory_adhesive_point *pull_off);

/* DIR/adhesion_theory.csv atomically: step,approach,load,load_theory per row, load_theory the theory's load
 * at the step's approach on the branch displacement control follows from contact (NaN where the theory
 * has come off; the approach before the jump into contact is not on it). For the punches
 * adhesion_theory_pull_off knows; IM_EINVAL for another. */
int adhesion_theory_write(const char *dir, const im_indenter *punch, const im_theory_adhesion *law,
                          const im_history_row *rows, int count);

/* ---- the history figure (history_figure.c) ---- */

/* What DIR/history.{png,pdf} draws of rows[0..count), as the paper draws it: on a periodic cell
 * (cell_area > 0) the contact fraction A / A0 against the mean pressure N / A0, with eq. (1) under a rigid
 * flat (flat_theory, the surface's interface; NULL: none); a cone or a sphere on the half-space A / A_cone
 * (A / A_Hertz) against N* (Fig. 7), with the theory columns (eqs. (12) and (6); the gamma integral and
 * eq. (3)) when theory is set (elastic, repulsive runs); any other run the load against the approach
 * (Fig. 6) with the smooth punch's load. Units: "" for delta, E* delta^2 and E*. Nothing is written for
 * count < 1; the plot's errors otherwise (IM_EINVAL when no step has a finite point). */
typedef struct history_figure {
    const im_history_row *rows;
    int count;
    const im_indenter *punch;
    double cell_area;
    const im_theory_interface *flat_theory;
    int theory;
    const char *length_unit, *force_unit, *pressure_unit;
    const run_figure_texts *texts; /* what the figure carries (NULL: none) */
} history_figure;
int history_figure_write(const char *dir, const history_figure *h);

/* The axis labels of N against w in the run's units ("" for delta and E* delta^2). */
void history_axis_labels(const char *length_unit, const char *force_unit, char *x_label, char *y_label, size_t size);

/* ---- the periodic mode (periodic.c; solver.h, "Periodic mode") ---- */

/* The cell's area nx ny delta^2: a mean pressure p_m is the load p_m times it. */
double periodic_cell_area(const im_field *surface);

/* The rigid flat pressed on the whole cell (the punch of a periodic run that names none). */
im_indenter periodic_rigid_flat(const im_field *surface);

/* A surface given as one period is not periodic when the rms of its steps across the cell's edges (last
 * column to first, last row to first) exceeds this many times that of the steps inside it. */
#define PERIODIC_EDGE_RATIO 3.0

/* Those two rms into *edge_rms and *inner_rms; 1 when the surface is not periodic by that rule. */
int periodic_edge_mismatch(const im_field *surface, double *edge_rms, double *inner_rms);
/* 1 with the warning in text ("warning: NAME is not periodic: ...", no newline) when the surface is not
 * periodic by that rule: the solver joins its edges as if they met (as ContactMechanics warns); else 0. */
int periodic_warning(const im_field *surface, const char *name, char *text, size_t size);

/* k of eq. (2) fitted to a periodic history under a rigid flat (theory.h: im_theory_fit_k) over its steps
 * with a positive load in partial contact, x = p_m / (h'rms E*), with the ranges of x and of A/A0 it spans.
 * Steps in full contact (A/A0 = 1: every patch) are left out and counted: the erf law reaches 1 only as
 * p_m grows without bound, so they bound k from below without measuring it, and counted as points they
 * shrank k_error (one step at A/A0 0.992 and four at 1: "+- 0.0000 over 5 steps"). */
typedef struct periodic_k_fit {
    im_theory_k_fit fit;
    int points;
    int full_contact;                           /* steps left out: A/A0 = 1 */
    double pressure_ratio[2], area_fraction[2]; /* least and largest */
} periodic_k_fit;
int periodic_fit_k(const im_history_row *rows, int count, double cell_area, double slope_rms, double e_star,
                   periodic_k_fit *out);

/* The fit's outputs, the same wherever it is made: the line `indent --periodic` and `theory --fit-k` print
 * (with the h'rms and its definition's name), and its columns in a CSV (a scene's k_fit.csv, `theory --fit-k
 * --format csv`; the line without its newline): PERIODIC_K_COLUMNS and one row of them, 17 digits, with its newline. */
void periodic_k_fit_describe(const periodic_k_fit *k, double slope_rms, const char *slope_definition, char *text,
                             size_t size);
extern const char PERIODIC_K_COLUMNS[];
void periodic_k_fit_write_row(FILE *stream, const periodic_k_fit *k);
/* Its block in run.json ("k_fit": k, k_error, rms_residual, points, the ranges, the h'rms and its definition,
 * k_linear or null); NULL when out of memory. */
json_t *periodic_k_fit_record(const periodic_k_fit *k, double slope_rms, const char *slope_definition);

/* ---- a surface file's preparation (preparation.c): what `indent` and `surface` do alike ---- */

/* --crop (crop[2] = NX > 0), --align and --detrend, in that order. */
typedef struct surface_preparation {
    int crop[4]; /* X0, Y0, NX, NY */
    enum im_detrend detrend;
    enum im_row_alignment align;
} surface_preparation;

/* Replaces *surface by its crop, then aligns its rows and detrends it; the error names the option. */
int surface_prepare(const surface_preparation *preparation, im_field **surface);
/* 1 with the warning in text ("warning: PATH: --fill invented ...") when more than 5% of the points
 * were filled; else 0. */
int surface_fill_warning(const char *path, long filled, size_t points, char *text, size_t size);
/* 1 with the warning in text ("warning: PATH: no '# Value units:' line: ...") when the reader took a unit
 * the file does not state (info->assumed); else 0. */
int surface_assumption_warning(const char *path, const im_surface_read_info *info, char *text, size_t size);
/* What was done, for records: "plane removed, cropped to 64 x 64 at (0, 0), rows aligned (median)". */
void surface_preparation_describe(const surface_preparation *preparation, long filled, char *text, size_t size);

/* ---- the files of one solved step (step_files.c): `indent --fields/--distributions` and a periodic
 * scene's contact panels and distributions ---- */

/* The fields of a step, DIR/{force,gap,displacement[,plastic]}_NNNN.npy (NNNN = the step, from 1): the
 * plastic depth only with a hardness. */
enum { STEP_FIELDS_MAX = 4 };
extern const char *const STEP_FIELD_PREFIXES[STEP_FIELDS_MAX];
/* How many of them a run writes: all with a hardness (> 0), the first three without. */
int step_field_count(double hardness);

/* The unit of loads and forces: N for Pa and m, else "E*-unit length-unit²" with E* and δ standing in
 * for an empty unit. */
void step_force_unit(const char *e_star_unit, const char *length_unit, char *out, size_t size);

/* What the fields are in, stated in each FILE.npy.json sidecar. */
typedef struct step_units {
    double hardness;         /* > 0: the plastic depth is written too */
    const char *length_unit; /* the surface's ("": delta) */
    const char *force_unit;  /* step_force_unit's */
} step_units;

/* Writes the fields of the run's last step as DIR/PREFIXNNNN.npy with their .npy.json sidecars, each
 * pair under the pair-writers lock (io.h). */
int step_fields_write(const char *dir, im_indentation *run, int step, const step_units *units);
/* One of them, field STEP_FIELD_PREFIXES[which] of step, from a field given whole (mpi-indent's, gathered on
 * rank 0): its units set from units, then written as step_fields_write writes it. */
int step_field_write(const char *dir, int step, int which, im_field *field, const step_units *units);

/* Writes the gap (in gap_scale, IM_MEASURE_GAP_BINS bins) and contact-patch size distributions of the run's last
 * step: PREFIX_{gaps,patches,patch_list}.csv (measure.h: im_measure_write_distributions). */
int step_distributions_write(const char *prefix, im_indentation *run, double gap_scale);

/* Contact frames of steps 1..count drawn from DIR/force_NNNN.npy (as step_fields_write wrote them) into
 * FRAMES/contact_MMMM.png (MMMM = step - 1, the viewer's numbering) with one log force norm (magma, two
 * decades: colormap.h, im_colormap_range_norm) over all of them and, where any step has tension, one tension norm and its bar (frame.c), the
 * smooth punch's contact circle where N* is finite (none for a periodic
 * cell), titled with the step and N* (else N in force_unit), carrying texts as PNG text chunks. */
typedef struct fields_frames {
    const char *dir, *frames;
    const im_history_row *rows;
    int count;
    const im_indenter *punch;
    const char *force_unit;
    const im_png_text *texts;
    int text_count;
} fields_frames;
int fields_frames_write(im_render_context *context, const fields_frames *f);
/* Their pixels per patch: enough for a map of about 384 pixels across (1 to 8; a 64 x 64 grid 6). */
int fields_frames_pixels_per_patch(int nx, int ny);

/* ---- frames of a history (frame.c): what a scene's frames and `indent --frames` draw alike ---- */

/* The range of values (colormap.h) over count fields: the forces, the tensions or the heights whose one
 * norm the frames share. */
im_colormap_range frame_range(im_field *const *fields, int count, im_colormap_values values);

/* Sets *under / *over (left as they are otherwise) where some value of field lies below / above norm (forces: of
 * those > 0, the ones drawn through it; NaN never): the colour bar's extension triangles, by which a clipped range
 * (im_colormap_range_clipped) shows. */
void frame_extends(const im_field *field, const im_colormap *norm, int forces, int *under, int *over);

/* A step's contact map: its force field through norm (tension: through tension) at pixels_per_patch,
 * with the smooth contact circle of circle_radius patches (0 or NaN: none) about (circle_x, circle_y)
 * in patches. */
typedef struct frame_contact {
    const im_field *force;
    const im_colormap *norm, *tension;
    int pixels_per_patch;
    double circle_radius, circle_x, circle_y;
} frame_contact;
int frame_contact_render(im_render_context *context, const frame_contact *contact, im_image *image);

/* What a frame's figure says: its title (e.g. "N* = 400") and its colour bar's norm and label, and the
 * tension's bar beside it (NULL: none; every frame of a history has it where any step has tension, so
 * that the frames keep one size). */
typedef struct frame_words {
    const char *title;
    const im_colormap *norm;
    const char *colorbar_label;
    const im_colormap *tension;
    const char *tension_label;
    const im_png_text *texts; /* PNG text chunks (e.g. the scene's contents); NULL: none */
    int text_count;
    int extend_under, extend_over; /* values lie below / above norm (frame_extends): its triangles */
} frame_words;

/* Writes image as a frame's figure at path (figure.h: one panel, the colour bar with an under triangle on
 * a log norm or where extend_under says, an over triangle where extend_over says, the scale bar, 150 dpi),
 * atomically; kept (not NULL) receives the frame's pixels. */
int frame_figure_write(const im_image *image, const frame_words *words, const char *path, im_image *kept);

/* ---- the units of the history's and the analysis' columns (units.c) ---- */

/* {"COLUMN": "UNIT", ...} for every column of history.csv (history.h), indentation.csv
 * (ANALYSIS_COLUMNS) and the tables a scene writes (results.csv, table1.csv, fig7.csv, sweep.csv,
 * k_fit.csv, flat_k.csv, flat/flat_contact.csv): "1" for numbers without a unit, "s" for seconds, "°"
 * for angles, else built from the run's length,
 * force and pressure units ("m²", "N / m", "N m"). run.json's "units" block holds it as "columns", from
 * which the viewer page heads its tables. NULL when out of memory. */
json_t *column_units_record(const char *length, const char *force, const char *pressure);

/* run.json's "units" block of an indentation history (`indent`; history.h: im_history_units_json): what
 * the numbers of history.csv and the fields are in, for the surface's length unit ("": units of delta)
 * and E*'s unit ("": as given), forces in step_force_unit's, with column_units_record as "columns". NULL
 * when out of memory. */
json_t *indent_units_record(const char *length_unit, const char *e_star_unit, int periodic);

/* ---- the JSON run record (record.c) ---- */

/* What every run record (OUTPUT/run.json of `indent` and of a scene) holds: the program, the
 * library's version, the inputs, and the solver options the run was made with. */
typedef struct run_record_solver {
    const char *quality;  /* preset name, "none" when the tolerance was given without one */
    const char *tol_from; /* "--tol", "--quality", "[solver] tol", "[scene] quality", "default" */
    const im_solver_options *options;
} run_record_solver;

/* A new record {"program", "version", "input": {"kind", "path"[, "path_encoding"]}, "solver":
 * {quality, tol, tol_from, e_star, max_iterations, hardness, crop, window_margin, cascade,
 * precondition}}, to which a front end adds its own blocks; NULL when out of memory. input_kind:
 * "surface", "smooth" or "scene"; input_path may be NULL. */
json_t *run_record_create(const char *program, const char *input_kind, const char *input_path,
                          const run_record_solver *solver);

/* The generator block of a surface file's sidecar (written by `indentmap surface`: the file is a generated
 * surface), a new reference; NULL for a NULL path, a file without a sidecar or a sidecar naming none. */
json_t *surface_sidecar_generator(const char *surface_path);

/* The h'rms definition its generator targeted (IM_SLOPE_*: the sidecar's "slope_definition"), or -1 for a
 * surface no generator made. A generated surface's h'rms in that definition is its target, as a
 * generated family's is: `indent` and scenes over files take it (finding R5). */
int surface_sidecar_slope_definition(const char *surface_path);

/* What run.json and the messages call an h'rms definition (IM_SLOPE_*): "spectral" or "finite differences". */
const char *slope_definition_name(int definition);

/* run.json's "adhesion" block of a run under options' law (solver.h, "Adhesion"): its name, work, range,
 * (peak) stress, the Dugdale zone's length (in the length unit and in patches of side delta) and, for a
 * sphere punch, Maugis's lambda and the law's Tabor mu, all of the law solved on patches of side delta
 * (solver.h: im_adhesion_solved_law); with options' adhesion_zone P > 0 also "zone": P, whether it widened
 * the law, and the law asked ("asked", the same fields). NULL when out of memory or for invalid options. */
json_t *run_record_adhesion_law(const im_solver_options *options, const im_indenter *punch, double delta);

/* With adhesion: the summary of rows[0..done) and DIR/force_distance.{png,pdf} (analysis_write_adhesion)
 * into *summary and the block law (the pull-off, the jumps, the lost work and the figure). The
 * summary's work_done is NaN when nothing was summarised (no step, or an error); returns the
 * analysis' status (a figure that could not be written, say), for the caller to report. */
int run_record_adhesion_summary(json_t *law, const char *dir, const im_history_row *rows, int done,
                                enum im_control control, const char *length_unit, const char *force_unit,
                                const run_figure_texts *texts, im_adhesion_summary *summary);

/* Appends {"key": key, "path": the absolute path (escaped where not UTF-8), "sha256": the file's}
 * to the record's inputs array; the error of a file that cannot be read, IM_ENOMEM. */
int run_record_add_input(json_t *inputs, const char *key, const char *path);

/* Writes the record to DIR/run.json atomically (2-space indentation, 17 digits). */
int run_record_write(const char *dir, const json_t *record);

/* The record as a run starts: "status" "running", then run_record_write; so that a run killed outright
 * (SIGKILL, the OOM killer, a power cut) leaves its inputs and options beside its results (an indent
 * history's rows, a scene's members). run_record_finish writes it again at the end. */
int run_record_start(const char *dir, json_t *record);

/* The record's end: "steps_completed" (where steps_done >= 0: an indentation's steps; a scene counts none),
 * "status" ("ok" or the status's name) and "error" (the message of a failed run, "" else), then
 * run_record_write; a start record whose end cannot be written is removed ("running" would be false). */
int run_record_finish(const char *dir, json_t *record, int steps_done, int status);

/* ---- a run made again from its record (`run --from-record`, `indent --from-record`) ---- */

/* Reads the record file into *root (the caller's reference): IM_EFORMAT naming the file (and the line)
 * when it is not JSON. */
int run_record_load(const char *record, json_t **root);

/* The record root (read from the file `record`) is one of `program` ("indentmap run", "indentmap
 * indent"; `kind` names it in the message) and of this version (another may solve differently in the
 * last bits): IM_EFORMAT for another program, IM_EINVAL for another version, each naming the file. */
int run_record_check_origin(const char *record, const json_t *root, const char *program, const char *kind);

/* The input `path` (under `key`) still has the SHA-256 `recorded` (hex) that `record` states:
 * IM_EINVAL naming the file and both checksums when it has changed, the read's error when it cannot be
 * read. */
int run_record_check_input(const char *record, const char *key, const char *path, const char *recorded);

#endif
