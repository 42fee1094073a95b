/* indentmap/indenter.h: rigid axisymmetric punches and their smooth-contact closed forms.
 *
 * Entry points:
 *   im_indenter_cone, im_indenter_sphere, im_indenter_flat, im_indenter_from_profile   a punch
 *   im_punch_parse, im_punch_name, im_indenter_check    punches by name, and checked
 *   im_indenter_height, im_indenter_profile, im_indenter_axis   its face over the grid
 *   im_indenter_load, im_indenter_contact_radius, im_indenter_pressure,
 *   im_indenter_approach_for_load, im_indenter_area_for_load    the smooth contact's closed forms
 *   im_profile_read, im_profile_axisymmetric, im_profile_field, im_profile_free   user-given profiles
 *
 * A punch is a rigid body of revolution whose axis is vertical and passes through the point
 * (x0, y0) of the surface plane. Its profile z(r) is the height of the punch face above its
 * lowest point at distance r from the axis (so z(0) = 0 and z >= 0):
 *     cone, semi-opening angle alpha:  z = r cot(alpha)
 *     sphere of radius R:              z = r^2 / (2 R)   (Hertz's paraboloid; exact for a << R)
 *     flat circular punch, radius a:   z = 0 for r <= a, +infinity outside (the punch's side is
 *                                      vertical, so no patch beyond r = a can touch it)
 *     profile (axisymmetric):          z(r) interpolated in a table of samples (r_i, z_i), +infinity
 *                                      beyond the last r (a vertical side, as the flat punch's)
 *     profile-2d:                      a height field z(x, y) around the axis (not axisymmetric),
 *                                      +infinity outside the field
 * (the two profile kinds: see "User-given profiles" below).
 * Lengths are in the units of the grid spacing delta (1 when dimensionless); E* is the composite
 * modulus E / (1 - nu^2) of the half-space (the punch is rigid).
 *
 * Closed forms (frictionless contact with a smooth elastic half-space, approach w > 0 counted from
 * first touch; Johnson, Contact Mechanics, ch. 5):
 *     cone (Love 1939):   a = 2 w / (pi cot alpha),   N = 2 E* w^2 / (pi cot alpha),
 *                         p(r) = (E* cot alpha / 2) acosh(a / r),  mean pressure E* cot alpha / 2
 *     sphere (Hertz):     a = sqrt(R w),   N = (4/3) E* sqrt(R) w^(3/2),
 *                         p(r) = p0 sqrt(1 - r^2/a^2) with p0 = 2 E* a / (pi R)
 *     flat (Boussinesq):  N = 2 a E* w,   p(r) = N / (2 pi a sqrt(a^2 - r^2))
 * The contact area as a function of load, A(N), gives the normalisations used by the solver's
 * histories: area_ratio = n_p delta^2 / A(N) and N* = A(N) / delta^2 (= 2N / (delta^2 E* cot alpha)
 * for the cone, the paper's N*), so that a smooth surface has area_ratio ~ 1 and N* ~ n_p.
 *
 * Misuse (status.h): IM_EINVAL for a NULL argument or an invalid field view; the value functions
 * of a NULL punch or profile give NaN (im_profile_kind: -1), im_indenter_axis and
 * im_profile_samples set their outputs to NaN, or NULL and 0; im_profile_free accepts NULL. The
 * closed forms (im_indenter_load, _contact_radius, _pressure, _approach_for_load, _area_for_load) of
 * a punch im_indenter_check refuses, or with an E* not finite and positive, give NaN and record the
 * message ("im_indenter_load: alpha = 95: expected 0 < alpha < 90 degrees").
 * Threads: thread-safe: a punch is a value and a profile immutable once made (one profile may
 * serve several threads at once).
 */
#ifndef INDENTMAP_INDENTER_H
#define INDENTMAP_INDENTER_H

#include "indentmap/field.h"

#ifdef __cplusplus
extern "C" {
#endif

enum im_punch_kind {
    IM_PUNCH_CONE = 0,
    IM_PUNCH_SPHERE = 1,
    IM_PUNCH_FLAT = 2,
    IM_PUNCH_PROFILE = 3,   /* axisymmetric profile table (im_profile_axisymmetric) */
    IM_PUNCH_PROFILE_2D = 4 /* height field around the axis (im_profile_field) */
};

/* ---- User-given profiles ----
 * An im_profile holds a punch shape given as data; an im_indenter of kind IM_PUNCH_PROFILE or
 * IM_PUNCH_PROFILE_2D BORROWS it (the `profile` member): the profile must outlive every indenter,
 * indentation (solver.h) and scene run made with it, and is freed by im_profile_free only after
 * them. The profile's constructors COPY the caller's arrays (they may change or go afterwards).
 * A profile is immutable once made, so one profile may serve several threads and runs at once.
 *
 * Axisymmetric (im_profile_axisymmetric): n >= 3 samples (r_i, z_i), lengths in the units of the
 * surface's delta (the length unit the run is solved in). Required, else IM_EINVAL naming the
 * sample: all values finite; r_0 = 0 and z_0 = 0 (the apex on the axis, heights above it);
 * r strictly increasing; z non-decreasing (monotone: the apex is the lowest point, so the smooth
 * contact is a disc about the axis; a profile with a hollow tip, whose contact would be a ring,
 * is refused). Between samples z(r) is Steffen's monotone cubic (M. Steffen, Astron. Astrophys.
 * 239, 443 (1990), GSL's gsl_interp_steffen): it keeps the samples' monotonicity (no overshoot
 * below a sample, so no spurious dimple that linear interpolation would avoid but a plain spline
 * would make), reproduces a straight line exactly (a sampled cone is the cone between its
 * samples), has a continuous slope (which the smooth-contact integrals below use) and converges
 * faster than linear interpolation on curved profiles (a sphere). Beyond the last sample r_max
 * the profile is +infinity: the punch's side is vertical there, no patch beyond r_max can touch
 * it, and the solver's window and edge checks know the punch's extent r_max (as for the flat
 * punch).
 * Its smooth-contact forms are Sneddon's (Int. J. Eng. Sci. 3, 47 (1965)) for a contact disc of
 * radius a <= r_max:
 *     w(a) = a int_0^(pi/2) z'(a sin t) dt,   N(a) = 2 E* a^2 int_0^(pi/2) sin^2 t z'(a sin t) dt,
 * tabulated when the profile is made (1024 contact radii, geometric from r_max 1e-9 to r_max,
 * 512-point midpoint quadrature in t; interpolated log-log between them, which is exact for
 * power-law profiles such as the cone and the paraboloid) and made non-decreasing in a (exact for
 * every profile whose smooth contact grows continuously with w: every convex profile; for others
 * an estimate, used only for the window bound, the reachability check and the normalisations).
 * Once the whole face r <= r_max touches (w > w(r_max)) the punch presses on as a flat punch of
 * radius r_max: N = N(r_max) + 2 r_max E* (w - w(r_max)). im_indenter_pressure is NaN for it
 * (no closed form).
 *
 * 2-D (im_profile_field): an nx x ny height field z (field.h layout, at least 3 x 3 samples, so
 * that an (n, 2) array is never one; heights in the units of delta, all finite) on the SURFACE'S
 * grid spacing: im_indentation_create refuses a profile whose
 * delta differs from the surface's (no resampling). Its patch (nx / 2, ny / 2) (the centre patch,
 * as for a centred axis) lies on the punch's axis: the height at offset (dx, dy) from the axis is
 * interpolated bilinearly between the sample centres (so a centred axis on a surface of the same
 * spacing reads the samples themselves), +infinity outside the samples' span. The heights need not
 * start at 0 (the gap subtracts its minimum). Its smooth-contact forms (load, radius, area,
 * approach, pressure) are NaN: there is no closed form; the solver then takes the window as the
 * field's whole footprint and reports load_star and area_ratio as NaN. */
typedef struct im_profile im_profile;

typedef struct im_indenter {
    enum im_punch_kind kind;
    double alpha_degrees;      /* cone: semi-opening angle, 0 < alpha < 90 (the paper: 80) */
    double radius;             /* sphere: R; flat punch: a (> 0, same units as delta) */
    double x0, y0;             /* axis position in the surface plane (same units as delta) */
    const im_profile *profile; /* profile kinds: the shape, BORROWED (see above); NULL otherwise */
    int centred;               /* 1: ignore x0, y0 and put the axis on the centre of patch
                              (nx / 2, ny / 2), i.e. at ((nx/2 + 0.5) delta, (ny/2 + 0.5) delta) */
} im_indenter;

/* Patch (ix, iy) covers [ix delta, (ix + 1) delta) x [iy delta, (iy + 1) delta); its centre is
 * ((ix + 0.5) delta, (iy + 0.5) delta). */

/* A centred cone of semi-opening alpha_degrees (radius unused). */
im_indenter im_indenter_cone(double alpha_degrees);
im_indenter im_indenter_sphere(double radius);
im_indenter im_indenter_flat(double radius);
/* A centred punch of the profile's kind (IM_PUNCH_PROFILE or IM_PUNCH_PROFILE_2D) that borrows
 * profile (NULL gives a punch that im_indenter_check refuses). */
im_indenter im_indenter_from_profile(const im_profile *profile);

/* An axisymmetric profile from n samples r[i], z[i] (copied). IM_EINVAL naming the first
 * offending sample (index, value and what was expected: see "User-given profiles"), IM_ENOMEM. */
int im_profile_axisymmetric(const double *r, const double *z, int n, im_profile **out);
/* A 2-D profile from a height field (copied, with its delta). IM_EINVAL for fewer than 3 x 3
 * samples, a delta not finite and positive, or naming the first non-finite sample (ix, iy);
 * IM_ENOMEM. */
int im_profile_field(const im_field *heights, im_profile **out);
void im_profile_free(im_profile *profile);
/* IM_PUNCH_PROFILE or IM_PUNCH_PROFILE_2D. */
enum im_punch_kind im_profile_kind(const im_profile *profile);
/* The last sample's r (axisymmetric), or the distance from the axis to the farthest sample centre
 * (2-D): no part of the punch beyond it can touch. */
double im_profile_extent(const im_profile *profile);
/* The samples as given: axisymmetric, *count samples at r[i], z[i]; 2-D, *field (r, z NULL).
 * Pointers into the profile (valid while it lives). */
void im_profile_samples(const im_profile *profile, const double **r, const double **z, int *count,
                        const im_field **field);

/* Name of a kind: "cone", "sphere", "flat", "profile", "profile-2d". */
const char *im_punch_name(enum im_punch_kind kind);

/* The kind named by name: "cone", "sphere", "flat" or "profile" (any case), as `indent --punch` and a scene's
 * [punch] shape take it. IM_OK, or IM_EINVAL with "'NAME': expected cone, sphere, flat or profile" (the
 * front end puts the option or key before it); *kind is left as it was then. */
int im_punch_parse(const char *name, enum im_punch_kind *kind);

/* IM_EINVAL naming the parameter when alpha is outside (0, 90) degrees (cone), a radius is not
 * finite and positive (sphere, flat), a profile kind has no profile or one of the other kind, or
 * the position is not finite. */
int im_indenter_check(const im_indenter *punch);

/* Profile z(r) >= 0 above the punch's lowest point (see above); +INFINITY outside a flat punch or
 * beyond an axisymmetric profile's last sample; NaN for a 2-D profile (use im_indenter_height). */
double im_indenter_profile(const im_indenter *punch, double r);
/* Height of the punch face at offset (dx, dy) from the axis: im_indenter_profile(hypot(dx, dy))
 * for the axisymmetric kinds; the 2-D profile's bilinear interpolation (+INFINITY outside it). */
double im_indenter_height(const im_indenter *punch, double dx, double dy);

/* The axis position for an nx x ny grid of spacing delta (resolves `centred`). */
void im_indenter_axis(const im_indenter *punch, int nx, int ny, double delta, double *x, double *y);

/* Smooth-contact closed forms for an approach w >= 0 (0 for w <= 0), modulus e_star; for the
 * profile kinds see "User-given profiles" (Sneddon's integrals; NaN for a 2-D profile). */
double im_indenter_load(const im_indenter *punch, double e_star, double w); /* N(w) */
double im_indenter_contact_radius(const im_indenter *punch, double w);      /* a(w) */
/* Pressure at distance r from the axis at approach w (0 outside the contact; +INFINITY at the
 * cone's apex and the flat punch's edge). */
double im_indenter_pressure(const im_indenter *punch, double e_star, double w, double r);
/* Approach that carries load n (inverse of im_indenter_load). */
double im_indenter_approach_for_load(const im_indenter *punch, double e_star, double n);
/* Contact area at load n: A_cone = 2N / (E* cot alpha), pi a^2 for Hertz and the flat punch. */
double im_indenter_area_for_load(const im_indenter *punch, double e_star, double n);

#ifdef __cplusplus
}
#endif

#endif
