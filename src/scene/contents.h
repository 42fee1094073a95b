/* Internal: the scene a file or a record describes (struct im_scene, opaque in indentmap/scene.h): what the
 * file said, with every key it left out at its default, and apart from it where the scene came from and
 * the caller's settings. What a run measures and makes is not here but in its run state (run_state.h),
 * which the copy of the scene that im_scene_run runs points to. */
#ifndef INDENTMAP_SCENE_CONTENTS_H
#define INDENTMAP_SCENE_CONTENTS_H

#include "indentmap/scene.h"

struct scene_run_state;

struct im_scene {
    char path[IM_SCENE_PATH];         /* the scene file as given */
    char contents[IM_SCENE_CONTENTS]; /* what the scene file set, as parsed: "[section]\nkey = value\n" for
                                        every key given, in the file's order, values trimmed, comments and
                                        blank lines dropped (the other keys take their defaults). Runs
                                        record it: run.json's scene_contents, PNG and PDF metadata */
    char name[64];
    char output_dir[IM_SCENE_PATH]; /* default output/NAME */
    char quality[16];               /* draft | standard (default) | publication: the solver
                                        tolerance preset of solver.h (1e-5, 1e-6, 1e-9); anything
                                        else is refused. [solver] tol, if given, overrides it.
                                        Both are recorded in OUTPUT/run.json. */

    im_surface_params surface;            /* template of every generated surface */
    char surface_file[IM_SCENE_PATH];     /* `file`: surface files instead of generated families, a
                                        comma-separated list ("" if none). The files are the
                                        ensemble of one family: seed_count is their number and
                                        seeds[i] = i picks file i. `slopes` and `seeds` are refused
                                        beside them (their h'rms is measured, each is one surface). */
    int file_count;                       /* files in surface_file (0: none), at most IM_SCENE_MAX_FAMILIES */
    enum im_detrend detrend;              /* for the files (default none) */
    enum im_row_alignment align;          /* the files' scan-line alignment, before detrend (default none) */
    int fill;                             /* 1: fill the files' missing points (NaN); 0: refuse them */
    char channel[64];                     /* the files' channel (instrument files read through Gwyddion: an
                                        index or a title); "": the first holding heights */
    int resample_square;                  /* 1: resample files whose pixels are not square onto square ones
                                        (formats.h: im_surface_read_options.resample_square); 0: refuse them */
    enum im_npy_order npy_order;          /* `npy_order`: which index of the .npy files is x (formats.h; sidecar, the
                                        default: as each file's sidecar states, else yx) */
    char file_unit[16];                   /* the files' length unit ("": lengths in delta), set on the run's copy
                                        when they are measured (scene_prepare) */
    double slopes[IM_SCENE_MAX_FAMILIES]; /* h'rms of each family; 0 means smooth. A scene over files: NaN,
                                            and on the run's copy the files' root mean square (scene_run_state) */
    int family_count;
    uint64_t seeds[IM_SCENE_MAX_FAMILIES];
    int seed_count;

    enum im_punch_kind punch; /* cone, sphere, flat, profile (indenter.h: im_punch_parse reads shape) */
    double alpha_degrees;     /* cone semi-opening angle */
    /* Sweeps (docs/scenes.md, "Sweeps"): [punch] alpha, [surfaces] hurst and lambda_s may be lists.
     * Each scalar above holds its list's first value; a count of 0 or 1 is no sweep. A scene with a
     * list of two or more values runs every combination (alpha x hurst x lambda_s, each with all
     * slopes x seeds) as a sweep point of its own in OUTPUT/alpha_A_hurst_H_lambda_s_L/; at most
     * IM_SCENE_MAX_SWEEP_POINTS combinations. */
    double alphas[IM_SCENE_MAX_SWEEP]; /* degrees */
    int alpha_count;
    double hursts[IM_SCENE_MAX_SWEEP];
    int hurst_count;
    double lambda_ss[IM_SCENE_MAX_SWEEP]; /* in delta */
    int lambda_s_count;
    double radius;                    /* sphere radius or flat punch radius, in delta */
    char profile_file[IM_SCENE_PATH]; /* [punch] profile: the file of shape = profile (im_profile_read:
                                        an (r, z) table, or a .npy 2-D field on the scene's grid),
                                        relative to the scene file's folder */
    /* [punch] periodic = yes (docs/scenes.md, "Periodic contact"; solver.h, "Periodic mode"): every
     * surface is one period of a periodic surface, pressed on the whole cell under mean-pressure control:
     * [loading] steps are mean pressures p_m (units of E*; control is then load), or with [loading]
     * control = mean_gap mean gaps over the cell (solver.h, IM_CONTROL_MEAN_GAP; any other control is
     * refused, and mean_gap without periodic). IM_SCENE_PERIODIC_FLAT without [punch] shape: a rigid flat on the whole cell, as `indent
     * --periodic`; IM_SCENE_PERIODIC_PUNCH with one: that punch, repeated with the cell. 0: the half-space.
     * What needs the smooth contact on a half-space (load_star, frames, table, adhesion and the plots
     * but fig3 and flat_k) is refused beside it, naming the key; contact_panels and distributions are
     * taken at every step of each family's first surface instead (see im_scene_run). Part of every
     * result's key. */
    int periodic;
    double modulus;  /* composite modulus E* */
    double hardness; /* [material] hardness: pressure cap H_p (solver.h), 0: none */

    /* [adhesion] (docs/scenes.md, "Adhesion"; solver.h, "Adhesion"): work w > 0 and range delta_c > 0
     * together, 0 for none; law: enum im_adhesion_law (maugis-dugdale, exponential). Every history is then solved with it
     * (steps may go down and below 0, pulling the punch away; under load control they are loads N, as
     * `indent --load`'s, not N*); what is solved at load_star or in the periodic mode (panels, frames,
     * table, distributions, flat_k) is refused beside it. Part of every result's key. */
    double adhesion_work, adhesion_range;
    int adhesion_law;
    double adhesion_zone; /* [adhesion] zone: the Dugdale zone widened to P patches (solver.h), 0: the law as given */

    enum im_control control;          /* displacement, load or (periodic only) mean gap */
    double load_star;                 /* N* at which contact panels are drawn (0: none) */
    double steps[IM_SCENE_MAX_STEPS]; /* approaches or loads of a history, ascending (may be empty):
                                        first:last:count or a list, parsed as `indent --approach`,
                                        and then required to increase */
    int step_count;

    double tol; /* solver tolerance (default: the quality preset's; the preset
                                        IM_QUALITY_DEFAULT of solver.h, as for `indent`) */
    int device; /* [solver] device = cpu|gpu|auto: the solver's engine, IM_DEVICE_*
                                        of solver.h (default cpu) */

    int contact_panels, frames, table;
    int distributions;                 /* 1: gap and patch-size distributions at load_star of each
                                        family's first surface (distributions/, docs/scenes.md) */
    int frames3d;                      /* with frames: a 3-D view of every step too (frames3d.c) */
    int page_embed;                    /* 1: index.html carries its images as data URIs (viewer.h) */
    im_colormap_id colormap;           /* default magma, as render, indent --frames and Python */
    int log_norm;                      /* 1 (default): forces on a log norm spanning two decades below the
                                        largest, smaller forces in the under colour; 0: linear from 0 */
    double frames_slope;               /* the family whose history is framed; < 0: the roughest */
    double frames_clip;                /* percent of the frames' values cut at each end of their colour
                                          ranges (forces: the top), render --clip's; default 0 */
    double contact_panels_clip;        /* the same for the contact panels' one force range; default 0 */
    int frame_count;                   /* steps of the framed history (default 24) */
    double frame_rate;                 /* frames per second of contact/view3d .gif and .mp4 (default 4) */
    int frame_scale;                   /* pixels per patch of the contact and height frames (default 1) */
    int frame3d_width, frame3d_height; /* the 3-D frames' view in pixels (default 960 x 540) */
    enum im_animation animation;
    unsigned plots; /* bit set of enum im_scene_plot, 0 for none */
    /* Not from the file. */
    char from_record[IM_SCENE_PATH]; /* the run.json the scene was rebuilt from (im_scene_load_record),
                                        "" for a scene file */
    int recorded_plans;              /* rebuilt from a record: 1 when its run's FFTW plans were measured
                                        (a wisdom file), 0 when estimated; -1 for a scene file */
    const char *wisdom_path;         /* im_scene_set_wisdom_path's (not owned); NULL: none */
    struct scene_run_state *run;     /* what the run measures and makes (run_state.h): set on the copy of
                                        the scene that im_scene_run runs (scene_prepare), NULL otherwise */
};

/* Defaults: the paper's surface family and 80 degree cone, E* = 1, no outputs. */
void scene_defaults(im_scene *scene);

#endif
