/* indentmap/viewer.h: a run's viewer page, DIR/index.html, written by every scene run and every
 * `indentmap indent` run over what the run left in its output folder.
 *
 * Entry points:
 *   im_viewer_write, im_viewer_write_with   DIR/index.html over the files now in DIR
 *
 * The page is self-contained: one HTML file with its style sheet and script inline, images
 * referenced by relative paths, nothing loaded from the network, so it opens from file:// (and
 * keeps working when the folder is moved or copied whole). It shows, in this order, the parts
 * for which files exist:
 *   - figures: every PNG and SVG image in DIR (sorted by name); animations: every GIF; links to
 *     the PDFs and MP4s;
 *   - frames: the images DIR/frames/PREFIX_NNNN.png grouped by PREFIX (contact, height, view3d,
 *     ...), shown side by side, one step at a time, chosen with a slider (and the arrow keys);
 *     steps that a prefix lacks are left blank;
 *   - results: each of results.csv, table1.csv, indentation.csv and history.csv as an HTML table,
 *     numbers shown with 6 significant digits (all of them on hover); a column that run.json's
 *     "units" block names in its "columns" object ({"load": "N", ...}) has its unit under its name;
 *   - the run record: run.json, verbatim.
 * Text from the files is HTML-escaped. The page is written atomically (io.h).
 *
 * With embed_images the page carries every image it shows (figures, animations, frames) as a base64
 * data URI, so that it travels as one file (about 4/3 of its images' bytes); the PDFs, MP4s, CSV files
 * and run.json it would link to are named, not linked.
 *
 * Misuse (status.h): IM_EINVAL for a NULL folder, title or options.
 * Threads: thread-safe on distinct folders; the page reflects the files there when it is written
 * (write it after the run's other files).
 */
#ifndef INDENTMAP_VIEWER_H
#define INDENTMAP_VIEWER_H

#ifdef __cplusplus
extern "C" {
#endif

/* Writes DIR/index.html for the files now in DIR. title (UTF-8) heads the page. Errors: IM_EIO
 * when DIR cannot be read or the page cannot be written (naming the path), IM_ENOMEM. A folder
 * with none of the files above still gets a page that says so. */
int im_viewer_write(const char *dir, const char *title);

typedef struct im_viewer_options {
    int embed_images; /* 1: images as data URIs, the page one file; 0 (default): relative paths */
} im_viewer_options;

/* The same with options. Also IM_EIO naming an image that cannot be read whole to embed (or is over
 * 256 MiB). */
int im_viewer_write_with(const char *dir, const char *title, const im_viewer_options *options);

#ifdef __cplusplus
}
#endif

#endif
