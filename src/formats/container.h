/* formats/container.h: contact.engineering containers, a zip of topography files with meta.yml. */
#ifndef INDENTMAP_FORMATS_CONTAINER_H
#define INDENTMAP_FORMATS_CONTAINER_H

#include <stddef.h>

enum { CONTAINER_MAX_TOPOGRAPHIES = 256 };

/* One topography of meta.yml. */
typedef struct container_topography {
    char name[128];
    char datafile[256];  /* the entry of the zip holding its data */
    int squeezed;        /* 1: datafile is contact.engineering's squeezed NetCDF (heights already scaled) */
    int data_source;     /* the channel of datafile (0 when not stated) */
    double size[2];      /* physical lengths along x and y, in unit */
    int size_count;      /* 0: not stated; 1: a line scan; 2: a map */
    char unit[16];       /* "" when not stated */
    double height_scale; /* 1 when not stated */
} container_topography;

typedef struct container_meta {
    container_topography topographies[CONTAINER_MAX_TOPOGRAPHIES];
    int count;
} container_meta;

/* Parses meta.yml's text (length bytes) into meta; IM_EFORMAT naming path, the key and what was expected. */
int container_meta_parse(const char *path, const char *text, size_t length, container_meta *meta);

#endif
