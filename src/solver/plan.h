/* Internal: the solver plan's layout, shared by plan.c (set-up, convolution) and pk.c (iteration). */
#ifndef INDENTMAP_SOLVER_PLAN_H
#define INDENTMAP_SOLVER_PLAN_H

#include "indentmap/solver.h"

#include <fftw3.h>

struct solver_engine;
struct gpu_solver;
struct im_mpi_solver;

struct im_solver_plan {
    const struct solver_engine *engine; /* whose passes the iteration runs on (engine.h) */
    struct gpu_solver *gpu;             /* the GPU engine's device state (engine_gpu.c), NULL on the CPU */
    /* The MPI engine's ranks and slabs (src/mpi/engine_mpi.c), NULL otherwise. An MPI plan is part of
     * its im_mpi_solver and holds only what pk.c reads: options, delta, kernel (K(0) alone) and a
     * direct_limit of 0; its fields and transforms are the solver's. */
    struct im_mpi_solver *mpi;
    int nx, ny; /* problem grid */
    int px, py; /* padded grid: 2nx x 2ny (periodic: nx x ny, no padding) */
    double delta;
    im_solver_options options;
    /* The tables, computed on the host for every engine; a GPU plan keeps only K(0) of them once its
     * device has them (kernel[0]; spectrum and inverse_spectrum NULL), and has none of the CPU
     * engine's arrays and FFTW plans below (direction ... modes: NULL). */
    double *kernel;   /* nx * ny: K at offset (|dx|, |dy|) delta, for direct summation */
    double *spectrum; /* py * (px/2 + 1): real spectrum of K, divided by px * py */
    /* The preconditioner M (pk.c): 1 / the spectrum of K wrapped periodically on the nx x ny grid
     * itself (divided by nx * ny), applied by an unpadded r2c / c2r pair in place of preconditioned,
     * a quarter of the padded transforms' size. */
    double *inverse_spectrum;         /* ny * (nx/2 + 1) */
    double *preconditioned;           /* nx * ny: the gap in, M g out */
    fftw_complex *precondition_modes; /* ny * (nx/2 + 1) */
    fftw_plan precondition_forward, precondition_backward;
    /* A convolution's plan (solver_convolution_plan_create: im_displacement_plan_create's) holds only
     * what a convolution reads: the spectrum, rows_in and modes; rows_out is rows_in (the c2r writes
     * the result back over the input rows), and it has no kernel table, preconditioner or work arrays. */
    int convolution_only;
    double *rows_in;     /* ny * px: the grid's rows, zero-padded to px (right halves stay 0) */
    double *rows_out;    /* ny * px (a convolution's plan: rows_in) */
    fftw_complex *modes; /* py * (px/2 + 1): the row transforms, then the 2-D transform */
    /* The 2-D transform of the padded grid, pruned: the x transforms of the py - ny zero rows are
     * skipped going forward, and those of the rows outside the result coming back. The column
     * transforms run in place: out of place, FFTW_ESTIMATE's strided column plans were up to 3x
     * slower on large grids (a 3584^2 convolution cost 1.26 full 2-D pairs at 2 threads; in place 0.85). */
    fftw_plan rows_forward, columns_forward, columns_backward, rows_backward;
    double *direction, *gap; /* nx * ny work arrays of the iteration; K t is read from rows_out */
    double uncentred_gz;     /* <g, z> over the step's set from the CPU engine's last precondition pass */
    long *changed;           /* nx * ny: indices of patches changed outside the CG step */
    double *changed_value;   /* their pressure changes */
    long direct_limit;       /* most changes added by direct summation rather than by FFT */
    double plan_seconds;
    int measured;
    int cascade_level; /* 0 for a top plan, 1 for its cascade's first coarser level, ... */
    /* The cascade (cascade.c): the plan of the grid twice as coarse (NULL when cascade is off or the
     * grid is too small), and the coarse problem's gap, pressure and displacement. */
    struct im_solver_plan *coarse;
    double *coarse_gap0, *coarse_pressure, *coarse_displacement;
};

/* The options a plan iterates with: the cascade and the preconditioner are made for an elastic
 * contact set, so with a hardness (a second bound) the iteration keeps plain PK. */
void solver_plan_options(im_solver_options *o);

/* im_solver_plan_create for one level: finer is the plan of the next finer cascade level (NULL for a
 * top plan), whose engine and device a coarse level shares. */
int solver_plan_create_level(int nx, int ny, double delta, const im_solver_options *options,
                             const struct im_solver_plan *finer, struct im_solver_plan **out);

/* A convolution's plan (convolution_only, on the CPU engine unless options ask for another): what
 * im_solver_convolve needs of im_solver_plan_create's, with the same transforms (the same bits);
 * im_solver_solve refuses it. */
/* im_solver_memory_needed for such a plan (im_displacement_memory_needed): on the CPU its peak, the
 * solver plan's estimate on a GPU. */
int solver_convolution_memory_needed(int nx, int ny, const im_solver_options *options, im_solver_memory *out);
int solver_convolution_plan_create(int nx, int ny, double delta, const im_solver_options *options,
                                   struct im_solver_plan **out);

/* Coarse grid sides of a cascade level under an nx x ny grid; 0 when there is none (too small). */
int solver_cascade_sides(int nx, int ny, int periodic, int *cx, int *cy);

/* Creates plan->coarse and its arrays (recursively, down to the smallest level). */
int solver_cascade_create(im_solver_plan *plan);
void solver_cascade_free(im_solver_plan *plan);

/* Cold start from the coarse grids: restricts gap0, solves there (itself started from the next
 * level), and prolongs the pressure into pressure. Returns the coarse iterations of all levels;
 * pressure stays all zero when the coarse grids found no contact. On an engine that keeps answers
 * (engine.h) the coarse answer stays there: *prolonged is then set, and the fine solve's begin
 * prolongs it on the engine (pressure is left as it was, all zero); else *prolonged is 0. */
int solver_cascade_start(im_solver_plan *plan, const double *gap0, enum im_control control, double target,
                         double *pressure, int *prolonged);
/* im_solver_solve of a cascade's coarse level, from zero pressure on a gap restricted from a checked
 * one: only the periodic approach is checked (the rest holds by construction), on mean_gap0, the mean
 * of gap0 that the restriction summed (sum_doubles' value). keep: its answer may stay on the engine for
 * the finer level (pk_run.keep_answer); *kept when it did, and then pressure and displacement are not
 * written. pk.c. */
int solver_solve_coarse(im_solver_plan *coarse, const double *gap0, double mean_gap0, enum im_control control,
                        double target, double *pressure, double *displacement, int keep, im_solve_result *result,
                        int *kept);

/* The pieces of a cascade start that the distributed solver (mpi/cascade.c) shares, so that its
 * coarse levels see the serial plan's numbers to the bit:
 * the options of a coarse level (the fine level's, at a tolerance no tighter than the cascade's); */
im_solver_options solver_cascade_options(const im_solver_options *fine);
/* the sum and count of the finite values of the x pair (2 cx, 2 cx + 1) of a fine row of nx; */
void solver_cascade_pair_sum(const double *row, int nx, int cx, double *sum, int *count);
/* a coarse gap from its block's upper and lower pair sums and their count (+inf for none); */
double solver_cascade_block_mean(double upper, double lower, int count);
/* the coarse solve (from zero pressure; mean_gap0: the coarse gap's mean, summed as sum_doubles sums it), its
 * iterations over all levels; *usable unless it broke down; */
int solver_cascade_solve(struct im_solver_plan *coarse, const double *coarse_gap0, double mean_gap0,
                         enum im_control control, double target, double *coarse_pressure, double *coarse_displacement,
                         int *usable);
/* a fine row of nx prolonged from its coarse row (0 where the fine gap is infinite); whether any > 0. */
int solver_cascade_prolong_row(const double *coarse_row, const double *gap_row, int nx, double *pressure_row);

/* Executes a one-off plan and destroys it (under the planner lock). */
void solver_execute_once(fftw_plan plan);

/* modes[k] *= spectrum[k] (a real, even kernel's spectrum) for k < count. */
void solver_multiply_modes(fftw_complex *modes, const double *spectrum, size_t count);

/* The transform pairs the CPU engine has run since the process started, by kind: convolutions with K
 * and preconditioner pairs on top plans, and every pair on a cascade's coarser levels (bench/bench_floor.c
 * counts a solve's work from them). One relaxed atomic increment per pair. */
enum solver_pair_kind { SOLVER_PAIR_K, SOLVER_PAIR_M, SOLVER_PAIR_COARSE, SOLVER_PAIR_KINDS };
void solver_count_pair(const im_solver_plan *plan, enum solver_pair_kind kind);
long solver_pairs_run(enum solver_pair_kind kind);
/* The grid points of the cascade levels' pairs since the process started (each pair counts the points of
 * the grid it transforms: px py for K, nx ny for M): over a top plan's px py, its coarse pairs in K pairs. */
long long solver_coarse_points_run(void);
/* The grids of the last top plan that ran a convolution: K's (px x py) and the problem's (nx x ny), which
 * an indentation's step box may make smaller than its window's. */
void solver_last_top_grid(int *px, int *py, int *nx, int *ny);

/* Transforms rows_in (filled by the caller: the grid's rows, stride px) and leaves the
 * convolution with K in rows_out (stride px, the first nx values of each of the ny rows). */
void solver_convolve_rows(im_solver_plan *plan);

/* displacement += sum_k value[k] K(x - x_index[k]) over the grid (direct summation). */
void solver_add_point_loads(const im_solver_plan *plan, const long *index, const double *value, long count,
                            double *displacement);

/* The periodic half-space's kernel (periodic.c): spectrum 2 / (E* |q|) with a zero mean mode, and
 * its real-space values for direct sums (options.periodic). IM_OK or IM_ENOMEM. */
int solver_periodic_kernel(im_solver_plan *plan);

/* The periodic half-space's mode (kx, ky) of the plan's nx x ny grid (kx <= nx / 2, ky < ny, index
 * ky > ny / 2 standing for ky - ny): K's spectrum 2 / (E* |q|) and the preconditioner's E* |q| / 2,
 * both divided by nx ny, 0 on the mean mode. Shared by the serial plan and the MPI engine. */
void solver_periodic_mode(const im_solver_plan *plan, int kx, int ky, double *spectrum, double *inverse);

#endif
