/* Argument checks at the public entry points (issue 32, SQLite's rule: a misuse is reported, not
 * undefined). Every public function checks its handles, output pointers and field views first and
 * returns IM_EINVAL with a message naming itself and the argument ("im_surface_psd: out is NULL:
 * expected a pointer"); void and value functions record the same message and return their safe
 * result (nothing, NULL, NaN, 0). Internal helpers (no im_ prefix) are not exported. */
#ifndef INDENTMAP_CORE_ARGS_H
#define INDENTMAP_CORE_ARGS_H

#include "indentmap/field.h"
#include "indentmap/status.h"

#include <math.h>

/* IM_EINVAL with "FUNCTION: ARGUMENT is NULL: expected a pointer". */
int arg_null(const char *function, const char *argument);
/* im_field_check_view(field, "FUNCTION: ARGUMENT"). */
int arg_view(const char *function, const char *argument, const im_field *field);

/* IM_EINVAL with "FUNCTION: nx x ny = NX x NY: expected each side in [1, IM_FIELD_MAX_SIDE]"
 * unless both sides are in that range. */
int arg_sides(const char *function, int nx, int ny);

/* The checks: p (f) is the parameter, name the argument as the header names it ("out"). */
/* In a function returning a status: return IM_EINVAL when the pointer p is NULL. */
#define ARG_REQUIRE(p, name)                                                                                         \
    do {                                                                                                             \
        if (!(p))                                                                                                    \
            return arg_null(__func__, name);                                                                         \
    } while (0)
/* In a void or value function: record the misuse and return `result` (empty for void). */
#define ARG_REQUIRE_OR(p, name, result)                                                                              \
    do {                                                                                                             \
        if (!(p)) {                                                                                                  \
            arg_null(__func__, name);                                                                                \
            return result;                                                                                           \
        }                                                                                                            \
    } while (0)
/* In a function returning a status: return IM_EINVAL when f is not a valid field view. */
#define ARG_VIEW(f, name)                                                                                            \
    do {                                                                                                             \
        int arg_status_ = arg_view(__func__, name, (f));                                                             \
        if (arg_status_ != IM_OK)                                                                                    \
            return arg_status_;                                                                                      \
    } while (0)
/* In a function returning a status (a value): return IM_EINVAL (result) for a grid size outside
 * [1, IM_FIELD_MAX_SIDE]. */
#define ARG_SIDES(nx, ny)                                                                                            \
    do {                                                                                                             \
        int arg_status_ = arg_sides(__func__, (nx), (ny));                                                           \
        if (arg_status_ != IM_OK)                                                                                    \
            return arg_status_;                                                                                      \
    } while (0)
#define ARG_SIDES_OR(nx, ny, result)                                                                                 \
    do {                                                                                                             \
        if (arg_sides(__func__, (nx), (ny)) != IM_OK)                                                                \
            return result;                                                                                           \
    } while (0)
/* The same in a void or value function. */
#define ARG_VIEW_OR(f, name, result)                                                                                 \
    do {                                                                                                             \
        if (arg_view(__func__, name, (f)) != IM_OK)                                                                  \
            return result;                                                                                           \
    } while (0)

#endif
