/* indentmap/field.h: a scalar field on a regular grid (heights, forces, gaps, ...).
 *
 * Entry points:
 *   im_field_create, im_field_clone, im_field_free   a field of the caller's (im_field_count: its size)
 *   im_field_check_view, im_field_check_finite       whether a field can be used
 *   im_memory_check, im_memory_available             the memory test every large allocation passes
 *   im_memory_set_limit, im_memory_limit             a cap below what the machine has
 *
 * Layout: row-major, value (ix, iy) at data[iy * nx + ix], ix along x in [0, nx), iy along y in
 * [0, ny). Row 0 is y = 0: images put it at the bottom, as a plot's axes would. The grid spacing
 * delta is the side of one square patch; lengths are in units of delta unless the field carries a
 * physical spacing (delta != 1, with unit naming it).
 *
 * Misuse (status.h): every function returns IM_EINVAL for a NULL output or an invalid view
 * (im_field_check_view) and does not crash; im_field_free accepts NULL.
 * Threads: thread-safe on distinct fields (one field may be read by several threads). The memory
 * cap is one process-wide value (atomic): set it before work starts.
 */
#ifndef INDENTMAP_FIELD_H
#define INDENTMAP_FIELD_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct im_field {
    int nx, ny;          /* grid size, >= 1 each */
    double delta;        /* patch side in physical units (1 when dimensionless) */
    char unit[16];       /* physical unit of delta and heights, "" when dimensionless */
    double *data;        /* nx * ny values, row-major, owned by the field */
    char value_unit[40]; /* unit of the values when they are not lengths in `unit` (a force field:
                            "N", "Pa·µm²", "E* δ²"); "" for heights and other lengths */
} im_field;

/* Largest side accepted for any grid; guards index arithmetic, not memory. */
#define IM_FIELD_MAX_SIDE (1 << 16)

/* Allocates a zeroed nx x ny field with spacing delta. Refuses sizes outside [1, IM_FIELD_MAX_SIDE]
 * and, before allocating, any field that would not fit in the memory available (im_memory_check).
 * Returns IM_OK and sets *out, or an error status. */
int im_field_create(int nx, int ny, double delta, im_field **out);

/* Deep copy of a field into a new *out; the same errors as im_field_create, IM_EINVAL for an
 * invalid src view. */
int im_field_clone(const im_field *src, im_field **out);

/* Frees a field; accepts NULL. */
void im_field_free(im_field *field);

/* The number of values, nx * ny; 0 for NULL or a side < 1 (a view im_field_check_view refuses). */
static inline size_t im_field_count(const im_field *f)
{
    return f && f->nx > 0 && f->ny > 0 ? (size_t)f->nx * (size_t)f->ny : 0;
}

/* IM_OK when field is a valid view: not NULL, nx and ny in [1, IM_FIELD_MAX_SIDE] (so nx * ny fits
 * any index arithmetic) and data not NULL. Otherwise IM_EINVAL with a message that starts with
 * `what` (the function and argument: "im_surface_psd: surface") and says which invariant is
 * broken. Every public function taking a field checks it so (what may be NULL: "field"). The view
 * cannot tell whether data really holds nx * ny values: that remains the caller's contract. */
int im_field_check_view(const im_field *field, const char *what);

/* IM_ENUMERIC with the first offending index in the message if any value is NaN or Inf; what
 * names the field in that message. */
int im_field_check_finite(const im_field *field, const char *what);

/* Physical memory available to this process now, in bytes: MemAvailable from /proc/meminfo,
 * bounded by what the address-space limit (ulimit -v) leaves beyond the process's present virtual
 * size and by the cap of im_memory_set_limit, if any; 0 if it cannot be determined. */
size_t im_memory_available(void);

/* A cap in bytes on the memory every check (im_memory_check, im_memory_available) allows, below
 * what the machine has; 0 (the default) for none. Process-wide, like the limits it joins; set it
 * before starting work. The library reads no environment: the indentmap program sets it from
 * IM_MEMORY_LIMIT_MIB (MiB; anything but a number > 0 is refused there, exit status 2). */
void im_memory_set_limit(size_t bytes);
/* The cap of im_memory_set_limit, 0 when none. */
size_t im_memory_limit(void);

/* What an address-space limit (ulimit -v) leaves beyond this process's present virtual size, in
 * bytes; 0 when there is no such limit. Reservations that use no memory (thread stacks, malloc's
 * per-thread arenas, mapped libraries) count against it. */
size_t im_address_space_available(void);

/* IM_ENOMEM, with the estimate and what is available in the message, when bytes exceed the
 * memory available; IM_OK otherwise. what names the allocation ("surface 8192 x 8192"). */
int im_memory_check(double bytes, const char *what);

#ifdef __cplusplus
}
#endif

#endif
