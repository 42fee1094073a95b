/* User-given punch profiles (indenter.h, "User-given profiles"): the interpolation and Sneddon's
 * smooth contact against the built-in punches' closed forms, the solver with a sampled cone or
 * sphere against the built-in punch, a paraboloid against Hertz, the profile files, and every
 * refusal. Grids are at most 128^2 so that the program stays fast under the sanitizers. */
#include "support.h"

#include "indentmap/indenter.h"
#include "indentmap/formats.h"
#include "indentmap/io.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "indentmap/surface.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#define MAX_SAMPLES 1024

typedef double (*shape)(double r, double parameter);

static double cone_shape(double r, double alpha_degrees) { return r / tan(alpha_degrees * M_PI / 180); }
static double paraboloid_shape(double r, double radius) { return r * r / (2 * radius); }
static double sphere_shape(double r, double radius) { return radius - sqrt(radius * radius - r * r); }

/* n samples of z(r) from 0 to r_max (z at 0 exactly 0). */
static im_profile *sampled(shape z, double parameter, double r_max, int n)
{
    double r[MAX_SAMPLES], h[MAX_SAMPLES];
    assert_true(n <= MAX_SAMPLES);
    for (int i = 0; i < n; ++i) {
        r[i] = r_max * i / (n - 1);
        h[i] = z(r[i], parameter);
    }
    im_profile *p = NULL;
    if (im_profile_axisymmetric(r, h, n, &p) != IM_OK)
        fail_msg("im_profile_axisymmetric: %s", im_last_error());
    return p;
}

static void assert_refused_naming(int status, const char *needle)
{
    assert_int_equal(status, IM_EINVAL);
    if (!strstr(im_last_error(), needle))
        fail_msg("message '%s' does not name '%s'", im_last_error(), needle);
}

/* ---- the profile itself ---- */

static void test_cone_table_is_the_cone(void **state)
{
    (void)state;
    im_profile *p = sampled(cone_shape, 80, 50, 6);
    im_indenter table = im_indenter_from_profile(p), cone = im_indenter_cone(80);
    assert_int_equal(im_indenter_check(&table), IM_OK);
    assert_int_equal(table.kind, IM_PUNCH_PROFILE);
    for (double r = 0; r <= 50; r += 0.37) /* Steffen's cubic reproduces a straight line */
        assert_close(im_indenter_profile(&table, r), im_indenter_profile(&cone, r), 1e-13);
    assert_true(isinf(im_indenter_profile(&table, 50.001)));
    assert_close(im_indenter_profile(&table, -7.5), im_indenter_profile(&cone, 7.5), 1e-13); /* a distance */
    assert_true(isnan(im_indenter_profile(&table, NAN)));
    assert_close(im_indenter_height(&table, 3, 4), im_indenter_profile(&cone, 5), 1e-13);
    /* Sneddon's integrals against Love's closed forms while the contact is inside r_max = 50 */
    for (double w = 0.05; im_indenter_contact_radius(&cone, w) < 50; w *= 1.7) {
        double n = im_indenter_load(&cone, 2.0, w);
        assert_close(im_indenter_load(&table, 2.0, w) / n, 1, 1e-6);
        assert_close(im_indenter_contact_radius(&table, w) / im_indenter_contact_radius(&cone, w), 1, 1e-6);
        assert_close(im_indenter_approach_for_load(&table, 2.0, n) / w, 1, 1e-6);
        assert_close(im_indenter_area_for_load(&table, 2.0, n) / im_indenter_area_for_load(&cone, 2.0, n), 1, 1e-6);
    }
    assert_true(isnan(im_indenter_pressure(&table, 1.0, 1.0, 0.5)));
    assert_close(im_profile_extent(p), 50, 0);
    im_profile_free(p);
}

static void test_paraboloid_table_is_hertz_then_flat(void **state)
{
    (void)state;
    const double radius = 500, r_max = 100;
    const int n = 41;
    const double h = r_max / (n - 1);
    im_profile *p = sampled(paraboloid_shape, radius, r_max, n);
    im_indenter table = im_indenter_from_profile(p), sphere = im_indenter_sphere(radius);
    /* the tolerance is the sampling's: the cubic's end slope at r = 0 is the first chord's, not 0, so a
     * contact only a few samples wide sees a blunted cone tip (measured: 5% at a = 0.9 h, 6e-5 at 4.5 h,
     * 5e-7 at 12 h); 0.1 (h / a)^2 bounds it */
    for (double w = 0.01; w < r_max * r_max / radius; w *= 1.5) {
        double a = sqrt(radius * w), tolerance = fmax(0.1 * (h / a) * (h / a), 1e-6);
        assert_close(im_indenter_load(&table, 1.0, w) / im_indenter_load(&sphere, 1.0, w), 1, tolerance);
        assert_close(im_indenter_contact_radius(&table, w) / a, 1, tolerance);
    }
    /* past full contact (w(r_max) = r_max^2 / R) it presses on as a flat punch of radius r_max */
    const double full = r_max * r_max / radius;
    double n1 = im_indenter_load(&table, 1.0, full + 1), n2 = im_indenter_load(&table, 1.0, full + 2);
    assert_close(n2 - n1, 2 * r_max, 1e-6 * n2);
    assert_close(im_indenter_contact_radius(&table, full + 1), r_max, 0);
    assert_close(im_indenter_approach_for_load(&table, 1.0, n2), full + 2, 1e-9 * n2);
    im_profile_free(p);
}

/* The sampled sphere's interpolation error shrinks as the samples are refined, at least as h^2
 * (measured 3.9-4x per halving: the largest error is in the last interval, where the cubic's end
 * slope is one-sided). */
static void test_sphere_table_converges(void **state)
{
    (void)state;
    const double radius = 100, r_max = 60;
    double previous = INFINITY;
    for (int n = 9; n <= 129; n = 2 * n - 1) {
        im_profile *p = sampled(sphere_shape, radius, r_max, n);
        im_indenter table = im_indenter_from_profile(p);
        double worst = 0;
        for (int k = 0; k < 2000; ++k) {
            double r = r_max * (k + 0.5) / 2000;
            worst = fmax(worst, fabs(im_indenter_profile(&table, r) - sphere_shape(r, radius)));
        }
        if (!(worst < previous / 3.5))
            fail_msg("%d samples: interpolation error %g, not 3.5x below %g with half as many", n, worst, previous);
        previous = worst;
        im_profile_free(p);
    }
    assert_true(previous < 1e-5 * r_max); /* measured: 3.2e-4 with 129 samples */
}

static void test_bad_samples_refused(void **state)
{
    (void)state;
    im_profile *p = NULL;
    double r[] = {0, 1, 2, 3}, z[] = {0, 0.1, 0.2, 0.3};
    assert_refused_naming(im_profile_axisymmetric(r, z, 2, &p), "2 samples");
    double r_back[] = {0, 1, 0.5, 3};
    assert_refused_naming(im_profile_axisymmetric(r_back, z, 4, &p), "sample 2");
    double r_neg[] = {0, -1, 2, 3};
    assert_refused_naming(im_profile_axisymmetric(r_neg, z, 4, &p), "sample 1");
    double r_start[] = {-1, 1, 2, 3};
    assert_refused_naming(im_profile_axisymmetric(r_start, z, 4, &p), "sample 0");
    double z_nan[] = {0, 0.1, NAN, 0.3};
    assert_refused_naming(im_profile_axisymmetric(r, z_nan, 4, &p), "sample 2");
    double z_down[] = {0, 0.1, 0.3, 0.2};
    assert_refused_naming(im_profile_axisymmetric(r, z_down, 4, &p), "sample 3");
    double z_lifted[] = {0.5, 0.6, 0.7, 0.8};
    assert_refused_naming(im_profile_axisymmetric(r, z_lifted, 4, &p), "sample 0");
    assert_null(p);
    im_indenter none = im_indenter_from_profile(NULL);
    assert_refused_naming(im_indenter_check(&none), "no profile");
    assert_int_equal(im_profile_axisymmetric(r, z, 4, &p), IM_OK);
    im_indenter wrong = im_indenter_from_profile(p);
    wrong.kind = IM_PUNCH_PROFILE_2D;
    assert_refused_naming(im_indenter_check(&wrong), "profile");
    im_profile_free(p);
}

static im_field *field_of(int nx, int ny, double delta)
{
    im_field *f = NULL;
    assert_int_equal(im_field_create(nx, ny, delta, &f), IM_OK);
    for (int i = 0; i < nx * ny; ++i)
        f->data[i] = 0.25 * (i % nx) + 1.5 * (i / nx) + 0.01 * (i % 7);
    return f;
}

static void test_field_profile(void **state)
{
    (void)state;
    im_field *f = field_of(8, 5, 2.0); /* an even side: its centre sample is 4, not 3.5 */
    im_profile *p = NULL;
    assert_int_equal(im_profile_field(f, &p), IM_OK);
    im_indenter punch = im_indenter_from_profile(p);
    assert_int_equal(punch.kind, IM_PUNCH_PROFILE_2D);
    assert_int_equal(im_indenter_check(&punch), IM_OK);
    f->data[0] = 99;               /* copied: the caller's array may change */
    for (int iy = 0; iy < 5; ++iy) /* the centre patch (4, 2) on the axis; samples read exactly */
        for (int ix = 0; ix < 8; ++ix)
            if (ix + iy > 0)
                assert_true(im_indenter_height(&punch, 2.0 * (ix - 4), 2.0 * (iy - 2)) == f->data[iy * 8 + ix]);
    /* halfway between samples (4, 2), (5, 2), (4, 3), (5, 3): the mean of the four */
    const double *z = f->data;
    assert_close(im_indenter_height(&punch, 1.0, 1.0), 0.25 * (z[20] + z[21] + z[28] + z[29]), 1e-14);
    assert_true(im_indenter_height(&punch, -8.0, -4.0) == 0.0); /* the corner as copied, not the 99 since */
    assert_true(isinf(im_indenter_height(&punch, 6.01, 0)));
    assert_true(isinf(im_indenter_height(&punch, -8.01, 0)));
    assert_true(isinf(im_indenter_height(&punch, 0, -4.01)));
    assert_true(isnan(im_indenter_load(&punch, 1.0, 1.0)) && isnan(im_indenter_area_for_load(&punch, 1.0, 1.0)));
    assert_true(isnan(im_indenter_approach_for_load(&punch, 1.0, 1.0)) && isnan(im_indenter_profile(&punch, 1.0)));
    assert_close(im_profile_extent(p), 2.0 * hypot(4, 2), 1e-14);
    im_profile_free(p);
    f->data[2 * 8 + 4] = INFINITY;
    assert_refused_naming(im_profile_field(f, &p), "(4, 2)");
    im_field *small = field_of(2, 9, 1.0);
    assert_refused_naming(im_profile_field(small, &p), "3 x 3");
    assert_null(p);
    im_field_free(small);
    im_field_free(f);
}

/* ---- files ---- */

static void write_text(const char *path, const char *text) { test_write_bytes(path, text, strlen(text)); }

static void test_profile_files(void **state)
{
    (void)state;
    const char *path = test_path("tip.csv");
    write_text(path, "r,z\n# a cone of 80 degrees\n0, 0\n\n10 1.7632698070846497\n20,\t3.5265396141692994\n");
    im_profile *p = NULL;
    if (im_profile_read(path, 1.0, &p) != IM_OK)
        fail_msg("%s", im_last_error());
    im_indenter punch = im_indenter_from_profile(p), cone = im_indenter_cone(80);
    assert_close(im_indenter_profile(&punch, 13.3), im_indenter_profile(&cone, 13.3), 1e-12);
    assert_close(im_profile_extent(p), 20, 0);
    im_profile_free(p);
    p = NULL;
    write_text(path, "r,z\n0 0\n1 0.5\n2 zero\n");
    assert_refused_naming(im_profile_read(path, 1.0, &p), "tip.csv:4");
    write_text(path, "0 0\n1 0.5 7\n");
    assert_refused_naming(im_profile_read(path, 1.0, &p), "tip.csv:2");
    write_text(path, "# header\n0 0\n1 0.5\n\n2 0.4\n3 0.6\n");
    assert_refused_naming(im_profile_read(path, 1.0, &p), "tip.csv:5"); /* z decreases at sample 2 */
    assert_refused_naming(im_profile_read(path, 1.0, &p), "sample 2");
    write_text(path, "0 0\n1 0.5\n");
    assert_refused_naming(im_profile_read(path, 1.0, &p), "tip.csv");
    assert_int_equal(im_profile_read(test_path("missing.txt"), 1.0, &p), IM_EIO);
    assert_non_null(strstr(im_last_error(), "missing.txt"));
    assert_null(p);
    /* a .npy file is a 2-D profile on the given spacing */
    im_field *f = field_of(5, 5, 1.0);
    const char *npy = test_path("tip.npy");
    assert_int_equal(im_npy_write(npy, f, IM_NPY_FLOAT64), IM_OK);
    assert_int_equal(im_profile_read(npy, 0.5, &p), IM_OK);
    assert_int_equal(im_profile_kind(p), IM_PUNCH_PROFILE_2D);
    im_indenter field_punch = im_indenter_from_profile(p);
    assert_true(im_indenter_height(&field_punch, 0.5, -0.5) == f->data[1 * 5 + 3]);
    im_profile_free(p);
    im_field_free(f);
}

/* ---- the solver ---- */

static im_field *smooth_surface(int n)
{
    im_field *s = NULL;
    assert_int_equal(im_field_create(n, n, 1.0, &s), IM_OK);
    return s;
}

static im_step_result solve_one(const im_field *s, const im_indenter *punch, enum im_control control, double target)
{
    im_indentation *run = NULL;
    im_step_result r;
    im_solver_options options = im_solver_options_default();
    options.tol = 1e-8; /* the bars below (1e-7, 1e-8) were set at this tolerance */
    if (im_indentation_create(s, punch, control, target, &options, &run) != IM_OK ||
        im_indentation_step(run, target, &r) != IM_OK)
        fail_msg("%s %s %g: %s", im_punch_name(punch->kind), control == IM_CONTROL_LOAD ? "load" : "approach", target,
                 im_last_error());
    im_indentation_free(run);
    return r;
}

static void assert_same_answer(const im_step_result *a, const im_step_result *b, double tol)
{
    if (a->contact_patches != b->contact_patches)
        fail_msg("contact sets differ: %ld vs %ld patches", a->contact_patches, b->contact_patches);
    if (test_relative_difference(a->load, b->load) > tol || test_relative_difference(a->approach, b->approach) > tol)
        fail_msg("N = %.17g vs %.17g, w = %.17g vs %.17g (beyond %g)", a->load, b->load, a->approach, b->approach,
                 tol);
}

/* A cone table (6 samples) on a rough surface: the cone's answer, under both controls. */
static void test_solver_cone_table(void **state)
{
    (void)state;
    im_field *s = test_rough_surface(128, 0.05, 3);
    im_profile *p = sampled(cone_shape, 80, 60, 6);
    im_indenter table = im_indenter_from_profile(p), cone = im_indenter_cone(80);
    for (double w = 1; w <= 4; w += 1.5) {
        im_step_result a = solve_one(s, &table, IM_CONTROL_DISPLACEMENT, w),
                       b = solve_one(s, &cone, IM_CONTROL_DISPLACEMENT, w);
        assert_same_answer(&a, &b, 1e-7);
        assert_close(a.area_ratio / b.area_ratio, 1, 1e-6); /* Sneddon's A(N) against A_cone */
    }
    im_step_result a = solve_one(s, &table, IM_CONTROL_LOAD, 40), b = solve_one(s, &cone, IM_CONTROL_LOAD, 40);
    assert_same_answer(&a, &b, 1e-7);
    im_profile_free(p);
    im_field_free(s);
}

/* The cone sampled on the surface's grid as a 2-D field: the cone's contact set and load. */
static void test_solver_cone_field(void **state)
{
    (void)state;
    im_field *s = test_rough_surface(128, 0.05, 4), *f = NULL;
    assert_int_equal(im_field_create(81, 81, 1.0, &f), IM_OK);
    im_indenter cone = im_indenter_cone(80);
    for (int iy = 0; iy < 81; ++iy)
        for (int ix = 0; ix < 81; ++ix) /* offsets as the solver forms them for a centred axis */
            f->data[iy * 81 + ix] = im_indenter_profile(&cone, hypot((64 + ix - 40 + 0.5) - 64.5,
                                                                     (64 + iy - 40 + 0.5) - 64.5));
    im_profile *p = NULL;
    assert_int_equal(im_profile_field(f, &p), IM_OK);
    im_indenter field = im_indenter_from_profile(p);
    im_step_result a = solve_one(s, &field, IM_CONTROL_DISPLACEMENT, 3),
                   b = solve_one(s, &cone, IM_CONTROL_DISPLACEMENT, 3);
    assert_same_answer(&a, &b, 1e-8);
    assert_true(isnan(a.area_ratio) && isnan(a.load_star)); /* no smooth-contact A(N) for a 2-D profile */
    a = solve_one(s, &field, IM_CONTROL_LOAD, 30);
    b = solve_one(s, &cone, IM_CONTROL_LOAD, 30);
    assert_same_answer(&a, &b, 1e-7);
    /* a field on another spacing is refused, naming it */
    f->delta = 0.5;
    im_profile *other = NULL;
    assert_int_equal(im_profile_field(f, &other), IM_OK);
    im_indenter wrong = im_indenter_from_profile(other);
    im_indentation *run = NULL;
    assert_refused_naming(im_indentation_create(s, &wrong, IM_CONTROL_DISPLACEMENT, 1, NULL, &run), "delta");
    assert_null(run);
    im_profile_free(other);
    im_profile_free(p);
    im_field_free(f);
    im_field_free(s);
}

/* A paraboloid table: Hertz's load (as the built-in sphere, tests/test_solver.c), and the built-in
 * sphere's answer, closer as the samples are refined. */
static void test_solver_paraboloid_is_hertz(void **state)
{
    (void)state;
    im_field *s = smooth_surface(128);
    const double radius = 1000, w = 1.2; /* a = sqrt(R w) ~ 34.6 */
    im_indenter sphere = im_indenter_sphere(radius);
    im_step_result built_in = solve_one(s, &sphere, IM_CONTROL_DISPLACEMENT, w);
    double previous = INFINITY;
    for (int n = 3; n <= 17; n = 2 * n - 1) {
        im_profile *p = sampled(paraboloid_shape, radius, 60, n);
        im_indenter table = im_indenter_from_profile(p);
        im_step_result r = solve_one(s, &table, IM_CONTROL_DISPLACEMENT, w);
        double error = test_relative_difference(r.load, built_in.load);
        if (!(error < previous || error < 1e-8))
            fail_msg("%d samples: load differs from the built-in sphere's by %g, not less than %g", n, error,
                     previous);
        previous = error;
        if (n == 17) {
            assert_close(r.load / im_indenter_load(&sphere, 1, w), 1, 1e-3); /* Hertz, as test_sphere_hertz */
            assert_close(r.area_ratio / built_in.area_ratio, 1, 1e-5);
        }
        im_profile_free(p);
    }
    assert_true(previous < 1e-5);
    im_field_free(s);
}

/* The exact sphere z = R - sqrt(R^2 - r^2), sampled: the built-in (Hertz's paraboloid) sphere's load
 * to within the profiles' difference, z_exact - z_parabola ~ r^4 / (8 R^3), i.e. a relative
 * (a / R)^2 / 4 at the contact radius a. */
static void test_solver_exact_sphere(void **state)
{
    (void)state;
    im_field *s = smooth_surface(128);
    const double radius = 300, w = 2.0, a = sqrt(radius * w);
    im_indenter sphere = im_indenter_sphere(radius);
    im_profile *p = sampled(sphere_shape, radius, 60, 65);
    im_indenter table = im_indenter_from_profile(p);
    im_step_result r = solve_one(s, &table, IM_CONTROL_DISPLACEMENT, w);
    im_step_result b = solve_one(s, &sphere, IM_CONTROL_DISPLACEMENT, w);
    double difference = (b.load - r.load) / b.load, bound = (a / radius) * (a / radius);
    /* the exact sphere is blunter than its paraboloid nowhere: it rises faster, so carries less */
    if (!(difference > 0 && difference < bound))
        fail_msg("exact sphere: load %g vs paraboloid %g (relative %g, expected in (0, (a/R)^2 = %g))", r.load,
                 b.load, difference, bound);
    im_profile_free(p);
    im_field_free(s);
}

/* Beyond the last sample the punch cannot touch: a short table on a smooth surface presses as a
 * flat punch of its extent once its whole face touches. */
static void test_solver_profile_extent(void **state)
{
    (void)state;
    im_field *s = smooth_surface(96);
    im_profile *p = sampled(paraboloid_shape, 100, 10, 11); /* full contact from w = 1 */
    im_indenter table = im_indenter_from_profile(p);
    im_step_result r = solve_one(s, &table, IM_CONTROL_DISPLACEMENT, 3);
    assert_true(r.contact_patches <= (long)(M_PI * 11 * 11));
    assert_close(r.load / im_indenter_load(&table, 1, 3), 1, 0.02); /* the staircase edge, as the flat punch's */
    im_profile_free(p);
    im_field_free(s);
}

#if !defined(__SANITIZE_ADDRESS__) /* see test_interpolation_out_of_memory */
/* Bytes of address space this process maps now (/proc/self/statm's first field, in pages). */
static size_t mapped_bytes(void)
{
    FILE *statm = fopen("/proc/self/statm", "r");
    unsigned long pages = 0;
    if (!statm || fscanf(statm, "%lu", &pages) != 1)
        _exit(3);
    fclose(statm);
    return (size_t)pages * (size_t)sysconf(_SC_PAGESIZE);
}
#endif

/* A profile whose interpolation cannot be allocated: IM_ENOMEM, not GSL's default handler's abort.
 * In a child whose address space leaves room for the profile's copies of r and z (2 x 8n bytes)
 * but not for Steffen's state (5 x 8n): the child's exit status says what im_profile_axisymmetric
 * returned (0: IM_ENOMEM), a signal that it aborted. Not under AddressSanitizer, whose shadow
 * memory needs far more address space than any such limit allows. */
static void test_interpolation_out_of_memory(void **state)
{
    (void)state;
#if defined(__SANITIZE_ADDRESS__)
    skip();
#else
    enum { SAMPLES = 1 << 21 };
    pid_t child = fork();
    assert_true(child >= 0);
    if (child == 0) {
        double *r = malloc(sizeof(double) * SAMPLES), *z = calloc(SAMPLES, sizeof(double));
        if (!r || !z)
            _exit(3);
        for (int i = 0; i < SAMPLES; ++i)
            r[i] = i;
        size_t arrays = sizeof(double) * SAMPLES;
        struct rlimit limit = {.rlim_cur = mapped_bytes() + 3 * arrays, .rlim_max = RLIM_INFINITY};
        if (setrlimit(RLIMIT_AS, &limit) != 0)
            _exit(3);
        im_profile *p = NULL;
        _exit(im_profile_axisymmetric(r, z, SAMPLES, &p) == IM_ENOMEM && !p ? 0 : 1);
    }
    int status = 0;
    assert_int_equal(waitpid(child, &status, 0), child);
    if (WIFSIGNALED(status))
        fail_msg("im_profile_axisymmetric was killed by signal %d (GSL's handler aborts)", WTERMSIG(status));
    assert_true(WIFEXITED(status));
    assert_int_equal(WEXITSTATUS(status), 0);
#endif
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cone_table_is_the_cone),
        cmocka_unit_test(test_paraboloid_table_is_hertz_then_flat),
        cmocka_unit_test(test_sphere_table_converges),
        cmocka_unit_test(test_bad_samples_refused),
        cmocka_unit_test(test_field_profile),
        cmocka_unit_test(test_profile_files),
        cmocka_unit_test(test_solver_cone_table),
        cmocka_unit_test(test_solver_cone_field),
        cmocka_unit_test(test_solver_paraboloid_is_hertz),
        cmocka_unit_test(test_solver_exact_sphere),
        cmocka_unit_test(test_solver_profile_extent),
        cmocka_unit_test(test_interpolation_out_of_memory),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
