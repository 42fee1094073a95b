/* indentmap/colormap.h: colour maps and norms, the single CPU definition of how a value becomes a
 * colour. The GL renderer uploads the same tables and must reproduce im_colormap_rgb exactly (to
 * one 8-bit level); its tests compare against this module.
 *
 * Entry points:
 *   im_colormap_make, im_colormap_check         a map with its norm; is the norm usable
 *   im_colormap_from_name, im_colormap_name     "viridis" <-> IM_COLORMAP_VIRIDIS
 *   im_colormap_index, im_colormap_rgb          one value's table entry and colour
 *   im_colormap_field_image                     a field as an RGB image
 *   im_colormap_table                           a map's 256 colours
 *   im_colormap_range_empty, im_colormap_range_add, im_colormap_range_norm
 *                                               one default norm shared by several fields (forces,
 *                                               heights, or the tension of patches under tension)
 *   im_colormap_range_clipped                   such a range with a percentage of outliers cut at each end
 *   im_colormap_outlier_note                    whether a few outliers set heights' default range, said
 *
 * A norm maps [lo, hi] linearly (or logarithmically, lo > 0) onto the 256 table entries:
 * index = floor(256 t) clamped to 255, with t = (v - lo) / (hi - lo) (or in log v). Values below
 * lo take the `under` colour, above hi the `over` colour, NaN the `bad` colour. Several panels
 * share a norm by sharing the struct.
 *
 * Misuse (status.h): IM_EINVAL for a NULL argument; im_colormap_index gives -2 (as for NaN) for a
 * NULL colormap, and im_colormap_rgb and im_colormap_field_image do nothing for a NULL argument or
 * an invalid field view (both record the message); im_colormap_range_norm gives NaN bounds (which
 * im_colormap_check refuses) for a NULL range or an unknown kind of values, recording the message.
 * Threads: every function is thread-safe (the tables are constant; nothing else is shared).
 */
#ifndef INDENTMAP_COLORMAP_H
#define INDENTMAP_COLORMAP_H

#include "indentmap/field.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum im_colormap_id {
    IM_COLORMAP_VIRIDIS = 0,
    IM_COLORMAP_CIVIDIS,
    IM_COLORMAP_MAGMA,
    IM_COLORMAP_INFERNO,
    IM_COLORMAP_GREY,
    IM_COLORMAP_TENSION, /* the blue ramp of patches under tension (render.h), light to dark as the
                            tension grows, ordered in CIELAB lightness; not chosen by name */
    IM_COLORMAP_COUNT
} im_colormap_id;

typedef struct im_colormap {
    im_colormap_id map;
    double lo, hi;   /* norm range; hi > lo */
    int logarithmic; /* 1: norm in log(value), requires lo > 0 */
    uint8_t under[3], over[3], bad[3];
} im_colormap;

/* A colour map with a linear norm on [lo, hi]; under and over take the end colours, bad grey. Checks
 * nothing (im_colormap_check does); an unknown map takes viridis's colours. */
im_colormap im_colormap_make(im_colormap_id map, double lo, double hi);

/* IM_EINVAL, listing the valid names, for an unknown name. */
int im_colormap_from_name(const char *name, im_colormap_id *map);
/* The name of a map ("viridis"), "unknown" for an id out of range; never NULL. */
const char *im_colormap_name(im_colormap_id map);

/* The 256 x 3 table of a map (static storage; viridis's for an id out of range); never NULL. */
const uint8_t (*im_colormap_table(im_colormap_id map))[3];

/* IM_EINVAL if the norm is unusable (hi <= lo, non-finite, log with lo <= 0). */
int im_colormap_check(const im_colormap *colormap);

/* Table index of a value: 0..255, or -1 under, 256 over, -2 NaN. */
int im_colormap_index(const im_colormap *colormap, double value);

/* The colour of a value (table entry, under, over or bad). */
void im_colormap_rgb(const im_colormap *colormap, double value, uint8_t rgb[3]);

/* CPU image of a field: one pixel per patch, RGB, stride 3 nx, image row 0 = field row ny - 1
 * (y up). The reference the GL renderer is tested against. */
void im_colormap_field_image(const im_colormap *colormap, const im_field *field, uint8_t *rgb);

/* ---- one norm over several fields ----
 * The default norm every front end gives a contact map, a height map, the frames of a history and the
 * panels of a figure: a range gathered field by field (so that frames need not be in memory at once),
 * then made a norm with the caller's bounds. The tension norm those maps share (render.h,
 * im_contact_style.tension) is the range of IM_COLORMAP_TENSIONS over their forces, made a norm of
 * IM_COLORMAP_TENSION; a figure draws the tension's colour bar only where that range's hi is > 0. */
typedef enum im_colormap_values {
    IM_COLORMAP_FORCES,  /* contact maps: 0 .. the largest finite force > 0; [0, 1] when no force is > 0 */
    IM_COLORMAP_HEIGHTS, /* every finite value, smallest .. largest; [v - 1, v + 1] when all are one value v
                            ([-1, 1] when none is finite) */
    IM_COLORMAP_TENSIONS /* force fields' patches under tension: 0 .. the largest finite tension -f of a
                            force f < 0; [0, 1] when no force is < 0 */
} im_colormap_values;

typedef struct im_colormap_range {
    im_colormap_values values;
    double lo, hi; /* the smallest and largest finite value gathered (forces: of those > 0; tensions: the
                      tensions -f > 0); lo = +Inf and hi = -Inf while there is none */
} im_colormap_range;

/* A range of the given kind with no value gathered yet. */
im_colormap_range im_colormap_range_empty(im_colormap_values values);

/* Widens range to the field's finite values (forces: those > 0; tensions: -f of those < 0). IM_EINVAL
 * (range unchanged) for a NULL argument or an invalid field view. */
int im_colormap_range_add(im_colormap_range *range, const im_field *field);

/* The range of the fields' values of the given kind (those im_colormap_range_add gathers) with `percent`
 * percent of them cut at each end, for a picture that a few outliers (a scan's spikes, its row of dropouts,
 * a needle asperity's force) would make one colour: lo the `percent` percentile, hi the 100 - `percent`
 * percentile (forces, tensions: their norm takes hi only, starting at 0 or two decades below it). Exact:
 * numpy.percentile's default method (the order statistics at ranks floor(r) and floor(r) + 1 of the n values,
 * interpolated linearly, r = percent / 100 (n - 1)), by selection in a copy of the values (8 bytes each,
 * freed before returning); percent 0 gives im_colormap_range_add's smallest .. largest, an empty range
 * when no value is gathered. IM_EINVAL (range unchanged) for a NULL range, NULL fields with count > 0,
 * count < 0, percent outside [0, 50), an unknown kind or an invalid field view; IM_ENOMEM. */
int im_colormap_range_clipped(im_colormap_values values, im_field *const *fields, int count, double percent,
                              im_colormap_range *range);

/* A picture of heights is dominated by outliers where the central 100 - 2 IM_COLORMAP_OUTLIER_PERCENT % of the
 * fields' finite values span less than 1 / IM_COLORMAP_OUTLIER_SHARE of their smallest .. largest (the default
 * linear range): the bulk then takes at most 13 of the 256 colours (findings S9: a scan's spikes and dropouts
 * leave its relief one colour). Where it is, the sentence every front end says, "a few outliers set the colour
 * range: the central 98% of the values span B U of its F U, N of the 256 colours" (U: fields[0]'s value unit,
 * else its unit), into text, and into *farthest the index of the field whose values reach farthest beyond the
 * central range (to name it); "" and -1 where it is not. The front end adds its remedy: cutting
 * IM_COLORMAP_OUTLIER_PERCENT % at each end (render --clip, Python's clip=). IM_EINVAL as
 * im_colormap_range_clipped's, for a NULL text or farthest, or size 0; IM_ENOMEM. */
#define IM_COLORMAP_OUTLIER_PERCENT 1.0
#define IM_COLORMAP_OUTLIER_SHARE 20.0
int im_colormap_outlier_note(im_field *const *fields, int count, char *text, size_t size, int *farthest);

/* The norm of map over the range (the defaults of im_colormap_values where it is empty or one value),
 * with the caller's bounds put in: vmin and vmax (NaN: not given) replace its lo and hi; a logarithmic
 * norm without vmin starts two decades below its top (lo = 0.01 hi) where the top is > 0. Checks
 * nothing more (im_colormap_check does: a vmin >= vmax stays the caller's to be refused). */
im_colormap im_colormap_range_norm(const im_colormap_range *range, im_colormap_id map, double vmin, double vmax,
                                   int logarithmic);

#ifdef __cplusplus
}
#endif

#endif
