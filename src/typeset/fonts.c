#include "typeset/fonts.h"

#include "indentmap/status.h"

#include <cairo-ft.h>
#include <ft2build.h>
#include FT_FREETYPE_H
#include <pthread.h>

static pthread_once_t once = PTHREAD_ONCE_INIT;
static FT_Library library;
static cairo_font_face_t *faces[2];
static const char *failed_file;
static int failed_error;

static cairo_font_face_t *load(const char *path)
{
    FT_Face face;
    int error = FT_New_Face(library, path, 0, &face);
    if (error) {
        failed_file = path;
        failed_error = error;
        return NULL;
    }
    cairo_font_face_t *font = cairo_ft_font_face_create_for_ft_face(face, 0);
    if (cairo_font_face_status(font) != CAIRO_STATUS_SUCCESS) {
        failed_file = path;
        return NULL;
    }
    return font;
}

static void load_fonts(void)
{
    int error = FT_Init_FreeType(&library);
    if (error) {
        failed_file = "(FreeType initialisation)";
        failed_error = error;
        return;
    }
    faces[0] = load(TYPESET_FONT);
    faces[1] = faces[0] ? load(TYPESET_FONT_BOLD) : NULL;
}

int typeset_fonts(cairo_font_face_t **regular, cairo_font_face_t **bold)
{
    pthread_once(&once, load_fonts);
    if (!faces[0] || !faces[1])
        return im_fail(IM_EUNSUPPORTED,
                       "font %s cannot be loaded (FreeType error %d): install the "
                       "DejaVu fonts (Debian: fonts-dejavu-core)",
                       failed_file, failed_error);
    *regular = faces[0];
    *bold = faces[1];
    return IM_OK;
}
