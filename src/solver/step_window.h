/* Internal: the windows an indentation solves on (indentation.c). The run's window holds every patch
 * its largest approach can touch; a displacement-controlled step at approach w can touch only the
 * patches with g0 <= w (u >= 0 under compression), so it is solved on the bounding box of those, a
 * sub-window of the run's: the same problem (the padded convolution is exact on any box that holds
 * every loaded patch), on fewer patches. Early steps of a cone touch a small disc. */
#ifndef INDENTMAP_SOLVER_STEP_WINDOW_H
#define INDENTMAP_SOLVER_STEP_WINDOW_H

#include "indentmap/solver.h"

/* The bounding box of the patches of the nx x ny grid gap0 with gap0 <= bound, plus margin patches
 * on each side, each side grown to an FFT-friendly length (2^a 3^b 5^c 7^d) within the grid, centred
 * on the box (the whole side when that length does not fit). An empty window (nx = ny = 0) when no
 * patch is that close. */
im_window solver_gap_window(const double *gap0, int nx, int ny, double bound, int margin);

/* The run's window grid, whose arrays a step reads (gap0) and writes (pressure, displacement). */
typedef struct window_grid {
    int nx, ny;
    const double *gap0;
    double *pressure, *displacement;
    im_solver_plan *plan; /* the whole window's */
} window_grid;

typedef struct step_window step_window;

/* NULL when there is no memory. */
step_window *step_window_create(void);
void step_window_free(step_window *s);

/* Solves the window grid at approach w under displacement control on the step's window (planned with
 * the whole window's options when the last step's does not hold it), warm-started from and writing back
 * into the grid's pressure (0 outside the step's window) and displacement, which outside the step's
 * window is then stale until step_window_refresh. As im_solver_solve (IM_ENOMEM also when a box's plan
 * does not fit). */
int step_window_solve(step_window *s, const window_grid *g, double w, im_solve_result *result);

/* Makes the grid's displacement K p on the whole window again, if a step left it stale. */
void step_window_refresh(step_window *s, const window_grid *g);

#endif
