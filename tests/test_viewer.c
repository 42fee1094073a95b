/* The viewer page (viewer.h): its structure, then the page itself in headless Chromium: it loads
 * without console messages, the slider changes the frames, and a screenshot shows the three frame
 * panels side by side. The Chromium tests are skipped (exit 77 when nothing else failed) when no
 * chromium is installed, unless IM_REQUIRE_CHROMIUM=1. */
#include "support.h"

#include "indentmap/io.h"
#include "indentmap/status.h"
#include "indentmap/viewer.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static int skipped;

/* Frame colours: one per prefix, so that a screenshot tells the panels apart. */
static const uint8_t CONTACT[3] = {220, 30, 30}, HEIGHT[3] = {30, 160, 30}, VIEW[3] = {30, 30, 220};

static void solid_png(const char *path, int width, int height, const uint8_t rgb[3])
{
    uint8_t *pixels = malloc((size_t)width * height * 3);
    for (int i = 0; i < width * height; ++i)
        memcpy(pixels + 3 * i, rgb, 3);
    assert_int_equal(im_png_write(path, pixels, width, height, 3, (size_t)width * 3, NULL), IM_OK);
    free(pixels);
}

static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        fail_msg("cannot read %s", path);
    char *text = calloc(1, 1 << 22);
    size_t length = fread(text, 1, (1 << 22) - 1, f);
    text[length] = '\0';
    fclose(f);
    return text;
}

/* A run folder: a figure, 4 steps of contact and height frames, 3 of view3d, a results table
 * with markup and a quoted field, a run record with a script tag. */
static const char *make_run(void)
{
    static char dir[600];
    char path[700];
    snprintf(dir, sizeof dir, "%s/run", test_temp_dir());
    snprintf(path, sizeof path, "%s/frames", dir);
    assert_int_equal(im_make_directories(path), IM_OK);
    snprintf(path, sizeof path, "%s/figure.png", dir);
    solid_png(path, 40, 20, (const uint8_t[3]){128, 128, 128});
    for (int step = 0; step < 4; ++step) {
        snprintf(path, sizeof path, "%s/frames/contact_%04d.png", dir, step);
        solid_png(path, 100, 100, CONTACT);
        snprintf(path, sizeof path, "%s/frames/height_%04d.png", dir, step);
        solid_png(path, 100, 100, HEIGHT);
        snprintf(path, sizeof path, "%s/frames/view3d_%04d.png", dir, step);
        if (step < 3)
            solid_png(path, 192, 108, VIEW);
    }
    const char results[] = "family,slope,note\n0,0.08,\"a, <b>bold</b> \"\"claim\"\"\"\n1,0.16,plain\n";
    snprintf(path, sizeof path, "%s/results.csv", dir);
    test_write_bytes(path, results, strlen(results));
    const char record[] = "{\"scene\": \"</pre><script>alert(1)</script>\"}\n";
    snprintf(path, sizeof path, "%s/run.json", dir);
    test_write_bytes(path, record, strlen(record));
    assert_int_equal(im_viewer_write(dir, "run <1>"), IM_OK);
    return dir;
}

static void test_page_structure(void **state)
{
    (void)state;
    const char *dir = make_run();
    char path[700];
    snprintf(path, sizeof path, "%s/index.html", dir);
    char *page = slurp(path);
    assert_non_null(strstr(page, "<title>run &lt;1&gt;</title>"));
    assert_non_null(strstr(page, "<img src=\"figure.png\""));
    /* frames: three panels in the known order, view3d missing its last step */
    char *contact = strstr(page, "id=\"frame-contact\""), *height = strstr(page, "id=\"frame-height\""),
         *view = strstr(page, "id=\"frame-view3d\"");
    assert_true(contact && height && view && contact < height && height < view);
    /* each panel's share of the row is its aspect ratio, its width capped at the panels' least height
     * (100 pixels): none is blown up beyond its image */
    assert_non_null(strstr(page, "<figure style=\"flex:1000 1 0;max-width:100px\"><img id=\"frame-contact\""));
    assert_non_null(strstr(page, "<figure style=\"flex:1777 1 0;max-width:177px\"><img id=\"frame-view3d\""));
    assert_non_null(strstr(page, "max=\"3\""));
    assert_non_null(strstr(page, "\"frames/view3d_0002.png\",null]"));
    /* tables and record escaped, the quoted field whole */
    assert_non_null(strstr(page, "<td>a, &lt;b&gt;bold&lt;/b&gt; &quot;claim&quot;</td>"));
    assert_non_null(strstr(page, "&lt;/pre&gt;&lt;script&gt;alert(1)&lt;/script&gt;"));
    assert_null(strstr(page, "<script>alert"));
    /* nothing from the network */
    assert_null(strstr(page, "http:"));
    assert_null(strstr(page, "https:"));
    assert_null(strstr(page, "src=\"//"));
    free(page);
}

static void test_empty_folder_and_unwritable(void **state)
{
    (void)state;
    char dir[600], path[700];
    snprintf(dir, sizeof dir, "%s/empty", test_temp_dir());
    assert_int_equal(im_make_directories(dir), IM_OK);
    assert_int_equal(im_viewer_write(dir, "empty"), IM_OK);
    snprintf(path, sizeof path, "%s/index.html", dir);
    char *page = slurp(path);
    assert_non_null(strstr(page, "holds no figures, frames, tables or run record yet"));
    free(page);
    snprintf(dir, sizeof dir, "%s/missing/folder", test_temp_dir());
    assert_int_equal(im_viewer_write(dir, "nowhere"), IM_EIO);
}

/* Decodes the base64 text at s (up to its closing quote) into out; its length. */
static size_t base64_decode(const char *s, unsigned char *out)
{
    size_t length = 0;
    unsigned long bits = 0;
    int count = 0;
    for (; *s && *s != '"' && *s != '='; ++s) {
        const char *alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        const char *at = strchr(alphabet, *s);
        assert_non_null(at);
        bits = bits << 6 | (unsigned long)(at - alphabet);
        if (++count == 4) {
            out[length++] = (unsigned char)(bits >> 16), out[length++] = (unsigned char)(bits >> 8);
            out[length++] = (unsigned char)bits, bits = 0, count = 0;
        }
    }
    if (count == 3)
        out[length++] = (unsigned char)(bits >> 10), out[length++] = (unsigned char)(bits >> 2);
    else if (count == 2)
        out[length++] = (unsigned char)(bits >> 4);
    return length;
}

static void test_embedded_page_is_one_file(void **state)
{
    (void)state;
    const char *dir = make_run();
    char path[700];
    const im_viewer_options options = {.embed_images = 1};
    assert_int_equal(im_viewer_write_with(dir, "embedded", &options), IM_OK);
    snprintf(path, sizeof path, "%s/index.html", dir);
    char *page = slurp(path);
    /* no image, frame or file referenced by a relative path */
    assert_null(strstr(page, "src=\"figure.png\""));
    assert_null(strstr(page, "frames/"));
    assert_null(strstr(page, "href="));
    /* the figure's data URI decodes to the file's bytes */
    const char *uri = strstr(page, "<img src=\"data:image/png;base64,");
    assert_non_null(uri);
    snprintf(path, sizeof path, "%s/figure.png", dir);
    char *file = slurp(path);
    FILE *f = fopen(path, "rb");
    fseek(f, 0, SEEK_END);
    size_t size = (size_t)ftell(f);
    fclose(f);
    unsigned char *decoded = malloc(strlen(uri));
    size_t length = base64_decode(uri + strlen("<img src=\"data:image/png;base64,"), decoded);
    assert_int_equal(length, size);
    assert_memory_equal(decoded, file, size);
    /* every frame step is a data URI, the missing one null */
    assert_non_null(strstr(page, "\"data:image/png;base64,"));
    assert_non_null(strstr(page, ",null]"));
    free(decoded);
    free(file);
    free(page);
}

/* The encoder's padding: files of 1, 2 and 3 bytes mod 3 decode to themselves. */
static void test_embedded_padding(void **state)
{
    (void)state;
    char dir[600], path[700];
    snprintf(dir, sizeof dir, "%s/padding", test_temp_dir());
    assert_int_equal(im_make_directories(dir), IM_OK);
    const char *const contents[3] = {"a", "ab", "abc"};
    const im_viewer_options options = {.embed_images = 1};
    for (int k = 0; k < 3; ++k) {
        snprintf(path, sizeof path, "%s/x.png", dir);
        test_write_bytes(path, contents[k], strlen(contents[k]));
        assert_int_equal(im_viewer_write_with(dir, "padding", &options), IM_OK);
        snprintf(path, sizeof path, "%s/index.html", dir);
        char *page = slurp(path);
        const char *uri = strstr(page, "base64,");
        assert_non_null(uri);
        unsigned char decoded[8];
        assert_int_equal(base64_decode(uri + strlen("base64,"), decoded), strlen(contents[k]));
        assert_memory_equal(decoded, contents[k], strlen(contents[k]));
        free(page);
    }
}

/* run.json's units.columns head the tables: a unit under each name it knows, none under others. */
/* The summary tables a run writes are shown, each under a link to its file, the scenes' and adhesion's
 * among them (k_fit.csv, adhesion_theory.csv were missing: redteam3 R5); other CSVs (a distribution's
 * per step) are linked, not shown. */
static void test_tables_shown_and_linked(void **state)
{
    (void)state;
    char dir[600], path[700];
    snprintf(dir, sizeof dir, "%s/tables", test_temp_dir());
    assert_int_equal(im_make_directories(dir), IM_OK);
    const char *const names[] = {"history.csv", "k_fit.csv", "adhesion_theory.csv", "step_0001_gaps.csv"};
    for (int k = 0; k < 4; ++k) {
        snprintf(path, sizeof path, "%s/%s", dir, names[k]);
        test_write_bytes(path, "a,b\n1,2\n", 8);
    }
    assert_int_equal(im_viewer_write(dir, "tables"), IM_OK);
    snprintf(path, sizeof path, "%s/index.html", dir);
    char *page = slurp(path);
    for (int k = 0; k < 3; ++k) {
        char shown[200];
        snprintf(shown, sizeof shown, "<h3><a href=\"%s\">%s</a></h3>", names[k], names[k]);
        if (!strstr(page, shown))
            fail_msg("%s is not shown under its link", names[k]);
    }
    const char *more = strstr(page, "More tables: <a href=\"step_0001_gaps.csv\">step_0001_gaps.csv</a></p>");
    assert_non_null(more);
    assert_null(strstr(page, "<h3><a href=\"step_0001_gaps.csv\""));
    free(page);
}

static void test_table_headers_carry_units(void **state)
{
    (void)state;
    char dir[600], path[700];
    snprintf(dir, sizeof dir, "%s/units", test_temp_dir());
    assert_int_equal(im_make_directories(dir), IM_OK);
    const char history[] = "step,load,note\n1,2.5,x\n";
    snprintf(path, sizeof path, "%s/history.csv", dir);
    test_write_bytes(path, history, strlen(history));
    const char record[] = "{\"units\": {\"load\": \"N\", \"columns\": {\"step\": \"1\", \"load\": \"N <b>\"}}}\n";
    snprintf(path, sizeof path, "%s/run.json", dir);
    test_write_bytes(path, record, strlen(record));
    assert_int_equal(im_viewer_write(dir, "units"), IM_OK);
    snprintf(path, sizeof path, "%s/index.html", dir);
    char *page = slurp(path);
    assert_non_null(strstr(page, "<th>step<br><span class=\"unit\">(1)</span></th>"));
    assert_non_null(strstr(page, "<th>load<br><span class=\"unit\">(N &lt;b&gt;)</span></th>"));
    assert_non_null(strstr(page, "<th>note</th>"));
    free(page);
}

/* ---- in Chromium ---- */

static const char *chromium(void)
{
    static const char *const candidates[] = {"/usr/bin/chromium", "/usr/bin/chromium-browser"};
    for (int i = 0; i < 2; ++i)
        if (access(candidates[i], X_OK) == 0)
            return candidates[i];
    return NULL;
}

#define REQUIRE_CHROMIUM()                                                                                           \
    do {                                                                                                             \
        if (!chromium()) {                                                                                           \
            const char *required = getenv("IM_REQUIRE_CHROMIUM");                                                    \
            if (required && strcmp(required, "1") == 0)                                                              \
                fail_msg("no chromium (IM_REQUIRE_CHROMIUM=1)");                                                     \
            skipped = 1;                                                                                             \
            skip();                                                                                                  \
        }                                                                                                            \
    } while (0)

/* Runs headless Chromium on a file with the arguments `what` (e.g. --dump-dom), stdout to out and
 * stderr (with the console's messages) to log. */
static void run_chromium(const char *what, const char *page, const char *out, const char *log)
{
    static int profile;
    char command[4096];
    snprintf(command, sizeof command,
             "timeout 120 %s --headless --no-sandbox --disable-gpu --no-first-run --disable-background-networking "
             "--disable-component-update --disable-sync --user-data-dir=%s/profile-%d --enable-logging=stderr "
             "--v=0 --allow-file-access-from-files --window-size=1200,900 %s 'file://%s' >'%s' 2>'%s'",
             chromium(), test_temp_dir(), profile++, what, page, out, log);
    if (system(command) != 0)
        fail_msg("chromium failed: %s (see %s)", command, log);
}

static int has_console_message(const char *log)
{
    char *text = slurp(log);
    int found = strstr(text, ":CONSOLE") != NULL;
    free(text);
    return found;
}

static void test_page_loads_without_console_messages(void **state)
{
    (void)state;
    REQUIRE_CHROMIUM();
    const char *dir = make_run();
    char page[700], out[700], log[700];
    snprintf(page, sizeof page, "%s/index.html", dir);
    snprintf(out, sizeof out, "%s/dom.html", test_temp_dir());
    snprintf(log, sizeof log, "%s/console.log", test_temp_dir());
    /* The check can fail: a page with a script error and a missing image shows up in the log. */
    char bad[700];
    snprintf(bad, sizeof bad, "%s/bad.html", dir);
    const char bad_page[] = "<!DOCTYPE html><img src=\"missing.png\"><script>no_such_function();</script>\n";
    test_write_bytes(bad, bad_page, strlen(bad_page));
    run_chromium("--dump-dom", bad, out, log);
    assert_true(has_console_message(log));
    run_chromium("--dump-dom", page, out, log);
    if (has_console_message(log)) {
        char *text = slurp(log);
        fail_msg("console messages from %s:\n%s", page, text);
    }
    char *dom = slurp(out);
    assert_non_null(strstr(dom, "step 1 of 4")); /* the script ran */
    free(dom);
}

/* A page that loads the viewer in a frame, moves its slider and records what the frames show. */
static void test_slider_changes_the_frame(void **state)
{
    (void)state;
    REQUIRE_CHROMIUM();
    make_run();
    char harness[700], out[700], log[700];
    snprintf(harness, sizeof harness, "%s/harness.html", test_temp_dir());
    snprintf(out, sizeof out, "%s/harness_dom.html", test_temp_dir());
    snprintf(log, sizeof log, "%s/harness.log", test_temp_dir());
    const char text[] =
        "<!DOCTYPE html><body><iframe id=\"f\" src=\"run/index.html\"></iframe><script>\n"
        "var f=document.getElementById('f');f.onload=function(){var d=f.contentDocument;\n"
        "var s=d.getElementById('frame-slider');var r=[];\n"
        "function look(){r.push(d.getElementById('frame-contact').getAttribute('src')+' '+\n"
        " d.getElementById('frame-view3d').getAttribute('src')+' "
        "'+d.getElementById('frame-view3d').style.visibility+' '+\n"
        " d.getElementById('frame-label').textContent);}\n"
        "look();[2,3].forEach(function(i){s.value=i;s.dispatchEvent(new Event('input'));look();});\n"
        "var "
        "p=document.createElement('pre');p.id='result';p.textContent=r.join('|');document.body.appendChild(p);};\n"
        "</script></body>\n";
    test_write_bytes(harness, text, strlen(text));
    run_chromium("--dump-dom --virtual-time-budget=5000", harness, out, log);
    char *dom = slurp(out);
    const char *expected = "frames/contact_0000.png frames/view3d_0000.png visible step 1 of 4|"
                           "frames/contact_0002.png frames/view3d_0002.png visible step 3 of 4|"
                           "frames/contact_0003.png frames/view3d_0002.png hidden step 4 of 4";
    if (!strstr(dom, expected))
        fail_msg("the slider did not change the frames as expected:\n%s", dom);
    free(dom);
}

/* The bounding box of the screenshot's pixels within 12 levels of rgb. */
static int find_colour(const uint8_t *pixels, int width, int height, int channels, const uint8_t rgb[3], int box[4])
{
    int count = 0;
    box[0] = box[1] = 1 << 30;
    box[2] = box[3] = -1;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const uint8_t *p = pixels + ((size_t)y * width + x) * channels;
            if (abs(p[0] - rgb[0]) > 12 || abs(p[1] - rgb[1]) > 12 || abs(p[2] - rgb[2]) > 12)
                continue;
            ++count;
            box[0] = x < box[0] ? x : box[0];
            box[1] = y < box[1] ? y : box[1];
            box[2] = x > box[2] ? x : box[2];
            box[3] = y > box[3] ? y : box[3];
        }
    return count;
}

static void test_screenshot_shows_the_panels(void **state)
{
    (void)state;
    REQUIRE_CHROMIUM();
    const char *dir = make_run();
    char page[700], shot[700], argument[800], out[700], log[700];
    snprintf(page, sizeof page, "%s/index.html", dir);
    snprintf(shot, sizeof shot, "%s/shot.png", test_temp_dir());
    snprintf(argument, sizeof argument, "--screenshot='%s'", shot);
    snprintf(out, sizeof out, "%s/shot.out", test_temp_dir());
    snprintf(log, sizeof log, "%s/shot.log", test_temp_dir());
    run_chromium(argument, page, out, log);
    uint8_t *pixels;
    int width, height, channels, boxes[3][4];
    assert_int_equal(im_png_read(shot, &pixels, &width, &height, &channels), IM_OK);
    const uint8_t *colours[3] = {CONTACT, HEIGHT, VIEW};
    for (int k = 0; k < 3; ++k)
        if (find_colour(pixels, width, height, channels, colours[k], boxes[k]) < 400)
            fail_msg("panel %d (colour %d, %d, %d) is not in the screenshot", k, colours[k][0], colours[k][1],
                     colours[k][2]);
    /* side by side, left to right, at one height (100 x 100, 100 x 100 and 192 x 108 images), each
     * keeping its aspect ratio */
    for (int k = 0; k < 2; ++k) {
        assert_true(boxes[k][2] < boxes[k + 1][0]);
        assert_true(abs(boxes[k][1] - boxes[k + 1][1]) <= 2);
        assert_true(abs(boxes[k][3] - boxes[k + 1][3]) <= 2);
    }
    double view_aspect = (boxes[2][2] - boxes[2][0] + 1.0) / (boxes[2][3] - boxes[2][1] + 1.0);
    assert_true(fabs(view_aspect - 192.0 / 108.0) < 0.03 * view_aspect);
    free(pixels);
}

/* `indent --frames` on a small grid: its page shows history.png loaded and a slider that moves the
 * contact frames, in Chromium. Skipped without chromium, or without OpenGL (the run then fails to
 * draw its frames and says so) unless IM_REQUIRE_GL=1. */
static void test_indent_page_in_chromium(void **state)
{
    (void)state;
    REQUIRE_CHROMIUM();
    const char *cli = getenv("IM_CLI");
    if (!cli)
        fail_msg("IM_CLI names no program");
    char command[2048], log[700], harness[700], out[700], chrome_log[700];
    snprintf(log, sizeof log, "%s/indent.log", test_temp_dir());
    snprintf(command, sizeof command,
             "'%s' indent --smooth --n 64 --alpha 70 --load 40:160:3 --frames --out '%s/ind' >'%s' 2>&1", cli,
             test_temp_dir(), log);
    if (system(command) != 0) {
        char *text = slurp(log);
        const char *required = getenv("IM_REQUIRE_GL");
        if (strstr(text, "no OpenGL 3.3 core context") && !(required && strcmp(required, "1") == 0)) {
            free(text);
            skipped = 1;
            skip();
        }
        fail_msg("%s failed:\n%s", command, text);
    }
    snprintf(harness, sizeof harness, "%s/indent_harness.html", test_temp_dir());
    snprintf(out, sizeof out, "%s/indent_dom.html", test_temp_dir());
    snprintf(chrome_log, sizeof chrome_log, "%s/indent_harness.log", test_temp_dir());
    const char text[] =
        "<!DOCTYPE html><body><iframe id=\"f\" src=\"ind/index.html\" style=\"width:1600px;height:900px\"></iframe>\n"
        "<script>\n"
        "var f=document.getElementById('f');f.onload=function(){var d=f.contentDocument;\n"
        "var h=d.querySelector('img[alt=\"history.png\"]');var s=d.getElementById('frame-slider');var r=[];\n"
        "r.push(h&&h.complete&&h.naturalWidth>0?'history loaded':'no history');\n"
        "var c0=d.getElementById('frame-contact');var w=c0.clientWidth;\n" /* its pixels, without the border */
        "r.push(w>0&&w<=c0.naturalWidth?'panel at most its width':'panel '+w+' px wide, its image "
        "'+c0.naturalWidth);\n"
        "function look(){var c=d.getElementById('frame-contact');r.push(c.getAttribute('src')+' '+\n"
        " (c.complete&&c.naturalWidth>0?'loaded':'not loaded')+' '+d.getElementById('frame-label').textContent);}\n"
        "look();s.value=2;s.dispatchEvent(new Event('input'));\n"
        "d.getElementById('frame-contact').onload=function(){look();var p=document.createElement('pre');\n"
        "p.id='result';p.textContent=r.join('|');document.body.appendChild(p);};};\n"
        "</script></body>\n";
    test_write_bytes(harness, text, strlen(text));
    run_chromium("--dump-dom --virtual-time-budget=5000", harness, out, chrome_log);
    char *dom = slurp(out);
    const char *expected = "history loaded|panel at most its width|frames/contact_0000.png loaded step 1 of 3|"
                           "frames/contact_0002.png loaded step 3 of 3";
    if (!strstr(dom, expected))
        fail_msg("the indent page's history figure or slider did not work as expected:\n%s", dom);
    free(dom);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_page_structure),
        cmocka_unit_test(test_empty_folder_and_unwritable),
        cmocka_unit_test(test_embedded_page_is_one_file),
        cmocka_unit_test(test_embedded_padding),
        cmocka_unit_test(test_table_headers_carry_units),
        cmocka_unit_test(test_tables_shown_and_linked),
        cmocka_unit_test(test_page_loads_without_console_messages),
        cmocka_unit_test(test_slider_changes_the_frame),
        cmocka_unit_test(test_screenshot_shows_the_panels),
        cmocka_unit_test(test_indent_page_in_chromium),
    };
    int failed = cmocka_run_group_tests(tests, NULL, NULL);
    return failed ? failed : skipped ? 77 : 0; /* 77: ctest's SKIP_RETURN_CODE */
}
