/* Compensated block sums (core/summation.h) over 16.8 million patches, the 4096^2 grid of the
 * solver benchmark, against a quad-precision (__float128) reference of our own. */
#include "support.h"

#include "core/summation.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#define SIDE 4096
#define COUNT ((size_t)SIDE * SIDE)

static double relative_error(double value, __float128 exact) { return (double)(((__float128)value - exact) / exact); }

/* Forces of a loaded cone: p_m acosh(a/r) inside r < a (from 10 to ~1e-7 near the rim), plus
 * patches outside carrying forces 12 decades smaller, so that the magnitudes span 19 decades. */
static double cone_like_force(size_t i)
{
    double x = (double)(i % SIDE) - SIDE / 2 + 0.5, y = (double)(i / SIDE) - SIDE / 2 + 0.5;
    double r = hypot(x, y), a = 1800.0;
    return r < a ? acosh(a / r) : 1e-12 * (1.0 + (double)(i % 7));
}

static __float128 quad_sum_doubles(const double *v, size_t n)
{
    __float128 s = 0;
    for (size_t i = 0; i < n; ++i)
        s += v[i];
    return s;
}

/* Single-precision forces (a float32 .npy, widened to double by the reader, as im_npy_read does):
 * a float accumulator would round every addition once the sum is 2^24 times the addend and end
 * 15% off; the compensated sum does not lose a digit. */
static void test_single_precision_data(void **state)
{
    (void)state;
    float *single = malloc(sizeof(float) * COUNT);
    double *widened = malloc(sizeof(double) * COUNT);
    assert_non_null(single);
    assert_non_null(widened);
    for (size_t i = 0; i < COUNT; ++i)
        single[i] = 0.1f;
    const __float128 exact = (__float128)COUNT * (double)0.1f;
    float naive = 0;
    for (size_t i = 0; i < COUNT; ++i)
        naive += single[i];
    assert_true(fabs(relative_error(naive, exact)) > 0.1); /* what the summation is for */
    for (size_t i = 0; i < COUNT; ++i)
        widened[i] = single[i];
    assert_true(fabs(relative_error(sum_doubles(widened, COUNT), exact)) < 1e-15);
    free(single);
    free(widened);
}

static void test_double_precision_over_19_decades(void **state)
{
    (void)state;
    double *v = malloc(sizeof(double) * COUNT);
    assert_non_null(v);
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < COUNT; ++i)
        v[i] = cone_like_force(i);
    const __float128 exact = quad_sum_doubles(v, COUNT);
    double e = relative_error(sum_doubles(v, COUNT), exact);
    assert_true(fabs(e) < 2 * 1.1102230246251565e-16); /* within one rounding of the exact sum */
    free(v);
}

/* The blocks do not depend on the thread count, so neither does any bit of the result. */
static void test_independent_of_thread_count(void **state)
{
    (void)state;
    const size_t n = 3 * IM_SUM_BLOCK * 100 + 17; /* a ragged last block */
    double *v = malloc(sizeof(double) * n);
    assert_non_null(v);
    for (size_t i = 0; i < n; ++i)
        v[i] = sin(0.37 * (double)i) * exp(-1e-5 * (double)i);
    int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    double one = sum_doubles(v, n);
    omp_set_num_threads(3);
    double three = sum_doubles(v, n);
    omp_set_num_threads(threads);
    assert_memory_equal(&one, &three, sizeof one);
    assert_true(fabs(relative_error(one, quad_sum_doubles(v, n))) < 1e-15);
    free(v);
}

/* Values made range by range and stored as they are summed (sum_ranges: the cascade's restriction). */
static double made_range(size_t lo, size_t hi, const void *context)
{
    double *v = *(double *const *)context;
    compensated c = {0, 0};
    for (size_t i = lo; i < hi; ++i) {
        v[i] = sin(0.37 * (double)i) * ldexp(1, (int)(i % 97) - 48); /* 29 decades: the order tells */
        compensated_add(&c, v[i]);
    }
    return compensated_total(&c);
}

/* summation.h's layout, written out: compensated sums of blocks of max(IM_SUM_BLOCK, n / IM_SUM_MAX_BLOCKS
 * rounded up) values, combined with compensation in block order. */
static double blocks_in_order(const double *v, size_t n)
{
    const size_t shortest = (n + IM_SUM_MAX_BLOCKS - 1) / IM_SUM_MAX_BLOCKS;
    const size_t length = shortest > IM_SUM_BLOCK ? shortest : IM_SUM_BLOCK;
    compensated total = {0, 0};
    for (size_t lo = 0; lo < n; lo += length) {
        compensated block = {0, 0};
        for (size_t i = lo; i < n && i < lo + length; ++i)
            compensated_add(&block, v[i]);
        compensated_add(&total, compensated_total(&block));
    }
    return compensated_total(&total);
}

/* sum_ranges of values made as they are summed is, to the bit, sum_doubles over the values stored and
 * the layout written out, at any thread count: with one block, a ragged last block, and beyond
 * IM_SUM_MAX_BLOCKS blocks of IM_SUM_BLOCK (longer blocks). */
static void test_ranges_are_sum_doubles(void **state)
{
    (void)state;
    const size_t sizes[] = {1, IM_SUM_BLOCK - 1, 3 * IM_SUM_BLOCK + 17,
                            (size_t)IM_SUM_MAX_BLOCKS * IM_SUM_BLOCK + 4097};
    const int threads = omp_get_max_threads();
    for (size_t k = 0; k < sizeof sizes / sizeof *sizes; ++k) {
        double *v = malloc(sizeof(double) * sizes[k]);
        assert_non_null(v);
        for (int team = 1; team <= 3; team += 2) {
            omp_set_num_threads(team);
            memset(v, 0, sizeof(double) * sizes[k]);
            const double made = sum_ranges(sizes[k], made_range, &v), stored = sum_doubles(v, sizes[k]),
                         reference = blocks_in_order(v, sizes[k]);
            assert_memory_equal(&made, &reference, sizeof made);
            assert_memory_equal(&stored, &reference, sizeof made);
        }
        free(v);
    }
    omp_set_num_threads(threads);
}

static void test_short_and_empty(void **state)
{
    (void)state;
    const double v[3] = {1e16, 1.0, -1e16}; /* the 1 survives the cancellation */
    assert_true(sum_doubles(v, 3) == 1.0);
    assert_true(sum_doubles(v, 0) == 0.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_single_precision_data),
        cmocka_unit_test(test_double_precision_over_19_decades),
        cmocka_unit_test(test_independent_of_thread_count),
        cmocka_unit_test(test_ranges_are_sum_doubles),
        cmocka_unit_test(test_short_and_empty),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
