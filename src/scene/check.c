/* The consistency of a scene's keys with each other, checked once every key is parsed (a message
 * citing the line of the key at fault). */
#include "scene/check.h"
#include "scene/contents.h"
#include "front/front.h"
#include "indentmap/status.h"
#include "scene/keys.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

/* The line of [section] key in the scene, 0 if it was not given. */
static int key_line(const scene_given *given, const char *section, const char *key)
{
    int index = scene_key_index(section, key);
    return index < 0 ? 0 : given->key_lines[index];
}

/* A scene over surface files: they are the ensemble (seeds[i] = i picks file i) and each has its
 * own h'rms, measured when the scene runs; `slopes` or `seeds` beside them would contradict that
 * (reliability finding 4: `slopes` labelled the file and chose the theory, `seeds = 1:3` solved
 * one file three times), and the generator's parameters would be taken without effect. Returns the
 * line at fault, 0 if none. */
static int check_files(const scene_given *given)
{
    im_scene *scene = given->scene;
    int slopes = key_line(given, "surfaces", "slopes"), seeds = key_line(given, "surfaces", "seeds");
    int file = key_line(given, "surfaces", "file");
    if (slopes || seeds) {
        im_fail(IM_EFORMAT, "%s beside `file` (line %d): %s", slopes ? "slopes" : "seeds", file,
                slopes ? "a file's h'rms is measured from the file, not given; remove `slopes`"
                       : "the files listed in `file` are the ensemble, and seeds would only solve the "
                         "same file again; remove `seeds`");
        return slopes ? slopes : seeds;
    }
    static const char *const GENERATOR_KEYS[] = {"hurst", "lambda_s", "lambda_r", "lambda_0", "slope_definition"};
    for (size_t k = 0; k < sizeof GENERATOR_KEYS / sizeof *GENERATOR_KEYS; ++k) {
        int line = key_line(given, "surfaces", GENERATOR_KEYS[k]);
        if (line) { /* it was taken without effect */
            im_fail(IM_EFORMAT,
                    "%s beside `file` (line %d): it sets how surfaces are generated, and the surfaces are the "
                    "files (their h'rms is measured as the solve and their sidecars say); remove `%s`",
                    GENERATOR_KEYS[k], file, GENERATOR_KEYS[k]);
            return line;
        }
    }
    int count = 1;
    for (const char *c = scene->surface_file; *c; ++c)
        count += *c == ',';
    char path[IM_SCENE_PATH];
    for (int i = 0; i < count; ++i) {
        if (i >= IM_SCENE_MAX_FAMILIES || im_scene_file_path(scene, i, path, sizeof path) != IM_OK) {
            im_fail(IM_EFORMAT,
                    "file: expected a comma-separated list of at most %d "
                    "non-empty paths",
                    IM_SCENE_MAX_FAMILIES);
            return file;
        }
    }
    scene->file_count = count;
    scene->family_count = 1;
    scene->slopes[0] = NAN; /* measured when the scene runs */
    scene->seed_count = count;
    for (int i = 0; i < count; ++i)
        scene->seeds[i] = (uint64_t)i;
    return 0;
}

/* A key the punch does not have: a cone's radius (indent refuses --radius with a cone alike). */
static int check_punch_keys(const scene_given *given)
{
    const im_scene *scene = given->scene;
    int radius = key_line(given, "punch", "radius");
    if (radius && (scene->punch == IM_PUNCH_CONE || scene->punch == IM_PUNCH_PROFILE)) {
        im_fail(IM_EFORMAT,
                "radius applies to shape = sphere or flat; a %s's shape is "
                "its %s",
                im_punch_name(scene->punch), scene->punch == IM_PUNCH_CONE ? "alpha" : "profile");
        return radius;
    }
    return 0;
}

/* What a periodic scene cannot take, each key with its section and why: all is solved at a mean pressure
 * on the whole cell, where there is no smooth contact on a half-space (its area N*, circle or theory).
 * Its contact panels and distributions are taken at every step instead (periodic_maps.c). */
static const struct {
    const char *section, *key;
    size_t flag; /* offsetof the yes/no it sets (refused when yes), 0: refused whenever given */
    const char *why;
} PERIODIC_REFUSED[] = {
    {"loading", "load_star", 0,
     "N* = A(N) / delta^2 is a smooth punch's contact area on a half-space, which the "
     "periodic cell does not have"},
    {"output", "frames", offsetof(im_scene, frames),
     "the frames are a history of their own up to load_star N*; a periodic scene draws the contact map of "
     "every step of its histories with contact_panels = yes"},
    {"output", "table", offsetof(im_scene, table), "the table compares A/A_cone at load_star N* with eq. (12)"},
};

/* The plots a periodic scene draws: the surfaces' own (fig3) and k's flat contacts (flat_k); the others
 * set a punch's contact on a half-space against its theory (Love's, Hertz's, eq. (12), gamma(r/a)). */
static const unsigned PERIODIC_PLOTS = IM_SCENE_PLOT_FIG3 | IM_SCENE_PLOT_FLAT_K;

/* A plot a periodic scene cannot draw, NULL if none. */
static const char *periodic_refused_plot(const im_scene *scene)
{
    for (unsigned bit = 1; im_scene_plot_name((enum im_scene_plot)bit); bit <<= 1)
        if ((scene->plots & bit) && !(bit & PERIODIC_PLOTS))
            return im_scene_plot_name((enum im_scene_plot)bit);
    return NULL;
}

/* [punch] periodic: sets which punch presses the cell (the rigid flat unless shape is given) and load
 * control, and refuses what does not apply. Returns the line at fault, 0 if none. */
static int check_periodic(const scene_given *given)
{
    im_scene *scene = given->scene;
    if (!scene->periodic)
        return 0;
    const int shape = key_line(given, "punch", "shape");
    scene->periodic = shape ? IM_SCENE_PERIODIC_PUNCH : IM_SCENE_PERIODIC_FLAT;
    const int control = key_line(given, "loading", "control");
    if (control && scene->control != IM_CONTROL_MEAN_GAP) {
        im_fail(IM_EFORMAT, "[loading] control beside [punch] periodic: a periodic scene's "
                            "steps are mean pressures p_m (units of E*), or mean gaps with control = mean_gap");
        return control;
    }
    if (!control)
        scene->control = IM_CONTROL_LOAD; /* mean pressures */
    for (size_t i = 0; i < sizeof PERIODIC_REFUSED / sizeof *PERIODIC_REFUSED; ++i) {
        const int line = key_line(given, PERIODIC_REFUSED[i].section, PERIODIC_REFUSED[i].key);
        const size_t flag = PERIODIC_REFUSED[i].flag;
        if (line && (!flag || *(const int *)((const char *)scene + flag))) {
            im_fail(IM_EFORMAT, "[%s] %s beside [punch] periodic: %s", PERIODIC_REFUSED[i].section,
                    PERIODIC_REFUSED[i].key, PERIODIC_REFUSED[i].why);
            return line;
        }
    }
    const char *const punch_keys[] = {"alpha", "radius", "profile"};
    for (int i = 0; !shape && i < 3; ++i)
        if (key_line(given, "punch", punch_keys[i])) {
            im_fail(IM_EFORMAT,
                    "[punch] %s beside periodic without shape: a rigid flat "
                    "is pressed on the whole cell, which has no %s; give shape for a punch repeated with the "
                    "cell",
                    punch_keys[i], punch_keys[i]);
            return key_line(given, "punch", punch_keys[i]);
        }
    const char *plot = periodic_refused_plot(scene);
    if (plot) {
        im_fail(IM_EFORMAT,
                "plots = %s beside [punch] periodic: it sets a punch's "
                "contact on a half-space against its smooth theory; a periodic scene draws fig3 and flat_k",
                plot);
        return key_line(given, "output", "plots");
    }
    if (scene->step_count < 1) {
        im_fail(IM_EFORMAT, "[punch] periodic needs [loading] steps: the mean "
                            "pressures p_m (units of E*) of each surface's history");
        return key_line(given, "punch", "periodic");
    }
    return 0;
}

/* Sweep lists that a scene cannot run: a list of angles for another punch, a list of generator
 * parameters beside surface files. Returns the line at fault, 0 if none. */
static int check_sweeps(const scene_given *given)
{
    const im_scene *scene = given->scene;
    if (scene->alpha_count > 1 && scene->punch != IM_PUNCH_CONE) {
        im_fail(IM_EFORMAT, "alpha: a list of angles sweeps a cone's half-angle; "
                            "[punch] shape is not cone");
        return key_line(given, "punch", "alpha");
    }
    int points = 1, last = 0;
    const char *keys[][2] = {{"punch", "alpha"}, {"surfaces", "hurst"}, {"surfaces", "lambda_s"}};
    const int counts[] = {scene->alpha_count, scene->hurst_count, scene->lambda_s_count};
    for (int i = 0; i < 3; ++i) {
        points *= counts[i] > 1 ? counts[i] : 1;
        int line = key_line(given, keys[i][0], keys[i][1]);
        last = line > last ? line : last;
    }
    if (points > IM_SCENE_MAX_SWEEP_POINTS) {
        im_fail(IM_EFORMAT,
                "the lists of alpha, hurst and lambda_s make %d sweep "
                "points: expected at most %d",
                points, IM_SCENE_MAX_SWEEP_POINTS);
        return last;
    }
    int hurst = scene->hurst_count > 1 ? key_line(given, "surfaces", "hurst") : 0;
    int lambda_s = scene->lambda_s_count > 1 ? key_line(given, "surfaces", "lambda_s") : 0;
    if (scene->surface_file[0] && (hurst || lambda_s)) {
        im_fail(IM_EFORMAT,
                "%s: a list sweeps the generated surfaces' parameter, but "
                "the surfaces are the files of `file`",
                hurst ? "hurst" : "lambda_s");
        return hurst ? hurst : lambda_s;
    }
    return 0;
}

/* The largest lambda_s of a sweep (the scalar when there is no list). */
static double largest_lambda_s(const im_scene *scene)
{
    double largest = scene->surface.lambda_s;
    for (int i = 0; i < scene->lambda_s_count; ++i)
        largest = fmax(largest, scene->lambda_ss[i]);
    return largest;
}

/* The line of the first [adhesion] key given, 0 if none. */
static int adhesion_line(const scene_given *given)
{
    const char *keys[] = {"work", "range", "law", "zone"};
    for (int i = 0; i < 4; ++i)
        if (key_line(given, "adhesion", keys[i]))
            return key_line(given, "adhesion", keys[i]);
    return 0;
}

/* What a scene that gives [adhesion] cannot take, NULL if nothing. */
static const char *adhesion_conflict(const im_scene *scene)
{
    if (scene->adhesion_zone > 0 && !(scene->adhesion_work > 0) && !(scene->adhesion_range > 0))
        return "[adhesion] zone widens the zone of the law's work and range: expected both";
    if (!(scene->adhesion_work > 0) || !(scene->adhesion_range > 0))
        return "[adhesion] work and range go together: expected both";
    if (scene->adhesion_zone > 0 && scene->adhesion_law != IM_ADHESION_MAUGIS_DUGDALE)
        return "[adhesion] zone widens the Maugis-Dugdale law's zone: expected law = maugis-dugdale (the exponential "
               "law has no Dugdale zone)";
    if (scene->plots & IM_SCENE_PLOT_FLAT_K)
        return "[adhesion] with plots = flat_k: its flat panels are solved at mean pressures, which an adhesive "
               "cell does not take";
    if (scene->periodic) /* as indent --periodic: mean pressures or mean gaps; its panels and distributions are
                            taken at every step */
        return NULL;
    if (scene->contact_panels || scene->frames || scene->table || scene->distributions)
        return "[adhesion] with [output] contact_panels, frames, table or distributions: those are solved under "
               "load control at load_star, which an adhesive contact does not take (its histories, plots = fig5, "
               "fig6, fig7 or sphere, do)";
    if (scene->plots & (IM_SCENE_PLOT_FIG7 | IM_SCENE_PLOT_SPHERE))
        return "[adhesion] with plots = fig7 or sphere: they set repulsive contact against N* on log axes, which a "
               "pulled (negative) load leaves (fig5 and fig6 draw adhesive histories)";
    return NULL;
}

/* [adhesion]'s consistency: the message (im_fail) and the line of the first [adhesion] key, 0 if
 * consistent or not given. */
static int check_adhesion(const scene_given *given)
{
    const int line = adhesion_line(given);
    const char *conflict = line ? adhesion_conflict(given->scene) : NULL;
    if (!conflict)
        return 0;
    im_fail(IM_EFORMAT, "%s", conflict);
    return line;
}

/* [loading] steps (kept by handle_key) into the scene: below 0 with [adhesion] only. 0, or the line of the
 * key with the message (im_fail). */
static int parse_kept_steps(const scene_given *given)
{
    im_scene *scene = given->scene;
    const int line = key_line(given, "loading", "steps");
    char error[512];
    if (line && steps_parse_signed("steps", given->steps, scene->adhesion_work > 0, scene->steps, &scene->step_count,
                                   error, sizeof error) != 0) {
        im_fail(IM_EFORMAT, "%s", error);
        return line;
    }
    return 0;
}

/* Fig. 7 draws A / A_cone against N* over the range a family's surfaces share, which one step is
 * not. Returns the line of plots at fault, 0 if none. */
static int check_fig7_steps(const scene_given *given)
{
    const im_scene *scene = given->scene;
    if (!(scene->plots & IM_SCENE_PLOT_FIG7) || scene->step_count >= 2)
        return 0;
    im_fail(IM_EFORMAT,
            "plots = fig7 needs at least two [loading] steps (%d given): it "
            "draws A / A_cone against N* over the range of N* the surfaces share",
            scene->step_count);
    return key_line(given, "output", "plots");
}

/* Settings that contradict each other: a message citing the line of the key at fault (the later
 * of two), by im_fail; returns that line (1 if no key was given), 0 if consistent. */
int scene_check_keys(const scene_given *given)
{
    const im_scene *scene = given->scene;
    int adhesion_line = check_adhesion(given); /* first: whether steps may go below 0 */
    if (adhesion_line)
        return adhesion_line;
    int steps_line = parse_kept_steps(given);
    if (steps_line)
        return steps_line;
    int periodic_line = check_periodic(given);
    if (periodic_line)
        return periodic_line;
    int sweep_line = check_sweeps(given);
    if (sweep_line)
        return sweep_line;
    int punch_line = check_punch_keys(given);
    if (punch_line)
        return punch_line;
    int fig7_line = check_fig7_steps(given);
    if (fig7_line)
        return fig7_line;
    if (scene->surface.lambda_r <= largest_lambda_s(scene)) {
        int r = key_line(given, "surfaces", "lambda_r"), s = key_line(given, "surfaces", "lambda_s");
        int n = key_line(given, "surfaces", "n"), m = key_line(given, "surfaces", "m");
        int r_from = r ? r : n > m ? n : m; /* a default lambda_r is the box's side: n (or m) made it */
        im_fail(IM_EFORMAT, "lambda_r = %g must exceed lambda_s = %g%s", scene->surface.lambda_r,
                largest_lambda_s(scene), r ? "" : " (lambda_r defaults to the box's side)");
        int line = r_from > s ? r_from : s;
        return line > 0 ? line : 1;
    }
    if (scene->surface_file[0]) {
        int line = check_files(given);
        if (line)
            return line;
    }
    if (scene->control == IM_CONTROL_MEAN_GAP && !scene->periodic) {
        im_fail(IM_EFORMAT, "control = mean_gap needs [punch] periodic: the half-space "
                            "has no mean gap");
        return key_line(given, "loading", "control");
    }
    for (int i = 0; scene->control == IM_CONTROL_MEAN_GAP && i < scene->step_count; ++i)
        if (!(scene->steps[i] > 0)) { /* refused before solving, not at its step */
            im_fail(IM_EFORMAT,
                    "steps: step %d is the mean gap %g: expected mean gaps > 0 (at 0 the cell is in full "
                    "contact)",
                    i + 1, scene->steps[i]);
            return key_line(given, "loading", "steps");
        }
    /* a history that unloads needs the cap's memory (or adhesion's); without one, unloading only
     * retraces loading and a list out of order is more likely a slip. Mean gaps load as they fall. */
    const double sense = scene->control == IM_CONTROL_MEAN_GAP ? -1 : 1;
    for (int i = 1; i < scene->step_count && !(scene->hardness > 0) && !(scene->adhesion_work > 0); ++i) {
        if (!(sense * scene->steps[i] > sense * scene->steps[i - 1])) {
            im_fail(IM_EFORMAT,
                    "steps must %s: %g follows %g (a history that "
                    "unloads needs [material] hardness: without one unloading retraces loading)",
                    sense > 0 ? "increase" : "decrease (mean gaps)", scene->steps[i], scene->steps[i - 1]);
            return key_line(given, "loading", "steps");
        }
    }
    return 0;
}
