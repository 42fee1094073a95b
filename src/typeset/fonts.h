/* typeset/: the typesetting shared by figure/ (maps) and plot/ (line plots); neither includes the
 * other's private headers.
 *
 * DejaVu Sans regular and bold as cairo font faces, loaded with FreeType from the font files
 * (no fontconfig). Loaded once per process and kept for its lifetime. */
#ifndef INDENTMAP_TYPESET_FONTS_H
#define INDENTMAP_TYPESET_FONTS_H

#include <cairo.h>

#ifndef IM_FONT_DIR /* the folder is a build setting: cmake -DIM_FONT_DIR=... */
#define IM_FONT_DIR "/usr/share/fonts/truetype/dejavu"
#endif
#define TYPESET_FONT IM_FONT_DIR "/DejaVuSans.ttf"
#define TYPESET_FONT_BOLD IM_FONT_DIR "/DejaVuSans-Bold.ttf"

/* IM_EUNSUPPORTED naming the file when a font cannot be loaded. The faces are borrowed. */
int typeset_fonts(cairo_font_face_t **regular, cairo_font_face_t **bold);

#endif
