/* Allocation-failure injection (SQLite's fault tests): every allocation that the library makes
 * itself (malloc, calloc, realloc, fftw_malloc, redirected here with the linker's --wrap) is made to
 * fail in turn, the first, the second, ..., until the operation succeeds. Each failure must come
 * back as IM_ENOMEM with a message, without a crash; under the sanitizer build LeakSanitizer checks
 * at exit that nothing the failed attempts allocated was left behind, and ASan that nothing was
 * freed twice. Covers the readers, synthesis and statistics, and the solver's plans and steps. */
#include "support.h"

#include "indentmap/indenter.h"
#include "indentmap/formats.h"
#include "indentmap/io.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"

#include <fftw3.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

/* ---- the injector: allocation number `fail_at` (counting from 0) returns NULL ---- */
static atomic_long allocations;
static atomic_long fail_at = -1;
static atomic_int injected;

void *__real_malloc(size_t size);
void *__real_calloc(size_t count, size_t size);
void *__real_realloc(void *pointer, size_t size);
void *__real_fftw_malloc(size_t size);

static int should_fail(void)
{
    long n = atomic_fetch_add(&allocations, 1);
    if (n == atomic_load(&fail_at)) {
        atomic_store(&injected, 1);
        return 1;
    }
    return 0;
}

void *__wrap_malloc(size_t size) { return should_fail() ? NULL : __real_malloc(size); }
void *__wrap_calloc(size_t count, size_t size) { return should_fail() ? NULL : __real_calloc(count, size); }
void *__wrap_realloc(void *pointer, size_t size) { return should_fail() ? NULL : __real_realloc(pointer, size); }
void *__wrap_fftw_malloc(size_t size) { return should_fail() ? NULL : __real_fftw_malloc(size); }

typedef int (*operation)(void *context);

/* Runs op with allocation k failing, for k = 0, 1, ... until it succeeds with nothing injected.
 * Returns how many allocations the successful run made. */
static long fail_each_allocation_in_turn(const char *name, operation op, void *context)
{
    for (long k = 0;; ++k) {
        atomic_store(&allocations, 0);
        atomic_store(&injected, 0);
        atomic_store(&fail_at, k);
        int status = op(context);
        atomic_store(&fail_at, -1);
        if (!atomic_load(&injected)) {
            if (status != IM_OK)
                fail_msg("%s failed without an injected fault: %s", name, im_last_error());
            print_message("%s: each of %ld allocations failed in turn, each reported\n", name, k);
            return k;
        }
        if (status != IM_ENOMEM)
            fail_msg("%s with allocation %ld failing: status %d (%s), expected IM_ENOMEM", name, k, status,
                     im_last_error());
        assert_true(strlen(im_last_error()) > 0);
        if (k > 10000)
            fail_msg("%s: more than 10000 allocations", name);
    }
}

/* ---- the operations ---- */
static im_field *make_surface(int n)
{
    im_surface_params p = im_surface_params_default();
    p.nx = p.ny = n;
    p.lambda_r = n;
    im_field *s = NULL;
    assert_int_equal(im_surface_generate(&p, &s), IM_OK);
    return s;
}

static int read_file(void *context)
{
    im_field *f = NULL;
    int status = im_surface_read(context, &f);
    im_field_free(f);
    return status;
}

static int generate(void *context)
{
    (void)context;
    im_surface_params p = im_surface_params_default();
    p.nx = p.ny = 32;
    p.lambda_r = 32;
    im_field *s = NULL;
    int status = im_surface_generate(&p, &s);
    im_field_free(s);
    return status;
}

static int statistics(void *context)
{
    im_surface_stats stats;
    im_psd *psd = NULL;
    im_histogram *histogram = NULL;
    int status = im_surface_statistics(context, &stats);
    if (status == IM_OK)
        status = im_surface_psd(context, 16, &psd);
    if (status == IM_OK)
        status = im_surface_histogram(context, IM_HIST_CURVATURE, 20, &histogram);
    im_psd_free(psd);
    im_histogram_free(histogram);
    return status;
}

static int plan(void *context)
{
    (void)context;
    im_solver_options o = im_solver_options_default();
    o.tol = 1e-8; /* the bars below were set at tol 1e-8 (not the default, 1e-6) */
    im_solver_plan *p = NULL;
    int status = im_solver_plan_create(24, 20, 1.0, &o, &p);
    im_solver_plan_free(p);
    return status;
}

static int indentation(void *context)
{
    im_indenter cone = im_indenter_cone(80);
    im_solver_options o = im_solver_options_default();
    o.tol = 1e-8; /* the bars below were set at tol 1e-8 (not the default, 1e-6) */
    im_indentation *run = NULL;
    im_step_result r;
    int status = im_indentation_create(context, &cone, IM_CONTROL_DISPLACEMENT, 2.0, &o, &run);
    if (status == IM_OK)
        status = im_indentation_step(run, 1.0, &r);
    if (status == IM_OK)
        status = im_indentation_step(run, 2.0, &r);
    im_field *force = NULL, *gap = NULL, *displacement = NULL;
    if (status == IM_OK)
        status = im_indentation_fields(run, &force, &gap, &displacement);
    im_field_free(force);
    im_field_free(gap);
    im_field_free(displacement);
    im_indentation_free(run);
    return status;
}

/* ---- the tests ---- */
static void test_readers(void **state)
{
    (void)state;
    im_field *s = make_surface(16);
    const char *formats[] = {"s.npy", "s.txt", "s.gsf"};
    for (int i = 0; i < 3; ++i) {
        const char *path = test_path(formats[i]);
        assert_int_equal(im_surface_write(path, s), IM_OK);
        long count = fail_each_allocation_in_turn(formats[i], read_file, (void *)path);
        assert_true(count >= 1);
    }
    im_field_free(s);
}

static void test_synthesis_and_statistics(void **state)
{
    (void)state;
    assert_true(fail_each_allocation_in_turn("im_surface_generate", generate, NULL) >= 2);
    im_field *s = make_surface(32);
    assert_true(fail_each_allocation_in_turn("statistics, PSD, histogram", statistics, s) >= 3);
    im_field_free(s);
}

static void test_solver(void **state)
{
    (void)state;
    assert_true(fail_each_allocation_in_turn("im_solver_plan_create", plan, NULL) >= 5);
    im_field *s = make_surface(32);
    assert_true(fail_each_allocation_in_turn("indentation history", indentation, s) >= 5);
    im_field_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_readers),
        cmocka_unit_test(test_synthesis_and_statistics),
        cmocka_unit_test(test_solver),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
