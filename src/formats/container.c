/* contact.engineering containers: a zip (libzip) of topography files and meta.yml (container_meta.c).
 * The topography chosen is copied into a private temporary folder and read by the reader its name
 * selects; meta.yml's size and unit then give a file that states none its spacing and unit, and its
 * height_scale multiplies that file's heights. A file that states its own (an instrument file) keeps
 * them: its sizes must agree with meta.yml's, and height_scale, contact.engineering's record of the
 * file's own factor, is not applied twice. */
#define _GNU_SOURCE /* secure_getenv, mkdtemp */
#include "indentmap/formats.h"
#include "indentmap/io.h"

#include "indentmap/status.h"
#include "formats/container.h"
#include "formats/readers.h"
#include "formats/zip_entry.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>
#include <zip.h>

enum { META_MAX_BYTES = 1 << 20 };
static const double SIZE_TOLERANCE = 1e-4; /* relative, as contact.engineering compares them */

static int read_meta(zip_t *archive, const char *path, container_meta *meta)
{
    char *text;
    size_t size;
    int status = zip_entry_read(archive, path, "meta.yml", META_MAX_BYTES,
                                "a zip archive without meta.yml: expected a contact.engineering container", &text,
                                &size);
    if (status == IM_OK)
        status = container_meta_parse(path, text, size, meta);
    free(text);
    return status;
}

/* "0 'a.asc' (line scan), 1 'b.001' (map)" for messages. */
static void list_topographies(const container_meta *meta, char *list, size_t size)
{
    static const char *const KIND[3] = {"size not stated", "line scan", "map"};
    size_t used = 0;
    list[0] = '\0';
    for (int k = 0; k < meta->count && used + 1 < size; ++k)
        used += (size_t)snprintf(list + used, size - used, "%s%d '%.40s' (%s)", k ? ", " : "", k,
                                 meta->topographies[k].name, KIND[meta->topographies[k].size_count]);
}

static int matches(const char *asked, const container_topography *t, int k)
{
    if (asked[0] && strspn(asked, "0123456789") == strlen(asked))
        return atol(asked) == k;
    return strcasecmp(asked, t->name) == 0;
}

/* The topography asked for (an index or a name, case ignored), else the first that is not a line scan. */
static int choose(const char *path, const container_meta *meta, const char *asked, int *k)
{
    char list[1024];
    list_topographies(meta, list, sizeof list);
    for (*k = 0; *k < meta->count; ++*k)
        if (asked[0] ? matches(asked, &meta->topographies[*k], *k) : meta->topographies[*k].size_count != 1)
            break;
    if (*k == meta->count && asked[0])
        return im_fail(IM_EFORMAT,
                       "%s: no topography has the index or name '%s'; its topographies: %s; choose one "
                       "with --channel",
                       path, asked, list);
    if (*k == meta->count)
        return im_fail(IM_EFORMAT,
                       "%s: a contact.engineering container of line scans only (a 2-D contact solver "
                       "cannot indent a 1-D profile); its topographies: %s",
                       path, list);
    if (meta->topographies[*k].size_count == 1)
        return im_fail(IM_EFORMAT,
                       "%s: topography %d '%s' is a line scan (meta.yml's size has one length): a 2-D "
                       "contact solver cannot indent a 1-D profile; its topographies: %s",
                       path, *k, meta->topographies[*k].name, list);
    return IM_OK;
}

/* The entry's last path component, refused when it is empty or a dot name (it names the copy). */
static int entry_file_name(const char *path, const char *entry, const char **name)
{
    const char *slash = strrchr(entry, '/');
    *name = slash ? slash + 1 : entry;
    if (!**name || **name == '.')
        return im_fail(IM_EFORMAT, "%s: meta.yml: datafile '%.100s': expected the name of a file in the archive",
                       path, entry);
    if (strlen(*name) > 4 && strcasecmp(*name + strlen(*name) - 4, ".zip") == 0)
        return im_fail(IM_EFORMAT,
                       "%s: datafile '%.100s' is a zip archive: a container inside a container is not "
                       "read",
                       path, entry);
    return IM_OK;
}

static int copy_entry(zip_t *archive, const char *path, const char *entry, const char *copy)
{
    zip_file_t *in = zip_fopen(archive, entry, 0);
    if (!in)
        return im_fail(IM_EFORMAT, "%s: meta.yml names '%.100s', which the archive cannot give: %s", path, entry,
                       zip_strerror(archive));
    FILE *out = fopen(copy, "wb");
    char block[65536];
    zip_int64_t got = 0;
    int written = out != NULL;
    while (written && (got = zip_fread(in, block, sizeof block)) > 0)
        written = fwrite(block, 1, (size_t)got, out) == (size_t)got;
    int status = got < 0    ? im_fail(IM_EFORMAT, "%s: '%.100s': %s", path, entry, zip_file_strerror(in))
                 : !written ? im_fail(IM_EIO, "%s: cannot write the copy of '%.100s' to %s", path, entry, copy)
                            : IM_OK;
    zip_fclose(in);
    if (out && fclose(out) != 0 && status == IM_OK)
        status = im_fail(IM_EIO, "%s: cannot write the copy of '%.100s' to %s", path, entry, copy);
    return status;
}

/* The topography's file read as its own reader reads it, with the caller's channel-independent options. */
static int read_inner(const char *path, const char *copy, const container_topography *t,
                      const im_surface_read_options *options, im_field **field)
{
    im_surface_read_options inner = {0};
    if (options) {
        inner.fill = options->fill;
        inner.field_values = options->field_values;
        inner.resample_square = options->resample_square;
    }
    if (t->data_source > 0)
        snprintf(inner.channel, sizeof inner.channel, "%d", t->data_source);
    int status = im_surface_read_with(copy, &inner, field, NULL);
    if (status == IM_OK)
        return IM_OK;
    char inner_refusal[600];
    snprintf(inner_refusal, sizeof inner_refusal, "%s", im_last_error());
    return im_fail(status, "%s: topography '%s' (%s): %s", path, t->name, t->datafile, inner_refusal);
}

static int read_copy(zip_t *archive, const char *path, const container_topography *t,
                     const im_surface_read_options *options, im_field **field)
{
    const char *name;
    int status = entry_file_name(path, t->datafile, &name);
    if (status != IM_OK)
        return status;
    const char *tmp = secure_getenv("TMPDIR");
    char folder[512], copy[1024];
    snprintf(folder, sizeof folder, "%s/indentmap-container-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(folder))
        return im_fail(IM_EIO, "%s: cannot make a temporary folder %s for the topography's file", path, folder);
    snprintf(copy, sizeof copy, "%s/%s", folder, name);
    status = copy_entry(archive, path, t->datafile, copy);
    if (status == IM_OK)
        status = read_inner(path, copy, t, options, field);
    unlink(copy);
    rmdir(folder);
    return status;
}

/* A file that stated its spacing: meta.yml's size, when given, must agree with it. */
static int check_sizes(const char *path, const container_topography *t, const im_field *field)
{
    double file_metres = im_length_unit_metres(field->unit, NULL);
    double meta_metres = im_length_unit_metres(t->unit[0] ? t->unit : field->unit, NULL);
    if (t->size_count != 2 || file_metres <= 0.0 || meta_metres <= 0.0)
        return IM_OK;
    double file_size[2] = {field->nx * field->delta * file_metres, field->ny * field->delta * file_metres};
    for (int k = 0; k < 2; ++k)
        if (fabs(file_size[k] - t->size[k] * meta_metres) > SIZE_TOLERANCE * file_size[k])
            return im_fail(IM_EFORMAT,
                           "%s: topography '%s': meta.yml's size %g x %g %s differs from its file's "
                           "%g x %g m beyond %g",
                           path, t->name, t->size[0], t->size[1], t->unit, file_size[0], file_size[1],
                           SIZE_TOLERANCE);
    return IM_OK;
}

/* The units a file without its own take from meta.yml, heights scaled by height_scale. */
static void apply_meta(const container_topography *t, im_field *field, surface_stated *stated)
{
    if (t->size_count == 2) {
        stated->units.delta_x = t->size[0] / field->nx;
        stated->units.delta_y = t->size[1] / field->ny;
    }
    snprintf(stated->units.lateral, sizeof stated->units.lateral, "%s", t->unit);
    if (!t->squeezed)
        for (size_t i = 0; i < im_field_count(field); ++i)
            field->data[i] *= t->height_scale;
}

/* The stated units for surface_finish, the field left bare; *scaled: height_scale was applied. */
static int stated_units(const char *path, const container_topography *t, im_field *field, surface_stated *stated,
                        int *scaled)
{
    *stated = (surface_stated){.spacing_keys = "meta.yml's size / grid",
                               .lateral_key = "meta.yml's unit",
                               .height_key = "meta.yml's unit"};
    int status = IM_OK;
    if (field->unit[0]) {
        status = check_sizes(path, t, field);
        stated->units.delta_x = stated->units.delta_y = field->delta;
        snprintf(stated->units.lateral, sizeof stated->units.lateral, "%s", field->unit);
        snprintf(stated->units.height, sizeof stated->units.height, "%s", field->unit);
    } else
        apply_meta(t, field, stated);
    *scaled = !field->unit[0] && !t->squeezed && t->height_scale != 1.0;
    field->delta = 1.0;
    field->unit[0] = '\0';
    return status;
}

static int read_archive(zip_t *archive, const char *path, const im_surface_read_options *options, im_field **out,
                        surface_stated *stated)
{
    container_meta *meta = malloc(sizeof *meta);
    if (!meta)
        return im_fail(IM_ENOMEM, "%s: allocation of meta.yml's topographies failed", path);
    int k = 0, scaled = 0, status = read_meta(archive, path, meta);
    if (status == IM_OK)
        status = choose(path, meta, options ? options->channel : "", &k);
    const container_topography *t = &meta->topographies[k];
    if (status == IM_OK)
        status = read_copy(archive, path, t, options, out);
    if (status == IM_OK)
        status = stated_units(path, t, *out, stated, &scaled);
    if (status == IM_OK)
        snprintf(stated->conversion, sizeof stated->conversion, "contact.engineering topography %d '%.30s' of %d%s",
                 k, t->name, meta->count, scaled ? ", height_scale applied" : "");
    free(meta);
    if (status != IM_OK) {
        im_field_free(*out);
        *out = NULL;
    }
    return status;
}

int container_read_raw(const char *path, const im_surface_read_options *options, im_field **out,
                       surface_stated *stated)
{
    *out = NULL;
    FILE *stream;
    int error = 0, status = im_read_open(path, "rb", IM_READ_REGULAR, &stream, NULL);
    if (status != IM_OK)
        return status;
    fclose(stream);
    zip_t *archive = zip_open(path, ZIP_RDONLY | ZIP_CHECKCONS, &error);
    if (!archive) {
        zip_error_t z;
        zip_error_init_with_code(&z, error);
        status = im_fail(IM_EFORMAT, "%s: cannot open as a zip archive (a contact.engineering container): %s", path,
                         zip_error_strerror(&z));
        zip_error_fini(&z);
        return status;
    }
    status = read_archive(archive, path, options, out, stated);
    zip_discard(archive);
    return status;
}
