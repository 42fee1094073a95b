/* ISO 25178-72 .x3p (ISO 5436-2 XML in a zip container): main.xml describes the grid (Record1 Axes:
 * CX and CY incremental with their Increment in metres, CZ absolute with its DataType, Increment
 * and Offset; Record3 MatrixDimension SizeX, SizeY, SizeZ = 1, and DataLink PointDataLink naming the
 * binary data in the archive), and the data holds SizeX x SizeY little-endian values, x fastest.
 * DataLink ValidPointsLink, when present, names a packed bit array of the points' validity: a bit
 * per point in the data's order, least significant bit first, 1 valid; an invalid point is a missing
 * point (NaN) whatever the data hold there; written (bindata/valid.bin, with its
 * MD5ChecksumValidPoints) when a surface has missing points, which its data then hold as NaN.
 * The zip is read with libzip and the XML with libxml2 (no network, no entity expansion). Written
 * files carry what the ISO5436_2 schema requires beyond that: Record2 (date, creator, instrument,
 * probing system "Software"), the data's MD5ChecksumPointData, and Record4's ChecksumFile
 * md5checksum.hex holding the MD5 of main.xml ("<hex> *main.xml", as md5sum writes it). Read, each
 * line of md5checksum.hex is checked against the entry it names: most writers name main.xml,
 * SurfaceTopography names bindata/data.bin; a line naming none is main.xml's. */
#include "indentmap/formats.h"
#include "indentmap/io.h"
#include "core/args.h"

#include "indentmap/status.h"
#include "formats/payload.h"
#include "formats/readers.h"
#include "formats/zip_entry.h"
#include "core/number.h"

#include <errno.h>
#include <libxml/parser.h>
#include <libxml/tree.h>
#include <math.h>
#include <nettle/md5.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>
#include <zip.h>

enum { X3P_MAX_XML = 16 << 20 }; /* main.xml of a surface is a few kB; more is refused */

enum { X3P_MAX_CHECKSUM_FILE = 4096 }; /* md5checksum.hex holds a line or two */

enum { MD5_HEX = 2 * MD5_DIGEST_SIZE }; /* an MD5 in hex digits */

enum { X3P_BLOCK = 8 * 4096 }; /* entries are read in blocks of this many bytes: whole values of any type */

/* An entry of the archive that Record3/DataLink links. */
typedef struct x3p_link {
    const char *key;       /* the element naming it, e.g. "PointDataLink" */
    const char *md5_key;   /* the element stating its MD5, e.g. "MD5ChecksumPointData" */
    char path[256];        /* the entry; "" when an optional link is absent */
    char md5[MD5_HEX + 1]; /* its stated MD5 (32 hex digits), or "" when none is stated */
} x3p_link;

typedef struct x3p_grid {
    long nx, ny, nz;
    double dx, dy, z_increment, z_offset;
    char z_type;    /* I int16, L int32, F float32, D float64 */
    x3p_link data;  /* the values: PointDataLink */
    x3p_link valid; /* the valid points' bits: ValidPointsLink, when there is one */
} x3p_grid;

/* The MD5 that `context` has taken in, as 32 hex digits (upper or lower case) and a terminating NUL. */
static void md5_finish_hex(struct md5_ctx *context, int upper, char hex[MD5_HEX + 1])
{
    uint8_t digest[MD5_DIGEST_SIZE];
    md5_digest(context, sizeof digest, digest);
    for (int i = 0; i < MD5_DIGEST_SIZE; ++i)
        snprintf(hex + 2 * i, 3, upper ? "%02X" : "%02x", digest[i]);
}

/* The MD5 of size bytes as hex (see md5_finish_hex). */
static void md5_hex(const void *bytes, size_t size, int upper, char hex[MD5_HEX + 1])
{
    struct md5_ctx context;
    md5_init(&context);
    md5_update(&context, size, bytes);
    md5_finish_hex(&context, upper, hex);
}

/* A stated checksum: IM_OK when it is not 32 hex digits (it says nothing) or equals `hex` in any case;
 * otherwise IM_EFORMAT naming both, since the bytes were damaged after they were written. */
static int check_md5(const char *path, const char *what, const char *stated, const char *hex, const char *key)
{
    if (strlen(stated) != MD5_HEX || strspn(stated, "0123456789abcdefABCDEF") != MD5_HEX ||
        strcasecmp(stated, hex) == 0)
        return IM_OK;
    return im_fail(IM_EFORMAT, "%s: %s: MD5 %s, but %s states %s: the file is damaged", path, what, hex, key, stated);
}

/* The first child element of node named name (local name: namespaces ignored), or NULL. */
static xmlNode *child(xmlNode *node, const char *name)
{
    for (xmlNode *c = node ? node->children : NULL; c; c = c->next)
        if (c->type == XML_ELEMENT_NODE && strcmp((const char *)c->name, name) == 0)
            return c;
    return NULL;
}

/* The text of the element at the path of child names below root (NULL-terminated), or NULL. */
static xmlNode *find(xmlNode *root, const char *const *names)
{
    xmlNode *node = root;
    for (; node && *names; ++names)
        node = child(node, *names);
    return node;
}

/* The element's text as a finite number; IM_EFORMAT naming the element otherwise (or when missing,
 * unless optional, in which case *out keeps its default). */
static int number_at(const char *path, xmlNode *root, const char *const *names, const char *what, int optional,
                     double *out)
{
    xmlNode *node = find(root, names);
    if (!node)
        return optional ? IM_OK : im_fail(IM_EFORMAT, "%s: main.xml lacks %s", path, what);
    xmlChar *text = xmlNodeGetContent(node);
    char *end;
    double value = text ? number_parse((const char *)text, &end) : NAN;
    int ok = text && end != (char *)text && end[strspn(end, " \t\r\n")] == '\0' && isfinite(value);
    if (!ok) {
        im_fail(IM_EFORMAT, "%s: main.xml %s '%.32s': expected a finite number", path, what,
                text ? (const char *)text : "");
        xmlFree(text);
        return IM_EFORMAT;
    }
    xmlFree(text);
    *out = value;
    return IM_OK;
}

static int text_at(const char *path, xmlNode *root, const char *const *names, const char *what, char *out,
                   size_t size)
{
    xmlNode *node = find(root, names);
    xmlChar *text = node ? xmlNodeGetContent(node) : NULL;
    const char *value = text ? (const char *)text + strspn((const char *)text, " \t\r\n") : NULL;
    size_t length = value ? strcspn(value, " \t\r\n") : 0;
    int ok = value && length > 0 && length < size;
    if (ok)
        snprintf(out, size, "%.*s", (int)length, value);
    else
        im_fail(IM_EFORMAT, "%s: main.xml %s: %s", path, what, node ? "expected a short word" : "missing");
    xmlFree(text);
    return ok ? IM_OK : IM_EFORMAT;
}

static int parse_axes(const char *path, xmlNode *root, x3p_grid *g)
{
    static const char *const CX_TYPE[] = {"Record1", "Axes", "CX", "AxisType", NULL};
    static const char *const CY_TYPE[] = {"Record1", "Axes", "CY", "AxisType", NULL};
    static const char *const CZ_TYPE[] = {"Record1", "Axes", "CZ", "AxisType", NULL};
    static const char *const CZ_DATA[] = {"Record1", "Axes", "CZ", "DataType", NULL};
    static const char *const CX_INC[] = {"Record1", "Axes", "CX", "Increment", NULL};
    static const char *const CY_INC[] = {"Record1", "Axes", "CY", "Increment", NULL};
    static const char *const CZ_INC[] = {"Record1", "Axes", "CZ", "Increment", NULL};
    static const char *const CZ_OFF[] = {"Record1", "Axes", "CZ", "Offset", NULL};
    char cx[4], cy[4], cz[4], z_type[4];
    int status = text_at(path, root, CX_TYPE, "Record1/Axes/CX/AxisType", cx, sizeof cx);
    if (status == IM_OK)
        status = text_at(path, root, CY_TYPE, "Record1/Axes/CY/AxisType", cy, sizeof cy);
    if (status == IM_OK)
        status = text_at(path, root, CZ_TYPE, "Record1/Axes/CZ/AxisType", cz, sizeof cz);
    if (status == IM_OK && (strcmp(cx, "I") != 0 || strcmp(cy, "I") != 0 || strcmp(cz, "A") != 0))
        return im_fail(IM_EFORMAT,
                       "%s: main.xml Record1/Axes: AxisType CX %s, CY %s, CZ %s: expected I, I, A (a "
                       "regular grid of heights)",
                       path, cx, cy, cz);
    if (status == IM_OK)
        status = text_at(path, root, CZ_DATA, "Record1/Axes/CZ/DataType", z_type, sizeof z_type);
    if (status == IM_OK && (strlen(z_type) != 1 || !strchr("ILFD", z_type[0])))
        return im_fail(IM_EFORMAT, "%s: main.xml Record1/Axes/CZ/DataType '%s': expected I, L, F or D", path, z_type);
    g->z_type = z_type[0];
    g->z_increment = 1.0;
    if (status == IM_OK)
        status = number_at(path, root, CX_INC, "Record1/Axes/CX/Increment", 0, &g->dx);
    if (status == IM_OK)
        status = number_at(path, root, CY_INC, "Record1/Axes/CY/Increment", 0, &g->dy);
    if (status == IM_OK)
        status = number_at(path, root, CZ_INC, "Record1/Axes/CZ/Increment", 1, &g->z_increment);
    if (status == IM_OK)
        status = number_at(path, root, CZ_OFF, "Record1/Axes/CZ/Offset", 1, &g->z_offset);
    if (status == IM_OK && !(g->dx > 0.0 && g->dy > 0.0 && g->z_increment != 0.0))
        return im_fail(IM_EFORMAT,
                       "%s: main.xml Record1/Axes: Increment CX %g, CY %g, CZ %g: expected CX, CY > 0 "
                       "and CZ non-zero",
                       path, g->dx, g->dy, g->z_increment);
    return status;
}

/* Record3/DataLink/<key> into link, with the MD5 its <md5_key> states (required by the schema,
 * optional here: some writers leave it out). */
static int parse_link(const char *path, xmlNode *root, const char *key, const char *md5_key, x3p_link *link)
{
    const char *const names[] = {"Record3", "DataLink", key, NULL};
    const char *const md5_names[] = {"Record3", "DataLink", md5_key, NULL};
    char what[64];
    link->key = key;
    link->md5_key = md5_key;
    xmlNode *md5 = find(root, md5_names);
    xmlChar *stated = md5 ? xmlNodeGetContent(md5) : NULL;
    if (stated)
        sscanf((const char *)stated, "%32s", link->md5);
    xmlFree(stated);
    snprintf(what, sizeof what, "Record3/DataLink/%s", key);
    return text_at(path, root, names, what, link->path, sizeof link->path);
}

static int parse_matrix(const char *path, xmlNode *root, x3p_grid *g)
{
    static const char *const SX[] = {"Record3", "MatrixDimension", "SizeX", NULL};
    static const char *const SY[] = {"Record3", "MatrixDimension", "SizeY", NULL};
    static const char *const SZ[] = {"Record3", "MatrixDimension", "SizeZ", NULL};
    static const char *const LINK[] = {"Record3", "DataLink", "PointDataLink", NULL};
    static const char *const VALID[] = {"Record3", "DataLink", "ValidPointsLink", NULL};
    static const char *const LIST[] = {"Record3", "DataList", NULL};
    double sx = 0, sy = 0, sz = 0;
    int status = number_at(path, root, SX, "Record3/MatrixDimension/SizeX", 0, &sx);
    if (status == IM_OK)
        status = number_at(path, root, SY, "Record3/MatrixDimension/SizeY", 0, &sy);
    if (status == IM_OK)
        status = number_at(path, root, SZ, "Record3/MatrixDimension/SizeZ", 0, &sz);
    if (status != IM_OK)
        return status;
    if (sx != floor(sx) || sy != floor(sy) || sx < 1 || sy < 1 || sx > IM_FIELD_MAX_SIDE || sy > IM_FIELD_MAX_SIDE ||
        sz != 1)
        return im_fail(IM_EFORMAT,
                       "%s: main.xml Record3/MatrixDimension %g x %g x %g: expected SizeX, SizeY "
                       "integers in [1, %d] and SizeZ 1",
                       path, sx, sy, sz, IM_FIELD_MAX_SIDE);
    g->nx = (long)sx;
    g->ny = (long)sy;
    if (!find(root, LINK) && find(root, LIST))
        return im_fail(IM_EFORMAT,
                       "%s: main.xml Record3/DataList: inline data is not read; expected a binary "
                       "PointDataLink",
                       path);
    status = parse_link(path, root, "PointDataLink", "MD5ChecksumPointData", &g->data);
    if (status == IM_OK && find(root, VALID))
        status = parse_link(path, root, "ValidPointsLink", "MD5ChecksumValidPoints", &g->valid);
    return status;
}

/* The size of the entry `name`, which `key` links; IM_EFORMAT naming both when the archive lacks it. */
static int entry_size(zip_t *archive, const char *path, const char *name, const char *key, size_t *size)
{
    zip_stat_t info;
    zip_stat_init(&info);
    if (zip_stat(archive, name, 0, &info) != 0 || !(info.valid & ZIP_STAT_SIZE))
        return im_fail(IM_EFORMAT, "%s: %s '%s' is not in the archive", path, key, name);
    *size = (size_t)info.size;
    return IM_OK;
}

/* What a reader does with an entry's bytes as they arrive: `size` bytes from byte `offset` of the
 * entry, a multiple of X3P_BLOCK. */
typedef void (*entry_sink)(void *context, const uint8_t *bytes, size_t size, size_t offset);

/* Reads the `size` bytes of entry `name` and one past them (zip_entry_check_end), handing each block to
 * sink (when not NULL) and taking their MD5 into hex (when not NULL). */
static int read_entry(zip_t *archive, const char *path, const char *name, size_t size, entry_sink sink, void *context,
                      char hex[MD5_HEX + 1])
{
    zip_file_t *file = zip_fopen(archive, name, 0);
    if (!file)
        return im_fail(IM_EFORMAT, "%s: %s cannot be opened: %s", path, name, zip_strerror(archive));
    uint8_t block[X3P_BLOCK];
    struct md5_ctx md5;
    md5_init(&md5);
    int status = IM_OK;
    for (size_t done = 0; done < size && status == IM_OK; done += X3P_BLOCK) {
        size_t want = size - done < X3P_BLOCK ? size - done : X3P_BLOCK;
        if (zip_fread(file, block, want) != (zip_int64_t)want)
            status = im_fail(IM_EFORMAT, "%s: %s: truncated or corrupt after %zu bytes: %s", path, name, done,
                             zip_file_strerror(file));
        if (status == IM_OK && hex)
            md5_update(&md5, want, block);
        if (status == IM_OK && sink)
            sink(context, block, want, done);
    }
    if (status == IM_OK)
        status = zip_entry_check_end(file, path, name);
    zip_fclose(file);
    if (status == IM_OK && hex)
        md5_finish_hex(&md5, 0, hex);
    return status;
}

/* A sink copying the bytes into the buffer `context`. */
static void copy_bytes(void *context, const uint8_t *bytes, size_t size, size_t offset)
{
    memcpy((uint8_t *)context + offset, bytes, size);
}

/* md5checksum.hex's text (at most X3P_MAX_CHECKSUM_FILE bytes, NUL-terminated); "" when the archive
 * has none. */
static int read_checksum_file(zip_t *archive, const char *path, char text[X3P_MAX_CHECKSUM_FILE + 1])
{
    zip_stat_t info;
    zip_stat_init(&info);
    text[0] = '\0';
    if (zip_stat(archive, "md5checksum.hex", 0, &info) != 0 || !(info.valid & ZIP_STAT_SIZE))
        return IM_OK;
    if (info.size > X3P_MAX_CHECKSUM_FILE)
        return im_fail(IM_EFORMAT, "%s: md5checksum.hex is %llu bytes: expected at most %d", path,
                       (unsigned long long)info.size, X3P_MAX_CHECKSUM_FILE);
    int status = read_entry(archive, path, "md5checksum.hex", (size_t)info.size, copy_bytes, text, NULL);
    text[status == IM_OK ? (size_t)info.size : 0] = '\0';
    return status;
}

/* The MD5 of the entry a line of md5checksum.hex names: main.xml's bytes (xml) when it names main.xml or
 * nothing, else the named entry's. */
static int named_entry_md5(zip_t *archive, const char *path, const char *name, const char *xml, size_t xml_size,
                           char hex[MD5_HEX + 1])
{
    if (strcmp(name, "main.xml") == 0) {
        md5_hex(xml, xml_size, 0, hex);
        return IM_OK;
    }
    size_t size = 0;
    int status = entry_size(archive, path, name, "md5checksum.hex's entry", &size);
    return status == IM_OK ? read_entry(archive, path, name, size, NULL, NULL, hex) : status;
}

/* One line of md5checksum.hex as md5sum writes it: 32 hex digits, blanks, '*' (binary mode) or not,
 * and the name of the entry whose MD5 they are (main.xml when the line names none). A line that does
 * not start with 32 hex digits states nothing. */
static int check_checksum_line(zip_t *archive, const char *path, const char *line, const char *xml, size_t xml_size)
{
    static const char BLANKS[] = " \t";
    char stated[MD5_HEX + 1], name[256], hex[MD5_HEX + 1];
    line += strspn(line, BLANKS);
    size_t digits = strspn(line, "0123456789abcdefABCDEF");
    if (digits != MD5_HEX || (line[digits] != '\0' && !strchr(BLANKS, line[digits])))
        return IM_OK;
    snprintf(stated, sizeof stated, "%.*s", MD5_HEX, line);
    const char *rest = line + MD5_HEX + strspn(line + MD5_HEX, BLANKS);
    rest += *rest == '*';
    size_t length = strlen(rest);
    while (length > 0 && strchr(BLANKS, rest[length - 1]))
        --length;
    if (length == 0)
        rest = "main.xml", length = strlen(rest);
    snprintf(name, sizeof name, "%.*s", (int)length, rest);
    int status = named_entry_md5(archive, path, name, xml, xml_size, hex);
    return status == IM_OK ? check_md5(path, name, stated, hex, "md5checksum.hex") : status;
}

/* md5checksum.hex, when the archive has it: every line's MD5 must be that of the entry it names. */
static int check_checksum_file(zip_t *archive, const char *path, const char *xml, size_t xml_size)
{
    char text[X3P_MAX_CHECKSUM_FILE + 1], *save = NULL;
    int status = read_checksum_file(archive, path, text);
    for (char *line = strtok_r(text, "\r\n", &save); line && status == IM_OK; line = strtok_r(NULL, "\r\n", &save))
        status = check_checksum_line(archive, path, line, xml, xml_size);
    return status;
}

/* main.xml from the archive, parsed; IM_EFORMAT naming what is missing or malformed. */
static int read_main_xml(zip_t *archive, const char *path, x3p_grid *g)
{
    char *text;
    size_t size;
    int status = zip_entry_read(archive, path, "main.xml", X3P_MAX_XML,
                                "the archive has no main.xml: not an x3p file", &text, &size);
    if (status == IM_OK)
        status = check_checksum_file(archive, path, text, size);
    if (status != IM_OK) {
        free(text);
        return status;
    }
    xmlDoc *doc = xmlReadMemory(text, (int)size, "main.xml", NULL,
                                XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING);
    free(text);
    xmlNode *root = doc ? xmlDocGetRootElement(doc) : NULL;
    if (!root || strcmp((const char *)root->name, "ISO5436_2") != 0)
        status = im_fail(IM_EFORMAT, "%s: main.xml is not well-formed ISO 5436-2 XML (no ISO5436_2 root)", path);
    else if (doc->intSubset) /* entities could expand without bound when the text is read */
        status = im_fail(IM_EFORMAT, "%s: main.xml declares a DTD: not accepted in an x3p file", path);
    if (status == IM_OK)
        status = parse_axes(path, root, g);
    if (status == IM_OK)
        status = parse_matrix(path, root, g);
    xmlFreeDoc(doc);
    return status;
}

static int value_size(char type) { return type == 'I' ? 2 : type == 'L' || type == 'F' ? 4 : 8; }

static double decode(const uint8_t *b, char type)
{
    uint64_t bits = 0;
    for (int i = value_size(type) - 1; i >= 0; --i)
        bits = bits << 8 | b[i];
    union {
        uint32_t u;
        float f;
    } f4 = {(uint32_t)bits};
    union {
        uint64_t u;
        double d;
    } d8 = {bits};
    return type == 'I' ? (int16_t)bits : type == 'L' ? (int32_t)bits : type == 'F' ? f4.f : d8.d;
}

/* The heights' destination while the data entry is read. */
typedef struct heights_sink {
    const x3p_grid *g;
    im_field *field;
} heights_sink;

/* A sink decoding whole values into heights Offset + Increment x value. */
static void decode_heights(void *context, const uint8_t *bytes, size_t size, size_t offset)
{
    const heights_sink *sink = context;
    size_t value = (size_t)value_size(sink->g->z_type), first = offset / value;
    for (size_t k = 0; k < size / value; ++k)
        sink->field->data[first + k] = sink->g->z_offset +
                                       sink->g->z_increment * decode(bytes + k * value, sink->g->z_type);
}

/* A sink marking the invalid points of the field `context` missing (NaN): a bit per point, least
 * significant first, 0 invalid; the bits past the last point, in the last byte, are padding. */
static void mark_invalid_points(void *context, const uint8_t *bytes, size_t size, size_t offset)
{
    im_field *field = context;
    size_t count = im_field_count(field);
    for (size_t k = 0; k < size; ++k)
        for (int bit = 0; bit < 8; ++bit) {
            size_t point = (offset + k) * 8 + (size_t)bit;
            if (point < count && !(bytes[k] >> bit & 1))
                field->data[point] = NAN;
        }
}

/* The entry link names must hold exactly `need` bytes (`needs` says what for); it is read through sink
 * and its MD5 checked when one is stated. */
static int read_link(zip_t *archive, const char *path, const x3p_link *link, size_t need, const char *needs,
                     entry_sink sink, void *context)
{
    size_t size = 0;
    int status = entry_size(archive, path, link->path, link->key, &size);
    if (status == IM_OK && size != need)
        return im_fail(IM_EFORMAT, "%s: %s holds %zu bytes, %s need %zu", path, link->path, size, needs, need);
    const int stated_md5 = link->md5[0] != '\0'; /* the MD5 is taken only when there is one to check */
    char hex[MD5_HEX + 1], md5_key[64];
    if (status == IM_OK)
        status = read_entry(archive, path, link->path, need, sink, context, stated_md5 ? hex : NULL);
    if (status != IM_OK || !stated_md5)
        return status;
    snprintf(md5_key, sizeof md5_key, "Record3/DataLink/%s", link->md5_key);
    return check_md5(path, link->path, link->md5, hex, md5_key);
}

/* The values, heights Offset + Increment x value in metres, then the valid points' bits, if any. */
static int read_values(zip_t *archive, const char *path, const x3p_grid *g, im_field *field)
{
    size_t count = im_field_count(field);
    char needs[96];
    snprintf(needs, sizeof needs, "SizeX x SizeY = %ld x %ld values of type %c", g->nx, g->ny, g->z_type);
    heights_sink heights = {g, field};
    int status = read_link(archive, path, &g->data, count * (size_t)value_size(g->z_type), needs, decode_heights,
                           &heights);
    if (status != IM_OK || g->valid.path[0] == '\0')
        return status;
    snprintf(needs, sizeof needs, "SizeX x SizeY = %ld x %ld points of a bit each", g->nx, g->ny);
    return read_link(archive, path, &g->valid, (count + 7) / 8, needs, mark_invalid_points, field);
}

int x3p_read_raw(const char *path, im_field **out, surface_stated *stated)
{
    *out = NULL;
    int error = 0;
    zip_t *archive = zip_open(path, ZIP_RDONLY | ZIP_CHECKCONS, &error);
    if (!archive) {
        zip_error_t z;
        zip_error_init_with_code(&z, error);
        int status = im_fail(error == ZIP_ER_OPEN || error == ZIP_ER_NOENT ? IM_EIO : IM_EFORMAT,
                             "%s: cannot open as an x3p (zip) archive: %s", path, zip_error_strerror(&z));
        zip_error_fini(&z);
        return status;
    }
    x3p_grid g = {0};
    int status = read_main_xml(archive, path, &g);
    if (status == IM_OK && (status = im_field_create((int)g.nx, (int)g.ny, 1.0, out)) != IM_OK)
        im_fail_context(status, "%s", path);
    if (status == IM_OK && (status = read_values(archive, path, &g, *out)) != IM_OK) {
        im_field_free(*out);
        *out = NULL;
    }
    zip_discard(archive);
    *stated = (surface_stated){.units = {g.dx, g.dy, "m", "m"},
                               .spacing_keys = "Record1/Axes/CX/Increment and CY/Increment",
                               .lateral_key = "x3p (metres)",
                               .height_key = "x3p (metres)"};
    return status;
}

int im_x3p_read(const char *path, im_field **out)
{
    ARG_REQUIRE(path, "path");
    ARG_REQUIRE(out, "out");
    return surface_read_format(path, x3p_read_raw, NULL, out, NULL);
}

/* ---- writing ---- */

/* A child element in no namespace, as ISO 5436-2 files have them under the p: root (xmlNewChild would
 * put it in the parent's namespace). Texts here are numbers and fixed words: nothing to escape. */
static xmlNode *add(xmlNode *parent, const char *name, const char *text)
{
    xmlNode *node = xmlNewDocNode(parent->doc, NULL, (const xmlChar *)name, (const xmlChar *)text);
    return xmlAddChild(parent, node);
}

static void add_axis(xmlNode *axes, const char *name, const char *type, const char *data_type, double increment)
{
    char text[32];
    xmlNode *axis = add(axes, name, NULL);
    add(axis, "AxisType", type);
    add(axis, "DataType", data_type);
    snprintf(text, sizeof text, "%.17g", increment);
    add(axis, "Increment", text);
    add(axis, "Offset", "0");
}

/* Record2: when and by what the file was made. The schema requires a date, an instrument and a probing
 * system; a computed surface's probing system is "Software". */
static void add_record2(xmlNode *root)
{
    char date[32];
    time_t now = time(NULL);
    struct tm utc;
    strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", gmtime_r(&now, &utc));
    xmlNode *record2 = add(root, "Record2", NULL);
    add(record2, "Date", date);
    add(record2, "Creator", "indentmap " IM_VERSION);
    xmlNode *instrument = add(record2, "Instrument", NULL);
    add(instrument, "Manufacturer", "indentmap");
    add(instrument, "Model", "indentmap");
    add(instrument, "Serial", "none");
    add(instrument, "Version", IM_VERSION);
    xmlNode *probing = add(record2, "ProbingSystem", NULL);
    add(probing, "Type", "Software");
    add(probing, "Identification", "indentmap " IM_VERSION);
}

/* Record3's DataLink: the data in bindata/data.bin as doubles whose MD5 is data_md5 (hex), and where
 * some points are missing, their validity bits in bindata/valid.bin whose MD5 is valid_md5 (else NULL). */
static void add_data_link(xmlNode *record3, const char *data_md5, const char *valid_md5)
{
    xmlNode *link = add(record3, "DataLink", NULL);
    add(link, "PointDataLink", "bindata/data.bin");
    add(link, "MD5ChecksumPointData", data_md5);
    if (!valid_md5)
        return;
    add(link, "ValidPointsLink", "bindata/valid.bin");
    add(link, "MD5ChecksumValidPoints", valid_md5);
}

/* main.xml for a field of spacing `spacing` metres (add_data_link: the data and valid points). */
static xmlDoc *main_xml(const im_field *field, double spacing, const char *data_md5, const char *valid_md5)
{
    xmlDoc *doc = xmlNewDoc((const xmlChar *)"1.0");
    xmlNode *root = xmlNewNode(NULL, (const xmlChar *)"ISO5436_2");
    xmlNs *ns = xmlNewNs(root, (const xmlChar *)"http://www.opengps.eu/2008/ISO5436_2", (const xmlChar *)"p");
    xmlSetNs(root, ns);
    xmlDocSetRootElement(doc, root);
    xmlNode *record1 = add(root, "Record1", NULL);
    add(record1, "Revision", "ISO5436 - 2000");
    add(record1, "FeatureType", "SUR");
    xmlNode *axes = add(record1, "Axes", NULL);
    add_axis(axes, "CX", "I", "D", spacing);
    add_axis(axes, "CY", "I", "D", spacing);
    add_axis(axes, "CZ", "A", "D", 1.0);
    add_record2(root);
    xmlNode *record3 = add(root, "Record3", NULL);
    xmlNode *matrix = add(record3, "MatrixDimension", NULL);
    char text[32];
    snprintf(text, sizeof text, "%d", field->nx);
    add(matrix, "SizeX", text);
    snprintf(text, sizeof text, "%d", field->ny);
    add(matrix, "SizeY", text);
    add(matrix, "SizeZ", "1");
    add_data_link(record3, data_md5, valid_md5);
    add(add(root, "Record4", NULL), "ChecksumFile", "md5checksum.hex");
    return doc;
}

/* Adds a malloc'ed buffer to the archive, which frees it (also on failure). */
static int add_buffer(zip_t *archive, const char *name, void *bytes, size_t size)
{
    zip_source_t *source = zip_source_buffer(archive, bytes, size, 1);
    if (!source) {
        free(bytes);
        return -1;
    }
    if (zip_file_add(archive, name, source, ZIP_FL_OVERWRITE) < 0) {
        zip_source_free(source);
        return -1;
    }
    return 0;
}

/* The heights in metres as the file's doubles (a little-endian host: the bytes are the file's; a
 * missing point stays NaN, which its validity bit marks), or NULL. */
static double *data_in_metres(const im_field *field, double metres)
{
    size_t count = im_field_count(field);
    double *data = malloc(count * sizeof *data);
    for (size_t i = 0; data && i < count; ++i)
        data[i] = field->data[i] * metres;
    return data;
}

static int has_missing_points(const im_field *field)
{
    size_t count = im_field_count(field);
    for (size_t i = 0; i < count; ++i)
        if (isnan(field->data[i]))
            return 1;
    return 0;
}

/* The points' validity as ValidPointsLink holds it (read by mark_invalid_points): a bit per point in
 * the data's order, least significant first, 1 valid, the last byte's unused bits 0; in a malloc'ed
 * buffer of *size bytes, or NULL. */
static uint8_t *validity_bits(const im_field *field, size_t *size)
{
    size_t count = im_field_count(field);
    *size = (count + 7) / 8;
    uint8_t *bits = calloc(*size, 1);
    for (size_t i = 0; bits && i < count; ++i)
        if (!isnan(field->data[i]))
            bits[i / 8] |= (uint8_t)(1u << (i % 8));
    return bits;
}

/* The document as UTF-8 text in a malloc'ed buffer (which the archive frees), or NULL; frees doc. */
static char *dump_xml(xmlDoc *doc, size_t *size)
{
    xmlChar *xml = NULL;
    int length = 0;
    xmlDocDumpFormatMemoryEnc(doc, &xml, &length, "UTF-8", 1);
    xmlFreeDoc(doc);
    char *copy = xml && length > 0 ? malloc((size_t)length) : NULL;
    if (copy)
        memcpy(copy, xml, (size_t)length);
    xmlFree(xml);
    *size = copy ? (size_t)length : 0;
    return copy;
}

/* md5checksum.hex: the MD5 of main.xml as md5sum writes it, in a malloc'ed buffer, or NULL. */
static char *checksum_file(const char *xml, size_t xml_size, size_t *size)
{
    char hex[MD5_HEX + 1], *text = malloc(sizeof hex + sizeof " *main.xml\n");
    if (!text)
        return NULL;
    md5_hex(xml, xml_size, 0, hex);
    *size = (size_t)snprintf(text, sizeof hex + sizeof " *main.xml\n", "%s *main.xml\n", hex);
    return text;
}

/* An entry of the archive written: its name and a malloc'ed buffer of its bytes (NULL: none, or
 * allocation failed). */
typedef struct x3p_entry {
    const char *name;
    void *bytes;
    size_t size;
} x3p_entry;

enum { X3P_DATA, X3P_VALID, X3P_XML, X3P_CHECKSUM, X3P_ENTRIES };

/* Frees the entries' buffers (the archive has not taken them). */
static void free_entries(x3p_entry entries[X3P_ENTRIES])
{
    for (int i = 0; i < X3P_ENTRIES; ++i)
        free(entries[i].bytes);
}

/* The entries of the archive for field: the data, the valid points' bits when some are missing
 * (entries[X3P_VALID].name NULL otherwise), main.xml and md5checksum.hex. IM_ENOMEM after freeing
 * them when one cannot be made. */
static int make_entries(const char *path, const im_field *field, double metres, x3p_entry entries[X3P_ENTRIES])
{
    size_t count = im_field_count(field), valid_size = 0, xml_size = 0, checksum_size = 0;
    const int missing = has_missing_points(field);
    char data_md5[MD5_HEX + 1] = "", valid_md5[MD5_HEX + 1] = "";
    double *data = data_in_metres(field, metres);
    uint8_t *valid = missing ? validity_bits(field, &valid_size) : NULL;
    int made = data && (valid || !missing);
    if (made) {
        md5_hex(data, count * sizeof *data, 1, data_md5);
        if (valid)
            md5_hex(valid, valid_size, 1, valid_md5);
    }
    char *xml = made ? dump_xml(main_xml(field, field->delta * metres, data_md5, valid ? valid_md5 : NULL), &xml_size)
                     : NULL;
    char *checksum = xml ? checksum_file(xml, xml_size, &checksum_size) : NULL;
    entries[X3P_DATA] = (x3p_entry){"bindata/data.bin", data, count * sizeof *data};
    entries[X3P_VALID] = (x3p_entry){valid ? "bindata/valid.bin" : NULL, valid, valid_size};
    entries[X3P_XML] = (x3p_entry){"main.xml", xml, xml_size};
    entries[X3P_CHECKSUM] = (x3p_entry){"md5checksum.hex", checksum, checksum_size};
    if (checksum)
        return IM_OK;
    free_entries(entries);
    return im_fail(IM_ENOMEM, "%s: allocation of the x3p contents (%zu values) failed", path, count);
}

/* The bytes a memory source holds, in a malloc'ed buffer. */
static int source_bytes(const char *path, zip_source_t *source, void **bytes, size_t *size)
{
    *bytes = NULL;
    if (zip_source_open(source) < 0)
        return im_fail(IM_EIO, "%s: cannot read the x3p archive made: %s", path,
                       zip_error_strerror(zip_source_error(source)));
    zip_int64_t length = zip_source_seek(source, 0, SEEK_END) == 0 ? zip_source_tell(source) : -1;
    *bytes = length > 0 && zip_source_seek(source, 0, SEEK_SET) == 0 ? malloc((size_t)length) : NULL;
    int read = *bytes && zip_source_read(source, *bytes, (zip_uint64_t)length) == length;
    zip_source_close(source);
    if (read) {
        *size = (size_t)length;
        return IM_OK;
    }
    free(*bytes);
    *bytes = NULL;
    return im_fail(IM_EIO, "%s: cannot read the x3p archive made (%lld bytes)", path, (long long)length);
}

/* The zip archive of the entries, made in memory (so that the file is written as every output is, by
 * im_write_file_atomic: through symbolic links, past the output guard); the entries' buffers go to it,
 * the archive's bytes to *bytes (malloc'ed). */
static int archive_in_memory(const char *path, x3p_entry entries[X3P_ENTRIES], void **bytes, size_t *size)
{
    zip_error_t error;
    zip_error_init(&error);
    zip_source_t *memory = zip_source_buffer_create(NULL, 0, 0, &error);
    zip_t *archive = memory ? zip_open_from_source(memory, ZIP_TRUNCATE, &error) : NULL;
    if (!archive) {
        free_entries(entries);
        zip_source_free(memory);
        int status = im_fail(IM_ENOMEM, "%s: cannot make the x3p archive: %s", path, zip_error_strerror(&error));
        zip_error_fini(&error);
        return status;
    }
    zip_source_keep(memory); /* read after zip_close, which drops the archive's reference */
    int failed = 0;          /* each buffer goes to the archive, which frees it, even after a failure */
    for (int i = 0; i < X3P_ENTRIES; ++i)
        if (entries[i].name)
            failed |= add_buffer(archive, entries[i].name, entries[i].bytes, entries[i].size) != 0;
    int status = IM_OK;
    if (failed || zip_close(archive) != 0) {
        status = im_fail(IM_EIO, "%s: cannot make the x3p archive: %s", path, zip_strerror(archive));
        zip_discard(archive);
    }
    if (status == IM_OK)
        status = source_bytes(path, memory, bytes, size);
    zip_source_free(memory);
    return status;
}

/* Writes heights and spacing in metres (the field needs a length unit); missing points (NaN) are
 * marked invalid in a ValidPointsLink. */
int im_x3p_write(const char *path, const im_field *field)
{
    ARG_REQUIRE(path, "path");
    ARG_VIEW(field, "field");
    int status = formats_check_heights_or_missing_writable(field, path);
    if (status != IM_OK)
        return status;
    double metres = im_length_unit_metres(field->unit, NULL);
    if (metres == 0.0)
        return im_fail(IM_EINVAL, "%s: an .x3p states metres: the surface needs a length unit (it has '%s')", path,
                       field->unit);
    x3p_entry entries[X3P_ENTRIES];
    void *bytes = NULL;
    size_t size = 0;
    status = make_entries(path, field, metres, entries);
    if (status == IM_OK)
        status = archive_in_memory(path, entries, &bytes, &size);
    if (status == IM_OK)
        status = im_write_file_atomic(path, bytes, size);
    free(bytes);
    return status;
}
