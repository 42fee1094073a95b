/* Internal: an indentation run into its folder, the steps and the files `indentmap indent` writes
 * (src/cli/indent.c is its options and reports).
 *
 * Entry points:
 *   indent_files_claims  whether a name in the folder is one the run writes (run_folder.h's claims)
 *   indent_files_clear   an earlier run's step files, analysis files and frames removed
 *   indent_files_earlier_bytes  the bytes those files hold
 *   indent_run_steps     the steps solved, measured and written (fields, distributions, history.csv)
 *   indent_run_check     the folder and wisdom file apart from the inputs, before any work
 *   indent_run_record    run.json's record of the run (indent_record.c)
 *   indent_run_results   what follows the steps: frames, analyses, figures, k fit (indent_results.c)
 * indent.c, the public im_indent_run (indentmap/indent.h), runs them in order. */
#ifndef INDENTMAP_FRONT_INDENT_RUN_H
#define INDENTMAP_FRONT_INDENT_RUN_H

#include "front/front.h"
#include "front/run_folder.h"

#include "indentmap/indent.h"

#include <stdarg.h>

/* What a run writes into its folder: history.csv, run.json, index.html, the analysis' files (the
 * history figure, indentation.csv, the load-displacement and force-distance figures) and, for the steps
 * 1..steps, with fields {force,gap,displacement[,plastic]}_NNNN.npy and their .npy.json sidecars,
 * with distributions distributions_NNNN_{gaps,patches,patch_list}.csv. */
typedef struct indent_files {
    int fields;
    double hardness; /* > 0: plastic_NNNN.npy too */
    int distributions;
    int steps;
} indent_files;

/* Whether the file name (without folder) is one the run of files (an indent_files) writes. */
int indent_files_claims(const char *name, const void *files);

/* Removes what an earlier run left in dir that this one would not replace: every step field file and
 * distribution (four or more digits), the analysis' files and frames/contact_NNNN.png. Inputs are
 * kept (io.h: the output guard names them). Call it while holding the folder's lock. IM_EIO naming a
 * file that cannot be removed or a folder that cannot be listed. */
int indent_files_clear(const char *dir);

/* The bytes held in dir by the files indent_files_clear removes (0 where dir does not exist): the room
 * a run into dir gets back before writing its own. */
double indent_files_earlier_bytes(const char *dir);

/* The steps of a run, solved in order on run (im_indentation) into dir. */
typedef struct indent_run_plan {
    const char *dir;
    const im_indenter *punch;
    const im_theory_interface *rough; /* the theory columns' interface; NULL: none (a periodic cell) */
    const double *targets;
    int count;
    double tol;              /* the solver's tolerance: area_ratio is NaN at a load zero to it (im_history_measure) */
    const char *target_name; /* "approach", "load", "mean_gap": the failure message names the target */
    indent_files files;      /* fields and distributions of each step */
    step_units units;        /* what the fields are in */
    double gap_scale;        /* the distributions' gap unit */
    int (*stop)(const void *state); /* NULL, or a signal's number (0: none): stop before the next step */
    void (*stepped)(const im_history_row *rows, int i, const void *state); /* NULL, or after step i's files */
    const void *state;
} indent_run_plan;

/* Solves the targets in order, each step measured (history.h: im_history_measure into rows[i], rows
 * holding plan->count), its fields and distributions written, then its line appended to history
 * (started by the caller), then plan->stepped called. *done: the steps whose files are all written.
 * Stops at the first failure with the error given the step's context ("step I of N (TARGET V; the
 * D steps before are in DIR/history.csv)", "the step before is in ...", "no step before it was
 * solved"), and before a step once plan->stop says a signal asked
 * to: IM_EINTERRUPTED "interrupted by signal S" with that context. A solve is never cut short. */
int indent_run_steps(const indent_run_plan *plan, im_indentation *run, history_file *history, im_history_row *rows,
                     int *done);

/* An im_indent_run in progress: its options and what it derived from them and the surface. */
typedef struct indent_run_state {
    const im_indent_options *options;
    int smooth;               /* no surface file: a flat grid */
    indent_files files;       /* what the run writes into out */
    im_indenter punch;        /* as solved: the profile's, the periodic cell's rigid flat */
    im_profile *profile;      /* the punch borrows it */
    double *targets;          /* the loads of pressures */
    double surface_delta;     /* the patch side as solved */
    double cell_area;         /* periodic: nx ny delta^2 */
    double gap_scale;         /* the distributions' gaps' unit: the surface's h_rms (delta when flat) */
    double theory_slope;      /* the theory's h'rms */
    int slope_definition;     /* IM_SLOPE_* */
    const char *slope_reason; /* why that definition, for run.json */
    char length_unit[16];     /* the surface's, as solved ("" in units of delta) */
    char force_unit[40];      /* of loads and forces */
    long filled;              /* missing points filled on reading */
    im_surface_read_info read_info;
    run_figure_texts figure_texts; /* what every figure carries */
} indent_run_state;

/* One line to options->log (none without one). */
void indent_say(const indent_run_state *state, im_log_level level, const char *format, ...)
    __attribute__((format(printf, 3, 4)));

/* What the step lines, messages and run.json call the targets: "approach", "load" or "mean_gap". */
const char *indent_target_name(enum im_control control);

/* The folder's rules for options (run_folder.h), files: what the run writes there. */
run_folder_rules indent_folder_rules(const im_indent_options *options, const indent_files *files);

/* Refuses, before any work, an output folder whose outputs would replace the surface file or the
 * profile, and a wisdom file that is an input or an output (run_folder.h: run_folder_check). */
int indent_run_check(const im_indent_options *options);

/* run.json's record of the run on surface (front.h: run_record_create), without its inputs; NULL when
 * out of memory. indent_run_record_inputs adds "inputs": the surface and profile files with their
 * SHA-256, as a scene's record has them (an empty list for a flat surface without a profile). */
json_t *indent_run_record(const indent_run_state *state, const im_field *surface, const im_indentation *run);
int indent_run_record_inputs(const im_indent_options *options, json_t *record);

/* What indent's history figure draws of a run under solver's options (front.h: history_figure's choices): a
 * periodic cell's contact fraction (cell_area) with eq. (1) of rough under the rigid flat (no punch_given), the
 * theory columns of an elastic, repulsive run; the caller sets the rows, the punch, the units and the texts.
 * `indent` and mpi-indent draw it alike. */
history_figure indent_history_figure(const im_solver_options *solver, int punch_given, double cell_area,
                                     const im_theory_interface *rough);

/* After the steps rows[0..done) (also after a failure, *status): the frames (a failure is the run's
 * when it had none), the indentation or adhesion analysis, the history figure, the k fit, each said
 * in record. rough: the theory's interface. */
void indent_run_results(indent_run_state *state, const im_theory_interface *rough, const im_history_row *rows,
                        int done, im_render_context *context, json_t *record, int *status);

#endif
