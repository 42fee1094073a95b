/* indentmap-gwyddion-read: reads one instrument file with Gwyddion's file modules and hands the
 * chosen channel to indentmap over its standard output.
 *
 * Why a separate program: Gwyddion's file modules (GPL-2.0-or-later) are plug-ins of the Gwyddion
 * application and pull GTK 2 in at run time; a vendor parser that crashes on a damaged file must not
 * take the caller (a Python kernel, an MPI rank) down with it. So libindentmap never links them: it
 * runs this program (src/formats/gwyddion.c) and reads the stream below.
 *
 * Usage: indentmap-gwyddion-read [--] FILE [CHANNEL] CHANNEL: an index or a title; default: the first
 *                                                    channel whose values are lengths
 *        indentmap-gwyddion-read --formats           the file modules that load, "NAME<TAB>WHAT" a line
 * Stream (text lines, then binary; see src/formats/gwyddion.h):
 *   indentmap-gwyddion-read 1
 *   module NAME
 *   channel ID<TAB>XRES<TAB>YRES<TAB>ZUNIT<TAB>TITLE      one line per channel, ZUNIT "-" when none
 *   field ID XRES YRES XREAL YREAL XYUNIT ZUNIT MASK TITLE the chosen channel (units "-" when none)
 *   XRES*YRES doubles (native byte order), row 0 first; then, when MASK is 1, XRES*YRES bytes (1: the
 *   point is invalid)
 * or, at any point before the field line, "error KIND MESSAGE" (KIND: unknown-format when no module
 * reads the file; line-scan when the file holds no image but curves, a profile's graph, MESSAGE then
 * saying how many; else failed) and exit status 2. Titles and units come from the file: control bytes
 * are written as '?' and blanks in units as '_', so that no file can break a line. A module that
 * runs longer than CHILD_READ_SECONDS is ended by SIGALRM (a parser looping on a damaged file). */
#include "formats/child_reader.h"

#include <libgwyddion/gwyddion.h>
#include <libgwymodule/gwymodule-file.h>
#include <libgwymodule/gwymoduleloader.h>
#include <libprocess/datafield.h>
#include <libprocess/gwyprocess.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Declared in Gwyddion's app/app.h, which includes GTK's development headers; this program needs
 * only this one function of it (loading the file modules without a display). */
void gwy_app_init_nongui(const gchar *option, ...);

/* Declared in Gwyddion's libgwydgets/gwygraphmodel.h and gwygraphcurvemodel.h, which include GTK's
 * development headers too: a module reading a profile (a stylus scan) gives graphs of curves, no image. */
typedef struct _GwyGraphModel GwyGraphModel;
typedef struct _GwyGraphCurveModel GwyGraphCurveModel;
gint gwy_graph_model_get_n_curves(GwyGraphModel *gmodel);
GwyGraphCurveModel *gwy_graph_model_get_curve(GwyGraphModel *gmodel, gint cindex);
gint gwy_graph_curve_model_get_ndata(GwyGraphCurveModel *gcmodel);

typedef struct channel {
    int id;
    GwyDataField *data, *mask;
    const char *title;
} channel;

static int fail(const char *kind, const char *format, const char *detail)
{
    printf("error %s ", kind);
    printf(format, detail);
    printf("\n");
    return 2;
}

/* A copy of text from the file that cannot break a line of the stream (the caller frees it). */
static gchar *one_line(const char *text, char blank)
{
    gchar *copy = g_strdup(text ? text : "");
    for (gchar *at = copy; *at; ++at)
        if ((unsigned char)*at < 0x20 || *at == 0x7f || (blank && *at == ' '))
            *at = (unsigned char)*at < 0x20 || *at == 0x7f ? '?' : blank;
    return copy;
}

/* The channel id of a container key "/ID/data", or -1. */
static int data_key_id(const char *key)
{
    int id, consumed = 0;
    return sscanf(key, "/%d/data%n", &id, &consumed) == 1 && key[consumed] == '\0' && id >= 0 ? id : -1;
}

static void collect_channel(gpointer key, gpointer value, gpointer user)
{
    GArray *channels = user;
    int id = data_key_id(g_quark_to_string(GPOINTER_TO_UINT(key)));
    GValue *held = value;
    if (id < 0 || !G_VALUE_HOLDS_OBJECT(held) || !GWY_IS_DATA_FIELD(g_value_get_object(held)))
        return;
    channel found = {.id = id, .data = g_value_get_object(held)};
    g_array_append_val(channels, found);
}

static gint by_id(gconstpointer a, gconstpointer b) { return ((const channel *)a)->id - ((const channel *)b)->id; }

/* Each channel's title and mask ("/ID/data/title", "/ID/mask"), when the file has them. */
static void complete_channels(GwyContainer *container, GArray *channels)
{
    for (guint k = 0; k < channels->len; ++k) {
        channel *c = &g_array_index(channels, channel, k);
        char key[64];
        const guchar *title = NULL;
        snprintf(key, sizeof key, "/%d/data/title", c->id);
        c->title = gwy_container_gis_string_by_name(container, key, &title) ? (const char *)title : "";
        GObject *mask = NULL;
        snprintf(key, sizeof key, "/%d/mask", c->id);
        if (gwy_container_gis_object_by_name(container, key, &mask) && GWY_IS_DATA_FIELD(mask))
            c->mask = GWY_DATA_FIELD(mask);
    }
}

/* A unit's plain name as one word, "-" for none (the caller frees it). */
static gchar *unit_name(GwySIUnit *unit)
{
    gchar *name = gwy_si_unit_get_string(unit, GWY_SI_UNIT_FORMAT_PLAIN);
    gchar *word = one_line(name[0] ? name : "-", '_');
    g_free(name);
    return word;
}

static int holds_lengths(const channel *c)
{
    gchar *z = unit_name(gwy_data_field_get_si_unit_z(c->data));
    int length = strcmp(z, "m") == 0;
    g_free(z);
    return length;
}

static void print_channels(const GArray *channels)
{
    for (guint k = 0; k < channels->len; ++k) {
        const channel *c = &g_array_index(channels, channel, k);
        gchar *z = unit_name(gwy_data_field_get_si_unit_z(c->data)), *title = one_line(c->title, 0);
        printf("channel %d\t%d\t%d\t%s\t%s\n", c->id, gwy_data_field_get_xres(c->data),
               gwy_data_field_get_yres(c->data), z, title);
        g_free(z);
        g_free(title);
    }
}

/* The channel asked for (an index or a title, case ignored), or by default the first holding lengths
 * (a lone channel of unknown unit is taken as a bare matrix would be); NULL when none is. */
static const channel *choose_channel(const GArray *channels, const char *asked)
{
    char *end = NULL;
    long index = asked ? strtol(asked, &end, 10) : -1;
    int by_index = asked && end != asked && *end == '\0';
    for (guint k = 0; k < channels->len; ++k) {
        const channel *c = &g_array_index(channels, channel, k);
        if (asked ? (by_index ? c->id == index : g_ascii_strcasecmp(c->title, asked) == 0) : holds_lengths(c))
            return c;
    }
    if (!asked && channels->len == 1) {
        gchar *z = unit_name(gwy_data_field_get_si_unit_z(g_array_index(channels, channel, 0).data));
        int unknown = strcmp(z, "-") == 0;
        g_free(z);
        return unknown ? &g_array_index(channels, channel, 0) : NULL;
    }
    return NULL;
}

/* masks_invalid: the module's masks mark invalid points (instrument importers); in Gwyddion's own
 * .gwy files a mask is a selection the user made (grains, a threshold), not missing data. */
static void write_field(const channel *c, int masks_invalid)
{
    GwyDataField *data = c->data;
    int xres = gwy_data_field_get_xres(data), yres = gwy_data_field_get_yres(data);
    int masked = masks_invalid && c->mask && gwy_data_field_get_xres(c->mask) == xres &&
                 gwy_data_field_get_yres(c->mask) == yres;
    gchar *xy = unit_name(gwy_data_field_get_si_unit_xy(data)), *z = unit_name(gwy_data_field_get_si_unit_z(data));
    gchar *title = one_line(c->title, 0);
    printf("field %d %d %d %.17g %.17g %s %s %d %s\n", c->id, xres, yres, gwy_data_field_get_xreal(data),
           gwy_data_field_get_yreal(data), xy, z, masked, title);
    g_free(xy);
    g_free(z);
    g_free(title);
    fwrite(gwy_data_field_get_data_const(data), sizeof(double), (size_t)xres * (size_t)yres, stdout);
    if (!masked)
        return;
    const double *mask = gwy_data_field_get_data_const(c->mask);
    for (size_t k = 0; k < (size_t)xres * (size_t)yres; ++k)
        putchar(mask[k] > 0.5);
}

/* The curves of the container's graphs: how many graphs, curves and points of the longest curve. */
typedef struct curves_found {
    GType graph_type;
    int graphs, curves, longest;
} curves_found;

static void count_curves(gpointer key, gpointer value, gpointer user)
{
    (void)key;
    curves_found *found = user;
    GValue *held = value;
    if (!found->graph_type || !G_VALUE_HOLDS_OBJECT(held) ||
        !G_TYPE_CHECK_INSTANCE_TYPE(g_value_get_object(held), found->graph_type))
        return;
    GwyGraphModel *graph = (GwyGraphModel *)g_value_get_object(held);
    int curves = gwy_graph_model_get_n_curves(graph);
    ++found->graphs;
    found->curves += curves;
    for (int k = 0; k < curves; ++k) {
        int points = gwy_graph_curve_model_get_ndata(gwy_graph_model_get_curve(graph, k));
        found->longest = points > found->longest ? points : found->longest;
    }
}

/* A container without images: a line scan when it holds curves (Bruker's OPDx of a stylus profile). */
static int refuse_without_images(GwyContainer *container)
{
    curves_found found = {.graph_type = g_type_from_name("GwyGraphModel")};
    gwy_container_foreach(container, NULL, count_curves, &found);
    if (found.curves == 0)
        return fail("failed", "%s", "the file holds no image (data field)");
    printf("error line-scan %d curve%s in %d graph%s, the longest of %d points, and no image (data field)\n",
           found.curves, found.curves == 1 ? "" : "s", found.graphs, found.graphs == 1 ? "" : "s", found.longest);
    return 2;
}

/* A module that loads files: its name and what it reads, e.g. "nanoscope<TAB>Nanoscope III files". */
static void print_module(gpointer name, gpointer user)
{
    (void)user;
    if (gwy_file_func_get_operations(name) & GWY_FILE_OPERATION_LOAD)
        printf("%s\t%s\n", (const char *)name, gwy_file_func_get_description(name));
}

static int list_formats(void)
{
    gwy_file_func_foreach(print_module, NULL);
    return 0;
}

static int read_file(const char *path, const char *asked)
{
    printf("indentmap-gwyddion-read 1\n");
    GError *error = NULL;
    const char *module = gwy_file_detect(path, FALSE, GWY_FILE_OPERATION_LOAD);
    GwyContainer *container = gwy_file_load(path, GWY_RUN_NONINTERACTIVE, &error);
    if (!container) {
        int unknown = error && error->domain == GWY_MODULE_FILE_ERROR &&
                      error->code == GWY_MODULE_FILE_ERROR_UNIMPLEMENTED;
        return fail(unknown ? "unknown-format" : "failed", "%s", error ? error->message : "Gwyddion gave no reason");
    }
    printf("module %s\n", module ? module : "-");
    GArray *channels = g_array_new(FALSE, FALSE, sizeof(channel));
    gwy_container_foreach(container, NULL, collect_channel, channels);
    g_array_sort(channels, by_id);
    complete_channels(container, channels);
    print_channels(channels);
    const channel *chosen = channels->len ? choose_channel(channels, asked) : NULL;
    int status = 0;
    if (chosen)
        write_field(chosen, !module || strcmp(module, "gwyfile") != 0);
    else
        status = channels->len == 0 ? refuse_without_images(container)
                 : asked            ? fail("failed", "no channel has the index or title '%s'", asked)
                                    : fail("failed", "%s", "no channel holds heights (values in a length unit)");
    g_array_free(channels, TRUE);
    g_object_unref(container);
    return status;
}

/* In a sanitizer build LeakSanitizer would end this program with status 1 for what GLib's type system
 * and Gwyddion's loaded modules keep until exit by design; its own code is still checked for errors.
 * Turned off by its hook, which ASAN_OPTIONS=detect_leaks=1 in the environment (the sanitizer pass of
 * scripts/test.sh, inherited from the program that starts this one) does not override as it does the
 * default options: `indentmap formats` failed there. */
const char *__asan_default_options(void);
const char *__asan_default_options(void) { return "detect_leaks=0"; }
int __lsan_is_turned_off(void);
int __lsan_is_turned_off(void) { return 1; }

int main(int argc, char **argv)
{
    int first = argc > 1 && strcmp(argv[1], "--") == 0 ? 2 : 1; /* "--": a file may be named --formats */
    if (argc - first < 1 || argc - first > 2) {
        fprintf(stderr, "usage: %s [--] FILE [CHANNEL] | --formats\n", argv[0]);
        return 2;
    }
    alarm(CHILD_READ_SECONDS);
    gwy_app_init_nongui(NULL);
    if (first == 1 && strcmp(argv[1], "--formats") == 0)
        return list_formats();
    int status = read_file(argv[first], argc - first == 2 ? argv[first + 1] : NULL);
    return fflush(stdout) == 0 && status == 0 ? 0 : status ? status : 1;
}
