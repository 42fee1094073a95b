/* What every reader's result must satisfy, shared by the fuzz harnesses (which abort on a
 * violation, a finding) and tests/test_fuzz_regressions.c (which fails the test). */
#ifndef INDENTMAP_FUZZ_CHECKS_H
#define INDENTMAP_FUZZ_CHECKS_H

#include "indentmap/field.h"
#include "indentmap/scene.h"
#include "scene/contents.h"
#include "indentmap/status.h"

#include <math.h>
#include <string.h>

static inline int fuzz_is_terminated(const char *text, size_t size) { return memchr(text, '\0', size) != NULL; }

/* A refusal: a known status code other than IM_OK, with a message. */
static inline int fuzz_is_refusal(int status)
{
    return status > IM_OK && status <= IM_EINTERRUPTED && im_last_error()[0] != '\0';
}

/* NULL if a surface reader's (status, field) is consistent, else what is wrong: on success a field
 * of valid size and spacing with finite values and a terminated unit, on failure no field. */
static inline const char *fuzz_field_problem(int status, const im_field *field)
{
    if (status != IM_OK)
        return field ? "a field returned with a failure" : fuzz_is_refusal(status) ? NULL : "unknown status";
    if (!field || field->nx < 1 || field->ny < 1 || field->nx > IM_FIELD_MAX_SIDE || field->ny > IM_FIELD_MAX_SIDE)
        return "success without a field of valid size";
    if (!isfinite(field->delta) || !(field->delta > 0.0) || !fuzz_is_terminated(field->unit, sizeof field->unit))
        return "success with a bad spacing or unit";
    size_t count = (size_t)field->nx * (size_t)field->ny;
    for (size_t i = 0; i < count; ++i)
        if (!isfinite(field->data[i]))
            return "success with a value that is not finite";
    return NULL;
}

/* NULL if im_scene_load's (status, scene) is consistent, else what is wrong: an accepted scene
 * (a scene, NULL when refused) holds its counts within its arrays, terminated strings, known plot bits and lambda_r > lambda_s. */
static inline const char *fuzz_scene_problem(int status, const im_scene *s)
{
    if (status != IM_OK)
        return fuzz_is_refusal(status) ? NULL : "unknown status";
    if (s->family_count < 0 || s->family_count > IM_SCENE_MAX_FAMILIES || s->seed_count < 0 ||
        s->seed_count > IM_SCENE_MAX_FAMILIES || s->step_count < 0 || s->step_count > IM_SCENE_MAX_STEPS)
        return "a count outside its array";
    if (!fuzz_is_terminated(s->name, sizeof s->name) || !fuzz_is_terminated(s->output_dir, sizeof s->output_dir) ||
        !fuzz_is_terminated(s->quality, sizeof s->quality) ||
        !fuzz_is_terminated(s->surface_file, sizeof s->surface_file))
        return "an unterminated string";
    if (s->plots >> 9) /* the bits of enum im_scene_plot: 1 << 0 .. 1 << 8 */
        return "a plot bit no plot has";
    if (!(s->surface.lambda_r > s->surface.lambda_s))
        return "lambda_r <= lambda_s accepted";
    return NULL;
}

#endif
