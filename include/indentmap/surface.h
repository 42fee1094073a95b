/* indentmap/surface.h: self-affine rough surfaces: spectral synthesis and statistics.
 *
 * Entry points:
 *   im_surface_params_default, im_surface_generate    a surface from its spectrum's parameters
 *   im_surface_statistics, im_surface_slope_rms       heights' and slopes' moments
 *   im_surface_psd, im_psd_fit_exponent               the isotropic spectrum and its power law
 *   im_surface_histogram                              distributions of height, slope, curvature
 *   im_surface_generator_record, _parse               a generated surface's record (its sidecar's)
 *   im_surface_detrend, im_surface_align_rows, im_surface_fill_missing, im_surface_crop,
 *   im_surface_resample_square, im_surface_tapered    preparing a measured surface
 *
 * Synthesis (the paper's section 2.2): an isotropic Gaussian surface on an nx x ny grid of spacing
 * delta whose power spectral density is
 *     C(q) = C0 |q|^(-2(1+H))   for q_r <= |q| <= q_s,
 *     C(q) = C0 q_r^(-2(1+H))   for q_0 <= |q| <  q_r   (roll-off plateau, only when lambda_0 > lambda_r),
 *     C(q) = 0                  elsewhere,
 * with q = 2 pi / lambda. Each discrete Fourier mode carries C averaged over its cell of the
 * reciprocal lattice (see psd_cell_average in src/surface/synthesis.c for why), and gets a complex Gaussian amplitude (Gaussian modulus
 * spread and uniform phase) drawn from a counter-based generator keyed by (seed, kx, ky), where
 * (kx, ky) are the mode's integer wave numbers on the periodic box. So the surface does not depend
 * on the thread count, and a surface refined on a finer grid of the same box keeps every mode it
 * had (spectral interpolation). The mean is zero. C0 is then fixed by the target: h'rms or h_rms.
 *
 * Slope definition: h'rms = sqrt(<|grad h|^2>) over both components, as in the paper. The
 * "spectral" value is that of the band-limited trigonometric interpolant, sqrt(sum q^2 |h_q|^2);
 * the "finite-difference" value uses forward differences between neighbouring patches,
 * (h[i+1] - h[i]) / delta, over all interior pairs (no wrap-around). Synthesis scales to the
 * spectral value unless told otherwise.
 *
 * Misuse (status.h): IM_EINVAL for NULL parameters or outputs and invalid field views; the value
 * functions of NULL parameters give NaN, and so does im_surface_generate_bytes for a side outside
 * [1, IM_FIELD_MAX_SIDE]; im_psd_free and im_histogram_free accept NULL.
 * Threads: thread-safe on distinct outputs (a surface changed in place is one thread's). The
 * transforms plan under the library's FFTW lock (solver.h) and run on the OpenMP thread count in
 * force; a generated surface does not depend on it.
 */
#ifndef INDENTMAP_SURFACE_H
#define INDENTMAP_SURFACE_H

#include "indentmap/field.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

enum im_slope_definition { IM_SLOPE_SPECTRAL = 0, IM_SLOPE_FINITE_DIFFERENCE = 1 };
enum im_surface_target { IM_TARGET_SLOPE = 0, IM_TARGET_HEIGHT = 1 };

typedef struct im_surface_params {
    int nx, ny;                    /* grid size (the paper: 512 x 512) */
    double delta;                  /* patch side (1: lengths in delta) */
    double hurst;                  /* Hurst exponent H in (0, 1) (the paper: 0.8) */
    double lambda_s;               /* short-wavelength cutoff 2 pi / q_s, in units of delta (paper: 4) */
    double lambda_r;               /* roll-off wavelength 2 pi / q_r, in units of delta (paper: 512) */
    double lambda_0;               /* longest wavelength 2 pi / q_0; <= lambda_r (default 0) means no plateau,
                              whatever lambda_r is set to */
    enum im_surface_target target; /* which of the two below is imposed */
    double slope_rms;              /* target h'rms (dimensionless) */
    double height_rms;             /* target h_rms, in units of delta */
    enum im_slope_definition slope_definition; /* how the target h'rms is measured */
    uint64_t seed;
} im_surface_params;

/* The paper's defaults: 512 x 512, delta = 1, H = 0.8, lambda_s = 4, lambda_r = 512, no
 * roll-off (lambda_0 = 0), target h'rms = 0.08 (spectral), seed 1. */
im_surface_params im_surface_params_default(void);

/* IM_EINVAL naming the first parameter out of range, IM_OK otherwise. */
int im_surface_params_check(const im_surface_params *params);

/* Generates a surface. Uses FFTW with the OpenMP threads in force; the result is bit-identical
 * for any thread count. *out is owned by the caller (im_field_free). */
int im_surface_generate(const im_surface_params *params, im_field **out);

/* Memory, in bytes, that im_surface_generate needs at its peak for this size. */
double im_surface_generate_bytes(int nx, int ny);

/* Slope of a surface by either definition (see the top of this header). IM_EINVAL for another
 * definition. */
int im_surface_slope_rms(const im_field *surface, enum im_slope_definition definition, double *slope_rms);

/* Summary statistics of a surface. Moments m_n are those of a profile along x and y (averaged),
 * computed spectrally, so that h'rms^2 = 2 m2 for an isotropic surface. */
typedef struct im_surface_stats {
    double mean;       /* mean height */
    double height_rms; /* sqrt(<(h - mean)^2>) */
    double slope_rms_spectral;
    double slope_rms_fd;  /* forward differences, see above */
    double curvature_rms; /* rms of the mean curvature (h_xx + h_yy) / 2, spectral */
    double m0, m2, m4;    /* spectral moments of profiles: m2 = <h_x^2>, m4 = <h_xx^2> */
    double nayak;         /* Nayak's parameter m0 m4 / m2^2 */
    double height_min, height_max;
} im_surface_stats;

/* Refuses (IM_EINVAL, naming the first) heights with |h| > 1e100, whose squares would overflow. */
int im_surface_statistics(const im_field *surface, im_surface_stats *stats);

/* IM_OK when every height has |h| <= 1e100 (the bound im_surface_statistics and the readers keep, far
 * below the ~1e154 where squares overflow); else IM_EINVAL naming `what` (NULL: "surface"), the first
 * such point and its value. */
int im_surface_check_height_range(const im_field *surface, const char *what);

/* Radially averaged power spectral density C_iso(q) as in Jacobs, Junge and Pastewka (2017):
 * C(q) = |h~(q)|^2 / A with h~ the discrete Fourier transform scaled by delta^2 and A = L_x L_y,
 * averaged over the modes in each of `bins` logarithmically spaced shells between the smallest
 * non-zero |q| and the largest |q| on the grid. q and the average C are written for each bin;
 * counts[i] is the number of modes in bin i (0 for an empty bin, whose q and C are NaN).
 * im_surface_psd: a new *out (im_psd_free); IM_EINVAL for bins outside [1, 100000], IM_ENOMEM. */
typedef struct im_psd {
    int bins;
    double *q, *c;
    long *counts;
} im_psd;

int im_surface_psd(const im_field *surface, int bins, im_psd **out);
void im_psd_free(im_psd *psd);

/* Least-squares slope of log C against log q over the non-empty bins with q_min <= q <= q_max;
 * for a self-affine surface it is -2(1 + H). IM_EINVAL if fewer than two bins qualify. */
int im_psd_fit_exponent(const im_psd *psd, double q_min, double q_max, double *exponent);

/* Histogram of values in `bins` equal bins over [lo, hi]; values outside are counted in the
 * first or last bin. density[i] is normalised so that sum(density) * width = 1. */
typedef struct im_histogram {
    int bins;
    double lo, hi;
    double *centre, *density;
} im_histogram;

enum im_histogram_quantity {
    IM_HIST_HEIGHT,   /* h - mean */
    IM_HIST_SLOPE,    /* both forward-difference slope components, pooled */
    IM_HIST_CURVATURE /* five-point mean curvature (h_xx + h_yy) / 2 at interior points */
};

/* Histogram of a quantity over [mean - 5 sd, mean + 5 sd] of that quantity: a new *out
 * (im_histogram_free). IM_EINVAL for bins outside [1, 1000000] or an unknown quantity, IM_ENOMEM. */
int im_surface_histogram(const im_field *surface, enum im_histogram_quantity quantity, int bins, im_histogram **out);
void im_histogram_free(im_histogram *histogram);

/* JSON sidecar of a surface file, written atomically beside it: the generation parameters and seed
 * (params may be NULL for a surface read from a file, then source names that file), the program
 * version, the grid, and its statistics with the eq. (15) estimate of h_rms where it applies. */
int im_surface_sidecar_write(const char *path, const im_field *surface, const im_surface_params *params,
                             const char *source, const im_surface_stats *stats);

/* The record of a generated surface that its sidecar holds as "generator" (im_surface_sidecar_write
 * writes it; `indent` and scenes read it: a file whose sidecar names a generator is a generated, periodic
 * surface, docs/theory.md): the parameters under the keys nx, ny, delta, hurst, lambda_s, lambda_r,
 * lambda_0 (the longest wavelength in effect: lambda_r when there is no plateau), target ("slope_rms"
 * or "height_rms"), slope_rms, height_rms, slope_definition ("spectral" or "finite-difference") and seed
 * (a signed 64-bit integer: a seed of 2^63 or more is its two's complement). */

/* The record of params as compact JSON text in a new *text (free()). IM_EINVAL naming the first parameter
 * out of range (im_surface_params_check) or a NULL argument, IM_ENOMEM. */
int im_surface_generator_record(const im_surface_params *params, char **text);

/* The parameters of a record (JSON text, as im_surface_generator_record or a sidecar has it): every key
 * present, of its type, no other key, and in range; else IM_EINVAL "generator: ..." naming the first
 * key that is not (params untouched). */
int im_surface_generator_parse(const char *text, im_surface_params *params);

/* Expected h_rms of a generated surface, in the units of its heights: from the exact moments of
 * eq. (13) (which the cell-averaged discrete spectrum reproduces) or from the paper's eq. (15). */
double im_surface_expected_height_rms(const im_surface_params *params, double slope_rms);
double im_surface_height_rms_eq15(const im_surface_params *params, double slope_rms);

/* ---- preparation of measured surfaces ----
 * Synthesised surfaces are periodic and exact; measured ones are not: they are tilted and bowed by
 * the instrument, have missing points, and end abruptly at the scan's edges, where the periodic
 * box of a Fourier transform sees a step. The spectral h'rms of such a crop is dominated by that
 * step (a 256^2 crop of a periodic surface of h'rms 0.08: 0.30 spectral, 0.079 by differences; with
 * a tilt of 0.05: 1.06). Hence plane and curvature removal, and a window for spectral estimates. */

/* Cuts the nx x ny block at (x0, y0) (nx, ny >= 2) into *out (caller frees); IM_EINVAL naming the
 * crop and the grid when it does not fit. */
int im_surface_crop(const im_field *surface, int x0, int y0, int nx, int ny, im_field **out);

/* Fills missing points (NaN) in place by repeated passes, each giving every missing point that has
 * a known 4-neighbour the mean of its known 4-neighbours (points filled in a pass do not feed each
 * other in that pass): a hole is filled from its rim inwards, a smooth continuation of its edges.
 * *filled counts the points filled. IM_ENUMERIC for Inf, or when every point is missing. */
int im_surface_fill_missing(im_field *surface, long *filled);

/* Resamples a field whose pixels are delta_x wide along x and delta_y along y onto square pixels of
 * the finer of the two spacings, by bilinear interpolation, into *out (caller frees; unit and
 * value_unit kept, field->delta ignored). The new nodes are j * min(delta_x, delta_y) from the first
 * point along each axis, as many as lie within the old grid's extent ((nx - 1) delta_x by (ny - 1)
 * delta_y): nothing is extrapolated, the finer axis keeps its points, and the coarser one gets
 * floor((n - 1) ratio) + 1 nodes for the ratio of the spacings. A node takes the values of the old
 * points around it that have a weight in its blend, so a missing point (NaN) makes NaN every node it
 * touches and no other (as does Inf, or +Inf beside -Inf). Planes and bilinear functions are
 * reproduced to rounding; a smooth field is off by at most (h^2 / 8) max |d^2 z / dy^2| for the
 * coarser spacing h (here y). IM_EINVAL for a spacing that is not finite > 0, or a new side beyond
 * IM_FIELD_MAX_SIDE (the message names the grid and the spacings); IM_ENOMEM as im_field_create. */
int im_surface_resample_square(const im_field *field, double delta_x, double delta_y, im_field **out);

enum im_detrend {
    IM_DETREND_NONE = 0,
    IM_DETREND_PLANE = 1,    /* least-squares plane a + b x + c y (mean and tilt) */
    IM_DETREND_CURVATURE = 2 /* least-squares quadric: the plane and x^2, xy, y^2 (bow) */
};

/* Subtracts the least-squares polynomial in place. IM_ENUMERIC for a non-finite height; IM_EINVAL for one
 * beyond im_surface_check_height_range's bound, named as given (before the fit spreads it). */
int im_surface_detrend(im_field *surface, enum im_detrend detrend);

/* Scan-line alignment of an AFM image (rows are the scan lines, along x): each row's offset (its median
 * or mean) or its least-squares line is removed and the mean of the rows' levels kept, as Gwyddion's
 * Align Rows does; the streaks a drifting feedback leaves are gone. A surface that varies only along x
 * plus a constant per row comes back exactly as one row repeated (median, mean). In place; IM_EINVAL for
 * an unknown method, IM_ENUMERIC for a non-finite height (fill missing points first), IM_EINVAL for one beyond
 * im_surface_check_height_range's bound. */
enum im_row_alignment { IM_ALIGN_NONE = 0, IM_ALIGN_MEDIAN = 1, IM_ALIGN_MEAN = 2, IM_ALIGN_LINE = 3 };
int im_surface_align_rows(im_field *surface, enum im_row_alignment how);

enum im_taper_kind { IM_TAPER_NONE = 0, IM_TAPER_HANN = 1, IM_TAPER_TUKEY = 2 };
typedef struct im_taper {
    enum im_taper_kind kind;
    double alpha; /* Tukey: the tapered fraction of the length, alpha / 2 at each end, in
                                 [0, 1] (1 is Hann, 0 no taper) */
} im_taper;

/* For spectral estimates of non-periodic data: *out = w (h - mean h) / sqrt(<w^2>) with w the
 * product of the 1-D window along x and along y, so that the mean power of the data is kept and the
 * window and its slope vanish at the edges (no step in the periodic box). The surface itself is
 * never windowed for solving. IM_EINVAL for a Tukey alpha outside [0, 1]. */
int im_surface_tapered(const im_field *surface, const im_taper *window, im_field **out);

/* im_surface_statistics with the spectral quantities (h'rms spectral, curvature, m0, m2, m4,
 * Nayak) taken from the windowed surface; the others (mean, h_rms, h'rms fd, range) from the
 * surface itself. A window of kind IM_TAPER_NONE gives im_surface_statistics. */
int im_surface_statistics_tapered(const im_field *surface, const im_taper *window, im_surface_stats *stats);

#ifdef __cplusplus
}
#endif

#endif
