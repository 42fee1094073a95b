#include "indentmap/indenter.h"
#include "core/args.h"

#include "indenter/profile.h"
#include "indentmap/status.h"

#include <math.h>
#include <stddef.h>
#include <strings.h>

static double cot_degrees(double alpha_degrees) { return 1.0 / tan(alpha_degrees * M_PI / 180.0); }

int im_punch_parse(const char *name, enum im_punch_kind *kind)
{
    ARG_REQUIRE(name, "name");
    ARG_REQUIRE(kind, "kind");
    static const enum im_punch_kind KINDS[] = {IM_PUNCH_CONE, IM_PUNCH_SPHERE, IM_PUNCH_FLAT, IM_PUNCH_PROFILE};
    for (size_t i = 0; name && i < sizeof KINDS / sizeof KINDS[0]; ++i)
        if (strcasecmp(name, im_punch_name(KINDS[i])) == 0) {
            *kind = KINDS[i];
            return IM_OK;
        }
    return im_fail(IM_EINVAL, "'%s': expected cone, sphere, flat or profile", name ? name : "");
}

im_indenter im_indenter_cone(double alpha_degrees)
{
    return (im_indenter){.kind = IM_PUNCH_CONE, .alpha_degrees = alpha_degrees, .radius = 1, .centred = 1};
}

im_indenter im_indenter_sphere(double radius)
{
    return (im_indenter){.kind = IM_PUNCH_SPHERE, .alpha_degrees = 80, .radius = radius, .centred = 1};
}

im_indenter im_indenter_flat(double radius)
{
    return (im_indenter){.kind = IM_PUNCH_FLAT, .alpha_degrees = 80, .radius = radius, .centred = 1};
}

im_indenter im_indenter_from_profile(const im_profile *profile)
{
    return (im_indenter){.kind = profile ? im_profile_kind(profile) : IM_PUNCH_PROFILE,
                         .alpha_degrees = 80,
                         .radius = 1,
                         .centred = 1,
                         .profile = profile};
}

const char *im_punch_name(enum im_punch_kind kind)
{
    switch (kind) {
    case IM_PUNCH_CONE: return "cone";
    case IM_PUNCH_SPHERE: return "sphere";
    case IM_PUNCH_FLAT: return "flat";
    case IM_PUNCH_PROFILE: return "profile";
    case IM_PUNCH_PROFILE_2D: return "profile-2d";
    }
    return "unknown";
}

static int is_profile(const im_indenter *punch)
{
    return punch->kind == IM_PUNCH_PROFILE || punch->kind == IM_PUNCH_PROFILE_2D;
}

int im_indenter_check(const im_indenter *punch)
{
    ARG_REQUIRE(punch, "punch");
    if (!punch)
        return im_fail(IM_EINVAL, "indenter: NULL");
    switch (punch->kind) {
    case IM_PUNCH_CONE:
        if (!(punch->alpha_degrees > 0 && punch->alpha_degrees < 90))
            return im_fail(IM_EINVAL, "alpha = %g: expected 0 < alpha < 90 degrees", punch->alpha_degrees);
        break;
    case IM_PUNCH_SPHERE:
    case IM_PUNCH_FLAT:
        if (!(isfinite(punch->radius) && punch->radius > 0))
            return im_fail(IM_EINVAL, "%s radius = %g: expected a finite radius > 0", im_punch_name(punch->kind),
                           punch->radius);
        break;
    case IM_PUNCH_PROFILE:
    case IM_PUNCH_PROFILE_2D:
        if (!punch->profile)
            return im_fail(IM_EINVAL, "%s punch: no profile given", im_punch_name(punch->kind));
        if (im_profile_kind(punch->profile) != punch->kind)
            return im_fail(IM_EINVAL, "%s punch: its profile is of kind %s", im_punch_name(punch->kind),
                           im_punch_name(im_profile_kind(punch->profile)));
        break;
    default:
        return im_fail(IM_EINVAL, "indenter kind %d: expected cone, sphere, flat, profile or profile-2d",
                       (int)punch->kind);
    }
    if (!punch->centred && !(isfinite(punch->x0) && isfinite(punch->y0)))
        return im_fail(IM_EINVAL, "indenter position (%g, %g): expected finite coordinates", punch->x0, punch->y0);
    return IM_OK;
}

/* The closed forms of a punch im_indenter_check refuses, or of a modulus that is not finite and positive,
 * are numbers of no meaning (a 95-degree cone's load is negative): the value functions record the
 * failure, prefixed with their name, and return NaN instead. e_star_used 0: the function takes none. */
static int closed_form_refused(const char *function, const im_indenter *punch, int e_star_used, double e_star)
{
    if (im_indenter_check(punch) != IM_OK) {
        im_fail_context(IM_EINVAL, "%s", function);
        return 1;
    }
    if (e_star_used && !(isfinite(e_star) && e_star > 0)) {
        im_fail(IM_EINVAL, "%s: E* = %g: expected a finite modulus > 0", function, e_star);
        return 1;
    }
    return 0;
}

double im_indenter_profile(const im_indenter *punch, double r)
{
    ARG_REQUIRE_OR(punch, "punch", NAN);
    switch (punch->kind) {
    case IM_PUNCH_CONE: return r * cot_degrees(punch->alpha_degrees);
    case IM_PUNCH_SPHERE: return r * r / (2 * punch->radius);
    case IM_PUNCH_FLAT: return r <= punch->radius ? 0.0 : INFINITY;
    case IM_PUNCH_PROFILE: return profile_axisymmetric_height(punch->profile, r);
    case IM_PUNCH_PROFILE_2D: return NAN;
    }
    return NAN;
}

double im_indenter_height(const im_indenter *punch, double dx, double dy)
{
    ARG_REQUIRE_OR(punch, "punch", NAN);
    if (punch->kind == IM_PUNCH_PROFILE_2D)
        return profile_field_height(punch->profile, dx, dy);
    return im_indenter_profile(punch, hypot(dx, dy));
}

void im_indenter_axis(const im_indenter *punch, int nx, int ny, double delta, double *x, double *y)
{
    ARG_REQUIRE_OR(x, "x", );
    ARG_REQUIRE_OR(y, "y", );
    *x = *y = NAN; /* for a NULL punch */
    ARG_REQUIRE_OR(punch, "punch", );
    if (punch->centred) {
        *x = (nx / 2 + 0.5) * delta;
        *y = (ny / 2 + 0.5) * delta;
    } else {
        *x = punch->x0;
        *y = punch->y0;
    }
}

double im_indenter_load(const im_indenter *punch, double e_star, double w)
{
    ARG_REQUIRE_OR(punch, "punch", NAN);
    if (closed_form_refused(__func__, punch, 1, e_star))
        return NAN;
    if (w <= 0)
        return 0;
    switch (punch->kind) {
    case IM_PUNCH_CONE: return 2 * e_star * w * w / (M_PI * cot_degrees(punch->alpha_degrees));
    case IM_PUNCH_SPHERE: return 4.0 / 3.0 * e_star * sqrt(punch->radius) * pow(w, 1.5);
    case IM_PUNCH_FLAT: return 2 * punch->radius * e_star * w;
    case IM_PUNCH_PROFILE: return profile_load(punch->profile, e_star, w);
    case IM_PUNCH_PROFILE_2D: return NAN;
    }
    return NAN;
}

double im_indenter_contact_radius(const im_indenter *punch, double w)
{
    ARG_REQUIRE_OR(punch, "punch", NAN);
    if (closed_form_refused(__func__, punch, 0, 0.0))
        return NAN;
    if (w <= 0)
        return 0;
    switch (punch->kind) {
    case IM_PUNCH_CONE: return 2 * w / (M_PI * cot_degrees(punch->alpha_degrees));
    case IM_PUNCH_SPHERE: return sqrt(punch->radius * w);
    case IM_PUNCH_FLAT: return punch->radius;
    case IM_PUNCH_PROFILE: return profile_contact_radius(punch->profile, w);
    case IM_PUNCH_PROFILE_2D: return NAN;
    }
    return NAN;
}

double im_indenter_pressure(const im_indenter *punch, double e_star, double w, double r)
{
    ARG_REQUIRE_OR(punch, "punch", NAN);
    if (closed_form_refused(__func__, punch, 1, e_star))
        return NAN;
    if (is_profile(punch))
        return NAN;
    double a = im_indenter_contact_radius(punch, w);
    if (w <= 0 || r > a)
        return 0;
    switch (punch->kind) {
    case IM_PUNCH_CONE: return r == 0 ? INFINITY : 0.5 * e_star * cot_degrees(punch->alpha_degrees) * acosh(a / r);
    case IM_PUNCH_SPHERE: return 2 * e_star * a / (M_PI * punch->radius) * sqrt(1 - (r / a) * (r / a));
    case IM_PUNCH_FLAT:
        return r == a ? INFINITY : im_indenter_load(punch, e_star, w) / (2 * M_PI * a * sqrt(a * a - r * r));
    case IM_PUNCH_PROFILE:
    case IM_PUNCH_PROFILE_2D: return NAN;
    }
    return NAN;
}

double im_indenter_approach_for_load(const im_indenter *punch, double e_star, double n)
{
    ARG_REQUIRE_OR(punch, "punch", NAN);
    if (closed_form_refused(__func__, punch, 1, e_star))
        return NAN;
    if (n <= 0)
        return 0;
    switch (punch->kind) {
    case IM_PUNCH_CONE: return sqrt(n * M_PI * cot_degrees(punch->alpha_degrees) / (2 * e_star));
    case IM_PUNCH_SPHERE: return pow(3 * n / (4 * e_star * sqrt(punch->radius)), 2.0 / 3.0);
    case IM_PUNCH_FLAT: return n / (2 * punch->radius * e_star);
    case IM_PUNCH_PROFILE: return profile_approach_for_load(punch->profile, e_star, n);
    case IM_PUNCH_PROFILE_2D: return NAN;
    }
    return NAN;
}

double im_indenter_area_for_load(const im_indenter *punch, double e_star, double n)
{
    ARG_REQUIRE_OR(punch, "punch", NAN);
    if (closed_form_refused(__func__, punch, 1, e_star))
        return NAN;
    if (n <= 0)
        return 0;
    if (punch->kind == IM_PUNCH_CONE)
        return 2 * n / (e_star * cot_degrees(punch->alpha_degrees));
    if (punch->kind == IM_PUNCH_PROFILE_2D)
        return NAN;
    if (punch->kind == IM_PUNCH_PROFILE) {
        double a = profile_radius_for_load(punch->profile, e_star, n);
        return M_PI * a * a;
    }
    double a = im_indenter_contact_radius(punch, im_indenter_approach_for_load(punch, e_star, n));
    return M_PI * a * a;
}
