/* Every input the fuzzers found (fuzz/regressions/NAME/) and every seed (fuzz/corpus/NAME/) goes
 * through the same reader as in its harness: each must come back as a status with a consistent
 * result (fuzz/fuzz_checks.h), with no crash and, in the sanitizer build, no ASan/UBSan report.
 * Seeds named valid_* must be accepted; the crash inputs and the near-valid seeds are files a
 * reader may refuse. */
#include "support.h"

#include "../fuzz/fuzz_checks.h"
#include "indentmap/io.h"
#include "indentmap/formats.h"
#include "indentmap/scene.h"
#include "formats/gwyddion.h"
#include "formats/hdf5.h"
#include "formats/readers.h"

#include <dirent.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef int (*surface_reader)(const char *path, im_field **out);

/* The readers the harnesses fuzz_tmd, fuzz_hdf5 and fuzz_container call, as those call them. */
static int tmd_read(const char *path, im_field **out)
{
    return surface_read_format(path, tmd_read_raw, NULL, out, NULL);
}
static int hdf5_read(const char *path, im_field **out)
{
    return surface_read_channel_format(path, hdf5_read_in_process, NULL, out, NULL);
}

/* Inputs that crash libhdf5 itself: read in this process, as fuzz_hdf5 reads, they would end the test, so
 * they are not replayed that way; the library reads HDF5 in a child, and
 * libhdf5_crashes_are_refused_from_a_child reads them so. */
static const char LIBHDF5_CRASH[] = "libhdf5-crash-";
static int container_read(const char *path, im_field **out)
{
    return surface_read_channel_format(path, container_read_raw, NULL, out, NULL);
}

/* The harness name's reader applied to path; NULL if the result is consistent, else the problem. */
static const char *read_like_harness(const char *harness, const char *path, int *status)
{
    if (strcmp(harness, "scene") == 0) {
        im_scene *scene = NULL;
        *status = im_scene_load(path, &scene);
        const char *problem = fuzz_scene_problem(*status, scene);
        im_scene_free(scene);
        return problem;
    }
    surface_reader read = strcmp(harness, "npy") == 0         ? im_npy_read
                          : strcmp(harness, "gsf") == 0       ? im_gsf_read
                          : strcmp(harness, "sdf") == 0       ? im_sdf_read
                          : strcmp(harness, "netcdf") == 0    ? im_netcdf_read
                          : strcmp(harness, "x3p") == 0       ? im_x3p_read
                          : strcmp(harness, "tmd") == 0       ? tmd_read
                          : strcmp(harness, "hdf5") == 0      ? hdf5_read
                          : strcmp(harness, "container") == 0 ? container_read
                          : strcmp(harness, "gwyddion") == 0  ? gwyddion_stream_file_read
                                                              : im_text_read;
    im_field *field = NULL;
    *status = read(path, &field);
    const char *problem = fuzz_field_problem(*status, field);
    im_field_free(field);
    return problem;
}

/* Feeds every file of fuzz/FOLDER/HARNESS; returns how many there were. */
static int feed_folder(const char *folder, const char *harness)
{
    char directory[4096];
    snprintf(directory, sizeof directory, "%s/fuzz/%s/%s", getenv("IM_SOURCE_DIR"), folder, harness);
    DIR *dir = opendir(directory);
    if (!dir)
        return 0;
    int count = 0;
    for (struct dirent *entry; (entry = readdir(dir));) {
        if (entry->d_name[0] == '.' || strncmp(entry->d_name, LIBHDF5_CRASH, strlen(LIBHDF5_CRASH)) == 0)
            continue;
        char path[8192];
        snprintf(path, sizeof path, "%s/%s", directory, entry->d_name);
        int status;
        const char *problem = read_like_harness(harness, path, &status);
        if (problem)
            fail_msg("%s: %s (status %d: %s)", path, problem, status, im_last_error());
        if (strncmp(entry->d_name, "valid_", 6) == 0 && status != IM_OK)
            fail_msg("%s: a valid seed was refused: %s", path, im_last_error());
        ++count;
    }
    closedir(dir);
    return count;
}

static void feed_harness(const char *harness)
{
    assert_non_null(getenv("IM_SOURCE_DIR"));
    assert_true(feed_folder("corpus", harness) >= 5); /* the seeds are there, so the path is right */
    feed_folder("regressions", harness);
}

static void scene_inputs(void **state)
{
    (void)state;
    feed_harness("scene");
}
static void npy_inputs(void **state)
{
    (void)state;
    feed_harness("npy");
}
static void text_inputs(void **state)
{
    (void)state;
    feed_harness("text");
}
static void gsf_inputs(void **state)
{
    (void)state;
    feed_harness("gsf");
}
static void sdf_inputs(void **state)
{
    (void)state;
    feed_harness("sdf");
}
static void netcdf_inputs(void **state)
{
    (void)state;
    feed_harness("netcdf");
}
static void x3p_inputs(void **state)
{
    (void)state;
    feed_harness("x3p");
}
static void tmd_inputs(void **state)
{
    (void)state;
    feed_harness("tmd");
}
static void hdf5_inputs(void **state)
{
    (void)state;
    feed_harness("hdf5");
}
static void container_inputs(void **state)
{
    (void)state;
    feed_harness("container");
}
static void gwyddion_inputs(void **state)
{
    (void)state;
    feed_harness("gwyddion");
}

/* fuzz_npy's out-of-memory input (and its .gsf twin): a header claiming 30000 x 30000 values over
 * no data made the reader allocate 7.2 GB before finding the data missing. The refusal must now
 * come from the size check that runs before the allocation, which names the bytes needed. */
static void oversized_headers_are_refused_before_allocation(void **state)
{
    (void)state;
    const char *files[] = {"npy/oom_shape_30000x30000.npy", "gsf/oom_xres_30000x30000.gsf"};
    const surface_reader readers[] = {im_npy_read, im_gsf_read};
    const char *needs[] = {"needs 7200000000 bytes after it, the file has 0",
                           "needs 3600000000 bytes after it, the file has 0"};
    for (int i = 0; i < 2; ++i) {
        char path[4096];
        snprintf(path, sizeof path, "%s/fuzz/regressions/%s", getenv("IM_SOURCE_DIR"), files[i]);
        im_field *field = NULL;
        int status = readers[i](path, &field);
        assert_null(field);
        if (status == IM_ENOMEM && strstr(im_last_error(), "MiB are available"))
            continue; /* a machine with less than the 7.2 GB free refuses it earlier still */
        if (status != IM_EFORMAT || !strstr(im_last_error(), needs[i]))
            fail_msg("%s: status %d '%s', expected the early size check ('%s')", files[i], status, im_last_error(),
                     needs[i]);
    }
}

/* fuzz/regressions/netcdf/FILE is refused with IM_EFORMAT and a message that starts with its name
 * and goes on with `message`. */
static void assert_netcdf_refused(const char *file, const char *message)
{
    char path[4096], expected[512];
    snprintf(path, sizeof path, "%s/fuzz/regressions/netcdf/%s", getenv("IM_SOURCE_DIR"), file);
    snprintf(expected, sizeof expected, "%s: %s", file, message);
    im_field *field = NULL;
    assert_int_equal(im_netcdf_read(path, &field), IM_EFORMAT);
    assert_null(field);
    if (!strstr(im_last_error(), expected))
        fail_msg("expected '%s' in '%s'", expected, im_last_error());
}

/* fuzz_netcdf's second out-of-memory input: a 3176-byte classic file whose dimensions declare
 * 63555 x 14082 heights made the reader allocate 7.2 GB before netCDF found the data missing (the
 * header walk had passed it: its stated vsize was small). Refused before the allocation. */
static void netcdf_dimensions_beyond_the_file_are_refused_before_allocation(void **state)
{
    (void)state;
    assert_netcdf_refused("oom_dims_63555x14082.nc", "truncated: heights (63555 x 14082 values of 8 bytes) needs "
                                                     "7159852080 bytes, the file has 3176");
}

/* fuzz_netcdf's out-of-memory input: an 88-byte classic header whose name length made netCDF allocate
 * gigabytes before finding the file too short. The reader's own walk over the header refuses it
 * first, naming the file. */
static void hostile_netcdf_header_is_refused_before_netcdf(void **state)
{
    (void)state;
    assert_netcdf_refused("oom_name_length.nc", "netCDF header: a count or name runs past the end");
}

/* fuzz_netcdf's crash: a CDF2 header whose variable has an nc_type of no known size made netCDF
 * divide by zero (SIGFPE in NC_check_vlen). Refused by the reader's walk, naming the file. */
static void unknown_type_is_refused_before_netcdf(void **state)
{
    (void)state;
    assert_netcdf_refused("unknown_type_divides_by_zero.nc", "netCDF header: a variable of no known type");
}

/* path refused with IM_EFORMAT and exactly "PATH: PARSER crashed reading it (signal 11): the file is damaged or
 * hostile". */
static void assert_crash_refused(const char *path, const char *parser)
{
    char expected[8400];
    snprintf(expected, sizeof expected, "%s: %s crashed reading it (signal %d): the file is damaged or hostile", path,
             parser, SIGSEGV);
    im_field *field = NULL;
    int status = im_surface_read(path, &field);
    assert_null(field);
    if (status != IM_EFORMAT || strcmp(im_last_error(), expected) != 0)
        fail_msg("status %d '%s', expected '%s'", status, im_last_error(), expected);
}

/* fuzz_hdf5's SIGSEGV inside libhdf5 1.10.8 (H5Ovisit -> H5B_get_info -> H5F_block_read: a memcpy into a
 * failed allocation of a size the file states) ended the caller (exit 139; a Python kernel with it), and
 * named .nc it did the same through netCDF. Read in a child, each such file is refused naming it and saying
 * that libhdf5 crashed, and this process goes on. */
static void libhdf5_crashes_are_refused_from_a_child(void **state)
{
    (void)state;
    char directory[4096];
    snprintf(directory, sizeof directory, "%s/fuzz/regressions/hdf5", getenv("IM_SOURCE_DIR"));
    DIR *dir = opendir(directory);
    assert_non_null(dir);
    int count = 0;
    for (struct dirent *entry; (entry = readdir(dir));) {
        if (strncmp(entry->d_name, LIBHDF5_CRASH, strlen(LIBHDF5_CRASH)) != 0)
            continue;
        char path[8192];
        snprintf(path, sizeof path, "%s/%s", directory, entry->d_name);
        assert_crash_refused(path, "the HDF5 library (libhdf5)");
        test_copy_file(path, test_path("hostile.nc"));
        assert_crash_refused(test_path("hostile.nc"), "netCDF's HDF5 layer (libnetcdf, libhdf5)");
        ++count;
    }
    closedir(dir);
    assert_true(count >= 1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(scene_inputs),
        cmocka_unit_test(npy_inputs),
        cmocka_unit_test(text_inputs),
        cmocka_unit_test(gsf_inputs),
        cmocka_unit_test(sdf_inputs),
        cmocka_unit_test(netcdf_inputs),
        cmocka_unit_test(x3p_inputs),
        cmocka_unit_test(tmd_inputs),
        cmocka_unit_test(hdf5_inputs),
        cmocka_unit_test(container_inputs),
        cmocka_unit_test(gwyddion_inputs),
        cmocka_unit_test(oversized_headers_are_refused_before_allocation),
        cmocka_unit_test(netcdf_dimensions_beyond_the_file_are_refused_before_allocation),
        cmocka_unit_test(hostile_netcdf_header_is_refused_before_netcdf),
        cmocka_unit_test(unknown_type_is_refused_before_netcdf),
        cmocka_unit_test(libhdf5_crashes_are_refused_from_a_child),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
