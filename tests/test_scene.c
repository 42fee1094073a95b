/* Tests of the scene parser: values, defaults, and errors with file:line and suggestions. */
#include "support.h"

#include "indentmap/scene.h"
#include "indentmap/status.h"
#include "scene/contents.h"

#include <dirent.h>
#include <ini.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *write_scene(const char *name, const char *text)
{
    const char *path = test_path(name);
    test_write_bytes(path, text, strlen(text));
    return path;
}

static void values_are_read(void **state)
{
    (void)state;
    const char *path = write_scene("a.ini", "[scene]\nname = demo\n[surfaces]\nn = 64\nhurst = 0.7\n"
                                            "slopes = 0, 0.02 ,0.16\nseeds = 3:7\n"
                                            "[punch]\nshape = Sphere\nradius = 50\n"
                                            "[loading]\nsteps = 0.5:2:4\n[output]\nframes = yes\n");
    im_scene *scene = NULL;
    assert_int_equal(im_scene_load(path, &scene), IM_OK);
    assert_string_equal(scene->name, "demo");
    assert_string_equal(scene->output_dir, "output/demo");
    assert_int_equal(scene->surface.nx, 64);
    assert_int_equal(scene->surface.ny, 64);
    assert_close(scene->surface.lambda_r, 64, 0);
    assert_int_equal(scene->family_count, 3);
    assert_close(scene->slopes[1], 0.02, 0);
    assert_int_equal(scene->seed_count, 5);
    assert_int_equal(scene->seeds[4], 7);
    assert_int_equal(scene->punch, 1); /* IM_PUNCH_SPHERE */
    assert_int_equal(scene->step_count, 4);
    assert_close(scene->steps[1], 1.0, 1e-15);
    assert_true(scene->frames);
    im_scene_free(scene);
}

static void expect_error(const char *name, const char *text, const char *phrase)
{
    const char *path = write_scene(name, text);
    im_scene *scene = NULL;
    int status = im_scene_load(path, &scene);
    im_scene_free(scene);
    char expected[1024];
    snprintf(expected, sizeof expected, "%s%s", path, phrase);
    if (status != IM_EFORMAT || !strstr(im_last_error(), expected))
        fail_msg("%s: status %d, message '%s', expected to contain '%s'", name, status, im_last_error(), expected);
}

/* Sweeps: alpha, hurst and lambda_s take lists (the scalar is the first value); lists that cannot
 * run are refused at their line. */
static void sweep_lists_are_read(void **state)
{
    (void)state;
    const char *path = write_scene("sweep.ini", "[surfaces]\nn = 64\nhurst = 0.6, 0.8\nlambda_s = 4:8:3\n"
                                                "[punch]\nalpha = 80, 70\n");
    im_scene *scene = NULL;
    assert_int_equal(im_scene_load(path, &scene), IM_OK);
    assert_int_equal(scene->alpha_count, 2);
    assert_close(scene->alphas[1], 70, 0);
    assert_close(scene->alpha_degrees, 80, 0);
    assert_int_equal(scene->hurst_count, 2);
    assert_close(scene->surface.hurst, 0.6, 0);
    assert_int_equal(scene->lambda_s_count, 3);
    assert_close(scene->lambda_ss[1], 6, 1e-15);
    assert_close(scene->surface.lambda_s, 4, 0);
    im_scene_free(scene);
    const char *single = write_scene("single.ini", "[punch]\nalpha = 75\n");
    assert_int_equal(im_scene_load(single, &scene), IM_OK);
    assert_int_equal(scene->alpha_count, 1);
    assert_close(scene->alpha_degrees, 75, 0);
    im_scene_free(scene);
}

static void sweep_lists_are_refused_at_their_line(void **state)
{
    (void)state;
    expect_error("sweep_twice.ini", "[scene]\nname = s\n[punch]\nalpha = 80, 70, 80\n",
                 ":4: alpha = '80, 70, 80': 80 is given twice");
    expect_error("sweep_range.ini", "[surfaces]\nhurst = 0.8, 1.2\n",
                 ":2: hurst = '0.8, 1.2': 1.2 is outside [0.01, 0.99]");
    /* the lists take the step lists' parser: no trailing text after a range, no repeated family */
    expect_error("cone_radius.ini", "[punch]\nshape = cone\nradius = 5\n",
                 ":3: radius applies to shape = sphere or flat; a cone's shape is its alpha");
    expect_error("sweep_tail.ini", "[punch]\nalpha = 70:85:4x\n",
                 ":2: alpha = '70:85:4x': '70:85:4x' is not a range first:last:count");
    expect_error("slopes_twice.ini", "[surfaces]\nslopes = 0.08, 0.04, 0.080\n",
                 ":2: slopes = '0.08, 0.04, 0.080': 0.08 is given twice");
    expect_error("sweep_empty.ini", "[surfaces]\nlambda_s = 4,,8\n", ":2: lambda_s = '4,,8': an empty item");
    expect_error("sweep_sphere.ini", "[punch]\nshape = sphere\nalpha = 80, 70\n[output]\ntable = no\n",
                 ":3: alpha: a list of angles sweeps a cone's half-angle");
    expect_error("sweep_file.ini", "[surfaces]\nfile = s.npy\nhurst = 0.7, 0.8\n",
                 ":3: hurst: a list sweeps the generated surfaces' parameter");
    expect_error("sweep_lambda_r.ini", "[surfaces]\nlambda_r = 32\nlambda_s = 4, 40\n",
                 ":3: lambda_r = 32 must exceed lambda_s = 40");
    expect_error("sweep_points.ini", "[surfaces]\nhurst = 0.1:0.9:9\n[punch]\nalpha = 60:80:8\n",
                 ":4: the lists of alpha, hurst and lambda_s make 72 sweep points: expected at most 64");
}

/* A list of files is the ensemble of one family (reliability finding 4): one member per file, each
 * path relative to the scene; `slopes` and `seeds` beside them are refused at their line. */
static void files_form_the_ensemble(void **state)
{
    (void)state;
    const char *path = write_scene("files.ini", "[surfaces]\nfile = s.npy , sub/t.npy\ndetrend = plane\n");
    im_scene *scene = NULL;
    assert_int_equal(im_scene_load(path, &scene), IM_OK);
    assert_int_equal(scene->file_count, 2);
    assert_int_equal(scene->family_count, 1);
    assert_int_equal(scene->seed_count, 2);
    assert_int_equal(scene->detrend, 1);
    assert_true(isnan(scene->slopes[0])); /* measured when the scene runs */
    char resolved[IM_SCENE_PATH];
    assert_int_equal(im_scene_file_path(scene, 0, resolved, sizeof resolved), IM_OK);
    assert_string_equal(resolved, test_path("s.npy"));
    assert_int_equal(im_scene_file_path(scene, 1, resolved, sizeof resolved), IM_OK);
    assert_string_equal(resolved, test_path("sub/t.npy"));
    assert_int_equal(im_scene_file_path(scene, 2, resolved, sizeof resolved), IM_EINVAL);
    im_scene_free(scene);
    expect_error("slopes.ini", "[surfaces]\nfile = s.npy\nslopes = 0.16\n",
                 ":3: slopes beside `file` (line 2): a file's h'rms is measured from the file, not given");
    expect_error("seeds.ini", "[surfaces]\nseeds = 1:3\nfile = s.npy\n",
                 ":2: seeds beside `file` (line 3): the files listed in `file` are the ensemble");
    expect_error("empty.ini", "[surfaces]\nfile = s.npy,,t.npy\n", ":2: file: expected a comma-separated list");
}

/* A refused value lies outside the range its message states: the range's ends are printed to as many
 * digits as they need (alpha's end 90 - 1e-9 was printed "90", refusing 90 as "expected a number in
 * [1e-09, 90]"). */
static void refused_values_lie_outside_the_stated_range(void **state)
{
    (void)state;
    const char *cases[][2] = {{"[punch]\nalpha = 90\n", "90"},        {"[punch]\nalpha = 0\n", "0"},
                              {"[punch]\nalpha = 70, 90\n", "90"},    {"[punch]\nradius = 0\n", "0"},
                              {"[material]\nmodulus = 0\n", "0"},     {"[surfaces]\nhurst = 1\n", "1"},
                              {"[output]\nframe_rate = 200\n", "200"}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        im_scene *scene = NULL;
        assert_int_equal(im_scene_load(write_scene("outside.ini", cases[i][0]), &scene), IM_EFORMAT);
        im_scene_free(scene);
        const char *range = strrchr(im_last_error(), '[');
        assert_non_null(range);
        char *end;
        double lo = strtod(range + 1, &end), hi = strtod(end + 1, NULL), value = strtod(cases[i][1], NULL);
        if (!(value < lo || value > hi))
            fail_msg("%s refused as '%s': %s lies in the stated range", cases[i][0], im_last_error(), cases[i][1]);
    }
}

static void errors_name_the_line(void **state)
{
    (void)state;
    expect_error("key.ini", "[surfaces]\nn = 64\n\nhurts = 0.8\n",
                 ":4: unknown key 'hurts' in [surfaces]; did you mean 'hurst'?");
    expect_error("section.ini", "; comment\n[surface]\nn = 64\n",
                 ":3: unknown section [surface]; did you mean [surfaces]?");
    expect_error("range.ini", "[punch]\nalpha = 95\n", ":2: alpha = '95': expected a number in");
    expect_error("number.ini", "[surfaces]\nn = 64x\n", ":2: n = '64x': expected an integer");
    expect_error("choice.ini", "[punch]\nshape = pyramid\n",
                 ":2: shape = 'pyramid': expected cone, sphere, flat or profile");
    expect_error("malformed.ini", "[punch]\nshape = cone\nthis line has no equals sign\n[material]\nmodulus = -1\n",
                 ":3: malformed line");
    expect_error("first.ini", "[punch]\nalpha = 100\nshape = pyramid\n", ":2: alpha");
    expect_error("list.ini", "[surfaces]\nslopes = 0.01, abc\n", ":2: slopes = '0.01, abc': ' abc' is not a number");
    expect_error("order.ini", "[loading]\ncontrol = load\n\nsteps = 3, 2\n", ":4: steps must increase");
    /* with a hardness a history may unload (the cap remembers): the same list is read */
    im_scene *unloading = NULL;
    assert_int_equal(im_scene_load(write_scene("unload.ini", "[material]\nhardness = 0.1\n[loading]\ncontrol = "
                                                             "load\nsteps = 1:3:3, 2\n"),
                                   &unloading),
                     IM_OK);
    assert_int_equal(unloading->step_count, 4);
    assert_true(unloading->steps[3] == 2.0);
    im_scene_free(unloading);
    expect_error("lambda.ini", "[surfaces]\nlambda_r = 8\nhurst = 0.8\nlambda_s = 16\n",
                 ":4: lambda_r = 8 must exceed");
    expect_error("lambda_r.ini", "[surfaces]\nlambda_s = 16\nlambda_r = 8\n", ":3: lambda_r = 8 must exceed");
    expect_error("box.ini", "[surfaces]\nlambda_s = 16\n\nn = 16\n",
                 ":4: lambda_r = 16 must exceed lambda_s = 16 "
                 "(lambda_r defaults to the box's side)");
}

static void missing_file_is_an_io_error(void **state)
{
    (void)state;
    im_scene *scene = NULL;
    assert_int_equal(im_scene_load(test_path("none.ini"), &scene), IM_EIO);
    assert_null(scene);
    assert_non_null(strstr(im_last_error(), "none.ini: cannot open"));
}

/* "slopes = 0.001, 0.002, ..." of exactly length characters (blanks pad the last item); returns how
 * many values it lists. */
static int slopes_line(char *out, size_t length)
{
    size_t used = (size_t)snprintf(out, length + 1, "slopes = 0.001");
    int count = 1;
    while (used + 7 <= length) /* ", 0.0NN" */
        used += (size_t)snprintf(out + used, length + 1 - used, ", 0.%03d", ++count);
    memmove(out + length - 5, out + used - 5, 5); /* keep the last value at the end ... */
    memset(out + used - 5, ' ', length - used);   /* ... after blanks that a token may have */
    out[length] = '\0';
    return count;
}

/* A seed range is of non-negative integers, first <= last: "-3:-1" was read by %llu as the seeds
 * 2^64 - 3 .. 2^64 - 1 and solved, "4:1" refused as a range of too many seeds. */
static void seed_ranges_are_checked(void **state)
{
    (void)state;
    expect_error("negative_range.ini", "[surfaces]\nseeds = -3:-1\n", ":2: seeds = '-3:-1': a '-' (a negative seed");
    expect_error("negative_first.ini", "[surfaces]\nseeds = -1:2\n", ":2: seeds = '-1:2': a '-' (a negative seed");
    expect_error("negative_list.ini", "[surfaces]\nseeds = 1, -2\n", ":2: seeds = '1, -2': a '-' (a negative seed");
    expect_error("dash_range.ini", "[surfaces]\nseeds = 1-3\n",
                 ":2: seeds = '1-3': a '-' (a negative seed, or a range "
                 "written first-last?)");
    expect_error("reversed.ini", "[surfaces]\nseeds = 4:1\n",
                 ":2: seeds = '4:1': expected first:last with first <= last");
    expect_error("too_many.ini", "[surfaces]\nseeds = 1:65\n",
                 ":2: seeds = '1:65': expected first:last with at most 64");
    im_scene *scene = NULL;
    assert_int_equal(im_scene_load(write_scene("top.ini", "[surfaces]\nseeds = 0:63\n"), &scene), IM_OK);
    assert_int_equal(scene->seed_count, 64);
    assert_true(scene->seeds[63] == 63);
    im_scene_free(scene);
}

/* inih reads into a buffer of INI_MAX_LINE bytes (200 in Debian's build) and would cut a longer
 * line in two, parsing the tail as a separate line or even as a continuation of the value. */
static void long_lines_are_refused(void **state)
{
    (void)state;
    char line[512], text[1024], expected[128];
    const int limit = INI_MAX_LINE - 1; /* characters, the newline not counted */
    int count = slopes_line(line, (size_t)limit);
    assert_int_equal((int)strlen(line), limit);
    snprintf(text, sizeof text, "[surfaces]\n%s\nseeds = 1:2\n", line);
    im_scene *scene = NULL;
    assert_int_equal(im_scene_load(write_scene("fits.ini", text), &scene), IM_OK);
    assert_int_equal(scene->family_count, count);
    assert_close(scene->slopes[count - 1], count * 1e-3, 1e-15);
    assert_int_equal(scene->seed_count, 2);
    im_scene_free(scene);

    slopes_line(line, (size_t)limit + 1);
    snprintf(text, sizeof text, "[surfaces]\n%s\nseeds = 1:2\n", line);
    snprintf(expected, sizeof expected, ":2: line longer than %d characters", limit);
    expect_error("long.ini", text, expected);
    /* the old failure: a tail beginning with a blank read as a continuation, replacing the list */
    slopes_line(line, 400);
    snprintf(text, sizeof text, "[scene]\nname = x\n[surfaces]\n%s\n", line);
    expect_error("continued.ini", text, ":4: line longer than");
    /* a key error before the long line is the one reported */
    snprintf(text, sizeof text, "[surfaces]\nhurst = 2\n%s\n", line);
    expect_error("first_error.ini", text, ":2: hurst");
}

static void binary_and_unreadable_files_are_refused(void **state)
{
    (void)state;
    const char *path = test_path("nul.ini");
    test_write_bytes(path, "[scene]\nname = a\0b\n", 19);
    im_scene *scene = NULL;
    assert_int_equal(im_scene_load(path, &scene), IM_EFORMAT);
    assert_non_null(strstr(im_last_error(), ":2: a NUL byte"));
    /* a directory opens for reading on Linux, but is refused before any read; so is a device */
    assert_int_equal(im_scene_load(test_temp_dir(), &scene), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "is a directory"));
    assert_int_equal(im_scene_load("/dev/zero", &scene), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "/dev/zero is a character device"));
}

/* What callers outside the library read of a scene, and the settings they give it. */
static void accessors_read_the_scene(void **state)
{
    (void)state;
    const char *path = write_scene("read.ini", "[scene]\nname = seen\n[loading]\nload_star = 10\n[output]\n"
                                               "contact_panels = yes\n");
    im_scene *scene = NULL;
    assert_int_equal(im_scene_load(path, &scene), IM_OK);
    assert_string_equal(im_scene_path(scene), path);
    assert_string_equal(im_scene_name(scene), "seen");
    assert_string_equal(im_scene_output_dir(scene), "output/seen");
    assert_int_equal(im_scene_recorded_plans(scene), -1);
    assert_int_equal(im_scene_asks_for_output(scene), 1);
    assert_int_equal(im_scene_renders(scene), 1);
    assert_int_equal(im_scene_set_output_dir(scene, "elsewhere"), IM_OK);
    assert_string_equal(im_scene_output_dir(scene), "elsewhere");
    char *long_dir = malloc(IM_SCENE_PATH + 1);
    assert_non_null(long_dir);
    memset(long_dir, 'd', IM_SCENE_PATH);
    long_dir[IM_SCENE_PATH] = '\0';
    assert_int_equal(im_scene_set_output_dir(scene, long_dir), IM_EINVAL);
    assert_non_null(strstr(im_last_error(), "4096 bytes: expected a path shorter than 4096 bytes"));
    assert_string_equal(im_scene_output_dir(scene), "elsewhere"); /* left as it was */
    free(long_dir);
    im_scene_free(scene);
    assert_int_equal(
        im_scene_load(write_scene("quiet.ini", "[scene]\nname = quiet\n[output]\nplots = fig1\n"), &scene), IM_OK);
    assert_int_equal(im_scene_asks_for_output(scene), 1);
    assert_int_equal(im_scene_renders(scene), 0);
    im_scene_free(scene);
    assert_int_equal(im_scene_load(write_scene("no_output.ini", "[scene]\nname = none\n"), &scene), IM_OK);
    assert_int_equal(im_scene_asks_for_output(scene), 0);
    im_scene_free(scene);
}

/* Every bundled scene parses. */
static void bundled_scenes_parse(void **state)
{
    (void)state;
    const char *source = getenv("IM_SOURCE_DIR");
    assert_non_null(source);
    char folder[2048];
    snprintf(folder, sizeof folder, "%s/scenes", source);
    DIR *dir = opendir(folder);
    assert_non_null(dir);
    int parsed = 0;
    for (struct dirent *entry; (entry = readdir(dir));) {
        size_t length = strlen(entry->d_name);
        if (length < 5 || strcmp(entry->d_name + length - 4, ".ini") != 0)
            continue;
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", folder, entry->d_name);
        im_scene *scene = NULL;
        if (im_scene_load(path, &scene) != IM_OK)
            fail_msg("%s", im_last_error());
        im_scene_free(scene);
        ++parsed;
    }
    closedir(dir);
    assert_true(parsed >= 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(values_are_read),
        cmocka_unit_test(accessors_read_the_scene),
        cmocka_unit_test(files_form_the_ensemble),
        cmocka_unit_test(refused_values_lie_outside_the_stated_range),
        cmocka_unit_test(errors_name_the_line),
        cmocka_unit_test(missing_file_is_an_io_error),
        cmocka_unit_test(seed_ranges_are_checked),
        cmocka_unit_test(long_lines_are_refused),
        cmocka_unit_test(binary_and_unreadable_files_are_refused),
        cmocka_unit_test(bundled_scenes_parse),
        cmocka_unit_test(sweep_lists_are_read),
        cmocka_unit_test(sweep_lists_are_refused_at_their_line),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
