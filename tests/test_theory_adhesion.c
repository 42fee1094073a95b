/* The adhesive references of theory.h ("Adhesion") against their known limits: the Maugis-Dugdale sphere
 * reaching JKR (pull-off 3/2 pi w R, the JKR curves) at large lambda and DMT (2 pi w R, Hertz shifted) at
 * small lambda, its scaling in E*, w and R, the load at an approach inverting the curve; Kendall's flat
 * punch and the JKR cone from the energy balance G = w, checked independently (the least load found by
 * scanning, Griffith's G recomputed); the refusals. The solver's side is in test_adhesion.c. */
#include "support.h"

#include "indentmap/status.h"
#include "indentmap/theory.h"

#include <math.h>
#include <string.h>

/* A law whose sphere of radius R has Maugis's lambda: sigma0 = lambda / 2 (pi w K^2 / R)^(1/3). */
static im_theory_adhesion law_for_lambda(double e_star, double work, double radius, double lambda)
{
    const double k = 4.0 * e_star / 3.0, sigma0 = lambda / 2.0 * cbrt(M_PI * work * k * k / radius);
    return (im_theory_adhesion){e_star, work, work / sigma0};
}

static im_theory_adhesive_point md_at(const im_theory_adhesion *law, double radius, double a)
{
    im_theory_adhesive_point p;
    if (im_theory_md_sphere(law, radius, a, &p) != IM_OK)
        fail_msg("im_theory_md_sphere(a = %g): %s", a, im_last_error());
    return p;
}

static double pull_off(const im_theory_adhesion *law, double radius)
{
    im_theory_adhesive_point p;
    assert_int_equal(im_theory_md_sphere_pull_off(law, radius, &p), IM_OK);
    return p.load;
}

static void lambda_is_maugis(void **state)
{
    (void)state;
    const im_theory_adhesion law = law_for_lambda(2.0, 0.3, 50.0, 1.7);
    double lambda;
    assert_int_equal(im_theory_maugis_lambda(&law, 50.0, &lambda), IM_OK);
    assert_close(lambda, 1.7, 1e-12);
}

/* Large lambda: JKR's pull-off -3/2 pi w R, its fixed-grip separation at 5/6 of it, and its curves
 * N = 4 E* a^3 / (3 R) - sqrt(8 pi w E* a^3), delta = a^2 / R - sqrt(2 pi w a / E*); E* = 2, w = 0.3, R = 50. */
static void sphere_reaches_jkr(void **state)
{
    (void)state;
    const double e = 2.0, w = 0.3, r = 50.0, unit = M_PI * w * r;
    const im_theory_adhesion law = law_for_lambda(e, w, r, 300.0);
    assert_close(pull_off(&law, r) / unit, -1.5, 2e-3);
    im_theory_adhesive_point sep;
    assert_int_equal(im_theory_md_sphere_separation(&law, r, &sep), IM_OK);
    assert_close(sep.load / unit, -5.0 / 6.0, 2e-3);
    assert_close(sep.approach, -3.0 / 4.0 * cbrt(M_PI * M_PI * w * w * r / (e * e)), 3e-3 * fabs(sep.approach));
    const double length = cbrt(3.0 * M_PI * w * r * r / (4.0 * e)); /* JKR's zero-load radius / 6^(1/3) */
    for (double a = 0.5 * length; a <= 3 * length; a += 0.5 * length) {
        const im_theory_adhesive_point p = md_at(&law, r, a);
        const double n = 4.0 * e * a * a * a / (3.0 * r) - sqrt(8.0 * M_PI * w * e * a * a * a);
        const double d = a * a / r - sqrt(2.0 * M_PI * w * a / e);
        if (!(fabs(p.load - n) <= 5e-3 * unit && fabs(p.approach - d) <= 5e-3 * length * length / r))
            fail_msg("a = %g: N %g against JKR's %g, delta %g against %g", a, p.load, n, p.approach, d);
        assert_true(p.zone_radius > a && p.zone_radius < 1.01 * a); /* the zone shrinks onto the edge */
    }
}

/* The largest departure from DMT (Hertz's curves shifted by -2 pi w R, delta = a^2 / R) over
 * L <= a <= 3 L, in units of pi w R and of L^2 / R; E* = 0.7, w = 0.05, R = 20. */
static double dmt_departure(double lambda)
{
    const double e = 0.7, w = 0.05, r = 20.0, unit = M_PI * w * r;
    const im_theory_adhesion law = law_for_lambda(e, w, r, lambda);
    const double length = cbrt(3.0 * M_PI * w * r * r / (4.0 * e));
    double worst = fabs(pull_off(&law, r) / unit + 2.0);
    for (double a = length; a <= 3 * length; a += 0.5 * length) {
        const im_theory_adhesive_point p = md_at(&law, r, a);
        const double n = 4.0 * e * a * a * a / (3.0 * r) - 2.0 * M_PI * w * r;
        worst = fmax(worst, fmax(fabs(p.load - n) / unit, fabs(p.approach - a * a / r) / (length * length / r)));
    }
    return worst;
}

/* Small lambda: DMT, approached as sqrt(lambda) (the zone's reach c ~ sqrt(lambda)^-1 a). */
static void sphere_reaches_dmt(void **state)
{
    (void)state;
    const double coarse = dmt_departure(1e-2), fine = dmt_departure(1e-4);
    print_message("largest departure from DMT: %.4f at lambda 1e-2, %.5f at 1e-4\n", coarse, fine);
    assert_true(fine < coarse / 5 && fine < 0.03);
}

/* In between, the pull-off force moves monotonically from DMT's to JKR's (Johnson & Greenwood's map). */
static void pull_off_between(void **state)
{
    (void)state;
    double last = 2.0;
    const double lambdas[] = {0.1, 0.3, 1.0, 3.0, 10.0};
    for (size_t i = 0; i < sizeof lambdas / sizeof lambdas[0]; ++i) {
        const im_theory_adhesion law = law_for_lambda(1.0, 0.1, 30.0, lambdas[i]);
        const double force = -pull_off(&law, 30.0) / (M_PI * 0.1 * 30.0);
        print_message("lambda %g: pull-off %.4f pi w R\n", lambdas[i], force);
        assert_true(force < last && force > 1.5);
        last = force;
    }
}

/* The load at an approach inverts the curve on the fixed-grip branch and is NaN below separation; the
 * pull-off is the least load of a scan, the separation the least approach. */
static void load_at_approach_inverts(void **state)
{
    (void)state;
    const double r = 40.0;
    const im_theory_adhesion law = law_for_lambda(1.0, 0.2, r, 1.0);
    im_theory_adhesive_point sep, least;
    assert_int_equal(im_theory_md_sphere_separation(&law, r, &sep), IM_OK);
    assert_int_equal(im_theory_md_sphere_pull_off(&law, r, &least), IM_OK);
    const double length = cbrt(3.0 * M_PI * 0.2 * r * r / 4.0); /* L */
    double scan_load = INFINITY, scan_approach = INFINITY;
    for (double a = 1e-3 * length; a <= 3 * length; a *= 1.01) {
        const im_theory_adhesive_point p = md_at(&law, r, a);
        scan_load = fmin(scan_load, p.load);
        scan_approach = fmin(scan_approach, p.approach);
        if (a > sep.contact_radius * 1.001) {
            double n;
            assert_int_equal(im_theory_md_sphere_load_at_approach(&law, r, p.approach, &n), IM_OK);
            assert_close(n, p.load, 1e-9 * fabs(least.load));
        }
    }
    assert_true(least.load <= scan_load && scan_load - least.load <= 1e-6 * fabs(least.load));
    assert_true(sep.approach <= scan_approach && scan_approach - sep.approach <= 1e-6 * fabs(sep.approach));
    double n;
    assert_int_equal(im_theory_md_sphere_load_at_approach(&law, r, sep.approach * 1.01, &n), IM_OK);
    assert_true(isnan(n));
}

/* Kendall: N_c = -sqrt(8 pi a^3 E* w), where Griffith's G = N^2 / (8 pi a^3 E*) equals w, on the line
 * N = 2 E* a delta; NaN beyond. */
static void kendall_flat_punch(void **state)
{
    (void)state;
    const im_theory_adhesion law = {3.0, 0.02, 0.1};
    const double a = 12.0;
    im_theory_adhesive_point p;
    assert_int_equal(im_theory_kendall_pull_off(&law, a, &p), IM_OK);
    assert_close(p.load * p.load / (8.0 * M_PI * a * a * a * law.e_star), law.work, 1e-15);
    assert_true(p.load < 0);
    assert_close(p.load, 2.0 * law.e_star * a * p.approach, 1e-12 * fabs(p.load));
    double n;
    assert_int_equal(im_theory_kendall_load_at_approach(&law, a, 0.5 * p.approach, &n), IM_OK);
    assert_close(n, 0.5 * p.load, 1e-12 * fabs(p.load));
    assert_int_equal(im_theory_kendall_load_at_approach(&law, a, 1.001 * p.approach, &n), IM_OK);
    assert_true(isnan(n));
}

/* The JKR cone: Love's cone less Kendall's punch with G = w at every a; the pull-off is the least load of
 * a scan; w -> 0 gives Love (N = pi/2 E* cot(alpha) a^2, delta = pi/2 cot(alpha) a). */
static void jkr_cone(void **state)
{
    (void)state;
    const double alpha = 80.0, cot = 1.0 / tan(alpha * M_PI / 180.0);
    const im_theory_adhesion law = {1.5, 0.04, 1.0};
    im_theory_adhesive_point c;
    assert_int_equal(im_theory_jkr_cone_pull_off(&law, alpha, &c), IM_OK);
    assert_close(c.load, -54.0 * law.work * law.work / (M_PI * law.e_star * pow(cot, 3)), 1e-12 * fabs(c.load));
    double scan = INFINITY;
    for (double a = 0.01 * c.contact_radius; a <= 4 * c.contact_radius; a *= 1.002) {
        im_theory_adhesive_point p;
        assert_int_equal(im_theory_jkr_cone(&law, alpha, a, &p), IM_OK);
        scan = fmin(scan, p.load);
        const double love = M_PI / 2.0 * law.e_star * cot * a * a, flat = love - p.load;
        assert_close(flat * flat / (8.0 * M_PI * a * a * a * law.e_star), law.work, 1e-12 * law.work);
        assert_close(p.approach, M_PI / 2.0 * cot * a - flat / (2.0 * law.e_star * a), 1e-12 * a);
    }
    assert_true(c.load <= scan && scan - c.load <= 1e-5 * fabs(c.load));
    const im_theory_adhesion faint = {1.5, 1e-30, 1.0};
    im_theory_adhesive_point p;
    assert_int_equal(im_theory_jkr_cone(&faint, alpha, 2.0, &p), IM_OK);
    assert_close(p.load, M_PI / 2.0 * 1.5 * cot * 4.0, 1e-12);
    assert_close(p.approach, M_PI / 2.0 * cot * 2.0, 1e-12);
}

static void refusals(void **state)
{
    (void)state;
    im_theory_adhesion law = {1.0, 0.1, 0.5};
    im_theory_adhesive_point p;
    double x;
    assert_int_equal(im_theory_md_sphere(&law, 10.0, 0.0, &p), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "a = 0"));
    assert_int_equal(im_theory_maugis_lambda(&law, -1.0, &x), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "R = -1"));
    assert_int_equal(im_theory_jkr_cone_pull_off(&law, 90.0, &p), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "alpha"));
    assert_int_equal(im_theory_md_sphere_load_at_approach(&law, 10.0, NAN, &x), IM_EINVAL);
    law.range = 0;
    assert_int_equal(im_theory_kendall_pull_off(&law, 1.0, &p), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "delta_c"));
    law.range = 0.5;
    law.work = -1;
    assert_int_equal(im_theory_md_sphere_pull_off(&law, 1.0, &p), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "work of adhesion"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(lambda_is_maugis),
        cmocka_unit_test(sphere_reaches_jkr),
        cmocka_unit_test(sphere_reaches_dmt),
        cmocka_unit_test(pull_off_between),
        cmocka_unit_test(load_at_approach_inverts),
        cmocka_unit_test(kendall_flat_punch),
        cmocka_unit_test(jkr_cone),
        cmocka_unit_test(refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
