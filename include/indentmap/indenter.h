/* indentmap/indenter.h: rigid axisymmetric punches and their smooth-contact closed forms.
 *
 * A punch is a rigid body of revolution whose axis is vertical and passes through the point
 * (x0, y0) of the surface plane. Its profile z(r) is the height of the punch face above its
 * lowest point at distance r from the axis (so z(0) = 0 and z >= 0):
 *     cone, semi-opening angle alpha:  z = r cot(alpha)
 *     sphere of radius R:              z = r^2 / (2 R)   (Hertz's paraboloid; exact for a << R)
 *     flat circular punch, radius a:   z = 0 for r <= a, +infinity outside (the punch's side is
 *                                      vertical, so no patch beyond r = a can touch it)
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
 */
#ifndef INDENTMAP_INDENTER_H
#define INDENTMAP_INDENTER_H

#ifdef __cplusplus
extern "C" {
#endif

enum im_punch_kind { IM_PUNCH_CONE = 0, IM_PUNCH_SPHERE = 1, IM_PUNCH_FLAT = 2 };

typedef struct im_indenter {
    enum im_punch_kind kind;
    double alpha_degrees;  /* cone: semi-opening angle, 0 < alpha < 90 (the paper: 80) */
    double radius;         /* sphere: R; flat punch: a (> 0, same units as delta) */
    double x0, y0;         /* axis position in the surface plane (same units as delta) */
    int centred;           /* 1: ignore x0, y0 and put the axis on the centre of patch
                              (nx / 2, ny / 2), i.e. at ((nx/2 + 0.5) delta, (ny/2 + 0.5) delta) */
} im_indenter;

/* Patch (ix, iy) covers [ix delta, (ix + 1) delta) x [iy delta, (iy + 1) delta); its centre is
 * ((ix + 0.5) delta, (iy + 0.5) delta). */

/* A centred cone of semi-opening alpha_degrees (radius unused). */
im_indenter im_indenter_cone(double alpha_degrees);
im_indenter im_indenter_sphere(double radius);
im_indenter im_indenter_flat(double radius);

/* Name of a kind: "cone", "sphere", "flat". */
const char *im_punch_name(enum im_punch_kind kind);

/* The kind named by name: "cone", "sphere" or "flat" (any case), as `indent --punch` and a scene's
 * [punch] shape take it. IM_OK, or IM_EINVAL with "'NAME': expected cone, sphere or flat" (the
 * front end puts the option or key before it); *kind is left as it was then. */
int im_punch_parse(const char *name, enum im_punch_kind *kind);

/* IM_EINVAL naming the parameter when alpha is outside (0, 90) degrees (cone), a radius is not
 * finite and positive (sphere, flat), or the position is not finite. */
int im_indenter_check(const im_indenter *punch);

/* Profile z(r) >= 0 above the punch's lowest point (see above); +INFINITY outside a flat punch. */
double im_indenter_profile(const im_indenter *punch, double r);

/* The axis position for an nx x ny grid of spacing delta (resolves `centred`). */
void im_indenter_axis(const im_indenter *punch, int nx, int ny, double delta, double *x, double *y);

/* Smooth-contact closed forms for an approach w >= 0 (0 for w <= 0), modulus e_star. */
double im_indenter_load(const im_indenter *punch, double e_star, double w);          /* N(w) */
double im_indenter_contact_radius(const im_indenter *punch, double w);               /* a(w) */
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
