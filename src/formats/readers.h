/* formats/readers.h: the surface readers' parsing step, shared by the public readers of formats.h.
 *
 * A raw reader parses one format into a field of spacing 1 with no unit, heights exactly as stored
 * (NaN and Inf included), and reports what the file states about its units, with the header keys
 * that stated them so that messages can name them. surface_finish then applies the units. */
#ifndef INDENTMAP_FORMATS_READERS_H
#define INDENTMAP_FORMATS_READERS_H

#include "indentmap/formats.h"
#include "indentmap/io.h"

typedef struct surface_stated {
    im_surface_units units;      /* what the file states (zeros and "" where nothing) */
    const char *spacing_keys;    /* e.g. "XReal / XRes and YReal / YRes", for messages */
    double spacing_rounding;     /* how far the printed digits of the stated extents leave the ratio of the
                                x and y spacings open, relative (a text header's "87.6 µm" and
                                "129.7 µm": 9.6e-4); 0 for spacings stored as binary numbers */
    const char *lateral_key;     /* e.g. "XYUnits" */
    const char *height_key;      /* e.g. "ZUnits" */
    int height_unit_unknown;     /* 1: heights with no stated unit have an unknown one (a .gsf without
                                ZUnits), refused once the spacing has a unit; 0: they are in the
                                lateral unit */
    const char *unstated_height; /* heights with no stated unit, taken in the lateral unit with a warning
                                (info->assumed): what the file lacks, e.g. "no '# Value units:' line";
                                NULL: taken without a word */
    char conversion[96];         /* how stored values became float64 row-major ("" for none) */
    enum im_npy_order npy_order; /* a .npy's, as its sidecar states it (IM_NPY_ORDER_YX without one);
                                IM_NPY_ORDER_SIDECAR (0) for the other formats: their layout is fixed */
} surface_stated;

/* The words every refusal of a 1-D profile (a line scan) holds, whatever read it, and its advice. */
#define LINE_SCAN_REFUSAL "a line scan (a 1-D profile), not a map"
#define LINE_SCAN_ADVICE "a 2-D contact needs heights on a grid of at least 3 x 3"

typedef int (*surface_raw_reader)(const char *path, im_field **out, surface_stated *stated);

int gsf_read_raw(const char *path, im_field **out, surface_stated *stated);
int text_read_raw(const char *path, im_field **out, surface_stated *stated);
int npy_read_raw(const char *path, im_field **out, surface_stated *stated);
int sdf_read_raw(const char *path, im_field **out, surface_stated *stated);
/* NetCDF (netcdf.c): a classic file read in this process; NetCDF-4, which netCDF reads with libhdf5, in a child
 * process (netcdf4_read_raw, hdf5.h), as HDF5 files are. */
int netcdf_read_raw(const char *path, im_field **out, surface_stated *stated);
/* Either kind read in this process: what the program runs for NetCDF-4. */
int netcdf_read_in_process(const char *path, im_field **out, surface_stated *stated);
int x3p_read_raw(const char *path, im_field **out, surface_stated *stated);
int tmd_read_raw(const char *path, im_field **out, surface_stated *stated);

/* A raw reader of files that hold several channels, options->channel choosing one (options may be NULL). */
typedef int (*surface_channel_reader)(const char *path, const im_surface_read_options *options, im_field **out,
                                      surface_stated *stated);

/* A channel reader, then surface_finish (as surface_read_format); *out is NULL on failure. */
int surface_read_channel_format(const char *path, surface_channel_reader read, const im_surface_read_options *options,
                                im_field **out, im_surface_read_info *info);

/* Plain HDF5: each 2-D numeric data set is a channel, by default the first; a bare matrix. Read in a child
 * process, indentmap-hdf5-read (hdf5_child.c), since libhdf5 crashes inside itself on some hostile files:
 * IM_EFORMAT naming path, saying so, when it does, and when this build's program is not found. */
int hdf5_read_raw(const char *path, const im_surface_read_options *options, im_field **out, surface_stated *stated);
/* A contact.engineering container (container.c): each topography of its meta.yml is a channel, by
 * default the first that is not a line scan. */
int container_read_raw(const char *path, const im_surface_read_options *options, im_field **out,
                       surface_stated *stated);

/* Applies the stated units and the overrides of options (may be NULL) to a raw field, as
 * im_surface_read_with describes; fills info (may be NULL). On failure the field is left to the
 * caller to free. */
int surface_finish(const char *path, im_field *field, const surface_stated *stated,
                   const im_surface_read_options *options, im_surface_read_info *info);

/* Reads PATH.json beside a .npy, when present, into stated (spacing, lateral unit, array order) and
 * value_unit (size bytes); IM_OK without one, IM_EFORMAT naming it when it is malformed. */
int npy_sidecar_read(const char *path, surface_stated *stated, char *value_unit, size_t size);

/* A .npy indexed [x, y] (options->npy_order, else stated->npy_order, the sidecar's) transposed so that
 * its rows are y, "indexed [x, y]" added to stated->conversion; other formats' fields are left as they
 * are. IM_ENOMEM naming path when the transposed copy does not fit. */
int npy_apply_order(const char *path, im_field *field, surface_stated *stated,
                    const im_surface_read_options *options);

/* A raw reader, npy_apply_order, then surface_finish; *out is NULL on failure. */
int surface_read_format(const char *path, surface_raw_reader read, const im_surface_read_options *options,
                        im_field **out, im_surface_read_info *info);

#endif
