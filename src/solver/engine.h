/* Internal: the grid operations that the one Polonsky-Keer iteration (pk.c) is written over.
 *
 * pk.c holds the algorithm: the cold and cascade starts, the stopping rule, the choice between a
 * plain PK step and a preconditioned CG step, the step length, the restarts, load control and the
 * pressure cap. An engine holds the fields and does the passes over them, each a fused
 * element-wise update with the reductions it needs, and the convolutions:
 *   engine_cpu.c   the plan's own arrays, OpenMP loops and FFTW (the default)
 *   engine_gpu.c   device-resident fields, compute shaders and VkFFT (IM_GPU builds, device = gpu)
 *   mpi/engine_mpi.c  this rank's rows, FFTW-MPI transforms; every sum, count and flag a pass returns
 *                  is global (row-ordered sums: the same bits on every rank, so every rank decides alike)
 * A pass never decides anything: it returns the sums and counts pk.c decides with. Engines give
 * the same answers to the solve's tolerance; they differ in the order of their sums.
 *
 * The patch sets (solver.h, "Hardness"): elastic = 0 < p < cap; moving = elastic, or p = cap and
 * g > 0 (capped and unloading); cap = +inf without a hardness. */
#ifndef INDENTMAP_SOLVER_ENGINE_H
#define INDENTMAP_SOLVER_ENGINE_H

#include "solver/plan.h"

typedef struct gap_stats {
    double approach;            /* w used for these gaps */
    long contact;               /* |I_c| */
    double sum_squares;         /* G = sum over I_c of g^2 */
    double moving_squares;      /* the same over the moving patches (without a cap: G) */
    double penetration;         /* max over the patches at a bound of their violation (0 if none) */
    double penetration_squares; /* sum over p = 0, g < 0 of g^2 */
} gap_stats;

/* The sums of a step length tau = <g, t> / <K t, t> over the moving patches. */
typedef struct step_terms {
    double gt, kt_t, kt_sum, t_sum;
    long count;
} step_terms;

/* How the penetrating patches at p = 0 join in a step: not at all (a preconditioned CG step on I_c),
 * by the gap (plain PK: p = min(-tau g, cap) beside the step, the change added to u afterwards), or in
 * the step's direction (a preconditioned join: the step's set is the moving patches and the penetrating
 * ones, and the preconditioner, the direction, its step length and the update all cover both). */
enum solver_join { SOLVER_JOIN_NONE, SOLVER_JOIN_BY_GAP, SOLVER_JOIN_IN_DIRECTION };

typedef struct pk_run {
    im_solver_plan *plan;
    const double *gap0; /* the caller's undeformed gap */
    enum im_control control;
    double target;
    double *p, *u; /* the caller's pressure (in: a warm start or zeros) and displacement */
    int convolutions;
    int status;            /* IM_OK, or the first failure of an engine pass (a lost GPU) */
    double approach;       /* load control: the last approach taken from the elastic patches (NaN: none) */
    enum solver_join join; /* the current step's (pk.c sets it before the step's passes) */
    /* load control: the rescaling impose_load leaves to the next contact_mean pass (1, 1: none) */
    double p_factor, u_factor;
    /* A cascade handed over on an engine that keeps answers (solver_engine.keeps_answers):
     * start_prolonged: the start is the coarse level's answer, which its solve left on the engine, and
     * begin prolongs it there rather than uploading p (once: a later begin uploads p);
     * keep_answer: this solve is a coarse level whose finer level prolongs its answer on the engine, so
     * finish leaves p and u there (the caller's arrays are not written); answer_kept: it did. */
    int start_prolonged, keep_answer, answer_kept;
} pk_run;

/* How many approaches winkler_loads takes at once: the midpoints of three halvings of a bisection. */
enum { SOLVER_WINKLER_BATCH = 7 };

typedef struct solver_engine {
    const char *name;
    /* Whether a cascade's levels may hand their answers over on the engine (pk_run.keep_answer and
     * start_prolonged; the GPU's: the levels share its buffers), rather than through the host. */
    int keeps_answers;
    /* The solve's inputs onto the engine (gap0, p) and its results back (p, u): nothing on the CPU. */
    int (*begin)(pk_run *r);
    int (*finish)(pk_run *r);
    /* u = K p */
    void (*convolve_pressure)(pk_run *r);
    /* K t of the current direction, kept for step_terms and update_pressure */
    void (*convolve_direction)(pk_run *r);
    /* p *= p_factor, u *= u_factor as scale does (load control's rescaling, fused into this pass), then
     * the mean of u + g0 over the elastic patches, and their count */
    double (*contact_mean)(pk_run *r, double p_factor, double u_factor, double cap, long *count);
    /* g = u + g0 - w, and its statistics (approach left for the caller); on a preconditioned plan
     * also the preconditioner's input for a step without a join: z = g on the moving patches, 0
     * elsewhere (fused here: precondition then masks only for a join) */
    gap_stats (*gaps)(pk_run *r, double w, double cap);
    /* The local (Winkler) guess p = max(w - g0, 0) / k0: its load delta^2 sum p, stored when store */
    double (*winkler)(pk_run *r, double w, double k0, int store);
    /* The local guess's loads at count <= SOLVER_WINKLER_BATCH approaches w (winkler's, p not stored), in
     * one round trip; NULL where winkler's one pass per approach costs no more (CPU, MPI) */
    void (*winkler_loads)(pk_run *r, const double *w, int count, double k0, double *loads);
    /* p = min(p, cap) */
    void (*clip)(pk_run *r, double cap);
    int (*any_positive)(pk_run *r);
    /* delta^2 sum p over the elastic and over the other patches */
    void (*load_split)(pk_run *r, double cap, double *elastic, double *capped);
    /* p = min(p scale, cap) on the elastic patches; returns whether any reached the cap */
    int (*scale_elastic)(pk_run *r, double scale, double cap);
    /* The exact (order-independent) sum of p */
    double (*pressure_sum)(pk_run *r);
    /* p *= p_factor, u *= u_factor (a factor of 1 leaves its field unchanged, bit for bit) */
    void (*scale)(pk_run *r, double p_factor, double u_factor);
    /* The passes below work on the step's set (solver_in_step, r->join). */
    /* t = source + beta t on the step's set, 0 elsewhere; source: g, or z when preconditioned */
    void (*direction)(pk_run *r, int preconditioned, double beta, double cap);
    /* z = M g of g restricted to the step's set (no cap with a preconditioner), from the gaps pass's
     * z = g on it (masked here only with a join); returns sum of z there and the count. z is M g on
     * the step's set only: the passes read it nowhere else (not zeroed there: a write saved) */
    double (*precondition)(pk_run *r, long *count);
    /* z -= mean on the step's set; returns <g, z> there */
    double (*precondition_centre)(pk_run *r, double mean);
    step_terms (*step)(pk_run *r, double cap);
    /* u -= tau K t; p -= tau t on the step's set, projected onto [0, cap]; joining by the gap, the
     * penetrating patches at p = 0 join with min(-tau g, cap). Returns how many patches differ from
     * the plain step (their changes kept for add_point_loads); *joined when any joined. */
    long (*update_pressure)(pk_run *r, double tau, double cap, int *joined);
    /* u += K (the recorded changes), by direct summation; never called when direct_limit is 0 */
    void (*add_point_loads)(pk_run *r, long changes);
    /* sum p, the patches with p > 0 and the largest p */
    void (*summary)(pk_run *r, double *sum, long *contact, double *peak);
    /* The caller's stop flag (options.stop) as the solve must read it: NULL reads it directly (one
     * process); over ranks, as any rank saw it, so that every rank stops at the same iteration. */
    int (*stop_signal)(pk_run *r);
    /* displacement = K pressure for the caller's arrays (im_solver_convolve) */
    int (*convolve_arrays)(im_solver_plan *plan, const double *pressure, double *displacement);
    void (*free)(im_solver_plan *plan);
} solver_engine;

extern const solver_engine solver_engine_cpu;

/* The run of one solve of the caller's arrays on plan's engine (no convolution yet, no approach taken). */
pk_run solver_pk_run(im_solver_plan *plan, const double *gap0, enum im_control control, double target, double *p,
                     double *u);

/* From the start in r->p (a warm start, or zeros: then the local guess) to the answer on the plan's
 * engine, r made by solver_pk_run: no input checks, no cascade, target > 0. Under load control with a
 * cap on the half-space, the approach is searched with displacement-controlled solves (pk.c says why). */
int solver_pk_solve(pk_run *r, im_solve_result *res);

/* A periodic cell under an imposed approach w (no cap): mean u = 0 (solver.h, "Periodic mode"), so
 * the mean gap is mean g0 - w whatever the pressure, and it must stay positive: a cell pressed to a
 * mean gap <= 0 is in full contact, which takes an infinite mean pressure. Whether the check applies,
 * and the check (IM_EINVAL naming both means), given the mean of the undeformed gap. */
int solver_periodic_approach_checked(const im_solver_plan *plan, enum im_control control);
int solver_check_periodic_mean_gap(double mean_gap0, double target);

/* Moves a plan made on the CPU (its spectra computed) onto the GPU engine: a new device for a top
 * plan (finer NULL), the finer level's device for a cascade level. engine_gpu.c, IM_GPU builds. */
int solver_engine_gpu_attach(im_solver_plan *plan, const im_solver_plan *finer);
const char *solver_engine_gpu_device(const im_solver_plan *plan);
/* What a plan of nx x ny with options o (solver_plan_options applied) would need on the GPU engine,
 * before any plan is made: its device memory as the engine counts it when it attaches the plan and its
 * cascade levels (device_bytes), what the engine may fill of the device (device_memory), the host's
 * staging buffers, and whether the device is a CPU one (lavapipe: its memory is the host's). Opens and
 * closes a context on the device o->device would take; its failure as gpu_context_open's. */
typedef struct solver_gpu_estimate {
    double device_bytes, device_memory, staging_bytes;
    int software;
    char device[256];
} solver_gpu_estimate;
int solver_engine_gpu_estimate(int nx, int ny, const im_solver_options *o, solver_gpu_estimate *out);
/* The engine a solve of nx x ny with options o takes given the GPU's estimate, and the memory it needs
 * (solver.h: im_solver_memory_needed): the GPU when its memory holds the plan; else device = auto
 * stays on the CPU with a note, device = gpu fails (IM_ENOMEM naming the device, the memory needed and
 * the memory it has) with the GPU's numbers in *out. plan.c; apart for the tests (lavapipe is never auto's). */
int solver_memory_choose(int nx, int ny, const im_solver_options *o, const solver_gpu_estimate *gpu,
                         im_solver_memory *out);
/* What the Vulkan validation layers reported so far on a GPU plan's device (-1 on the CPU). */
long solver_engine_gpu_validation_messages(const im_solver_plan *plan);
/* The device memory the plan's solver counted before allocating (all its cascade levels and the
 * reductions' buffers: solver_footprint) and what its buffers hold on the device now (the context's
 * count of device-local allocations); -1 for a plan without a GPU. Tests compare the two. */
void solver_engine_gpu_memory(const im_solver_plan *plan, double *counted, double *held);
/* The bytes the plan's device has received from and sent to the host so far (uploads and downloads
 * of fields and tables; not the reductions' few values); -1 for a plan without a GPU. */
void solver_engine_gpu_transfers(const im_solver_plan *plan, double *uploaded, double *downloaded);
/* The submissions the plan's device has waited for so far (gpu_context_submissions: the host's round
 * trips, uploads and downloads among them); -1 for a plan without a GPU. */
long solver_engine_gpu_submissions(const im_solver_plan *plan);

/* p = min(p scale, cap) on the elastic patches of p[0..n); whether any reached the cap (engine_cpu.c,
 * also the MPI engine's pass on its rows). */
int solver_scale_elastic_patches(double *p, size_t n, double scale, double cap);

/* The patch sets, shared by the engines' passes. */
static inline int solver_elastic(double p, double cap) { return p > 0 && p < cap; }
static inline int solver_moving(double p, double g, double cap)
{
    return solver_elastic(p, cap) || (p == cap && g > 0);
}
/* The patches a step moves: the moving ones, and with a join in the direction the penetrating ones at p = 0. */
static inline int solver_in_step(double p, double g, double cap, enum solver_join join)
{
    return solver_moving(p, g, cap) || (join == SOLVER_JOIN_IN_DIRECTION && p == 0 && g < 0);
}
/* Whether a patch outside the step's set joins by the gap (plain PK). */
static inline int solver_joins_by_gap(double p, double g, enum solver_join join)
{
    return join == SOLVER_JOIN_BY_GAP && p == 0 && g < 0;
}
static inline double solver_project(double p, double cap) { return p < 0 ? 0 : (p > cap ? cap : p); }
/* Whether any of the n pressures is positive (a warm start, or a contact left). */
static inline int solver_any_positive(const double *p, size_t n)
{
    for (size_t i = 0; i < n; ++i)
        if (p[i] > 0)
            return 1;
    return 0;
}
/* How far a patch at a bound violates its condition: -g at p = 0, g at p = cap. */
static inline double solver_bound_violation(double p, double g) { return p > 0 ? g : -g; }

#endif
