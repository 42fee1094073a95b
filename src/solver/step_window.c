/* The windows an indentation solves on (step_window.h). */
#include "solver/step_window.h"
#include "solver/plan.h"

#include "indentmap/status.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Smallest 2^a 3^b 5^c 7^d >= n (FFTW is fastest on such sizes). */
static int fft_friendly(int n)
{
    for (int m = n;; ++m) {
        int k = m;
        static const int primes[] = {2, 3, 5, 7};
        for (int j = 0; j < 4; ++j)
            while (k % primes[j] == 0)
                k /= primes[j];
        if (k == 1)
            return m;
    }
}

/* Grows [lo, hi) by margin on each side and then to a friendly length inside [0, n), centred on the
 * span; the whole range when the friendly length does not fit. */
static void grow_span(int *lo, int *hi, int margin, int n)
{
    *lo = *lo - margin < 0 ? 0 : *lo - margin;
    *hi = *hi + margin > n ? n : *hi + margin;
    int length = fft_friendly(*hi - *lo);
    if (length >= n) {
        *lo = 0;
        *hi = n;
        return;
    }
    int start = *lo - (length - (*hi - *lo)) / 2;
    if (start < 0)
        start = 0;
    if (start + length > n)
        start = n - length;
    *lo = start;
    *hi = start + length;
}

static const im_window NO_BOX = {0, 0, 0, 0};

static int inside(im_window b, int ix, int iy)
{
    return ix >= b.x0 && ix < b.x0 + b.nx && iy >= b.y0 && iy < b.y0 + b.ny;
}

/* Which patches a box is drawn around: those outside skip whose g0 + scale u is at most w (below w with
 * strict), u NULL counting 0. */
typedef struct gap_test {
    const double *gap0, *u;
    double w, scale;
    int strict;
    im_window skip; /* nx = 0: none */
} gap_test;

static int selected(const gap_test *t, size_t i, int ix, int iy)
{
    if (inside(t->skip, ix, iy))
        return 0;
    const double g = t->u ? t->gap0[i] + t->scale * t->u[i] : t->gap0[i];
    return t->strict ? g < t->w : g <= t->w;
}

/* The bounding box of the selected patches of region (of the nx x ny grid), joined with also (nx = 0:
 * nothing), grown by margin and then to a friendly size (grow_span); empty when none is selected. */
static im_window box_of(const gap_test *t, im_window region, im_window also, int nx, int ny, int margin)
{
    int x_lo = nx, x_hi = -1, y_lo = ny, y_hi = -1;
#pragma omp parallel for schedule(static) reduction(min : x_lo, y_lo) reduction(max : x_hi, y_hi)
    for (int iy = region.y0; iy < region.y0 + region.ny; ++iy)
        for (int ix = region.x0; ix < region.x0 + region.nx; ++ix)
            if (selected(t, (size_t)iy * nx + ix, ix, iy)) {
                x_lo = ix < x_lo ? ix : x_lo;
                x_hi = ix > x_hi ? ix : x_hi;
                y_lo = iy < y_lo ? iy : y_lo;
                y_hi = iy > y_hi ? iy : y_hi;
            }
    if (x_hi < 0)
        return NO_BOX;
    int x1 = x_hi + 1, y1 = y_hi + 1;
    if (also.nx > 0) {
        x_lo = x_lo < also.x0 ? x_lo : also.x0, y_lo = y_lo < also.y0 ? y_lo : also.y0;
        x1 = x1 > also.x0 + also.nx ? x1 : also.x0 + also.nx, y1 = y1 > also.y0 + also.ny ? y1 : also.y0 + also.ny;
    }
    grow_span(&x_lo, &x1, margin, nx);
    grow_span(&y_lo, &y1, margin, ny);
    return (im_window){x_lo, y_lo, x1 - x_lo, y1 - y_lo};
}

im_window solver_gap_window(const double *gap0, int nx, int ny, double bound, int margin)
{
    const gap_test within = {.gap0 = gap0, .w = bound};
    return box_of(&within, (im_window){0, 0, nx, ny}, NO_BOX, nx, ny, margin);
}

/* A box of the run's window (in its patches) with a plan and the box's own arrays; no plan when the box
 * is the whole window (the run's plan serves). */
typedef struct box_plan {
    im_window box; /* nx = 0: none yet */
    im_solver_plan *plan;
    double *gap0, *pressure, *displacement;
} box_plan;

/* inner: where the step is solved, the box of the patches that its estimated gap brings into contact;
 * outer: the box of the patches within reach (g0 <= w), where u is computed to confirm that no patch
 * outside inner penetrates. */
struct step_window {
    box_plan inner, outer;
    double approach; /* the last step's; NAN before the first */
    int stale;       /* the run window's displacement is not K p everywhere (step_window_refresh) */
};

step_window *step_window_create(void)
{
    step_window *s = calloc(1, sizeof(step_window));
    if (s)
        s->approach = NAN;
    return s;
}

static void release_box(box_plan *b)
{
    im_solver_plan_free(b->plan);
    free(b->gap0);
    free(b->pressure);
    free(b->displacement);
    *b = (box_plan){NO_BOX, NULL, NULL, NULL, NULL};
}

void step_window_free(step_window *s)
{
    if (!s)
        return;
    release_box(&s->inner);
    release_box(&s->outer);
    free(s);
}

static int holds(im_window outer, im_window inner)
{
    return inner.x0 >= outer.x0 && inner.y0 >= outer.y0 && inner.x0 + inner.nx <= outer.x0 + outer.nx &&
           inner.y0 + inner.ny <= outer.y0 + outer.ny;
}

/* A new box is wider than the step needs on each side, so that the next steps of a rising history fit in
 * it too: a plan per few steps, not per step. The solved box keeps less slack (its iterations cost more
 * than the one convolution of the box within reach; the paper's history: 1/16 took 0.8x the CPU time of
 * 1/8, less was not measurably better). */
enum { SOLVED_SLACK_DIVISOR = 16, REACH_SLACK_DIVISOR = 8 };

static im_window roomy_box(im_window need, const window_grid *g, int solving)
{
    const int divisor = solving ? SOLVED_SLACK_DIVISOR : REACH_SLACK_DIVISOR;
    int x0 = need.x0, x1 = need.x0 + need.nx, y0 = need.y0, y1 = need.y0 + need.ny;
    grow_span(&x0, &x1, need.nx / divisor, g->nx);
    grow_span(&y0, &y1, need.ny / divisor, g->ny);
    return (im_window){x0, y0, x1 - x0, y1 - y0};
}

/* Plans box, a solver's plan (solving) or a convolution's, both FFTW_ESTIMATE; IM_ENOMEM and no box when it
 * does not fit in memory. */
static int plan_box(box_plan *b, im_window box, const window_grid *g, int solving)
{
    release_box(b);
    const size_t n = (size_t)box.nx * box.ny;
    b->gap0 = malloc(sizeof(double) * n);
    b->pressure = malloc(sizeof(double) * n);
    b->displacement = malloc(sizeof(double) * n);
    int status = b->gap0 && b->pressure && b->displacement
                     ? IM_OK
                     : im_fail(IM_ENOMEM, "step box %d x %d: allocation of 3 x %.1f MiB failed", box.nx, box.ny,
                               sizeof(double) * (double)n / 1048576.0);
    const int whole = box.nx == g->nx && box.ny == g->ny;
    im_solver_options estimated = g->plan->options;
    estimated.fft_measure = 0;    /* a history plans a dozen boxes: measuring each would cost more than it */
    estimated.wisdom_path = NULL; /* saves, and a wisdom file would gain a dozen sizes per surface */
    if (status == IM_OK && !whole && solving)
        status = im_solver_plan_create(box.nx, box.ny, g->plan->delta, &estimated, &b->plan);
    else if (status == IM_OK && !whole)
        status = im_displacement_plan_create(box.nx, box.ny, g->plan->delta, &g->plan->options, &b->plan);
    if (status != IM_OK) {
        release_box(b);
        return status;
    }
    b->box = box;
    return IM_OK;
}

/* The box b holds need, replanned (roomy) when it does not. */
static int hold(box_plan *b, im_window need, const window_grid *g, int solving)
{
    return b->box.nx > 0 && holds(b->box, need) ? IM_OK : plan_box(b, roomy_box(need, g, solving), g, solving);
}

static im_solver_plan *plan_of(const box_plan *b, const window_grid *g) { return b->plan ? b->plan : g->plan; }

/* Copies the box's rows between the window grid's array (stride g->nx) and the box's own. */
static void copy_box(const box_plan *b, const window_grid *g, const double *from, double *to, int into_box)
{
    const im_window w = b->box;
#pragma omp parallel for schedule(static)
    for (int iy = 0; iy < w.ny; ++iy) {
        const size_t at = (size_t)(iy + w.y0) * g->nx + w.x0, row = (size_t)iy * w.nx;
        if (into_box)
            memcpy(to + row, from + at, sizeof(double) * w.nx);
        else
            memcpy(to + at, from + row, sizeof(double) * w.nx);
    }
}

/* Solves on the inner box, warm-started from the grid's pressure; the grid's pressure is then the box's
 * (0 outside it). */
static int solve_inner(step_window *s, const window_grid *g, double w, im_solve_result *result)
{
    box_plan *b = &s->inner;
    copy_box(b, g, g->gap0, b->gap0, 1);
    copy_box(b, g, g->pressure, b->pressure, 1);
    int status = im_solver_solve(plan_of(b, g), b->gap0, IM_CONTROL_DISPLACEMENT, w, b->pressure, b->displacement,
                                 result);
    memset(g->pressure, 0, sizeof(double) * (size_t)g->nx * g->ny);
    copy_box(b, g, b->pressure, g->pressure, 0);
    return status;
}

/* u = K p on the outer box into the grid's displacement; the box of the patches outside the inner box that
 * penetrate (g0 - w + u < 0), grown by margin (nx = 0: none). */
static im_window penetrating_outside(step_window *s, const window_grid *g, double w, int margin)
{
    box_plan *b = &s->outer;
    copy_box(b, g, g->pressure, b->pressure, 1);
    im_solver_convolve(plan_of(b, g), b->pressure, b->displacement);
    copy_box(b, g, b->displacement, g->displacement, 0);
    const gap_test penetrating = {g->gap0, g->displacement, w, 1, 1, s->inner.box};
    return box_of(&penetrating, b->box, s->inner.box, g->nx, g->ny, margin);
}

/* The box of the patches that the last step's displacement, scaled with the approach (a cone's contact
 * is self-similar: u grows as w), brings into contact, g0 - w + u w / w_last <= 0, grown by margin; need
 * itself without a last step or such a patch. A guess: penetrating_outside confirms it. */
static im_window contact_guess(const step_window *s, const window_grid *g, im_window need, double w, int margin)
{
    if (!(s->approach > 0))
        return need;
    const gap_test touching = {g->gap0, g->displacement, w, w / s->approach, 0, NO_BOX};
    const im_window guess = box_of(&touching, need, NO_BOX, g->nx, g->ny, margin);
    return guess.nx > 0 ? guess : need;
}

static void add_try(im_solve_result *total, const im_solve_result *last)
{
    const im_solve_result before = *total;
    *total = *last;
    total->iterations += before.iterations;
    total->coarse_iterations += before.coarse_iterations;
    total->convolutions += before.convolutions;
    total->seconds += before.seconds;
}

/* Solves on the guessed box, then confirms on the box within reach that no patch outside it penetrates;
 * else again on the box with those patches too, warm-started. */
static int solve_in_boxes(step_window *s, const window_grid *g, im_window need, double w, im_solve_result *result)
{
    const int margin = g->plan->options.window_margin;
    im_window guess = contact_guess(s, g, need, w, margin);
    int status = hold(&s->outer, need, g, 0);
    *result = (im_solve_result){0};
    while (status == IM_OK && guess.nx > 0 && (status = hold(&s->inner, guess, g, 1)) == IM_OK) {
        im_solve_result try;
        status = solve_inner(s, g, w, &try);
        add_try(result, &try);
        s->stale = 1; /* the grid's u is K p on the outer box at most (after penetrating_outside) */
        if (status != IM_OK)
            return status;
        guess = penetrating_outside(s, g, w, margin);
    }
    return status;
}

int step_window_solve(step_window *s, const window_grid *g, double w, im_solve_result *result)
{
    const im_window need = solver_gap_window(g->gap0, g->nx, g->ny, w, g->plan->options.window_margin);
    int status;
    if (need.nx > 0) {
        status = solve_in_boxes(s, g, need, w, result);
    } else { /* no patch within reach (a plastic surface withdrawn): no contact, on the whole window */
        s->stale = 0;
        status = im_solver_solve(g->plan, g->gap0, IM_CONTROL_DISPLACEMENT, w, g->pressure, g->displacement, result);
    }
    s->approach = status == IM_OK ? w : NAN;
    return status;
}

void step_window_refresh(step_window *s, const window_grid *g)
{
    if (!s->stale)
        return;
    im_solver_convolve(g->plan, g->pressure, g->displacement);
    s->stale = 0;
}
