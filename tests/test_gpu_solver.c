/* The GPU engine (src/solver/engine_gpu.c) against the CPU engine: the same Polonsky-Keer iteration
 * over Vulkan compute shaders and VkFFT must give the CPU's answers (loads and approaches to 1e-10 at
 * tol 1e-10, identical contact sets) on rough cones, spheres, flat punches, the hardness cap, both
 * controls and periodic flat contact, under the Vulkan validation layers, which must report nothing.
 * Runs on whatever Vulkan device opens first (lavapipe in CI, a CPU device). Exits 77 (skipped) in
 * builds without IM_GPU. */
#include "support.h"

#include "indentmap/gpu_config.h"
#include "indentmap/indenter.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"
#include "solver/engine.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if IM_HAVE_GPU
#include "gpu/vulkan.h"

static const double TOL = 1e-10;

static im_solver_options engine_options(int device)
{
    im_solver_options o = im_solver_options_default();
    o.tol = TOL;
    o.device = device;
    o.gpu_validation = device == IM_DEVICE_GPU;
    return o;
}

static im_indentation *prepare(const im_field *s, const im_indenter *punch, enum im_control control, double largest,
                               const im_solver_options *o)
{
    im_indentation *run = NULL;
    if (im_indentation_create(s, punch, control, largest, o, &run) != IM_OK)
        fail_msg("im_indentation_create (%s): %s", o->device == IM_DEVICE_GPU ? "gpu" : "cpu", im_last_error());
    return run;
}

static void assert_no_validation_messages(const im_solver_plan *plan)
{
    long messages = solver_engine_gpu_validation_messages(plan);
    if (messages != 0)
        fail_msg("the Vulkan validation layers reported %ld messages (stderr has them)", messages);
}

/* The contact sets (force > 0) of two fields are the same patches. */
static void assert_same_contact(const im_field *a, const im_field *b, int step)
{
    long differ = 0, contact = 0;
    for (size_t i = 0; i < im_field_count(a); ++i) {
        differ += (a->data[i] > 0) != (b->data[i] > 0);
        contact += a->data[i] > 0;
    }
    if (differ)
        fail_msg("step %d: the contact sets differ in %ld of %ld patches", step, differ, contact);
}

/* Load control with a hardness searches the approach (indentation.c, solve_at_load): it stops at
 * |N - target| <= tol target, or where the approach's bracket is tol w wide and the solves cannot
 * resolve N closer; on a steep unloading branch that leaves N up to (dN/dw) tol w from the target
 * (seen: 3.6e-10 N on an H200's host, CPU 29.999999989 and GPU 29.9999999994 for 30 with approaches
 * 6.4e-11 apart; 1.5e-9 N on both engines for 5 on lavapipe). There the approaches are compared to
 * 1e-10, the loads to each other within the larger of their misses of the target, and each miss to
 * SEARCHED_LOAD_TOL (100 tol: an unloading branch with (dN/dw) w / N up to 100); elsewhere the loads
 * to 1e-10. */
static const double SEARCHED_LOAD_TOL = 1e-8;

static int loads_agree(const im_step_result *cpu, const im_step_result *gpu, double searched_target)
{
    if (test_relative_difference(cpu->load, gpu->load) <= 1e-10)
        return 1;
    if (!isfinite(searched_target))
        return 0;
    const double cpu_miss = fabs(cpu->load - searched_target), gpu_miss = fabs(gpu->load - searched_target);
    return fmax(cpu_miss, gpu_miss) <= SEARCHED_LOAD_TOL * searched_target &&
           fabs(cpu->load - gpu->load) <= fmax(cpu_miss, gpu_miss);
}

static void assert_same_step(const im_step_result *cpu, const im_step_result *gpu, int step, double searched_target)
{
    if (!loads_agree(cpu, gpu, searched_target) || test_relative_difference(cpu->approach, gpu->approach) > 1e-10)
        fail_msg("step %d: cpu N = %.17g w = %.17g, gpu N = %.17g w = %.17g", step, cpu->load, cpu->approach,
                 gpu->load, gpu->approach);
    assert_int_equal(cpu->contact_patches, gpu->contact_patches);
    /* The engines add a step's few changes to u by direct sums (up to limits of their own) and confirm
     * on an exact u at the end, so a wrong direct sum shows as iterations spent correcting it. */
    if (abs(cpu->iterations - gpu->iterations) > 2 + cpu->iterations / 10)
        fail_msg("step %d: cpu %d iterations, gpu %d", step, cpu->iterations, gpu->iterations);
    if (test_relative_difference(cpu->plastic_work, gpu->plastic_work) > 1e-9)
        fail_msg("step %d: cpu dissipation %.17g, gpu %.17g", step, cpu->plastic_work, gpu->plastic_work);
    if (test_relative_difference(cpu->tensile_force, gpu->tensile_force) > 1e-9)
        fail_msg("step %d: cpu tensile force %.17g, gpu %.17g", step, cpu->tensile_force, gpu->tensile_force);
}

/* Runs the same history on both engines, with the physics of `physics` (hardness, adhesion), and compares
 * every step. */
static double compare_runs(const im_field *s, const im_indenter *punch, enum im_control control,
                           const double *targets, int count, const im_solver_options *physics)
{
    double least_load = INFINITY; /* the CPU's most tensile (least) load, returned */
    im_solver_options cpu_options = engine_options(IM_DEVICE_CPU), gpu_options = engine_options(IM_DEVICE_GPU);
    cpu_options.hardness = gpu_options.hardness = physics->hardness;
    cpu_options.adhesion_work = gpu_options.adhesion_work = physics->adhesion_work;
    cpu_options.adhesion_range = gpu_options.adhesion_range = physics->adhesion_range;
    cpu_options.periodic = gpu_options.periodic = physics->periodic;
    double largest = 0;
    for (int k = 0; k < count; ++k)
        largest = fmax(largest, fabs(targets[k]));
    im_indentation *cpu = prepare(s, punch, control, largest, &cpu_options);
    im_indentation *gpu = prepare(s, punch, control, largest, &gpu_options);
    assert_string_equal(im_solver_plan_device(im_indentation_plan(cpu)), "cpu");
    assert_string_not_equal(im_solver_plan_device(im_indentation_plan(gpu)), "cpu");
    for (int k = 0; k < count; ++k) {
        im_step_result a, b;
        assert_int_equal(im_indentation_step(cpu, targets[k], &a), IM_OK);
        if (im_indentation_step(gpu, targets[k], &b) != IM_OK)
            fail_msg("gpu step %d: %s", k, im_last_error());
        const int searched = control == IM_CONTROL_LOAD && physics->hardness > 0;
        assert_same_step(&a, &b, k, searched ? targets[k] : NAN);
        least_load = fmin(least_load, a.load);
        im_field *fa = NULL, *fb = NULL;
        assert_int_equal(im_indentation_fields(cpu, &fa, NULL, NULL), IM_OK);
        assert_int_equal(im_indentation_fields(gpu, &fb, NULL, NULL), IM_OK);
        assert_same_contact(fa, fb, k);
        im_field_free(fa);
        im_field_free(fb);
    }
    assert_no_validation_messages(im_indentation_plan(gpu));
    im_indentation_free(cpu);
    im_indentation_free(gpu);
    return least_load;
}

static void compare_history(const im_field *s, const im_indenter *punch, enum im_control control,
                            const double *targets, int count, double hardness)
{
    im_solver_options physics = {.hardness = hardness};
    compare_runs(s, punch, control, targets, count, &physics);
}

static void test_rough_cone_displacement(void **state)
{
    (void)state;
    im_field *s = test_rough_surface(128, 0.08, 3);
    im_indenter cone = im_indenter_cone(80);
    const double approaches[] = {0.5, 2, 4};
    compare_history(s, &cone, IM_CONTROL_DISPLACEMENT, approaches, 3, 0);
    im_field_free(s);
}

static void test_rough_cone_load(void **state)
{
    (void)state;
    im_field *s = test_rough_surface(256, 0.08, 5);
    im_indenter cone = im_indenter_cone(80);
    const double loads[] = {50, 400};
    compare_history(s, &cone, IM_CONTROL_LOAD, loads, 2, 0);
    im_field_free(s);
}

static void test_rough_sphere(void **state)
{
    (void)state;
    im_field *s = test_rough_surface(128, 0.04, 7);
    im_indenter sphere = im_indenter_sphere(400);
    const double loads[] = {20, 120};
    compare_history(s, &sphere, IM_CONTROL_LOAD, loads, 2, 0);
    im_field_free(s);
}

static void test_flat_punch(void **state)
{
    (void)state;
    im_field *s = test_rough_surface(64, 0.02, 9);
    im_indenter flat = im_indenter_flat(20);
    const double approaches[] = {0.3, 1};
    compare_history(s, &flat, IM_CONTROL_DISPLACEMENT, approaches, 2, 0);
    im_field_free(s);
}

static void test_hardness_cap(void **state)
{
    (void)state;
    im_field *s = test_rough_surface(128, 0.08, 11);
    im_indenter cone = im_indenter_cone(80);
    /* H = 2 binds nowhere at these loads (nor did it at 100 and 600, 6321 patches, 68% of the case's time): load
     * control's search of the approach under a cap, each trial solve as long as the contact is wide */
    const double loads[] = {20, 100}, approaches[] = {1, 3};
    compare_history(s, &cone, IM_CONTROL_LOAD, loads, 2, 2.0);
    compare_history(s, &cone, IM_CONTROL_DISPLACEMENT, approaches, 2, 0.5);
    /* the cap's memory: loading and unloading, under both controls (load control searches the approach) */
    const double cycle[] = {1, 2.5, 4, 3, 1.5, 0.5}, load_cycle[] = {20, 45, 30, 5};
    compare_history(s, &cone, IM_CONTROL_DISPLACEMENT, cycle, 6, 0.05);
    compare_history(s, &cone, IM_CONTROL_LOAD, load_cycle, 4, 0.05);
    im_field_free(s);
}

/* Adhesion runs its passes over the plan's engine: an approach, a retraction through pull-off and the
 * separated punch give the same loads, tension and contact on both. */
static void test_adhesion(void **state)
{
    (void)state;
    im_field *s = test_rough_surface(96, 0.04, 13);
    im_indenter sphere = im_indenter_sphere(64);
    const double approaches[] = {-0.5, 1, 2.5, 1, 0, -1, -2};
    im_solver_options physics = {.adhesion_work = 0.05, .adhesion_range = 0.6};
    assert_true(compare_runs(s, &sphere, IM_CONTROL_DISPLACEMENT, approaches, 7, &physics) < 0); /* it pulled */
    im_field_free(s);
}

/* A large grid: 1024^2 transforms of the padded 2048^2 grid (lavapipe's buffers stop at 128 MiB); the same host
 * code as the smaller cones (ctest's gpu_solver_slow, not under the sanitizers). */
static void test_rough_cone_1024(void **state)
{
    (void)state;
    im_field *s = test_rough_surface(1024, 0.08, 13);
    im_indenter cone = im_indenter_cone(80);
    const double approaches[] = {12};
    compare_history(s, &cone, IM_CONTROL_DISPLACEMENT, approaches, 1, 0);
    im_field_free(s);
}

static void compare_flat_on(const im_field *s, const double *pressures, int count)
{
    im_solver_options cpu_options = engine_options(IM_DEVICE_CPU), gpu_options = engine_options(IM_DEVICE_GPU);
    im_flat_contact *cpu = NULL, *gpu = NULL;
    assert_int_equal(im_flat_contact_create(s, &cpu_options, &cpu), IM_OK);
    if (im_flat_contact_create(s, &gpu_options, &gpu) != IM_OK)
        fail_msg("gpu flat contact: %s", im_last_error());
    for (int k = 0; k < count; ++k) {
        im_flat_result a, b;
        assert_int_equal(im_flat_contact_solve(cpu, pressures[k], &a), IM_OK);
        if (im_flat_contact_solve(gpu, pressures[k], &b) != IM_OK)
            fail_msg("gpu flat contact p = %g: %s", pressures[k], im_last_error());
        if (test_relative_difference(a.approach, b.approach) > 1e-10)
            fail_msg("p = %g: cpu approach %.17g, gpu %.17g", pressures[k], a.approach, b.approach);
        assert_int_equal(a.contact_patches, b.contact_patches);
        const double *pa = im_flat_contact_pressure(cpu), *pb = im_flat_contact_pressure(gpu);
        for (size_t i = 0; i < im_field_count(s); ++i)
            if ((pa[i] > 0) != (pb[i] > 0))
                fail_msg("p = %g: patch %zu in contact on one engine only", pressures[k], i);
    }
    im_flat_contact_free(cpu);
    im_flat_contact_free(gpu);
}

static void compare_flat(int n, double slope, const double *pressures, int count)
{
    im_field *s = test_rough_surface(n, slope, 17);
    compare_flat_on(s, pressures, count);
    im_field_free(s);
}

static void test_periodic_flat(void **state)
{
    (void)state;
    const double pressures[] = {0.005, 0.02};
    compare_flat(128, 0.1, pressures, 2);
}

/* The same on a larger cell: the same host code as at 128^2 (ctest's gpu_solver_slow, not under the sanitizers). */
static void test_periodic_flat_512(void **state)
{
    (void)state;
    const double pressures[] = {0.01};
    compare_flat(512, 0.1, pressures, 1);
}

/* One cold solve of a periodic 128^2 cell without the cascade at tolerance tol, under load (mean
 * pressure 0.005) or under the approach that load needs (*approach: found under load, used under the
 * approach): its iterations and the submissions its device waited for (*waits). */
static int counted_periodic_solve(const im_field *s, const double *gap0, double tol, enum im_control control,
                                  double *approach, long *waits)
{
    const size_t n = im_field_count(s);
    im_solver_options o = engine_options(IM_DEVICE_GPU);
    o.periodic = 1;
    o.cascade = 0;
    o.tol = tol;
    im_solver_plan *plan = NULL;
    if (im_solver_plan_create(s->nx, s->ny, 1.0, &o, &plan) != IM_OK)
        fail_msg("plan: %s", im_last_error());
    double *p = calloc(n, sizeof(double)), *u = malloc(sizeof(double) * n);
    const long before = solver_engine_gpu_submissions(plan);
    const double target = control == IM_CONTROL_LOAD ? 0.005 * (double)n : *approach;
    im_solve_result r;
    if (im_solver_solve(plan, gap0, control, target, p, u, &r) != IM_OK)
        fail_msg("periodic solve, control %d, tol %g: %s", (int)control, tol, im_last_error());
    *waits = solver_engine_gpu_submissions(plan) - before;
    *approach = r.approach;
    assert_no_validation_messages(plan);
    im_solver_plan_free(plan);
    free(p);
    free(u);
    return r.iterations;
}

/* The waits per iteration, from two cold solves at tolerances 1e-5 and 1e-10 (what they wait for
 * besides their iterations is the same), at most `most`; and the tight solve's waits, at most `most` per
 * iteration and `fixed_most` besides. (Not the line's intercept: the early iterations, whose steps
 * change patches, wait once more under displacement control than the last ones, whose rate the two
 * solves measure: 18 besides 3 per iteration on this cell, 7 of them outside the iterations.) */
static void check_waits(const im_field *s, const double *gap0, enum im_control control, double *approach, int most,
                        long fixed_most)
{
    long loose_waits, tight_waits;
    const int loose = counted_periodic_solve(s, gap0, 1e-5, control, approach, &loose_waits);
    const int tight = counted_periodic_solve(s, gap0, 1e-10, control, approach, &tight_waits);
    const double per_iteration = (double)(tight_waits - loose_waits) / (tight - loose);
    const long fixed = tight_waits - (long)most * tight;
    print_message("control %d: %d and %d iterations, %ld and %ld submissions: %.2f per iteration, %ld besides\n",
                  (int)control, loose, tight, loose_waits, tight_waits, per_iteration, fixed);
    if (tight <= loose)
        fail_msg("control %d: %d iterations at tol 1e-10, %d at 1e-5", (int)control, tight, loose);
    if (per_iteration > most)
        fail_msg("control %d: %.2f submissions per iteration, expected at most %d", (int)control, per_iteration,
                 most);
    if (fixed > fixed_most)
        fail_msg("control %d: %ld submissions besides %d per iteration, expected at most %ld", (int)control, fixed,
                 most, fixed_most);
}

/* The host's waits (engine_gpu.c, "Fewer waits"). A preconditioned iteration under displacement
 * control waits for the preconditioner's sums, the step's and the update's, and the gaps' unless the
 * update recorded them: at most 4 (5 before the kept sums); under load control also for the contact
 * mean and the centring: 6 (7 before, the pressure sum among them). Besides them a cold solve waits for
 * the uploads of gap0 and p, any_positive, the local guess, the last gaps, the downloads of p and u
 * (7), and under load control also the guess's bisection (20 waits; 60 before winkler_loads), the first
 * load's sum, the last rescaling and the summary after it, and the last contact mean (31). The bounds
 * leave room for a restart or two (an iteration that waits again without an update), and still fail
 * the code before: 7 and 5 per iteration, 57 and 29 besides on this cell. */
static void test_round_trips_per_iteration(void **state)
{
    (void)state;
    im_field *s = test_rough_surface(128, 0.1, 17);
    const size_t n = im_field_count(s);
    double *gap0 = malloc(sizeof(double) * n), highest = -INFINITY, approach = 0;
    for (size_t i = 0; i < n; ++i)
        highest = fmax(highest, s->data[i]);
    for (size_t i = 0; i < n; ++i)
        gap0[i] = highest - s->data[i];
    check_waits(s, gap0, IM_CONTROL_LOAD, &approach, 6, 40);
    check_waits(s, gap0, IM_CONTROL_DISPLACEMENT, &approach, 4, 12);
    free(gap0);
    im_field_free(s);
}

/* Mean-gap control of a periodic cell (displacement control with mean u = 0) over the GPU engine: the same
 * loads, approaches and contact at three mean gaps, down and up. */
static void test_periodic_mean_gap(void **state)
{
    (void)state;
    im_field *s = test_rough_surface(128, 0.1, 19);
    im_indenter flat = im_indenter_flat(2.0 * 128 * 1.5);
    const double gaps[] = {0.5, 0.3, 0.4};
    im_solver_options physics = {.periodic = 1};
    compare_runs(s, &flat, IM_CONTROL_MEAN_GAP, gaps, 3, &physics);
    im_field_free(s);
}

/* The engines with the GPU's fields split into chunks of at most `limit` bytes
 * (INDENTMAP_GPU_MAX_BUFFER, read when a GPU plan opens its device), chunk ends mid-row. */
static void set_chunk_limit(const char *limit)
{
    if (limit)
        setenv("INDENTMAP_GPU_MAX_BUFFER", limit, 1);
    else
        unsetenv("INDENTMAP_GPU_MAX_BUFFER");
}

/* Periodic cells of 240^2 in chunks of 16384 doubles (68.3 rows): the fields in 4 chunks, the
 * modes in 4, the spectra in 2; both controls. */
static void test_chunked_periodic(void **state)
{
    (void)state;
    set_chunk_limit("131072");
    const double pressures[] = {0.005, 0.02};
    compare_flat(240, 0.1, pressures, 2);
    im_field *s = test_rough_surface(240, 0.1, 19);
    im_indenter flat = im_indenter_flat(2.0 * 240 * 1.5);
    const double gaps[] = {0.5, 0.3};
    im_solver_options physics = {.periodic = 1};
    compare_runs(s, &flat, IM_CONTROL_MEAN_GAP, gaps, 2, &physics);
    im_field_free(s);
    set_chunk_limit(NULL);
}

/* A rough cone of 200^2 in chunks of 32768 doubles (163.8 rows): the fields in 2 chunks, the
 * padded 400^2 grid's modes in 5 (the grid's, whatever the load); with and without the hardness cap
 * (load control's search of the approach: N = 30, 474 patches, a third of N = 150's time). */
static void test_chunked_cone(void **state)
{
    (void)state;
    set_chunk_limit("262144");
    im_field *s = test_rough_surface(200, 0.08, 23);
    im_indenter cone = im_indenter_cone(80);
    const double approaches[] = {1, 3}, loads[] = {30};
    compare_history(s, &cone, IM_CONTROL_DISPLACEMENT, approaches, 2, 0);
    compare_history(s, &cone, IM_CONTROL_LOAD, loads, 1, 2.0);
    im_field_free(s);
    set_chunk_limit(NULL);
}

/* A periodic strip of 16384 x 64 patches (H 0.8, lambda_r 64): its first axis takes several of
 * VkFFT's uploads, the one way its multi-buffer mode transforms buffers in parts (fft.c,
 * check_parts_path). */
static im_field *long_strip(void)
{
    im_surface_params p = im_surface_params_default();
    p.nx = 16384;
    p.ny = 64;
    p.lambda_r = 64;
    p.slope_rms = 0.1;
    p.seed = 29;
    im_field *s = NULL;
    assert_int_equal(im_surface_generate(&p, &s), IM_OK);
    return s;
}

/* Whether the device transforms buffers in parts (VkFFT's multi-buffer mode): the strip's GPU plan
 * is made, or refused naming non-uniform indexing (lavapipe). */
static int parts_supported(const im_field *s)
{
    gpu_context *c = NULL; /* the part size the plans will have: INDENTMAP_GPU_MAX_PART's, below the modes' */
    assert_int_equal(gpu_context_open(GPU_ANY, 0, &c), IM_OK);
    assert_int_equal(gpu_context_part_bytes(c), 2097152);
    assert_true(gpu_fft_modes_bytes(s->nx, s->ny) > 2 * gpu_context_part_bytes(c));
    gpu_context_close(c);
    im_solver_options o = engine_options(IM_DEVICE_GPU);
    o.periodic = 1;
    im_flat_contact *flat = NULL;
    const int status = im_flat_contact_create(s, &o, &flat);
    if (status != IM_OK && !strstr(im_last_error(), "non-uniformly"))
        fail_msg("gpu flat contact in parts: %s", im_last_error());
    if (status != IM_OK)
        print_message("skipped: %s\n", im_last_error());
    im_flat_contact_free(flat);
    return status == IM_OK;
}

/* The engines with the GPU's buffers in parts of 2 MiB (INDENTMAP_GPU_MAX_PART): the strip's fields
 * in 4 parts, its modes in 5, VkFFT's scratch in z and the transform grid (the periodic mode's), as a
 * 16384^2 cell's are in 2 GiB parts. Devices that do not index buffer arrays non-uniformly natively
 * (lavapipe) refuse transforms in parts and skip this case, saying so; NVIDIA's run it
 * (scripts/gpu-check.sh, GPUCHECK_PARTS=1). */
static void test_buffers_in_parts(void **state)
{
    (void)state;
    setenv("INDENTMAP_GPU_MAX_PART", "2097152", 1);
    im_field *s = long_strip();
    if (parts_supported(s)) {
        const double pressures[] = {0.01};
        compare_flat_on(s, pressures, 1);
    }
    im_field_free(s);
    unsetenv("INDENTMAP_GPU_MAX_PART");
}

/* The device memory a GPU plan counts before allocating (solver_footprint, the refusal's number)
 * is what its buffers then hold, with the cascade's levels (which borrow the finest level's work
 * buffers) and with fields split into chunks; and it is the closed form of engine_gpu.c's list:
 * the finest level's five fields, z (as large as the unpadded grid's modes), the transform grid and
 * its modes (each as large as the modes), VkFFT's scratch on the padded grid (as large), the spectrum, K (padded grid) and the
 * preconditioner's spectrum (padded grid), the change lists (3088 bytes); a coarse level the same
 * tables and lists only; and the reductions' 65536 bytes. */
static double expected_device_bytes(int nx, int ny, int periodic, int cascade)
{
    const double n = (double)nx * ny, small = (double)ny * (nx / 2 + 1);
    const double modes = periodic ? small : 2.0 * ny * (nx + 1),
                 tables = 8 * modes + (periodic ? 0 : 8 * n + 8 * small);
    double bytes = 65536 + tables + 3088;
    bytes += 5 * 8 * n + 16 * small + 16 * modes * (periodic ? 2 : 3);
    for (int cx = nx, cy = ny; cascade && solver_cascade_sides(cx, cy, periodic, &cx, &cy);)
        bytes += (periodic ? 8.0 * cy * (cx / 2 + 1)
                           : 16.0 * cy * (cx + 1) + 8.0 * cx * cy + 8.0 * cy * (cx / 2 + 1)) +
                 3088;
    return bytes;
}

static void check_device_memory(int n, int periodic, int cascade)
{
    im_solver_options o = engine_options(IM_DEVICE_GPU);
    o.periodic = periodic;
    o.cascade = cascade;
    im_solver_plan *plan = NULL;
    if (im_solver_plan_create(n, n, 1.0, &o, &plan) != IM_OK)
        fail_msg("gpu plan %d^2: %s", n, im_last_error());
    double counted, held;
    solver_engine_gpu_memory(plan, &counted, &held);
    const double expected = expected_device_bytes(n, n, periodic, cascade);
    print_message("%d^2 %s, cascade %d: counted %.0f bytes, held %.0f, expected %.0f\n", n,
                  periodic ? "periodic" : "half-space", cascade, counted, held, expected);
    if (counted != held || counted != expected)
        fail_msg("%d^2 periodic %d cascade %d: counted %.0f bytes of device memory, the buffers hold %.0f, the "
                 "closed form gives %.0f",
                 n, periodic, cascade, counted, held, expected);
    im_solver_plan_free(plan);
}

static void test_device_memory_counted(void **state)
{
    (void)state;
    const char *limits[] = {NULL, "262144"}; /* the second: fields in 2 chunks, modes in up to 5 */
    for (int k = 0; k < 2; ++k) {
        set_chunk_limit(limits[k]);
        check_device_memory(240, 1, 1);
        check_device_memory(240, 1, 0);
        check_device_memory(200, 0, 1);
        check_device_memory(96, 0, 0);
    }
    set_chunk_limit(NULL);
}

/* What a cold cascade solve of nx x ny moves (bytes up, down), the coarse answers handed over on the
 * device: each level's gap up, the coarsest level's zero start up, the top level's p and u down. */
static void expected_cascade_transfers(int nx, int ny, int periodic, double *up, double *down)
{
    *up = 8.0 * nx * ny;
    *down = 16.0 * nx * ny;
    for (int cx, cy; solver_cascade_sides(nx, ny, periodic, &cx, &cy); nx = cx, ny = cy)
        *up += 8.0 * cx * cy;
    *up += 8.0 * nx * ny;
}

/* One cold solve of a rough flat contact under load on the engine: its result, pressure and the bytes
 * its device moved (-1 on the CPU). */
static im_solve_result cold_flat_solve(int device, const im_field *s, int periodic, double *p, double *up,
                                       double *down)
{
    const size_t n = im_field_count(s);
    double highest = -INFINITY, *gap0 = malloc(sizeof(double) * n), *u = malloc(sizeof(double) * n);
    for (size_t i = 0; i < n; ++i)
        highest = fmax(highest, s->data[i]);
    for (size_t i = 0; i < n; ++i)
        gap0[i] = highest - s->data[i];
    im_solver_options o = engine_options(device);
    o.periodic = periodic;
    im_solver_plan *plan = NULL;
    if (im_solver_plan_create(s->nx, s->ny, 1.0, &o, &plan) != IM_OK)
        fail_msg("plan %d x %d: %s", s->nx, s->ny, im_last_error());
    double up0, down0;
    solver_engine_gpu_transfers(plan, &up0, &down0);
    memset(p, 0, sizeof(double) * n);
    im_solve_result r;
    if (im_solver_solve(plan, gap0, IM_CONTROL_LOAD, 0.01 * (double)n, p, u, &r) != IM_OK)
        fail_msg("cold solve %d x %d on device %d: %s", s->nx, s->ny, device, im_last_error());
    solver_engine_gpu_transfers(plan, up, down);
    *up -= up0;
    *down -= down0;
    if (device == IM_DEVICE_GPU)
        assert_no_validation_messages(plan);
    im_solver_plan_free(plan);
    free(gap0);
    free(u);
    return r;
}

static void check_cascade_on_device(int side, int periodic)
{
    im_field *s = test_rough_surface(side, 0.1, 23);
    const int nx = side, ny = side;
    const size_t n = (size_t)nx * ny;
    double *cpu_p = malloc(sizeof(double) * n), *gpu_p = malloc(sizeof(double) * n), up, down, want_up, want_down;
    im_solve_result cpu = cold_flat_solve(IM_DEVICE_CPU, s, periodic, cpu_p, &up, &down);
    im_solve_result gpu = cold_flat_solve(IM_DEVICE_GPU, s, periodic, gpu_p, &up, &down);
    expected_cascade_transfers(nx, ny, periodic, &want_up, &want_down);
    print_message("%d x %d periodic %d: %d + %d iterations, up %.0f bytes (expected %.0f), down %.0f (%.0f)\n", nx,
                  ny, periodic, gpu.iterations, gpu.coarse_iterations, up, want_up, down, want_down);
    if (up != want_up || down != want_down)
        fail_msg("%d x %d: the solve moved %.0f bytes up and %.0f down, expected %.0f and %.0f", nx, ny, up, down,
                 want_up, want_down);
    if (test_relative_difference(cpu.approach, gpu.approach) > 1e-10)
        fail_msg("%d x %d: approach %.17g on the cpu, %.17g on the gpu", nx, ny, cpu.approach, gpu.approach);
    assert_int_equal(cpu.iterations, gpu.iterations);
    assert_int_equal(cpu.coarse_iterations, gpu.coarse_iterations);
    for (size_t i = 0; i < n; ++i)
        if ((cpu_p[i] > 0) != (gpu_p[i] > 0))
            fail_msg("%d x %d: patch %zu in contact on one engine only", nx, ny, i);
    free(cpu_p);
    free(gpu_p);
    im_field_free(s);
}

/* The cascade's coarse answers are prolonged on the device: the bytes a cold solve moves, and its
 * answer against the CPU engine's (which prolongs on the host), on a periodic cell and on an odd
 * half-space grid whose last blocks are cut by its odd side (63^2: 32^2 below it). */
static void test_cascade_on_device(void **state)
{
    (void)state;
    check_cascade_on_device(128, 1);
    check_cascade_on_device(63, 0);
}

/* A GPU plan, each of its cascade levels, holds none of the CPU engine's arrays and FFTW plans on
 * the host, and of the tables only K(0); a CPU plan has them all. */
static void assert_host_side(const im_solver_plan *p, int gpu)
{
    const void *cpu_arrays[] = {p->direction,
                                p->gap,
                                p->changed,
                                p->changed_value,
                                p->preconditioned,
                                p->precondition_modes,
                                p->rows_in,
                                p->rows_out,
                                p->modes,
                                p->spectrum,
                                p->inverse_spectrum,
                                p->rows_forward,
                                p->columns_forward,
                                p->columns_backward,
                                p->rows_backward,
                                p->precondition_forward,
                                p->precondition_backward};
    for (size_t k = 0; k < sizeof cpu_arrays / sizeof *cpu_arrays; ++k)
        if ((cpu_arrays[k] != NULL) == gpu)
            fail_msg("%s plan %d x %d: CPU array %zu is %s", gpu ? "GPU" : "CPU", p->nx, p->ny, k,
                     gpu ? "allocated" : "missing");
    assert_non_null(p->kernel);
}

static void test_gpu_plan_host_side(void **state)
{
    (void)state;
    for (int periodic = 0; periodic < 2; ++periodic)
        for (int device = IM_DEVICE_CPU; device <= IM_DEVICE_GPU; ++device) {
            im_solver_options o = engine_options(device);
            o.periodic = periodic;
            im_solver_plan *plan = NULL;
            assert_int_equal(im_solver_plan_create(160, 128, 1.0, &o, &plan), IM_OK);
            int levels = 0;
            for (const im_solver_plan *p = plan; p; p = p->coarse, ++levels)
                assert_host_side(p, device == IM_DEVICE_GPU);
            assert_int_equal(levels, 3); /* 160 x 128, 80 x 64, 40 x 32 */
            im_solver_plan_free(plan);
        }
}

/* The convolution alone, for a pressure of the caller's: both engines' K p agree to rounding. */
static void test_convolution(void **state)
{
    (void)state;
    const int nx = 96, ny = 80;
    im_solver_options cpu_options = engine_options(IM_DEVICE_CPU), gpu_options = engine_options(IM_DEVICE_GPU);
    im_solver_plan *cpu = NULL, *gpu = NULL;
    assert_int_equal(im_solver_plan_create(nx, ny, 1.0, &cpu_options, &cpu), IM_OK);
    assert_int_equal(im_solver_plan_create(nx, ny, 1.0, &gpu_options, &gpu), IM_OK);
    double *p = malloc(sizeof(double) * nx * ny), *a = malloc(sizeof(double) * nx * ny),
           *b = malloc(sizeof(double) * nx * ny);
    srand(5);
    for (int i = 0; i < nx * ny; ++i)
        p[i] = (double)rand() / RAND_MAX;
    im_solver_convolve(cpu, p, a);
    im_solver_convolve(gpu, p, b);
    double largest = 0, worst = 0;
    for (int i = 0; i < nx * ny; ++i) {
        largest = fmax(largest, fabs(a[i]));
        worst = fmax(worst, fabs(a[i] - b[i]));
    }
    if (!(worst <= 1e-13 * largest))
        fail_msg("K p: the engines differ by %.3g of max |u| = %.3g", worst, largest);
    assert_no_validation_messages(gpu);
    free(p);
    free(a);
    free(b);
    im_solver_plan_free(cpu);
    im_solver_plan_free(gpu);
}

/* VkFFT's path for sides with a prime factor above 13 returned zeros in a probe: such grids are
 * refused, naming the side, never solved. */
static void test_unsupported_grid_refused(void **state)
{
    (void)state;
    im_solver_options o = engine_options(IM_DEVICE_GPU);
    im_solver_plan *plan = NULL;
    assert_int_equal(im_solver_plan_create(17, 64, 1.0, &o, &plan), IM_EUNSUPPORTED);
    assert_null(plan);
    assert_non_null(strstr(im_last_error(), "side 17"));
    /* auto never fails for it: the CPU engine takes what the GPU cannot */
    o.device = IM_DEVICE_AUTO;
    assert_int_equal(im_solver_plan_create(17, 64, 1.0, &o, &plan), IM_OK);
    assert_string_equal(im_solver_plan_device(plan), "cpu");
    im_solver_plan_free(plan);
}

/* test_gpu_solver [NAMES | --skip NAMES]: only the cases named (comma-separated), or all but those
 * (test_run_cases), as scripts/gpu-check.sh runs one case on a device machine whose time is counted. */
int main(int argc, char **argv)
{
    test_keep_vulkan_libraries_loaded();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_convolution),
        cmocka_unit_test(test_unsupported_grid_refused),
        cmocka_unit_test(test_device_memory_counted),
        cmocka_unit_test(test_gpu_plan_host_side),
        cmocka_unit_test(test_cascade_on_device),
        cmocka_unit_test(test_rough_cone_displacement),
        cmocka_unit_test(test_rough_cone_load),
        cmocka_unit_test(test_rough_sphere),
        cmocka_unit_test(test_flat_punch),
        cmocka_unit_test(test_hardness_cap),
        cmocka_unit_test(test_adhesion),
        cmocka_unit_test(test_periodic_flat),
        cmocka_unit_test(test_periodic_flat_512),
        cmocka_unit_test(test_periodic_mean_gap),
        cmocka_unit_test(test_round_trips_per_iteration),
        cmocka_unit_test(test_chunked_periodic),
        cmocka_unit_test(test_chunked_cone),
        cmocka_unit_test(test_buffers_in_parts),
        cmocka_unit_test(test_rough_cone_1024),
    };
    return test_run_chosen_cases(tests, argc, argv);
}
#else
int main(void)
{
    printf("SKIPPED: the library is built without the GPU engine (IM_GPU off)\n");
    return 77;
}
#endif
