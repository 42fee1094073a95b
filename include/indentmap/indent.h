/* indentmap/indent.h: one indentation run into its output folder, as `indentmap indent` makes it.
 *
 * Entry points:
 *   im_indent_options_default   the options of `indentmap indent` given nothing but the targets
 *   im_indent_run               the run: the surface read and prepared, the steps solved, every file
 *
 * The run writes into options->out what the program writes there (docs/solver.md): history.csv (one
 * line per step, synced as it is solved), run.json, index.html, with fields the step fields
 * ({force,gap,displacement[,plastic]}_NNNN.npy), with frames frames/contact_NNNN.png, with
 * distributions distributions_NNNN_*.csv, and after the steps the history figure, the indentation
 * analysis of an unloading history, adhesion's force-distance figure and theory and run.json's k fit
 * of a periodic cell. The folder is locked while the run writes there (out/.lock) and an earlier
 * run's step files are removed first; inputs are never written over.
 *
 * Misuse (status.h): IM_EINVAL for a NULL options, out or targets and a target_count outside
 * 1..IM_HISTORY_MAX_STEPS (history.h).
 * Threads: one run at a time in a process (the solver's FFTW plans and OpenMP workers are the
 * process's); the callbacks are called from the calling thread, one at a time. The library prints
 * nothing: the run's lines go to options->log.
 */
#ifndef INDENTMAP_INDENT_H
#define INDENTMAP_INDENT_H

#include "indentmap/formats.h"
#include "indentmap/indenter.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"

#include <signal.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct im_indent_options {
    /* The surface: a file, or (surface_path NULL) a flat nx x ny grid of patches of side delta in the
     * length unit read.set.lateral. */
    const char *surface_path;
    int nx, ny;
    double delta;
    im_surface_read_options read; /* how surface_path is read (formats.h) */
    int crop[4];                  /* X0, Y0, NX, NY of the block indented; NX = 0: the whole surface */
    enum im_row_alignment align;  /* scan lines, before the detrending */
    enum im_detrend detrend;
    int slope_definition; /* the theory's h'rms: IM_SLOPE_*, or -1: spectral for a flat, generated or
                             periodic surface, forward differences for a measured one */
    /* The punch: punch.kind IM_PUNCH_PROFILE takes its shape from profile_path (formats.h:
     * im_profile_read), keeping punch's axis. With solver.periodic and punch_given 0: a rigid flat on
     * the whole cell. */
    im_indenter punch;
    const char *profile_path;
    int punch_given;
    /* The steps: targets[0..target_count) under control; with pressures (IM_CONTROL_LOAD on a periodic
     * cell) mean pressures, the loads being these times the cell's area. */
    enum im_control control;
    const double *targets;
    int target_count;
    int pressures;
    im_solver_options solver;
    const char *quality;     /* the preset solver.tol came from, for run.json; NULL: none */
    int tol_given;           /* 1: solver.tol was given (run.json says "--tol") */
    const char *e_star_unit; /* the unit of E*, for the records (NULL or "": none) */
    /* The outputs */
    const char *out;
    int fields;         /* the step fields */
    int frames;         /* frames/contact_NNNN.png (implies fields; needs OpenGL) */
    int page_embed;     /* index.html carries its images as data URIs */
    int distributions;  /* the gap and patch distributions of every step */
    int backend;        /* the frames' renderer: im_render_backend of render.h (0: auto) */
    int no_space_check; /* 1: skip the check, before any step, of the free disk against the step files'
                           estimated size (fields, frames; `indentmap indent` sets it from IM_NO_SPACE_CHECK) */
    /* The record: run.json's "arguments" (the options of the run as recorded, UTF-8; NULL: none; with
     * arguments_escaped 1 when one was not UTF-8), "from_record" (the record the run was made from,
     * NULL: none), and the figures' Command text (NULL: none). */
    const char *const *arguments;
    int argument_count;
    int arguments_escaped;
    const char *from_record;
    const char *command;
    /* Reports: stop (may be NULL) holds a signal's number when one asked to stop: the run stops before
     * the next step (a solve is never cut short) with IM_EINTERRUPTED. log gets each line the run has
     * to say: IM_LOG_INFO the surface's and each step's line and what was written after the steps
     * (`indentmap indent` prints them on stdout), IM_LOG_WARNING the warnings ("warning: ...") and the
     * failures of what follows the steps (the analysis, the figures), which leave the run's status
     * alone. progress is called with stage "steps" after each step's files. NULL: dropped. */
    const volatile sig_atomic_t *stop;
    im_log_fn log;
    im_progress_fn progress;
    void *user;
} im_indent_options;

/* A cone of 80 degrees on a flat 512 x 512 surface of delta 1 into output/indent, under displacement
 * control, the solver's defaults (solver.h), no targets (set targets and target_count). */
im_indent_options im_indent_options_default(void);

/* Makes the run options ask for (above). Returns IM_OK, or the first failure: what the options or
 * the inputs refuse (IM_EINVAL, IM_EIO, IM_EFORMAT naming the file or the option as the program calls
 * it, "--radius"), a step that fails (its status, "step I of N (...)": the steps before it are
 * written), IM_EINTERRUPTED. run.json and index.html say what happened in every case where the folder
 * was opened. */
int im_indent_run(const im_indent_options *options);

#ifdef __cplusplus
}
#endif

#endif
