/* The step lists of `indent --approach/--load` and of a scene's [loading] steps: one parser, one
 * limit, one set of messages. */
#include "front/front.h"
#include "core/number.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A finite number >= lowest spanning the whole of [start, start + length), blanks around it allowed. */
static int parse_value(const char *start, size_t length, double lowest, double *value)
{
    char item[128], *end;
    while (length > 0 && (*start == ' ' || *start == '\t'))
        ++start, --length;
    while (length > 0 && (start[length - 1] == ' ' || start[length - 1] == '\t'))
        --length;
    if (length == 0 || length >= sizeof item)
        return 0;
    memcpy(item, start, length);
    item[length] = '\0';
    errno = 0;
    *value = number_parse(item, &end);
    return end == item + length && errno != ERANGE && isfinite(*value) && *value >= lowest;
}

/* The refusal of a list of more than STEPS_MAX values; returns 0. */
static int too_many_steps(const char *name, const char *text, char *error, size_t size)
{
    snprintf(error, size, "%s '%.64s%s': more than %d values: expected at most %d steps", name, text,
             strlen(text) > 64 ? "..." : "", STEPS_MAX, STEPS_MAX);
    return 0;
}

/* Value i of first:last:n (n >= 2) by first + (last - first) i / (n - 1), the formula every kept result's
 * approaches (and so its scene key) came from, but that a value past the first within RANGE_ZERO_ULPS of the
 * ends' size from 0 is 0: the formula's own rounding is that large (0.6:-3:37 gave -1.11e-16 for 0), so such a
 * value means 0, and its sign and size are noise. The first is first itself, exactly (1e-20:1:3 starts at
 * 1e-20). Every other value keeps the formula's bits. */
#define RANGE_ZERO_ULPS 4
static double range_value(double first, double last, int i, int n)
{
    const double value = first + (last - first) * i / (n - 1);
    const double ends = fmax(fabs(first), fabs(last));
    return i > 0 && fabs(value) <= RANGE_ZERO_ULPS * DBL_EPSILON * ends ? 0 : value;
}

/* "first:last:count" spanning [start, start + length) into values (room for `room` values); 0 with a
 * message naming the item when it is not one or holds more values than fit. */
static int parse_range(const char *name, const char *text, const char *start, size_t length, double lowest,
                       double *values, int room, int *count, char *error, size_t size)
{
    const char *colon = memchr(start, ':', length), *end = start + length;
    const char *second = colon ? memchr(colon + 1, ':', (size_t)(end - colon - 1)) : NULL;
    double first, last, n;
    if (!second || memchr(second + 1, ':', (size_t)(end - second - 1)) ||
        !parse_value(start, (size_t)(colon - start), lowest, &first) ||
        !parse_value(colon + 1, (size_t)(second - colon - 1), lowest, &last) ||
        !parse_value(second + 1, (size_t)(end - second - 1), 0, &n)) {
        snprintf(error, size,
                 "%s '%s': '%.*s' is not a range first:last:count (three numbers%s): expected "
                 "values and ranges separated by commas",
                 name, text, (int)length, start, lowest == 0 ? " >= 0" : "");
        return 0;
    }
    if (n < 1 || n > STEPS_MAX || n != floor(n)) {
        snprintf(error, size, "%s '%s': '%.*s': expected first:last:count with 1 <= count <= %d (an integer)", name,
                 text, (int)length, start, STEPS_MAX);
        return 0;
    }
    if (n > room)
        return too_many_steps(name, text, error, size);
    *count = (int)n;
    for (int i = 0; i < *count; ++i)
        values[i] = *count == 1 ? last : range_value(first, last, i, *count);
    values[*count - 1] = last; /* exactly: 0:0.3:3 must end at 0.3, not 0.30000000000000004 */
    return 1;
}

/* One comma-separated item: a value or a range. Adds its values after values[0..*count). */
static int parse_item(const char *name, const char *text, const char *item, size_t length, double lowest,
                      double *values, int *count, char *error, size_t size)
{
    if (memchr(item, ':', length)) {
        int added = 0;
        if (!parse_range(name, text, item, length, lowest, values + *count, STEPS_MAX - *count, &added, error, size))
            return 0;
        *count += added;
        return 1;
    }
    if (*count >= STEPS_MAX)
        return too_many_steps(name, text, error, size);
    if (!parse_value(item, length, lowest, &values[*count])) {
        snprintf(error, size,
                 "%s '%s': '%.*s' is not a number%s: expected values and ranges separated by "
                 "commas",
                 name, text, (int)length, item, lowest == 0 ? " >= 0" : "");
        return 0;
    }
    ++*count;
    return 1;
}

int steps_check_mean_gaps(const char *name, const char *text, const double *values, int count, char *error,
                          size_t size)
{
    for (int i = 0; i < count; ++i)
        if (!(values[i] > 0)) {
            snprintf(error, size, "%s '%s': step %d is %g: expected mean gaps > 0 (at 0 the cell is in full contact)",
                     name, text, i + 1, values[i]);
            return -1;
        }
    return 0;
}

int steps_parse(const char *name, const char *text, double *values, int *count, char *error, size_t size)
{
    return steps_parse_signed(name, text, 0, values, count, error, size);
}

int steps_parse_signed(const char *name, const char *text, int negative, double *values, int *count, char *error,
                       size_t size)
{
    const double lowest = negative ? -INFINITY : 0;
    *count = 0;
    for (const char *item = text;;) {
        const char *comma = strchr(item, ',');
        size_t length = comma ? (size_t)(comma - item) : strlen(item);
        if (strspn(item, " \t") >= length) {
            snprintf(error, size, "%s '%s': %s", name, text,
                     *count == 0 && !comma ? "expected a list v1, v2, ... "
                                             "or a range first:last:count"
                                           : "an empty item (two commas, or a comma at either end): "
                                             "expected values separated by commas");
            return -1;
        }
        if (!parse_item(name, text, item, length, lowest, values, count, error, size))
            return -1;
        if (!comma)
            return 0;
        item = comma + 1;
    }
}

double steps_largest(const double *values, int count)
{
    double largest = 0;
    for (int i = 0; i < count; ++i)
        largest = fmax(largest, fabs(values[i]));
    return largest;
}
