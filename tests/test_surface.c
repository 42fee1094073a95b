/* Tests of surface synthesis and statistics against the definitions and the paper's relations. */
#include "support.h"

#include "indentmap/surface.h"
#include "indentmap/status.h"

#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static im_field *generate(const im_surface_params *p)
{
    im_field *s = NULL;
    int status = im_surface_generate(p, &s);
    if (status != IM_OK)
        fail_msg("generate: %s", im_last_error());
    return s;
}

static void target_slope_is_met(void **state)
{
    (void)state;
    im_surface_params p = im_surface_params_default();
    p.nx = p.ny = 256;
    p.lambda_r = p.lambda_0 = 256;
    const double slopes[] = {1e-6, 0.01, 0.08, 1.0};
    for (size_t i = 0; i < sizeof slopes / sizeof *slopes; ++i) {
        for (int definition = 0; definition < 2; ++definition) {
            p.slope_rms = slopes[i];
            p.slope_definition = (enum im_slope_definition)definition;
            im_field *s = generate(&p);
            double measured;
            assert_int_equal(im_surface_slope_rms(s, p.slope_definition, &measured), IM_OK);
            if (test_relative_difference(measured, slopes[i]) > 1e-12)
                fail_msg("definition %d: h'rms %.17g, requested %.17g", definition, measured, slopes[i]);
            im_field_free(s);
        }
    }
}

static void target_height_is_met(void **state)
{
    (void)state;
    im_surface_params p = im_surface_params_default();
    p.nx = 128;
    p.ny = 96;
    p.lambda_r = p.lambda_0 = 128;
    p.target = IM_TARGET_HEIGHT;
    p.height_rms = 2.5;
    im_field *s = generate(&p);
    im_surface_stats st;
    assert_int_equal(im_surface_statistics(s, &st), IM_OK);
    assert_true(test_relative_difference(st.height_rms, 2.5) < 1e-12);
    im_field_free(s);
}

static double mean_of(const im_field *s)
{
    double sum = 0.0;
    for (size_t i = 0; i < im_field_count(s); ++i)
        sum += s->data[i];
    return sum / (double)im_field_count(s);
}

static void surfaces_have_zero_mean(void **state)
{
    (void)state;
    im_surface_params p = im_surface_params_default();
    p.nx = 200; /* not a power of two, odd half size */
    p.ny = 150;
    p.lambda_r = p.lambda_0 = 200;
    im_field *s = generate(&p);
    double rms;
    assert_int_equal(im_surface_slope_rms(s, IM_SLOPE_SPECTRAL, &rms), IM_OK);
    assert_true(fabs(mean_of(s)) < 1e-12); /* heights are O(1) here */
    im_field_free(s);
}

static void same_seed_same_surface_any_thread_count(void **state)
{
    (void)state;
    im_surface_params p = im_surface_params_default();
    p.nx = p.ny = 256;
    p.lambda_r = p.lambda_0 = 256;
    int saved = omp_get_max_threads();
    omp_set_num_threads(1);
    im_field *one = generate(&p);
    omp_set_num_threads(2);
    im_field *two = generate(&p);
    omp_set_num_threads(saved);
    assert_memory_equal(one->data, two->data, im_field_count(one) * sizeof(double));
    p.seed = 2;
    im_field *other = generate(&p);
    assert_true(memcmp(one->data, other->data, im_field_count(one) * sizeof(double)) != 0);
    im_field_free(one);
    im_field_free(two);
    im_field_free(other);
}

/* A surface on a grid refined 2x over the same box keeps every mode it had: sampled at the coarse
 * points, and with the fine-only modes removed, it equals the coarse surface up to the scale
 * factor. Checked through the spectra: the coarse modes' coefficients are proportional. */
static void refined_surface_keeps_its_modes(void **state)
{
    (void)state;
    im_surface_params coarse = im_surface_params_default();
    coarse.nx = coarse.ny = 64;
    coarse.lambda_s = 8;
    coarse.lambda_r = coarse.lambda_0 = 64;
    im_surface_params fine = coarse;
    fine.nx = fine.ny = 128;
    fine.delta = 0.5;
    fine.lambda_s = 16; /* the same physical cutoffs */
    fine.lambda_r = fine.lambda_0 = 128;
    im_field *a = generate(&coarse), *b = generate(&fine);
    /* Both are band-limited below the coarse Nyquist frequency: sampling the fine surface at the
     * coarse points gives the coarse surface (same slope target, same physical spectrum). */
    double max_difference = 0.0, max_height = 0.0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            double d = fabs(a->data[y * 64 + x] - b->data[(2 * y) * 128 + 2 * x]);
            max_difference = fmax(max_difference, d);
            max_height = fmax(max_height, fabs(a->data[y * 64 + x]));
        }
    if (max_difference > 1e-10 * max_height)
        fail_msg("refined surface differs at coarse points by %g (heights up to %g)", max_difference, max_height);
    im_field_free(a);
    im_field_free(b);
}

/* Without --lambda-0 there is no roll-off plateau whatever lambda_r is: a default surface on a
 * smaller box equals one generated with lambda_0 = lambda_r explicitly. (A default lambda_0 of
 * 512 once put a plateau under the longest waves of every box smaller than 512 cells, which also
 * broke 4x refinement.) And a 4x refinement keeps the surface. */
static void default_has_no_plateau_and_refines(void **state)
{
    (void)state;
    im_surface_params base = im_surface_params_default();
    base.nx = base.ny = 128;
    base.lambda_r = 128;
    im_surface_params explicit_params = base;
    explicit_params.lambda_0 = 128;
    im_surface_params fine = base;
    fine.nx = fine.ny = 512;
    fine.delta = 0.25;
    fine.lambda_s = 16;
    fine.lambda_r = 512;
    im_field *a = generate(&base), *b = generate(&explicit_params), *c = generate(&fine);
    assert_memory_equal(a->data, b->data, im_field_count(a) * sizeof(double));
    double worst = 0.0;
    for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 128; ++x)
            worst = fmax(worst, fabs(a->data[y * 128 + x] - c->data[(4 * y) * 512 + 4 * x]));
    if (worst > 1e-10)
        fail_msg("4x refinement differs at the coarse points by %g", worst);
    im_field_free(a);
    im_field_free(b);
    im_field_free(c);
}

/* The fitted PSD exponent recovers -2(1 + H): median over seeds, 1024 x 1024. */
static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void psd_slope_recovers_hurst(void **state)
{
    (void)state;
    const double hursts[] = {0.3, 0.8};
    for (int h = 0; h < 2; ++h) {
        double estimates[5];
        for (int seed = 0; seed < 5; ++seed) {
            im_surface_params p = im_surface_params_default();
            p.nx = p.ny = 1024;
            p.lambda_r = p.lambda_0 = 1024;
            p.hurst = hursts[h];
            p.seed = (uint64_t)seed + 1;
            im_field *s = generate(&p);
            im_psd *psd = NULL;
            assert_int_equal(im_surface_psd(s, 40, &psd), IM_OK);
            double q_r = 2 * M_PI / 1024, q_s = 2 * M_PI / 4, exponent;
            assert_int_equal(im_psd_fit_exponent(psd, 2 * q_r, q_s / 1.5, &exponent), IM_OK);
            estimates[seed] = -exponent / 2.0 - 1.0;
            im_psd_free(psd);
            im_field_free(s);
        }
        qsort(estimates, 5, sizeof *estimates, compare_doubles);
        if (fabs(estimates[2] - hursts[h]) > 0.05)
            fail_msg("H = %g: median fitted H = %g", hursts[h], estimates[2]);
    }
}

/* Over 10 seeds the mean h_rms agrees with the exact moments of eq. (13) within 5%; eq. (15), the
 * paper's large-zeta approximation, is 7.5% below those for H = 0.8, zeta = 128 (checked too). */
static void mean_height_rms_matches_moments(void **state)
{
    (void)state;
    im_surface_params p = im_surface_params_default(); /* the paper's 512 x 512 family */
    double sum = 0.0;
    for (uint64_t seed = 1; seed <= 10; ++seed) {
        p.seed = seed;
        im_field *s = generate(&p);
        im_surface_stats st;
        assert_int_equal(im_surface_statistics(s, &st), IM_OK);
        sum += st.height_rms;
        im_field_free(s);
    }
    double mean = sum / 10.0, expected = im_surface_expected_height_rms(&p, p.slope_rms);
    double eq15 = im_surface_height_rms_eq15(&p, p.slope_rms);
    print_message("mean h_rms %.4f, eq. (13) %.4f, eq. (15) %.4f\n", mean, expected, eq15);
    if (test_relative_difference(mean, expected) > 0.05)
        fail_msg("mean h_rms %g differs from eq. (13)'s %g by more than 5%%", mean, expected);
    assert_close(eq15 / expected, 1.0 / sqrt(1.0 / (1.0 - pow(128.0, -0.4))), 1e-3);
}

/* The statistics of a single cosine are known in closed form. */
static void statistics_of_a_cosine(void **state)
{
    (void)state;
    im_field *s = NULL;
    assert_int_equal(im_field_create(64, 32, 1.0, &s), IM_OK);
    double k = 2 * M_PI * 4 / 64, amplitude = 0.3;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 64; ++x)
            s->data[y * 64 + x] = amplitude * cos(k * x);
    im_surface_stats st;
    assert_int_equal(im_surface_statistics(s, &st), IM_OK);
    assert_close(st.height_rms, amplitude / sqrt(2), 1e-14);
    assert_close(st.slope_rms_spectral, amplitude * k / sqrt(2), 1e-14);
    assert_close(st.curvature_rms, amplitude * k * k / 2 / sqrt(2), 1e-14);
    /* profile moments average x and y: m2 = <h_x^2> / 2 here since h_y = 0 */
    assert_close(st.m2, amplitude * amplitude * k * k / 4, 1e-15);
    assert_close(st.m4, amplitude * amplitude * k * k * k * k / 4, 1e-15);
    /* forward differences of a cosine: slope 2 sin(k/2) instead of k */
    double fd = 0.0;
    for (int x = 0; x + 1 < 64; ++x)
        fd += pow(amplitude * (cos(k * (x + 1)) - cos(k * x)), 2);
    assert_close(st.slope_rms_fd, sqrt(fd / 63), 1e-14);
    im_field_free(s);
}

static void histograms_are_normalised(void **state)
{
    (void)state;
    im_surface_params p = im_surface_params_default();
    p.nx = p.ny = 128;
    p.lambda_r = p.lambda_0 = 128;
    im_field *s = generate(&p);
    for (int q = 0; q < 3; ++q) {
        im_histogram *h = NULL;
        assert_int_equal(im_surface_histogram(s, (enum im_histogram_quantity)q, 51, &h), IM_OK);
        double integral = 0.0, width = (h->hi - h->lo) / h->bins;
        for (int b = 0; b < h->bins; ++b)
            integral += h->density[b] * width;
        assert_close(integral, 1.0, 1e-12);
        im_histogram_free(h);
    }
    im_field_free(s);
}

/* Issue 13: a 256^2 crop of a periodic 1024^2 surface of h'rms 0.08 is not periodic; its plain
 * spectral h'rms sees the step at the box's edges (0.30, or 1.06 with a tilt of 0.05). Detrended
 * and tapered, the spectral estimate must come within 5% of the finite-difference slope of the
 * untilted crop, where the plain one is more than 3 times off. */
static void prepared_crop_estimates_the_slope(void **state)
{
    (void)state;
    im_surface_params p = im_surface_params_default();
    p.nx = p.ny = 1024;
    p.lambda_r = 1024;
    im_field *periodic = generate(&p), *crop = NULL;
    assert_int_equal(im_surface_crop(periodic, 300, 500, 256, 256, &crop), IM_OK);
    double truth;
    assert_int_equal(im_surface_slope_rms(crop, IM_SLOPE_FINITE_DIFFERENCE, &truth), IM_OK);
    for (int tilted = 0; tilted < 2; ++tilted) {
        im_field *data = NULL;
        assert_int_equal(im_field_clone(crop, &data), IM_OK);
        for (int iy = 0; iy < 256; ++iy)
            for (int ix = 0; ix < 256; ++ix)
                data->data[iy * 256 + ix] += tilted * (0.05 * ix - 0.02 * iy);
        double plain;
        assert_int_equal(im_surface_slope_rms(data, IM_SLOPE_SPECTRAL, &plain), IM_OK);
        assert_int_equal(im_surface_detrend(data, IM_DETREND_PLANE), IM_OK);
        const im_taper tapers[] = {{IM_TAPER_HANN, 0.0}, {IM_TAPER_TUKEY, 0.5}};
        for (int t = 0; t < 2; ++t) {
            im_surface_stats stats;
            assert_int_equal(im_surface_statistics_tapered(data, &tapers[t], &stats), IM_OK);
            print_message("tilted %d taper %d: truth %.4f plain %.4f prepared %.4f\n", tilted, t, truth, plain,
                          stats.slope_rms_spectral);
            assert_true(plain > 3.0 * truth);
            assert_close(stats.slope_rms_spectral / truth, 1.0, 0.05);
        }
        im_field_free(data);
    }
    im_field_free(crop);
    im_field_free(periodic);
}

static void bad_parameters_are_refused(void **state)
{
    (void)state;
    im_field *s = NULL;
    im_surface_params p = im_surface_params_default();
    p.hurst = 1.0;
    assert_int_equal(im_surface_generate(&p, &s), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "hurst"));
    p = im_surface_params_default();
    p.lambda_s = 1.0;
    assert_int_equal(im_surface_generate(&p, &s), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "lambda_s"));
    p = im_surface_params_default();
    p.slope_rms = NAN;
    assert_int_equal(im_surface_generate(&p, &s), IM_EINVAL);
    p = im_surface_params_default();
    p.nx = p.ny = 2048; /* about 0.3 GiB at its peak: refused under a 64 MiB cap, before allocating */
    p.lambda_r = p.lambda_0 = 2048;
    char estimate[64];
    snprintf(estimate, sizeof estimate, "needs about %.1f MiB but only 64.0 MiB",
             im_surface_generate_bytes(2048, 2048) / 1048576.0);
    im_memory_set_limit(64u << 20);
    int status = im_surface_generate(&p, &s);
    im_memory_set_limit(0);
    assert_int_equal(status, IM_ENOMEM);
    if (!strstr(im_last_error(), estimate) || !strstr(im_last_error(), "2048 x 2048"))
        fail_msg("message '%s' lacks '%s'", im_last_error(), estimate);
    assert_null(s);
}

/* A generator record made, parsed and made again: the same text and the same parameters, a seed of 2^64 - 1
 * (recorded as that decimal, which JSON's signed integers do not hold) and a record without a plateau
 * (lambda_0 0: recorded as lambda_r) included. */
static void generator_record_round_trips(void **state)
{
    (void)state;
    im_surface_params p = im_surface_params_default(), back;
    p.nx = 96;
    p.ny = 48;
    p.delta = 0.25;
    p.hurst = 0.6;
    p.lambda_r = 64;
    p.lambda_0 = 0.0;
    p.target = IM_TARGET_HEIGHT;
    p.height_rms = 1.0 / 3.0;
    p.slope_definition = IM_SLOPE_FINITE_DIFFERENCE;
    p.seed = UINT64_MAX;
    char *text = NULL, *again = NULL;
    assert_int_equal(im_surface_generator_record(&p, &text), IM_OK);
    assert_non_null(strstr(text, "\"lambda_0\":64.0,"));
    assert_non_null(strstr(text, "\"seed\":18446744073709551615}"));
    assert_int_equal(im_surface_generator_parse(text, &back), IM_OK);
    assert_int_equal(im_surface_generator_record(&back, &again), IM_OK);
    assert_string_equal(again, text);
    p.lambda_0 = p.lambda_r; /* the one in effect */
    assert_true(back.nx == p.nx && back.ny == p.ny && back.delta == p.delta && back.hurst == p.hurst &&
                back.lambda_s == p.lambda_s && back.lambda_r == p.lambda_r && back.lambda_0 == p.lambda_0 &&
                back.target == p.target && back.slope_rms == p.slope_rms && back.height_rms == p.height_rms &&
                back.slope_definition == p.slope_definition && back.seed == p.seed);
    free(text);
    free(again);
}

/* text with its first `old` replaced by `new`, into out. */
static const char *replaced(const char *text, const char *old, const char *new, char *out, size_t size)
{
    const char *at = strstr(text, old);
    if (!at)
        fail_msg("'%s' is not in '%s'", old, text);
    snprintf(out, size, "%.*s%s%s", (int)(at - text), text, new, at + strlen(old));
    return out;
}

/* Seeds as unsigned 64-bit integers: 2^63 round trips as its decimal; an earlier build's record of a seed of
 * 2^63 or more, its two's complement (a negative integer), is read as that seed; beyond 0 .. 2^64 - 1, a
 * fraction or a string is refused naming the seed. */
static void generator_seeds_are_unsigned(void **state)
{
    (void)state;
    im_surface_params p = im_surface_params_default(), back;
    p.nx = p.ny = 64;
    p.lambda_r = 64;
    p.seed = (uint64_t)1 << 63;
    char *text = NULL, *again = NULL, changed[1024];
    assert_int_equal(im_surface_generator_record(&p, &text), IM_OK);
    const char *seed = "\"seed\":9223372036854775808}";
    assert_non_null(strstr(text, seed));
    assert_int_equal(im_surface_generator_parse(text, &back), IM_OK);
    assert_true(back.seed == p.seed);
    const struct {
        const char *recorded;
        uint64_t seed;
    } earlier[] = {{"\"seed\":-9223372036854775808}", (uint64_t)1 << 63}, {"\"seed\":-1}", UINT64_MAX}};
    for (size_t i = 0; i < sizeof earlier / sizeof earlier[0]; ++i) {
        assert_int_equal(
            im_surface_generator_parse(replaced(text, seed, earlier[i].recorded, changed, sizeof changed), &back),
            IM_OK);
        assert_true(back.seed == earlier[i].seed);
    }
    assert_int_equal(im_surface_generator_record(&back, &again), IM_OK);
    assert_non_null(strstr(again, "\"seed\":18446744073709551615}"));
    const char *refused[] = {"\"seed\":18446744073709551616}", "\"seed\":-9223372036854775809}",
                             "\"seed\":99999999999999999999999}", "\"seed\":1.5}", "\"seed\":\"1\"}"};
    for (size_t i = 0; i < sizeof refused / sizeof refused[0]; ++i) {
        assert_int_equal(im_surface_generator_parse(replaced(text, seed, refused[i], changed, sizeof changed), &back),
                         IM_EINVAL);
        if (!strstr(im_last_error(), "generator: \"seed\": expected an integer in [0, 18446744073709551615]"))
            fail_msg("%s: message '%s'", changed, im_last_error());
    }
    free(text);
    free(again);
}

static void malformed_generator_records_are_refused(void **state)
{
    (void)state;
    im_surface_params p = im_surface_params_default(), back = {.nx = -7};
    p.nx = p.ny = 64;
    p.lambda_r = 64;
    p.hurst = 0.5; /* printed as it is written here */
    char *text = NULL, spoilt[1024];
    assert_int_equal(im_surface_generator_record(&p, &text), IM_OK);
    const struct {
        const char *old, *new, *message;
    } cases[] = {
        {"{", "[", "generator: expected a JSON object"},
        {"\"seed\"", "\"sead\"", "generator: \"sead\": not a key of the record"},
        {"\"nx\":64,", "", "generator: \"nx\" is missing"},
        {"\"nx\":64", "\"nx\":1", "generator: \"nx\": expected an integer in [2, "},
        {"\"nx\":64", "\"nx\":64.0", "generator: \"nx\": expected an integer"},
        {"\"hurst\":0.5,", "\"hurst\":\"0.5\",", "generator: \"hurst\": expected a number"},
        {"\"hurst\":0.5,", "\"hurst\":1.0,", "generator: hurst = 1: expected 0 < H < 1"},
        {"\"target\":\"slope_rms\"", "\"target\":\"slope\"", "generator: \"target\": expected"},
        {"\"spectral\"", "\"fd\"", "generator: \"slope_definition\": expected"},
        {"\"ny\":64", "\"ny\":64,\"nx\":64", "generator: expected a JSON object"}, /* a duplicate key */
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        replaced(text, cases[i].old, cases[i].new, spoilt, sizeof spoilt);
        assert_int_equal(im_surface_generator_parse(spoilt, &back), IM_EINVAL);
        if (!strstr(im_last_error(), cases[i].message))
            fail_msg("%s: message '%s' lacks '%s'", spoilt, im_last_error(), cases[i].message);
        assert_int_equal(back.nx, -7); /* untouched */
    }
    free(text);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(target_slope_is_met),
        cmocka_unit_test(target_height_is_met),
        cmocka_unit_test(surfaces_have_zero_mean),
        cmocka_unit_test(same_seed_same_surface_any_thread_count),
        cmocka_unit_test(refined_surface_keeps_its_modes),
        cmocka_unit_test(default_has_no_plateau_and_refines),
        cmocka_unit_test(psd_slope_recovers_hurst),
        cmocka_unit_test(mean_height_rms_matches_moments),
        cmocka_unit_test(statistics_of_a_cosine),
        cmocka_unit_test(histograms_are_normalised),
        cmocka_unit_test(prepared_crop_estimates_the_slope),
        cmocka_unit_test(bad_parameters_are_refused),
        cmocka_unit_test(generator_record_round_trips),
        cmocka_unit_test(generator_seeds_are_unsigned),
        cmocka_unit_test(malformed_generator_records_are_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
