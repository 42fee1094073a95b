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

/* Real stride of a padded row in FFTW's in-place r2c layout: 2 (px / 2 + 1). */
static size_t padded_stride(const im_mpi_solver *s) { return (size_t)s->px + 2; }

/* Slab sizes of the padded grid for `ranks` ranks without a communicator: FFTW-MPI's default
 * block is ceil(n / ranks) rows (fftw_mpi_local_size's documented default distribution). */
static ptrdiff_t block_of(ptrdiff_t n, int ranks) { return (n + ranks - 1) / ranks; }

double im_mpi_solver_bytes(int nx, int ny, int ranks)
{
    ARG_SIDES_OR(nx, ny, NAN);
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

void im_mpi_solver_rows(const im_mpi_solver *s, int *y0, int *rows)
{
    ARG_REQUIRE_OR(y0, "y0", );
    ARG_REQUIRE_OR(rows, "rows", );
    *y0 = *rows = 0; /* for a NULL solver */
    ARG_REQUIRE_OR(s, "solver", );
    *y0 = s->y0;
    *rows = s->rows;
}

static int allocate(im_mpi_solver *s, ptrdiff_t alloc_local)
{
    const size_t n = (size_t)s->rows * s->nx + 1; /* + 1: ranks without surface rows */
    s->buffer = fftw_alloc_real(2 * (size_t)alloc_local);
    s->preconditioned = malloc(sizeof(double) * n);
    s->spectrum = fftw_alloc_real((size_t)s->local_n1 * s->py + 1);
    s->direction = calloc(n, sizeof(double));
    s->gap = malloc(sizeof(double) * n);
    s->response = malloc(sizeof(double) * n);
    s->row_sums = malloc(sizeof(double) * MPI_SUMS_MAX * ((size_t)s->rows + 1));
    s->all_row_sums = malloc(sizeof(double) * MPI_SUMS_MAX * (size_t)s->ny);
    s->row_counts = malloc(sizeof(int) * (size_t)s->ranks);
    s->row_starts = malloc(sizeof(int) * (size_t)s->ranks);
    if (!s->buffer || !s->spectrum || !s->direction || !s->gap || !s->response || !s->row_sums ||
        !s->all_row_sums || !s->row_counts || !s->row_starts || !s->preconditioned)
        return im_fail(IM_ENOMEM, "distributed solver %d x %d: allocation of rank %d's share failed", s->nx, s->ny,
                       s->rank);
    return IM_OK;
}

static int make_plans(im_mpi_solver *s)
{
    unsigned flags = s->plan.options.fft_measure ? FFTW_MEASURE : FFTW_ESTIMATE;
    fft_planner_lock();
    fft_prepare_planner();
    s->forward = fftw_mpi_plan_dft_r2c_2d(s->py, s->px, s->buffer, (fftw_complex *)s->buffer, s->comm,
                                          flags | FFTW_MPI_TRANSPOSED_OUT);
    s->backward = fftw_mpi_plan_dft_c2r_2d(s->py, s->px, (fftw_complex *)s->buffer, s->buffer, s->comm,
                                           flags | FFTW_MPI_TRANSPOSED_IN);
    fft_planner_unlock();
    if (!s->forward || !s->backward)
        return im_fail(IM_ENOMEM, "FFTW-MPI could not plan a %d x %d transform", s->px, s->py);
    return IM_OK;
}

static long wrapped_offset(long j, long n, long padded) { return j <= n ? j : padded - j; }

/* K sampled on this rank's padded rows with wrap-around offsets (even, so its spectrum is real),
 * transformed; the real parts, scaled by 1 / (px py), are the spectrum (transposed layout). */
static void compute_spectrum(im_mpi_solver *s)
{
    const size_t stride = padded_stride(s);
    const double d = s->delta, e = s->plan.options.e_star;
#pragma omp parallel for schedule(static)
    for (ptrdiff_t r = 0; r < s->local_n0; ++r) {
        long dy = wrapped_offset(s->local_0_start + r, s->ny, s->py);
        for (int jx = 0; jx < s->px; ++jx)
            s->buffer[(size_t)r * stride + jx] = im_influence_square(wrapped_offset(jx, s->nx, s->px) * d, dy * d, d, e);
    }
    fftw_execute(s->forward);
    const fftw_complex *modes = (const fftw_complex *)s->buffer;
    const double scale = 1.0 / ((double)s->px * s->py);
#pragma omp parallel for schedule(static)
    for (size_t k = 0; k < (size_t)s->local_n1 * s->py; ++k)
        s->spectrum[k] = modes[k][0] * scale;
}

/* The preconditioner's transforms of the unpadded ny x nx grid, its rows in blocks of the padded
 * slabs' size (FFTW-MPI's default block of the 2 ny padded rows): rank k's block is then exactly its
 * surface rows [y0, y0 + rows), so the gap goes in and M g comes out where they are. */
static int plan_preconditioner(im_mpi_solver *s)
{
    const ptrdiff_t block = (s->py + s->ranks - 1) / s->ranks, real[2] = {s->ny, s->nx},
                    complex[2] = {s->ny, s->nx / 2 + 1};
    ptrdiff_t n0, start0, n1, start1;
    ptrdiff_t alloc_local = fftw_mpi_local_size_many_transposed(2, complex, 1, block, FFTW_MPI_DEFAULT_BLOCK, s->comm,
                                                                &n0, &start0, &n1, &start1);
    if (n0 != s->rows || (n0 > 0 && start0 != s->y0))
        return im_fail(IM_EUNSUPPORTED, "distributed solver: FFTW-MPI gives rank %d rows [%td, %td) of the unpadded "
                       "grid, not its surface rows [%d, %d)", s->rank, start0, start0 + n0, s->y0, s->y0 + s->rows);
    s->precondition_columns = n1;
    s->precondition_buffer = fftw_alloc_real(2 * (size_t)alloc_local + 1);
    s->inverse_spectrum = fftw_alloc_real((size_t)n1 * s->ny + 1);
    if (!s->precondition_buffer || !s->inverse_spectrum)
        return im_fail(IM_ENOMEM, "distributed solver %d x %d: rank %d's preconditioner", s->nx, s->ny, s->rank);
    unsigned flags = s->plan.options.fft_measure ? FFTW_MEASURE : FFTW_ESTIMATE;
    fftw_complex *modes = (fftw_complex *)s->precondition_buffer;
    fft_planner_lock();
    fft_prepare_planner();
    s->precondition_forward = fftw_mpi_plan_many_dft_r2c(2, real, 1, block, FFTW_MPI_DEFAULT_BLOCK,
                                                         s->precondition_buffer, modes, s->comm,
                                                         flags | FFTW_MPI_TRANSPOSED_OUT);
    s->precondition_backward = fftw_mpi_plan_many_dft_c2r(2, real, 1, FFTW_MPI_DEFAULT_BLOCK, block, modes,
                                                          s->precondition_buffer, s->comm,
                                                          flags | FFTW_MPI_TRANSPOSED_IN);
    fft_planner_unlock();
    if (!s->precondition_forward || !s->precondition_backward)
        return im_fail(IM_ENOMEM, "FFTW-MPI could not plan a %d x %d transform", s->nx, s->ny);
    return IM_OK;
}

/* M = 1 / the spectrum of K wrapped periodically on the nx x ny grid (offsets min(j, n - j)), as
 * solver/plan.c's serial preconditioner: the same kernel values, transformed over the ranks. */
static void compute_preconditioner(im_mpi_solver *s)
{
    const size_t stride = 2 * ((size_t)s->nx / 2 + 1);
    const double d = s->delta, e = s->plan.options.e_star;
#pragma omp parallel for schedule(static)
    for (int r = 0; r < s->rows; ++r) {
        const int y = s->y0 + r, dy = y <= s->ny - y ? y : s->ny - y;
        for (int jx = 0; jx < s->nx; ++jx)
            s->precondition_buffer[(size_t)r * stride + jx] =
                im_influence_square((jx <= s->nx - jx ? jx : s->nx - jx) * d, dy * d, d, e);
    }
    fftw_execute(s->precondition_forward);
    const fftw_complex *modes = (const fftw_complex *)s->precondition_buffer;
    const double scale = 1.0 / ((double)s->nx * s->ny);
#pragma omp parallel for schedule(static)
    for (size_t k = 0; k < (size_t)s->precondition_columns * s->ny; ++k) {
        const double re = modes[k][0];
        s->inverse_spectrum[k] = re > 0 ? scale / re : 0;
    }
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
        return im_fail(IM_EUNSUPPORTED, "adhesion work = %g: the distributed solver solves the repulsive problem "
                       "(adhesion acts in an indentation, im_indentation_create, which has no distributed form)",
                       o->adhesion_work);
    if (o->periodic)
        return im_fail(IM_EUNSUPPORTED, "periodic = 1: the distributed solver solves the half-space on the "
                       "zero-padded grid (periodic contact is serial: im_flat_contact_create)");
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

static int set_up(im_mpi_solver *s)
{
    char what[96];
    snprintf(what, sizeof what, "rank %d's share of a %d x %d distributed solver", s->rank, s->nx, s->ny);
    int status = im_memory_check(im_mpi_solver_bytes(s->nx, s->ny, s->ranks), what);
    status = mpi_collective_status(s->comm, status);
    if (status != IM_OK)
        return status;
    ptrdiff_t alloc_local = fftw_mpi_local_size_2d_transposed(s->py, s->px / 2 + 1, s->comm, &s->local_n0,
                                                              &s->local_0_start, &s->local_n1, &s->local_1_start);
    s->y0 = s->local_0_start < s->ny ? (int)s->local_0_start : s->ny;
    s->rows = (int)(s->local_0_start + s->local_n0 < s->ny ? s->local_n0 : s->ny - s->y0);
    status = mpi_collective_status(s->comm, allocate(s, alloc_local));
    if (status == IM_OK)
        status = mpi_collective_status(s->comm, make_plans(s));
    if (status == IM_OK)
        status = mpi_collective_status(s->comm, plan_preconditioner(s));
    if (status != IM_OK)
        return status;
    share_rows(s);
    compute_spectrum(s);
    compute_preconditioner(s);
    s->k0 = im_influence_square(0, 0, s->delta, s->plan.options.e_star);
    return IM_OK;
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
    /* No cascade start: its coarse levels would each need their own decomposition and FFTW-MPI plans
     * (docs/mpi.md); cold starts are the local (Winkler) guess. */
    o.cascade = 0;
    *s = (im_mpi_solver){.nx = nx, .ny = ny, .px = 2 * nx, .py = 2 * ny, .delta = delta};
    s->plan = (im_solver_plan){.engine = &solver_engine_mpi, .mpi = s, .nx = nx, .ny = ny, .px = 2 * nx,
                               .py = 2 * ny, .delta = delta, .options = o, .kernel = &s->k0, .direct_limit = 0};
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
    fft_planner_lock();
    if (s->forward)
        fftw_destroy_plan(s->forward);
    if (s->backward)
        fftw_destroy_plan(s->backward);
    if (s->precondition_forward)
        fftw_destroy_plan(s->precondition_forward);
    if (s->precondition_backward)
        fftw_destroy_plan(s->precondition_backward);
    fft_planner_unlock();
    fftw_free(s->precondition_buffer);
    fftw_free(s->inverse_spectrum);
    free(s->preconditioned);
    fftw_free(s->buffer);
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

void mpi_convolve(im_mpi_solver *s, const double *pressure, double *displacement)
{
    const size_t stride = padded_stride(s);
    const int nx = s->nx;
    /* every padded row is rewritten: the c2r transform leaves garbage in the padding */
#pragma omp parallel for schedule(static)
    for (ptrdiff_t r = 0; r < s->local_n0; ++r) {
        double *row = s->buffer + (size_t)r * stride;
        if (r < s->rows) {
            memcpy(row, pressure + (size_t)r * nx, sizeof(double) * nx);
            memset(row + nx, 0, sizeof(double) * (stride - nx));
        } else
            memset(row, 0, sizeof(double) * stride);
    }
    fftw_execute(s->forward);
    fftw_complex *modes = (fftw_complex *)s->buffer;
#pragma omp parallel for schedule(static)
    for (size_t k = 0; k < (size_t)s->local_n1 * s->py; ++k) {
        modes[k][0] *= s->spectrum[k];
        modes[k][1] *= s->spectrum[k];
    }
    fftw_execute(s->backward);
#pragma omp parallel for schedule(static)
    for (int r = 0; r < s->rows; ++r)
        memcpy(displacement + (size_t)r * nx, s->buffer + (size_t)r * stride, sizeof(double) * nx);
}
