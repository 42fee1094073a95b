/* DIR/index.html: a self-contained page over a run's figures, frames, tables and record. */
#include "indentmap/viewer.h"
#include "core/args.h"
#include "io/json_file.h"

#include "indentmap/io.h"
#include "indentmap/status.h"

#include <ctype.h>
#include <jansson.h>
#include <math.h>
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { MAX_NAMES = 4096, MAX_TEXT_BYTES = 4 << 20, MAX_TABLE_ROWS = 2000, PATH_SIZE = 4096 };
/* The largest image a page embeds (--page-embed): 256 MiB. */
#define MAX_IMAGE_BYTES ((long)256 << 20)

/* What every part of the page is written with. */
typedef struct page {
    FILE *out;
    const char *dir;
    int embed;           /* images as data URIs (viewer.h: im_viewer_options) */
    const json_t *units; /* run.json's units.columns, or NULL */
} page;

typedef struct name_list {
    char *names[MAX_NAMES];
    int count;
} name_list;

static void free_names(name_list *list)
{
    for (int i = 0; i < list->count; ++i)
        free(list->names[i]);
    list->count = 0;
}

static int compare_names(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

static int ends_with(const char *name, const char *suffix)
{
    size_t n = strlen(name), s = strlen(suffix);
    return n > s && strcmp(name + n - s, suffix) == 0;
}

/* The names in folder whose ending is one of suffixes (NULL-terminated), sorted; a missing
 * folder gives none. */
static int list_folder(const char *folder, const char *const *suffixes, name_list *list)
{
    list->count = 0;
    DIR *dir = opendir(folder);
    if (!dir)
        return IM_OK;
    struct dirent *entry;
    int status = IM_OK;
    while (status == IM_OK && (entry = readdir(dir)) != NULL) {
        int wanted = entry->d_name[0] != '.';
        for (int k = 0; wanted && suffixes[k]; ++k)
            if (ends_with(entry->d_name, suffixes[k]))
                break;
            else if (!suffixes[k + 1])
                wanted = 0;
        if (!wanted || list->count == MAX_NAMES)
            continue;
        if (!(list->names[list->count] = strdup(entry->d_name)))
            status = im_fail(IM_ENOMEM, "viewer page: out of memory");
        else
            list->count++;
    }
    closedir(dir);
    qsort(list->names, (size_t)list->count, sizeof list->names[0], compare_names);
    return status;
}

static void escape(FILE *out, const char *text, size_t length)
{
    for (size_t i = 0; i < length; ++i)
        switch (text[i]) {
        case '&': fputs("&amp;", out); break;
        case '<': fputs("&lt;", out); break;
        case '>': fputs("&gt;", out); break;
        case '"': fputs("&quot;", out); break;
        case '\'': fputs("&#39;", out); break;
        default: fputc(text[i], out);
        }
}

static void escape_all(FILE *out, const char *text) { escape(out, text, strlen(text)); }

/* The whole file as a NUL-terminated string; NULL when it is missing, unreadable or too large. */
static char *read_text(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *text = malloc(MAX_TEXT_BYTES + 1);
    size_t length = text ? fread(text, 1, MAX_TEXT_BYTES + 1, f) : 0;
    fclose(f);
    if (!text || length > MAX_TEXT_BYTES) {
        free(text);
        return NULL;
    }
    text[length] = '\0';
    return text;
}

/* RFC 4648 base64 of data[0..size), with padding, no line breaks. */
static void write_base64(FILE *out, const unsigned char *data, size_t size)
{
    static const char ALPHABET[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for (size_t i = 0; i < size; i += 3) {
        const size_t left = size - i;
        const unsigned long bits = (unsigned long)data[i] << 16 | (left > 1 ? (unsigned long)data[i + 1] << 8 : 0) |
                                   (left > 2 ? data[i + 2] : 0);
        const char quad[4] = {ALPHABET[bits >> 18 & 63], ALPHABET[bits >> 12 & 63],
                              left > 1 ? ALPHABET[bits >> 6 & 63] : '=', left > 2 ? ALPHABET[bits & 63] : '='};
        fwrite(quad, 1, 4, out);
    }
}

static const char *media_type(const char *name)
{
    return ends_with(name, ".svg") ? "image/svg+xml" : ends_with(name, ".gif") ? "image/gif" : "image/png";
}

/* An image's file as a data URI: "data:TYPE;base64,...". IM_EIO naming the file when it cannot be read
 * whole (or is larger than MAX_IMAGE_BYTES). */
static int write_data_uri(FILE *out, const char *path)
{
    FILE *f = fopen(path, "rb");
    long size = f && fseek(f, 0, SEEK_END) == 0 ? ftell(f) : -1;
    unsigned char *data = size >= 0 && size <= MAX_IMAGE_BYTES && fseek(f, 0, SEEK_SET) == 0
                              ? malloc((size_t)size + 1)
                              : NULL;
    int read = data && fread(data, 1, (size_t)size, f) == (size_t)size;
    if (f)
        fclose(f);
    if (read) {
        fprintf(out, "data:%s;base64,", media_type(path));
        write_base64(out, data, (size_t)size);
    }
    free(data);
    return read ? IM_OK
                : im_fail(IM_EIO, "viewer page: cannot embed %s (unreadable, or over %ld MiB)", path,
                          MAX_IMAGE_BYTES >> 20);
}

/* Where an image is, relative to the page (name under dir): the name itself, or its data URI when the
 * page embeds its images. */
static int write_source(const page *p, const char *name)
{
    if (!p->embed) {
        escape_all(p->out, name);
        return IM_OK;
    }
    char path[PATH_SIZE];
    int status = im_path_join(path, sizeof path, p->dir, name);
    return status == IM_OK ? write_data_uri(p->out, path) : status;
}

static const char STYLE[] =
    "body{font-family:'DejaVu Sans',Helvetica,Arial,sans-serif;margin:1.5em 2em;color:#222;background:#fff}"
    "h1{font-size:1.5em;margin:0 0 .2em}h2{font-size:1.15em;border-bottom:1px solid #ccc;padding-bottom:.2em;"
    "margin-top:1.6em}.figures{display:flex;flex-wrap:wrap;gap:1.2em}figure{margin:0}"
    "figure img{max-width:100%;height:auto;border:1px solid #eee}figcaption{font-size:.85em;color:#555}"
    ".figures figure{flex:0 1 auto;max-width:100%}.animations "
    "img{width:30em;image-rendering:pixelated}.frames{display:flex;gap:1em;align-items:flex-start}"
    ".frames figure{flex:1 1 0;min-width:0}.frames figure "
    "img{width:100%}.slider{display:flex;align-items:center;gap:1em;margin:.6em 0}"
    ".slider input{flex:1}table{border-collapse:collapse;font-size:.85em;font-variant-numeric:tabular-nums}"
    "th,td{border:1px solid #ddd;padding:.2em .5em;text-align:right}th{background:#f4f4f4}"
    "tr:nth-child(even) td{background:#fafafa}pre{background:#f7f7f7;padding:1em;overflow:auto;font-size:.8em}"
    ".scroll{max-height:32em;overflow:auto}.note{color:#777;font-size:.85em}.unit{font-weight:normal;color:#555}";

/* One row of images under a heading: class names the row's style. */
static int write_images(const page *p, const name_list *list, const char *heading, const char *class_name)
{
    FILE *out = p->out;
    int status = IM_OK;
    if (list->count == 0)
        return status;
    fprintf(out, "<h2>%s</h2>\n<div class=\"figures %s\">\n", heading, class_name);
    for (int i = 0; i < list->count && status == IM_OK; ++i) {
        fputs("<figure><img src=\"", out);
        status = write_source(p, list->names[i]);
        fputs("\" alt=\"", out);
        escape_all(out, list->names[i]);
        fputs("\"><figcaption>", out);
        escape_all(out, list->names[i]);
        fputs("</figcaption></figure>\n", out);
    }
    fputs("</div>\n", out);
    return status;
}

/* A link to a file beside the page; its name alone on a page that embeds its images. */
/* A file of the folder by its name, linked unless the page embeds its images (it may travel alone). */
static void write_file_name(const page *p, const char *name)
{
    if (!p->embed) {
        fputs("<a href=\"", p->out);
        escape_all(p->out, name);
        fputs("\">", p->out);
    }
    escape_all(p->out, name);
    fputs(p->embed ? "" : "</a>", p->out);
}

/* The same after a space, in a sentence. */
static void write_link(const page *p, const char *name)
{
    fputc(' ', p->out);
    write_file_name(p, name);
}

/* Figures (PNG, SVG) and animations (GIF) shown, documents (PDF, MP4) linked (named only, on a page that
 * embeds its images: it may travel without them). */
static int write_figures(const page *p)
{
    FILE *out = p->out;
    const char *dir = p->dir;
    static const char *const figures[] = {".png", ".svg", NULL}, *const animations[] = {".gif", NULL},
                             *const documents[] = {".pdf", ".mp4", NULL};
    name_list list;
    int status = list_folder(dir, figures, &list);
    if (status == IM_OK)
        status = write_images(p, &list, "Figures", "");
    free_names(&list);
    if (status == IM_OK)
        status = list_folder(dir, animations, &list);
    if (status == IM_OK)
        status = write_images(p, &list, "Animations", "animations");
    free_names(&list);
    if (status == IM_OK)
        status = list_folder(dir, documents, &list);
    if (status == IM_OK && list.count > 0) {
        fputs(p->embed ? "<p class=\"note\">Also in the run's folder:" : "<p class=\"note\">Also:", out);
        for (int i = 0; i < list.count; ++i)
            write_link(p, list.names[i]);
        fputs("</p>\n", out);
    }
    free_names(&list);
    return status;
}

/* A frame name PREFIX_NNNN.png, PREFIX of letters, digits, '_' and '-' (so that it can go into
 * HTML ids and script strings as it is): its prefix length and step number; 0 when it is not one. */
static int parse_frame_name(const char *name, size_t *prefix, int *step)
{
    const char *underscore = strrchr(name, '_');
    char *end;
    if (!underscore || underscore == name || !ends_with(name, ".png"))
        return 0;
    for (const char *p = name; p < underscore; ++p)
        if (!(isalnum((unsigned char)*p) || *p == '_' || *p == '-'))
            return 0;
    long number = strtol(underscore + 1, &end, 10);
    if (end == underscore + 1 || strcmp(end, ".png") != 0 || number < 0 || number >= MAX_NAMES)
        return 0;
    *prefix = (size_t)(underscore - name);
    *step = (int)number;
    return 1;
}

/* The order of the frame panels: the known prefixes first, with their captions. */
static const char *caption_of(const char *prefix, size_t length)
{
    static const char *const known[][2] = {{"contact", "contact map"},
                                           {"height", "deformed surface (h − u)"},
                                           {"view3d", "3-D view"}};
    for (int k = 0; k < 3; ++k)
        if (strlen(known[k][0]) == length && strncmp(prefix, known[k][0], length) == 0)
            return known[k][1];
    return NULL;
}

typedef struct frame_group {
    char prefix[64];
    int rank;  /* known prefixes first */
    int first; /* index in the sorted name list of its first frame */
} frame_group;

static int compare_groups(const void *a, const void *b)
{
    const frame_group *x = a, *y = b;
    return x->rank != y->rank ? x->rank - y->rank : strcmp(x->prefix, y->prefix);
}

/* Groups of frames by prefix and the number of steps (largest step + 1). */
static int frame_groups(const name_list *list, frame_group *groups, int capacity, int *steps)
{
    int count = 0;
    *steps = 0;
    for (int i = 0; i < list->count; ++i) {
        size_t length;
        int step;
        if (!parse_frame_name(list->names[i], &length, &step) || length >= sizeof groups[0].prefix)
            continue;
        *steps = step + 1 > *steps ? step + 1 : *steps;
        int g = 0;
        while (g < count &&
               !(strlen(groups[g].prefix) == length && strncmp(groups[g].prefix, list->names[i], length) == 0))
            ++g;
        if (g == count && count < capacity) {
            snprintf(groups[count].prefix, sizeof groups[count].prefix, "%.*s", (int)length, list->names[i]);
            groups[count].rank = caption_of(list->names[i], length) ? 0 : 1;
            groups[count++].first = i;
        }
    }
    qsort(groups, (size_t)count, sizeof *groups, compare_groups);
    return count;
}

/* A frame's image source: frames/NAME, or its data URI. */
static int write_frame_source(const page *p, const char *name)
{
    char relative[PATH_SIZE];
    int status = im_path_join(relative, sizeof relative, "frames", name);
    return status == IM_OK ? write_source(p, relative) : status;
}

/* The frames of one prefix as a JSON array indexed by step (null where missing). */
static int write_frame_array(const page *p, const name_list *list, const frame_group *group, int steps)
{
    FILE *out = p->out;
    int status = IM_OK;
    fputs("[", out);
    for (int step = 0; step < steps && status == IM_OK; ++step) {
        char wanted[1024];
        snprintf(wanted, sizeof wanted, "%s_%04d.png", group->prefix, step);
        const char *found = bsearch(&(const char *){wanted}, list->names, (size_t)list->count, sizeof list->names[0],
                                    compare_names)
                                ? wanted
                                : NULL;
        fputs(step ? "," : "", out);
        if (!found) {
            fputs("null", out);
            continue;
        }
        fputs("\"", out);
        status = write_frame_source(p, found);
        fputs("\"", out);
    }
    fputs("]", out);
    return status;
}

static const char SCRIPT[] =
    "(function(){var slider=document.getElementById('frame-slider');"
    "var label=document.getElementById('frame-label');var steps=FRAMES.steps;"
    "function show(i){FRAMES.groups.forEach(function(g){var img=document.getElementById('frame-'+g.prefix);"
    "var src=g.frames[i];if(src){img.src=src;img.style.visibility='visible';}else{img.style.visibility='hidden';}});"
    "label.textContent='step '+(i+1)+' of '+steps;slider.value=i;}"
    "slider.addEventListener('input',function(){show(parseInt(slider.value,10));});"
    "document.addEventListener('keydown',function(e){var i=parseInt(slider.value,10);"
    "if(e.key==='ArrowRight'&&i<steps-1)show(i+1);else if(e.key==='ArrowLeft'&&i>0)show(i-1);});"
    "show(0);})();\n";

/* At most this many kinds of frames (contact, height, view3d, ...) side by side. */
enum { FRAME_GROUPS_MAX = 8 };

/* A PNG's width and height in pixels from its IHDR chunk; 0 when unreadable. */
static void png_size(const char *path, long *width, long *height)
{
    unsigned char header[24];
    FILE *f = fopen(path, "rb");
    size_t got = f ? fread(header, 1, sizeof header, f) : 0;
    if (f)
        fclose(f);
    *width = *height = 0;
    if (got != sizeof header || memcmp(header + 12, "IHDR", 4) != 0)
        return;
    long w = (long)header[16] << 24 | (long)header[17] << 16 | (long)header[18] << 8 | header[19];
    long h = (long)header[20] << 24 | (long)header[21] << 16 | (long)header[22] << 8 | header[23];
    if (h > 0 && w > 0 && w < (1L << 20) && h < (1L << 20))
        *width = w, *height = h;
}

/* The size of a panel's first frame (0 x 0 when unreadable: a path that does not fit is "" too). */
typedef struct panel_size {
    long width, height;
} panel_size;

/* A frame panel's style: its share of the row is its image's aspect ratio, so that all are drawn at one
 * height, and its width is capped at the one it has at common_height, the least natural height of the
 * panels: no panel is blown up beyond its image (a lone 256-pixel frame would fill the window), and the
 * panels stay at one height. An unreadable image takes a square's share, uncapped. */
static void write_panel_style(FILE *out, panel_size size, long common_height)
{
    if (size.width == 0) {
        fputs("flex:1000 1 0", out);
        return;
    }
    fprintf(out, "flex:%ld 1 0;max-width:%ldpx", 1000 * size.width / size.height,
            size.width * common_height / size.height);
}

/* The frame panels side by side, each showing its prefix's first frame until the script takes over. */
static int write_frame_panels(const page *p, const char *folder, const name_list *list, const frame_group *groups,
                              int count)
{
    panel_size sizes[FRAME_GROUPS_MAX];
    long common_height = 0;
    for (int g = 0; g < count; ++g) {
        char path[PATH_SIZE + 64];
        im_path_join(path, sizeof path, folder, list->names[groups[g].first]);
        png_size(path, &sizes[g].width, &sizes[g].height);
        if (sizes[g].height > 0 && (common_height == 0 || sizes[g].height < common_height))
            common_height = sizes[g].height;
    }
    int status = IM_OK;
    fputs("<div class=\"frames\">\n", p->out);
    for (int g = 0; g < count && status == IM_OK; ++g) {
        const char *caption = caption_of(groups[g].prefix, strlen(groups[g].prefix));
        fputs("<figure style=\"", p->out);
        write_panel_style(p->out, sizes[g], common_height);
        fprintf(p->out, "\"><img id=\"frame-%s\" src=\"", groups[g].prefix);
        status = write_frame_source(p, list->names[groups[g].first]);
        fprintf(p->out, "\" alt=\"%s\"><figcaption>%s</figcaption></figure>\n", groups[g].prefix,
                caption ? caption : groups[g].prefix);
    }
    fputs("</div>\n", p->out);
    return status;
}

static int write_frames(const page *p)
{
    static const char *const pngs[] = {".png", NULL};
    FILE *out = p->out;
    char folder[PATH_SIZE];
    if (im_path_join(folder, sizeof folder, p->dir, "frames") != IM_OK)
        return IM_OK; /* no frames can be listed there: the page goes without them */
    name_list list;
    int status = list_folder(folder, pngs, &list), steps;
    frame_group groups[FRAME_GROUPS_MAX];
    int count = status == IM_OK ? frame_groups(&list, groups, FRAME_GROUPS_MAX, &steps) : 0;
    if (count > 0) {
        fputs("<h2>Frames</h2>\n<div class=\"slider\"><input type=\"range\" id=\"frame-slider\" min=\"0\" max=\"",
              out);
        fprintf(out,
                "%d\" value=\"0\" step=\"1\" aria-label=\"step\"><span id=\"frame-label\">step 1 of "
                "%d</span></div>\n",
                steps - 1, steps);
        status = write_frame_panels(p, folder, &list, groups, count);
        fprintf(out, "<script>var FRAMES={steps:%d,groups:[", steps);
        for (int g = 0; g < count && status == IM_OK; ++g) {
            fprintf(out, "%s{prefix:\"%s\",frames:", g ? "," : "", groups[g].prefix);
            status = write_frame_array(p, &list, &groups[g], steps);
            fputs("}", out);
        }
        fprintf(out, "]};\n%s</script>\n", SCRIPT);
    }
    free_names(&list);
    return status;
}

/* An unquoted CSV value: a number written with more than 6 significant digits is shown with 6 (the
 * files keep 17 for the machine; a page is read by people), the whole of it on hover. */
static void write_csv_value(FILE *out, const char *s, size_t length)
{
    char text[64], *end;
    if (length > 0 && length < sizeof text) {
        memcpy(text, s, length);
        text[length] = '\0';
        double value = strtod(text, &end);
        char shown[32];
        snprintf(shown, sizeof shown, "%.6g", value);
        if (end == text + length && isfinite(value) && strlen(shown) < length) {
            fprintf(out, "<span title=\"%s\">%s</span>", text, shown);
            return;
        }
    }
    escape(out, s, length);
}

/* One CSV field from *p (double quotes allowed); advances past its comma. */
static void write_csv_field(FILE *out, const char **p)
{
    const char *s = *p;
    if (*s == '"') {
        for (++s; *s && !(*s == '"' && s[1] != '"'); ++s) {
            s += *s == '"'; /* "" is one quote */
            escape(out, s, 1);
        }
        s += *s == '"';
    } else {
        size_t length = strcspn(s, ",\n\r");
        write_csv_value(out, s, length);
        s += length;
    }
    *p = *s == ',' ? s + 1 : s;
}

/* A header cell: the column's name and, under it, its unit from run.json's units.columns when that
 * names it ("1": a number without unit). */
static void write_header_field(const page *p, const char **cursor)
{
    const char *s = *cursor, *unit = NULL;
    size_t length = *s == '"' ? 0 : strcspn(s, ",\n\r");
    char name[128];
    if (p->units && length > 0 && length < sizeof name) {
        memcpy(name, s, length);
        name[length] = '\0';
        unit = json_string_value(json_object_get(p->units, name));
    }
    write_csv_field(p->out, cursor);
    if (!unit)
        return;
    fputs("<br><span class=\"unit\">(", p->out);
    escape_all(p->out, unit);
    fputs(")</span>", p->out);
}

static void write_table(const page *p, const char *name)
{
    FILE *out = p->out;
    char path[PATH_SIZE];
    char *text = im_path_join(path, sizeof path, p->dir, name) == IM_OK ? read_text(path) : NULL;
    if (!text)
        return;
    fputs("<h3>", out);
    write_file_name(p, name);
    fputs("</h3>\n<div class=\"scroll\"><table>\n", out);
    const char *c = text;
    int row = 0;
    for (; *c && row <= MAX_TABLE_ROWS; ++row) {
        if (*c == '#') { /* a comment line (a history's key) */
            c += strcspn(c, "\n");
            c += *c == '\n';
            --row;
            continue;
        }
        const char *cell = row == 0 ? "th" : "td";
        fputs("<tr>", out);
        while (*c && *c != '\n' && *c != '\r') {
            fprintf(out, "<%s>", cell);
            if (row == 0)
                write_header_field(p, &c);
            else
                write_csv_field(out, &c);
            fprintf(out, "</%s>", cell);
        }
        fputs("</tr>\n", out);
        c += strspn(c, "\r\n");
    }
    fputs("</table></div>\n", out);
    if (*c) {
        fprintf(out, "<p class=\"note\">The first %d rows; the rest are in", MAX_TABLE_ROWS);
        write_link(p, name);
        fputs(".</p>\n", out);
    }
    free(text);
}

/* The summary tables a run or scene writes, shown in this order; any other CSV of the folder (a
 * distribution's per step, say: many and long) is linked under them. */
static const char *const SHOWN_TABLES[] = {"results.csv", "table1.csv", "indentation.csv",
                                           "history.csv", "k_fit.csv",  "flat_k.csv",
                                           "sweep.csv",   "fig7.csv",   "adhesion_theory.csv"};

static int shown_table(const char *name)
{
    for (size_t k = 0; k < sizeof SHOWN_TABLES / sizeof *SHOWN_TABLES; ++k)
        if (strcmp(name, SHOWN_TABLES[k]) == 0)
            return 1;
    return 0;
}

/* The CSVs not shown, named (linked unless embedded) in one line. */
static int write_other_tables(const page *p, int any)
{
    static const char *const tables[] = {".csv", NULL};
    name_list list;
    int status = list_folder(p->dir, tables, &list), listed = 0;
    for (int k = 0; status == IM_OK && k < list.count; ++k) {
        if (shown_table(list.names[k]))
            continue;
        if (!listed++)
            fputs(any ? "<p class=\"note\">More tables:" : "<h2>Results</h2>\n<p class=\"note\">Tables:", p->out);
        write_link(p, list.names[k]);
    }
    if (listed)
        fputs("</p>\n", p->out);
    free_names(&list);
    return status;
}

static int write_results(const page *p)
{
    char path[PATH_SIZE];
    int any = 0;
    for (size_t k = 0; k < sizeof SHOWN_TABLES / sizeof *SHOWN_TABLES; ++k) {
        if (im_path_join(path, sizeof path, p->dir, SHOWN_TABLES[k]) != IM_OK)
            continue;
        FILE *f = fopen(path, "rb");
        if (!f)
            continue;
        fclose(f);
        if (!any++)
            fputs("<h2>Results</h2>\n", p->out);
        write_table(p, SHOWN_TABLES[k]);
    }
    return write_other_tables(p, any);
}

static void write_record(const page *p, const char *text)
{
    FILE *out = p->out;
    if (!text)
        return;
    fputs("<h2>Run record</h2>\n<p class=\"note\">", out);
    write_link(p, "run.json");
    fputs("</p>\n<pre>", out);
    escape_all(out, text);
    fputs("</pre>\n", out);
}

/* The page's text into p->out: its head, then each part for which files exist. */
static int write_page(const page *p, const char *title, const char *record)
{
    FILE *out = p->out;
    fputs("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
          "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>",
          out);
    escape_all(out, title);
    fprintf(out, "</title>\n<style>%s</style>\n</head>\n<body>\n<h1>", STYLE);
    escape_all(out, title);
    fputs(p->embed ? "</h1>\n<p class=\"note\">Written by indentmap " IM_VERSION
                     "; its images are in this page, which stands alone.</p>\n"
                   : "</h1>\n<p class=\"note\">Written by indentmap " IM_VERSION
                     "; every file is beside this page in the run's folder.</p>\n",
          out);
    long before = ftell(out);
    int status = write_figures(p);
    if (status == IM_OK)
        status = write_frames(p);
    if (status == IM_OK)
        status = write_results(p);
    if (status == IM_OK)
        write_record(p, record);
    if (ftell(out) == before)
        fputs("<p>This folder holds no figures, frames, tables or run record yet.</p>\n", out);
    fputs("</body>\n</html>\n", out);
    return status;
}

int im_viewer_write_with(const char *dir, const char *title, const im_viewer_options *options)
{
    ARG_REQUIRE(dir, "dir");
    ARG_REQUIRE(title, "title");
    ARG_REQUIRE(options, "options");
    char *text = NULL, path[PATH_SIZE];
    size_t size = 0;
    page p = {open_memstream(&text, &size), dir, options->embed_images, NULL};
    if (!p.out)
        return im_fail(IM_ENOMEM, "viewer page %s/index.html: out of memory", dir);
    char *record = im_path_join(path, sizeof path, dir, "run.json") == IM_OK ? read_text(path) : NULL;
    json_t *root = record ? json_text_load(record, 0, NULL) : NULL;
    p.units = json_object_get(json_object_get(root, "units"), "columns");
    int status = write_page(&p, title, record);
    json_decref(root);
    free(record);
    if (fclose(p.out) != 0 || !text) {
        free(text);
        return im_fail(IM_ENOMEM, "viewer page %s/index.html: out of memory", dir);
    }
    if (status == IM_OK)
        status = im_path_join(path, sizeof path, dir, "index.html");
    if (status == IM_OK)
        status = im_write_file_atomic(path, text, size);
    free(text);
    return status;
}

int im_viewer_write(const char *dir, const char *title)
{
    const im_viewer_options options = {0};
    return im_viewer_write_with(dir, title, &options);
}
