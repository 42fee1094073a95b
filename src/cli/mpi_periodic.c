/* indentmap mpi-indent's histories over MPI ranks: --periodic, indent --periodic's history of a rigid flat on
 * a periodic cell (mpi.h: im_mpi_flat_contact_step), and the half-space's approaches or loads by a punch, with
 * plastic memory and adhesion (im_mpi_indentation_step), written in indent's schema: the history's columns (history.h) on stdout and
 * in DIR/history.csv, DIR/run.json, and indent's figures (the history figure, the analyses', --frames' contact maps)
 * drawn on rank 0 by indent's writers from what it gathers, with front.h's pieces. Built only with MPI. */
#include "cli/mpi_indent.h"

#if IM_HAVE_MPI

#include "cli/cli.h"
#include "io/json_file.h"
#include "core/error_keep.h"
#include "front/front.h"
#include "front/indent_run.h"
#include "mpi/agree.h"

#include "indentmap/history.h"
#include "indentmap/io.h"
#include "indentmap/measure.h"
#include "indentmap/status.h"

#include <errno.h>
#include <fcntl.h>
#include <jansson.h>
#include <limits.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

typedef struct history_run {
    const mpi_indent_options *o;
    im_mpi_solver *solver;
    im_mpi_flat_contact *cell;       /* --periodic */
    im_mpi_indentation *indentation; /* the half-space */
    int rank;
    im_field shape;    /* the surface's grid and patch side (no data) */
    im_indenter punch; /* the rigid flat on the whole cell, or the half-space's punch */
    double *targets;   /* loads N (from the mean pressures) or mean gaps */
    im_history_row *rows;
    history_file history;      /* rank 0, with --out */
    json_t *record;            /* rank 0, with --out */
    double slope_rms;          /* rank 0: the surface's spectral h'rms */
    im_theory_interface rough; /* rank 0, the half-space: the theory columns' interface (h'rms above) */
    char force_unit[40];       /* of loads and forces (units of E* delta^2) */
    run_figure_texts texts;    /* rank 0, with --out: what the figures carry (indent's, with this Command) */
    im_render_context *render; /* rank 0, --frames: opened before any step is solved, as indent's */
    int record_failed;         /* rank 0: run.json could not be written (said once) */
} history_run;

/* Rank 0: the whole field of this rank's rows of values (caller frees; NULL elsewhere). Collective. */
static int gather_whole(const history_run *run, const double *values, im_field **whole)
{
    *whole = NULL;
    return im_mpi_gather_map(run->solver, values, 1, whole);
}

/* The surface's h'rms (spectral: indent's default for a periodic cell and a generated surface) and the theory
 * columns' interface of the half-space (indent's), or a cell's warning when its edges do not meet, on rank 0
 * from the gathered heights. */
static int measure_surface(history_run *run, const double *heights)
{
    im_field *surface;
    int status = gather_whole(run, heights, &surface);
    if (status == IM_OK && run->rank == 0) {
        char warning[8192];
        if (run->o->periodic && periodic_warning(surface, run->o->surface_file ? run->o->surface_file : "the surface",
                                                 warning, sizeof warning))
            fprintf(stderr, "indentmap: %s\n", warning);
        status = im_surface_slope_rms(surface, IM_SLOPE_SPECTRAL, &run->slope_rms);
        run->rough = im_theory_interface_default(run->slope_rms);
        run->rough.e_star = run->o->solver.e_star;
    }
    im_field_free(surface);
    return mpi_collective_status(MPI_COMM_WORLD, status);
}

/* The step list as the cell takes it: loads N = p_m A0 from mean pressures, or the mean gaps. */
static int prepare_targets(history_run *run)
{
    const mpi_indent_options *o = run->o;
    const int pressures = o->periodic && o->control == IM_CONTROL_LOAD; /* --pressure */
    run->targets = malloc(sizeof(double) * (size_t)o->target_count);
    run->rows = calloc((size_t)o->target_count, sizeof *run->rows);
    if (!run->targets || !run->rows)
        return im_fail(IM_ENOMEM, "a history of %d steps", o->target_count);
    for (int i = 0; i < o->target_count; ++i)
        run->targets[i] = pressures ? o->targets[i] * periodic_cell_area(&run->shape) : o->targets[i];
    return IM_OK;
}

/* The solver's options with --adhesion-work's law (the cell's steps'; the solver's have none). */
static im_solver_options adhesive_options(const mpi_indent_options *o)
{
    im_solver_options adhesive = o->solver;
    adhesive.adhesion_work = o->adhesion_work;
    adhesive.adhesion_range = o->adhesion_range;
    adhesive.adhesion_law = o->adhesion_law;
    adhesive.adhesion_zone = o->adhesion_zone;
    return adhesive;
}

/* run.json's "adhesion" block of an adhesive history (no smooth theory beside it: indent's is a cell's, or a
 * smooth punch's, which indent draws), or null. */
static json_t *adhesion_block(const history_run *run)
{
    if (!(run->o->adhesion_work > 0))
        return json_null();
    const im_solver_options adhesive = adhesive_options(run->o);
    json_t *law = run_record_adhesion_law(&adhesive, &run->punch, run->shape.delta);
    json_object_set_new(law, "theory", json_null());
    return law;
}

/* run.json's blocks beside the common record: indent --periodic's (surface, punch, control, targets,
 * periodic, threads, history, theory_slope_rms, units, inputs) and the ranks. */
static int add_blocks(const history_run *run, json_t *root)
{
    const mpi_indent_options *o = run->o;
    json_t *targets = json_array();
    for (int i = 0; i < o->target_count; ++i)
        json_array_append_new(targets, json_real(run->targets[i]));
    json_t *blocks = json_pack(
        "{s:{s:s, s:i, s:i, s:f, s:s}, s:{s:s, s:f}, s:s, s:o, s:b, s:i, s:s, s:{s:f, s:s, s:s}, s:o, s:n, s:o}",
        "surface", "source", o->surface_file ? o->surface_file : "synthesised over the ranks", "nx", run->shape.nx,
        "ny", run->shape.ny, "delta", run->shape.delta, "unit", "", "punch", "kind", im_punch_name(run->punch.kind),
        "radius", run->punch.radius, "control", indent_target_name(o->control), "targets", targets, "periodic",
        o->periodic, "threads", omp_get_max_threads(), "history", "history.csv", "theory_slope_rms", "value",
        run->slope_rms, "definition", "spectral", "chosen_by",
        o->periodic ? "default: a periodic cell" : "mpi-indent: spectral (indent's default for a generated surface)",
        "units", indent_units_record("", "", 1), "indentation", "adhesion", adhesion_block(run));
    if (!blocks)
        return im_fail(IM_ENOMEM, "run.json: out of memory");
    json_t *punch = json_object_get(blocks, "punch");
    if (run->punch.kind != IM_PUNCH_SPHERE && run->punch.kind != IM_PUNCH_FLAT) /* as indent's record: */
        json_object_del(punch, "radius");                                       /* a cone's angle, a profile's file */
    if (run->punch.kind == IM_PUNCH_CONE)
        json_object_set_new(punch, "alpha_degrees", json_real(run->punch.alpha_degrees));
    if (o->profile_path) {
        char profile[4 * PATH_MAX + 1];
        im_path_utf8(o->profile_path, profile, sizeof profile);
        json_object_set_new(punch, "profile", json_string(profile));
    }
    int ranks;
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    if (!o->surface_file)
        json_object_set_new(blocks, "seed", json_unsigned(o->surface.seed));
    json_object_set_new(blocks, "ranks", json_integer(ranks));
    json_object_set_new(blocks, "fields", json_array()); /* none until the last step's are written */
    json_object_update(root, blocks);
    json_decref(blocks);
    json_t *inputs = json_array();
    int status = inputs && o->surface_file ? run_record_add_input(inputs, "--surface", o->surface_file) : IM_OK;
    if (status == IM_OK && inputs && o->profile_path)
        status = run_record_add_input(inputs, "--profile", o->profile_path);
    json_object_set_new(root, "inputs", inputs);
    return status;
}

/* Rank 0, with --out: the folder, history.csv's column line and the record. */
static int start_outputs(history_run *run)
{
    const mpi_indent_options *o = run->o;
    if (run->rank != 0 || !o->out)
        return IM_OK;
    int status = im_make_directories(o->out);
    run_record_solver solver = {.quality = o->tol_given ? "none" : IM_QUALITY_DEFAULT,
                                .tol_from = o->tol_given ? "--tol" : "default",
                                .options = &o->solver};
    if (status == IM_OK)
        run->record = run_record_create("indentmap mpi-indent", "surface", o->surface_file, &solver);
    if (status == IM_OK && !run->record)
        status = im_fail(IM_ENOMEM, "run.json: out of memory");
    if (status == IM_OK)
        status = add_blocks(run, run->record);
    const im_png_text command = {"Command", o->command};
    if (status == IM_OK) /* the figures' texts: indent's, from the record's inputs */
        status = run_figure_texts_make(&command, o->command ? 1 : 0, json_object_get(run->record, "inputs"),
                                       &run->texts);
    if (status == IM_OK) /* an earlier run's step files, figures and frames, as indent */
        status = indent_files_clear(o->out);
    if (status == IM_OK && o->frames)
        status = cli_render_open(IM_RENDER_AUTO, &run->render);
    return status == IM_OK ? history_start(o->out, &run->history) : status;
}

/* This rank's rows of the last step's (net) pressure. */
static const double *last_pressure(const history_run *run)
{
    return run->cell ? im_mpi_flat_contact_pressure(run->cell) : im_mpi_indentation_pressure(run->indentation);
}

/* Rank 0: a line of the history on stdout, written to the descriptor itself. mpirun signalled itself stops
 * reading its ranks' output: once a signal is caught, a write that would block (the pipe or pty full) gives way
 * to the interruption's record and the rest of the row is dropped (it is in history.csv): stdout is then made
 * non-blocking, checked before every write, so neither a write begun after the signal nor the rest of a row the
 * signal cut short (a partial count, not EINTR) can block until mpirun's SIGKILL; a reader that still reads
 * gets the whole row. stdio would keep the row and block again at exit. */
static void print_line(const char *line)
{
    size_t left = strlen(line);
    int flags = -1; /* stdout's flags, restored (a singleton's stdout may be a terminal the shell shares) */
    if (!cli_stop_signal)
        fflush(stdout); /* anything printed through stdio before comes first */
    while (left > 0) {
        if (cli_stop_signal && flags < 0) {
            flags = fcntl(STDOUT_FILENO, F_GETFL);
            if (flags < 0 || fcntl(STDOUT_FILENO, F_SETFL, flags | O_NONBLOCK) != 0)
                break; /* cannot tell whether the write would block: the row is in history.csv */
        }
        const ssize_t written = write(STDOUT_FILENO, line, left);
        if (written > 0) {
            line += written;
            left -= (size_t)written;
        } else if (written == 0 || errno != EINTR) {
            break; /* stdout gone, or full once interrupted (EAGAIN): the live view loses the row, not the run */
        }
    }
    if (flags >= 0)
        fcntl(STDOUT_FILENO, F_SETFL, flags);
}

/* Step i: solved on every rank, its contact patches counted on rank 0 from the gathered forces, its row
 * measured (history.h), printed and appended to DIR/history.csv on rank 0. */
static int run_step(history_run *run, int i)
{
    im_history_row *row = &run->rows[i];
    int status = run->cell ? im_mpi_flat_contact_step(run->cell, run->o->control, run->targets[i], &row->result)
                           : im_mpi_indentation_step(run->indentation, run->targets[i], &row->result);
    im_field *force = NULL;
    if (status == IM_OK)
        status = gather_whole(run, last_pressure(run), &force);
    if (status == IM_OK && run->rank == 0) /* the theory columns are the half-space's */
        status = im_history_measure(&run->punch, run->cell ? NULL : &run->rough, NULL, run->o->solver.tol, run->rows,
                                    i);
    im_contact_patches patches = {0};
    const step_units units = {run->o->solver.hardness, "", run->force_unit};
    if (status == IM_OK && run->rank == 0 && run->o->frames) /* what the frames are drawn from, as indent's */
        status = step_field_write(run->o->out, i + 1, 0, force, &units);
    if (status == IM_OK && run->rank == 0 && (status = im_measure_contact_patches(force, &patches, NULL)) == IM_OK) {
        row->patches = patches.patches;
        row->perimeter = patches.perimeter;
        char line[IM_HISTORY_LINE_MAX];
        im_history_format(row, line, sizeof line);
        print_line(line);
    }
    if (status == IM_OK && run->rank == 0 && run->o->out)
        status = history_append(&run->history, row);
    im_field_free(force);
    return mpi_collective_status(MPI_COMM_WORLD, status);
}

static void say_note(void *user, const char *note)
{
    (void)user;
    fprintf(stderr, "indentation analysis: %s\n", note);
}

/* Rank 0: the half-space's Oliver-Pharr analysis of the unloading branches (indentation.csv and
 * load_displacement.{png,pdf}), as indent's, and why a branch's S is NaN, on stderr beside the CSV; said, not
 * the run's error, when it fails. */
static void write_analysis(const history_run *run, int done)
{
    int branches = 0;
    int status = analysis_write(run->o->out, &run->punch, run->rows, done, run->shape.delta, run->o->solver.e_star,
                                "", run->force_unit, &run->texts, &branches);
    if (status == IM_OK && branches > 0) {
        json_object_set_new(run->record, "indentation", json_string("indentation.csv"));
        status = analysis_notes(&run->punch, run->rows, done, say_note, NULL);
    }
    if (status != IM_OK)
        fprintf(stderr, "indentmap: indentation analysis: %s\n", im_last_error());
}

/* Rank 0: DIR/history.{png,pdf} of the steps done, as indent draws it; said, not the run's error, when it fails. */
static void write_history_figure(const history_run *run, int done)
{
    const im_solver_options options = adhesive_options(run->o);
    history_figure figure = indent_history_figure(&options, run->o->punch_given, periodic_cell_area(&run->shape),
                                                  &run->rough);
    figure.rows = run->rows;
    figure.count = done;
    figure.punch = &run->punch;
    figure.length_unit = figure.pressure_unit = "";
    figure.force_unit = run->force_unit;
    figure.texts = &run->texts;
    if (history_figure_write(run->o->out, &figure) != IM_OK)
        fprintf(stderr, "indentmap: history figure: %s\n", im_last_error());
}

/* Rank 0, with adhesion: the pull-off, the jumps and the lost work (front.h), with --out in run.json's
 * "adhesion" block and force_distance.{png,pdf}, and said in indent's words (analysis_describe_adhesion) on
 * stderr: stdout is the history's CSV (findings R7: the summary was in run.json only). */
static void summarise_adhesion(const history_run *run, int done)
{
    im_adhesion_summary summary = {.work_done = NAN};
    int status = IM_OK;
    if (run->record)
        status = run_record_adhesion_summary(json_object_get(run->record, "adhesion"), run->o->out, run->rows, done,
                                             run->o->control, "", run->force_unit, &run->texts, &summary);
    else if (done >= 1 && (status = analysis_measure_adhesion(run->rows, done, run->o->control, &summary)) != IM_OK)
        summary.work_done = NAN;
    if (status != IM_OK)
        fprintf(stderr, "indentmap: adhesion summary: %s\n", im_last_error());
    if (isnan(summary.work_done))
        return;
    char line[8192];
    analysis_describe_adhesion(&summary, run->rows, done, run->o->control, run->o->out, line, sizeof line);
    fprintf(stderr, "%s\n", line);
}

/* Rank 0, with --out and no adhesion: the half-space's analysis, or a cell's k of eq. (2) (elastic steps only, as
 * indent; eq. (2) is the repulsive law). */
static void write_repulsive_results(history_run *run, int done)
{
    periodic_k_fit k;
    if (!run->o->periodic)
        write_analysis(run, done);
    else if (!(run->o->solver.hardness > 0) && periodic_fit_k(run->rows, done, periodic_cell_area(&run->shape),
                                                              run->slope_rms, run->o->solver.e_star, &k) == IM_OK)
        json_object_set_new(run->record, "k_fit", periodic_k_fit_record(&k, run->slope_rms, "spectral"));
}

/* Rank 0, with --out: DIR/run.json of the done steps and what the record holds so far. After a failed or
 * interrupted step the step's error stays the run's: a record that cannot be written is said on its own line. */
static int record_steps(history_run *run, int done, int status)
{
    if (run->rank != 0 || !run->record || run->record_failed)
        return status;
    kept_error kept;
    error_keep(&kept);
    const int recorded = run_record_finish(run->o->out, run->record, done, status);
    run->record_failed = recorded != IM_OK;
    if (status == IM_OK)
        return recorded;
    if (recorded != IM_OK)
        fprintf(stderr, "indentmap: %s\n", im_last_error());
    return error_restore(&kept, status);
}

/* Rank 0: the adhesion's summary, and with --out the other results, the record's end and the history figure. */
static int finish_record(history_run *run, int done, int status)
{
    if (run->rank != 0)
        return status;
    kept_error kept;
    error_keep(&kept);
    if (run->o->adhesion_work > 0)
        summarise_adhesion(run, done);
    if (status != IM_OK)
        error_restore(&kept, status); /* the step's error, not the summary's */
    if (!run->record)
        return status;
    if (!(run->o->adhesion_work > 0))
        write_repulsive_results(run, done);
    if (status != IM_OK)
        error_restore(&kept, status); /* the step's error, not the fit's */
    /* the record (again, with the analyses' keys, after an interruption) before the figure: docs/mpi.md */
    const int outcome = record_steps(run, done, status);
    error_keep(&kept); /* the step's or the record's error, not the figure's */
    write_history_figure(run, done);
    return outcome == IM_OK ? IM_OK : error_restore(&kept, outcome);
}

/* DIR/force.npy and gap.npy of the last step, and run.json's "fields" naming them. Collective. */
static int write_last_fields(const history_run *run)
{
    int y0, rows;
    im_mpi_solver_rows(run->solver, &y0, &rows);
    double *gap = malloc(sizeof(double) * ((size_t)rows * run->shape.nx + 1));
    int status = !gap        ? im_fail(IM_ENOMEM, "the last step's gap")
                 : run->cell ? im_mpi_flat_contact_gap(run->cell, gap)
                             : im_mpi_indentation_gap(run->indentation, gap);
    status = mpi_collective_status(MPI_COMM_WORLD, status);
    if (status == IM_OK)
        status = mpi_indent_write_fields(run->o, run->solver, last_pressure(run), gap);
    free(gap);
    if (status == IM_OK && run->record) /* rank 0: the record names the fields that are this run's */
        json_object_set_new(run->record, "fields",
                            run->o->map_factor > 0 ? json_pack("[sss]", "force.npy", "gap.npy", "force_map.npy")
                                                   : json_pack("[ss]", "force.npy", "gap.npy"));
    return status;
}

/* Rank 0, --frames: DIR/frames/contact_NNNN.png of the steps done from their force files (front.h:
 * fields_frames_write, indent's): a failure is the run's error when it had none. */
static int draw_frames(const history_run *run, int done, int status)
{
    if (run->rank != 0 || !run->o->frames)
        return status;
    char folder[PATH_MAX];
    kept_error kept;
    error_keep(&kept);
    const fields_frames frames = {run->o->out, folder,          run->rows,        done,
                                  &run->punch, run->force_unit, run->texts.texts, run->texts.count};
    int drawn = im_path_join(folder, sizeof folder, run->o->out, "frames");
    if (drawn == IM_OK)
        drawn = fields_frames_write(run->render, &frames);
    if (drawn != IM_OK)
        im_fail_context(drawn, "--frames");
    if (status == IM_OK)
        return drawn;
    if (drawn != IM_OK)
        fprintf(stderr, "indentmap: %s\n", im_last_error());
    return error_restore(&kept, status); /* the step's error */
}

/* The signal that asked to stop on any rank (SIGTERM from mpirun, or sent to one rank alone), 0 if none: every
 * rank stops before the same step. Collective. */
static int stop_agreed(const mpi_indent_options *o)
{
    int local = o->solver.stop ? (int)*o->solver.stop : 0, any;
    MPI_Allreduce(&local, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    return any;
}

static int run_steps(history_run *run)
{
    const mpi_indent_options *o = run->o;
    int status = IM_OK, done = 0;
    if (run->rank == 0) {
        print_line(im_history_columns());
        print_line("\n");
    }
    while (done < o->target_count) {
        const int signal = stop_agreed(o);
        status = signal ? im_fail(IM_EINTERRUPTED, "interrupted by signal %d", signal) : run_step(run, done);
        if (status != IM_OK)
            break;
        ++done;
    }
    if (status != IM_OK) /* done: the steps whose rows are written */
        im_fail_context(status, "step %d of %d (%s %g)", done + 1, o->target_count, o->targets_option,
                        o->targets[done]);
    if (status == IM_EINTERRUPTED) /* mpirun kills the ranks a second after passing a signal on: the record first */
        status = record_steps(run, done, status);
    status = mpi_collective_status(MPI_COMM_WORLD, draw_frames(run, done, status));
    if (status == IM_OK && o->out)
        status = write_last_fields(run);
    return mpi_collective_status(MPI_COMM_WORLD, finish_record(run, done, status));
}

/* The cell (--periodic) or the half-space's indentation, with the options' adhesion. Collective. */
static int prepare_contact(history_run *run, const double *heights)
{
    const mpi_indent_options *o = run->o;
    const im_solver_options adhesive = adhesive_options(o);
    if (!o->periodic)
        return im_mpi_indentation_create(run->solver, heights, &o->punch, o->control,
                                         steps_largest(o->targets, o->target_count), &adhesive, &run->indentation);
    int status = im_mpi_flat_contact_create(run->solver, heights, &run->cell);
    if (status == IM_OK && o->adhesion_work > 0)
        status = im_mpi_flat_contact_adhesion(run->cell, &adhesive);
    return status;
}

int mpi_indent_history(const mpi_indent_options *o, im_mpi_solver *solver, const double *heights)
{
    history_run run = {.o = o,
                       .solver = solver,
                       .history = {.fd = -1},
                       .shape = {.nx = o->surface.nx, .ny = o->surface.ny, .delta = 1.0}};
    MPI_Comm_rank(MPI_COMM_WORLD, &run.rank);
    step_force_unit("", "", run.force_unit, sizeof run.force_unit);
    run.punch = o->periodic ? periodic_rigid_flat(&run.shape) : o->punch;
    int status = mpi_collective_status(MPI_COMM_WORLD, prepare_targets(&run));
    if (status == IM_OK)
        status = prepare_contact(&run, heights);
    if (status == IM_OK)
        status = measure_surface(&run, heights);
    if (status == IM_OK)
        status = mpi_collective_status(MPI_COMM_WORLD, start_outputs(&run));
    if (status == IM_OK)
        status = run_steps(&run);
    history_close(&run.history);
    json_decref(run.record);
    run_figure_texts_free(&run.texts);
    im_render_close(run.render);
    im_mpi_flat_contact_free(run.cell);
    im_mpi_indentation_free(run.indentation);
    free(run.targets);
    free(run.rows);
    return status;
}

#endif
