/* Internal to `indentmap mpi-indent` (mpi_indent.c): its options, and its histories (mpi_periodic.c): the
 * periodic cell's and the half-space's adhesive one. Built only with MPI (IM_HAVE_MPI). */
#ifndef INDENTMAP_CLI_MPI_INDENT_H
#define INDENTMAP_CLI_MPI_INDENT_H

#include "indentmap/mpi.h"

#if IM_HAVE_MPI

typedef struct mpi_indent_options {
    im_surface_params surface; /* synthesised when no file is given */
    int m_given;               /* --m; else NY = NX, as indent's and surface's */
    const char *surface_file;  /* float64 .npy heights in units of delta, or NULL */
    im_indenter punch;
    const char *profile_path;   /* --profile: the punch's shape (indent's), read on every rank */
    im_profile *profile;        /* read from it: the punch borrows it */
    int punch_given;            /* --punch, --alpha, --radius or --profile */
    enum im_control control;    /* --approach, --load; --periodic: --pressure (load), --mean-gap */
    const char *target_text;    /* the half-space's --approach or --load: W or N, or a LIST (a history) */
    double target;              /* w or N; NaN until given (and for a history) */
    int periodic;               /* --periodic: a rigid flat on the periodic cell, a history of targets */
    const char *targets_option; /* --pressure or --mean-gap, or the half-space's --approach or --load LIST */
    double *targets;            /* its step list (mean pressures, mean gaps or approaches): a history */
    int target_count;
    im_solver_options solver;
    /* --adhesion-work, --adhesion-range, --adhesion-law, --adhesion-zone: the history's steps' (the solver's options
     * have none) */
    double adhesion_work, adhesion_range, adhesion_zone;
    int adhesion_law, adhesion_law_given;
    int tol_given;       /* --tol (run.json: no quality preset) */
    const char *out;     /* folder for force.npy and gap.npy, or NULL */
    int map_factor;      /* > 0: also DIR/force_map.npy, forces summed over factor^2 blocks */
    int frames;          /* --frames: DIR/force_NNNN.npy and DIR/frames/contact_NNNN.png of every step (indent's) */
    const char *command; /* the command line as given, the Command its figures carry (rank 0; NULL elsewhere) */
} mpi_indent_options;

/* DIR/force.npy and DIR/gap.npy of this rank's rows (and DIR/force_map.npy with --map): rank 0 makes
 * the folder. Collective. */
int mpi_indent_write_fields(const mpi_indent_options *o, const im_mpi_solver *solver, const double *pressure,
                            const double *gap);

/* The history of o's targets on the surface of heights (this rank's rows): --periodic, the cell under a rigid
 * flat on a periodic solver; else the half-space's approaches or loads by o's punch (plastic memory with a
 * hardness, adhesion). On rank 0 the history CSV
 * on stdout and, with --out DIR, DIR/history.csv appended step by step, DIR/run.json (indent's schema) and the
 * history figure (history.png and .pdf, indent's); the last step's fields in DIR; with --frames each step's
 * force field and contact map, drawn by rank 0 from the forces it gathers. Collective. */
int mpi_indent_history(const mpi_indent_options *o, im_mpi_solver *solver, const double *heights);

#endif

#endif
