/* The periodic mode's pieces both front ends share (front.h): the cell, the rigid flat pressed on it,
 * the edge-mismatch test of a surface given as one period, and k of eq. (2) fitted to a history, with its
 * printed line and CSV row. */
#include "front/front.h"

#include "indentmap/status.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

double periodic_cell_area(const im_field *surface)
{
    return (double)surface->nx * surface->ny * surface->delta * surface->delta;
}

/* A flat punch wider than the cell's diagonal covers every nearest image of the cell. */
im_indenter periodic_rigid_flat(const im_field *surface)
{
    return im_indenter_flat(2.0 * hypot(surface->nx, surface->ny) * surface->delta);
}

int periodic_edge_mismatch(const im_field *s, double *edge_rms, double *inner_rms)
{
    double edge = 0, inner = 0;
    long edges = 0, inners = 0;
    for (int iy = 0; iy < s->ny; ++iy)
        for (int ix = 0; ix < s->nx; ++ix) {
            const double h = s->data[(size_t)iy * s->nx + ix];
            const double dx = s->data[(size_t)iy * s->nx + (ix + 1) % s->nx] - h;
            const double dy = s->data[(size_t)((iy + 1) % s->ny) * s->nx + ix] - h;
            if (ix + 1 == s->nx)
                edge += dx * dx, ++edges;
            else
                inner += dx * dx, ++inners;
            if (iy + 1 == s->ny)
                edge += dy * dy, ++edges;
            else
                inner += dy * dy, ++inners;
        }
    *edge_rms = edges ? sqrt(edge / edges) : 0;
    *inner_rms = inners ? sqrt(inner / inners) : 0;
    return *edge_rms > PERIODIC_EDGE_RATIO * *inner_rms;
}

int periodic_warning(const im_field *surface, const char *name, char *text, size_t size)
{
    double edge, inner;
    if (!periodic_edge_mismatch(surface, &edge, &inner))
        return 0;
    snprintf(text, size,
             "warning: %s is not periodic: the steps across its edges have rms %.3g, %.3g times those inside it "
             "(%.3g); --periodic joins its edges as if they met. Use a periodic surface (indentmap surface "
             "generates them) or indent it on the half-space (no --periodic)",
             name, edge, edge / inner, inner);
    return 1;
}

int periodic_fit_k(const im_history_row *rows, int count, double cell_area, double slope_rms, double e_star,
                   periodic_k_fit *out)
{
    *out = (periodic_k_fit){.points = 0};
    if (!(slope_rms > 0))
        return im_fail(IM_EINVAL, "k of eq. (2): the surface's h'rms is %g: expected a rough surface (> 0)",
                       slope_rms);
    double *x = malloc(sizeof(double) * (size_t)(count + 1)), *area = malloc(sizeof(double) * (size_t)(count + 1));
    int status = x && area ? IM_OK : im_fail(IM_ENOMEM, "k of eq. (2) over %d steps", count);
    for (int i = 0; status == IM_OK && i < count; ++i) {
        if (!(rows[i].result.load > 0))
            continue;
        if (rows[i].result.area_ratio >= 1) {
            ++out->full_contact;
            continue;
        }
        x[out->points] = rows[i].result.load / cell_area / (slope_rms * e_star);
        area[out->points++] = rows[i].result.area_ratio;
    }
    if (status == IM_OK && out->points == 0)
        status = out->full_contact ? im_fail(IM_EINVAL,
                                             "k of eq. (2): every step with a positive load is in full contact "
                                             "(A/A0 = 1, %d step%s), which does not measure k: expected a step in "
                                             "partial contact (a smaller load or pressure)",
                                             out->full_contact, out->full_contact == 1 ? "" : "s")
                                   : im_fail(IM_EINVAL, "k of eq. (2): no step with a positive load");
    if (status == IM_OK)
        status = im_theory_fit_k(x, area, out->points, &out->fit);
    for (int i = 0; status == IM_OK && i < out->points; ++i) {
        out->pressure_ratio[0] = i ? fmin(out->pressure_ratio[0], x[i]) : x[i];
        out->pressure_ratio[1] = i ? fmax(out->pressure_ratio[1], x[i]) : x[i];
        out->area_fraction[0] = i ? fmin(out->area_fraction[0], area[i]) : area[i];
        out->area_fraction[1] = i ? fmax(out->area_fraction[1], area[i]) : area[i];
    }
    free(x);
    free(area);
    return status;
}

void periodic_k_fit_describe(const periodic_k_fit *k, double slope_rms, const char *slope_definition, char *text,
                             size_t size)
{
    const im_theory_k_fit *fit = &k->fit;
    char spread[64]; /* one point has no spread: its k_error 0 read as "+- 0.0000", an exact k */
    if (k->points > 1)
        snprintf(spread, sizeof spread, "+- %.4f over %d steps", fit->k_error, k->points);
    else
        snprintf(spread, sizeof spread, "from 1 step (no error estimate)");
    char left_out[96] = "";
    if (k->full_contact)
        snprintf(left_out, sizeof left_out,
                 "; %d step%s in full contact (A/A0 = 1) left out: they bound k, not measure it", k->full_contact,
                 k->full_contact == 1 ? "" : "s");
    snprintf(text, size,
             "k of eq. (2): %.4f %s (p_m / (h'rms E*) %.4g to %.4g, A/A0 %.4f to %.4f; "
             "h'rms %.6g, %s); slope through 0 over A/A0 <= 0.5: %.4f (%d step%s)%s",
             fit->k, spread, k->pressure_ratio[0], k->pressure_ratio[1], k->area_fraction[0], k->area_fraction[1],
             slope_rms, slope_definition, fit->k_linear, fit->linear_points, fit->linear_points == 1 ? "" : "s",
             left_out);
}

const char PERIODIC_K_COLUMNS[] = "points,k,k_error,rms_residual,k_linear,linear_points,pressure_ratio_min,"
                                  "pressure_ratio_max,area_fraction_min,area_fraction_max";

void periodic_k_fit_write_row(FILE *stream, const periodic_k_fit *k)
{
    fprintf(stream, "%d,%.17g,%.17g,%.17g,%.17g,%d,%.17g,%.17g,%.17g,%.17g\n", k->points, k->fit.k, k->fit.k_error,
            k->fit.rms_residual, k->fit.k_linear, k->fit.linear_points, k->pressure_ratio[0], k->pressure_ratio[1],
            k->area_fraction[0], k->area_fraction[1]);
}

json_t *periodic_k_fit_record(const periodic_k_fit *k, double slope_rms, const char *slope_definition)
{
    const im_theory_k_fit *fit = &k->fit;
    json_t *block = json_pack("{s:f, s:f, s:f, s:i, s:i, s:[f, f], s:[f, f], s:f, s:s}", "k", fit->k, "k_error",
                              fit->k_error, "rms_residual", fit->rms_residual, "points", k->points, "linear_points",
                              fit->linear_points, "pressure_ratio_range", k->pressure_ratio[0], k->pressure_ratio[1],
                              "area_fraction_range", k->area_fraction[0], k->area_fraction[1], "slope_rms", slope_rms,
                              "slope_rms_definition", slope_definition);
    if (block) {
        json_object_set_new(block, "k_linear", isfinite(fit->k_linear) ? json_real(fit->k_linear) : json_null());
        json_object_set_new(block, "full_contact_points", json_integer(k->full_contact));
    }
    return block;
}
