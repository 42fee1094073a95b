/* indentmap mpi-indent --periodic: indent --periodic's history of a rigid flat on a periodic cell over
 * MPI ranks (mpi.h: im_mpi_flat_contact_step), written in its schema: the history's columns (history.h)
 * on stdout and in DIR/history.csv, and DIR/run.json, with front.h's pieces. Built only with MPI. */
#include "cli/mpi_indent.h"

#if IM_HAVE_MPI

#include "front/front.h"
#include "mpi/agree.h"

#include "indentmap/history.h"
#include "indentmap/io.h"
#include "indentmap/measure.h"
#include "indentmap/status.h"

#include <jansson.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>

typedef struct periodic_run {
    const mpi_indent_options *o;
    im_mpi_solver *solver;
    im_mpi_flat_contact *cell;
    int rank;
    im_field shape;   /* the cell's grid and patch side (no data) */
    im_indenter flat; /* the rigid flat on the whole cell */
    double *targets;  /* loads N (from the mean pressures) or mean gaps */
    im_history_row *rows;
    history_file history; /* rank 0, with --out */
    json_t *record;       /* rank 0, with --out */
    double slope_rms;     /* rank 0: the cell's spectral h'rms */
} periodic_run;

/* Rank 0: the whole field of this rank's rows of values (caller frees; NULL elsewhere). Collective. */
static int gather_whole(const periodic_run *run, const double *values, im_field **whole)
{
    *whole = NULL;
    return im_mpi_gather_map(run->solver, values, 1, whole);
}

/* The surface's h'rms (spectral: a periodic cell, as indent's default) and indent's warning when its edges
 * do not meet, on rank 0 from the gathered heights. */
static int measure_surface(periodic_run *run, const double *heights)
{
    im_field *surface;
    int status = gather_whole(run, heights, &surface);
    if (status == IM_OK && run->rank == 0) {
        char warning[8192];
        if (periodic_warning(surface, run->o->surface_file ? run->o->surface_file : "the surface", warning,
                             sizeof warning))
            fprintf(stderr, "indentmap: %s\n", warning);
        status = im_surface_slope_rms(surface, IM_SLOPE_SPECTRAL, &run->slope_rms);
    }
    im_field_free(surface);
    return mpi_collective_status(MPI_COMM_WORLD, status);
}

/* The step list as the cell takes it: loads N = p_m A0 from mean pressures, or the mean gaps. */
static int prepare_targets(periodic_run *run)
{
    const mpi_indent_options *o = run->o;
    const int pressures = o->control == IM_CONTROL_LOAD; /* --pressure */
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
    return adhesive;
}

/* run.json's "adhesion" block of an adhesive cell (as indent's: no smooth theory beside a cell), or null. */
static json_t *adhesion_block(const periodic_run *run)
{
    if (!(run->o->adhesion_work > 0))
        return json_null();
    const im_solver_options adhesive = adhesive_options(run->o);
    json_t *law = run_record_adhesion_law(&adhesive, &run->flat, run->shape.delta);
    json_object_set_new(law, "theory", json_null());
    return law;
}

/* run.json's blocks beside the common record: indent --periodic's (surface, punch, control, targets,
 * periodic, threads, history, theory_slope_rms, units, inputs) and the ranks. */
static int add_blocks(const periodic_run *run, json_t *root)
{
    const mpi_indent_options *o = run->o;
    json_t *targets = json_array();
    for (int i = 0; i < o->target_count; ++i)
        json_array_append_new(targets, json_real(run->targets[i]));
    json_t *blocks = json_pack(
        "{s:{s:s, s:i, s:i, s:f, s:s}, s:{s:s, s:f}, s:s, s:o, s:b, s:i, s:s, s:{s:f, s:s, s:s}, s:o, s:n, s:o}",
        "surface", "source", o->surface_file ? o->surface_file : "synthesised over the ranks", "nx", run->shape.nx,
        "ny", run->shape.ny, "delta", run->shape.delta, "unit", "", "punch", "kind", im_punch_name(run->flat.kind),
        "radius", run->flat.radius, "control", o->control == IM_CONTROL_LOAD ? "load" : "mean_gap", "targets",
        targets, "periodic", 1, "threads", omp_get_max_threads(), "history", "history.csv", "theory_slope_rms",
        "value", run->slope_rms, "definition", "spectral", "chosen_by", "default: a periodic cell", "units",
        indent_units_record("", "", 1), "indentation", "adhesion", adhesion_block(run));
    if (!blocks)
        return im_fail(IM_ENOMEM, "run.json: out of memory");
    int ranks;
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    if (!o->surface_file)
        json_object_set_new(blocks, "seed", json_integer((json_int_t)o->surface.seed));
    json_object_set_new(blocks, "ranks", json_integer(ranks));
    json_object_update(root, blocks);
    json_decref(blocks);
    json_t *inputs = json_array();
    int status = inputs && o->surface_file ? run_record_add_input(inputs, "--surface", o->surface_file) : IM_OK;
    json_object_set_new(root, "inputs", inputs);
    return status;
}

/* Rank 0, with --out: the folder, history.csv's column line and the record. */
static int start_outputs(periodic_run *run)
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
    return status == IM_OK ? history_start(o->out, &run->history) : status;
}

/* Step i: solved on every rank, its contact patches counted on rank 0 from the gathered forces, its row
 * measured (history.h), printed and appended to DIR/history.csv on rank 0. */
static int run_step(periodic_run *run, int i)
{
    im_history_row *row = &run->rows[i];
    int status = im_mpi_flat_contact_step(run->cell, run->o->control, run->targets[i], &row->result);
    im_field *force = NULL;
    if (status == IM_OK)
        status = gather_whole(run, im_mpi_flat_contact_pressure(run->cell), &force);
    if (status == IM_OK && run->rank == 0)
        status = im_history_measure(&run->flat, NULL, NULL, run->rows, i);
    im_contact_patches patches = {0};
    if (status == IM_OK && run->rank == 0 && (status = im_measure_contact_patches(force, &patches, NULL)) == IM_OK) {
        row->patches = patches.patches;
        row->perimeter = patches.perimeter;
        char line[IM_HISTORY_LINE_MAX];
        im_history_format(row, line, sizeof line);
        fputs(line, stdout);
        fflush(stdout);
    }
    if (status == IM_OK && run->rank == 0 && run->o->out)
        status = history_append(&run->history, row);
    im_field_free(force);
    return mpi_collective_status(MPI_COMM_WORLD, status);
}

/* Rank 0, with --out: k of eq. (2) (elastic steps only, as indent) and the record's end. */
static int finish_record(periodic_run *run, int done, int status)
{
    if (run->rank != 0 || !run->record)
        return status;
    periodic_k_fit k;
    char message[1024];
    snprintf(message, sizeof message, "%s", im_last_error());
    im_adhesion_summary summary;
    if (run->o->adhesion_work > 0) { /* eq. (2) is the repulsive law: no k fitted, as indent */
        if (run_record_adhesion_summary(json_object_get(run->record, "adhesion"), run->o->out, run->rows, done, "",
                                        "", NULL, &summary) != IM_OK)
            fprintf(stderr, "indentmap: adhesion summary: %s\n", im_last_error());
    } else if (!(run->o->solver.hardness > 0) && periodic_fit_k(run->rows, done, periodic_cell_area(&run->shape),
                                                                run->slope_rms, run->o->solver.e_star, &k) == IM_OK)
        json_object_set_new(run->record, "k_fit", periodic_k_fit_record(&k, run->slope_rms, "spectral"));
    if (status != IM_OK)
        im_fail(status, "%s", message); /* the step's error, not the fit's */
    int recorded = run_record_finish(run->o->out, run->record, done, status);
    return status == IM_OK ? recorded : status;
}

/* DIR/force.npy and gap.npy of the last step. Collective. */
static int write_last_fields(const periodic_run *run)
{
    int y0, rows;
    im_mpi_solver_rows(run->solver, &y0, &rows);
    double *gap = malloc(sizeof(double) * ((size_t)rows * run->shape.nx + 1));
    int status = mpi_collective_status(MPI_COMM_WORLD, gap ? im_mpi_flat_contact_gap(run->cell, gap)
                                                           : im_fail(IM_ENOMEM, "the last step's gap"));
    if (status == IM_OK)
        status = mpi_indent_write_fields(run->o, run->solver, im_mpi_flat_contact_pressure(run->cell), gap);
    free(gap);
    return status;
}

static int run_steps(periodic_run *run)
{
    const mpi_indent_options *o = run->o;
    int status = IM_OK, done = 0;
    if (run->rank == 0) {
        printf("%s\n", im_history_columns());
        fflush(stdout);
    }
    while (done < o->target_count && (status = run_step(run, done)) == IM_OK)
        ++done;
    if (status != IM_OK) /* done: the steps whose rows are written */
        im_fail_context(status, "step %d of %d (%s %g)", done + 1, o->target_count, o->targets_option,
                        o->targets[done]);
    else if (o->out)
        status = write_last_fields(run);
    return mpi_collective_status(MPI_COMM_WORLD, finish_record(run, done, status));
}

int mpi_indent_periodic(const mpi_indent_options *o, im_mpi_solver *solver, const double *heights)
{
    periodic_run run = {.o = o,
                        .solver = solver,
                        .history = {.fd = -1},
                        .shape = {.nx = o->surface.nx, .ny = o->surface.ny, .delta = 1.0}};
    MPI_Comm_rank(MPI_COMM_WORLD, &run.rank);
    run.flat = periodic_rigid_flat(&run.shape);
    int status = mpi_collective_status(MPI_COMM_WORLD, prepare_targets(&run));
    if (status == IM_OK)
        status = im_mpi_flat_contact_create(solver, heights, &run.cell);
    const im_solver_options adhesive = adhesive_options(o);
    if (status == IM_OK && o->adhesion_work > 0)
        status = im_mpi_flat_contact_adhesion(run.cell, &adhesive);
    if (status == IM_OK)
        status = measure_surface(&run, heights);
    if (status == IM_OK)
        status = mpi_collective_status(MPI_COMM_WORLD, start_outputs(&run));
    if (status == IM_OK)
        status = run_steps(&run);
    history_close(&run.history);
    json_decref(run.record);
    im_mpi_flat_contact_free(run.cell);
    free(run.targets);
    free(run.rows);
    return status;
}

#endif
