/* The adhesive references (theory.h, "Adhesion"): the Maugis-Dugdale sphere in Johnson and Greenwood's
 * reduced form, Kendall's flat punch and the JKR cone. */
#include "indentmap/status.h"
#include "core/args.h"
#include "indentmap/theory.h"
#include "core/gsl_handler.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>
#include <math.h>

static const double DEGREE = M_PI / 180.0;

static int check_law(const im_theory_adhesion *law)
{
    if (!(law->e_star > 0.0 && isfinite(law->e_star)))
        return im_fail(IM_EINVAL, "E* = %g: expected a finite E* > 0", law->e_star);
    if (!(law->work > 0.0 && isfinite(law->work)))
        return im_fail(IM_EINVAL, "work of adhesion w = %g: expected a finite w > 0", law->work);
    if (!(law->range > 0.0 && isfinite(law->range)))
        return im_fail(IM_EINVAL, "adhesion range delta_c = %g: expected a finite delta_c > 0", law->range);
    return IM_OK;
}

static int check_length(const im_theory_adhesion *law, const char *name, double value)
{
    int status = check_law(law);
    if (status == IM_OK && !(value > 0.0 && isfinite(value)))
        status = im_fail(IM_EINVAL, "%s = %g: expected a finite %s > 0", name, value, name);
    return status;
}

static int check_cone(const im_theory_adhesion *law, double alpha_deg)
{
    int status = check_law(law);
    if (status == IM_OK && !(alpha_deg > 0.0 && alpha_deg < 90.0))
        status = im_fail(IM_EINVAL, "alpha = %g: expected 0 < alpha < 90 degrees", alpha_deg);
    return status;
}

/* ---- the Maugis-Dugdale sphere in reduced units ---- */

/* The sphere's scales: lambda, the radius L, the load pi w R and the approach L^2 / R. */
typedef struct md_scales {
    double lambda, length, load, approach;
} md_scales;

static md_scales md_scales_of(const im_theory_adhesion *law, double radius)
{
    const double k = 4.0 * law->e_star / 3.0, sigma0 = law->work / law->range;
    const double length = cbrt(M_PI * law->work * radius * radius / k);
    return (md_scales){2.0 * sigma0 * cbrt(radius / (M_PI * law->work * k * k)), length, M_PI * law->work * radius,
                       length * length / radius};
}

static double md_zone_equation(double m, void *params)
{
    const double *p = params, lambda = p[0], a = p[1];
    const double s = sqrt(m * m - 1.0), t = atan(s);
    return lambda * a * a / 2.0 * (s + (m * m - 2.0) * t) + 4.0 * lambda * lambda * a / 3.0 * (s * t - m + 1.0) - 1.0;
}

/* Brent's root of f in [lo, hi] (a sign change) to 1e-14 relative; IM_ENOCONV if it does not settle. */
static int brent_root(double (*f)(double, void *), void *params, double lo, double hi, double *root)
{
    gsl_function fn = {f, params};
    gsl_root_fsolver *solver = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    if (!solver)
        return im_fail(IM_ENOMEM, "Maugis-Dugdale: GSL root solver allocation failed");
    core_gsl_handler_off();
    int status = gsl_root_fsolver_set(solver, &fn, lo, hi), settled = 0;
    for (int i = 0; i < 500 && status == GSL_SUCCESS && !settled; ++i) {
        status = gsl_root_fsolver_iterate(solver);
        settled = gsl_root_test_interval(gsl_root_fsolver_x_lower(solver), gsl_root_fsolver_x_upper(solver), 0.0,
                                         1e-14) == GSL_SUCCESS;
    }
    *root = gsl_root_fsolver_root(solver);
    core_gsl_handler_restore();
    gsl_root_fsolver_free(solver);
    if (!settled)
        return im_fail(IM_ENOCONV, "Maugis-Dugdale: root in [%g, %g] not found: %s", lo, hi, gsl_strerror(status));
    return IM_OK;
}

/* The upper end of a bracket: hi doubled from 2 until f(hi) >= 0 (f increasing). */
static int bracket_above(double (*f)(double, void *), void *params, double *hi)
{
    for (*hi = 2.0; f(*hi, params) < 0.0; *hi *= 2.0)
        if (*hi > 1e150)
            return im_fail(IM_ENUMERIC, "Maugis-Dugdale: no bracket below %g", *hi);
    return IM_OK;
}

/* The reduced point at reduced radius a: m, P and D. */
static int md_reduced(double lambda, double a, double out[3])
{
    double params[2] = {lambda, a}, hi, m;
    int status = bracket_above(md_zone_equation, params, &hi);
    if (status == IM_OK)
        status = brent_root(md_zone_equation, params, 1.0, hi, &m);
    if (status != IM_OK)
        return status;
    const double s = sqrt(m * m - 1.0);
    out[0] = m;
    out[1] = a * a * a - lambda * a * a * (s + m * m * atan(s));
    out[2] = a * a - 4.0 / 3.0 * lambda * a * s;
    return IM_OK;
}

static int md_point(const md_scales *sc, double a, im_theory_adhesive_point *out)
{
    double r[3];
    int status = md_reduced(sc->lambda, a, r);
    if (status == IM_OK)
        *out = (im_theory_adhesive_point){a * sc->length, r[0] * a * sc->length, r[1] * sc->load,
                                          r[2] * sc->approach};
    return status;
}

/* The reduced radius in [lo, hi] least in P (which = 1) or D (which = 2): golden section (both unimodal
 * there). */
static int md_minimiser(double lambda, int which, double lo, double hi, double *a)
{
    const double g = (sqrt(5.0) - 1.0) / 2.0;
    double fc[3], fd[3];
    while (hi - lo > 1e-12) {
        const double c = hi - g * (hi - lo), d = lo + g * (hi - lo);
        int status = md_reduced(lambda, c, fc);
        if (status == IM_OK)
            status = md_reduced(lambda, d, fd);
        if (status != IM_OK)
            return status;
        if (fc[which] < fd[which])
            hi = d;
        else
            lo = c;
    }
    *a = (lo + hi) / 2.0;
    return IM_OK;
}

int im_theory_maugis_lambda(const im_theory_adhesion *law, double radius, double *lambda)
{
    ARG_REQUIRE(law, "law");
    ARG_REQUIRE(lambda, "lambda");
    int status = check_length(law, "R", radius);
    if (status == IM_OK)
        *lambda = md_scales_of(law, radius).lambda;
    return status;
}

int im_theory_md_sphere(const im_theory_adhesion *law, double radius, double contact_radius,
                        im_theory_adhesive_point *out)
{
    ARG_REQUIRE(law, "law");
    ARG_REQUIRE(out, "out");
    int status = check_length(law, "R", radius);
    if (status == IM_OK)
        status = check_length(law, "a", contact_radius);
    if (status != IM_OK)
        return status;
    const md_scales sc = md_scales_of(law, radius);
    return md_point(&sc, contact_radius / sc.length, out);
}

/* The point least in P (which = 1) or D (which = 2). */
static int md_least(const im_theory_adhesion *law, double radius, int which, im_theory_adhesive_point *out)
{
    int status = check_length(law, "R", radius);
    if (status != IM_OK)
        return status;
    const md_scales sc = md_scales_of(law, radius);
    double a;
    status = md_minimiser(sc.lambda, which, 1e-4, 3.0, &a);
    return status == IM_OK ? md_point(&sc, a, out) : status;
}

int im_theory_md_sphere_pull_off(const im_theory_adhesion *law, double radius, im_theory_adhesive_point *out)
{
    ARG_REQUIRE(law, "law");
    ARG_REQUIRE(out, "out");
    return md_least(law, radius, 1, out);
}

int im_theory_md_sphere_separation(const im_theory_adhesion *law, double radius, im_theory_adhesive_point *out)
{
    ARG_REQUIRE(law, "law");
    ARG_REQUIRE(out, "out");
    return md_least(law, radius, 2, out);
}

typedef struct md_target {
    double lambda, approach;
    int status;
} md_target;

static double md_approach_above_target(double a, void *params)
{
    md_target *t = params;
    double r[3];
    if (t->status == IM_OK)
        t->status = md_reduced(t->lambda, a, r);
    return t->status == IM_OK ? r[2] - t->approach : 0.0;
}

int im_theory_md_sphere_load_at_approach(const im_theory_adhesion *law, double radius, double approach, double *load)
{
    ARG_REQUIRE(law, "law");
    ARG_REQUIRE(load, "load");
    im_theory_adhesive_point separation;
    int status = isfinite(approach) ? md_least(law, radius, 2, &separation)
                                    : im_fail(IM_EINVAL, "approach = %g: expected a finite approach", approach);
    if (status != IM_OK)
        return status;
    if (approach <= separation.approach) {
        *load = NAN;
        return IM_OK;
    }
    const md_scales sc = md_scales_of(law, radius);
    md_target t = {sc.lambda, approach / sc.approach, IM_OK};
    double hi, a, r[3];
    status = bracket_above(md_approach_above_target, &t, &hi);
    if (status == IM_OK)
        status = brent_root(md_approach_above_target, &t, separation.contact_radius / sc.length, hi, &a);
    if (status == IM_OK)
        status = t.status != IM_OK ? t.status : md_reduced(sc.lambda, a, r);
    if (status == IM_OK)
        *load = r[1] * sc.load;
    return status;
}

/* ---- the JKR limits: Kendall's flat punch and the cone ---- */

int im_theory_kendall_pull_off(const im_theory_adhesion *law, double punch_radius, im_theory_adhesive_point *out)
{
    ARG_REQUIRE(law, "law");
    ARG_REQUIRE(out, "out");
    int status = check_length(law, "a", punch_radius);
    if (status == IM_OK)
        *out = (im_theory_adhesive_point){punch_radius, punch_radius,
                                          -sqrt(8.0 * M_PI * pow(punch_radius, 3) * law->e_star * law->work),
                                          -sqrt(2.0 * M_PI * law->work * punch_radius / law->e_star)};
    return status;
}

int im_theory_kendall_load_at_approach(const im_theory_adhesion *law, double punch_radius, double approach,
                                       double *load)
{
    ARG_REQUIRE(law, "law");
    ARG_REQUIRE(load, "load");
    im_theory_adhesive_point pull_off;
    int status = isfinite(approach) ? im_theory_kendall_pull_off(law, punch_radius, &pull_off)
                                    : im_fail(IM_EINVAL, "approach = %g: expected a finite approach", approach);
    if (status == IM_OK)
        *load = approach >= pull_off.approach ? 2.0 * law->e_star * punch_radius * approach : NAN;
    return status;
}

static im_theory_adhesive_point jkr_cone_at(const im_theory_adhesion *law, double cot_alpha, double a)
{
    return (im_theory_adhesive_point){
        a, a, M_PI / 2.0 * law->e_star * cot_alpha * a * a - sqrt(8.0 * M_PI * law->e_star * law->work * a * a * a),
        M_PI / 2.0 * cot_alpha * a - sqrt(2.0 * M_PI * law->work * a / law->e_star)};
}

static double cot_degrees(double alpha_deg) { return cos(alpha_deg * DEGREE) / sin(alpha_deg * DEGREE); }

int im_theory_jkr_cone(const im_theory_adhesion *law, double alpha_deg, double contact_radius,
                       im_theory_adhesive_point *out)
{
    ARG_REQUIRE(law, "law");
    ARG_REQUIRE(out, "out");
    int status = check_cone(law, alpha_deg);
    if (status == IM_OK)
        status = check_length(law, "a", contact_radius);
    if (status == IM_OK)
        *out = jkr_cone_at(law, cot_degrees(alpha_deg), contact_radius);
    return status;
}

int im_theory_jkr_cone_pull_off(const im_theory_adhesion *law, double alpha_deg, im_theory_adhesive_point *out)
{
    ARG_REQUIRE(law, "law");
    ARG_REQUIRE(out, "out");
    int status = check_cone(law, alpha_deg);
    if (status != IM_OK)
        return status;
    const double cot_alpha = cot_degrees(alpha_deg);
    *out = jkr_cone_at(law, cot_alpha, 18.0 * law->work / (M_PI * law->e_star * cot_alpha * cot_alpha));
    return IM_OK;
}
