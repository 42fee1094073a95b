/* The files of one solved step (front.h, "files of a step"): its fields and its distributions, written
 * alike by `indent --fields/--distributions` and a periodic scene's contact panels and distributions. */
#include "front/front.h"

#include "indentmap/io.h"
#include "indentmap/formats.h"
#include "indentmap/measure.h"
#include "indentmap/status.h"

#include <stdio.h>
#include <string.h>

const char *const STEP_FIELD_PREFIXES[STEP_FIELDS_MAX] = {"force_", "gap_", "displacement_", "plastic_"};

static const char *const STEP_FIELD_QUANTITIES[STEP_FIELDS_MAX] = {
    "force per patch", "gap", "surface displacement", "plastic depth (the surface flattened down by yielding)"};

int step_field_count(double hardness) { return hardness > 0 ? STEP_FIELDS_MAX : STEP_FIELDS_MAX - 1; }

void step_force_unit(const char *e_star_unit, const char *length_unit, char *out, size_t size)
{
    if (strcmp(e_star_unit, "Pa") == 0 && strcmp(length_unit, "m") == 0)
        snprintf(out, size, "N");
    else
        snprintf(out, size, "%s %s\u00b2", e_star_unit[0] ? e_star_unit : "E*",
                 length_unit[0] ? length_unit : "\u03b4");
}

/* FILE.npy, then FILE.npy.json beside it, under one lock so that no reader pairs two writers' halves. */
static int write_field_pair(const char *path, const im_field *field, const char *quantity)
{
    int pair_lock = im_pair_writers_lock(path);
    int status = pair_lock < 0 ? IM_EIO : im_npy_write(path, field, IM_NPY_FLOAT64);
    if (status == IM_OK)
        status = im_field_sidecar_write(path, field, quantity);
    im_pair_writers_unlock(pair_lock);
    return status;
}

int step_field_write(const char *dir, int step, int which, im_field *field, const step_units *units)
{
    char name[64], path[4096];
    snprintf(name, sizeof name, "%s%04d.npy", STEP_FIELD_PREFIXES[which], step);
    int status = im_path_join(path, sizeof path, dir, name);
    if (status != IM_OK)
        return status;
    snprintf(field->unit, sizeof field->unit, "%s", units->length_unit);
    if (which == 0)
        snprintf(field->value_unit, sizeof field->value_unit, "%s", units->force_unit);
    return write_field_pair(path, field, STEP_FIELD_QUANTITIES[which]);
}

int step_fields_write(const char *dir, im_indentation *run, int step, const step_units *units)
{
    im_field *f[STEP_FIELDS_MAX] = {NULL, NULL, NULL, NULL};
    const int count = step_field_count(units->hardness);
    int status = im_indentation_fields_full(run, &f[0], &f[1], &f[2]);
    if (status == IM_OK && count == STEP_FIELDS_MAX)
        status = im_indentation_plastic(run, &f[3]);
    for (int i = 0; i < count && status == IM_OK; ++i)
        status = step_field_write(dir, step, i, f[i], units);
    for (int i = 0; i < STEP_FIELDS_MAX; ++i)
        im_field_free(f[i]);
    return status;
}

int step_distributions_write(const char *prefix, im_indentation *run, double gap_scale)
{
    im_field *force = NULL, *gap = NULL;
    int status = im_indentation_fields_full(run, &force, &gap, NULL);
    if (status == IM_OK)
        status = im_measure_write_distributions(force, gap, gap_scale, IM_MEASURE_GAP_BINS, prefix);
    im_field_free(force);
    im_field_free(gap);
    return status;
}
