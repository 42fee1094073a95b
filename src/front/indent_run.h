/* Internal: an indentation run into its folder, the steps and the files `indentmap indent` writes
 * (src/cli/indent.c is its options and reports).
 *
 * Entry points:
 *   indent_files_claims  whether a name in the folder is one the run writes (run_folder.h's claims)
 *   indent_files_clear   an earlier run's step files, analysis files and frames removed
 *   indent_run_steps     the steps solved, measured and written (fields, distributions, history.csv) */
#ifndef INDENTMAP_FRONT_INDENT_RUN_H
#define INDENTMAP_FRONT_INDENT_RUN_H

#include "front/front.h"

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

/* The steps of a run, solved in order on run (im_indentation) into dir. */
typedef struct indent_run_plan {
    const char *dir;
    const im_indenter *punch;
    const im_theory_interface *rough; /* the theory columns' interface; NULL: none (a periodic cell) */
    const double *targets;
    int count;
    const char *target_name;        /* "approach", "load", "mean_gap": the failure message names the target */
    indent_files files;             /* fields and distributions of each step */
    step_units units;               /* what the fields are in */
    double gap_scale;               /* the distributions' gap unit */
    int (*stop)(const void *state); /* NULL, or a signal's number (0: none): stop before the next step */
    void (*stepped)(const im_history_row *rows, int i, const void *state); /* NULL, or after step i's files */
    const void *state;
} indent_run_plan;

/* Solves the targets in order, each step measured (history.h: im_history_measure into rows[i], rows
 * holding plan->count), its fields and distributions written, then its line appended to history
 * (started by the caller), then plan->stepped called. *done: the steps whose files are all written.
 * Stops at the first failure with the error given the step's context ("step I of N (TARGET V; the
 * D steps before are in DIR/history.csv)"), and before a step once plan->stop says a signal asked
 * to: IM_EINTERRUPTED "interrupted by signal S" with that context. A solve is never cut short. */
int indent_run_steps(const indent_run_plan *plan, im_indentation *run, history_file *history, im_history_row *rows,
                     int *done);

#endif
