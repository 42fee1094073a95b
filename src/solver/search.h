/* Internal: the search of an approach whose solution meets a target (a load, a periodic cell's mean gap),
 * written once for the serial indentation (indentation.c) and the distributed periodic cell (mpi/flat.c):
 * displacement-controlled solves on the approach, each warm-started from the last, bracketed and narrowed
 * by the Illinois variant of regula falsi. */
#ifndef INDENTMAP_SOLVER_SEARCH_H
#define INDENTMAP_SOLVER_SEARCH_H

#include "indentmap/solver.h"

/* The solves a search may take before it gives up. */
enum { SEARCH_MAX = 200 };

typedef struct approach_search {
    void *context; /* what solve and measure act on: an indentation, a distributed cell */
    double target;
    double tol; /* the solver's */
    /* what the search matches to target: non-decreasing in the approach */
    double (*measure)(void *context, const im_solve_result *s);
    /* one displacement-controlled solve at approach w */
    int (*solve)(void *context, double w, im_solve_result *s);
    double length;        /* the approaches' scale where they pass 0 (adhesion's range; else 0) */
    double lowest;        /* the least approach a trial takes: 0, below which the flat is clear of the surface,
                             or -INFINITY with adhesion, whose zone pulls before it touches */
    im_solve_result last; /* the last trial's, with iterations, convolutions and seconds summed */
    int trials;
} approach_search;

/* One solve at approach w; its measure minus the target in *excess. */
int search_trial(approach_search *search, double w, double *excess);

/* Narrows [lo, hi] (excess e_lo <= 0 <= e_hi; e the last trial's) to |excess| <= tol scale, or to tol w in
 * the approach where the solves (each exact to tol w in the gap) cannot resolve the measure closer; the
 * state is the last solve's. IM_ENOCONV after SEARCH_MAX solves. */
int search_refine(approach_search *search, double lo, double e_lo, double hi, double e_hi, double e, double scale);

/* A periodic cell's mean gap under a hardness H_p (0: none): the search's measure is minus the mean open
 * gap and its target minus the mean gap. From approach w (mean g0 - mean gap: exact without yielding, as
 * mean u = 0) upwards while yielded patches, whose overlap opens no gap, leave the mean gap above the
 * target. w <= lowest leaves the flat clear (one solve at lowest); the result's approach is w there. */
int search_mean_gap(approach_search *search, double w, double hardness, im_solve_result *out);

#endif
