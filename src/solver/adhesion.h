/* Internal: adhesion (the Maugis-Dugdale law, or the exponential one) in an indentation (solver.h,
 * "Adhesion"), written above the engines: the adhesive stress enters each solve as a displacement added to
 * the undeformed gap, and the repulsive problem is im_solver_solve's, on whatever engine the plan has. */
#ifndef INDENTMAP_SOLVER_ADHESION_H
#define INDENTMAP_SOLVER_ADHESION_H

#include "indentmap/solver.h"

/* Over ranks, each holding rows of the grid: the solve and what the passes (and an indentation's steps over
 * ranks, indentation_rows.h) need of the whole grid. Every reduction is over all ranks and in a fixed order, so
 * every rank takes the same decisions (mpi/flat.c, mpi/indentation.c). */
enum adhesion_combine { ADHESION_MIN, ADHESION_MAX, ADHESION_SUM };
typedef struct adhesion_ranks {
    void *context;
    /* the repulsive solve on gap0 (im_solver_solve's arguments; pressure and displacement: warm in, solution out) */
    int (*solve)(void *context, const double *gap0, enum im_control control, double target, double *pressure,
                 double *displacement, im_solve_result *result);
    void (*convolve)(void *context, const double *in, double *out); /* out = K in */
    double (*sum)(void *context, const double *field);              /* over the grid, in row order */
    /* values[0..count) replaced by their minimum, maximum or sum over the ranks */
    void (*combine)(void *context, double *values, int count, enum adhesion_combine how);
    /* the rows of field just outside this rank's: above (its first row - 1) and below (its last + 1),
     * wrapping around a periodic cell, NaN off the grid */
    void (*outer_rows)(void *context, const double *field, double *above, double *below);
    /* the first patch y nx + x (row-major) on the grid's outer row or column where values > 0, or LONG_MAX */
    long (*first_on_edge)(void *context, const double *values);
} adhesion_ranks;

/* The adhesive zone Z (patches where the stress sigma0 = w / delta_c pulls the surface up: repulsive
 * contact, or a gap of at most delta_c) and what it does to the surface, on the solve window. Under the
 * exponential law sigma0 is the peak w / rho and a patch's share the mean of sigma / sigma0 over it. */
typedef struct adhesion_state {
    int law;                        /* enum im_adhesion_law */
    double stress;                  /* sigma0 */
    double range;                   /* delta_c, or rho */
    int nx, ny;                     /* the window (over ranks: this rank's rows) */
    int periodic;                   /* the window is a periodic cell: its gaps wrap around at the edges */
    double *share;                  /* the share of each patch on Z, in [0, 1] (1 in repulsive contact) */
    double *gap_rows;               /* the last pass's gaps with the rows just outside them (fill_outer_rows) */
    double *gaps;                   /* gap_rows + nx: the gaps of the window's rows */
    double *proposal;               /* the shares they call for (between steps: adhesion_split's scratch) */
    double *lift;                   /* K 1_Z: the displacement of a unit stress on Z (sigma0 lift pulls up) */
    double *gap0;                   /* the repulsive solve's undeformed gap: g0 - sigma0 lift + shift */
    double shift;                   /* what was added to make min gap0 = 0 */
    long zone_patches;              /* patches with a share > 0 */
    double zone_area;               /* the sum of the shares (patches) */
    double approach;                /* the last step's (retraction shrinks Z, approach grows it) */
    int stepped;                    /* 0 before the first step */
    struct adhesion_mark *marks[2]; /* the states adhesion_rewind returns to (adhesion_set_mark), or NULL */
    const adhesion_ranks *ranks;    /* NULL: one process holds the whole window */
} adhesion_state;

/* A state for an nx x ny window, or a periodic cell (IM_ENOMEM), with the options' law checked by the caller. */
int adhesion_create(int nx, int ny, int periodic, const im_solver_options *options, adhesion_state **out);

/* Makes a state's passes run over ranks (the caller's ranks, kept until adhesion_free): its nx x ny are this
 * rank's rows, and adhesion_solve's plan gives delta and tol only. */
void adhesion_over_ranks(adhesion_state *a, const adhesion_ranks *ranks);

/* The largest gap at which the options' law pulls: delta_c, or the exponential law's cut 35 rho. */
double adhesion_reach(const im_solver_options *options);
void adhesion_free(adhesion_state *a);

/* The step at approach w under displacement control: the repulsive pressure p_r and its
 * displacement u_r (warm in, solution out) on the window's gap0, Z iterated to its fixed point.
 * result: the repulsive solve's counts summed over the passes, with the NET load and approach w. */
int adhesion_solve(adhesion_state *a, im_solver_plan *plan, const double *gap0, double w, double *pressure,
                   double *displacement, im_solve_result *result);

/* A search that tries several approaches (load control) marks a state and rewinds to it before a try, so
 * that the try moves from that history: the last accepted try's (ADHESION_MARK_TRY), and the step's start,
 * which a failed step returns to (ADHESION_MARK_STEP). adhesion_reserve_mark allocates a slot ahead (a run over
 * ranks reserves its slots where every rank can agree on an allocation failure, not inside a step's collective
 * solves); adhesion_set_mark allocates what is not reserved. Both: IM_ENOMEM. */
enum adhesion_mark_slot { ADHESION_MARK_TRY, ADHESION_MARK_STEP };
int adhesion_reserve_mark(adhesion_state *a, enum adhesion_mark_slot slot);
int adhesion_set_mark(adhesion_state *a, enum adhesion_mark_slot slot);
void adhesion_rewind(adhesion_state *a, enum adhesion_mark_slot slot);

/* The net pressure and displacement of window patch i from the repulsive ones. */
static inline double adhesion_net_pressure(const adhesion_state *a, size_t i, double repulsive)
{
    return a ? repulsive - a->stress * a->share[i] : repulsive;
}
static inline double adhesion_net_displacement(const adhesion_state *a, size_t i, double repulsive)
{
    return a ? repulsive - a->stress * a->lift[i] : repulsive;
}

/* Sums of the net pressure over the window: tensile force delta^2 sum(-p) over p < 0 (compensated, as
 * loads; a->proposal is its scratch), the patches with p < 0 and p > 0. */
void adhesion_split(adhesion_state *a, const double *pressure, double delta, double *tensile, long *adhesive_patches,
                    long *repulsive_patches);

/* Whether Z reaches the window's outer row or column (*x, *y: the patch, window coordinates); never for a
 * periodic cell, which has no edge. One process only. */
int adhesion_zone_on_border(const adhesion_state *a, int *x, int *y);

#endif
