/* The plots a scene can ask for in [output] plots, by name, and the nearest name to a mistyped word. */
#include "scene/names.h"
#include "core/args.h"
#include "indentmap/scene.h"

#include <string.h>

static const char *const PLOT_NAMES[] = {"fig1", "fig2",    "fig3",   "fig5",  "fig6",
                                         "fig7", "density", "sphere", "flat_k"}; /* of the bits 1 << 0, 1 << 1, ... */
enum { PLOT_COUNT = sizeof PLOT_NAMES / sizeof PLOT_NAMES[0] };

const char *im_scene_plot_name(enum im_scene_plot plot)
{
    for (int i = 0; i < PLOT_COUNT; ++i)
        if ((unsigned)plot == 1u << i)
            return PLOT_NAMES[i];
    return NULL;
}

enum im_scene_plot im_scene_plot_parse(const char *name)
{
    ARG_REQUIRE_OR(name, "name", 0);
    for (int i = 0; i < PLOT_COUNT; ++i)
        if (strcmp(name, PLOT_NAMES[i]) == 0)
            return (enum im_scene_plot)(1u << i);
    return (enum im_scene_plot)0;
}

size_t scene_edit_distance(const char *a, const char *b)
{
    size_t la = strlen(a), lb = strlen(b), row[64];
    if (lb >= 64)
        return (size_t)-1;
    for (size_t j = 0; j <= lb; ++j)
        row[j] = j;
    for (size_t i = 1; i <= la; ++i) {
        size_t diagonal = row[0];
        row[0] = i;
        for (size_t j = 1; j <= lb; ++j) {
            size_t above = row[j];
            size_t substitute = diagonal + (a[i - 1] != b[j - 1]);
            size_t best = above + 1 < row[j - 1] + 1 ? above + 1 : row[j - 1] + 1;
            row[j] = substitute < best ? substitute : best;
            diagonal = above;
        }
    }
    return row[lb];
}

const char *scene_suggest_plot(const char *word)
{
    const char *best = NULL;
    size_t best_distance = strlen(word) / 2 + 1;
    for (int i = 0; i < PLOT_COUNT; ++i) {
        size_t distance = scene_edit_distance(word, PLOT_NAMES[i]);
        if (distance < best_distance) {
            best_distance = distance;
            best = PLOT_NAMES[i];
        }
    }
    return best;
}
