/* The step lists of `indent --approach/--load` and of a scene's [loading] steps: one parser, one
 * limit, one set of messages. */
#include "front/front.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A finite number >= 0 spanning the whole of [start, start + length), blanks around it allowed. */
static int parse_value(const char *start, size_t length, double *value)
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
    *value = strtod(item, &end);
    return end == item + length && errno != ERANGE && isfinite(*value) && *value >= 0;
}

/* "first:last:count": 1 when text is one (parsed or refused), 0 when it holds no ':'. */
static int parse_range(const char *name, const char *text, double *values, int *count, char *error, size_t size,
                       int *failed)
{
    const char *colon = strchr(text, ':'), *second = colon ? strchr(colon + 1, ':') : NULL;
    if (!colon)
        return 0;
    double first, last, n;
    *failed = 1;
    if (!second || strchr(second + 1, ':') || !parse_value(text, (size_t)(colon - text), &first) ||
        !parse_value(colon + 1, (size_t)(second - colon - 1), &last) ||
        !parse_value(second + 1, strlen(second + 1), &n)) {
        snprintf(error, size, "%s '%s': expected a range first:last:count (three numbers >= 0) or a list "
                 "v1, v2, ...", name, text);
        return 1;
    }
    if (n < 1 || n > STEPS_MAX || n != floor(n)) {
        snprintf(error, size, "%s '%s': expected first:last:count with 1 <= count <= %d (an integer)", name, text,
                 STEPS_MAX);
        return 1;
    }
    *count = (int)n;
    for (int i = 0; i < *count; ++i)
        values[i] = *count == 1 ? last : first + (last - first) * i / (*count - 1);
    *failed = 0;
    return 1;
}

int steps_parse(const char *name, const char *text, double *values, int *count, char *error, size_t size)
{
    int failed = 0;
    *count = 0;
    if (parse_range(name, text, values, count, error, size, &failed))
        return failed ? -1 : 0;
    for (const char *item = text;; ++*count) {
        const char *comma = strchr(item, ',');
        size_t length = comma ? (size_t)(comma - item) : strlen(item);
        if (*count >= STEPS_MAX) {
            snprintf(error, size, "%s '%.64s%s': more than %d values: expected at most %d steps", name, text,
                     strlen(text) > 64 ? "..." : "", STEPS_MAX, STEPS_MAX);
            return -1;
        }
        if (strspn(item, " \t") >= length) {
            snprintf(error, size, "%s '%s': %s", name, text, *count == 0 && !comma ? "expected a list v1, v2, ... "
                     "or a range first:last:count" : "an empty item (two commas, or a comma at either end): "
                     "expected values separated by commas");
            return -1;
        }
        if (!parse_value(item, length, &values[*count])) {
            snprintf(error, size, "%s '%s': '%.*s' is not a number >= 0: expected values separated by commas", name,
                     text, (int)length, item);
            return -1;
        }
        if (!comma)
            break;
        item = comma + 1;
    }
    ++*count;
    return 0;
}
