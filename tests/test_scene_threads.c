/* Two scene runs at once in two threads of one process (scene.h, "Threads"): each its own scene and
 * output folder, their files the same bytes as when the two run one after the other; and again with
 * --resume's reading back (members, histories, the plans record) in both threads at once. */
#include "support.h"

#include "indentmap/scene.h"
#include "indentmap/status.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { SCENES = 2, COMPARED = 3 };

/* A history figure from displacement steps, and the table at load_star: neither renders (scene.h). */
static const char *const SCENE_TEXT[SCENES] = {
    "[scene]\nname = histories\n[surfaces]\nn = 64\nlambda_r = 64\nslopes = 0, 0.04\nseeds = 1:2\n"
    "[loading]\ncontrol = displacement\nsteps = 1:6:4\n[output]\nplots = fig5\n",
    "[scene]\nname = table\n[surfaces]\nn = 64\nlambda_r = 64\nslopes = 0, 0.08\nseeds = 1:2\n"
    "[loading]\ncontrol = load\nload_star = 300\n[output]\ntable = yes\n"};

/* The files of each run that hold no time (the members' files and run.json do). */
static const char *const COMPARED_FILES[SCENES][COMPARED] = {{"fig5.png", "fftw-plans.txt", "outputs.txt"},
                                                             {"table1.csv", "table1.md", "outputs.txt"}};

typedef struct scene_job {
    im_scene *scene;
    int resume;
    int status;
    char error[512];
} scene_job;

/* Loads scene i to write into folder `run`/i. */
static im_scene *load_scene(int i, const char *run)
{
    char name[64], folder[64];
    snprintf(name, sizeof name, "scene_%d.ini", i);
    test_write_bytes(test_path(name), SCENE_TEXT[i], strlen(SCENE_TEXT[i]));
    im_scene *scene = NULL;
    assert_int_equal(im_scene_load(test_path(name), &scene), IM_OK);
    snprintf(folder, sizeof folder, "%s_%d", run, i);
    assert_int_equal(im_scene_set_output_dir(scene, test_path(folder)), IM_OK);
    return scene;
}

static void *run_job(void *data)
{
    scene_job *job = data;
    im_scene_run_options options = {.quiet = 1, .resume = job->resume};
    job->status = im_scene_run(job->scene, &options);
    snprintf(job->error, sizeof job->error, "%s", job->status == IM_OK ? "" : im_last_error());
    return NULL;
}

static char *read_whole(const char *path, size_t *size)
{
    FILE *file = fopen(path, "rb");
    if (!file)
        fail_msg("cannot open %s", path);
    fseek(file, 0, SEEK_END);
    *size = (size_t)ftell(file);
    rewind(file);
    char *bytes = malloc(*size + 1);
    assert_non_null(bytes);
    assert_int_equal(fread(bytes, 1, *size, file), *size);
    fclose(file);
    return bytes;
}

static void assert_same_file(const char *a, const char *b)
{
    size_t size_a, size_b;
    char *bytes_a = read_whole(a, &size_a), *bytes_b = read_whole(b, &size_b);
    if (size_a != size_b || memcmp(bytes_a, bytes_b, size_a) != 0)
        fail_msg("%s (%zu bytes) differs from %s (%zu bytes)", a, size_a, b, size_b);
    free(bytes_a);
    free(bytes_b);
}

/* Runs both scenes at once, each in a thread of its own, into folders `run`_i. */
static void run_together(const char *run, int resume)
{
    scene_job jobs[SCENES];
    pthread_t threads[SCENES];
    for (int i = 0; i < SCENES; ++i) {
        jobs[i] = (scene_job){.scene = load_scene(i, run), .resume = resume};
        assert_int_equal(pthread_create(&threads[i], NULL, run_job, &jobs[i]), 0);
    }
    for (int i = 0; i < SCENES; ++i) {
        assert_int_equal(pthread_join(threads[i], NULL), 0);
        if (jobs[i].status != IM_OK)
            fail_msg("scene %d in its thread: status %d: %s", i, jobs[i].status, jobs[i].error);
        im_scene_free(jobs[i].scene);
    }
}

/* The compared files of folders `run`_i are those of alone_i. */
static void assert_same_as_alone(const char *run)
{
    for (int i = 0; i < SCENES; ++i)
        for (int f = 0; f < COMPARED; ++f) {
            char alone[96], other[96], alone_path[4096];
            snprintf(alone, sizeof alone, "alone_%d/%s", i, COMPARED_FILES[i][f]);
            snprintf(other, sizeof other, "%s_%d/%s", run, i, COMPARED_FILES[i][f]);
            snprintf(alone_path, sizeof alone_path, "%s", test_path(alone));
            assert_same_file(alone_path, test_path(other));
        }
}

static void two_runs_at_once_write_what_they_write_alone(void **state)
{
    (void)state;
    for (int i = 0; i < SCENES; ++i) { /* one after the other, in this thread */
        scene_job job = {.scene = load_scene(i, "alone")};
        run_job(&job);
        assert_int_equal(job.status, IM_OK);
        im_scene_free(job.scene);
    }
    run_together("together", 0);
    assert_same_as_alone("together");
    run_together("together", 1); /* everything read back */
    assert_same_as_alone("together");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(two_runs_at_once_write_what_they_write_alone),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
