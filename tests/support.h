/* Shared helpers for the test programs (cmocka). */
#ifndef INDENTMAP_TEST_SUPPORT_H
#define INDENTMAP_TEST_SUPPORT_H

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>

/* A fresh empty directory under $TMPDIR (or /tmp) for this test program; removed at exit. */
const char *test_temp_dir(void);

/* test_temp_dir()/name in a static buffer (one of 8 rotating buffers). */
const char *test_path(const char *name);

/* Writes bytes to a file; fails the test if it cannot. */
void test_write_bytes(const char *path, const void *data, size_t size);

/* Copies a file's bytes to another; fails the test if it cannot. */
void test_copy_file(const char *from, const char *to);

/* A generated rough surface n x n (H 0.8, lambda_s 4, lambda_r n, h'rms slope, the seed); the test
 * fails if it cannot be made. Caller frees (im_field_free). */
struct im_field;
struct im_field *test_rough_surface(int n, double slope, uint64_t seed);

/* Under AddressSanitizer: the Vulkan loader unloads drivers and layers when an instance ends, so what
 * they keep until exit would be reported in "<unknown module>"; kept loaded, LeakSanitizer names their
 * libraries and tests/gpu_lsan.supp can suppress those (and nothing of ours). A no-op otherwise. Call
 * first in main of a test that opens Vulkan. */
void test_keep_vulkan_libraries_loaded(void);

/* Runs the cases of `tests` that the program's arguments choose: none, every case; NAMES (comma-separated),
 * those; --skip NAMES, all the others. A name that is no case's is refused with a message and exit status 2,
 * so a renamed case cannot drop out of both of the ctest entries that split a program: the cases costly under
 * the sanitizers in one labelled slow, the rest in the other (CMakeLists.txt, docs/tests.md). */
int test_run_cases(const struct CMUnitTest *tests, size_t count, int argc, char **argv);
#define test_run_chosen_cases(tests, argc, argv) test_run_cases(tests, sizeof tests / sizeof *tests, argc, argv)

/* Relative difference |a - b| / max(|a|, |b|, tiny). */
double test_relative_difference(double a, double b);

/* Asserts |actual - expected| <= tolerance with a message naming the values. */
#define assert_close(actual, expected, tolerance)                                                                    \
    do {                                                                                                             \
        double a_ = (actual), e_ = (expected), t_ = (tolerance);                                                     \
        if (!(fabs(a_ - e_) <= t_))                                                                                  \
            fail_msg("%s = %.17g, expected %.17g within %g", #actual, a_, e_, t_);                                   \
    } while (0)

#endif
