/* User-given punch profiles (indenter.h, "User-given profiles"): an axisymmetric table interpolated
 * by Steffen's monotone cubic with Sneddon's smooth-contact integrals tabulated, or a 2-D height
 * field read bilinearly around the axis. */
#include "indenter/profile.h"
#include "core/args.h"

#include "indentmap/status.h"
#include "core/gsl_handler.h"

#include <gsl/gsl_interp.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Sneddon's table: contact radii from r_max * SMALLEST_RADIUS to r_max, geometric. */
#define TABLE_SIZE 1024
#define SMALLEST_RADIUS 1e-9
#define QUADRATURE_POINTS 512

struct im_profile {
    enum im_punch_kind kind;
    /* axisymmetric */
    int count;
    double *r, *z;
    gsl_interp *interp;
    double r_max;
    double radius[TABLE_SIZE + 1], approach[TABLE_SIZE + 1], load[TABLE_SIZE + 1]; /* load per unit E* */
    /* 2-D */
    im_field *field;
};

enum im_punch_kind im_profile_kind(const im_profile *profile)
{
    ARG_REQUIRE_OR(profile, "profile", (enum im_punch_kind) - 1);
    return profile->kind;
}

void im_profile_free(im_profile *profile)
{
    if (!profile)
        return;
    if (profile->interp)
        gsl_interp_free(profile->interp);
    free(profile->r);
    free(profile->z);
    im_field_free(profile->field);
    free(profile);
}

static int check_samples(const double *r, const double *z, int n)
{
    if (!r || !z)
        return im_fail(IM_EINVAL, "profile: NULL sample array");
    if (n < 3)
        return im_fail(IM_EINVAL, "profile: %d samples: expected at least 3 (r, z) samples", n);
    for (int i = 0; i < n; ++i) {
        if (!isfinite(r[i]) || !isfinite(z[i]))
            return im_fail(IM_EINVAL, "profile sample %d (r = %g, z = %g): expected finite values", i, r[i], z[i]);
        if (i == 0 && (r[0] != 0.0 || z[0] != 0.0))
            return im_fail(IM_EINVAL,
                           "profile sample 0 (r = %g, z = %g): expected r = 0 and z = 0 (the apex, on "
                           "the axis; heights are counted above it)",
                           r[0], z[0]);
        if (i > 0 && !(r[i] > r[i - 1]))
            return im_fail(IM_EINVAL,
                           "profile sample %d: r = %g after r = %g: expected r strictly increasing "
                           "(and r >= 0)",
                           i, r[i], r[i - 1]);
        if (i > 0 && z[i] < z[i - 1])
            return im_fail(IM_EINVAL,
                           "profile sample %d: z = %g after z = %g: expected z non-decreasing (a "
                           "monotone profile, the apex its lowest point)",
                           i, z[i], z[i - 1]);
    }
    return IM_OK;
}

static double slope_at(const im_profile *p, double r)
{
    return gsl_interp_eval_deriv(p->interp, p->r, p->z, r, NULL);
}

/* Sneddon's w(a) and N(a) / E* by the midpoint rule in t (r = a sin t). */
static void sneddon(const im_profile *p, double a, double *approach, double *load)
{
    double w = 0.0, n = 0.0;
    for (int k = 0; k < QUADRATURE_POINTS; ++k) {
        double t = (k + 0.5) * (M_PI / 2) / QUADRATURE_POINTS, s = sin(t);
        double slope = slope_at(p, fmin(a * s, p->r_max));
        w += slope;
        n += s * s * slope;
    }
    const double dt = (M_PI / 2) / QUADRATURE_POINTS;
    *approach = a * w * dt;
    *load = 2.0 * a * a * n * dt;
}

/* The table, made non-decreasing in a (see indenter.h: exact where the contact grows continuously). */
static void tabulate(im_profile *p)
{
    p->radius[0] = p->approach[0] = p->load[0] = 0.0;
    for (int k = 1; k <= TABLE_SIZE; ++k) {
        p->radius[k] = k == TABLE_SIZE ? p->r_max
                                       : p->r_max * pow(SMALLEST_RADIUS, (double)(TABLE_SIZE - k) / (TABLE_SIZE - 1));
        sneddon(p, p->radius[k], &p->approach[k], &p->load[k]);
        p->approach[k] = fmax(p->approach[k], p->approach[k - 1]);
        p->load[k] = fmax(p->load[k], p->load[k - 1]);
    }
}

int im_profile_axisymmetric(const double *r, const double *z, int n, im_profile **out)
{
    ARG_REQUIRE(r, "r");
    ARG_REQUIRE(z, "z");
    ARG_REQUIRE(out, "out");
    *out = NULL;
    int status = check_samples(r, z, n);
    if (status != IM_OK)
        return status;
    im_profile *p = calloc(1, sizeof *p);
    if (p) {
        p->r = malloc(sizeof(double) * (size_t)n);
        p->z = malloc(sizeof(double) * (size_t)n);
        core_gsl_handler_off(); /* a failed allocation is IM_ENOMEM, not GSL's abort */
        p->interp = gsl_interp_alloc(gsl_interp_steffen, (size_t)n);
        core_gsl_handler_restore();
    }
    if (!p || !p->r || !p->z || !p->interp) {
        im_profile_free(p);
        return im_fail(IM_ENOMEM, "profile of %d samples", n);
    }
    p->kind = IM_PUNCH_PROFILE;
    p->count = n;
    memcpy(p->r, r, sizeof(double) * (size_t)n);
    memcpy(p->z, z, sizeof(double) * (size_t)n);
    p->r_max = r[n - 1];
    gsl_interp_init(p->interp, p->r, p->z, (size_t)n); /* cannot fail: the samples were checked */
    tabulate(p);
    *out = p;
    return IM_OK;
}

int im_profile_field(const im_field *heights, im_profile **out)
{
    ARG_VIEW(heights, "heights");
    ARG_REQUIRE(out, "out");
    *out = NULL;
    if (!heights)
        return im_fail(IM_EINVAL, "2-D profile: NULL height field");
    if (heights->nx < 3 || heights->ny < 3)
        return im_fail(IM_EINVAL,
                       "2-D profile of %d x %d samples: expected at least 3 x 3 (the apex and its "
                       "neighbours; an (n, 2) array is an axisymmetric (r, z) table)",
                       heights->nx, heights->ny);
    if (!(isfinite(heights->delta) && heights->delta > 0))
        return im_fail(IM_EINVAL, "2-D profile delta = %g: expected > 0", heights->delta);
    for (int iy = 0; iy < heights->ny; ++iy)
        for (int ix = 0; ix < heights->nx; ++ix) {
            double z = heights->data[(size_t)iy * heights->nx + ix];
            if (!isfinite(z))
                return im_fail(IM_EINVAL, "2-D profile sample (%d, %d) = %g: expected finite heights", ix, iy, z);
        }
    im_profile *p = calloc(1, sizeof *p);
    if (!p)
        return im_fail(IM_ENOMEM, "2-D profile");
    int status = im_field_clone(heights, &p->field);
    if (status != IM_OK) {
        free(p);
        return status;
    }
    p->kind = IM_PUNCH_PROFILE_2D;
    *out = p;
    return IM_OK;
}

double im_profile_extent(const im_profile *p)
{
    ARG_REQUIRE_OR(p, "profile", NAN);
    if (p->kind == IM_PUNCH_PROFILE)
        return p->r_max;
    const im_field *f = p->field;
    double cx = f->nx / 2, cy = f->ny / 2;
    return f->delta * hypot(fmax(cx, f->nx - 1 - cx), fmax(cy, f->ny - 1 - cy));
}

void im_profile_samples(const im_profile *p, const double **r, const double **z, int *count, const im_field **field)
{
    ARG_REQUIRE_OR(r, "r", );
    ARG_REQUIRE_OR(z, "z", );
    ARG_REQUIRE_OR(count, "count", );
    ARG_REQUIRE_OR(field, "field", );
    *r = *z = NULL; /* for a NULL profile */
    *count = 0;
    *field = NULL;
    ARG_REQUIRE_OR(p, "profile", );
    *r = p->r;
    *z = p->z;
    *count = p->kind == IM_PUNCH_PROFILE ? p->count : 0;
    *field = p->field;
}

double profile_axisymmetric_height(const im_profile *p, double r)
{
    r = fabs(r); /* a distance; and GSL's evaluation outside [0, r_max] would call its error handler */
    if (isnan(r))
        return NAN;
    if (r > p->r_max)
        return INFINITY;
    return gsl_interp_eval(p->interp, p->r, p->z, r, NULL);
}

/* Bilinear between the sample centres; the centre patch (nx / 2, ny / 2) on the axis. */
double profile_field_height(const im_profile *p, double dx, double dy)
{
    const im_field *f = p->field;
    double u = dx / f->delta + f->nx / 2, v = dy / f->delta + f->ny / 2;
    if (!(u >= 0 && v >= 0 && u <= f->nx - 1 && v <= f->ny - 1))
        return INFINITY;
    int ix = (int)u, iy = (int)v; /* at least 3 x 3 samples: ix + 1, iy + 1 exist after the clamps */
    ix = ix > f->nx - 2 ? f->nx - 2 : ix;
    iy = iy > f->ny - 2 ? f->ny - 2 : iy;
    double fu = u - ix, fv = v - iy;
    const double *row = f->data + (size_t)iy * f->nx, *next = row + f->nx;
    /* an exact grid point (fu = fv = 0) reads its sample exactly: the zero-weight terms vanish */
    double low = fu == 0.0 ? row[ix] : (1 - fu) * row[ix] + fu * row[ix + 1];
    double high = fu == 0.0 ? next[ix] : (1 - fu) * next[ix] + fu * next[ix + 1];
    return fv == 0.0 ? low : (1 - fv) * low + fv * high;
}

/* y at x in the non-decreasing table xs -> ys: log-log between positive neighbours (exact for
 * power laws), linear otherwise; the last entry for x beyond the table. */
static double table_lookup(const double *xs, const double *ys, double x)
{
    if (x >= xs[TABLE_SIZE])
        return ys[TABLE_SIZE];
    int lo = 0, hi = TABLE_SIZE; /* xs[lo] <= x < xs[hi] */
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (xs[mid] <= x)
            lo = mid;
        else
            hi = mid;
    }
    if (xs[lo] == xs[hi])
        return ys[lo];
    if (xs[lo] > 0 && ys[lo] > 0 && ys[hi] > 0 && x > 0)
        return ys[lo] * exp(log(ys[hi] / ys[lo]) * log(x / xs[lo]) / log(xs[hi] / xs[lo]));
    return ys[lo] + (ys[hi] - ys[lo]) * (x - xs[lo]) / (xs[hi] - xs[lo]);
}

double profile_contact_radius(const im_profile *p, double w)
{
    return w >= p->approach[TABLE_SIZE] ? p->r_max : table_lookup(p->approach, p->radius, w);
}

double profile_load(const im_profile *p, double e_star, double w)
{
    const double full = p->approach[TABLE_SIZE];
    if (w >= full) /* the whole face touches: a flat punch of radius r_max from here */
        return e_star * p->load[TABLE_SIZE] + 2.0 * p->r_max * e_star * (w - full);
    return e_star * table_lookup(p->approach, p->load, w);
}

double profile_approach_for_load(const im_profile *p, double e_star, double n)
{
    const double full = e_star * p->load[TABLE_SIZE];
    if (n >= full)
        return p->approach[TABLE_SIZE] + (n - full) / (2.0 * p->r_max * e_star);
    return table_lookup(p->load, p->approach, n / e_star);
}

double profile_radius_for_load(const im_profile *p, double e_star, double n)
{
    return n >= e_star * p->load[TABLE_SIZE] ? p->r_max : table_lookup(p->load, p->radius, n / e_star);
}
