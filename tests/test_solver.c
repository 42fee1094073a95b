/* The contact solver against closed forms (Love's cone, Hertz, the flat punch), against a direct
 * convolution, and against itself (load vs displacement control, threads, cropping), plus its
 * refusals. Grids are at most 256^2 so that the program stays fast under the sanitizers. */
#include "support.h"

#include "indentmap/indenter.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"

#include <math.h>
#include <omp.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>

static im_field *smooth_surface(int n)
{
    im_field *s = NULL;
    assert_int_equal(im_field_create(n, n, 1.0, &s), IM_OK);
    return s;
}

static im_indentation *prepare(const im_field *s, const im_indenter *punch, enum im_control control, double largest,
                               const im_solver_options *o)
{
    im_indentation *run = NULL;
    im_solver_options tight = im_solver_options_default();
    tight.tol = 1e-8; /* without options: the tolerance this file's closed-form bars were set at */
    int status = im_indentation_create(s, punch, control, largest, o ? o : &tight, &run);
    if (status != IM_OK)
        fail_msg("im_indentation_create: %s", im_last_error());
    return run;
}

static im_step_result step(im_indentation *run, double target)
{
    im_step_result r;
    int status = im_indentation_step(run, target, &r);
    if (status != IM_OK)
        fail_msg("step %g: %s", target, im_last_error());
    return r;
}

/* ---- the influence kernel and the linear (non-periodic) convolution ---- */

static void test_influence_kernel(void **state)
{
    (void)state;
    /* centre: (1 / pi E*) 4 delta asinh(1); far away: a point force delta^2 / (pi E* r) */
    assert_close(im_influence_square(0, 0, 2.0, 3.0), 4 * 2.0 * asinh(1.0) / (M_PI * 3.0), 1e-15);
    double far = im_influence_square(300, 400, 1.0, 1.0);
    assert_close(far / (1.0 / (M_PI * 500)), 1, 1e-6);
    /* a neighbour, against midpoint quadrature of the smooth integrand 1/r over the patch */
    const int m = 1000;
    double sum = 0;
    for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i) {
            /* the point (1, 0) minus a point of the unit patch centred at the origin */
            double x = 1 - (-0.5 + (i + 0.5) / m), y = -(-0.5 + (j + 0.5) / m);
            sum += 1 / hypot(x, y) / ((double)m * m);
        }
    assert_close(im_influence_square(1, 0, 1, 1) * M_PI, sum, 1e-6);
}

/* The largest relative difference between u and the direct sum of K p (E* = 1) on an nx x ny grid. */
static double direct_sum_difference(int nx, int ny, double delta, const double *p, const double *u)
{
    double worst = 0;
    for (int iy = 0; iy < ny; ++iy)
        for (int ix = 0; ix < nx; ++ix) {
            double direct = 0;
            for (int jy = 0; jy < ny; ++jy)
                for (int jx = 0; jx < nx; ++jx)
                    direct += p[jy * nx + jx] * im_influence_square((ix - jx) * delta, (iy - jy) * delta, delta, 1.0);
            worst = fmax(worst, fabs(u[iy * nx + ix] - direct) / direct);
        }
    return worst;
}

static void test_convolution_is_linear_not_periodic(void **state)
{
    (void)state;
    const int nx = 13, ny = 9;
    im_solver_plan *plan = NULL;
    assert_int_equal(im_solver_plan_create(nx, ny, 0.5, NULL, &plan), IM_OK);
    double p[13 * 9], u[13 * 9];
    for (int i = 0; i < nx * ny; ++i)
        p[i] = (double)((i * 7919) % 17) / 17.0;
    im_solver_convolve(plan, p, u);
    double worst = direct_sum_difference(nx, ny, 0.5, p, u);
    if (worst > 1e-12)
        fail_msg("FFT convolution differs from direct summation by %g (relative)", worst);
    im_solver_plan_free(plan);
}

/* A plan solves under displacement or load control only; a mean gap is refused naming the function, the
 * control and the ones it takes (redteam5 P3: the message was "control 2: expected displacement or load"). */
static void test_solve_refuses_mean_gap_control_by_name(void **state)
{
    (void)state;
    im_solver_plan *plan = NULL;
    assert_int_equal(im_solver_plan_create(8, 8, 1.0, NULL, &plan), IM_OK);
    double gap0[64], p[64], u[64];
    for (int i = 0; i < 64; ++i)
        gap0[i] = 1.0;
    im_solve_result result;
    assert_int_equal(im_solver_solve(plan, gap0, IM_CONTROL_MEAN_GAP, 0.5, p, u, &result), IM_EINVAL);
    const char *message = im_last_error();
    if (!strstr(message, "im_solver_solve: control = 2") || !strstr(message, "IM_CONTROL_LOAD"))
        fail_msg("message '%s' does not name im_solver_solve, the control and the ones it takes", message);
    im_solver_plan_free(plan);
}

/* A convolution's plan (im_displacement_plan_create: no solver arrays, its result written back over its
 * input rows) against the direct sum, in place, twice: the second load, nonzero in one corner only, is
 * convolved after the first result filled the padded rows. */
static void test_convolution_plan_in_place(void **state)
{
    (void)state;
    const int nx = 11, ny = 14;
    im_solver_plan *plan = NULL;
    assert_int_equal(im_displacement_plan_create(nx, ny, 0.25, NULL, &plan), IM_OK);
    double p[11 * 14], u[11 * 14];
    for (int load = 0; load < 2; ++load) {
        for (int i = 0; i < nx * ny; ++i)
            p[i] = load == 0 ? (double)((i * 7919) % 13) / 13.0 + 0.1 : (i % nx < 3 && i / nx < 2);
        memcpy(u, p, sizeof p);
        im_solver_convolve(plan, u, u);
        double worst = direct_sum_difference(nx, ny, 0.25, p, u);
        if (worst > 1e-12)
            fail_msg("load %d: the convolution's plan differs from direct summation by %g (relative)", load, worst);
    }
    im_solver_plan_free(plan);
}

/* ---- closed forms ---- */

static void test_cone_love(void **state)
{
    (void)state;
    im_field *s = smooth_surface(256);
    im_indenter cone = im_indenter_cone(80);
    im_indentation *run = prepare(s, &cone, IM_CONTROL_DISPLACEMENT, 16, NULL);
    int checked_area = 0;
    for (int k = 1; k <= 10; ++k) {
        double w = 1.6 * k;
        im_step_result r = step(run, w);
        double love = im_indenter_load(&cone, 1.0, w);
        if (r.contact_patches > 1000) {
            if (fabs(r.load / love - 1) > 0.005)
                fail_msg("w = %g: N = %g, Love %g (%.3f%%)", w, r.load, love, 100 * (r.load / love - 1));
            /* n_p delta^2 against A_cone: the discrete contact extends ~0.1 delta beyond a (patches
             * straddling the edge carry force), i.e. +0.3 to +0.9% for 1000 < n_p < 8000 on this
             * grid; below 0.5% from n_p ~ 8000 (see docs/solver.md). */
            double limit = r.contact_patches > 8000 ? 0.005 : 0.01;
            if (fabs(r.area_ratio - 1) > limit)
                fail_msg("w = %g: n_p = %ld, area ratio %g beyond %g", w, r.contact_patches, r.area_ratio, limit);
            assert_close(r.load_star / r.contact_patches, 1, limit);
            checked_area += r.contact_patches > 8000;
        }
        assert_true(r.residual <= 1e-8);
    }
    assert_true(checked_area >= 2);
    /* pressure profile of the last step against p_m acosh(a / r), away from apex and edge */
    im_field *force = NULL;
    assert_int_equal(im_indentation_fields(run, &force, NULL, NULL), IM_OK);
    double a = im_indenter_contact_radius(&cone, 16), ax, ay, worst = 0;
    im_indenter_axis(&cone, 256, 256, 1.0, &ax, &ay);
    for (int iy = 0; iy < 256; ++iy)
        for (int ix = 0; ix < 256; ++ix) {
            double r = hypot(ix + 0.5 - ax, iy + 0.5 - ay);
            if (r < 0.2 * a || r > 0.8 * a)
                continue;
            double exact = im_indenter_pressure(&cone, 1.0, 16, r);
            worst = fmax(worst, fabs(force->data[iy * 256 + ix] - exact) / exact);
        }
    if (worst > 1e-3) /* measured: 5e-5 at a = 58 */
        fail_msg("cone pressure differs from p_m acosh(a/r) by %g (relative) for 0.2a < r < 0.8a", worst);
    im_field_free(force);
    im_indentation_free(run);
    im_field_free(s);
}

static void test_sphere_hertz(void **state)
{
    (void)state;
    im_field *s = smooth_surface(128);
    im_indenter sphere = im_indenter_sphere(1000);
    const double w = 1.2; /* a = sqrt(R w) ~ 34.6 */
    im_indentation *run = prepare(s, &sphere, IM_CONTROL_DISPLACEMENT, w, NULL);
    im_step_result r = step(run, w);
    double n = im_indenter_load(&sphere, 1, w), a = im_indenter_contact_radius(&sphere, w);
    double p0 = im_indenter_pressure(&sphere, 1, w, 0);
    /* measured: load 5e-5, radius 3e-3 (lattice count), peak 5e-5 */
    if (fabs(r.load / n - 1) > 1e-3)
        fail_msg("Hertz load: %g vs %g", r.load, n);
    if (fabs(sqrt(r.contact_patches / M_PI) / a - 1) > 0.01)
        fail_msg("Hertz radius: sqrt(n_p / pi) = %g vs a = %g", sqrt(r.contact_patches / M_PI), a);
    if (fabs(r.max_pressure / p0 - 1) > 1e-3)
        fail_msg("Hertz peak pressure: %g vs p0 = %g", r.max_pressure, p0);
    im_indentation_free(run);
    im_field_free(s);
}

static void test_flat_punch(void **state)
{
    (void)state;
    im_field *s = smooth_surface(96);
    im_indenter flat = im_indenter_flat(20);
    const double w = 0.5;
    im_indentation *run = prepare(s, &flat, IM_CONTROL_DISPLACEMENT, w, NULL);
    im_step_result r = step(run, w);
    /* the face is the patches whose centres lie within a: compare with the disc of equal area */
    double a_eq = sqrt(r.contact_patches / M_PI);
    double n = 2 * a_eq * w;
    if (fabs(r.load / n - 1) > 0.01) /* measured: -0.5%, the staircase edge of the discrete face */
        fail_msg("flat punch: N = %g vs 2 a E* w = %g (n_p = %ld, a_eq = %g)", r.load, n, r.contact_patches, a_eq);
    im_field *force = NULL;
    assert_int_equal(im_indentation_fields(run, &force, NULL, NULL), IM_OK);
    double ax, ay, worst = 0;
    im_indenter_axis(&flat, 96, 96, 1.0, &ax, &ay);
    for (int i = 0; i < 96 * 96; ++i) {
        double rr = hypot(i % 96 + 0.5 - ax, i / 96 + 0.5 - ay);
        if (rr > 0.6 * a_eq)
            continue;
        double exact = r.load / (2 * M_PI * a_eq * sqrt(a_eq * a_eq - rr * rr));
        worst = fmax(worst, fabs(force->data[i] - exact) / exact);
    }
    if (worst > 0.02) /* measured: 1.5% */
        fail_msg("flat punch pressure differs from N / (2 pi a sqrt(a^2 - r^2)) by %g for r < 0.6 a", worst);
    im_field_free(force);
    im_indentation_free(run);
    im_field_free(s);
}

/* ---- consistency ---- */

static void assert_complementarity(const im_indentation *run, double w)
{
    im_field *f = NULL, *g = NULL;
    assert_int_equal(im_indentation_fields(run, &f, &g, NULL), IM_OK);
    double load = 0, work = 0, worst_gap = 0;
    for (size_t i = 0; i < im_field_count(f); ++i) {
        assert_true(f->data[i] >= 0);
        load += f->data[i];
        work += f->data[i] * fabs(g->data[i]);
        worst_gap = fmin(worst_gap, g->data[i]);
    }
    if (-worst_gap > 1e-7 * w)
        fail_msg("gap %g < 0 beyond the tolerance at w = %g", worst_gap, w);
    if (work / (load * w) > 1e-7)
        fail_msg("force x gap = %g relative to N w", work / (load * w));
    im_field_free(f);
    im_field_free(g);
}

static void test_load_matches_displacement_control(void **state)
{
    (void)state;
    im_field *s = test_rough_surface(128, 0.08, 3);
    im_indenter cone = im_indenter_cone(80);
    im_indentation *d = prepare(s, &cone, IM_CONTROL_DISPLACEMENT, 8, NULL);
    step(d, 4);
    im_step_result rd = step(d, 8);
    assert_complementarity(d, 8);
    im_indentation *l = prepare(s, &cone, IM_CONTROL_LOAD, rd.load, NULL);
    step(l, 0.5 * rd.load);
    im_step_result rl = step(l, rd.load);
    assert_complementarity(l, rl.approach);
    assert_close(rl.load, rd.load, 1e-10 * rd.load);
    assert_close(rl.approach, 8, 1e-6 * 8);
    assert_int_equal(rl.contact_patches, rd.contact_patches);
    im_indentation_free(d);
    im_indentation_free(l);
    im_field_free(s);
}

static im_step_result run_with_threads(const im_field *s, int threads, int crop, im_field **force, im_window *window)
{
    int saved = omp_get_max_threads();
    omp_set_num_threads(threads);
    im_indenter cone = im_indenter_cone(80);
    im_solver_options o = im_solver_options_default();
    o.tol = 1e-8; /* the bars below were set at tol 1e-8 (not the default, 1e-6) */
    o.crop = crop;
    im_indentation *run = prepare(s, &cone, IM_CONTROL_DISPLACEMENT, 10, &o);
    step(run, 5);
    im_step_result r = step(run, 10);
    assert_int_equal(im_indentation_fields(run, force, NULL, NULL), IM_OK);
    *window = im_indentation_window(run);
    im_indentation_free(run);
    omp_set_num_threads(saved);
    return r;
}

static void assert_same_solution(im_step_result a, const im_field *fa, im_step_result b, const im_field *fb)
{
    assert_close(a.load, b.load, 1e-7 * a.load);
    double peak = 0, worst = 0;
    long differing = 0;
    for (size_t i = 0; i < im_field_count(fa); ++i) {
        peak = fmax(peak, fa->data[i]);
        worst = fmax(worst, fabs(fa->data[i] - fb->data[i]));
        differing += (fa->data[i] > 0) != (fb->data[i] > 0);
    }
    if (worst > 1e-6 * peak)
        fail_msg("forces differ by %g (peak %g)", worst, peak);
    if (differing > 0) /* only patches whose force is at round-off level could flip */
        fail_msg("%ld patches in contact in one solution only (n_p %ld vs %ld)", differing, a.contact_patches,
                 b.contact_patches);
}

static void test_thread_count_independence(void **state)
{
    (void)state;
    im_field *s = test_rough_surface(128, 0.08, 5), *f1 = NULL, *f2 = NULL;
    im_window w1, w2;
    im_step_result one = run_with_threads(s, 1, 1, &f1, &w1), two = run_with_threads(s, 2, 1, &f2, &w2);
    assert_same_solution(one, f1, two, f2);
    im_field_free(f1);
    im_field_free(f2);
    im_field_free(s);
}

/* Plans made for two threads, solved by a team of one and by a team of two (core/team_size.c picks a
 * solve's team from the free cores): the same bits, for a cold cone and a periodic cell. */
static im_indentation *cone_planned_for_two(const im_field *s)
{
    im_indenter cone = im_indenter_cone(80);
    omp_set_num_threads(2);
    return prepare(s, &cone, IM_CONTROL_DISPLACEMENT, 10, NULL);
}

static im_field *cone_force_with_team(const im_field *s, int team, double *load)
{
    im_indentation *run = cone_planned_for_two(s);
    im_field *force = NULL;
    omp_set_num_threads(team);
    *load = step(run, 10).load;
    assert_int_equal(im_indentation_fields(run, &force, NULL, NULL), IM_OK);
    im_indentation_free(run);
    return force;
}

static double *periodic_pressure_with_team(const im_field *s, int team, double *approach)
{
    im_flat_contact *run = NULL;
    im_flat_result r;
    omp_set_num_threads(2);
    assert_int_equal(im_flat_contact_create(s, NULL, &run), IM_OK);
    omp_set_num_threads(team);
    assert_int_equal(im_flat_contact_solve(run, 0.004, &r), IM_OK);
    *approach = r.approach;
    double *pressure = malloc(sizeof(double) * im_field_count(s));
    memcpy(pressure, im_flat_contact_pressure(run), sizeof(double) * im_field_count(s));
    im_flat_contact_free(run);
    return pressure;
}

static void test_team_size_independence(void **state)
{
    (void)state;
    const int saved = omp_get_max_threads();
    im_field *s = test_rough_surface(128, 0.08, 5);
    double load1, load2, approach1, approach2;
    im_field *f1 = cone_force_with_team(s, 1, &load1), *f2 = cone_force_with_team(s, 2, &load2);
    assert_memory_equal(&load1, &load2, sizeof load1);
    assert_memory_equal(f1->data, f2->data, sizeof(double) * im_field_count(f1));
    double *p1 = periodic_pressure_with_team(s, 1, &approach1), *p2 = periodic_pressure_with_team(s, 2, &approach2);
    assert_memory_equal(&approach1, &approach2, sizeof approach1);
    assert_memory_equal(p1, p2, sizeof(double) * im_field_count(s));
    omp_set_num_threads(saved);
    free(p1);
    free(p2);
    im_field_free(f1);
    im_field_free(f2);
    im_field_free(s);
}

static void test_cropped_window_equals_full_grid(void **state)
{
    (void)state;
    im_field *s = test_rough_surface(160, 0.08, 7), *fc = NULL, *ff = NULL;
    im_window wc, wf;
    im_step_result cropped = run_with_threads(s, omp_get_max_threads(), 1, &fc, &wc);
    im_step_result full = run_with_threads(s, omp_get_max_threads(), 0, &ff, &wf);
    assert_true(wc.nx < s->nx && wc.ny < s->ny);
    assert_true(wf.nx == s->nx && wf.ny == s->ny && wf.x0 == 0 && wf.y0 == 0);
    assert_same_solution(cropped, fc, full, ff);
    im_field_free(fc);
    im_field_free(ff);
    im_field_free(s);
}

/* The default solver (cascade cold starts, preconditioned steps) against plain Polonsky-Keer on a
 * rough cone at tol 1e-10: a cold solve and a warm-started history, under each control. Loads agree
 * to the tolerance and the contact sets are identical; the cold solve went through the coarse grids
 * and the warm steps did not. */
static void compare_with_plain_pk(enum im_control control, const double *targets, int steps)
{
    im_field *s = test_rough_surface(256, 0.08, 11);
    im_indenter cone = im_indenter_cone(80);
    im_solver_options fast = im_solver_options_default(), plain = fast;
    fast.tol = plain.tol = 1e-10;
    plain.cascade = plain.precondition = 0;
    im_indentation *a = prepare(s, &cone, control, targets[steps - 1], &fast);
    im_indentation *b = prepare(s, &cone, control, targets[steps - 1], &plain);
    for (int k = 0; k < steps; ++k) {
        im_step_result ra = step(a, targets[k]), rb = step(b, targets[k]);
        if (k == 0)
            assert_true(ra.coarse_iterations > 0);
        else
            assert_int_equal(ra.coarse_iterations, 0);
        assert_int_equal(rb.coarse_iterations, 0);
        im_field *fa = NULL, *fb = NULL;
        assert_int_equal(im_indentation_fields(a, &fa, NULL, NULL), IM_OK);
        assert_int_equal(im_indentation_fields(b, &fb, NULL, NULL), IM_OK);
        assert_close(ra.load, rb.load, 1e-9 * rb.load);
        assert_close(ra.approach, rb.approach, 1e-9 * rb.approach);
        assert_same_solution(ra, fa, rb, fb);
        im_field_free(fa);
        im_field_free(fb);
    }
    im_indentation_free(a);
    im_indentation_free(b);
    im_field_free(s);
}

static void test_accelerated_equals_plain_pk_displacement(void **state)
{
    (void)state;
    /* w = pi a cot(alpha) / 2 for a smooth contact radius a = 256 / 5 */
    const double w = M_PI * 51.2 / (2 * tan(80 * M_PI / 180)), targets[3] = {w, 1.1 * w, 1.2 * w};
    compare_with_plain_pk(IM_CONTROL_DISPLACEMENT, targets, 3);
}

static void test_accelerated_equals_plain_pk_load(void **state)
{
    (void)state;
    im_indenter cone = im_indenter_cone(80);
    const double w = M_PI * 51.2 / (2 * tan(80 * M_PI / 180)), n = im_indenter_load(&cone, 1, w);
    const double targets[3] = {0.6 * n, 0.8 * n, n};
    compare_with_plain_pk(IM_CONTROL_LOAD, targets, 3);
}

/* u on the whole grid, for what is written or drawn: from the cropped run's force it matches the
 * displacement of the same contact solved on the whole grid (crop off, an independent solve), and
 * far from the contact Boussinesq's point load u = N / (pi E* r); the window's own u is 0 outside
 * the window (the step that deformed-surface frames showed). */
static void test_full_grid_displacement(void **state)
{
    (void)state;
    im_field *s = test_rough_surface(96, 0.08, 3), *fc = NULL, *uc = NULL, *uf = NULL, *full = NULL;
    im_indenter cone = im_indenter_cone(80.0);
    im_solver_options o = im_solver_options_default();
    o.tol = 1e-8; /* the bars below were set at tol 1e-8 (not the default, 1e-6) */
    o.tol = 1e-10;
    im_indentation *cropped = prepare(s, &cone, IM_CONTROL_DISPLACEMENT, 1.5, &o);
    im_step_result r = step(cropped, 1.5);
    assert_int_equal(im_indentation_fields(cropped, &fc, NULL, &uc), IM_OK);
    im_window w = im_indentation_window(cropped);
    assert_true(w.x0 > 0 && w.y0 > 0);
    assert_int_equal(im_displacement_full(fc, &o, &full), IM_OK);
    o.crop = 0;
    im_indentation *whole = prepare(s, &cone, IM_CONTROL_DISPLACEMENT, 1.5, &o);
    step(whole, 1.5);
    assert_int_equal(im_indentation_fields(whole, NULL, NULL, &uf), IM_OK);
    double peak = 0, worst = 0;
    for (size_t i = 0; i < im_field_count(uf); ++i) {
        peak = fmax(peak, uf->data[i]);
        worst = fmax(worst, fabs(full->data[i] - uf->data[i]));
    }
    if (worst > 1e-6 * peak)
        fail_msg("full-grid u differs from the uncropped solve's by %g (peak %g)", worst, peak);
    assert_true(uc->data[0] == 0.0); /* the corner is outside the window: the window's u is 0 there */
    double cx = w.x0 + 0.5 * w.nx, cy = w.y0 + 0.5 * w.ny, r0 = hypot(0.5 - cx, 0.5 - cy);
    assert_close(full->data[0], r.load / (M_PI * o.e_star * r0), 0.05 * r.load / (M_PI * o.e_star * r0));
    im_indentation_free(cropped);
    im_indentation_free(whole);
    im_field_free(fc);
    im_field_free(uc);
    im_field_free(uf);
    im_field_free(full);
    im_field_free(s);
}

/* Without a crop the window is the whole grid and the whole grid's u is convolved on the run's own
 * (estimated) solver plan: to the bit what a convolution's plan gives for the same force, and the gap
 * g0 - w + u with that u (on a flat surface g0 is the cone's height less its lowest on the grid). */
static void test_full_grid_displacement_on_solver_plan(void **state)
{
    (void)state;
    im_field *s = smooth_surface(48), *f = NULL, *g = NULL, *u = NULL, *again = NULL;
    im_indenter cone = im_indenter_cone(80.0);
    im_solver_options o = im_solver_options_default();
    o.crop = 0;
    im_indentation *run = prepare(s, &cone, IM_CONTROL_DISPLACEMENT, 2.0, &o);
    step(run, 2.0);
    assert_int_equal(im_indentation_fields_full(run, &f, &g, &u), IM_OK);
    assert_int_equal(im_displacement_full(f, &o, &again), IM_OK);
    if (memcmp(u->data, again->data, sizeof(double) * im_field_count(u)) != 0)
        fail_msg("u on the solver's plan differs from a convolution plan's");
    double ax, ay, lowest = INFINITY, worst = 0;
    im_indenter_axis(&cone, 48, 48, 1.0, &ax, &ay);
    for (int i = 0; i < 48 * 48; ++i)
        lowest = fmin(lowest, im_indenter_height(&cone, i % 48 + 0.5 - ax, i / 48 + 0.5 - ay));
    for (int i = 0; i < 48 * 48; ++i) {
        const double g0 = im_indenter_height(&cone, i % 48 + 0.5 - ax, i / 48 + 0.5 - ay) - lowest;
        worst = fmax(worst, fabs(g->data[i] - (g0 - 2.0 + u->data[i])));
    }
    if (worst > 1e-12)
        fail_msg("g differs from g0 - w + u by %g", worst);
    im_field *fields[] = {s, f, g, u, again};
    for (int k = 0; k < 5; ++k)
        im_field_free(fields[k]);
    im_indentation_free(run);
}

/* A convolution's plan estimated before it is made (im_displacement_memory_needed: scenes' limits) is the
 * plan as made (im_solver_plan_memory), half-space and periodic, under a solve's options whose cascade and
 * preconditioner it drops; below the solver plan's estimate of the same grid, which scenes counted for it. */
static void test_convolution_plan_estimated_as_made(void **state)
{
    (void)state;
    const int sides[][2] = {{64, 64}, {96, 40}, {200, 128}};
    for (int k = 0; k < 3; ++k)
        for (int periodic = 0; periodic < 2; ++periodic) {
            im_solver_options o = im_solver_options_default();
            o.periodic = periodic;
            im_solver_memory estimated, made, solver;
            im_solver_plan *plan = NULL;
            assert_int_equal(im_displacement_memory_needed(sides[k][0], sides[k][1], &o, &estimated), IM_OK);
            assert_int_equal(im_displacement_plan_create(sides[k][0], sides[k][1], 1.0, &o, &plan), IM_OK);
            assert_int_equal(im_solver_plan_memory(plan, &made), IM_OK);
            assert_int_equal(im_solver_memory_needed(sides[k][0], sides[k][1], &o, &solver), IM_OK);
            if (estimated.host_bytes != made.host_bytes || !(made.host_bytes < solver.host_bytes))
                fail_msg("%d x %d periodic %d: estimated %.0f bytes, the plan %.0f, a solver plan %.0f", sides[k][0],
                         sides[k][1], periodic, estimated.host_bytes, made.host_bytes, solver.host_bytes);
            im_solver_plan_free(plan);
        }
}

/* im_indentation_window_for is the window im_indentation_create solves on, without making its plan: under
 * displacement and load control, with a cap (whose fully plastic approach widens the load's bound), and
 * with the crop off (the whole grid); a punch that covers no patch fails as the run does. */
static void test_window_for_is_the_runs(void **state)
{
    (void)state;
    im_field *s = test_rough_surface(96, 0.08, 3);
    const im_indenter cone = im_indenter_cone(80.0);
    const struct {
        enum im_control control;
        double target, hardness;
        int crop;
    } cases[] = {{IM_CONTROL_DISPLACEMENT, 1.5, 0, 1},
                 {IM_CONTROL_LOAD, 2.0, 0, 1},
                 {IM_CONTROL_LOAD, 2.0, 0.5, 1},
                 {IM_CONTROL_DISPLACEMENT, 1.5, 0, 0}};
    for (size_t k = 0; k < sizeof cases / sizeof *cases; ++k) {
        im_solver_options o = im_solver_options_default();
        o.hardness = cases[k].hardness;
        o.crop = cases[k].crop;
        im_window w;
        assert_int_equal(im_indentation_window_for(s, &cone, cases[k].control, cases[k].target, &o, &w), IM_OK);
        im_indentation *run = prepare(s, &cone, cases[k].control, cases[k].target, &o);
        const im_window made = im_indentation_window(run);
        print_message("case %zu: window [%d, %d) x [%d, %d)\n", k, w.x0, w.x0 + w.nx, w.y0, w.y0 + w.ny);
        assert_true(w.x0 == made.x0 && w.y0 == made.y0 && w.nx == made.nx && w.ny == made.ny);
        assert_true(cases[k].crop ? w.nx < 96 && w.ny < 96 : w.nx == 96 && w.ny == 96);
        im_indentation_free(run);
    }
    im_indenter away = im_indenter_flat(20);
    away.centred = 0;
    away.x0 = away.y0 = 1e6; /* far outside the surface */
    im_solver_options o = im_solver_options_default();
    im_window w = {1, 1, 1, 1};
    assert_int_equal(im_indentation_window_for(s, &away, IM_CONTROL_DISPLACEMENT, 1.0, &o, &w), IM_EINVAL);
    assert_int_equal(w.nx, 0);
    im_field_free(s);
}

/* Each displacement-controlled step is solved on the box its approach can touch (solver/step_window.h),
 * inside the run's window: a history that rises (boxes replanned as they grow), falls (a smaller approach
 * in the same box) and rises again, against the same history solved on the whole surface (crop off, no
 * boxes), at tol 1e-10: loads to 1e-9, the same contact sets, and u and g inside the window (u outside
 * the last box is recomputed when the fields are asked for; the full grid's g too). With a hardness, the plastic memory too. */
static void assert_same_fields_in_window(im_indentation *boxed, im_indentation *whole)
{
    im_field *fb = NULL, *gb = NULL, *ub = NULL, *fw = NULL, *gw = NULL, *uw = NULL;
    assert_int_equal(im_indentation_fields(boxed, &fb, &gb, &ub), IM_OK);
    assert_int_equal(im_indentation_fields(whole, &fw, &gw, &uw), IM_OK);
    const im_window w = im_indentation_window(boxed);
    double peak = 0, worst_u = 0, worst_g = 0;
    long differing = 0;
    for (int iy = w.y0; iy < w.y0 + w.ny; ++iy)
        for (int ix = w.x0; ix < w.x0 + w.nx; ++ix) {
            const size_t i = (size_t)iy * fb->nx + ix;
            peak = fmax(peak, uw->data[i]);
            worst_u = fmax(worst_u, fabs(ub->data[i] - uw->data[i]));
            worst_g = fmax(worst_g, fabs(gb->data[i] - gw->data[i]));
            differing += (fb->data[i] > 0) != (fw->data[i] > 0);
        }
    if (worst_u > 1e-8 * peak || worst_g > 1e-8 * peak)
        fail_msg("u differs by %g and g by %g in the window (peak u %g)", worst_u, worst_g, peak);
    if (differing > 0)
        fail_msg("%ld patches in contact in one history only", differing);
    im_field *fields[] = {fb, gb, ub, fw, gw, uw};
    for (int k = 0; k < 6; ++k)
        im_field_free(fields[k]);
    assert_int_equal(im_indentation_fields_full(boxed, NULL, &gb, NULL), IM_OK);
    assert_int_equal(im_indentation_fields_full(whole, NULL, &gw, NULL), IM_OK);
    worst_g = 0;
    for (size_t i = 0; i < im_field_count(gb); ++i)
        worst_g = fmax(worst_g, fabs(gb->data[i] - gw->data[i]));
    if (worst_g > 1e-8 * peak)
        fail_msg("the full grid's g differs by %g (peak u %g)", worst_g, peak);
    im_field_free(gb);
    im_field_free(gw);
}

static void assert_same_plastic_depth(const im_indentation *boxed, const im_indentation *whole)
{
    im_field *a = NULL, *b = NULL;
    assert_int_equal(im_indentation_plastic(boxed, &a), IM_OK);
    assert_int_equal(im_indentation_plastic(whole, &b), IM_OK);
    double peak = 0, worst = 0;
    for (size_t i = 0; i < im_field_count(a); ++i) {
        peak = fmax(peak, b->data[i]);
        worst = fmax(worst, fabs(a->data[i] - b->data[i]));
    }
    if (worst > 1e-8 * peak)
        fail_msg("plastic depths differ by %g (peak %g)", worst, peak);
    im_field_free(a);
    im_field_free(b);
}

static void compare_boxed_history(double hardness)
{
    im_field *s = test_rough_surface(192, 0.08, 13);
    im_indenter cone = im_indenter_cone(80);
    im_solver_options o = im_solver_options_default();
    o.tol = 1e-10;
    o.hardness = hardness;
    im_indentation *boxed = prepare(s, &cone, IM_CONTROL_DISPLACEMENT, 6, &o);
    o.crop = 0;
    im_indentation *whole = prepare(s, &cone, IM_CONTROL_DISPLACEMENT, 6, &o);
    const double targets[] = {0.4, 1.2, 2.5, 4, 6, 3, 0.8, 5};
    long yielded = 0;
    for (size_t k = 0; k < sizeof targets / sizeof *targets; ++k) {
        im_step_result rb = step(boxed, targets[k]), rw = step(whole, targets[k]);
        assert_close(rb.load, rw.load, 1e-9 * rw.load);
        assert_int_equal(rb.contact_patches, rw.contact_patches);
        assert_same_fields_in_window(boxed, whole);
        yielded += rb.yielding_patches;
        if (hardness > 0) {
            assert_close(rb.plastic_work, rw.plastic_work, 1e-8 * rw.plastic_work);
            assert_same_plastic_depth(boxed, whole);
        }
    }
    assert_true(hardness > 0 ? yielded > 0 : yielded == 0);
    im_indentation_free(boxed);
    im_indentation_free(whole);
    im_field_free(s);
}

static void test_step_boxes_equal_whole_surface(void **state)
{
    (void)state;
    compare_boxed_history(0);
}

static void test_step_boxes_keep_plastic_memory(void **state)
{
    (void)state;
    compare_boxed_history(0.25);
}

/* ---- refusals, with nothing computed lost ---- */

/* The stopping rule bounds both halves of the complementarity conditions: the rms gap over the
 * contact set AND the penetration of patches outside it, each relative to w. A solve that stops on
 * the first alone leaves patches inside the punch. Checked on the solution's own fields, for a rough
 * cone in both controls, at a loose tolerance where the two halves part. */
static void assert_penetration_within_tol(const im_field *force, const im_field *gap, double w, double tol)
{
    double worst = 0;
    for (size_t i = 0; i < im_field_count(gap); ++i)
        if (!(force->data[i] > 0) && -gap->data[i] > worst)
            worst = -gap->data[i];
    if (!(worst <= tol * w))
        fail_msg("a patch outside contact penetrates by %.3g > tol w = %.3g", worst, tol * w);
}

static void test_stopping_rule_bounds_penetration(void **state)
{
    (void)state;
    im_field *s = test_rough_surface(128, 0.16, 3);
    im_indenter cone = im_indenter_cone(80);
    im_solver_options o = im_solver_options_default();
    o.tol = 1e-8; /* the bars below were set at tol 1e-8 (not the default, 1e-6) */
    o.tol = 3e-3;
    for (int control = 0; control <= 1; ++control) {
        double target = control == IM_CONTROL_LOAD ? 400.0 : 4.0;
        im_indentation *run = prepare(s, &cone, (enum im_control)control, target, &o);
        for (int k = 1; k <= 4; ++k) {
            im_step_result r = step(run, target * k / 4);
            im_field *force = NULL, *gap = NULL;
            assert_int_equal(im_indentation_fields(run, &force, &gap, NULL), IM_OK);
            assert_penetration_within_tol(force, gap, r.approach, o.tol);
            im_field_free(force);
            im_field_free(gap);
        }
        im_indentation_free(run);
    }
    im_field_free(s);
}

static void test_edge_contact(void **state)
{
    (void)state;
    im_field *s = smooth_surface(48);
    im_indenter cone = im_indenter_cone(80);
    im_indentation *run = prepare(s, &cone, IM_CONTROL_DISPLACEMENT, 8, NULL);
    im_step_result first = step(run, 2), r;
    assert_true(first.contact_patches > 0);
    assert_int_equal(im_indentation_step(run, 8, &r), IM_EEDGE); /* a(8) = 29 > 24 */
    assert_non_null(strstr(im_last_error(), "edge"));
    im_indentation_free(run);
    im_field_free(s);
}

static void test_no_convergence(void **state)
{
    (void)state;
    im_field *s = test_rough_surface(64, 0.08, 2);
    im_indenter cone = im_indenter_cone(80);
    im_solver_options o = im_solver_options_default();
    o.tol = 1e-8; /* the bars below were set at tol 1e-8 (not the default, 1e-6) */
    o.max_iterations = 3;
    o.tol = 1e-14;
    im_indentation *run = prepare(s, &cone, IM_CONTROL_DISPLACEMENT, 4, &o);
    im_step_result r;
    assert_int_equal(im_indentation_step(run, 4, &r), IM_ENOCONV);
    assert_int_equal(r.iterations, 3);
    assert_true(r.residual > 1e-14);
    assert_non_null(strstr(im_last_error(), "cap"));
    im_indentation_free(run);
    im_field_free(s);
}

/* The least tolerance, 1e-15, is at double precision's rounding of the gaps on a 128^2 periodic cell:
 * each solve reaches it, or stops with "no convergence" naming the rounding within a few hundred
 * iterations: never a numeric failure (p_m 0.01 and 0.03: the centred step length came out negative
 * at iteration 34 and 37), never the iteration cap (p_m 0.1: 10000 iterations); and a tol below it is
 * refused when the plan is made. */
static void test_tolerance_at_the_rounding(void **state)
{
    (void)state;
    im_field *s = test_rough_surface(128, 0.08, 3);
    im_solver_options o = im_solver_options_default();
    o.tol = IM_SOLVER_TOL_MIN;
    const double pressures[] = {0.001, 0.01, 0.03, 0.1};
    int stopped = 0;
    for (size_t k = 0; k < sizeof pressures / sizeof *pressures; ++k) {
        im_flat_contact *run = NULL;
        im_flat_result r;
        assert_int_equal(im_flat_contact_create(s, &o, &run), IM_OK);
        const int status = im_flat_contact_solve(run, pressures[k], &r);
        if (status == IM_OK) {
            assert_true(r.residual <= o.tol);
        } else {
            assert_int_equal(status, IM_ENOCONV);
            assert_non_null(strstr(im_last_error(), "rounding"));
            assert_true(r.iterations < 1000);
            ++stopped;
        }
        im_flat_contact_free(run);
    }
    assert_true(stopped > 0); /* the case this test is about */
    o.tol = 0.5 * IM_SOLVER_TOL_MIN;
    im_flat_contact *refused = NULL;
    assert_int_equal(im_flat_contact_create(s, &o, &refused), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "tol = 5e-16"));
    im_field_free(s);
}

/* A cone's undeformed gap r cot(alpha) on an n x n grid of unit spacing, axis at the centre. */
static double *cone_gap(int n, double alpha_degrees)
{
    double *gap = malloc(sizeof(double) * (size_t)n * n);
    assert_non_null(gap);
    for (int iy = 0; iy < n; ++iy)
        for (int ix = 0; ix < n; ++ix)
            gap[(size_t)iy * n + ix] = hypot(ix - 0.5 * (n - 1), iy - 0.5 * (n - 1)) /
                                       tan(alpha_degrees * M_PI / 180);
    return gap;
}

/* The stop flag: a set flag ends the solve with IM_EINTERRUPTED before its first iteration, with a
 * valid iterate (p >= 0) left in pressure; the plan stays usable: once the flag is cleared, a cold
 * solve on it is bit for bit a fresh plan's, and the interrupted iterate is a warm start to the same
 * answer. Solved at tol 1e-10: at the default tol (1e-6 on the gaps) two valid answers differ in the
 * load by more than 1e-6 (warm and cold ones from the same start by 2.4e-6, the exact load between them). */
static void test_stop_flag_interrupts(void **state)
{
    (void)state;
    enum { N = 64 };
    const size_t n = (size_t)N * N;
    double *gap0 = cone_gap(N, 80), *p = calloc(n, sizeof *p), *u = calloc(n, sizeof *u);
    double *fresh_p = calloc(n, sizeof *p), *fresh_u = calloc(n, sizeof *u);
    assert_true(p && u && fresh_p && fresh_u);
    volatile sig_atomic_t stop = SIGINT;
    im_solver_options o = im_solver_options_default();
    o.tol = 1e-10;
    im_solver_options plain = o;
    o.stop = &stop;
    im_solver_plan *plan = NULL, *fresh = NULL;
    assert_int_equal(im_solver_plan_create(N, N, 1.0, &o, &plan), IM_OK);
    assert_int_equal(im_solver_plan_create(N, N, 1.0, &plain, &fresh), IM_OK);
    im_solve_result r, reference;
    assert_int_equal(im_solver_solve(plan, gap0, IM_CONTROL_DISPLACEMENT, 4.0, p, u, &r), IM_EINTERRUPTED);
    assert_int_equal(r.iterations, 0);
    assert_non_null(strstr(im_last_error(), "interrupted by signal 2"));
    for (size_t i = 0; i < n; ++i)
        assert_true(p[i] >= 0 && isfinite(p[i]));
    stop = 0;
    assert_int_equal(im_solver_solve(plan, gap0, IM_CONTROL_DISPLACEMENT, 4.0, p, u, &r), IM_OK); /* warm */
    assert_int_equal(im_solver_solve(fresh, gap0, IM_CONTROL_DISPLACEMENT, 4.0, fresh_p, fresh_u, &reference), IM_OK);
    assert_true(fabs(r.load - reference.load) <= 1e-6 * reference.load);
    memset(p, 0, sizeof(double) * n);
    assert_int_equal(im_solver_solve(plan, gap0, IM_CONTROL_DISPLACEMENT, 4.0, p, u, &r), IM_OK); /* cold */
    assert_int_equal(r.iterations, reference.iterations);
    assert_memory_equal(p, fresh_p, sizeof(double) * n);
    im_solver_plan_free(plan);
    im_solver_plan_free(fresh);
    free(gap0), free(p), free(u), free(fresh_p), free(fresh_u);
}

static void test_bad_input(void **state)
{
    (void)state;
    im_field *s = smooth_surface(32);
    im_indenter cone = im_indenter_cone(80), bad = im_indenter_cone(90);
    im_indentation *run = NULL;
    assert_int_equal(im_indentation_create(s, &bad, IM_CONTROL_DISPLACEMENT, 1, NULL, &run), IM_EINVAL);
    s->data[17] = NAN;
    assert_int_equal(im_indentation_create(s, &cone, IM_CONTROL_DISPLACEMENT, 1, NULL, &run), IM_ENUMERIC);
    s->data[17] = INFINITY;
    assert_int_equal(im_indentation_create(s, &cone, IM_CONTROL_DISPLACEMENT, 1, NULL, &run), IM_ENUMERIC);
    s->data[17] = 0;
    assert_int_equal(im_indentation_create(s, &cone, IM_CONTROL_DISPLACEMENT, NAN, NULL, &run), IM_EINVAL);
    assert_null(run);
    run = prepare(s, &cone, IM_CONTROL_DISPLACEMENT, 1, NULL);
    im_step_result r;
    assert_int_equal(im_indentation_step(run, 2, &r), IM_EINVAL); /* beyond the prepared window */
    assert_int_equal(im_indentation_step(run, -1, &r), IM_EINVAL);
    im_step_result zero = step(run, 0);
    assert_int_equal(zero.contact_patches, 0);
    assert_close(zero.load, 0, 0);
    im_indentation_free(run);
    im_solver_options o = im_solver_options_default();
    o.tol = 1e-8; /* the bars below were set at tol 1e-8 (not the default, 1e-6) */
    o.tol = 0;
    im_solver_plan *plan = NULL;
    assert_int_equal(im_solver_plan_create(8, 8, 1, &o, &plan), IM_EINVAL);
    assert_null(plan);
    im_field_free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_influence_kernel),
        cmocka_unit_test(test_convolution_is_linear_not_periodic),
        cmocka_unit_test(test_solve_refuses_mean_gap_control_by_name),
        cmocka_unit_test(test_tolerance_at_the_rounding),
        cmocka_unit_test(test_convolution_plan_in_place),
        cmocka_unit_test(test_cone_love),
        cmocka_unit_test(test_sphere_hertz),
        cmocka_unit_test(test_flat_punch),
        cmocka_unit_test(test_load_matches_displacement_control),
        cmocka_unit_test(test_thread_count_independence),
        cmocka_unit_test(test_team_size_independence),
        cmocka_unit_test(test_cropped_window_equals_full_grid),
        cmocka_unit_test(test_accelerated_equals_plain_pk_displacement),
        cmocka_unit_test(test_accelerated_equals_plain_pk_load),
        cmocka_unit_test(test_stopping_rule_bounds_penetration),
        cmocka_unit_test(test_full_grid_displacement),
        cmocka_unit_test(test_full_grid_displacement_on_solver_plan),
        cmocka_unit_test(test_convolution_plan_estimated_as_made),
        cmocka_unit_test(test_window_for_is_the_runs),
        cmocka_unit_test(test_step_boxes_equal_whole_surface),
        cmocka_unit_test(test_step_boxes_keep_plastic_memory),
        cmocka_unit_test(test_edge_contact),
        cmocka_unit_test(test_no_convergence),
        cmocka_unit_test(test_stop_flag_interrupts),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
