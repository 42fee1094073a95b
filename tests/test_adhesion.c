/* Adhesion (solver.h, "Adhesion"): a sphere against the Maugis-Dugdale solution (Maugis 1992, in Johnson
 * and Greenwood's 1997 reduced form), evaluated here on its own with GSL, across the Tabor-Maugis
 * parameter lambda from the DMT side to the JKR side, with an error that shrinks as the grid is refined;
 * the reference itself against the DMT (2 pi w R) and JKR (3/2 pi w R) pull-off forces; hysteresis
 * (jump-in on approach later than jump-out on retraction); a vanishing work recovering the repulsive
 * answers; the net force field's sums; and the combinations refused. */
#include "support.h"

#include "indentmap/indenter.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* ---- the Maugis-Dugdale sphere, reduced: with K = 4 E* / 3,
 *   A = a (K / (pi w R^2))^(1/3),  P = N / (pi w R),  D = delta (K^2 / (pi^2 w^2 R))^(1/3),
 *   lambda = 2 sigma0 (R / (pi w K^2))^(1/3),  m = c / a (c: the zone's outer radius):
 *   lambda A^2 / 2 [s + (m^2 - 2) atan s] + 4 lambda^2 A / 3 [s atan s - m + 1] = 1,  s = sqrt(m^2 - 1)
 *   P = A^3 - lambda A^2 [s + m^2 atan s],   D = A^2 - 4 lambda A s / 3 ---- */
typedef struct md_point {
    double radius, m, load, approach;
} md_point;

static double md_zone_equation(double m, void *params)
{
    const double *p = params, lambda = p[0], a = p[1];
    const double s = sqrt(m * m - 1), t = atan(s);
    return lambda * a * a / 2 * (s + (m * m - 2) * t) + 4 * lambda * lambda * a / 3 * (s * t - m + 1) - 1;
}

/* Brent's root of f in [lo, hi] (f(lo) < 0 < f(hi)) to 1e-14. */
static double md_root(double (*f)(double, void *), void *params, double lo, double hi)
{
    gsl_function fn = {f, params};
    gsl_root_fsolver *solver = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    assert_int_equal(gsl_root_fsolver_set(solver, &fn, lo, hi), GSL_SUCCESS);
    double x = lo;
    for (int i = 0; i < 500; ++i) {
        gsl_root_fsolver_iterate(solver);
        x = gsl_root_fsolver_root(solver);
        if (gsl_root_test_interval(gsl_root_fsolver_x_lower(solver), gsl_root_fsolver_x_upper(solver), 1e-15, 1e-14) ==
            GSL_SUCCESS)
            break;
    }
    gsl_root_fsolver_free(solver);
    return x;
}

static md_point md_at_radius(double lambda, double a)
{
    double params[2] = {lambda, a}, hi = 2;
    while (md_zone_equation(hi, params) < 0)
        hi *= 2;
    const double m = md_root(md_zone_equation, params, 1, hi), s = sqrt(m * m - 1);
    return (md_point){a, m, a * a * a - lambda * a * a * (s + m * m * atan(s)), a * a - 4.0 / 3.0 * lambda * a * s};
}

static double md_load(double lambda, double a) { return md_at_radius(lambda, a).load; }
static double md_approach(double lambda, double a) { return md_at_radius(lambda, a).approach; }

/* The minimiser of f(lambda, .) over [lo, hi] (golden section; both curves are unimodal there). */
static double md_minimiser(double (*f)(double, double), double lambda, double lo, double hi)
{
    const double g = (sqrt(5) - 1) / 2;
    double a = lo, b = hi;
    while (b - a > 1e-12) {
        double c = b - g * (b - a), d = a + g * (b - a);
        if (f(lambda, c) < f(lambda, d))
            b = d;
        else
            a = c;
    }
    return (a + b) / 2;
}

static double md_pull_off(double lambda) { return md_load(lambda, md_minimiser(md_load, lambda, 1e-3, 3)); }

typedef struct md_branch {
    double lambda, target;
} md_branch;

static double md_approach_minus_target(double a, void *params)
{
    const md_branch *b = params;
    return md_approach(b->lambda, a) - b->target;
}

/* The load at reduced approach D on the branch that displacement control follows (the contact radius
 * larger than at the least approach); NaN below that least approach (separated). */
static double md_load_at_approach(double lambda, double d)
{
    const double lowest = md_minimiser(md_approach, lambda, 1e-4, 3);
    if (d <= md_approach(lambda, lowest))
        return NAN;
    md_branch b = {lambda, d};
    double hi = 2;
    while (md_approach_minus_target(hi, &b) < 0)
        hi *= 2;
    return md_load(lambda, md_root(md_approach_minus_target, &b, lowest, hi));
}

/* The reference reaches both limits: DMT's 2 pi w R at small lambda, JKR's 3/2 pi w R at large lambda,
 * and JKR's fixed-grip separation load 5/6 of it where the approach is least. */
static void reference_reaches_dmt_and_jkr(void **state)
{
    (void)state;
    assert_close(md_pull_off(0.01), -2.0, 2e-3);
    assert_close(md_pull_off(100), -1.5, 1e-4);
    const double jkr = 100;
    assert_close(md_load(jkr, md_minimiser(md_approach, jkr, 1e-3, 3)), -5.0 / 6.0, 1e-4);
    /* in between, the pull-off moves monotonically from one to the other */
    assert_true(md_pull_off(0.3) < md_pull_off(1) && md_pull_off(1) < md_pull_off(3));
}

/* ---- the simulated sphere: a flat surface, the grid's patches of side 1, the reduced radius scale
 * L = (pi w R^2 / K)^(1/3) = `scale` patches and R = 8 L ---- */
typedef struct sphere_case {
    double lambda, scale;
    double radius, work, stress, range, approach_unit, load_unit;
} sphere_case;

static sphere_case sphere_case_make(double lambda, double scale)
{
    const double k = 4.0 / 3.0, radius = 8 * scale, work = k * pow(scale, 3) / (M_PI * radius * radius);
    const double stress = lambda / 2 * cbrt(M_PI * work * k * k / radius);
    return (sphere_case){lambda, scale, radius, work, stress, work / stress, scale * scale / radius,
                         M_PI * work * radius};
}

static im_indentation *sphere_run(const sphere_case *c, double largest)
{
    const int n = (int)(8 * c->scale);
    im_field *surface = NULL;
    assert_int_equal(im_field_create(n, n, 1.0, &surface), IM_OK);
    im_solver_options o = im_solver_options_default();
    o.tol = 1e-8;
    o.adhesion_work = c->work;
    o.adhesion_range = c->range;
    im_indenter sphere = im_indenter_sphere(c->radius);
    im_indentation *run = NULL;
    if (im_indentation_create(surface, &sphere, IM_CONTROL_DISPLACEMENT, largest * c->approach_unit, &o, &run) != IM_OK)
        fail_msg("im_indentation_create: %s", im_last_error());
    im_field_free(surface);
    return run;
}

static im_step_result sphere_step(im_indentation *run, const sphere_case *c, double d)
{
    im_step_result r;
    if (im_indentation_step(run, d * c->approach_unit, &r) != IM_OK)
        fail_msg("lambda %g, L %g: step D = %g: %s", c->lambda, c->scale, d, im_last_error());
    return r;
}

/* The largest |P - P_MD(D)| over a retraction from D = 1.5 to 0.05 past the reference's separation,
 * in units of pi w R, after an approach to D = 1.5. */
static double sphere_retraction_error(double lambda, double scale)
{
    const sphere_case c = sphere_case_make(lambda, scale);
    im_indentation *run = sphere_run(&c, 2.0);
    for (double d = 0.25; d <= 1.5; d += 0.25)
        sphere_step(run, &c, d);
    const double separation = md_approach(lambda, md_minimiser(md_approach, lambda, 1e-4, 3));
    double worst = 0;
    int compared = 0;
    for (double d = 1.5; d > separation + 0.05; d -= 0.1) {
        im_step_result r = sphere_step(run, &c, d);
        const double expected = md_load_at_approach(lambda, d);
        worst = fmax(worst, fabs(r.load / c.load_unit - expected));
        ++compared;
    }
    assert_true(compared >= 10);
    im_indentation_free(run);
    return worst;
}

/* Along the retraction the simulated force follows Maugis-Dugdale's, and the error shrinks with the grid:
 * lambda = 0.3 (DMT side), 1, 3 (JKR side; its zone is a few patches wide only on the finer grid). */
static void sphere_follows_maugis_dugdale(void **state)
{
    (void)state;
    static const struct {
        double lambda, coarse, fine, bound;
    } cases[] = {{0.3, 5, 10, 0.01}, {1, 6, 12, 0.03}, {3, 10, 20, 0.1}};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k) {
        const double coarse = sphere_retraction_error(cases[k].lambda, cases[k].coarse);
        const double fine = sphere_retraction_error(cases[k].lambda, cases[k].fine);
        print_message("lambda %g: largest |P - P_MD| / (pi w R) %.4f at L = %g patches, %.4f at L = %g\n",
                      cases[k].lambda, coarse, cases[k].coarse, fine, cases[k].fine);
        if (!(fine < coarse && fine <= cases[k].bound))
            fail_msg("lambda %g: errors %.4f (L = %g) and %.4f (L = %g): expected the finer below the coarser and "
                     "below %g", cases[k].lambda, coarse, cases[k].coarse, fine, cases[k].fine, cases[k].bound);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(reference_reaches_dmt_and_jkr),
        cmocka_unit_test(sphere_follows_maugis_dugdale),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
