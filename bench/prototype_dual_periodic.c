/* Issue 33, sixth step: a prototype measured and dropped (docs/benchmarks.md, "The dual (gap) iteration"); kept
 * in history only, removed by the next commit. Build: gcc -O2 -Ibench -Iinclude bench/prototype_dual_periodic.c
 * -Lbuild -lindentmap -lfftw3 -lm; run: ./a.out N TOL LEAD (CASCADE=1 for the coarse start, TRACE=1 per step). */
/* Prototype (not project code): Polonsky-Keer on the dual variable (the gap) for a periodic cell under
 * mean-pressure control, preconditioned by K (the exact inverse of M = E*|q|/2 on the whole cell).
 * Counts M pairs (the operator) and K pairs (the preconditioner); the primal stopping rule is evaluated
 * with extra uncounted transforms. */
#include "bench_recipe.h"
#include "indentmap/solver.h"

#include <fftw3.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct ops {
    int n;
    size_t count, modes_count;
    double *in;
    fftw_complex *modes;
    fftw_plan forward, backward;
    double *k_spec, *m_spec;
} ops;

static long k_pairs, m_pairs;

static ops ops_create(int n, double kzero)
{
    ops o = {.n = n, .count = (size_t)n * n, .modes_count = (size_t)n * (n / 2 + 1)};
    o.in = fftw_malloc(sizeof(double) * o.count);
    o.modes = fftw_malloc(sizeof(fftw_complex) * o.modes_count);
    o.forward = fftw_plan_dft_r2c_2d(n, n, o.in, o.modes, FFTW_ESTIMATE);
    o.backward = fftw_plan_dft_c2r_2d(n, n, o.modes, o.in, FFTW_ESTIMATE);
    o.k_spec = malloc(sizeof(double) * o.modes_count);
    o.m_spec = malloc(sizeof(double) * o.modes_count);
    const double scale = 1.0 / (double)o.count, step = 2 * M_PI / n;
    for (int ky = 0; ky < n; ++ky)
        for (int kx = 0; kx <= n / 2; ++kx) {
            const double sy = ky <= n / 2 ? ky : ky - n;
            const double q = hypot(kx * step, sy * step);
            const size_t k = (size_t)ky * (n / 2 + 1) + kx;
            o.k_spec[k] = q > 0 ? 2.0 / q * scale : kzero * scale;
            o.m_spec[k] = q > 0 ? q / 2.0 * scale : 0.0;
        }
    return o;
}

static void apply(ops *o, const double *x, double *y, const double *spec)
{
    memcpy(o->in, x, sizeof(double) * o->count);
    fftw_execute(o->forward);
    for (size_t k = 0; k < o->modes_count; ++k) {
        o->modes[k][0] *= spec[k];
        o->modes[k][1] *= spec[k];
    }
    fftw_execute(o->backward);
    memcpy(y, o->in, sizeof(double) * o->count);
}

/* The project's stopping rule on p+ = max(p, 0) scaled to the load: max(rms gap on I_c, largest
 * penetration) / approach, and the approach. */
static double primal_residual(ops *o, const double *p, const double *g0, double mean_pressure, double *work,
                              double *work2, double *approach, long *contact)
{
    double sum = 0;
    for (size_t i = 0; i < o->count; ++i) {
        work[i] = p[i] > 0 ? p[i] : 0;
        sum += work[i];
    }
    const double s = mean_pressure * o->count / sum;
    for (size_t i = 0; i < o->count; ++i)
        work[i] *= s;
    apply(o, work, work2, o->k_spec);
    double wsum = 0;
    long c = 0;
    for (size_t i = 0; i < o->count; ++i)
        if (work[i] > 0) {
            wsum += work2[i] + g0[i];
            ++c;
        }
    const double w = wsum / c;
    double sq = 0, pen = 0;
    for (size_t i = 0; i < o->count; ++i) {
        const double g = work2[i] + g0[i] - w;
        if (work[i] > 0)
            sq += g * g;
        else if (-g > pen)
            pen = -g;
    }
    *approach = w;
    *contact = c;
    return fmax(sqrt(sq / c), pen) / w;
}

/* p = M (g - g0) + mean pressure */
static void pressure_of(ops *o, const double *g, const double *g0, double mean_pressure, double *p, double *work)
{
    for (size_t i = 0; i < o->count; ++i)
        work[i] = g[i] - g0[i];
    apply(o, work, p, o->m_spec);
    for (size_t i = 0; i < o->count; ++i)
        p[i] += mean_pressure;
    ++m_pairs;
}


static double mean_over(const double *x, const unsigned char *set, size_t count)
{
    double s = 0;
    long c = 0;
    for (size_t i = 0; i < count; ++i)
        if (set[i]) {
            s += x[i];
            ++c;
        }
    return c ? s / c : 0;
}

/* the project's rule under displacement control at approach w, on p = max(m + lambda, 0) */
static double primal_residual_gap(ops *o, const double *gap, const double *m, double lambda, const double *g0, double w, double *work,
                                  double *work2, long *contact, double *load)
{
    double sum = 0;
    for (size_t i = 0; i < o->count; ++i) {
        work[i] = gap[i] > 0 ? 0 : fmax(m[i] + lambda, 0);
        sum += work[i];
    }
    *load = sum;
    apply(o, work, work2, o->k_spec);
    double sq = 0, pen = 0;
    long c = 0;
    for (size_t i = 0; i < o->count; ++i) {
        const double g = work2[i] + g0[i] - w;
        if (work[i] > 0) {
            sq += g * g;
            ++c;
        } else if (-g > pen)
            pen = -g;
    }
    *contact = c;
    return fmax(sqrt(sq / (c ? c : 1)), pen) / w;
}

int main(int argc, char **argv)
{
    int n = argc > 1 ? atoi(argv[1]) : 256;
    double tol = argc > 2 ? atof(argv[2]) : 1e-8;
    double lead = argc > 3 ? atof(argv[3]) : 0; /* 0: join every tension patch each step */
    const double mean_pressure = 0.004;
    im_field *surface;
    bench_paper_surface(n, &surface);
    const size_t count = (size_t)n * n;
    double *g0 = malloc(sizeof(double) * count), *g = malloc(sizeof(double) * count),
           *mg = malloc(sizeof(double) * count), *mg0 = malloc(sizeof(double) * count),
           *m = malloc(sizeof(double) * count), *r = malloc(sizeof(double) * count),
           *z = malloc(sizeof(double) * count), *t = calloc(count, sizeof(double)),
           *mt = malloc(sizeof(double) * count), *w1 = malloc(sizeof(double) * count),
           *w2 = malloc(sizeof(double) * count);
    unsigned char *free_set = calloc(count, 1);
    bench_cell_gap(surface, g0);
    ops o = ops_create(n, 0);
    /* the reference: the library's load-controlled solve at tol 1e-10, and its approach */
    im_solver_options opt = im_solver_options_default();
    opt.periodic = 1;
    opt.tol = 1e-10;
    im_solver_plan *plan;
    im_solver_plan_create(n, n, 1.0, &opt, &plan);
    double *pr = calloc(count, sizeof(double)), *ur = malloc(sizeof(double) * count);
    im_solve_result sr;
    im_solver_solve(plan, g0, IM_CONTROL_LOAD, mean_pressure * count, pr, ur, &sr);
    const double w = sr.approach;
    double g0sum = 0;
    for (size_t i = 0; i < count; ++i)
        g0sum += g0[i];
    const double gap_total = g0sum - w * count; /* sum of g at the approach (mean u = 0) */
    apply(&o, g0, mg0, o.m_spec);
    /* start: the rigid gap at w, or (CASCADE) the gap of the coarse answer prolonged, scaled to the mean gap */
    double gs = 0;
    if (getenv("CASCADE")) {
        const int c = n / 2;
        double *cg0 = malloc(sizeof(double) * c * c), *cp = calloc((size_t)c * c, sizeof(double)),
               *cu = malloc(sizeof(double) * c * c);
        for (int y = 0; y < c; ++y)
            for (int x = 0; x < c; ++x)
                cg0[y * c + x] = 0.25 * (g0[(2 * y) * n + 2 * x] + g0[(2 * y) * n + 2 * x + 1] +
                                         g0[(2 * y + 1) * n + 2 * x] + g0[(2 * y + 1) * n + 2 * x + 1]);
        im_solver_options co = im_solver_options_default();
        co.periodic = 1;
        co.tol = 1e-4;
        im_solver_plan *cplan;
        im_solver_plan_create(c, c, 2.0, &co, &cplan);
        im_solve_result cr;
        im_solver_solve(cplan, cg0, IM_CONTROL_DISPLACEMENT, w, cp, cu, &cr);
        printf("  coarse: %d iterations (+%d coarser)\n", cr.iterations, cr.coarse_iterations);
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                w1[y * n + x] = cp[(y / 2) * c + x / 2];
        apply(&o, w1, w2, o.k_spec);
        ++k_pairs;
        for (size_t i = 0; i < count; ++i) {
            g[i] = fmax(w2[i] + g0[i] - w, 0);
            gs += g[i];
        }
    } else
        for (size_t i = 0; i < count; ++i) {
            g[i] = fmax(g0[i] - w, 0);
            gs += g[i];
        }
    for (size_t i = 0; i < count; ++i)
        g[i] *= gap_total / gs;
    apply(&o, g, mg, o.m_spec);
    ++m_pairs;
    int restart = 1, it = 0, joins = 0;
    double rz_old = 1, res = 1, load = 0;
    long contact = 0;
    for (;;) {
        for (size_t i = 0; i < count; ++i)
            m[i] = mg[i] - mg0[i];
        /* lambda from the open set: p = 0 there on average */
        for (size_t i = 0; i < count; ++i)
            free_set[i] = g[i] > 0;
        double lambda = -mean_over(m, free_set, count);
        res = primal_residual_gap(&o, g, m, lambda, g0, w, w1, w2, &contact, &load);
        if (getenv("TRACE"))
            printf("it %d residual %.3e contact %ld load %.6g\n", it, res, contact, load);
        if (res <= tol || it >= 3000)
            break;
        ++it;
        double sq = 0, tension = 0;
        long open = 0;
        for (size_t i = 0; i < count; ++i)
            if (g[i] > 0) {
                sq += (m[i] + lambda) * (m[i] + lambda);
                ++open;
            } else if (-(m[i] + lambda) > tension)
                tension = -(m[i] + lambda);
        const int join = lead <= 0 || tension > lead * sqrt(sq / (open ? open : 1));
        long joined = 0;
        static unsigned char *previous;
        if (!previous)
            previous = calloc(count, 1);
        for (size_t i = 0; i < count; ++i) {
            const unsigned char f = g[i] > 0 || (join && m[i] + lambda < 0);
            joined += f && !previous[i];
            free_set[i] = previous[i] = f;
        }
        if (joined && join) {
            restart = 1;
            ++joins;
        }
        const double mean_m = mean_over(m, free_set, count);
        for (size_t i = 0; i < count; ++i)
            r[i] = free_set[i] ? m[i] - mean_m : 0;
        apply(&o, r, z, o.k_spec);
        ++k_pairs;
        for (size_t i = 0; i < count; ++i)
            z[i] = free_set[i] ? z[i] : 0;
        const double mean_z = mean_over(z, free_set, count);
        double rz = 0;
        for (size_t i = 0; i < count; ++i)
            if (free_set[i]) {
                z[i] -= mean_z;
                rz += r[i] * z[i];
            }
        const double beta = restart ? 0 : rz / rz_old;
        for (size_t i = 0; i < count; ++i)
            t[i] = free_set[i] ? z[i] + beta * t[i] : 0;
        apply(&o, t, mt, o.m_spec);
        ++m_pairs;
        double rt = 0, mtt = 0;
        for (size_t i = 0; i < count; ++i) {
            rt += r[i] * t[i];
            mtt += mt[i] * t[i];
        }
        double tau = rt / mtt;
        if (!(tau > 0)) {
            restart = 1;
            continue;
        }
        long clipped = 0;
        double total = 0;
        for (size_t i = 0; i < count; ++i) {
            g[i] -= tau * t[i];
            mg[i] -= tau * mt[i];
            if (g[i] < 0) {
                g[i] = 0;
                ++clipped;
            }
            total += g[i];
        }
        const double scale = gap_total / total;
        for (size_t i = 0; i < count; ++i)
            g[i] *= scale;
        if (clipped) {
            apply(&o, g, mg, o.m_spec);
            ++m_pairs;
        } else
            for (size_t i = 0; i < count; ++i)
                mg[i] *= scale;
        restart = 0;
        rz_old = rz;
    }
    printf("dual mean-gap n %d tol %g lead %g: iterations %d (joins %d), M pairs %ld, K pairs %ld, residual %.3e, "
           "contact %ld, load %.12g\n",
           n, tol, lead, it, joins, m_pairs, k_pairs, res, contact, load);
    long differ = 0;
    double perr = 0, pmax = 0, lambda = 0;
    for (size_t i = 0; i < count; ++i)
        free_set[i] = g[i] > 0;
    for (size_t i = 0; i < count; ++i)
        m[i] = mg[i] - mg0[i];
    lambda = -mean_over(m, free_set, count);
    for (size_t i = 0; i < count; ++i) {
        const double pp = g[i] > 0 ? 0 : fmax(m[i] + lambda, 0);
        differ += (pp > 0) != (pr[i] > 0);
        perr = fmax(perr, fabs(pp - pr[i]));
        pmax = fmax(pmax, pr[i]);
    }
    printf("  reference (load control, tol 1e-10, %d iterations): load %.12g (rel. diff %.2e), contact %ld, "
           "differing %ld, max |dp| / max p %.2e\n",
           sr.iterations, sr.load, fabs(load / sr.load - 1), sr.contact_patches, differ, perr / pmax);
    return 0;
}
