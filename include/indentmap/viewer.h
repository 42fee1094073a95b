/* indentmap/viewer.h: a run's viewer page, DIR/index.html, written by every scene run and every
 * `indentmap indent` run over what the run left in its output folder.
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
 *   - results: each of results.csv, table1.csv and history.csv as an HTML table;
 *   - the run record: run.json, verbatim.
 * Text from the files is HTML-escaped. The page is written atomically (io.h).
 *
 * Misuse (status.h): IM_EINVAL for a NULL folder or title.
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

#ifdef __cplusplus
}
#endif

#endif
