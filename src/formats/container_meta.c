/* meta.yml of a contact.engineering container, read with libyaml: surfaces[].topographies[], each with
 * name, datafile (original, else squeezed-netcdf), data_source, size, unit and height_scale. */
#include "formats/container.h"

#include "indentmap/status.h"
#include "core/number.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <yaml.h>

typedef struct meta_reader {
    yaml_document_t *document;
    const char *path;
} meta_reader;

static yaml_node_t *node_at(const meta_reader *m, int index)
{
    return index ? yaml_document_get_node(m->document, index) : NULL;
}

/* The value of key in a mapping node; NULL when absent or when node is not a mapping. */
static yaml_node_t *value_of(const meta_reader *m, yaml_node_t *node, const char *key)
{
    if (!node || node->type != YAML_MAPPING_NODE)
        return NULL;
    for (yaml_node_pair_t *pair = node->data.mapping.pairs.start; pair < node->data.mapping.pairs.top; ++pair) {
        yaml_node_t *name = node_at(m, pair->key);
        if (name && name->type == YAML_SCALAR_NODE && name->data.scalar.length == strlen(key) &&
            memcmp(name->data.scalar.value, key, name->data.scalar.length) == 0)
            return node_at(m, pair->value);
    }
    return NULL;
}

/* A scalar's text into out (size bytes); IM_EFORMAT naming key when it is not a short scalar. */
static int text_of(const meta_reader *m, yaml_node_t *node, const char *key, char *out, size_t size)
{
    if (!node || node->type != YAML_SCALAR_NODE || node->data.scalar.length >= size)
        return im_fail(IM_EFORMAT, "%s: meta.yml: %s: expected a text of at most %zu bytes", m->path, key, size - 1);
    memcpy(out, node->data.scalar.value, node->data.scalar.length);
    out[node->data.scalar.length] = '\0';
    return IM_OK;
}

static int number_of(const meta_reader *m, yaml_node_t *node, const char *key, double *value)
{
    char text[64], *end;
    int status = text_of(m, node, key, text, sizeof text);
    if (status != IM_OK)
        return status;
    *value = number_parse(text, &end);
    if (end == text || *end || !isfinite(*value))
        return im_fail(IM_EFORMAT, "%s: meta.yml: %s = '%s': expected a finite number", m->path, key, text);
    return IM_OK;
}

/* size: one length (a line scan) or two (a map), each positive. */
static int read_size(const meta_reader *m, yaml_node_t *node, container_topography *t)
{
    if (node->type != YAML_SEQUENCE_NODE)
        return im_fail(IM_EFORMAT, "%s: meta.yml: topography '%s': size: expected a list of one or two lengths",
                       m->path, t->name);
    yaml_node_item_t *items = node->data.sequence.items.start;
    long count = node->data.sequence.items.top - items;
    if (count < 1 || count > 2)
        return im_fail(IM_EFORMAT,
                       "%s: meta.yml: topography '%s': size has %ld entries: expected one (a line "
                       "scan) or two (a map)",
                       m->path, t->name, count);
    for (long k = 0; k < count; ++k) {
        int status = number_of(m, node_at(m, items[k]), "size", &t->size[k]);
        if (status == IM_OK && t->size[k] <= 0.0)
            status = im_fail(IM_EFORMAT, "%s: meta.yml: topography '%s': size %g: expected a positive length",
                             m->path, t->name, t->size[k]);
        if (status != IM_OK)
            return status;
    }
    t->size_count = (int)count;
    return IM_OK;
}

/* datafile: original, else squeezed-netcdf (contact.engineering's own NetCDF, whose heights are
 * already scaled). */
static int read_datafile(const meta_reader *m, yaml_node_t *node, container_topography *t)
{
    yaml_node_t *original = value_of(m, node, "original"), *squeezed = value_of(m, node, "squeezed-netcdf");
    if (!original && !squeezed)
        return im_fail(IM_EFORMAT,
                       "%s: meta.yml: topography '%s': datafile names no file: expected 'original' or "
                       "'squeezed-netcdf'",
                       m->path, t->name);
    t->squeezed = !original;
    return text_of(m, original ? original : squeezed, "datafile", t->datafile, sizeof t->datafile);
}

static int read_optional(const meta_reader *m, yaml_node_t *node, container_topography *t)
{
    yaml_node_t *source = value_of(m, node, "data_source"), *size = value_of(m, node, "size");
    yaml_node_t *unit = value_of(m, node, "unit"), *scale = value_of(m, node, "height_scale");
    double channel = 0.0;
    int status = source ? number_of(m, source, "data_source", &channel) : IM_OK;
    if (status == IM_OK && (channel < 0 || channel > 999 || channel != floor(channel)))
        status = im_fail(IM_EFORMAT, "%s: meta.yml: topography '%s': data_source %g: expected a channel index",
                         m->path, t->name, channel);
    t->data_source = (int)channel;
    if (status == IM_OK && size)
        status = read_size(m, size, t);
    if (status == IM_OK && unit)
        status = text_of(m, unit, "unit", t->unit, sizeof t->unit);
    t->height_scale = 1.0;
    if (status == IM_OK && scale)
        status = number_of(m, scale, "height_scale", &t->height_scale);
    return status;
}

static int read_topography(const meta_reader *m, yaml_node_t *node, container_topography *t)
{
    *t = (container_topography){0};
    yaml_node_t *name = value_of(m, node, "name"), *datafile = value_of(m, node, "datafile");
    int status = name ? text_of(m, name, "name", t->name, sizeof t->name) : IM_OK;
    if (status == IM_OK && !datafile)
        status = im_fail(IM_EFORMAT, "%s: meta.yml: topography '%s' has no datafile", m->path, t->name);
    if (status == IM_OK)
        status = read_datafile(m, datafile, t);
    if (status == IM_OK && !t->name[0])
        memcpy(t->name, t->datafile, strnlen(t->datafile, sizeof t->name - 1));
    return status == IM_OK ? read_optional(m, node, t) : status;
}

static int read_surfaces(const meta_reader *m, yaml_node_t *surfaces, container_meta *meta)
{
    if (!surfaces || surfaces->type != YAML_SEQUENCE_NODE)
        return im_fail(IM_EFORMAT, "%s: meta.yml: expected a list 'surfaces' (a contact.engineering container)",
                       m->path);
    for (yaml_node_item_t *s = surfaces->data.sequence.items.start; s < surfaces->data.sequence.items.top; ++s) {
        yaml_node_t *list = value_of(m, node_at(m, *s), "topographies");
        if (!list || list->type != YAML_SEQUENCE_NODE)
            return im_fail(IM_EFORMAT, "%s: meta.yml: a surface without a list 'topographies'", m->path);
        for (yaml_node_item_t *t = list->data.sequence.items.start; t < list->data.sequence.items.top; ++t) {
            if (meta->count == CONTAINER_MAX_TOPOGRAPHIES)
                return im_fail(IM_EFORMAT, "%s: meta.yml: more than %d topographies", m->path,
                               CONTAINER_MAX_TOPOGRAPHIES);
            int status = read_topography(m, node_at(m, *t), &meta->topographies[meta->count]);
            if (status != IM_OK)
                return status;
            ++meta->count;
        }
    }
    return IM_OK;
}

int container_meta_parse(const char *path, const char *text, size_t length, container_meta *meta)
{
    meta->count = 0;
    yaml_parser_t parser;
    yaml_document_t document;
    if (!yaml_parser_initialize(&parser))
        return im_fail(IM_ENOMEM, "%s: libyaml cannot start a parser", path);
    yaml_parser_set_input_string(&parser, (const unsigned char *)text, length);
    int status = IM_OK;
    if (!yaml_parser_load(&parser, &document))
        status = im_fail(IM_EFORMAT, "%s: meta.yml line %lu: %s: expected YAML", path,
                         (unsigned long)parser.problem_mark.line + 1, parser.problem ? parser.problem : "error");
    else {
        meta_reader m = {.document = &document, .path = path};
        status = read_surfaces(&m, value_of(&m, yaml_document_get_root_node(&document), "surfaces"), meta);
        yaml_document_delete(&document);
    }
    yaml_parser_delete(&parser);
    return status;
}
