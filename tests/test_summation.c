/* Compensated block sums (core/summation.h) over 16.8 million patches, the 4096^2 grid of the
 * solver benchmark, against a quad-precision (__float128) reference of our own. */
#include "support.h"

#include "core/summation.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>

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
        cmocka_unit_test(test_short_and_empty),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
