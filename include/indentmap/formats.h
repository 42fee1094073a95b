/* indentmap/formats.h: surface files in and out (.npy, text, Gwyddion .gsf, .sdf, NetCDF, .x3p, HDF5,
 * instrument formats through Gwyddion), their units, and punch profile files. Above surface.h and
 * indenter.h; every file is written atomically and read boundedly (io.h).
 *
 * Readers refuse, with IM_EFORMAT and a message naming the file (and the line for text), anything
 * they cannot read exactly: truncated data, extra data, unsupported types, NaN or Inf heights.
 * Sizes are checked against the memory available before allocating.
 *
 * Misuse (status.h): IM_EINVAL for a NULL path, buffer, stream or output and for an invalid field
 * view; im_length_unit_metres(NULL) is 0.
 */
#ifndef INDENTMAP_FORMATS_H
#define INDENTMAP_FORMATS_H

#include "indentmap/field.h"
#include "indentmap/indenter.h"
#include "indentmap/surface.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- surfaces ---- */
enum im_npy_dtype { IM_NPY_FLOAT64 = 0, IM_NPY_FLOAT32 = 1 };

/* NumPy .npy, version 1.0, little-endian, C order, 2-D shape (ny, nx) (rows are y). A .npy states
 * no units: its sidecar PATH.json does, when present ("delta", "unit" and, for fields other than
 * heights, "value_unit": written by `surface --out` and im_field_sidecar_write), and im_npy_read takes
 * them from it (IM_EFORMAT naming the sidecar when it is not a JSON object of those types, or larger
 * than 1 MiB). A sidecar's "order": "xy" says that the array is indexed [x, y] (enum im_npy_order):
 * it is read transposed, rows along y; "yx" (and none) is the layout above. */
int im_npy_write(const char *path, const im_field *field, enum im_npy_dtype dtype);

/* Writes PATH.json beside the .npy at path: program, version, quantity (e.g. "force per patch"),
 * the grid, delta, unit and value_unit of field, atomically. */
int im_field_sidecar_write(const char *path, const im_field *field, const char *quantity);
/* Reads versions 1.0 to 3.0, 2-D, C or Fortran order, floats of 4 or 8 bytes and integers of 1, 2, 4
 * or 8 bytes (signed or not) in either byte order, each converted to double (int64 and uint64 beyond
 * 2^53 rounded); im_surface_read_with records the conversion in its info. */
int im_npy_read(const char *path, im_field **out);

/* Plain text: one grid row per line (row 0 first), values separated by blanks, tabs, commas or
 * semicolons ("1,5 2,25" with blanks or semicolons between values and no '.' is read with decimal
 * commas: 1.5 and 2.25); lines starting with '#' are header lines. What the numbers are:
 * - three columns (and no header stating a matrix): x y z points, in any order; when each (x, y) of a
 *   regular grid appears once, the heights on that grid, spaced by the steps of x and y; otherwise
 *   refused (scattered points, repeats, uneven steps);
 * - fewer than three columns or rows: a line scan (a 1-D profile), refused with that reason;
 * - otherwise a matrix.
 * Gwyddion's "# Width: 5.12 um" and "# Height:" headers ("# Breite:" and "# Höhe:" from a German
 * Gwyddion; Height in another length unit is converted into Width's) set the spacing (Width /
 * columns, Height / rows; one alone states square pixels) and lateral unit, and "# Value units: m"
 * the unit of the heights (converted as im_surface_read_with says). Wyko/Vision ASCII headers before
 * the numbers, "h=ROWS w=COLUMNS", "pixel size=3.7e-007 m", "data unit=rad" and "height conversion
 * factor (-> m)=2.9e-008", set the grid, the spacing and heights in metres (value times the factor);
 * a data unit that is not a length with no factor, or another key=value line, is refused. A header
 * stating the grid (Vision's, or "# ... C columns x R rows ..." as written here) must match the data:
 * a file with rows missing or added is refused (IM_EFORMAT, naming that line, the header's grid and
 * the data's). Gwyddion's Width and Height are extents, not counts, and are not checked against the
 * data. Writing uses %.17g, so a round trip is exact. */
int im_text_write(const char *path, const im_field *field);
int im_text_read(const char *path, im_field **out);

/* Gwyddion Simple Field (.gsf): a text header ("Gwyddion Simple Field 1.0", then KEY = VALUE
 * lines with XRes, YRes and optionally XReal, YReal, XYUnits, ZUnits), NUL padding to a multiple
 * of 4 bytes, then XRes * YRes little-endian float32 values, row by row. XRes and YRes must be
 * decimal integers (no "16abc", no "1.6e1"), XReal and YReal finite numbers > 0; a value that is
 * not is refused naming its key. As the GSF specification says, an absent XReal or YReal is 1.0 (each
 * on its own: a spacing of 1.0 / XRes, 1.0 / YRes in XYUnits), and XYUnits and ZUnits have no default:
 * without ZUnits the heights' unit is unknown, not XYUnits', and such a file is refused (IM_EFORMAT
 * naming ZUnits) when the spacing has a unit, unless the heights' unit is set (options->set.height);
 * without either unit it is read bare. Units as for im_surface_read_with.
 * Writing is in base SI units, as Gwyddion writes and reads them (it keeps no prefix: "XYUnits = um"
 * would read as metres): a field in a known length unit is written with XReal, YReal and the heights
 * in metres and XYUnits = ZUnits = m; a field without a unit with no units; another unit is refused
 * (IM_EINVAL, nothing written). */
int im_gsf_write(const char *path, const im_field *field);
int im_gsf_read(const char *path, im_field **out);

/* ISO 25178-71 surface data file (.sdf): ASCII ("aISO-1.0" or "aBCR-1.0") or binary ("bISO-1.0",
 * "bBCR-1.0"; an 81-byte little-endian header, then the values), and Gwyddion's "aBCR-0.0" and
 * "bBCR-0.0". NumPoints columns by NumProfiles rows; Xscale, Yscale (spacings) and Zscale (the height
 * of one unit of a value) in metres, each checked to be a finite number > 0; DataType 0-7
 * (uint8/16/32, float, int8/16/32, double); Compression must be 0; Gwyddion's NumDataSet, when
 * present, must be 1 and NanPresent 0 or 1; "BAD" (ASCII) or NaN marks a missing point. Values after the data other
 * than a '*' trailer are refused. Writing is binary, DataType double, in metres (the field needs a
 * length unit; IM_EINVAL otherwise). */
int im_sdf_write(const char *path, const im_field *field);
int im_sdf_read(const char *path, im_field **out);

/* NetCDF (.nc) in the layout of ContactMechanics/SurfaceTopography and contact.engineering:
 * dimensions x and y, heights(x, y) (first index x; (y, x) is read too), and optional coordinate
 * variables x and y whose attributes `length` (physical size) and `unit` (today's name; `length_unit`
 * in older files) state the spacing (length / points) and the lateral unit; heights:unit the unit of
 * the heights (else the lateral one). Any numeric type is read as double;
 * values equal to the fill value (heights:_FillValue, else netCDF's default for the type, which is
 * also what netCDF returns for values past the end of a truncated file) are missing points. Refused with IM_EFORMAT naming the file and
 * the dimension, variable or attribute at fault. Writing uses the classic 64-bit offset format (as
 * SurfaceTopography does), with the unit in ASCII ("um" for µm) and periodic = 0, built in
 * memory and written atomically; the unit is written as x:unit, y:unit and heights:unit and, for older
 * readers, x:length_unit and y:length_unit. */
int im_netcdf_write(const char *path, const im_field *field);
int im_netcdf_read(const char *path, im_field **out);

/* ISO 25178-72 .x3p: a zip archive (libzip) holding main.xml (ISO 5436-2, parsed with libxml2
 * without network access or entity expansion) and the binary data it links. Read: Record1 Axes CX,
 * CY of AxisType I with Increment (the spacings, metres), CZ of AxisType A with DataType I (int16),
 * L (int32), F (float32) or D (float64), heights Offset + Increment x value in metres; Record3
 * MatrixDimension SizeX, SizeY, SizeZ = 1 and DataLink/PointDataLink, whose entry must hold exactly
 * SizeX x SizeY values (x fastest). NaN marks a missing point, and so does a point that
 * DataLink/ValidPointsLink marks invalid: that entry, when linked, must hold a bit per point in the
 * same order, least significant bit first, 1 valid (ISO 5436-2), (SizeX x SizeY + 7) / 8 bytes, and
 * match its MD5ChecksumValidPoints when one is stated. Inline DataList data are not read.
 * Stated checksums must match: the data's MD5ChecksumPointData, and each line of md5checksum.hex
 * ("<md5> *<entry>", as md5sum writes it) that of the entry it names, main.xml when it names none
 * (SurfaceTopography names bindata/data.bin); every entry is read to its end so that libzip checks its
 * CRC-32. Refused with IM_EFORMAT naming the file and the element or entry. Written: DataType D in
 * metres (the field needs a length unit; IM_EINVAL otherwise), with MD5ChecksumPointData and
 * md5checksum.hex naming main.xml. */
int im_x3p_write(const char *path, const im_field *field);
int im_x3p_read(const char *path, im_field **out);

/* ---- units of a surface ----
 * A surface's lateral spacing and its heights are lengths. Files state them (GSF XReal/YReal/
 * XYUnits/ZUnits, Gwyddion text "# Width:", "# Height:", "# Value units:"), the user may set or
 * override them (.npy files state none), and a surface read into an im_field always has its heights
 * in the unit of its spacing (field->unit), converted when the file gives them in another one, so
 * that slopes such as h'rms are dimensionless and right. Known length units: "m", "cm", "mm", "µm"
 * (also "um", "μm", "micron"), "nm", "pm", "Å" (also "A", "angstrom"). */
typedef struct im_surface_units {
    double delta_x, delta_y; /* pixel spacing along x (columns) and y (rows), in `lateral`; 0: not stated */
    char lateral[16];        /* unit of the spacing; "" when not stated */
    char height[16];         /* unit of the heights; "" when not stated (then: the lateral unit; for a
                                .gsf, whose heights are then in no known unit, refused when the spacing
                                has one) */
} im_surface_units;

/* Metres per unit of a length unit's name (1e-6 for "µm"), and its canonical spelling in
 * *canonical (may be NULL); 0 when the name is not a known length unit. */
double im_length_unit_metres(const char *name, const char **canonical);

/* Pixels whose x and y spacings differ by at most this, relative to their mean, are square: read
 * with the mean spacing, the difference recorded (im_surface_read_info.spacing_difference). 2^-16,
 * 1.5e-5, because spacings reach a reader rounded: stored as float32 (a 24-bit significand: 6e-8
 * relative each), and printed in headers with 6 or 7 significant digits (%g: up to 5e-6 relative
 * each, 5e-7 with 7). x and y are rounded apart (on a grid that is not square XReal and YReal are
 * different numbers), so one square pixel can come out as 6-digit spacings 1e-5 apart: a 512 x 256
 * grid of 1.23456789e-8 m pixels, printed "6.32099e-06" and "3.16049e-06", differs by 1.6e-6; 2^-20
 * (1e-6) would refuse it. Taking the mean misplaces a point by at most 2^-17 spacings per spacing
 * from the first: half a pixel across the largest grid (IM_FIELD_MAX_SIDE), 0.03 across 4096.
 * A text header that prints its extents with fewer digits (a Gwyddion export's "# Width: 87.6 µm" and
 * "# Height: 129.7 µm", 200 x 296 points: spacings 0.438 and 0.438176 µm, 4e-4 apart) leaves their ratio
 * open by half a unit of each last digit (0.05 / 87.6 + 0.05 / 129.7 = 9.6e-4): the tolerance is then
 * that, up to IM_SQUARE_PIXEL_PRINTED_LIMIT (im_surface_read_info.square_tolerance says which applied).
 * Beyond it the pixels are refused unless resample_square is set. */
#define IM_SQUARE_PIXEL_TOLERANCE (1.0 / 65536.0) /* 2^-16 */
/* The most a header's printed digits may widen the tolerance: 2e-3, two 4-digit extents ("1.000 µm":
 * 5e-4 each) with room; a hand-written "# Width: 4 um" and "# Height: 4.2 um" (5% apart) stays refused. */
#define IM_SQUARE_PIXEL_PRINTED_LIMIT 2e-3

/* Which index of a .npy array is x. indentmap writes and reads arrays of shape (ny, nx), rows along y
 * (the first index is y, as NumPy images are); SurfaceTopography's heights() are indexed [x, y], shape
 * (nx, ny). The order is of the array's indices, whatever its memory order (C or Fortran). */
enum im_npy_order {
    IM_NPY_ORDER_SIDECAR = 0, /* as the sidecar PATH.json states ("order": "yx" or "xy"), else yx */
    IM_NPY_ORDER_YX = 1,      /* the first index is y: rows are y */
    IM_NPY_ORDER_XY = 2       /* the first index is x: the array is transposed on reading */
};

/* How a surface file is read. Zero-initialised means: as the file states. */
typedef struct im_surface_read_options {
    im_surface_units set;        /* each stated member (non-zero, non-empty) overrides the file's; a
                                delta_x without delta_y sets both */
    int fill;                    /* 1: fill missing points (NaN) with im_surface_fill_missing (surface.h);
                                0: refuse them, naming the first one's (x, y) */
    char express_in[16];         /* a length unit ("m" for SI): spacing and heights are converted into it
                                from the surface's unit, which must then be known; "": kept */
    int field_values;            /* 1: the file holds a field to draw (forces, gaps, displacements), not
                                heights to solve on: NaN and Inf are kept (a flat punch's gap is +Inf
                                where it can never touch); fill is then ignored */
    char channel[64];            /* of a multi-channel instrument file read through Gwyddion: an index or
                                a title (case ignored); "": the first channel holding lengths */
    int resample_square;         /* 1: pixels whose spacings differ beyond IM_SQUARE_PIXEL_TOLERANCE are
                                resampled onto square pixels of the finer spacing after the heights are
                                converted and their missing points refused or filled
                                (im_surface_resample_square, surface.h: bilinear, within the stored
                                extent); 0: they are refused */
    enum im_npy_order npy_order; /* of a .npy: overrides its sidecar's "order" (IM_NPY_ORDER_SIDECAR: keeps
                                it); other formats' layouts are their own, and ignore it */
} im_surface_read_options;

/* What the reader found and did, for reports and run records. */
typedef struct im_surface_read_info {
    im_surface_units file;     /* as the file stated them (zeros and "" where it stated nothing) */
    im_surface_units used;     /* after overrides (delta_y = delta_x when only delta_x is set), in the unit
                                of the field read (used.lateral: after express_in); field->delta is
                                delta_x when they are equal, their mean when they differ within
                                IM_SQUARE_PIXEL_TOLERANCE, the finer when the grid was resampled */
    double height_factor;      /* the heights were multiplied by this to bring them into `used.lateral` */
    long filled;               /* missing points filled (options->fill) */
    char conversion[96];       /* how the stored values were converted, e.g. "'>i2' (int16) converted to
                                float64; Fortran order transposed to C order"; "" when none */
    double spacing_difference; /* |used.delta_x - used.delta_y| / their mean: 0 for square pixels */
    double square_tolerance;   /* the difference up to which pixels were square: IM_SQUARE_PIXEL_TOLERANCE, or
                                more where a header's printed digits leave the spacings open (above) */
    char resampled[16];        /* how the grid was brought to square pixels: "bilinear" (resample_square,
                                spacing_difference beyond IM_SQUARE_PIXEL_TOLERANCE), or "" when it
                                was not resampled */
    double resampled_delta;    /* the square pixels' spacing when resampled (field->delta, in its unit);
                                0 otherwise */
    int stored_nx, stored_ny;  /* the grid as the file stores it (before resampling) */
    char assumed[128];         /* what was assumed where the file is silent and a reader should be told (the
                                indentmap program and Python's im.read warn with it, after the path):
                                e.g. "no '# Value units:' line: its heights are taken in µm, the lateral
                                unit" for a Gwyddion text export without one; "" when nothing */
} im_surface_read_info;

/* Reads a surface by extension (.npy, .gsf, .sdf, .nc, .x3p), else as text (see im_text_read) when the
 * file is text whose first data line starts with a number, else through Gwyddion's file modules when
 * this build has them (im_gwyddion_reader): Bruker Nanoscope, Asylum .ibw, Park TIFF, Zygo MetroPro,
 * Wyko .opd, Sensofar .plu, Alicona .al3d, Digital Surf .sur, FRT, Nanosurf .nid, Molecular Imaging
 * .mi, WSxM .stp, BCR and more (`indentmap formats` lists them). From such a file the channel
 * options->channel names is read, by default the first whose values are lengths (a file of one
 * channel without a unit is read as a bare matrix); masked (invalid) points become missing points;
 * info->conversion names the module and channel. Then its units are applied: field->delta
 * is the spacing (1 when none is stated), field->unit the canonical lateral unit, heights converted
 * into it. Refused with IM_EFORMAT, naming the file and the header field (or option): pixels that
 * are not square (x and y spacings differing by more than IM_SQUARE_PIXEL_TOLERANCE of their mean;
 * the message names both spacings, their difference, the tolerance and the option that resamples)
 * unless options->resample_square, a unit that is not a length, heights in a unit without a lateral
 * unit to convert them to, Inf heights, and NaN heights (missing points) unless options->fill. A .npy
 * indexed [x, y] (options->npy_order, else its sidecar's "order") is transposed first, and
 * info->conversion says "indexed [x, y]". options and info may be NULL; IM_EINVAL for an npy_order
 * outside the enumeration. */
int im_surface_read_with(const char *path, const im_surface_read_options *options, im_field **out,
                         im_surface_read_info *info);

/* im_surface_read_with(path, NULL, out, NULL). */
int im_surface_read(const char *path, im_field **out);

/* The path of indentmap-gwyddion-read, the program that runs Gwyddion's file modules (GPL-2.0+, kept
 * out of this library: see README's License), or NULL when this build has none. The environment
 * variable INDENTMAP_GWYDDION_READER chooses another; otherwise the one beside the running executable,
 * then the one beside the shared object holding this library (a build tree's, or the Python extension,
 * beside which the build copies it), then the installed one. HDF5 and NetCDF-4 files are read the same
 * way by indentmap-hdf5-read (INDENTMAP_HDF5_READER). */
const char *im_gwyddion_reader(void);
/* Writes a surface by extension: .npy (float64), .gsf, .sdf (binary, metres), .nc, .x3p, else a text
 * matrix. A NaN or Inf height is refused before anything is written (IM_EINVAL naming the path and
 * the point), here and by each format's writer: no reader takes such a file back. */
int im_surface_write(const char *path, const im_field *field);

/* Writes the surface file (im_surface_write) and then its sidecar PATH.json as one writer's pair: under
 * im_pair_writers_lock (io.h), so that writers racing for the name, the program's and Python's, leave one
 * writer's file beside that writer's sidecar. With params, source or stats, the sidecar is the surface's
 * record (im_surface_sidecar_write: params and source may be NULL; stats NULL: computed here); with none of
 * them, a .npy gets the sidecar stating its units (im_field_sidecar_write, quantity "height"; written even
 * where one exists, so that none from an earlier file stays) and another format no sidecar (nor the lock).
 * IM_EINVAL for a NULL path or an invalid field view; else the first failing step's status. */
int im_surface_write_with_sidecar(const char *path, const im_field *surface, const im_surface_params *params,
                                  const char *source, const im_surface_stats *stats);

/* ---- punch profiles ---- */

/* Reads a profile file. A .npy file (any case) is a 2-D profile: its heights in the surface's
 * length unit, its delta set to `delta` (the surface's spacing: the field is on the surface's
 * grid). Any other file is an axisymmetric table: one sample "r z" or "r,z" per line (spaces,
 * tabs or one comma between them), r and z in the surface's length unit; blank lines and lines
 * starting with '#' are skipped, and so is a first line that holds no number (a header such as
 * "r,z"). IM_EIO naming the file when it cannot be read; IM_EINVAL naming the file and line of
 * a line that is not two numbers, or the file and the sample's line for a profile that
 * im_profile_axisymmetric refuses. */
int im_profile_read(const char *path, double delta, im_profile **out);

#ifdef __cplusplus
}
#endif

#endif
