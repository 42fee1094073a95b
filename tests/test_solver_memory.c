/* The memory a solve needs, estimated before any plan is made (im_solver_memory_needed; scenes' limits
 * and `indentmap info --memory` use it), against what the engines then take: the GPU's device memory
 * exactly as the engine counts it when it attaches the plan (which test_gpu_solver checks against its
 * buffers), and the host's peak against /proc/self/status's VmHWM of real solves on the Vulkan device
 * that opens (lavapipe in CI: its device memory is the host's, so the peak there is the host's and the
 * device's together, plus lavapipe's compiled shaders, which the estimate leaves out). device = auto
 * stays on the CPU with a note when the GPU's memory is too small, and device = gpu is refused naming
 * the device, the memory needed and the memory it has. Exits 77 (skipped) in builds without IM_GPU. */
#include "support.h"

#include "indentmap/field.h"
#include "indentmap/gpu_config.h"
#include "indentmap/indenter.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "gpu/vulkan.h"
#include "solver/engine.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#if IM_HAVE_GPU
static const double MIB = 1048576.0;

static im_solver_options gpu_options(int periodic, int cascade, double hardness)
{
    im_solver_options o = im_solver_options_default();
    o.device = IM_DEVICE_GPU;
    o.periodic = periodic;
    o.cascade = cascade;
    o.hardness = hardness;
    return o;
}

/* The estimate's device memory is what the engine counted once the plan was made, to the byte. */
static void check_device_estimate(int nx, int ny, const im_solver_options *o)
{
    im_solver_memory m;
    if (im_solver_memory_needed(nx, ny, o, &m) != IM_OK)
        fail_msg("estimate %d x %d: %s", nx, ny, im_last_error());
    im_solver_plan *plan = NULL;
    if (im_solver_plan_create(nx, ny, 1.0, o, &plan) != IM_OK)
        fail_msg("gpu plan %d x %d: %s", nx, ny, im_last_error());
    double counted, held;
    solver_engine_gpu_memory(plan, &counted, &held);
    print_message("%d x %d periodic %d cascade %d hardness %g: estimated %.0f bytes, counted %.0f, held %.0f\n", nx,
                  ny, o->periodic, o->cascade, o->hardness, m.device_bytes, counted, held);
    assert_int_equal(m.gpu, 1);
    assert_string_equal(m.device, im_solver_plan_device(plan));
    if (m.device_bytes != counted)
        fail_msg("%d x %d: estimated %.0f bytes of device memory, the engine counted %.0f", nx, ny, m.device_bytes,
                 counted);
    im_solver_plan_free(plan);
}

static void test_device_estimate_exact(void **state)
{
    (void)state;
    const int sides[][2] = {{96, 96}, {128, 64}, {200, 200}, {240, 240}, {256, 256}};
    for (size_t k = 0; k < sizeof sides / sizeof *sides; ++k)
        for (int periodic = 0; periodic < 2; ++periodic) {
            im_solver_options o = gpu_options(periodic, 1, 0);
            check_device_estimate(sides[k][0], sides[k][1], &o);
            o.cascade = 0;
            check_device_estimate(sides[k][0], sides[k][1], &o);
            o = gpu_options(periodic, 1, 0.5); /* a cap: no cascade, no preconditioner */
            check_device_estimate(sides[k][0], sides[k][1], &o);
        }
}

/* indent's note under auto (src/front/indent.c) estimates the plan as made (im_solver_plan_memory): an
 * indentation's plan solves the repulsive problem on its window, with the cap H_p + w / delta_c, no
 * adhesion, and neither cascade nor preconditioner under the cap; its estimate is what the engine counted
 * for it, and the estimate of the run's own grid and options is not. */
static void test_plan_memory_is_the_plans(void **state)
{
    (void)state;
    im_field *surface = test_rough_surface(128, 0.08, 3);
    const im_indenter cone = im_indenter_cone(80);
    im_solver_options o = gpu_options(0, 1, 0.5);
    o.adhesion_work = 0.05;
    o.adhesion_range = 0.6;
    im_indentation *run = NULL;
    if (im_indentation_create(surface, &cone, IM_CONTROL_DISPLACEMENT, 2.0, &o, &run) != IM_OK)
        fail_msg("indentation: %s", im_last_error());
    const im_solver_plan *plan = im_indentation_plan(run);
    const im_window w = im_indentation_window(run);
    im_solver_memory m, whole;
    assert_int_equal(im_solver_plan_memory(plan, &m), IM_OK);
    assert_int_equal(im_solver_memory_needed(128, 128, &o, &whole), IM_OK);
    double counted, held;
    solver_engine_gpu_memory(plan, &counted, &held);
    print_message("window %d x %d of 128 x 128: the plan's estimate %.0f bytes, counted %.0f; the grid's %.0f\n",
                  w.nx, w.ny, m.device_bytes, counted, whole.device_bytes);
    assert_true(w.nx < 128 && w.ny < 128);
    assert_int_equal(m.gpu, 1);
    assert_true(m.device_bytes == counted);
    assert_true(whole.device_bytes > counted);
    im_indentation_free(run);
    im_field_free(surface);
}

/* ---- the host's peak against VmHWM ---- */

/* A line "NAME:   123 kB" of /proc/self/status, in bytes. */
static double status_bytes(const char *name)
{
    FILE *f = fopen("/proc/self/status", "r");
    char line[256];
    double kib = NAN;
    while (f && fgets(line, sizeof line, f))
        if (strncmp(line, name, strlen(name)) == 0)
            kib = strtod(line + strlen(name) + 1, NULL);
    if (f)
        fclose(f);
    return 1024 * kib;
}

/* Resets VmHWM to the resident set now (Linux >= 4.0); the resident set then. */
static double reset_peak(void)
{
    FILE *f = fopen("/proc/self/clear_refs", "w");
    if (!f || fputs("5", f) < 0)
        fail_msg("cannot reset the peak resident set through /proc/self/clear_refs");
    fclose(f);
    return status_bytes("VmRSS");
}

/* A smooth periodic surface (no synthesis: its temporaries would count in the peak). */
static im_field *wavy_surface(int n)
{
    im_field *s = NULL;
    if (im_field_create(n, n, 1.0, &s) != IM_OK)
        fail_msg("surface %d^2: %s", n, im_last_error());
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            s->data[(size_t)y * n + x] = 2.0 * cos(2 * M_PI * x / n) * cos(2 * M_PI * y / n);
    return s;
}

typedef struct {
    double measured, estimated; /* bytes */
} peak;

/* A periodic cell solved (the cascade's coarse levels, then the fine one: every buffer written); the
 * estimate of the plan and the caller's surface and cell (gap, pressure, displacement: 32 bytes a
 * patch) beside the rise of the peak resident set. */
static peak periodic_peak(int n)
{
    const double before = reset_peak();
    im_field *surface = wavy_surface(n);
    im_solver_options o = gpu_options(1, 1, 0);
    o.tol = 1e-4;
    im_solver_memory m;
    if (im_solver_memory_needed(n, n, &o, &m) != IM_OK)
        fail_msg("estimate %d^2: %s", n, im_last_error());
    im_flat_contact *cell = NULL;
    if (im_flat_contact_create(surface, &o, &cell) != IM_OK)
        fail_msg("flat contact %d^2: %s", n, im_last_error());
    im_flat_result result;
    if (im_flat_contact_solve(cell, 0.01, &result) != IM_OK)
        fail_msg("flat contact %d^2: %s", n, im_last_error());
    const peak p = {status_bytes("VmHWM") - before, m.host_bytes + 32.0 * n * n};
    im_flat_contact_free(cell);
    im_field_free(surface);
    return p;
}

/* The peak at n^2 in a process of its own (this program with --peak N), which opens Vulkan there
 * first: memory an earlier solve's libraries kept (lavapipe's, glibc's) would be reused by a later one
 * and hide from its peak. */
static peak peak_alone(int n)
{
    char command[128], line[512];
    snprintf(command, sizeof command, "/proc/%d/exe --peak %d", (int)getpid(), n);
    FILE *child = popen(command, "r");
    peak p = {NAN, NAN};
    while (child && fgets(line, sizeof line, child))
        sscanf(line, "peak %lf %lf", &p.measured, &p.estimated);
    if (!child || pclose(child) != 0 || !isfinite(p.measured))
        fail_msg("%s failed", command);
    print_message("%d^2 periodic: peak resident set rose %.1f MiB, estimated %.1f MiB: measured / estimated %.2f, "
                  "measured - estimated %.1f MiB\n",
                  n, p.measured / MIB, p.estimated / MIB, p.measured / p.estimated, (p.measured - p.estimated) / MIB);
    return p;
}

/* What the estimate leaves out is a constant: lavapipe's and LLVM's libraries and the compiled shaders
 * (160-180 MiB measured). Between 512^2 and 2048^2 the rise of the peak is the rise of the estimate. */
static void test_host_estimate_against_peak(void **state)
{
    (void)state;
#ifdef __SANITIZE_ADDRESS__
    skip(); /* the sanitizer's shadow memory and quarantine are in the resident set */
#endif
    const peak small = peak_alone(512), middle = peak_alone(1024), large = peak_alone(2048);
    (void)middle;
    const double ratio = (large.measured - small.measured) / (large.estimated - small.estimated);
    print_message("512^2 to 2048^2: the peak rose %.2f times as much as the estimate\n", ratio);
    if (!(ratio >= 0.9 && ratio <= 1.1))
        fail_msg("512^2 to 2048^2 periodic: the peak resident set rose %.2f times the estimate's rise, expected "
                 "0.9 to 1.1",
                 ratio);
}

/* ---- refusals and the fall-back ---- */

/* device = gpu on a device the engine may fill only 1 MiB of: refused before any plan, naming the
 * device, the memory needed and the memory it has; a plan made anyway is refused by the engine, with
 * the same status (IM_ENOMEM: the device's memory is too small, whichever finds it). */
static void test_gpu_refused_when_too_small(void **state)
{
    (void)state;
    im_solver_options o = gpu_options(1, 1, 0);
    im_solver_memory m;
    im_solver_plan *plan = NULL;
    setenv("INDENTMAP_GPU_MAX_MEMORY", "1048576", 1);
    const int estimated = im_solver_memory_needed(256, 256, &o, &m);
    char error[1024];
    snprintf(error, sizeof error, "%s", im_last_error());
    const int planned = im_solver_plan_create(256, 256, 1.0, &o, &plan);
    unsetenv("INDENTMAP_GPU_MAX_MEMORY");
    print_message("%s\n", error);
    assert_int_equal(estimated, IM_ENOMEM);
    assert_int_equal(planned, IM_ENOMEM);
    char needed[128], has[sizeof m.device + 64];
    snprintf(needed, sizeof needed, "a 256 x 256 solve needs %.3g GiB of device memory",
             m.device_bytes / 1073741824.0);
    snprintf(has, sizeof has, "%s has 0.000977 GiB", m.device);
    assert_non_null(strstr(error, needed));
    assert_non_null(strstr(error, has));
    assert_true(m.device_memory == 1048576.0);
    assert_int_equal(im_solver_memory_needed(256, 256, &o, &m), IM_OK);
    assert_true(m.device_bytes <= m.device_memory);
}

/* device = auto on a GPU too small: the CPU's estimate, with a note naming the device and both sizes;
 * on one that holds the plan, the GPU's. (auto never takes lavapipe: the choice is checked on its
 * estimate.) */
static void test_auto_falls_back(void **state)
{
    (void)state;
    im_solver_options o = gpu_options(1, 1, 0);
    solver_gpu_estimate gpu;
    assert_int_equal(solver_engine_gpu_estimate(512, 512, &o, &gpu), IM_OK);
    o.device = IM_DEVICE_AUTO;
    im_solver_memory m = {.host_bytes = im_solver_plan_bytes(512, 512), .device = "cpu"};
    assert_int_equal(solver_memory_choose(512, 512, &o, &gpu, &m), IM_OK);
    assert_int_equal(m.gpu, 1);
    assert_string_equal(m.note, "");
    gpu.device_memory = gpu.device_bytes - 1;
    m = (im_solver_memory){.host_bytes = im_solver_plan_bytes(512, 512), .device = "cpu"};
    assert_int_equal(solver_memory_choose(512, 512, &o, &gpu, &m), IM_OK);
    print_message("%s\n", m.note);
    assert_int_equal(m.gpu, 0);
    assert_string_equal(m.device, "cpu");
    assert_true(m.host_bytes == im_solver_plan_bytes(512, 512));
    assert_non_null(strstr(m.note, gpu.device));
    assert_non_null(strstr(m.note, "solved on the CPU"));
}

/* The estimate with buffers in parts of `part` bytes (INDENTMAP_GPU_MAX_PART; NULL: the device's own). */
static int estimate_in_parts(int nx, int ny, const im_solver_options *o, const char *part, im_solver_memory *m)
{
    if (part)
        setenv("INDENTMAP_GPU_MAX_PART", part, 1);
    const int status = im_solver_memory_needed(nx, ny, o, m);
    unsetenv("INDENTMAP_GPU_MAX_PART");
    return status;
}

/* Grids the engine would refuse are refused by the estimate too (gpu) or estimated on the CPU (auto):
 * a side of 17 (a prime above VkFFT's radices), and a periodic 256^2 cell in parts of 256 KiB (its
 * 528 KiB of modes in 3), whose first axis takes one upload. */
static void check_refused_like_the_engine(int nx, int ny, int periodic, const char *part, const char *phrase)
{
    im_solver_options o = gpu_options(periodic, 1, 0);
    im_solver_memory m;
    assert_int_equal(estimate_in_parts(nx, ny, &o, part, &m), IM_EUNSUPPORTED);
    if (!strstr(im_last_error(), phrase))
        fail_msg("%d x %d: '%s' does not say '%s'", nx, ny, im_last_error(), phrase);
    o.device = IM_DEVICE_AUTO;
    assert_int_equal(estimate_in_parts(nx, ny, &o, part, &m), IM_OK);
    assert_string_equal(m.device, "cpu");
    assert_true(m.host_bytes == im_solver_plan_bytes(nx, ny));
}

static void test_estimate_refuses_what_the_engine_refuses(void **state)
{
    (void)state;
    check_refused_like_the_engine(17, 64, 0, NULL, "prime factor above 13");
    check_refused_like_the_engine(256, 256, 1, "262144", "first axis (256)");
}

/* The estimate's rule for buffers in parts at its edge, GPU_PARTS_FIRST_AXIS (vulkan.h, the rule
 * fft.c's refusal names too): a periodic cell in parts of 256 KiB whose first axis is the largest
 * side under it that VkFFT transforms (16380 = 2^2 3^2 5 7 13) is refused naming the constant, one of
 * GPU_PARTS_FIRST_AXIS is estimated (its modes in 4 parts). */
static void test_parts_rule_at_its_edge(void **state)
{
    (void)state;
    im_solver_options o = gpu_options(1, 0, 0);
    im_solver_memory m;
    char phrase[128];
    snprintf(phrase, sizeof phrase, "first axis (16380) is shorter than VkFFT's several uploads need (%d)",
             GPU_PARTS_FIRST_AXIS);
    assert_int_equal(estimate_in_parts(16380, 8, &o, "262144", &m), IM_EUNSUPPORTED);
    if (!strstr(im_last_error(), phrase))
        fail_msg("'%s' does not say '%s'", im_last_error(), phrase);
    if (estimate_in_parts(GPU_PARTS_FIRST_AXIS, 8, &o, "262144", &m) != IM_OK)
        fail_msg("%d x 8 in parts: %s", GPU_PARTS_FIRST_AXIS, im_last_error());
    assert_int_equal(m.gpu, 1);
}

/* INDENTMAP_GPU_MAX_MEMORY is a whole number of bytes: other text fails the estimate and the plan, under
 * gpu and under auto alike (not read as some other size, nor ignored), naming the variable, its text and
 * what is expected; empty is unset, as for INDENTMAP_GPU_MAX_PART. */
static void test_max_memory_parsed_strictly(void **state)
{
    (void)state;
    const char *bad[] = {"abc", "-5", "12GiB", "1e400", "nan", "0", "1048576.5", "99999999999999999999999"};
    for (size_t k = 0; k < sizeof bad / sizeof *bad; ++k)
        for (int device = IM_DEVICE_GPU; device <= IM_DEVICE_AUTO; ++device) {
            im_solver_options o = gpu_options(1, 1, 0);
            o.device = device;
            im_solver_memory m;
            im_solver_plan *plan = NULL;
            setenv("INDENTMAP_GPU_MAX_MEMORY", bad[k], 1);
            const int estimated = im_solver_memory_needed(64, 64, &o, &m);
            char error[1024], expected[128];
            snprintf(error, sizeof error, "%s", im_last_error());
            const int planned = device == IM_DEVICE_GPU ? im_solver_plan_create(64, 64, 1.0, &o, &plan) : IM_EINVAL;
            unsetenv("INDENTMAP_GPU_MAX_MEMORY");
            im_solver_plan_free(plan);
            snprintf(expected, sizeof expected, "INDENTMAP_GPU_MAX_MEMORY=%s: expected a whole number of bytes",
                     bad[k]);
            if (estimated != IM_EINVAL || planned != IM_EINVAL || !strstr(error, expected))
                fail_msg("INDENTMAP_GPU_MAX_MEMORY=%s, device %d: estimate %d (%s), plan %d", bad[k], device,
                         estimated, error, planned);
        }
    im_solver_options o = gpu_options(1, 1, 0);
    im_solver_memory m;
    setenv("INDENTMAP_GPU_MAX_MEMORY", "", 1);
    assert_int_equal(im_solver_memory_needed(64, 64, &o, &m), IM_OK);
    setenv("INDENTMAP_GPU_MAX_MEMORY", "1048576", 1);
    assert_int_equal(im_solver_memory_needed(64, 64, &o, &m), IM_OK);
    unsetenv("INDENTMAP_GPU_MAX_MEMORY");
    assert_true(m.device_memory == 1048576.0);
}

int main(int argc, char **argv)
{
    test_keep_vulkan_libraries_loaded();
    if (argc == 3 && strcmp(argv[1], "--peak") == 0) {
        const peak p = periodic_peak(atoi(argv[2]));
        printf("peak %.0f %.0f\n", p.measured, p.estimated);
        return 0;
    }
    im_solver_options o = gpu_options(0, 1, 0);
    solver_gpu_estimate gpu;
    if (solver_engine_gpu_estimate(64, 64, &o, &gpu) != IM_OK) {
        printf("SKIPPED: no Vulkan device opens (%s)\n", im_last_error());
        return 77;
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_device_estimate_exact),
        cmocka_unit_test(test_plan_memory_is_the_plans),
        cmocka_unit_test(test_gpu_refused_when_too_small),
        cmocka_unit_test(test_auto_falls_back),
        cmocka_unit_test(test_estimate_refuses_what_the_engine_refuses),
        cmocka_unit_test(test_parts_rule_at_its_edge),
        cmocka_unit_test(test_max_memory_parsed_strictly),
        cmocka_unit_test(test_host_estimate_against_peak),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
#else
int main(void)
{
    printf("SKIPPED: the library is built without the GPU engine (IM_GPU off)\n");
    return 77;
}
#endif
