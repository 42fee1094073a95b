/* Internal: nominally flat contact of a periodic cell (solver.h, "nominally flat contact"), written
 * once for the serial plan (periodic.c, im_flat_contact_*) and the distributed solver
 * (mpi/flat.c, im_mpi_flat_contact_*): the undeformed gap, the two controls and the result. */
#ifndef INDENTMAP_SOLVER_FLAT_H
#define INDENTMAP_SOLVER_FLAT_H

#include "indentmap/solver.h"

#include <stddef.h>

/* One solve of a cell's problem on its solver (im_solver_solve or im_mpi_solver_solve). */
typedef int (*flat_solve_fn)(void *solver, const double *gap0, enum im_control control, double target,
                             double *pressure, double *displacement, im_solve_result *result);

/* A cell's fields (the patches this process holds: all of them, or a rank's rows) and its totals. */
typedef struct flat_cell {
    flat_solve_fn solve;
    void *solver;
    double *gap0, *pressure, *displacement;
    double patches;   /* nx ny, of the whole cell */
    double cell_area; /* nx ny delta^2: the load per unit mean pressure */
    double mean_gap0; /* the mean of gap0 over the cell: the mean gap at approach 0 (mean u = 0 always) */
    double approach;  /* the last solve's */
} flat_cell;

/* The cell's fields for n patches (gap0 uninitialised, pressure and displacement zero); IM_ENOMEM. */
int flat_cell_allocate(flat_cell *cell, size_t n);
void flat_cell_free(flat_cell *cell);

/* g0 = highest - h for n heights (highest: the largest height of the whole cell; the flat touches
 * that patch first). */
void flat_gap(const double *heights, size_t n, double highest, double *gap0);

/* im_flat_contact_solve and _solve_gap on a cell whose gap0, totals and solver are set. */
int flat_solve_pressure(flat_cell *cell, double mean_pressure, im_flat_result *out);
int flat_solve_gap(flat_cell *cell, double mean_gap, im_flat_result *out);

/* The plan a flat contact solves on (periodic.c; its GPU counts for bench_gpu). */
const im_solver_plan *flat_contact_plan(const im_flat_contact *run);

/* A step's result from its solve s (indentation.c's steps, mpi/flat.c's periodic steps): the solve's values,
 * area_ratio n_p delta2 / area where the load is positive (on a cell, also where there is contact) and NaN
 * elsewhere, load_star area / delta2 (NaN on a cell, which has no smooth contact, and under tension). The
 * mean gap, plastic and adhesive values are zero: the caller's. */
void step_result_from_solve(const im_solve_result *s, double area, double delta2, int cell, im_step_result *out);

#endif
