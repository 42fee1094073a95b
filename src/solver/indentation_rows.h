/* Internal: im_indentation_step's history on a half-space whose grid is held in rows by several ranks
 * (mpi/indentation.c): each rank runs the serial steps (indentation.c: plastic memory, load control, the
 * searches of the approach, adhesion) on its rows of the whole surface (no crop window), its solves and its
 * reductions over the ranks (adhesion.h: adhesion_ranks), so that every rank takes the same decisions. One
 * step logic, written once in indentation.c. */
#ifndef INDENTMAP_SOLVER_INDENTATION_ROWS_H
#define INDENTMAP_SOLVER_INDENTATION_ROWS_H

#include "solver/adhesion.h"

/* This rank's part of the grid and what it runs on. */
typedef struct indentation_rows {
    int nx, ny;                  /* the whole surface */
    int rows;                    /* this rank's (0 allowed) */
    double delta;                /* patch side */
    const double *gap0;          /* this rank's rows of g0 = z - h - min(z - h) over the whole surface */
    double height_range;         /* max h - min h over the whole surface (load control's bound) */
    im_solver_plan *plan;        /* the distributed solver's plan: its cap is set to the run's (see below) */
    const adhesion_ranks *ranks; /* the solves and the reductions over the ranks; kept until the run is freed */
} indentation_rows;

/* As im_indentation_create on the half-space with crop = 0 (options' crop and periodic ignored and refused), for
 * grid's rows: options are the run's (hardness, adhesion, tol, e_star), and the plan's hardness is set to the
 * cap of the repulsive pressure the steps solve (H_p, or H_p + sigma0 with adhesion: indentation.c's
 * repulsive_cap), which the caller restores when it needs the plan's own. Not collective: IM_EINVAL for what
 * im_indentation_create refuses (the same on every rank), IM_ENOMEM on this rank only. */
int indentation_create_on_rows(const indentation_rows *grid, const im_indenter *punch, enum im_control control,
                               double largest_target, const im_solver_options *options, im_indentation **out);

/* The last step's state on this rank's rows: the repulsive pressure and displacement, the undeformed gap with
 * the plastic depth, and the adhesion (NULL without), for the net pressure and the gap (adhesion.h). */
typedef struct indentation_rows_state {
    const double *pressure, *displacement, *gap0;
    const adhesion_state *adhesion;
    double approach;
} indentation_rows_state;
indentation_rows_state indentation_rows_state_of(const im_indentation *run);

#endif
