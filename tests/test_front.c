/* What the two front ends (`indentmap indent` and scenes) share (src/front/): one history schema
 * read by one reader, one step-list parser with one limit, one punch parser, one default
 * tolerance, and the checked path join. Both front ends are run through the command line
 * ($IM_CLI) where the test is that they agree. */
#include "support.h"

#include "front/front.h"
#include "indentmap/indenter.h"
#include "indentmap/io.h"
#include "indentmap/scene.h"
#include "indentmap/solver.h"
#include "indentmap/status.h"
#include "scene/contents.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- step lists ---- */

/* The message of a scene whose [loading] steps is `steps`, after its "FILE:LINE: ". */
static const char *scene_steps_error(const char *steps)
{
    static char message[1024];
    char text[512];
    snprintf(text, sizeof text, "[loading]\nsteps = %s\n", steps);
    const char *path = test_path("steps.ini");
    test_write_bytes(path, text, strlen(text));
    im_scene *scene = NULL;
    if (im_scene_load(path, &scene) == IM_OK) {
        im_scene_free(scene);
        return NULL;
    }
    const char *colon = strstr(im_last_error(), ".ini:2: ");
    snprintf(message, sizeof message, "%s", colon ? colon + 8 : im_last_error());
    return message;
}

static void step_lists_one_limit(void **state)
{
    (void)state;
    double values[STEPS_MAX];
    int count = 0;
    char error[512];
    assert_int_equal(steps_parse("steps", "1:2:4096", values, &count, error, sizeof error), 0);
    assert_int_equal(count, STEPS_MAX);
    assert_close(values[0], 1, 0);
    assert_close(values[STEPS_MAX - 1], 2, 0);
    assert_int_equal(steps_parse("steps", "2:1:3", values, &count, error, sizeof error), 0); /* unloading */
    assert_close(values[1], 1.5, 1e-15);
    assert_int_equal(steps_parse("steps", " 0.5 , 1,2e1", values, &count, error, sizeof error), 0);
    assert_int_equal(count, 3);
    assert_close(values[2], 20, 0);
    /* values and ranges mixed: a loading-unloading history */
    assert_int_equal(steps_parse("--approach", "2:8:4, 7:2:6,3", values, &count, error, sizeof error), 0);
    assert_int_equal(count, 11);
    const double cycle[] = {2, 4, 6, 8, 7, 6, 5, 4, 3, 2, 3};
    for (int i = 0; i < 11; ++i)
        assert_close(values[i], cycle[i], 1e-15);
    assert_int_equal(steps_parse("steps", "1:2:4000,3:4:97", values, &count, error, sizeof error), -1);
    assert_non_null(strstr(error, "expected at most 4096 steps"));
    assert_int_equal(steps_parse("steps", "1:2:3,4:5", values, &count, error, sizeof error), -1);
    assert_non_null(strstr(error, "'4:5' is not a range first:last:count"));
    assert_int_equal(steps_parse("steps", "1:2:4097", values, &count, error, sizeof error), -1);
    assert_non_null(strstr(error, "1 <= count <= 4096"));
    /* the scene holds its steps inline: its limit is the parser's */
    assert_int_equal(IM_SCENE_MAX_STEPS, STEPS_MAX);
    char *many = malloc(4 * (STEPS_MAX + 1) + 1);
    assert_non_null(many);
    many[0] = '\0';
    for (int i = 0; i <= STEPS_MAX; ++i)
        strcat(many, i ? ",1.5" : "1.5");
    assert_int_equal(steps_parse("--load", many, values, &count, error, sizeof error), -1);
    assert_non_null(strstr(error, "expected at most 4096 steps"));
    free(many);
}

/* The range's formula, first + (last - first) i / (n - 1), as every kept result's approaches were made. */
static double range_formula(double first, double last, int i, int n)
{
    return n == 1 || i == n - 1 ? last : first + (last - first) * i / (n - 1);
}

/* first:last:n of thousandths (first = a k / 1000 and last = -a (n - 1 - k) / 1000, or both negated), parsed. */
static void parse_thousandths(long long first, long long last, int n, double *values, int *count)
{
    char text[128], error[512];
    snprintf(text, sizeof text, "%s%lld.%03lld:%s%lld.%03lld:%d", first < 0 ? "-" : "", llabs(first) / 1000,
             llabs(first) % 1000, last < 0 ? "-" : "", llabs(last) / 1000, llabs(last) % 1000, n);
    if (steps_parse_signed("--approach", text, 1, values, count, error, sizeof error) != 0)
        fail_msg("%s: %s", text, error);
}

/* A range crossing 0 has 0 in it exactly (findings R4: 0.6:-3:37 gave -1.11e-16 at its 7th step), and no other
 * value of any range moves from the formula's bits (a kept scene result's key hashes its approaches). */
static void ranges_cross_zero_exactly(void **state)
{
    (void)state;
    static const long long STEP[] = {100, 50, 300, 10, 20, 3, 70, 110, 1100, 125, 2500, 13, 7, 250, 150};
    double values[STEPS_MAX];
    int count = 0, zeros = 0, others = 0;
    for (size_t a = 0; a < sizeof STEP / sizeof *STEP; ++a)
        for (int n = 3; n <= 120; ++n)
            for (int k = 1; k < n - 1; ++k)
                for (int sign = -1; sign <= 1; sign += 2) {
                    const long long first = sign * STEP[a] * k, last = -sign * STEP[a] * (n - 1 - k);
                    parse_thousandths(first, last, n, values, &count);
                    for (int i = 0; i < n; ++i) {
                        const double old = range_formula(first / 1000.0, last / 1000.0, i, n);
                        if (i == k) {
                            if (values[i] != 0)
                                fail_msg("%lld:%lld:%d (thousandths): step %d is %g, expected 0", first, last, n,
                                         i + 1, values[i]);
                            zeros += old != 0;
                        } else if (memcmp(&values[i], &old, sizeof old) != 0) {
                            fail_msg("%lld:%lld:%d (thousandths): step %d is %.17g, the formula's %.17g", first, last,
                                     n, i + 1, values[i], old);
                        } else {
                            ++others;
                        }
                    }
                }
    assert_true(zeros > 1000); /* the formula missed 0 in many of them */
    assert_true(others > 1000000);
    char error[512]; /* a range's first is the one given, however small */
    assert_int_equal(steps_parse("steps", "1e-20:1:3", values, &count, error, sizeof error), 0);
    assert_true(values[0] == 1e-20 && values[1] == 0.5);
}

/* A scene's steps refuse what `indent --approach` refuses, with the same message. */
static void step_lists_same_messages(void **state)
{
    (void)state;
    static const char *const BAD[] = {"1:2:5000", "1:2", "1,,2", "1,abc", "-1,2", "1:2:0", ",1", "1:2:3:4"};
    for (size_t i = 0; i < sizeof BAD / sizeof *BAD; ++i) {
        double values[STEPS_MAX];
        int count;
        char error[512];
        assert_int_equal(steps_parse("steps", BAD[i], values, &count, error, sizeof error), -1);
        const char *scene = scene_steps_error(BAD[i]);
        if (!scene || strcmp(scene, error) != 0)
            fail_msg("steps = %s: the scene says '%s', the parser '%s'", BAD[i], scene ? scene : "(accepted)", error);
    }
}

/* ---- punch names ---- */

static void punch_names_one_parser(void **state)
{
    (void)state;
    enum im_punch_kind kind = IM_PUNCH_CONE;
    assert_int_equal(im_punch_parse("sphere", &kind), IM_OK);
    assert_int_equal(kind, IM_PUNCH_SPHERE);
    assert_int_equal(im_punch_parse("Flat", &kind), IM_OK);
    assert_int_equal(kind, IM_PUNCH_FLAT);
    assert_int_equal(im_punch_parse("pyramid", &kind), IM_EINVAL);
    assert_int_equal(kind, IM_PUNCH_FLAT);
    char expected[256];
    snprintf(expected, sizeof expected, "shape = %s", im_last_error());
    const char *path = test_path("punch.ini");
    test_write_bytes(path, "[punch]\nshape = pyramid\n", 24);
    im_scene *scene = NULL;
    assert_int_equal(im_scene_load(path, &scene), IM_EFORMAT);
    if (!strstr(im_last_error(), expected))
        fail_msg("scene: '%s', expected to contain '%s'", im_last_error(), expected);
}

/* ---- one default tolerance ---- */

static void one_default_tolerance(void **state)
{
    (void)state;
    double standard;
    assert_int_equal(im_quality_tolerance(IM_QUALITY_DEFAULT, &standard), IM_OK);
    assert_close(im_solver_options_default().tol, standard, 0);
    im_scene scene;
    scene_defaults(&scene);
    assert_close(scene.tol, standard, 0);
    assert_string_equal(scene.quality, IM_QUALITY_DEFAULT);
}

/* ---- the history schema ---- */

static void read_whole(const char *path, char **text)
{
    *text = NULL;
    if (im_read_text_file(path, 1 << 24, text, NULL) != IM_OK)
        fail_msg("%s: %s", path, im_last_error());
}

static void run_cli(const char *arguments)
{
    const char *cli = getenv("IM_CLI");
    if (!cli)
        fail_msg("IM_CLI is not set (ctest sets it)");
    char command[4096];
    snprintf(command, sizeof command, "OMP_NUM_THREADS=1 '%s' %s >/dev/null 2>&1", cli, arguments);
    if (system(command) != 0)
        fail_msg("failed: %s", command);
}

/* The history each front end writes parses with the one reader: indent's history.csv whole, a
 * scene's after its "# ..." line (key, row count, checksum). */
static void both_histories_one_reader(void **state)
{
    (void)state;
    const char *dir = test_temp_dir();
    char arguments[2048], path[1024];
    snprintf(arguments, sizeof arguments, "indent --smooth --n 32 --approach 0.5:2:3 --out '%s/indent'", dir);
    run_cli(arguments);
    const char *scene = "[scene]\noutput = scene\n[surfaces]\nn = 32\nslopes = 0.08\nseeds = 1\n"
                        "[loading]\nsteps = 0.5:2:3\n[output]\nplots = fig5\n";
    test_write_bytes(test_path("h.ini"), scene, strlen(scene));
    snprintf(arguments, sizeof arguments, "run --quiet '%s'", test_path("h.ini"));
    run_cli(arguments);
    im_history_row rows[8];
    int count = 0;
    char why[160];
    snprintf(path, sizeof path, "%s/indent/history.csv", dir);
    char *indent, *member;
    read_whole(path, &indent);
    if (!im_history_parse(indent, 1, rows, 8, &count, why, sizeof why))
        fail_msg("indent's history.csv: %s", why);
    assert_int_equal(count, 3);
    assert_close(rows[2].result.approach, 2, 0);
    assert_true(rows[2].patches >= 1 && rows[2].result.iterations > 0 && isfinite(rows[2].stiffness));
    snprintf(path, sizeof path, "%s/scene/histories/member_00_1.csv", dir);
    read_whole(path, &member);
    const char *body = strchr(member, '\n');
    assert_non_null(body);
    if (!im_history_parse(body + 1, 1, rows, 8, &count, why, sizeof why))
        fail_msg("the scene's history: %s", why);
    assert_int_equal(count, 3);
    assert_true(rows[1].result.load > 0 && rows[1].patches >= 1 && isfinite(rows[1].theory.area_ratio_gamma));
    assert_memory_equal(indent, body + 1, strlen(im_history_columns()) + 1); /* the same column line */
    free(indent);
    free(member);
}

/* A history of the previous version (the scene's nine columns) is refused, never misread; so are an
 * empty file (said to be empty), a row short of a column, a NaN approach and rows out of order. */
static void other_histories_refused(void **state)
{
    (void)state;
    static const char *const OLD = "approach,load,load_star,contact_patches,area_ratio,load_smooth,area_smooth,"
                                   "area_ratio_constant,area_ratio_gamma\n0.5,1,2,3,1,1,2,1,1\n";
    im_history_row rows[4];
    int count;
    char why[160], text[2048];
    assert_false(im_history_parse(OLD, 1, rows, 4, &count, why, sizeof why));
    assert_non_null(strstr(why, "older version"));
    assert_false(im_history_parse("", 1, rows, 4, &count, why, sizeof why)); /* not an older version's */
    assert_non_null(strstr(why, "it is empty"));
    im_history_row row = {.step = 1,
                          .result = {.approach = 1,
                                     .load = 2,
                                     .load_star = 3,
                                     .contact_patches = 4,
                                     .area_ratio = 1,
                                     .iterations = 5,
                                     .residual = 1e-7},
                          .stiffness = NAN,
                          .e_star_sneddon = NAN,
                          .patches = 1,
                          .perimeter = 8};
    char line[IM_HISTORY_LINE_MAX];
    im_history_format(&row, line, sizeof line);
    snprintf(text, sizeof text, "%s\n%s", im_history_columns(), line);
    assert_true(im_history_parse(text, 1, rows, 4, &count, why, sizeof why));
    assert_int_equal(count, 1);
    assert_close(rows[0].result.load_star, 3, 0);
    assert_int_equal(rows[0].patches, 1);
    assert_true(isnan(rows[0].stiffness));
    snprintf(text, sizeof text, "%s\n%.*s\n", im_history_columns(), (int)(strrchr(line, ',') - line), line);
    assert_false(im_history_parse(text, 1, rows, 4, &count, why, sizeof why)); /* a column short */
    row.result.approach = NAN;
    im_history_format(&row, line, sizeof line);
    snprintf(text, sizeof text, "%s\n%s", im_history_columns(), line);
    assert_false(im_history_parse(text, 1, rows, 4, &count, why, sizeof why));
    row.result.approach = 1;
    row.step = 2;
    im_history_format(&row, line, sizeof line);
    snprintf(text, sizeof text, "%s\n%s", im_history_columns(), line);
    assert_false(im_history_parse(text, 1, rows, 4, &count, why, sizeof why));
}

/* The history text of rows[0..n): the column line, then each row's. */
static void history_text(const im_history_row *rows, int n, char *text, size_t size)
{
    size_t used = (size_t)snprintf(text, size, "%s\n", im_history_columns());
    for (int i = 0; i < n; ++i)
        used += (size_t)im_history_format(&rows[i], text + used, size - used);
}

/* A / A_Hertz at a load held at zero only to the solver's tolerance (T8: 9.5e-7 after 5 at tol 1e-6 gave
 * 52665): im_history_measure makes it NaN where N <= tol max |N| of the rows so far, keeps it just above, and
 * the reader takes such a NaN back, but not at a load above every load before it (the first step's, a new
 * largest), where the ratio is always a number. */
static void area_ratio_undefined_at_a_zero_load(void **state)
{
    (void)state;
    const im_indenter sphere = im_indenter_sphere(100);
    const im_theory_interface smooth = im_theory_interface_default(0);
    im_history_row rows[3] = {{.result = {.approach = 0.76, .load = 5, .load_star = 163, .area_ratio = 2.36}},
                              {.result = {.approach = 0.45, .load = 4e-6, .load_star = 0.03, .area_ratio = 5e4}},
                              {.result = {.approach = 0.46, .load = 5.1e-6, .load_star = 0.03, .area_ratio = 5e4}}};
    for (int i = 0; i < 3; ++i)
        assert_int_equal(im_history_measure(&sphere, &smooth, NULL, 1e-6, rows, i), IM_OK);
    assert_close(rows[0].result.area_ratio, 2.36, 0);
    assert_true(isnan(rows[1].result.area_ratio)); /* 4e-6 <= 1e-6 x 5 */
    assert_close(rows[2].result.area_ratio, 5e4, 0);
    char text[4 * IM_HISTORY_LINE_MAX], why[160];
    im_history_row back[3];
    int count;
    history_text(rows, 3, text, sizeof text);
    if (!im_history_parse(text, IM_HISTORY_AREA_SMOOTH, back, 3, &count, why, sizeof why))
        fail_msg("a history through zero load: %s", why);
    assert_true(isnan(back[1].result.area_ratio));
    rows[0].result.area_ratio = NAN; /* the first step's load is the largest so far: its ratio is a number */
    history_text(rows, 3, text, sizeof text);
    assert_false(im_history_parse(text, IM_HISTORY_AREA_SMOOTH, back, 3, &count, why, sizeof why));
}

/* A plastic sphere unloaded past where it touches its impression (R = 100, H_p = 0.05 to w = 3, then
 * down: `indent --smooth --n 128 --punch sphere --radius 100 --hardness 0.05`, steps 12 to 15, residual
 * approach 1.107): below that approach N is 0 about the step, so its stiffness dN/dw is exactly 0 (the
 * three-point formula across the touch gave -1.28 and -2.77); at the step still in contact the formula
 * stands (positive: N rises with w); a reload's first steps past the touch get none (NaN), as after a turn. */
static void stiffness_is_zero_where_the_punch_is_withdrawn(void **state)
{
    (void)state;
    const im_indenter sphere = im_indenter_sphere(100);
    const im_theory_interface smooth = im_theory_interface_default(0);
    const double w[4] = {1.5, 1.25, 1.0, 0.75}, n[4] = {6.18954, 1.38721, 0, 0};
    const long patches[4] = {421, 177, 0, 0};
    im_history_row rows[4];
    for (int i = 0; i < 4; ++i) {
        rows[i] = (im_history_row){.result = {.approach = w[i],
                                              .load = n[i],
                                              .contact_patches = patches[i],
                                              .area_ratio = patches[i] ? 2 : NAN,
                                              .residual_approach = 1.10707}};
        assert_int_equal(im_history_measure(&sphere, &smooth, NULL, 1e-6, rows, i), IM_OK);
    }
    assert_true(rows[2].stiffness == 0.0 && rows[3].stiffness == 0.0);
    assert_true(isnan(rows[2].e_star_sneddon));
    rows[2].result.approach = rows[2].result.residual_approach; /* touching: the formula's one-sided slope */
    assert_int_equal(im_history_measure(&sphere, &smooth, NULL, 1e-6, rows, 2), IM_OK);
    assert_true(rows[2].stiffness != 0.0);
    /* reloaded from withdrawn steps (steps 19 to 21: w = 0.5, 1, 1.5): no derivative spans the touch */
    im_history_row reload[3] = {rows[3], rows[3], rows[0]};
    reload[1].result.approach = 1.0;
    for (int i = 0; i < 3; ++i)
        assert_int_equal(im_history_measure(&sphere, &smooth, NULL, 1e-6, reload, i), IM_OK);
    assert_true(isnan(reload[2].stiffness));
}

/* A punch without a smooth-contact area (a 2-D profile): its rows' N* and A / A_cone are NaN, as
 * the solver writes them, and read back; a finite one there is not its history, and a NaN where a
 * punch with that area has a number, or a NaN approach, is still refused. */
/* im_history_row_values gives each column's number in the order the writer writes them (read back from
 * im_history_format's line), im_history_row_from_values takes them back, and it refuses a fraction in
 * exactly the columns im_history_integer_columns names. */
static void row_values_are_the_written_columns(void **state)
{
    (void)state;
    double values[IM_HISTORY_COLUMN_COUNT], back[IM_HISTORY_COLUMN_COUNT];
    char integers[512], line[IM_HISTORY_LINE_MAX], *column = NULL, name[64];
    snprintf(integers, sizeof integers, ",%s,", im_history_integer_columns());
    const char *names = im_history_columns();
    im_history_row row;
    int integer[IM_HISTORY_COLUMN_COUNT];
    for (int i = 0; i < IM_HISTORY_COLUMN_COUNT; ++i, names += strcspn(names, ",") + 1) {
        snprintf(name, sizeof name, ",%.*s,", (int)strcspn(names, ","), names);
        integer[i] = strstr(integers, name) != NULL;
        for (int k = 0; k < IM_HISTORY_COLUMN_COUNT; ++k)
            values[k] = k + 1; /* step 1; each other column its own number */
        values[i] += 0.5;
        assert_int_equal(im_history_row_from_values(values, &row), integer[i] ? IM_EINVAL : IM_OK);
        snprintf(name, sizeof name, "%.*s = %g", (int)strcspn(names, ","), names, values[i]);
        if (integer[i]) /* the message names the column and its value */
            assert_non_null(strstr(im_last_error(), name));
    }
    for (int i = 0; i < IM_HISTORY_COLUMN_COUNT; ++i)
        values[i] = i + 1 + (integer[i] ? 0.0 : 0.5); /* every column told apart, the real ones by a fraction */
    assert_int_equal(im_history_row_from_values(values, &row), IM_OK);
    im_history_format(&row, line, sizeof line);
    column = line;
    for (int i = 0; i < IM_HISTORY_COLUMN_COUNT; ++i, column = strchr(column, ',') + 1)
        assert_true(strtod(column, NULL) == values[i]);
    assert_int_equal(im_history_row_values(&row, back), IM_OK);
    assert_memory_equal(back, values, sizeof values);
}

static void histories_without_smooth_area(void **state)
{
    (void)state;
    im_history_row rows[2];
    int count;
    char why[160], text[2048], line[IM_HISTORY_LINE_MAX];
    im_history_row row = {.step = 1,
                          .result = {.approach = 1,
                                     .load = 2,
                                     .load_star = NAN,
                                     .contact_patches = 4,
                                     .area_ratio = NAN,
                                     .iterations = 5,
                                     .residual = 1e-7},
                          .stiffness = NAN,
                          .e_star_sneddon = NAN,
                          .patches = 1,
                          .perimeter = 8};
    im_history_format(&row, line, sizeof line);
    snprintf(text, sizeof text, "%s\n%s", im_history_columns(), line);
    assert_true(im_history_parse(text, 0, rows, 2, &count, why, sizeof why));
    assert_int_equal(count, 1);
    assert_true(isnan(rows[0].result.load_star) && isnan(rows[0].result.area_ratio));
    assert_false(im_history_parse(text, 1, rows, 2, &count, why, sizeof why)); /* a cone's has numbers there */
    row.result.load_star = 3;
    im_history_format(&row, line, sizeof line);
    snprintf(text, sizeof text, "%s\n%s", im_history_columns(), line);
    assert_false(im_history_parse(text, 0, rows, 2, &count, why, sizeof why));
    row.result.load_star = NAN;
    row.result.approach = NAN;
    im_history_format(&row, line, sizeof line);
    snprintf(text, sizeof text, "%s\n%s", im_history_columns(), line);
    assert_false(im_history_parse(text, 0, rows, 2, &count, why, sizeof why));
}

/* A periodic cell's row (solver.h, "Periodic mode"): N* NaN beside a finite A / A0, which neither a smooth
 * punch's rows (N* finite) nor a 2-D profile's (both NaN) hold. */
static void histories_of_a_periodic_cell(void **state)
{
    (void)state;
    im_history_row rows[2];
    int count;
    char why[160], text[2048], line[IM_HISTORY_LINE_MAX];
    im_history_row row = {.step = 1,
                          .result = {.approach = 1,
                                     .load = 2,
                                     .load_star = NAN,
                                     .contact_patches = 4,
                                     .area_ratio = 0.25,
                                     .iterations = 5,
                                     .residual = 1e-7},
                          .stiffness = NAN,
                          .e_star_sneddon = NAN,
                          .patches = 1,
                          .perimeter = 8};
    im_history_format(&row, line, sizeof line);
    snprintf(text, sizeof text, "%s\n%s", im_history_columns(), line);
    assert_true(im_history_parse(text, IM_HISTORY_AREA_CELL, rows, 2, &count, why, sizeof why));
    assert_int_equal(count, 1);
    assert_true(isnan(rows[0].result.load_star) && rows[0].result.area_ratio == 0.25);
    assert_false(im_history_parse(text, IM_HISTORY_AREA_SMOOTH, rows, 2, &count, why, sizeof why));
    assert_false(im_history_parse(text, IM_HISTORY_AREA_NONE, rows, 2, &count, why, sizeof why));
    row.result.load_star = 3; /* a cell has no N* */
    im_history_format(&row, line, sizeof line);
    snprintf(text, sizeof text, "%s\n%s", im_history_columns(), line);
    assert_false(im_history_parse(text, IM_HISTORY_AREA_CELL, rows, 2, &count, why, sizeof why));
    row.result.load_star = NAN;
    row.result.area_ratio = NAN; /* under a load, A / A0 is a number */
    im_history_format(&row, line, sizeof line);
    snprintf(text, sizeof text, "%s\n%s", im_history_columns(), line);
    assert_false(im_history_parse(text, IM_HISTORY_AREA_CELL, rows, 2, &count, why, sizeof why));
}

/* ---- paths ---- */

static void path_join_refuses_what_does_not_fit(void **state)
{
    (void)state;
    char out[16];
    assert_int_equal(im_path_join(out, sizeof out, "dir", "name.csv"), IM_OK);
    assert_string_equal(out, "dir/name.csv");
    assert_int_equal(im_path_join(out, sizeof out, "directory", "history.csv"), IM_EINVAL);
    assert_string_equal(out, "");
    assert_non_null(strstr(im_last_error(), "path too long: 21 bytes where at most 15 fit"));
    assert_non_null(strstr(im_last_error(), "history.csv'"));
    assert_int_equal(im_path_suffix(out, sizeof out, "surface.npy", ".json"), IM_EINVAL);
    assert_int_equal(im_path_suffix(out, sizeof out, "s.npy", ".json"), IM_OK);
    assert_string_equal(out, "s.npy.json");
}

/* im_history_integer_columns names exactly the columns im_history_format writes as integers: a row
 * whose counts are 7 and whose every other value is 0.5 prints "7" in those columns only. */
static void integer_columns_as_written(void **state)
{
    (void)state;
    const double half = 0.5;
    const im_step_result result = {.approach = half,
                                   .load = half,
                                   .load_star = half,
                                   .contact_patches = 7,
                                   .area_ratio = half,
                                   .mean_pressure = half,
                                   .max_pressure = half,
                                   .iterations = 7,
                                   .convolutions = 7,
                                   .residual = half,
                                   .seconds = half,
                                   .yielding_patches = 7,
                                   .plastic_depth = half,
                                   .plastic_work = half,
                                   .residual_approach = half,
                                   .tensile_force = half,
                                   .adhesive_patches = 7,
                                   .repulsive_patches = 7,
                                   .mean_gap = half};
    const im_history_row row = {.step = 7,
                                .result = result,
                                .theory = {half, half, half, half},
                                .stiffness = half,
                                .e_star_sneddon = half,
                                .patches = 7,
                                .perimeter = half};
    char line[IM_HISTORY_LINE_MAX], names[IM_HISTORY_LINE_MAX], integers[IM_HISTORY_LINE_MAX] = "";
    assert_true(im_history_format(&row, line, sizeof line) > 0);
    snprintf(names, sizeof names, "%s", im_history_columns());
    char *name_rest = NULL, *value_rest = NULL;
    char *name = strtok_r(names, ",", &name_rest), *value = strtok_r(line, ",\n", &value_rest);
    for (; name && value; name = strtok_r(NULL, ",", &name_rest), value = strtok_r(NULL, ",\n", &value_rest))
        if (strcmp(value, "7") == 0)
            snprintf(integers + strlen(integers), sizeof integers - strlen(integers), "%s%s", integers[0] ? "," : "",
                     name);
    assert_null(name);
    assert_null(value);
    assert_string_equal(im_history_integer_columns(), integers);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(step_lists_one_limit),
        cmocka_unit_test(step_lists_same_messages),
        cmocka_unit_test(ranges_cross_zero_exactly),
        cmocka_unit_test(punch_names_one_parser),
        cmocka_unit_test(one_default_tolerance),
        cmocka_unit_test(both_histories_one_reader),
        cmocka_unit_test(area_ratio_undefined_at_a_zero_load),
        cmocka_unit_test(stiffness_is_zero_where_the_punch_is_withdrawn),
        cmocka_unit_test(other_histories_refused),
        cmocka_unit_test(row_values_are_the_written_columns),
        cmocka_unit_test(histories_without_smooth_area),
        cmocka_unit_test(histories_of_a_periodic_cell),
        cmocka_unit_test(path_join_refuses_what_does_not_fit),
        cmocka_unit_test(integer_columns_as_written),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
