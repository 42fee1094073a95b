/* core/sort.h: ascending sort of doubles, shared by the readers (x y z points) and the surface
 * preparation (row medians). The values must be numbers: NaN has no place in the order. */
#ifndef INDENTMAP_CORE_SORT_H
#define INDENTMAP_CORE_SORT_H

#include <stddef.h>

void sort_doubles(double *values, size_t count);

#endif
