/* The JSON run record of `indent` and of scenes (OUTPUT/run.json): one set of common fields, one
 * writer. */
#include "front/front.h"
#include "io/checksum.h"
#include "io/json_file.h"

#include "indentmap/io.h"
#include "indentmap/status.h"

#include <limits.h>
#include <stdio.h>

/* The solver options a run was made with. The accelerations of issue 15 are on unless switched
 * off, and off with a hardness (solver.h). */
static json_t *solver_record(const run_record_solver *s)
{
    const im_solver_options *o = s->options;
    const int capped = o->hardness > 0;
    static const char *const devices[] = {[IM_DEVICE_CPU] = "cpu", [IM_DEVICE_GPU] = "gpu", [IM_DEVICE_AUTO] = "auto"};
    return json_pack("{s:s, s:f, s:s, s:f, s:i, s:f, s:b, s:i, s:b, s:b, s:b, s:s}", "quality", s->quality, "tol", o->tol,
                     "tol_from", s->tol_from, "e_star", o->e_star, "max_iterations", o->max_iterations, "hardness",
                     o->hardness, "crop", o->crop, "window_margin", o->window_margin, "cascade",
                     o->cascade && !capped, "precondition", o->precondition && !capped, "fftw_wisdom",
                     im_solver_wisdom_file(o) != NULL, "device", devices[o->device]);
}

json_t *run_record_create(const char *program, const char *input_kind, const char *input_path,
                          const run_record_solver *solver)
{
    char path[4 * PATH_MAX + 1]; /* a path is bytes; JSON is UTF-8 */
    int escaped = input_path ? im_path_utf8(input_path, path, sizeof path) : 0;
    json_t *input = json_pack("{s:s}", "kind", input_kind);
    if (input && input_path)
        json_object_set_new(input, "path", json_string(path));
    if (input && escaped) /* the path is not UTF-8: its other bytes are written \xHH, backslashes \\ */
        json_object_set_new(input, "path_encoding", json_string("escaped"));
    return json_pack("{s:s, s:s, s:o, s:o}", "program", program, "version", IM_VERSION, "input", input, "solver",
                     solver_record(solver));
}

int run_record_write(const char *dir, const json_t *record)
{
    char path[4096];
    int status = im_path_join(path, sizeof path, dir, "run.json");
    if (status != IM_OK)
        return status;
    return json_file_write(path, record);
}

int run_record_add_input(json_t *inputs, const char *key, const char *path)
{
    char hex[IM_SHA256_HEX + 1], absolute[PATH_MAX], text[4 * PATH_MAX + 1];
    int status = im_file_sha256(path, hex);
    if (status == IM_OK)
        status = im_path_absolute(path, absolute, sizeof absolute);
    if (status != IM_OK)
        return status;
    im_path_utf8(absolute, text, sizeof text);
    return json_array_append_new(inputs, json_pack("{s:s, s:s, s:s}", "key", key, "path", text, "sha256", hex)) == 0
               ? IM_OK
               : im_fail(IM_ENOMEM, "run.json: out of memory");
}

int run_record_finish(const char *dir, json_t *record, int steps_done, int status)
{
    json_object_set_new(record, "steps_completed", json_integer(steps_done));
    json_object_set_new(record, "status", json_string(status == IM_OK ? "ok" : im_strstatus(status)));
    char error[4 * 1024 + 1]; /* a message may quote a path that is not UTF-8 */
    im_path_utf8(status == IM_OK ? "" : im_last_error(), error, sizeof error);
    json_object_set_new(record, "error", json_string(error));
    return run_record_write(dir, record);
}
