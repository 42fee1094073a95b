/* Frames of an indentation run and animations: GIF with one palette built from all its frames, MP4 via ffmpeg. */
#include "indentmap/figure.h"
#include "core/args.h"
#include "figure/palette.h"

#include "indentmap/status.h"

#include <errno.h>
#include <gif_lib.h>
#include <math.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

int im_frame_path(char *buffer, size_t size, const char *directory, const char *prefix, int index)
{
    ARG_REQUIRE(buffer, "buffer");
    ARG_REQUIRE(directory, "directory");
    ARG_REQUIRE(prefix, "prefix");
    if (index < 0)
        return im_fail(IM_EINVAL, "frame index %d: expected >= 0", index);
    char name[128];
    snprintf(name, sizeof name, "%.100s_%04d.png", prefix, index); /* the callers' prefixes are short words */
    return im_path_join(buffer, size, directory, name);
}

/* ---- GIF ---- */

im_gif_options im_gif_options_default(void)
{
    return (im_gif_options){.seconds_per_frame = 0.25, .colours = 256, .dither = 0};
}

static int write_to_file(GifFileType *gif, const GifByteType *data, int length)
{
    return (int)fwrite(data, 1, (size_t)length, (FILE *)gif->UserData);
}

/* NETSCAPE2.0 application extension: loop forever. */
static int put_loop_extension(GifFileType *gif)
{
    static const GifByteType loop[3] = {1, 0, 0};
    return EGifPutExtensionLeader(gif, APPLICATION_EXT_FUNC_CODE) == GIF_OK &&
           EGifPutExtensionBlock(gif, 11, "NETSCAPE2.0") == GIF_OK && EGifPutExtensionBlock(gif, 3, loop) == GIF_OK &&
           EGifPutExtensionTrailer(gif) == GIF_OK;
}

/* The screen descriptor with the palette as the global colour table (padded to a power of two). */
static int put_screen(GifFileType *gif, const im_image *frame, const gif_palette *p)
{
    int size = 2;
    while (size < p->count)
        size *= 2;
    ColorMapObject *map = GifMakeMapObject(size, NULL);
    if (!map)
        return 0;
    memset(map->Colors, 0, (size_t)size * sizeof *map->Colors);
    for (int i = 0; i < p->count; ++i)
        map->Colors[i] = (GifColorType){p->rgb[i][0], p->rgb[i][1], p->rgb[i][2]};
    int ok = EGifPutScreenDesc(gif, frame->width, frame->height, 8, 0, map) == GIF_OK;
    GifFreeMapObject(map);
    return ok;
}

static int put_frame(GifFileType *gif, const im_image *frame, const GifByteType *indices, int delay_centiseconds)
{
    GraphicsControlBlock control = {DISPOSE_DO_NOT, false, delay_centiseconds, NO_TRANSPARENT_COLOR};
    GifByteType extension[4];
    EGifGCBToExtension(&control, extension);
    int ok = EGifPutExtension(gif, GRAPHICS_EXT_FUNC_CODE, 4, extension) == GIF_OK &&
             EGifPutImageDesc(gif, 0, 0, frame->width, frame->height, false, NULL) == GIF_OK;
    for (int row = 0; ok && row < frame->height; ++row)
        ok = EGifPutLine(gif, (GifByteType *)indices + (size_t)row * frame->width, frame->width) == GIF_OK;
    return ok;
}

static int check_options(const im_gif_options *o)
{
    if (!(o->seconds_per_frame >= 0.01 && o->seconds_per_frame <= 600.0))
        return im_fail(IM_EINVAL, "GIF: %g s per frame: expected [0.01, 600] (GIF delays are in 1/100 s)",
                       o->seconds_per_frame);
    if (o->colours < 2 || o->colours > 256)
        return im_fail(IM_EINVAL, "GIF: %d colours: expected 2 to 256", o->colours);
    if (o->dither != 0 && o->dither != 1)
        return im_fail(IM_EINVAL, "GIF: dither = %d: expected 0 or 1", o->dither);
    return IM_OK;
}

static int check_frames(const im_image *frames, int count)
{
    if (count < 1)
        return im_fail(IM_EINVAL, "animation: %d frames: expected at least 1", count);
    for (int i = 0; i < count; ++i) {
        if (frames[i].width < 1 || frames[i].height < 1)
            return im_fail(IM_EINVAL, "animation: frame %d is %d x %d: expected at least 1 x 1 pixels", i,
                           frames[i].width, frames[i].height);
        if (!frames[i].rgba || frames[i].width != frames[0].width || frames[i].height != frames[0].height)
            return im_fail(IM_EINVAL, "animation: frame %d is %d x %d (or empty): expected %d x %d like frame 0", i,
                           frames[i].width, frames[i].height, frames[0].width, frames[0].height);
        if (frames[i].width > 65535 || frames[i].height > 65535)
            return im_fail(IM_EINVAL, "animation: frame %d x %d: GIF sides are at most 65535", frames[i].width,
                           frames[i].height);
    }
    return IM_OK;
}

typedef struct gif_input {
    const im_image *frames;
    int count;
    const im_gif_options *options;
    colour_table *table;
    const gif_palette *palette;
    GifByteType *indices;
} gif_input;

static int encode_gif(FILE *stream, const gif_input *in)
{
    int error = 0;
    GifFileType *gif = EGifOpen(stream, write_to_file, &error);
    if (!gif)
        return im_fail(IM_EIO, "GIF: %s", GifErrorString(error));
    EGifSetGifVersion(gif, true);
    int status = put_screen(gif, &in->frames[0], in->palette) && put_loop_extension(gif)
                     ? IM_OK
                     : im_fail(IM_EIO, "GIF header: %s", GifErrorString(gif->Error));
    int delay = (int)lround(100.0 * in->options->seconds_per_frame);
    for (int i = 0; status == IM_OK && i < in->count; ++i) {
        status = palette_index_frame(in->table, in->palette, &in->frames[i], in->options->dither, in->indices);
        if (status == IM_OK && !put_frame(gif, &in->frames[i], in->indices, delay))
            status = im_fail(IM_EIO, "GIF frame %d: %s", i, GifErrorString(gif->Error));
    }
    if (EGifCloseFile(gif, &error) != GIF_OK && status == IM_OK)
        status = im_fail(IM_EIO, "GIF: %s", GifErrorString(error));
    return status;
}

static int write_gif(gif_input *in, const char *path)
{
    gif_palette palette;
    int status = colour_table_build(in->frames, in->count, &in->table);
    if (status == IM_OK)
        status = palette_build(in->table, in->options->colours, &palette);
    in->palette = &palette;
    im_atomic_file file;
    if (status == IM_OK)
        status = im_atomic_open(&file, path);
    if (status == IM_OK) {
        status = encode_gif(file.stream, in);
        if (status == IM_OK)
            status = im_atomic_commit(&file);
        else
            im_atomic_abort(&file);
    }
    colour_table_free(in->table);
    return status;
}

int im_animation_gif_with(const im_image *frames, int count, const im_gif_options *options, const char *path)
{
    ARG_REQUIRE(frames, "frames");
    ARG_REQUIRE(options, "options");
    ARG_REQUIRE(path, "path");
    int status = check_options(options);
    if (status == IM_OK)
        status = check_frames(frames, count);
    if (status != IM_OK)
        return status;
    gif_input in = {frames, count, options, NULL, NULL, malloc((size_t)frames[0].width * frames[0].height)};
    status = in.indices ? write_gif(&in, path)
                        : im_fail(IM_ENOMEM, "GIF %d x %d: out of memory", frames[0].width, frames[0].height);
    free(in.indices);
    if (status != IM_OK)
        return im_fail_context(status, "%s", path);
    return IM_OK;
}

int im_animation_gif(const im_image *frames, int count, double seconds_per_frame, const char *path)
{
    ARG_REQUIRE(frames, "frames");
    ARG_REQUIRE(path, "path");
    im_gif_options options = im_gif_options_default();
    options.seconds_per_frame = seconds_per_frame;
    return im_animation_gif_with(frames, count, &options, path);
}

/* ---- MP4 through the ffmpeg command ---- */

int im_ffmpeg_available(void)
{
    /* PATH is not a setting of the library: it is where posix_spawnp, which runs ffmpeg, will look */
    const char *path = getenv("PATH");
    char candidate[4096];
    for (const char *p = path; p && *p;) {
        size_t length = strcspn(p, ":");
        if (length > 0 && length < sizeof candidate - 8) {
            snprintf(candidate, sizeof candidate, "%.*s/ffmpeg", (int)length, p);
            if (access(candidate, X_OK) == 0)
                return 1;
        }
        p += length + (p[length] == ':');
    }
    return 0;
}

static int run_ffmpeg(char *const arguments[])
{
    pid_t child;
    int error = posix_spawnp(&child, "ffmpeg", NULL, NULL, arguments, environ);
    if (error)
        return im_fail(IM_EIO, "ffmpeg cannot be started: %s", strerror(error));
    int wait_status = 0;
    while (waitpid(child, &wait_status, 0) < 0)
        if (errno != EINTR)
            return im_fail(IM_EIO, "ffmpeg: waitpid: %s", strerror(errno));
    if (!WIFEXITED(wait_status) || WEXITSTATUS(wait_status) != 0)
        return im_fail(IM_EIO, "ffmpeg failed (status %d); see its messages above", WEXITSTATUS(wait_status));
    return IM_OK;
}

int im_animation_mp4(const char *directory, const char *prefix, int count, double frames_per_second, const char *path)
{
    ARG_REQUIRE(directory, "directory");
    ARG_REQUIRE(prefix, "prefix");
    ARG_REQUIRE(path, "path");
    if (!(frames_per_second > 0.0 && frames_per_second <= 240.0))
        return im_fail(IM_EINVAL, "MP4: %g frames per second: expected (0, 240]", frames_per_second);
    if (count < 1)
        return im_fail(IM_EINVAL, "MP4: %d frames: expected at least 1", count);
    if (!im_ffmpeg_available())
        return im_fail(IM_EUNSUPPORTED, "ffmpeg not found on PATH: no MP4 written; the frames are in %s", directory);
    char pattern[4096], rate[32], frames[32], name[128];
    snprintf(name, sizeof name, "%.100s_%%04d.png", prefix);
    int joined = im_path_join(pattern, sizeof pattern, directory, name);
    if (joined != IM_OK)
        return joined;
    snprintf(rate, sizeof rate, "%g", frames_per_second);
    snprintf(frames, sizeof frames, "%d", count);
    /* ffmpeg picks the container from the extension, so the temporary name ends in .mp4 too; it
     * overwrites (-y) the empty temporary file, whose descriptor then syncs what it wrote. */
    im_atomic_file file;
    int status = im_atomic_open_suffixed(&file, path, ".mp4");
    if (status != IM_OK)
        return status;
    /* -frames:v: ffmpeg reads the pattern until its numbering stops, so a frame left from a longer run
     * would otherwise be encoded too */
    char *arguments[] = {"ffmpeg", "-y",      "-loglevel", "error",   "-framerate",   rate,
                         "-i",     pattern,   "-frames:v", frames,    "-vf",          "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                         "-c:v",   "libx264", "-pix_fmt",  "yuv420p", file.temp_path, NULL};
    status = run_ffmpeg(arguments);
    if (status == IM_OK)
        status = im_atomic_commit(&file);
    else
        im_atomic_abort(&file);
    return status;
}
