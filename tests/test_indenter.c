/* Punch profiles and the smooth-contact closed forms: each closed form is checked against another
 * one derived independently (the pressure integrates to the load, the area law, the inverse). */
#include "support.h"

#include "indentmap/indenter.h"
#include "indentmap/status.h"

#include <math.h>
#include <string.h>

/* 2 pi int_0^a p(r) r dr by the midpoint rule after r = a (1 - s^2), which removes the flat punch's
 * inverse-square-root edge singularity; the cone's logarithmic one at r = 0 is tamed by the weight r. */
static double integrated_load(const im_indenter *p, double w)
{
    const double a = im_indenter_contact_radius(p, w);
    const int n = 200000;
    double sum = 0;
    for (int k = 0; k < n; ++k) {
        double s = (k + 0.5) / n, r = a * (1 - s * s);
        sum += im_indenter_pressure(p, 1.0, w, r) * r * 2 * a * s / n;
    }
    return 2 * M_PI * sum;
}

static void test_pressures_integrate_to_load(void **state)
{
    (void)state;
    im_indenter punches[] = {im_indenter_cone(80), im_indenter_cone(60), im_indenter_sphere(500),
                             im_indenter_flat(20)};
    for (int i = 0; i < 4; ++i) {
        double w = 3.7, n = im_indenter_load(&punches[i], 1.0, w);
        double rel = test_relative_difference(integrated_load(&punches[i], w), n);
        if (rel > 1e-4)
            fail_msg("%s: integrated pressure differs from N(w) = %g by %g", im_punch_name(punches[i].kind), n, rel);
    }
}

static void test_cone_love(void **state)
{
    (void)state;
    im_indenter cone = im_indenter_cone(80);
    const double cot = 1 / tan(80 * M_PI / 180), w = 12.5, e = 2.5;
    double a = im_indenter_contact_radius(&cone, w), n = im_indenter_load(&cone, e, w);
    assert_close(a, 2 * w / (M_PI * cot), 1e-12);
    /* mean pressure E* cot(alpha) / 2, so A_cone = 2N / (E* cot alpha) = pi a^2 */
    assert_close(n / (M_PI * a * a), e * cot / 2, 1e-12);
    assert_close(im_indenter_area_for_load(&cone, e, n) / (M_PI * a * a), 1, 1e-12);
    assert_close(im_indenter_approach_for_load(&cone, e, n), w, 1e-12);
    assert_close(im_indenter_pressure(&cone, e, w, a / cosh(1.0)), e * cot / 2, 1e-12);
    assert_close(im_indenter_pressure(&cone, e, w, 1.01 * a), 0, 0);
    assert_close(im_indenter_profile(&cone, 3.0), 3 * cot, 1e-15);
}

static void test_hertz_and_flat(void **state)
{
    (void)state;
    im_indenter sphere = im_indenter_sphere(400), flat = im_indenter_flat(15);
    const double w = 0.9, e = 1.0;
    double a = sqrt(400 * w), n = im_indenter_load(&sphere, e, w);
    assert_close(im_indenter_contact_radius(&sphere, w), a, 1e-12);
    /* p0 = 3N / (2 pi a^2) (Hertz) must equal 2 E* a / (pi R) */
    assert_close(im_indenter_pressure(&sphere, e, w, 0), 3 * n / (2 * M_PI * a * a), 1e-12);
    assert_close(im_indenter_approach_for_load(&sphere, e, n), w, 1e-12);
    assert_close(im_indenter_area_for_load(&sphere, e, n), M_PI * a * a, 1e-9);
    assert_close(im_indenter_load(&flat, e, w), 2 * 15 * w, 1e-12);
    assert_close(im_indenter_pressure(&flat, e, w, 0), 2 * 15 * w / (2 * M_PI * 15 * 15), 1e-12);
    assert_true(isinf(im_indenter_profile(&flat, 15.01)));
    assert_close(im_indenter_profile(&flat, 14.99), 0, 0);
    assert_close(im_indenter_profile(&sphere, 20), 20.0 * 20 / 800, 1e-15);
}

static void test_refusals(void **state)
{
    (void)state;
    double bad_alpha[] = {0, 90, -10, 120, NAN};
    for (int i = 0; i < 5; ++i) {
        im_indenter c = im_indenter_cone(bad_alpha[i]);
        assert_int_equal(im_indenter_check(&c), IM_EINVAL);
        assert_non_null(strstr(im_last_error(), "alpha"));
    }
    im_indenter ok = im_indenter_cone(80);
    assert_int_equal(im_indenter_check(&ok), IM_OK);
    im_indenter s = im_indenter_sphere(0), f = im_indenter_flat(INFINITY);
    assert_int_equal(im_indenter_check(&s), IM_EINVAL);
    assert_int_equal(im_indenter_check(&f), IM_EINVAL);
    im_indenter off = {.kind = IM_PUNCH_CONE, .alpha_degrees = 80, .x0 = NAN, .y0 = 1};
    assert_int_equal(im_indenter_check(&off), IM_EINVAL);
}

static void test_axis(void **state)
{
    (void)state;
    im_indenter c = im_indenter_cone(80);
    double x, y;
    im_indenter_axis(&c, 64, 33, 2.0, &x, &y);
    assert_close(x, 65, 0); /* centre of patch (32, 16) */
    assert_close(y, 33, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pressures_integrate_to_load),
        cmocka_unit_test(test_cone_love),
        cmocka_unit_test(test_hertz_and_flat),
        cmocka_unit_test(test_refusals),
        cmocka_unit_test(test_axis),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
