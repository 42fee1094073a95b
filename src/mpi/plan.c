/* The distributed solver's plan: slabs, FFTW-MPI transforms, the kernel spectrum, convolution. */
#include "mpi/mpi_internal.h"
#include "core/args.h"

#include "core/fft_threads.h"
#include "indentmap/status.h"

#include <stdlib.h>
#include <string.h>

void im_mpi_init(void)
{
    fft_planner_lock();
    fft_prepare_planner(); /* fftw_init_threads, which must come before fftw_mpi_init */
    fft_planner_unlock();
    fftw_mpi_init();
}

void im_mpi_cleanup(void) { fftw_mpi_cleanup(); }

/* Slab sizes of the padded grid for `ranks` ranks without a communicator: FFTW-MPI's default
 * block is ceil(n / ranks) rows (fftw_mpi_local_size's documented default distribution). */
static ptrdiff_t block_of(ptrdiff_t n, int ranks) { return (n + ranks - 1) / ranks; }

/* The cascade's coarse levels, whole on every rank (cascade.c): the first level's serial plan (with
 * its own coarser levels) and its gap, pressure, displacement and four pair-sum arrays. */
static double cascade_bytes(int nx, int ny, int periodic)
{
    int cx, cy;
    if (!solver_cascade_sides(nx, ny, periodic, &cx, &cy))
        return 0;
    return im_solver_plan_bytes(cx, cy) + 7.0 * 8.0 * cx * cy;
}

/* Without the cascade's levels. */
static double mpi_solver_bytes(int nx, int ny, int ranks)
{
    const double rows0 = (double)block_of(2 * (ptrdiff_t)ny, ranks); /* rank 0's padded rows */
    const double rows = rows0 < ny ? rows0 : ny;                     /* its surface rows */
    const double columns = (double)block_of(nx + 1, ranks);          /* its spectrum columns */
    const double buffer = 16.0 * fmax(rows0 * (nx + 1), columns * 2.0 * ny);
    const double spectrum = 8.0 * columns * 2.0 * ny;
    /* the preconditioner's transform (its columns: of nx / 2 + 1) and inverse spectrum */
    const double small_columns = (double)block_of(nx / 2 + 1, ranks);
    const double precondition = 16.0 * fmax(rows * (nx / 2 + 1), small_columns * ny) + 8.0 * small_columns * ny;
    /* t, g, K t, z of the solver and the caller's g0, p, u; the row sums */
    const double vectors = 7.0 * 8.0 * rows * nx + 8.0 * MPI_SUMS_MAX * (rows + ny);
    return buffer + spectrum + precondition + vectors;
}

double im_mpi_solver_bytes(int nx, int ny, int ranks)
{
    ARG_SIDES_OR(nx, ny, NAN);
    return mpi_solver_bytes(nx, ny, ranks) + cascade_bytes(nx, ny, 0);
}

void im_mpi_solver_rows(const im_mpi_solver *s, int *y0, int *rows)
{
    ARG_REQUIRE_OR(y0, "y0", );
    ARG_REQUIRE_OR(rows, "rows", );
    *y0 = *rows = 0; /* for a NULL solver */
    ARG_REQUIRE_OR(s, "solver", );
    *y0 = s->y0;
    *rows = s->rows;
}

static int allocate(im_mpi_solver *s)
{
    const size_t n = (size_t)s->rows * s->nx + 1; /* + 1: ranks without surface rows */
    s->preconditioned = malloc(sizeof(double) * n);
    s->spectrum = fftw_alloc_real((size_t)s->convolution.columns * s->py + 1);
    s->direction = calloc(n, sizeof(double));
    s->gap = malloc(sizeof(double) * n);
    s->response = malloc(sizeof(double) * n);
    s->row_sums = malloc(sizeof(double) * MPI_SUMS_MAX * ((size_t)s->rows + 1));
    s->all_row_sums = malloc(sizeof(double) * MPI_SUMS_MAX * (size_t)s->ny);
    s->row_counts = malloc(sizeof(int) * (size_t)s->ranks);
    s->row_starts = malloc(sizeof(int) * (size_t)s->ranks);
    if (!s->spectrum || !s->direction || !s->gap || !s->response || !s->row_sums || !s->all_row_sums ||
        !s->row_counts || !s->row_starts || !s->preconditioned)
        return im_fail(IM_ENOMEM, "distributed solver %d x %d: allocation of rank %d's share failed", s->nx, s->ny,
                       s->rank);
    return IM_OK;
}

/* The pair of an n0 x n1 real grid whose real rows are cut in blocks of `block` rows (FFTW-MPI's
 * default block: FFTW_MPI_DEFAULT_BLOCK); *row_start and *column_start are this rank's first row and
 * first spectrum column. */
static int make_transform(const im_mpi_solver *s, mpi_transform *t, ptrdiff_t n0, ptrdiff_t n1, ptrdiff_t block,
                          ptrdiff_t *row_start, ptrdiff_t *column_start)
{
    const ptrdiff_t real[2] = {n0, n1}, complex[2] = {n0, n1 / 2 + 1};
    ptrdiff_t alloc_local = fftw_mpi_local_size_many_transposed(2, complex, 1, block, FFTW_MPI_DEFAULT_BLOCK, s->comm,
                                                                &t->rows, row_start, &t->columns, column_start);
    t->column_length = n0;
    t->stride = 2 * ((size_t)n1 / 2 + 1);
    t->buffer = fftw_alloc_real(2 * (size_t)alloc_local + 1);
    if (!t->buffer)
        return im_fail(IM_ENOMEM, "distributed solver %d x %d: rank %d's transform of %td x %td", s->nx, s->ny,
                       s->rank, n1, n0);
    unsigned flags = s->plan.options.fft_measure ? FFTW_MEASURE : FFTW_ESTIMATE;
    fftw_complex *modes = (fftw_complex *)t->buffer;
    fft_planner_lock();
    fft_prepare_planner();
    t->forward = fftw_mpi_plan_many_dft_r2c(2, real, 1, block, FFTW_MPI_DEFAULT_BLOCK, t->buffer, modes, s->comm,
                                            flags | FFTW_MPI_TRANSPOSED_OUT);
    t->backward = fftw_mpi_plan_many_dft_c2r(2, real, 1, FFTW_MPI_DEFAULT_BLOCK, block, modes, t->buffer, s->comm,
                                             flags | FFTW_MPI_TRANSPOSED_IN);
    fft_planner_unlock();
    if (!t->forward || !t->backward)
        return im_fail(IM_ENOMEM, "FFTW-MPI could not plan a %td x %td transform", n1, n0);
    return IM_OK;
}

static void free_transform(mpi_transform *t)
{
    fft_planner_lock();
    if (t->forward)
        fftw_destroy_plan(t->forward);
    if (t->backward)
        fftw_destroy_plan(t->backward);
    fft_planner_unlock();
    fftw_free(t->buffer);
}

static long wrapped_offset(long j, long n, long padded) { return j <= n ? j : padded - j; }

/* The real parts of this rank's spectrum columns of t, scaled by 1 / the grid's size. */
static void take_real_spectrum(const mpi_transform *t, double scale, double *spectrum)
{
    const fftw_complex *modes = (const fftw_complex *)t->buffer;
#pragma omp parallel for schedule(static)
    for (size_t k = 0; k < (size_t)t->columns * t->column_length; ++k)
        spectrum[k] = modes[k][0] * scale;
}

/* K sampled on this rank's padded rows with wrap-around offsets (even, so its spectrum is real),
 * transformed; the real parts, scaled by 1 / (px py), are the spectrum (transposed layout). */
static void compute_spectrum(im_mpi_solver *s)
{
    const mpi_transform *t = &s->convolution;
    const double d = s->delta, e = s->plan.options.e_star;
#pragma omp parallel for schedule(static)
    for (ptrdiff_t r = 0; r < t->rows; ++r) {
        long dy = wrapped_offset(s->local_0_start + r, s->ny, s->py);
        for (int jx = 0; jx < s->px; ++jx)
            t->buffer[(size_t)r * t->stride + jx] = im_influence_square(wrapped_offset(jx, s->nx, s->px) * d, dy * d,
                                                                        d, e);
    }
    fftw_execute(t->forward);
    take_real_spectrum(t, 1.0 / ((double)s->px * s->py), s->spectrum);
}

/* The preconditioner's pair of the unpadded ny x nx grid, its rows in blocks of the padded slabs'
 * size (FFTW-MPI's default block of the 2 ny padded rows): rank k's block is then exactly its
 * surface rows [y0, y0 + rows), so the gap goes in and M g comes out where they are. */
static int plan_preconditioner(im_mpi_solver *s)
{
    ptrdiff_t start0, start1;
    int status = make_transform(s, &s->unpadded, s->ny, s->nx, (s->py + s->ranks - 1) / s->ranks, &start0, &start1);
    if (status == IM_OK && (s->unpadded.rows != s->rows || (s->rows > 0 && start0 != s->y0)))
        return im_fail(IM_EUNSUPPORTED,
                       "distributed solver: FFTW-MPI gives rank %d rows [%td, %td) of the unpadded "
                       "grid, not its surface rows [%d, %d)",
                       s->rank, start0, start0 + s->unpadded.rows, s->y0, s->y0 + s->rows);
    return status;
}

/* M = 1 / the spectrum of K wrapped periodically on the nx x ny grid (offsets min(j, n - j)), as
 * solver/plan.c's serial preconditioner: the same kernel values, transformed over the ranks. */
static void compute_preconditioner(im_mpi_solver *s)
{
    const mpi_transform *t = &s->unpadded;
    const double d = s->delta, e = s->plan.options.e_star;
#pragma omp parallel for schedule(static)
    for (int r = 0; r < s->rows; ++r) {
        const int y = s->y0 + r, dy = y <= s->ny - y ? y : s->ny - y;
        for (int jx = 0; jx < s->nx; ++jx)
            t->buffer[(size_t)r * t->stride + jx] = im_influence_square((jx <= s->nx - jx ? jx : s->nx - jx) * d,
                                                                        dy * d, d, e);
    }
    fftw_execute(t->forward);
    const size_t count = (size_t)t->columns * t->column_length;
    take_real_spectrum(t, 1.0, s->inverse_spectrum);
    const double scale = 1.0 / ((double)s->nx * s->ny);
#pragma omp parallel for schedule(static)
    for (size_t k = 0; k < count; ++k)
        s->inverse_spectrum[k] = s->inverse_spectrum[k] > 0 ? scale / s->inverse_spectrum[k] : 0;
}

/* The periodic half-space (solver/periodic.c's modes) on this rank's spectrum columns, and K(0) for
 * the Winkler start as the serial plan takes it: the inverse transform of the spectrum at the
 * origin (rank 0's first value), shared. */
static void compute_periodic_spectra(im_mpi_solver *s)
{
    const mpi_transform *t = &s->convolution;
    fftw_complex *modes = (fftw_complex *)t->buffer;
#pragma omp parallel for schedule(static)
    for (ptrdiff_t c = 0; c < t->columns; ++c)
        for (int ky = 0; ky < s->ny; ++ky) {
            const size_t k = (size_t)c * s->ny + ky;
            solver_periodic_mode(&s->plan, (int)(s->local_1_start + c), ky, &s->spectrum[k], &s->inverse_spectrum[k]);
            modes[k][0] = s->spectrum[k];
            modes[k][1] = 0;
        }
    fftw_execute(t->backward);
    s->k0 = t->buffer[0];
    MPI_Bcast(&s->k0, 1, MPI_DOUBLE, 0, s->comm);
}

/* Every rank's surface rows, for the ordered sums' gather. */
static void share_rows(im_mpi_solver *s)
{
    int mine[2] = {s->rows, s->y0}, *all = malloc(sizeof(int) * 2 * (size_t)s->ranks);
    MPI_Allgather(mine, 2, MPI_INT, all, 2, MPI_INT, s->comm);
    for (int r = 0; r < s->ranks; ++r) {
        s->row_counts[r] = all[2 * r];
        s->row_starts[r] = all[2 * r + 1];
    }
    free(all);
}

/* The options the MPI engine cannot honour are refused, never ignored. */
static int check_engine_options(const im_solver_options *o)
{
    if (o->adhesion_work > 0)
        return im_fail(IM_EUNSUPPORTED,
                       "adhesion work = %g: the distributed solver solves the repulsive problem "
                       "(adhesion acts in the steps of a periodic cell, im_mpi_flat_contact_adhesion, and "
                       "of an indentation, im_mpi_indentation_create)",
                       o->adhesion_work);
    if (o->device == IM_DEVICE_GPU)
        return im_fail(IM_EUNSUPPORTED, "device = gpu: the distributed solver runs on each rank's CPU (OpenMP "
                                        "and FFTW-MPI); expected device = cpu or auto");
    return IM_OK;
}

static int check_create(int nx, int ny, double delta, const im_solver_options *o)
{
    int status = im_solver_options_check(o);
    if (status == IM_OK)
        status = check_engine_options(o);
    if (status != IM_OK)
        return status;
    if (nx < 1 || ny < 1 || nx > IM_FIELD_MAX_SIDE || ny > IM_FIELD_MAX_SIDE)
        return im_fail(IM_EINVAL, "solver grid %d x %d: expected sides in [1, %d]", nx, ny, IM_FIELD_MAX_SIDE);
    if (!(isfinite(delta) && delta > 0))
        return im_fail(IM_EINVAL, "delta = %g: expected a finite patch side > 0", delta);
    return IM_OK;
}

/* The transforms and the arrays of this rank's rows; the preconditioner's own pair on the half-space. */
static int make_transforms(im_mpi_solver *s)
{
    int status = make_transform(s, &s->convolution, s->py, s->px, FFTW_MPI_DEFAULT_BLOCK, &s->local_0_start,
                                &s->local_1_start);
    s->y0 = s->local_0_start < s->ny ? (int)s->local_0_start : s->ny;
    s->rows = (int)(s->local_0_start + s->convolution.rows < s->ny ? s->convolution.rows : s->ny - s->y0);
    status = mpi_collective_status(s->comm, status);
    if (status == IM_OK)
        status = mpi_collective_status(s->comm, allocate(s));
    if (status == IM_OK && !s->plan.options.periodic)
        status = mpi_collective_status(s->comm, plan_preconditioner(s));
    if (status != IM_OK)
        return status;
    s->precondition_with = s->plan.options.periodic ? &s->convolution : &s->unpadded;
    const mpi_transform *m = s->precondition_with;
    s->inverse_spectrum = fftw_alloc_real((size_t)m->columns * m->column_length + 1);
    return mpi_collective_status(s->comm, s->inverse_spectrum ? IM_OK
                                                              : im_fail(IM_ENOMEM,
                                                                        "distributed solver "
                                                                        "%d x %d: rank %d's preconditioner",
                                                                        s->nx, s->ny, s->rank));
}

static int set_up(im_mpi_solver *s)
{
    char what[192];
    const double coarse = s->plan.options.cascade ? cascade_bytes(s->nx, s->ny, s->plan.options.periodic) : 0;
    snprintf(what, sizeof what, "rank %d's share of a %d x %d distributed solver%s", s->rank, s->nx, s->ny,
             coarse > 0 ? " (with the cascade's coarse levels, whole on every rank; cascade = 0 leaves them out)"
                        : "");
    int status = im_memory_check(mpi_solver_bytes(s->nx, s->ny, s->ranks) + coarse, what);
    status = mpi_collective_status(s->comm, status);
    if (status == IM_OK)
        status = make_transforms(s);
    if (status != IM_OK)
        return status;
    share_rows(s);
    if (s->plan.options.periodic)
        compute_periodic_spectra(s);
    else {
        compute_spectrum(s);
        compute_preconditioner(s);
        s->k0 = im_influence_square(0, 0, s->delta, s->plan.options.e_star);
    }
    return mpi_cascade_create(s);
}

int im_mpi_solver_create(MPI_Comm comm, int nx, int ny, double delta, const im_solver_options *options,
                         im_mpi_solver **out)
{
    ARG_REQUIRE(out, "out");

    *out = NULL;
    im_solver_options o = options ? *options : im_solver_options_default();
    int status = check_create(nx, ny, delta, &o); /* the same arguments on every rank: the same answer */
    if (status != IM_OK)
        return status;
    im_mpi_solver *s = calloc(1, sizeof *s);
    status = mpi_collective_status(comm, s ? IM_OK : im_fail(IM_ENOMEM, "distributed solver"));
    if (status != IM_OK) {
        free(s);
        return status;
    }
    o.wisdom_path = NULL; /* not owned, and not used: FFTW-MPI plans are made without wisdom */
    solver_plan_options(&o);
    const int pad = o.periodic ? 1 : 2; /* periodic: the circular convolution on the grid itself */
    *s = (im_mpi_solver){.nx = nx, .ny = ny, .px = pad * nx, .py = pad * ny, .delta = delta};
    s->plan = (im_solver_plan){.engine = &solver_engine_mpi,
                               .mpi = s,
                               .nx = nx,
                               .ny = ny,
                               .px = pad * nx,
                               .py = pad * ny,
                               .delta = delta,
                               .options = o,
                               .kernel = &s->k0,
                               .direct_limit = 0};
    MPI_Comm_dup(comm, &s->comm);
    MPI_Comm_rank(s->comm, &s->rank);
    MPI_Comm_size(s->comm, &s->ranks);
    status = set_up(s);
    if (status != IM_OK) {
        im_mpi_solver_free(s);
        return status;
    }
    *out = s;
    return IM_OK;
}

void im_mpi_solver_free(im_mpi_solver *s)
{
    if (!s)
        return;
    free_transform(&s->convolution);
    free_transform(&s->unpadded);
    mpi_cascade_free(s);
    fftw_free(s->inverse_spectrum);
    free(s->preconditioned);
    fftw_free(s->spectrum);
    free(s->direction);
    free(s->gap);
    free(s->response);
    free(s->row_sums);
    free(s->all_row_sums);
    free(s->row_counts);
    free(s->row_starts);
    MPI_Comm_free(&s->comm);
    free(s);
}

void im_mpi_convolve(im_mpi_solver *s, const double *pressure, double *displacement)
{
    ARG_REQUIRE_OR(s, "solver", );
    mpi_convolve(s, pressure, displacement);
}

void mpi_transform_apply(const im_mpi_solver *s, const mpi_transform *t, const double *spectrum, const double *in,
                         double *out)
{
    const int nx = s->nx;
    /* every row is rewritten: the c2r transform leaves garbage in the padding */
#pragma omp parallel for schedule(static)
    for (ptrdiff_t r = 0; r < t->rows; ++r) {
        double *row = t->buffer + (size_t)r * t->stride;
        if (r < s->rows) {
            memcpy(row, in + (size_t)r * nx, sizeof(double) * nx);
            memset(row + nx, 0, sizeof(double) * (t->stride - nx));
        } else
            memset(row, 0, sizeof(double) * t->stride);
    }
    fftw_execute(t->forward);
    solver_multiply_modes((fftw_complex *)t->buffer, spectrum, (size_t)t->columns * t->column_length);
    fftw_execute(t->backward);
#pragma omp parallel for schedule(static)
    for (int r = 0; r < s->rows; ++r)
        memcpy(out + (size_t)r * nx, t->buffer + (size_t)r * t->stride, sizeof(double) * nx);
}

void mpi_convolve(im_mpi_solver *s, const double *pressure, double *displacement)
{
    mpi_transform_apply(s, &s->convolution, s->spectrum, pressure, displacement);
}
