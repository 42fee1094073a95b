/* indentmap/solver.h: frictionless normal contact of a rigid punch with a rough elastic half-space,
 * by FFT boundary elements and Polonsky-Keer constrained conjugate gradients.
 *
 * Entry points:
 *   im_solver_options_default, im_solver_options_check   what a solve does (tolerance, engine, ...)
 *   im_indentation_create, im_indentation_step, im_indentation_free   a history of steps on one surface
 *   im_indentation_fields, im_indentation_fields_full    a step's force, gap and displacement
 *   im_flat_contact_create, im_flat_contact_solve, im_flat_contact_free   a periodic cell under a flat
 *   im_solver_plan_create, im_solver_solve, im_solver_plan_free   one solve on a planned grid
 *   im_displacement_full                                 a force field's displacement
 *
 * ---- Model and conventions ----
 * The surface is an nx x ny grid of square patches of side delta (field.h layout), heights h up;
 * the punch comes from above. Each patch carries a uniform pressure p >= 0; its force is
 * f = p delta^2. The surface displacement u (positive = pushed into the half-space, i.e. down) at
 * a patch centre is the linear (NOT periodic) convolution
 *     u_i = sum_j K(x_i - x_j) p_j,   K(x, y) = (1 / (pi E*)) integral over the patch of dA / r,
 * Love's closed form for a uniformly loaded rectangle, evaluated in a cancellation-free asinh form
 * (im_influence_square). E* = E / (1 - nu^2) is the composite modulus.
 * Gap. With z(r) the punch profile (indenter.h) and the undeformed gap at first touch
 *     g0_i = z(|x_i - axis|) - h_i - min_j (z_j - h_j)        (so min g0 = 0),
 * the gap at approach w is
 *     g_i = g0_i - w + u_i.
 * w is the rigid approach counted from first touch: at w = 0 the punch touches the patch of least
 * undeformed gap. A solution has p_i >= 0, g_i >= 0 and p_i g_i = 0; a patch is in contact when
 * its force is positive.
 *
 * ---- Discretisation of the convolution ----
 * DC-FFT: pressures are zero-padded to a 2nx x 2ny grid and multiplied in Fourier space by the
 * spectrum of K sampled on the same padded grid with wrap-around offsets; the product's nx x ny
 * quadrant is the exact linear convolution. FFTW real-to-complex / complex-to-real transforms; K
 * is even, so its spectrum is real and stored as such (with the 1 / (4 nx ny) normalisation).
 * The 2-D transform is done as row then column transforms so that the x transforms of the ny zero
 * rows (forward) and of the ny rows that are not needed (backward) are skipped: about 0.65-0.75 of
 * a full padded r2c + c2r pair (measured, bench/bench_solver.c).
 *
 * ---- Algorithm (Polonsky & Keer 1999, Wear 231:206) ----
 * Conjugate gradients on the contact set I_c = {p > 0}, restarted whenever patches with p = 0 and
 * g < 0 join; negative pressures are clipped to zero. Displacement control imposes w. Load control
 * imposes N = delta^2 sum p: the approach is the mean of (u + g0) over I_c, gaps and search
 * responses have their I_c mean removed, and p is rescaled to the load each iteration (PK's own
 * variant; cheaper than an outer loop on w, which costs several displacement solves per step).
 * One convolution per iteration in the steady state (two with the preconditioner, below): u is updated as u - tau K t, and the few
 * patches that the clipping or the restarts change are added back by direct summation against the
 * stored kernel (a full convolution only when they are many).
 *
 * ---- Preconditioning (default; option precondition = 0 for plain PK) ----
 * Plain CG's rate is set by K's spread of eigenvalues on the contact set, which grows with the
 * contact's size in patches (K ~ 1 / (E* |k|)): cold solves took 104 / 167 / 231 iterations at
 * 512^2 / 1024^2 / 2048^2. The steps that keep the contact set are preconditioned CG steps with
 * z = M g on I_c, M ~ E* |k| the inverse of the spectrum of K's samples wrapped periodically on
 * the nx x ny grid (unpadded: a transform pair a quarter of a convolution's size), and 3-5x fewer
 * iterations. Patches join (g < 0 outside I_c) only in a join step, a preconditioned steepest-descent
 * step over I_c and the joining patches together (z = M g on both, its exact step length over both),
 * taken when the penetration outside I_c outweighs the gap left on it, sum over p = 0, g < 0 of g^2
 * > sum over I_c of g^2 (Dostal's proportioning test), or its largest value > 4 times the rms gap
 * on I_c (the stopping rule's terms); the next step restarts the conjugacy.
 * Letting patches join in every step, as plain PK does, restarted the conjugacy at almost every
 * step. Clipping may shrink I_c in any step. In the periodic mode K is circulant and M is its exact
 * inverse E* |q| / 2 (0 on the mean mode). Neither this nor the cascade below is used with a
 * hardness (a second bound): plain PK there.
 *
 * ---- Cascade start (default; option cascade = 0 for the local guess) ----
 * A cold solve (all-zero pressure in) on a grid whose halves are at least 32 patches a side first
 * solves the problem restricted to patches of side 2 delta (gap0: the mean of each 2 x 2 block's
 * finite values; the same target approach or load; tolerance max(tol, 1e-4)), itself started the
 * same way from 4 delta patches and so on, and starts from that pressure, prolonged piecewise
 * constant (zero where gap0 is infinite). Bemporad & Paggi 2015 (arXiv 1506.00532). The coarse
 * plans are made with the fine one (about a third more memory) and reused. The answer is the fine
 * solve's, to the same stopping rule: tested equal to plain PK's at tol 1e-10 (identical contact
 * sets). A periodic cell is halved only while both sides are even (a coarse cell keeps the period).
 *
 * ---- Stopping rule ----
 * residual = max( rms over I_c of g ,  max over p = 0 of (-g) ) / w   (with a hardness, also g at p = H_p)
 * i.e. the rms gap left in the contact set and the worst penetration outside it, relative to the
 * approach. A solve stops when residual <= tol (default 1e-6), taken on the incrementally updated u
 * where it is below tol by more than that u's rounding can move it (a bound, about 1e-11 after 40 steps),
 * else on u recomputed exactly by FFT; IM_ENOCONV after max_iterations (default 10000)
 * iterations. Both the iteration count and the residual are reported for every solve. A solve whose
 * options.stop flag is set ends with IM_EINTERRUPTED after the iteration in progress.
 *
 * Misuse (status.h): IM_EINVAL for a NULL plan, run, array or output, an invalid field view or a
 * grid side outside [1, IM_FIELD_MAX_SIDE]. The getters of a NULL plan or run give NaN, NULL, 0 or
 * an all-zero window, im_solver_convolve does nothing, im_solver_plan_bytes is NaN for such sides.
 * NULL options mean the defaults (plans, indentations, flat contact, im_displacement_*) and no
 * wisdom file (im_solver_wisdom_file); the *_free functions accept NULL.
 *
 * Threads: a plan, an indentation or a flat contact is used by one thread at a time; distinct ones
 * may be made and solved in different threads at once on the CPU engine (scenes' ensembles do).
 * The library holds one lock around FFTW's planner and wisdom for all its own calls; an application
 * that calls FFTW's planner itself meanwhile races with it (FFTW's planner is not thread-safe). Each
 * solve runs on at most the OpenMP thread count in force, fewer while other processes hold the
 * cores, unless OMP_NUM_THREADS or OMP_WAIT_POLICY is set (docs/solver.md, "Threads"); the caller's
 * count is restored after. A plan gives the same bits whatever the team that solves with it; plans
 * made at different thread counts agree to a few ulp (loads compensated). GPU plans
 * (options.device) are made and used from one thread.
 */
/* ---- Hardness (perfect plasticity at a pressure cap) ----
 * With options.hardness = H_p > 0 no patch carries more than H_p: a patch whose elastic pressure
 * would exceed it yields and carries exactly H_p. The solution then satisfies, patch by patch,
 *     p = 0       and g >= 0   (out of contact)
 *     0 < p < H_p and g = 0    (elastic contact)
 *     p = H_p     and g <= 0   (plastic contact: -g is the surface's plastic flattening)
 * The iteration is the same with I_c = {0 < p < H_p}, every update projected onto [0, H_p], and
 * patches at either bound that violate their condition released by a local step; the stopping rule's
 * penetration term counts g > 0 at p = H_p as well. Under load control on the half-space the load is
 * found by displacement-controlled solves on the approach (bracketed from w = 0, narrowed by regula
 * falsi, each warm-started from the last: 5-9 times the iterations of the one displacement-controlled
 * solve at the approach found), because Polonsky-Keer's own load control breaks down with a cap (a
 * negative step length); a load the cap does not let the punch carry is IM_EEDGE. On a periodic cell
 * the elastic pressures are rescaled to the mean pressure with the capped ones fixed, and u is
 * recomputed by FFT (one convolution more per iteration while a patch is capped). The cone's apex singularity and a flat punch's edge are capped;
 * in the fully plastic limit A = N / H_p.
 * Memory (an indentation, im_indentation_step): after each step the overlap -g of every capped patch
 * is added to its plastic depth d and to its undeformed gap (g0 + d: the surface pushed down by d),
 * as the BEM elastic-perfectly-plastic models of Almqvist et al. (2007) and Sahlin et al. (2010) do.
 * The solved state stays a solution (g = 0 there now) and the next step sees the deformed surface:
 * unloading is elastic, reloading retraces the unloading curve until a patch reaches H_p again, and
 * the energy H_p delta^2 sum(increments of d) is dissipated (im_step_result). The gaps that
 * im_indentation_fields reports are those of the deformed surface. The approach w stays counted
 * from first touch of the undeformed surface. A single im_solver_solve has no memory. */

/* ---- Engines ----
 * The iteration is written once (src/solver/pk.c) over an engine of grid passes (engine.h): the
 * CPU engine (OpenMP, FFTW) and, in builds with IM_GPU, a Vulkan compute engine (VkFFT, double
 * precision), whose fields stay on the device for a whole solve. Both solve the same problem to the
 * same stopping rule; their sums run in a different order, so results agree to the tolerance, not
 * bit for bit. The GPU engine recomputes u by FFT where the CPU engine adds a few changes by direct
 * summation, and needs grid and transform sides that factor into 2, 3, 5, 7, 11 and 13. */

/* ---- Periodic mode (nominally flat contact) ----
 * With options.periodic the grid is one period of a periodic surface pressed by a rigid flat under
 * a mean pressure. The convolution is circular on the nx x ny grid (no padding) with the periodic
 * half-space's response u(q) = 2 p(q) / (E* |q|) (Johnson, Contact Mechanics, 13.2): the spectrum
 * of the sampled pressure is multiplied by 2 / (E* |q|), q = 2 pi (kx / (nx delta), ky / (ny delta))
 * with the wrapped (signed) mode numbers, and the mean (q = 0) mode by 0, which fixes the free
 * rigid displacement of a periodic half-space so that mean u = 0. Its real-space value at the
 * origin tends to Love's 4 delta asinh(1) / (pi E*) on fine grids (the Brillouin zone's mean of
 * 2 / (E* |q|)). Under load control the reported approach is the mean of u + g0 over the contact.
 * With mean u = 0 an approach w also fixes the mean gap over the cell, mean g0 - w, whatever the
 * pressure: displacement control is mean-gap control (Persson's u-bar). Without a hardness it needs
 * w < mean g0 (IM_EINVAL otherwise): a mean gap <= 0 is full contact at an infinite pressure. */
/* ---- Adhesion (the Maugis-Dugdale law, and an exponential one) ----
 * With options.adhesion_work = w > 0 and adhesion_range = delta_c the surfaces attract: a constant
 * tensile stress sigma0 = w / delta_c acts on every patch whose gap is at most delta_c, and on the
 * patches in contact (Maugis 1992; Johnson & Greenwood 1997). The net pressure is
 *     p = p_r - sigma0   on the adhesive zone Z = {g <= delta_c} (contact included),  p = p_r elsewhere,
 * with the repulsive part p_r >= 0, g >= 0, p_r g = 0 (the stress is continuous at the contact's edge:
 * no JKR singularity). The work of separating a patch is sigma0 delta_c = w. A patch cut by the
 * zone's edge carries the stress on its share of Z (the gap taken linear across it). Given Z this is
 * the repulsive problem with the undeformed gap g0 - sigma0 K 1_Z; an indentation step alternates that
 * solve (any engine) with Z taken from its gaps until no share would move by more than tol / 100
 * (src/solver/adhesion.c). The passes are monotone: a step whose approach is not below the last
 * one's only adds to Z, a retraction only removes from it, so each step ends on the state its history
 * leads to (jump-in on approach, pull-off on retraction: the hysteresis). Each pass is one
 * warm-started solve and one convolution.
 * Resolution: Z must span patches. A Dugdale zone's length at a crack tip is of the order of
 * l = pi E* w / (8 sigma0^2); a sphere's pull-off force is within 0.6% of Maugis-Dugdale's at
 * l = 3 patches, 8% at l = 0.33, and far off (several times too strong) at l < 0.1: the JKR limit
 * (lambda -> infinity, l -> 0) needs grids fine enough for l (im_adhesion_zone_length), or a law of the same
 * work whose zone spans a patch (adhesion_zone below: a smoother law, the pull-off within 2-5% at mu = 10).
 * Controls: displacement or load on the half-space, mean gap on a periodic cell. A hardness H_p goes with
 * it on the half-space (a periodic cell refuses it, IM_EINVAL): the repulsive part is capped at
 * H_p + sigma0, so the net pressure lies in [-sigma0, H_p], and the flattening is kept across steps as
 * under "Hardness" (an unloading and its pull-off are those of the flattened profile). Approaches and loads may be negative (the punch pulled away, the contact under tension):
 * im_indentation_step takes targets in [-largest, largest]. Under load control a step walks forward over
 * the approach from the last step's state (the first approach met that carries the load, on the stable
 * branch) and refuses a load beyond the pull-off force with IM_EINVAL naming the least load the
 * retraction held (the contact jumps out there), leaving the state as it was. The window is
 * chosen for g0 <= largest + 2 delta_c; a step whose zone reaches the window's outer row or column
 * fails with IM_EEDGE (solve the whole surface: crop = 0). Step results give the net load (negative
 * under tension), the tensile force and the patches under tension and under compression;
 * contact_patches are those with p_r > 0 (g = 0). Fields report the net force and displacement.
 * The exponential law (adhesion_law = IM_ADHESION_EXPONENTIAL, adhesion_range = rho): the tension
 * sigma(g) = (w / rho) exp(-g / rho) at a gap g >= 0, w / rho in repulsive contact (the work of separation
 * is w), cut to 0 beyond g = 35 rho (below 1e-15 of its peak). The same passes, each patch carrying the
 * mean of sigma over it (the gap linear across it) as its share of the peak w / rho; the window is chosen
 * for g0 <= largest + 36 rho. Near the jumps its passes slow down as the zone's do (docs/solver.md). */
#ifndef INDENTMAP_SOLVER_H
#define INDENTMAP_SOLVER_H

#include "indentmap/field.h"
#include "indentmap/indenter.h"

#include <signal.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The tolerances every front end accepts (im_solver_options_check; --tol, [solver] tol, Python's tol):
 * below 1e-15 the residual, relative to the approach, is at double precision's rounding of the gaps
 * (it scatters between 1e-16 and 1e-14 on 256^2-512^2 grids), which no iteration lowers; a tol there is
 * refused rather than iterated to max_iterations. Between 1e-15 and the stopping rule's rounding bound
 * (about 1e-13 on 128^2, 5e-13 on 512^2) a solve may end with IM_ENOCONV once its residual has reached
 * that bound and stopped falling, naming a tol that works; a coarser tol is never stopped so. */
#define IM_SOLVER_TOL_MIN 1e-15
#define IM_SOLVER_TOL_MAX 0.5

typedef struct im_solver_options {
    double e_star;           /* composite modulus E* (default 1) */
    double tol;              /* stopping tolerance on the relative residual (default 1e-6,
                               IM_QUALITY_DEFAULT), in [IM_SOLVER_TOL_MIN, IM_SOLVER_TOL_MAX] */
    int max_iterations;      /* iteration cap per solve (default 10000) */
    int fft_measure;         /* 1: plan with FFTW_MEASURE; 0 (default): FFTW_ESTIMATE, unless a
                               wisdom file is in use, which implies FFTW_MEASURE */
    const char *wisdom_path; /* FFTW wisdom file imported before planning and exported (merged with
                               what the file holds then, replaced atomically) after it; NULL
                               (default) or "": no wisdom. Not owned. The library reads no
                               environment: the command line resolves its default (docs/solver.md) */
    int crop;                /* 1 (default): solve on the window that can touch; 0: whole surface */
    int window_margin;       /* patches added around the window on each side (default 4) */
    int periodic;            /* 0 (default): the half-space, DC-FFT on the zero-padded grid; 1: a
                               periodic half-space (the grid repeats in x and y), for nominally flat
                               contact: no padding, the kernel's spectrum 2 / (E* |q|) (see
                               "Periodic mode" above); load control only; im_flat_contact_* set it */
    double hardness;         /* 0 (default): none; H_p > 0: perfect plasticity at the pressure cap
                               H_p (units of E*'s stress), see "Hardness" above */
    int cascade;             /* 1 (default): cold starts from the solution on coarser grids (see
                               "Cascade start" above); 0: from the local (Winkler) guess */
    int precondition;        /* 1 (default): preconditioned CG steps on the contact set (see
                               "Preconditioning" above); 0: plain Polonsky-Keer */
    /* Cancellation (NULL, the default: none). A flag the caller owns, typically set by a signal handler
     * to the signal's number, that must outlive every solve of the plans made with these options (a
     * plan keeps the pointer). Each solve (im_solver_solve, the cascade's coarse solves,
     * im_indentation_step, im_flat_contact_solve, im_mpi_solver_solve) reads it once per iteration and,
     * once non-zero, stops within one iteration with IM_EINTERRUPTED ("contact solve: interrupted by
     * signal N after K iterations"): pressure and displacement then hold the last iterate (p >= 0, a
     * valid warm start) and the plan stays usable, so the same solve run again with the flag cleared
     * gives the uninterrupted answer. Not in the solve's key (it does not change a result). */
    const volatile sig_atomic_t *stop;
    /* The engine the solves run on (see "Engines" above): IM_DEVICE_CPU (default), IM_DEVICE_GPU
     * (a Vulkan device: a hardware GPU when there is one, else a CPU implementation such as lavapipe;
     * IM_EUNSUPPORTED without any, or in a build without IM_GPU), IM_DEVICE_AUTO (a hardware GPU when
     * there is one, else the CPU engine: a software Vulkan device is never chosen for speed). */
    int device;
    int gpu_validation; /* 1: run the GPU engine under the Vulkan validation layers (tests, debugging);
                               IM_EUNSUPPORTED when they are not installed */
    /* Adhesion (see "Adhesion" above; 0, the default: none). It acts in an indentation only: a plan
     * made with adhesion_work > 0 is refused (a single solve is the repulsive problem). */
    double adhesion_work;  /* work of adhesion w (E*'s stress times length), the Maugis-Dugdale law's */
    double adhesion_range; /* delta_c > 0 (length): the gap up to which the stress w / delta_c pulls;
                               the exponential law's decay length rho */
    int adhesion_law;      /* enum im_adhesion_law (default IM_ADHESION_MAUGIS_DUGDALE) */
    double adhesion_zone;  /* 0 (default): the law as given; P > 0 (the Maugis-Dugdale law only): an
                               indentation solves the law of the same work whose Dugdale zone spans at
                               least P patches (im_adhesion_solved_law), a smoother one where the
                               given zone is narrower (docs/solver.md, "Across Tabor's mu") */
} im_solver_options;

/* The cohesive laws of "Adhesion" above. */
enum im_adhesion_law { IM_ADHESION_MAUGIS_DUGDALE = 0, IM_ADHESION_EXPONENTIAL = 1 };

/* "maugis-dugdale", "exponential" -> IM_ADHESION_*; IM_EINVAL naming the word otherwise. */
int im_adhesion_law_parse(const char *word, int *law);
/* The law's name as run.json states it ("Maugis-Dugdale", "exponential"); NULL for another value. */
const char *im_adhesion_law_name(int law);

enum im_device { IM_DEVICE_CPU = 0, IM_DEVICE_GPU = 1, IM_DEVICE_AUTO = 2 };

/* "cpu", "gpu", "auto" -> IM_DEVICE_*; IM_EINVAL naming the word otherwise. */
int im_device_parse(const char *word, int *device);

/* The defaults: E* = 1, tol im_quality_default_tolerance(), at most 10000 iterations, FFTW_ESTIMATE
 * without wisdom, crop windows (margin 4), the cascade start and the preconditioner, no hardness,
 * adhesion or periodic mode, the CPU engine. */
im_solver_options im_solver_options_default(void);
/* IM_EINVAL naming the first option out of range. */
int im_solver_options_check(const im_solver_options *options);

/* The wisdom file the options name (wisdom_path), or NULL for none (NULL or ""). */
const char *im_solver_wisdom_file(const im_solver_options *options);
/* IM_OK when the wisdom file (if any) may be read and replaced: missing, empty or FFTW wisdom, and
 * no input of the process (io.h: im_output_protect). Otherwise IM_EINVAL naming the file and what it
 * holds (a surface, a scene, a device). Planning checks it too, before reading the file; callers check
 * it before any work. */
int im_solver_wisdom_check(const im_solver_options *options);
/* im_solver_wisdom_check, then whether FFTW accepts the file's text: IM_OK when it does, or when the
 * file is missing or empty (it is then imported into the process's wisdom, as planning would);
 * IM_EFORMAT naming the file when FFTW rejects it (damaged, truncated, or another FFTW version's).
 * Planning never fails on such a file: it plans afresh and replaces it; this lets a caller say so.
 * Thread-safe (FFTW's planner is locked). */
int im_solver_wisdom_verify(const im_solver_options *options);

/* Quality presets: the stopping tolerance of a named speed/accuracy trade-off.
 *   draft        1e-5   N within 1.8e-5, n_p within 3.5e-4, 0.85x the iterations of standard
 *   standard     1e-6   N within 1.9e-6, n_p within 1.0e-4
 *   publication  1e-9   N within 1.8e-9, n_p exact, 1.44x the iterations of standard
 * N within 2 tol throughout (measured again with the preconditioned, cascaded solver, redteam4; the
 * first measurement, before them: 1.4e-5 / 1.0e-6 / 1.1e-9, 0.73x and 1.6x the iterations)
 * (the largest relative errors against tol 1e-11 over the paper's history: 25 approaches
 * w = 1.26..31.5 of an 80 degree cone on the 512 x 512 h'rms = 0.08 surface, seed 1; docs/benchmarks.md,
 * "Speed against accuracy"). An explicit tol overrides a preset wherever both can be given.
 * IM_EINVAL naming the name for anything else. */
int im_quality_tolerance(const char *name, double *tol);

/* The default of every front end and of im_solver_options_default: the standard preset, tol 1e-6
 * (`indent` without --quality or --tol, a scene without quality or [solver] tol). A tighter
 * tolerance is asked for explicitly (--tol, --quality publication, options.tol). */
#define IM_QUALITY_DEFAULT "standard"
double im_quality_default_tolerance(void);

/* Displacement at a patch centre offset (x, y) from the centre of a delta x delta patch carrying
 * unit pressure, for composite modulus e_star (Love 1929). At (0, 0): 4 delta asinh(1) / (pi E*). */
double im_influence_square(double x, double y, double delta, double e_star);

/* ---- plan / execute on one grid size ---- */
typedef struct im_solver_plan im_solver_plan;

/* Plans an nx x ny problem (FFTW plans on the 2nx x 2ny padded grid, the kernel and its spectrum,
 * work buffers) with the OpenMP thread count in force. Thread-safe (the planner lock above).
 * IM_ENOMEM when im_solver_plan_bytes exceeds the memory available. */
int im_solver_plan_create(int nx, int ny, double delta, const im_solver_options *options, im_solver_plan **out);
void im_solver_plan_free(im_solver_plan *plan);

/* Memory a plan takes, in bytes, with its cascade levels (the default options; less without). */
double im_solver_plan_bytes(int nx, int ny);
/* The memory a solve of an nx x ny grid needs with these options (NULL: the defaults), by the engine
 * options->device takes, before any plan is made (scenes' limits, indentmap info --memory). Not counted:
 * the caller's fields (surface, gap, pressure, displacement), VkFFT's twiddle tables and the driver's
 * own memory (on lavapipe its compiled shaders: about 150 MiB). device = cpu: the CPU plan
 * (im_solver_plan_bytes; one level where the options have no cascade, or a cap turns it off). gpu: the GPU engine's device memory, its buffers and those of its cascade
 * levels as the engine counts them before allocating (exact), and the host's peak (the tables and their
 * temporaries while computed, the staging buffers, the cascade's coarse arrays; with the device memory
 * on a CPU device such as lavapipe, whose memory is the host's); IM_ENOMEM naming the device, the memory
 * needed and the memory it has when it does not hold them (*out then has the GPU's numbers), or the
 * engine's refusal (IM_EUNSUPPORTED: no GPU engine, no device). auto: the GPU's when a hardware GPU
 * opens and holds the plan, else the CPU's, with a note in out->note when the GPU's memory was too
 * small. The opening and closing of a Vulkan device takes a fraction of a second. IM_EINVAL for a NULL
 * out or invalid sides or options, and under gpu and auto alike for an INDENTMAP_GPU_MAX_MEMORY (or
 * _MAX_PART, _MAX_BUFFER) that is not a whole number of bytes >= 4096, naming it and its text. */
typedef struct im_solver_memory {
    int gpu;              /* 1: the GPU engine solves it; 0: the CPU engine */
    double host_bytes;    /* the plan's host memory at its peak */
    double device_bytes;  /* on the GPU: its buffers' device memory; 0 on the CPU */
    double device_memory; /* the GPU's memory that the engine may fill (INDENTMAP_GPU_MAX_MEMORY, bytes,
                             lowers it for tests); 0 when no GPU was opened */
    char device[256];     /* "cpu", or the GPU's name */
    char note[512];       /* device = auto on the CPU because the GPU's memory is too small: why; else "" */
} im_solver_memory;
int im_solver_memory_needed(int nx, int ny, const im_solver_options *options, im_solver_memory *out);
/* The same estimate for a plan as made: its grid and the options it was made with, which a caller's may
 * not be (an indentation's plan solves the repulsive problem: no adhesion, the cap H_p + w / delta_c;
 * a cap turns the cascade and the preconditioner off), and its device as asked (auto: the note says
 * why a plan that stayed on the CPU did). IM_EINVAL for a NULL plan or out; else as above. */
int im_solver_plan_memory(const im_solver_plan *plan, im_solver_memory *out);
/* Seconds spent planning (FFTW planning plus the kernel spectrum). */
double im_solver_plan_seconds(const im_solver_plan *plan);
/* The engine a plan's solves run on: "cpu", or the GPU's device name. */
const char *im_solver_plan_device(const im_solver_plan *plan);
/* 1 if the plan was made with FFTW_MEASURE. */
int im_solver_plan_measured(const im_solver_plan *plan);

/* u = K p on the plan's grid (nx * ny values each; displacement may be pressure itself: in place). */
void im_solver_convolve(im_solver_plan *plan, const double *pressure, double *displacement);

/* The displacement u = K p (positive into the half-space, units of force->delta) on the whole grid
 * of force (force per patch f = p delta^2, as im_indentation_fields gives it), for the modulus
 * options->e_star. The solver computes u only in its window and im_indentation_fields reports 0
 * outside it; what is written or drawn uses this instead (the deformed surface h - u would show a
 * step at the window's edge). Plans one full-grid convolution per call (FFTW_ESTIMATE; wisdom as
 * options says). Returns IM_OK and a new field in *displacement (the caller frees it), or IM_ENOMEM
 * when the plan would not fit in memory. */
int im_displacement_full(const im_field *force, const im_solver_options *options, im_field **displacement);

/* The same with a plan made once for many fields of one grid (frames, steps): the plan of
 * im_displacement_plan_create, a convolution's (on the CPU: the kernel's spectrum and the padded
 * transform's arrays only, about 64 B per patch held and 80 B while planned, against a solver plan's
 * 140 and more; the same FFTW_ESTIMATE transforms, so the same u to the bit; im_solver_convolve takes
 * it, im_solver_solve refuses it), used by im_displacement_full_with (IM_EINVAL for a force field of
 * another grid). */
int im_displacement_plan_create(int nx, int ny, double delta, const im_solver_options *options,
                                im_solver_plan **plan);
/* im_solver_memory_needed for the plan im_displacement_plan_create makes of nx x ny under options (what
 * im_solver_plan_memory says of it once made), without making it: a scene's estimate. */
int im_displacement_memory_needed(int nx, int ny, const im_solver_options *options, im_solver_memory *out);
int im_displacement_full_with(im_solver_plan *plan, const im_field *force, im_field **displacement);

/* What a solve or a step imposes: the approach w, the load N, or (im_indentation on a periodic cell
 * only) the mean gap over the cell, the mean of max(g, 0): Persson's u-bar (see "Periodic mode"). */
enum im_control { IM_CONTROL_DISPLACEMENT = 0, IM_CONTROL_LOAD = 1, IM_CONTROL_MEAN_GAP = 2 };

typedef struct im_solve_result {
    double approach;      /* w (imposed, or found under load control) */
    double load;          /* N = delta^2 sum p */
    long contact_patches; /* n_p: patches with p > 0 */
    double mean_pressure; /* N / (n_p delta^2), 0 without contact */
    double max_pressure;
    int iterations;        /* CG iterations (one search-direction convolution each) */
    int convolutions;      /* all convolutions with K, including the exact recomputations (not
                               the preconditioner's unpadded transforms) */
    double residual;       /* the stopping rule's value at exit */
    double seconds;        /* wall time of the solve */
    int coarse_iterations; /* CG iterations on the cascade's coarser grids (all levels; one on the
                               grid 2^k times coarser costs ~4^-k of a fine one); 0 without cascade */
} im_solve_result;

/* Solves one contact problem on the plan's grid. gap0: undeformed gap at first touch (>= 0;
 * +INFINITY for patches that can never touch). target: w >= 0 (displacement control) or N >= 0
 * (load control). pressure: in: warm start (any p >= 0; all zero for a cold start), out: the
 * solution. displacement: out, u = K p. result may be NULL. IM_ENOCONV after the cap (pressure and
 * displacement hold the last iterate and result its residual); IM_ENUMERIC if the iteration breaks
 * down (non-finite values). */
int im_solver_solve(im_solver_plan *plan, const double *gap0, enum im_control control, double target,
                    double *pressure, double *displacement, im_solve_result *result);

/* ---- nominally flat contact: a periodic surface under a rigid flat ---- */
typedef struct im_flat_result {
    double mean_pressure;    /* the imposed nominal mean pressure p_m, units of E* */
    double area_fraction;    /* A / A0 = n_p / (nx ny) */
    long contact_patches;    /* n_p */
    double contact_pressure; /* mean pressure over the contact, p_m / (A / A0); 0 without contact */
    double max_pressure;
    double approach; /* mean of u + g0 over the contact, with mean u = 0 (the imposed one
                                  under mean-gap control) */
    double mean_gap; /* the mean gap over the cell, mean g0 - approach (mean u = 0) */
    int iterations;
    double residual;
} im_flat_result;

typedef struct im_flat_contact im_flat_contact;

/* Prepares nominally flat, periodic contact of surface (heights in units of its delta, one period
 * in x and y; not referenced after the call) with a rigid flat: g0 = max h - h. options may be NULL
 * (defaults); its periodic flag is set here, crop and window are unused. IM_ENUMERIC for NaN/Inf
 * heights, IM_EINVAL for bad options, IM_ENOMEM. */
int im_flat_contact_create(const im_field *surface, const im_solver_options *options, im_flat_contact **out);
void im_flat_contact_free(im_flat_contact *run);

/* Solves the contact at nominal mean pressure p_m >= 0 (units of E*; load N = p_m nx ny delta^2),
 * warm-started from the last solve. Errors as im_solver_solve's. */
int im_flat_contact_solve(im_flat_contact *run, double mean_pressure, im_flat_result *out);

/* Solves the contact at the mean gap g_m (units of delta) over the cell: the mean separation of the
 * flat and the deformed surface (Persson's u-bar), imposed as the approach w = mean g0 - g_m
 * (displacement control; mean u = 0), warm-started from the last solve. out->mean_pressure is the
 * load's. 0 < g_m <= mean g0 (at mean g0 the flat touches the highest patch; as g_m falls to 0 the
 * contact fills the cell and the mean pressure grows without bound): IM_EINVAL outside it. Errors
 * otherwise as im_solver_solve's. */
int im_flat_contact_solve_gap(im_flat_contact *run, double mean_gap, im_flat_result *out);

/* The pressure field of the last solve (nx * ny values, field.h layout; owned by run). */
const double *im_flat_contact_pressure(const im_flat_contact *run);

/* ---- indentation histories on a surface ---- */
typedef struct im_window {
    int x0, y0, nx, ny; /* the solved sub-grid of the surface: [x0, x0 + nx) x [y0, y0 + ny) */
} im_window;

typedef struct im_step_result {
    double approach, load;
    double load_star; /* N* = A(N) / delta^2 (the paper's 2N / (delta^2 E* cot alpha)) */
    long contact_patches;
    double area_ratio; /* n_p delta^2 / A(N), A from im_indenter_area_for_load; NaN at N = 0 */
    double mean_pressure, max_pressure;
    int iterations, convolutions;
    double residual, seconds;
    int coarse_iterations; /* as im_solve_result's */
    /* Plastic memory (with a hardness; 0 without): */
    long yielding_patches;    /* patches at the cap in this step (they flowed, or would under more load) */
    double plastic_depth;     /* the largest plastic depth so far (units of delta) */
    double plastic_work;      /* energy dissipated so far: H_p delta^2 times the summed depth increments
                               (units of E*'s stress times delta^3) */
    double residual_approach; /* min of g0 + plastic depth over the window: the approach at which the
                               withdrawn punch would touch the impression (0 without plastic flow) */
    /* Adhesion (0 without): */
    double tensile_force;   /* delta^2 times the sum of -p over the patches under tension (>= 0) */
    long adhesive_patches;  /* patches whose net pressure is tensile (p < 0) */
    long repulsive_patches; /* patches whose net pressure is compressive (p > 0) */
    /* A periodic cell (NaN on the half-space): */
    double mean_gap; /* the mean of max(g, 0) over the cell (Persson's u-bar; mean u = 0): a yielded
                               patch's overlap is its plastic flattening and counts 0 */
} im_step_result;

/* The length l = pi E* w / (8 sigma0^2) = pi E* delta_c^2 / (8 w) (units of delta_c) of the Dugdale zone
 * at a crack tip, for options' adhesion: the zone must span patches ("Adhesion" above). NaN without
 * adhesion or for NULL or invalid options. */
double im_adhesion_zone_length(const im_solver_options *options);

/* Maugis's transition parameter of a sphere (paraboloid) of radius R under options' adhesion:
 * lambda = 2 sigma0 (R / (pi w K^2))^(1/3), K = 4 E* / 3 (lambda > 5: JKR, lambda < 0.1: DMT; Tabor's
 * mu = lambda / 1.157 for a Lennard-Jones law of the same work and peak stress; sigma0 is the law's peak
 * stress w / adhesion_range, the exponential law's too). NaN without adhesion,
 * for R <= 0 or NULL or invalid options. */
double im_adhesion_maugis_lambda(const im_solver_options *options, double radius);

/* Tabor's parameter of that sphere: the Maugis-Dugdale law's lambda / 1.157 (the Lennard-Jones law of the
 * same work and peak stress), the exponential law's own (R w^2 / (E*^2 rho^3))^(1/3) = lambda / 1.127
 * (lambda: the Maugis-Dugdale law of its work and peak stress w / rho, Johnson & Greenwood's matching).
 * NaN as im_adhesion_maugis_lambda. */
double im_adhesion_tabor_mu(const im_solver_options *options, double radius);

/* The law an indentation on patches of side delta solves (*solved: options' copy): options' own, or with
 * adhesion_zone = P > 0 and a Dugdale zone l (im_adhesion_zone_length) shorter than P delta, the
 * Maugis-Dugdale law of the same work w whose zone spans P patches: delta_c' = (8 w P delta / (pi E*))^(1/2),
 * sigma0' = w / delta_c' (the cohesive-zone rule of fracture mechanics' finite elements: the strength lowered,
 * the toughness kept). Its lambda and mu are then those of the law solved, not the law given: the pull-off
 * of a JKR-like contact is w's, the curve Maugis-Dugdale's at that lambda (docs/solver.md). solved's
 * adhesion_zone is 0 (solving it again changes nothing); *widened (may be NULL): 1 when the range was raised.
 * IM_EINVAL as im_solver_options_check, or for a delta not finite and > 0. */
int im_adhesion_solved_law(const im_solver_options *options, double delta, im_solver_options *solved, int *widened);

typedef struct im_indentation im_indentation;

/* Prepares an indentation of surface (heights in units of its delta; not referenced after the
 * call) by punch.
 * largest_target is the largest approach (displacement control) or load (load control) the run
 * will impose: it fixes the solve window, the bounding box of the patches whose undeformed gap is
 * at most the largest approach, plus options->window_margin, grown to an FFT-friendly size
 * (2^a 3^b 5^c 7^d) within the surface. Exact, because u >= 0 under compression: no patch with
 * g0 > w can touch (with adhesion the surface is pulled up: the bound adds 2 delta_c, or 36 rho under
 * the exponential law, a margin that a step checks, "Adhesion" above). Under load control the largest
 * approach is bounded by 1.1 w_smooth(N) + (max h - min h) (with adhesion plus that margin) (a rough surface is everywhere below the smooth one shifted up
 * by its height range, and the smooth discrete solution is within 1% of the closed form); each
 * step checks that its approach stays below that bound. The plan is made here (serial code).
 * Errors: IM_ENUMERIC for NaN/Inf heights, IM_EINVAL for bad punch/options/target. */
int im_indentation_create(const im_field *surface, const im_indenter *punch, enum im_control control,
                          double largest_target, const im_solver_options *options, im_indentation **out);
void im_indentation_free(im_indentation *run);

/* Solves the next step (approach or load, per the run's control), warm-started from the last one.
 * Targets may go up and down. With a hardness the run remembers plastic flow ("Hardness" above):
 * each step starts from the surface the steps before deformed. Under displacement control (cropped
 * half-space, no adhesion, CPU engine) a step is solved on the box of the window its contact can
 * reach, confirmed on the box of g0 <= w (docs/solver.md, "Step boxes"): the same answer to the
 * tolerance, in less time; max_iterations caps each solve of it.
 * IM_EINVAL for a target outside [0, largest_target]; IM_ENOCONV (out holds the residual; the run
 * keeps the last iterate); IM_EEDGE when a contact patch lies on the outer row or column of the
 * surface, where the finite surface, not the half-space, would decide the answer, and, under load
 * control, before solving, when the smooth contact at the load would have a radius reaching from
 * the punch axis past the surface's edge (a load this surface cannot carry). Loads are summed with
 * compensation (a few ulp over any grid, whatever the threads); contact counts are integers. */
int im_indentation_step(im_indentation *run, double target, im_step_result *out);

/* The plastic depth accumulated so far on the FULL surface grid (a new field, caller frees; units of
 * delta, >= 0, positive where the surface was flattened down; 0 outside the window and without a
 * hardness): the residual impression once the punch is withdrawn. */
int im_indentation_plastic(const im_indentation *run, im_field **plastic);

/* The sub-grid the run solves (all zero for a NULL run), and the plan it solves on (NULL for a NULL
 * run; owned by the run). */
im_window im_indentation_window(const im_indentation *run);
/* The window im_indentation_create would solve on with these arguments, without making its plan or
 * fields (the undeformed gap of the whole grid is made and freed): what a solve there allocates is
 * that window's (scenes' limits). Its errors are im_indentation_create's checks'; *out is all zero
 * on an error. IM_EINVAL for a NULL out, punch or an invalid surface view. */
int im_indentation_window_for(const im_field *surface, const im_indenter *punch, enum im_control control,
                              double largest_target, const im_solver_options *options, im_window *out);
const im_solver_plan *im_indentation_plan(const im_indentation *run);

/* Fields of the last step on the FULL surface grid (new fields, caller frees; any pointer may be
 * NULL to skip that field): force per patch f = p delta^2; displacement u; gap g = g0 - w + u.
 * Outside the window the force is zero, u is reported as 0 (not computed: the true u there is
 * positive) and the gap is the undeformed g0 - w, a lower bound of the true gap (> 0 there).
 * Patches a flat punch can never touch have gap +INFINITY. After a step solved on a box of the window
 * (im_indentation_step) u or g costs one convolution of the window, at the first such call; so the
 * call is not thread-safe on one run when it asks for u or g. */
int im_indentation_fields(const im_indentation *run, im_field **force, im_field **gap, im_field **displacement);

/* im_indentation_fields with the displacement on the whole grid (im_displacement_full_with, on a
 * plan the run makes at the first call and keeps) and the gap g = g0 - w + u corrected with it:
 * what is written or drawn. Any pointer may be NULL to skip that field. Not thread-safe on one run
 * (the first call plans). */
int im_indentation_fields_full(im_indentation *run, im_field **force, im_field **gap, im_field **displacement);

#ifdef __cplusplus
}
#endif

#endif
