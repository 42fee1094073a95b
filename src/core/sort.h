/* core/sort.h: ascending sort of doubles, shared by the readers (x y z points) and the surface
 * preparation (row medians), and selection of one order statistic (colour ranges' percentiles). The
 * values must be numbers: NaN has no place in the order. */
#ifndef INDENTMAP_CORE_SORT_H
#define INDENTMAP_CORE_SORT_H

#include <stddef.h>

void sort_doubles(double *values, size_t count);
/* Reorders values[0..count) (k < count) so that values[k] is the k-th smallest, none before it larger and
 * none after it smaller, in O(count) on average: a percentile without a whole sort. */
void select_doubles(double *values, size_t count, size_t k);

#endif
