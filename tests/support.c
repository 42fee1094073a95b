#include "support.h"

#include <dlfcn.h>

#include "indentmap/status.h"
#include "indentmap/surface.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static char temp_dir[512];

static void remove_temp_dir(void)
{
    char command[600];
    snprintf(command, sizeof command, "rm -rf '%s'", temp_dir);
    if (system(command) != 0)
        fprintf(stderr, "could not remove %s\n", temp_dir);
}

const char *test_temp_dir(void)
{
    if (temp_dir[0] == '\0') {
        const char *base = getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp";
        snprintf(temp_dir, sizeof temp_dir, "%s/indentmap-test-XXXXXX", base);
        if (!mkdtemp(temp_dir)) {
            perror("mkdtemp");
            exit(1);
        }
        atexit(remove_temp_dir);
    }
    return temp_dir;
}

const char *test_path(const char *name)
{
    static char buffers[8][700];
    static int next;
    char *buffer = buffers[next++ % 8];
    snprintf(buffer, sizeof buffers[0], "%s/%s", test_temp_dir(), name);
    return buffer;
}

void test_write_bytes(const char *path, const void *data, size_t size)
{
    FILE *stream = fopen(path, "wb");
    assert_non_null(stream);
    assert_int_equal(fwrite(data, 1, size, stream), size);
    assert_int_equal(fclose(stream), 0);
}

void test_copy_file(const char *from, const char *to)
{
    FILE *source = fopen(from, "rb");
    assert_non_null(source);
    assert_int_equal(fseek(source, 0, SEEK_END), 0);
    long size = ftell(source);
    assert_true(size >= 0);
    char *bytes = malloc((size_t)size + 1);
    assert_non_null(bytes);
    rewind(source);
    assert_int_equal(fread(bytes, 1, (size_t)size, source), (size_t)size);
    fclose(source);
    test_write_bytes(to, bytes, (size_t)size);
    free(bytes);
}

/* The name after the next comma of a comma-separated list, or NULL after the last. */
static const char *next_name(const char *at)
{
    const char *comma = strchr(at, ',');
    return comma ? comma + 1 : NULL;
}

/* Whether the list's name at `at` (up to a comma or the end) is `name`. */
static int name_is(const char *at, const char *name)
{
    const size_t length = strcspn(at, ",");
    return strncmp(at, name, length) == 0 && name[length] == '\0';
}

static int listed(const char *list, const char *name)
{
    for (const char *at = list; at; at = next_name(at))
        if (name_is(at, name))
            return 1;
    return 0;
}

/* Exits with status 2 naming the first name of `list` that no case has. */
static void refuse_unknown_names(const char *program, const char *list, const struct CMUnitTest *tests, size_t count)
{
    for (const char *at = list; at; at = next_name(at)) {
        size_t k = 0;
        while (k < count && !name_is(at, tests[k].name))
            ++k;
        if (k == count) {
            fprintf(stderr, "%s: '%.*s' is not one of its cases: expected case names separated by commas\n", program,
                    (int)strcspn(at, ","), at);
            exit(2);
        }
    }
}

int test_run_cases(const struct CMUnitTest *tests, size_t count, int argc, char **argv)
{
    const int skip = argc == 3 && strcmp(argv[1], "--skip") == 0;
    if (argc > 1 && !skip && !(argc == 2 && argv[1][0] != '-')) {
        fprintf(stderr, "%s: '%s': expected no argument, case NAMES (comma-separated) or --skip NAMES\n", argv[0],
                argv[1]);
        exit(2);
    }
    const char *names = argc > 1 ? argv[argc - 1] : NULL;
    if (names)
        refuse_unknown_names(argv[0], names, tests, count);
    struct CMUnitTest *chosen = malloc(sizeof *chosen * count);
    size_t n = 0;
    for (size_t k = 0; chosen && k < count; ++k)
        if (!names || listed(names, tests[k].name) != skip)
            chosen[n++] = tests[k];
    const int failed = chosen ? _cmocka_run_group_tests("tests", chosen, n, NULL, NULL) : 1;
    free(chosen);
    return failed;
}

double test_relative_difference(double a, double b)
{
    double scale = fmax(fmax(fabs(a), fabs(b)), 1e-300);
    return fabs(a - b) / scale;
}

im_field *test_rough_surface(int n, double slope, uint64_t seed)
{
    im_surface_params p = im_surface_params_default();
    p.nx = p.ny = n;
    p.lambda_r = n;
    p.slope_rms = slope;
    p.seed = seed;
    im_field *s = NULL;
    assert_int_equal(im_surface_generate(&p, &s), IM_OK);
    return s;
}

void test_keep_vulkan_libraries_loaded(void)
{
#ifdef __SANITIZE_ADDRESS__
    static const char *const libraries[] = {"libvulkan_lvp.so", "libVkLayer_khronos_validation.so",
                                            "libVkLayer_MESA_device_select.so"};
    for (size_t i = 0; i < sizeof libraries / sizeof libraries[0]; ++i)
        dlopen(libraries[i], RTLD_NOW | RTLD_NODELETE); /* never closed, on purpose */
#endif
}
