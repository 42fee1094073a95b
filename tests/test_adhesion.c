/* Adhesion (solver.h, "Adhesion"): a sphere against the Maugis-Dugdale solution (Maugis 1992, in Johnson
 * and Greenwood's 1997 reduced form), evaluated here on its own with GSL, across the Tabor-Maugis
 * parameter lambda from the DMT side to the JKR side, with an error that shrinks as the grid is refined;
 * the reference itself against the DMT (2 pi w R) and JKR (3/2 pi w R) pull-off forces; hysteresis
 * (jump-in on approach later than jump-out on retraction); a vanishing work recovering the repulsive
 * answers; the net force field's sums; and the combinations refused. */
#include "support.h"

#include "indentmap/indenter.h"
#include "indentmap/measure.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
    } cases[] = {{0.3, 5, 10, 0.004}, {1, 6, 12, 0.017}, {3, 10, 20, 0.07}};
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

/* Jump-in and jump-out: on approach the surface snaps into contact before the undeformed surfaces
 * meet, on retraction it holds on to a more negative approach (Maugis-Dugdale's least approach), and
 * the force-distance loop encloses work (dissipated by the two jumps). */
static void approach_and_retraction_differ(void **state)
{
    (void)state;
    const sphere_case c = sphere_case_make(1.0, 8);
    im_indentation *run = sphere_run(&c, 2.0);
    double jump_in = NAN, jump_out = NAN, loop = 0, last_d = NAN, last_n = 0;
    for (int k = 0; k <= 60; ++k) {
        const double d = k <= 30 ? -1.5 + 0.1 * k : 1.5 - 0.1 * (k - 30);
        im_step_result r = sphere_step(run, &c, d);
        if (k <= 30 && r.contact_patches > 0 && isnan(jump_in))
            jump_in = d;
        if (k > 30 && r.contact_patches > 0)
            jump_out = d;
        if (k > 0) /* the trapezoid rule: approach adds, retraction subtracts */
            loop += 0.5 * (r.load + last_n) * (d - last_d);
        last_d = d;
        last_n = r.load;
    }
    im_indentation_free(run);
    const double separation = md_approach(1.0, md_minimiser(md_approach, 1.0, 1e-4, 3));
    print_message("jump-in at D = %.2f, last contact on retraction at D = %.2f (Maugis-Dugdale separates at %.3f); "
                  "loop work %.4g\n", jump_in, jump_out, separation, loop);
    assert_true(jump_in < 0);                    /* the surface reaches up to the punch */
    assert_true(jump_in > jump_out + 0.3);       /* and lets go much later */
    assert_true(fabs(jump_out - separation) <= 0.1 + 1e-9); /* within a step of the reference's separation */
    assert_true(loop > 0); /* the retraction pulls where the approach did not: work lost in the jumps */
}

/* A vanishing work of adhesion gives the repulsive answers: the same loads to 1e-8 and the same contact
 * on a rough surface under a cone. */
static void vanishing_work_is_repulsive(void **state)
{
    (void)state;
    im_field *surface = test_rough_surface(64, 0.08, 3);
    im_indenter cone = im_indenter_cone(80.0);
    im_solver_options plain = im_solver_options_default(), sticky = plain;
    plain.tol = sticky.tol = 1e-10;
    sticky.adhesion_work = 1e-16;
    sticky.adhesion_range = 1e-6;
    im_indentation *a = NULL, *b = NULL;
    assert_int_equal(im_indentation_create(surface, &cone, IM_CONTROL_DISPLACEMENT, 4, &plain, &a), IM_OK);
    assert_int_equal(im_indentation_create(surface, &cone, IM_CONTROL_DISPLACEMENT, 4, &sticky, &b), IM_OK);
    for (double w = 1; w <= 4; w += 1) {
        im_step_result ra, rb;
        assert_int_equal(im_indentation_step(a, w, &ra), IM_OK);
        assert_int_equal(im_indentation_step(b, w, &rb), IM_OK);
        if (!(test_relative_difference(ra.load, rb.load) <= 1e-8 && ra.contact_patches == rb.contact_patches))
            fail_msg("w = %g: load %.17g against %.17g, contact %ld against %ld", w, rb.load, ra.load,
                     rb.contact_patches, ra.contact_patches);
        /* the zone pulls, with at most sigma0 on each patch under tension */
        const double stress = sticky.adhesion_work / sticky.adhesion_range;
        assert_true(rb.tensile_force > 0 && rb.tensile_force <= stress * (double)rb.adhesive_patches * (1 + 1e-12));
    }
    im_indentation_free(a);
    im_indentation_free(b);
    im_field_free(surface);
}

/* The step's sums are the net force field's: load = sum f, tensile force = -sum of the negative f,
 * the patches under tension and compression counted; and the field's displacement is K f. */
static void step_sums_are_the_fields(void **state)
{
    (void)state;
    const sphere_case c = sphere_case_make(1.0, 8);
    im_indentation *run = sphere_run(&c, 2.0);
    sphere_step(run, &c, 0.5);
    im_step_result r = sphere_step(run, &c, -0.3);
    assert_true(r.load < 0 && r.tensile_force > 0 && r.adhesive_patches > 0 && r.repulsive_patches > 0);
    im_field *force = NULL, *displacement = NULL, *again = NULL;
    assert_int_equal(im_indentation_fields(run, &force, NULL, &displacement), IM_OK);
    double sum = 0, pull = 0;
    long negative = 0, positive = 0;
    for (size_t i = 0; i < im_field_count(force); ++i) {
        sum += force->data[i];
        pull += force->data[i] < 0 ? -force->data[i] : 0;
        negative += force->data[i] < 0;
        positive += force->data[i] > 0;
    }
    assert_close(sum, r.load, 1e-12 * r.tensile_force);
    assert_close(pull, r.tensile_force, 1e-12 * r.tensile_force);
    assert_int_equal(negative, r.adhesive_patches);
    assert_int_equal(positive, r.repulsive_patches);
    im_solver_options o = im_solver_options_default();
    assert_int_equal(im_displacement_full(force, &o, &again), IM_OK);
    const im_window w = im_indentation_window(run);
    double worst = 0, largest = 0;
    for (int y = w.y0; y < w.y0 + w.ny; ++y)
        for (int x = w.x0; x < w.x0 + w.nx; ++x) {
            size_t i = (size_t)y * force->nx + x;
            worst = fmax(worst, fabs(again->data[i] - displacement->data[i]));
            largest = fmax(largest, fabs(again->data[i]));
        }
    assert_true(worst <= 1e-10 * largest);
    im_field_free(force);
    im_field_free(displacement);
    im_field_free(again);
    im_indentation_free(run);
}

/* The combinations the solver does not solve, and a zone that outgrows the surface, are refused. */
static void refusals(void **state)
{
    (void)state;
    im_field *surface = NULL;
    assert_int_equal(im_field_create(24, 24, 1.0, &surface), IM_OK);
    im_indenter sphere = im_indenter_sphere(40);
    im_indentation *run = NULL;
    im_solver_plan *plan = NULL;
    im_solver_options o = im_solver_options_default();
    o.adhesion_work = 0.01;
    assert_int_equal(im_indentation_create(surface, &sphere, IM_CONTROL_DISPLACEMENT, 1, &o, &run), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "adhesion work"));
    o.adhesion_range = 0.5;
    assert_int_equal(im_indentation_create(surface, &sphere, IM_CONTROL_LOAD, 1, &o, &run), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "load control"));
    o.hardness = 0.1;
    assert_int_equal(im_indentation_create(surface, &sphere, IM_CONTROL_DISPLACEMENT, 1, &o, &run), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "adhesion under a hardness"));
    o.hardness = 0;
    assert_int_equal(im_solver_plan_create(24, 24, 1.0, &o, &plan), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "acts in an indentation"));
    assert_int_equal(im_indentation_create(surface, &sphere, IM_CONTROL_DISPLACEMENT, 1, &o, &run), IM_OK);
    im_step_result r;
    assert_int_equal(im_indentation_step(run, -1.5, &r), IM_EINVAL);
    /* a wide, weak zone on a small surface: it reaches the surface's edge */
    o.adhesion_work = 0.5;
    o.adhesion_range = 20;
    im_indentation_free(run);
    assert_int_equal(im_indentation_create(surface, &sphere, IM_CONTROL_DISPLACEMENT, 1, &o, &run), IM_OK);
    assert_int_equal(im_indentation_step(run, 1, &r), IM_EEDGE);
    assert_non_null(strstr(im_last_error(), "adhesive zone reached the edge"));
    im_indentation_free(run);
    im_field_free(surface);
}

/* The zone length and Maugis's lambda of the sphere cases above, from their definitions. */
static void zone_length_and_lambda(void **state)
{
    (void)state;
    const sphere_case c = sphere_case_make(3.0, 10);
    im_solver_options o = im_solver_options_default();
    o.adhesion_work = c.work;
    o.adhesion_range = c.range;
    assert_close(im_adhesion_maugis_lambda(&o, c.radius), 3.0, 1e-12);
    assert_close(im_adhesion_zone_length(&o), M_PI * c.work / (8 * c.stress * c.stress), 1e-12);
    o.adhesion_work = 0;
    assert_true(isnan(im_adhesion_zone_length(&o)) && isnan(im_adhesion_maugis_lambda(&o, 1)));
}

/* The summary of a hand-made history: approach without contact, a jump into contact at w = 2, a
 * retraction pulling 2 at w = 1 and separating below it; the loop's trapezoids add up to 2. */
static void summary_of_a_loop(void **state)
{
    (void)state;
    const double w[] = {0, 1, 2, 1, 0}, n[] = {0, 0, -1, -2, 0};
    const long contact[] = {0, 0, 5, 5, 0};
    im_adhesion_summary s;
    assert_int_equal(im_measure_adhesion(w, n, contact, 5, &s), IM_OK);
    assert_true(s.pull_off_force == 2 && s.pull_off_approach == 1);
    assert_true(s.jump_in_approach == 2 && s.jump_out_approach == 1);
    assert_close(s.hysteresis_work, 2.0, 1e-15);
    const double none[] = {0, 1};
    const long touching[] = {1, 2};
    assert_int_equal(im_measure_adhesion(w, none, touching, 2, &s), IM_OK);
    assert_true(isnan(s.pull_off_force) && isnan(s.jump_in_approach) && isnan(s.jump_out_approach));
    const double broken[] = {0, NAN};
    assert_int_equal(im_measure_adhesion(broken, n, contact, 2, &s), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "step 2"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(reference_reaches_dmt_and_jkr),
        cmocka_unit_test(sphere_follows_maugis_dugdale),
        cmocka_unit_test(approach_and_retraction_differ),
        cmocka_unit_test(vanishing_work_is_repulsive),
        cmocka_unit_test(step_sums_are_the_fields),
        cmocka_unit_test(refusals),
        cmocka_unit_test(zone_length_and_lambda),
        cmocka_unit_test(summary_of_a_loop),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
