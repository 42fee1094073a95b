/* The windows an indentation solves on (step_window.h). */
#include "solver/step_window.h"
#include "solver/plan.h"

#include "indentmap/status.h"

#include <stdlib.h>
#include <string.h>

struct step_window {
    im_window box; /* in the run window's patches; nx = 0: none, the steps are solved on the whole window */
    im_solver_plan *plan;
    double *gap0, *pressure, *displacement; /* box.nx * box.ny */
    int stale;                              /* the run window's displacement outside the box is not K p */
};

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

im_window solver_gap_window(const double *gap0, int nx, int ny, double bound, int margin)
{
    int x_lo = nx, x_hi = -1, y_lo = ny, y_hi = -1;
#pragma omp parallel for schedule(static) reduction(min : x_lo, y_lo) reduction(max : x_hi, y_hi)
    for (int iy = 0; iy < ny; ++iy)
        for (int ix = 0; ix < nx; ++ix)
            if (gap0[(size_t)iy * nx + ix] <= bound) {
                x_lo = ix < x_lo ? ix : x_lo;
                x_hi = ix > x_hi ? ix : x_hi;
                y_lo = iy < y_lo ? iy : y_lo;
                y_hi = iy > y_hi ? iy : y_hi;
            }
    if (x_hi < 0)
        return (im_window){0, 0, 0, 0};
    int x1 = x_hi + 1, y1 = y_hi + 1;
    grow_span(&x_lo, &x1, margin, nx);
    grow_span(&y_lo, &y1, margin, ny);
    return (im_window){x_lo, y_lo, x1 - x_lo, y1 - y_lo};
}

step_window *step_window_create(void) { return calloc(1, sizeof(step_window)); }

static void release_box(step_window *s)
{
    im_solver_plan_free(s->plan);
    free(s->gap0);
    free(s->pressure);
    free(s->displacement);
    s->plan = NULL;
    s->gap0 = s->pressure = s->displacement = NULL;
    s->box = (im_window){0, 0, 0, 0};
}

void step_window_free(step_window *s)
{
    if (!s)
        return;
    release_box(s);
    free(s);
}

static int holds(im_window outer, im_window inner)
{
    return inner.x0 >= outer.x0 && inner.y0 >= outer.y0 && inner.x0 + inner.nx <= outer.x0 + outer.nx &&
           inner.y0 + inner.ny <= outer.y0 + outer.ny;
}

/* A new box is an eighth wider than the step needs on each side, so that the next steps of a rising
 * history fit in it too: a plan per few steps, not per step. */
enum { BOX_SLACK_DIVISOR = 8 };

static im_window roomy_box(im_window need, const window_grid *g)
{
    int x0 = need.x0, x1 = need.x0 + need.nx, y0 = need.y0, y1 = need.y0 + need.ny;
    grow_span(&x0, &x1, need.nx / BOX_SLACK_DIVISOR, g->nx);
    grow_span(&y0, &y1, need.ny / BOX_SLACK_DIVISOR, g->ny);
    return (im_window){x0, y0, x1 - x0, y1 - y0};
}

/* Plans box (the whole window: none, the whole window's plan solves); IM_ENOMEM and no box when it
 * does not fit. */
static int plan_box(step_window *s, im_window box, const window_grid *g)
{
    release_box(s);
    if (box.nx == g->nx && box.ny == g->ny)
        return IM_OK;
    const size_t n = (size_t)box.nx * box.ny;
    s->gap0 = malloc(sizeof(double) * n);
    s->pressure = malloc(sizeof(double) * n);
    s->displacement = malloc(sizeof(double) * n);
    int status = s->gap0 && s->pressure && s->displacement
                     ? im_solver_plan_create(box.nx, box.ny, g->plan->delta, &g->plan->options, &s->plan)
                     : IM_ENOMEM;
    if (status != IM_OK) {
        release_box(s);
        return status;
    }
    s->box = box;
    return IM_OK;
}

/* Copies the box's rows between the window grid's array (stride g->nx) and the box's own. */
static void copy_box(const step_window *s, const window_grid *g, const double *from, double *to, int into_box)
{
    const im_window b = s->box;
#pragma omp parallel for schedule(static)
    for (int iy = 0; iy < b.ny; ++iy) {
        const size_t at = (size_t)(iy + b.y0) * g->nx + b.x0, row = (size_t)iy * b.nx;
        if (into_box)
            memcpy(to + row, from + at, sizeof(double) * b.nx);
        else
            memcpy(to + at, from + row, sizeof(double) * b.nx);
    }
}

static int solve_in_box(step_window *s, const window_grid *g, double w, im_solve_result *result)
{
    copy_box(s, g, g->gap0, s->gap0, 1);
    copy_box(s, g, g->pressure, s->pressure, 1); /* the last step's, outside the box 0 at this w anyway */
    int status = im_solver_solve(s->plan, s->gap0, IM_CONTROL_DISPLACEMENT, w, s->pressure, s->displacement, result);
    memset(g->pressure, 0, sizeof(double) * (size_t)g->nx * g->ny);
    copy_box(s, g, s->pressure, g->pressure, 0);
    copy_box(s, g, s->displacement, g->displacement, 0);
    s->stale = 1;
    return status;
}

int step_window_solve(step_window *s, const window_grid *g, double w, im_solve_result *result)
{
    const im_window need = solver_gap_window(g->gap0, g->nx, g->ny, w, g->plan->options.window_margin);
    int status = IM_OK;
    if (need.nx > 0 && !(s->box.nx > 0 && holds(s->box, need)))
        status = plan_box(s, roomy_box(need, g), g);
    if (need.nx > 0 && s->box.nx > 0 && status == IM_OK)
        return solve_in_box(s, g, w, result);
    /* no patch within reach, a box as large as the window, or no memory for a box's plan: the whole window */
    s->stale = 0;
    return im_solver_solve(g->plan, g->gap0, IM_CONTROL_DISPLACEMENT, w, g->pressure, g->displacement, result);
}

void step_window_refresh(step_window *s, const window_grid *g)
{
    if (!s->stale)
        return;
    im_solver_convolve(g->plan, g->pressure, g->displacement);
    s->stale = 0;
}
