/* Compensated block sums (see summation.h). */
#include "core/summation.h"

#include <math.h>

/* Compensated sum of v[lo..hi). */
static double range_sum(const double *v, size_t lo, size_t hi)
{
    compensated c = {0, 0};
    for (size_t i = lo; i < hi; ++i)
        compensated_add(&c, v[i]);
    return compensated_total(&c);
}

/* Blocks summed in parallel, then combined in block order, so the result does not depend on the
 * thread count; the block length grows with n so that the block sums fit on the stack. */
double sum_doubles(const double *v, size_t n)
{
    const size_t shortest = (n + IM_SUM_MAX_BLOCKS - 1) / IM_SUM_MAX_BLOCKS;
    const size_t length = shortest > IM_SUM_BLOCK ? shortest : IM_SUM_BLOCK;
    const size_t blocks = (n + length - 1) / length;
    double block[IM_SUM_MAX_BLOCKS];
#pragma omp parallel for schedule(static)
    for (size_t b = 0; b < blocks; ++b)
        block[b] = range_sum(v, b * length, b + 1 < blocks ? (b + 1) * length : n);
    compensated total = {0, 0};
    for (size_t b = 0; b < blocks; ++b)
        compensated_add(&total, block[b]);
    return compensated_total(&total);
}
