/* indentmap theory: the paper's contact-area theory for a cone, and its local density of contact
 * for a sphere or a flat punch, as a table or CSV; k of eq. (2) over a periodic history (theory_fit_k.c). */
#include "cli/cli.h"

#include "indentmap/status.h"
#include "indentmap/theory.h"

#include <math.h>
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Longest --slope list and --rho sweep accepted. */
enum { MAX_VALUES = 100000 };
/* Points of the --gamma grid r/a = 0, 0.01, ..., 1. */
enum { GAMMA_POINTS = 101 };
/* Width of a column in the aligned (non-CSV) format. */
enum { COLUMN_WIDTH = 16 };

static void usage(FILE *stream)
{
    fprintf(stream, "usage: indentmap theory --alpha DEG --slope S1,S2,... [OPTIONS]\n"
                    "       indentmap theory --rho MIN:MAX:N [OPTIONS]\n"
                    "       indentmap theory --punch sphere|flat --radius R --load N --slope S1,S2,... [OPTIONS]\n"
                    "       indentmap theory --punch sphere|flat --rho MIN:MAX:N [OPTIONS]\n"
                    "       indentmap theory --fit-k DIR/history.csv [--format table|csv]\n\n"
                    "The contact area of a rough elastic half-space under a cone (the paper's section 2.1):\n"
                    "rho_c = k cot(alpha) / (2 h'rms) (eq. 7), the constant-density ratio A/A_cone of eq. (6)\n"
                    "and the variable-density ratio of eq. (12), or with --gamma the local contact density\n"
                    "gamma(r/a) of eqs. (10)-(11) on r/a = 0, 0.01, ..., 1 (one column per slope or rho_c).\n"
                    "For a sphere (Hertz) or a flat punch (Boussinesq) the same local density with that punch's\n"
                    "smooth pressure: rho = p_m / p_rough with the smooth mean pressure p_m = N / A_smooth, the\n"
                    "constant-density ratio erf(sqrt(pi)/2 rho) (eq. 3 for the sphere) and the integral of gamma.\n\n"
                    "  --punch cone|sphere|flat  the punch (default cone)\n"
                    "  --radius R             sphere radius or flat punch radius, in grid spacings (with --slope)\n"
                    "  --load N               load in E* delta^2 (E* = 1; with --slope, sphere and flat only)\n"
                    "  --alpha DEG            cone semi-opening angle in degrees, 0 < DEG < 90 (the paper: 80)\n"
                    "  --slope LIST           comma-separated h'rms values >= 0 (0: smooth, rho_c = inf)\n"
                    "  --rho MIN:MAX:N        N values of rho_c (rho = p_m / p_rough for sphere and flat),\n"
                    "                         log-spaced from MIN to MAX (0 < MIN <= MAX)\n"
                    "  --gamma                print gamma(r/a) instead of the area ratios\n"
                    "  --format table|csv     aligned table (default) or CSV; CSV columns are\n"
                    "                         slope,rho_c,area_ratio_eq6,area_ratio_eq12 (no slope with --rho);\n"
                    "                         sphere: slope,rho,area_ratio_eq3,area_ratio_gamma; flat:\n"
                    "                         slope,rho,area_ratio_constant,area_ratio_gamma;\n"
                    "                         or r_over_a,gamma_slope_S,... (gamma_rho_c_R,...) with --gamma\n"
                    "  --normalisation pr|mg  the erf law's pressure: pr (default) p_PR = 2 p_rough / sqrt(pi),\n"
                    "                         the paper's; mg p_MG = E* h'rms / sqrt(2), Manners and Greenwood's,\n"
                    "                         used in eqs. (6), (10) and (12) alike\n"
                    "  --k K                  p_rough = h'rms E* / K, eq. (2), 1e-6 <= K <= 1e6 (default 2)\n"
                    "  --fit-k HISTORY        k of eq. (2) fitted to the history of a periodic indent run under\n"
                    "                         the rigid flat (A/A0 against p_m / (h'rms E*)), with the cell, h'rms\n"
                    "                         and E* of the run.json beside it: the k line that run printed, or\n"
                    "                         with --format csv slope_rms,points,k,k_error,... (17 digits; the\n"
                    "                         columns of a scene's k_fit.csv)\n");
}

typedef struct theory_options {
    enum im_punch_kind punch;
    double alpha, radius, load;
    int alpha_given, radius_given, load_given;
    const char *slope_list, *rho_sweep, *fit_k;
    int gamma, csv;
    int others; /* options other than --fit-k and --format */
    double k;
    im_theory_normalisation normalisation;
} theory_options;

/* The columns' inputs: slopes (with alpha) or rho_c values, and the erf scale of each. */
typedef struct theory_columns {
    int count, by_slope;
    double *slope, *rho_c, *beta;
} theory_columns;

enum {
    OPT_ALPHA = 256,
    OPT_SLOPE,
    OPT_RHO,
    OPT_GAMMA,
    OPT_FORMAT,
    OPT_NORMALISATION,
    OPT_K,
    OPT_PUNCH,
    OPT_RADIUS,
    OPT_LOAD,
    OPT_FIT_K,
    OPT_HELP
};

static const struct option LONG_OPTIONS[] = {{"alpha", required_argument, 0, OPT_ALPHA},
                                             {"slope", required_argument, 0, OPT_SLOPE},
                                             {"rho", required_argument, 0, OPT_RHO},
                                             {"gamma", no_argument, 0, OPT_GAMMA},
                                             {"format", required_argument, 0, OPT_FORMAT},
                                             {"normalisation", required_argument, 0, OPT_NORMALISATION},
                                             {"k", required_argument, 0, OPT_K},
                                             {"punch", required_argument, 0, OPT_PUNCH},
                                             {"radius", required_argument, 0, OPT_RADIUS},
                                             {"load", required_argument, 0, OPT_LOAD},
                                             {"fit-k", required_argument, 0, OPT_FIT_K},
                                             {"help", no_argument, 0, OPT_HELP},
                                             {0, 0, 0, 0}};

static int parse_punch(const char *text, enum im_punch_kind *out)
{
    const enum im_punch_kind kinds[] = {IM_PUNCH_CONE, IM_PUNCH_SPHERE, IM_PUNCH_FLAT};
    for (int i = 0; i < 3; ++i)
        if (strcmp(text, im_punch_name(kinds[i])) == 0) {
            *out = kinds[i];
            return 0;
        }
    fprintf(stderr, "indentmap: --punch: '%s': expected 'cone', 'sphere' or 'flat'\n", text);
    return -1;
}

static int parse_choice(const char *option, const char *text, const char *first, const char *second, int *out)
{
    if (strcmp(text, first) == 0 || strcmp(text, second) == 0) {
        *out = strcmp(text, second) == 0;
        return 0;
    }
    fprintf(stderr, "indentmap: %s: '%s': expected '%s' or '%s'\n", option, text, first, second);
    return -1;
}

static int apply_option(int code, const char *arg, void *state)
{
    theory_options *o = state;
    int choice;
    o->others += code != OPT_FIT_K && code != OPT_FORMAT;
    switch (code) {
    case OPT_ALPHA:
        o->alpha_given = 1;
        if (cli_parse_double("--alpha", arg, 0.0, 90.0, &o->alpha) != 0)
            return -1;
        if (o->alpha == 0.0 || o->alpha == 90.0) {
            fprintf(stderr, "indentmap: --alpha = %g: expected 0 < alpha < 90 degrees\n", o->alpha);
            return -1;
        }
        return 0;
    case OPT_SLOPE: o->slope_list = arg; return 0;
    case OPT_RHO: o->rho_sweep = arg; return 0;
    case OPT_GAMMA: o->gamma = 1; return 0;
    case OPT_FORMAT: return parse_choice("--format", arg, "table", "csv", &o->csv);
    case OPT_FIT_K: o->fit_k = arg; return 0;
    case OPT_NORMALISATION:
        if (parse_choice("--normalisation", arg, "pr", "mg", &choice) != 0)
            return -1;
        o->normalisation = choice ? IM_THEORY_NORMALISATION_MG : IM_THEORY_NORMALISATION_PR;
        return 0;
    case OPT_K: return cli_parse_double("--k", arg, 1e-6, 1e6, &o->k);
    case OPT_PUNCH: return parse_punch(arg, &o->punch);
    case OPT_RADIUS: o->radius_given = 1; return cli_parse_double("--radius", arg, 1e-300, 1e300, &o->radius);
    case OPT_LOAD: o->load_given = 1; return cli_parse_double("--load", arg, 1e-300, 1e300, &o->load);
    default: return -1;
    }
}

/* What is missing or superfluous for a cone, NULL if nothing. */
static const char *cone_problem(const theory_options *o)
{
    if (o->radius_given || o->load_given)
        return "--radius and --load are for --punch sphere or flat (a cone's rho_c needs no load)";
    if (o->slope_list && !o->alpha_given)
        return "--slope needs --alpha";
    if (o->rho_sweep && o->alpha_given)
        return "--alpha has no effect with --rho (rho_c already includes the cone)";
    return NULL;
}

/* The same for a sphere or a flat punch. */
static const char *round_punch_problem(const theory_options *o)
{
    if (o->alpha_given)
        return "--alpha is for the cone; a sphere or a flat punch takes --radius";
    if (o->slope_list && !(o->radius_given && o->load_given))
        return "--slope with --punch sphere or flat needs --radius and --load";
    if (o->rho_sweep && (o->radius_given || o->load_given))
        return "--radius and --load have no effect with --rho (rho = p_m / p_rough already includes them)";
    return NULL;
}

/* 1 after --help, 0 when the options are complete and consistent, -1 after printing an error. */
static int parse_options(int argc, char **argv, theory_options *o)
{
    int parsed = cli_parse_options(argc, argv, LONG_OPTIONS, OPT_HELP, usage, apply_option, o);
    if (parsed != 0)
        return parsed;
    if (optind < argc) {
        fprintf(stderr, "indentmap: theory: unexpected argument '%s'\n", argv[optind]);
        return -1;
    }
    const char *problem = NULL;
    if (o->fit_k)
        problem = o->others ? "--fit-k takes no other option than --format (the run.json beside the history holds "
                              "the rest)"
                            : NULL;
    else if (!o->slope_list == !o->rho_sweep)
        problem = "give either --slope (with --alpha, or --radius and --load) or --rho";
    else
        problem = o->punch == IM_PUNCH_CONE ? cone_problem(o) : round_punch_problem(o);
    if (!problem)
        return 0;
    fprintf(stderr, "indentmap: theory: %s\n", problem);
    return -1;
}

static void columns_free(theory_columns *c)
{
    free(c->slope);
    free(c->rho_c);
    free(c->beta);
}

static int columns_alloc(theory_columns *c, int count)
{
    c->count = count;
    c->slope = calloc((size_t)count, sizeof *c->slope);
    c->rho_c = calloc((size_t)count, sizeof *c->rho_c);
    c->beta = calloc((size_t)count, sizeof *c->beta);
    if (c->slope && c->rho_c && c->beta)
        return 0;
    fprintf(stderr, "indentmap: theory: out of memory for %d values\n", count);
    return -1;
}

/* "S1,S2,...": each a finite h'rms >= 0. */
static int parse_slopes(const char *list, theory_columns *c)
{
    int count = 1;
    for (const char *p = list; *p; ++p)
        count += *p == ',';
    if (count > MAX_VALUES) {
        fprintf(stderr, "indentmap: --slope: %d values: expected at most %d\n", count, MAX_VALUES);
        return -1;
    }
    if (columns_alloc(c, count) != 0)
        return -1;
    c->by_slope = 1;
    const char *item = list;
    for (int i = 0; i < count; ++i) {
        size_t length = strcspn(item, ",");
        char text[64];
        if (length >= sizeof text) {
            fprintf(stderr, "indentmap: --slope: '%.*s...' is too long for a number\n", 20, item);
            return -1;
        }
        memcpy(text, item, length);
        text[length] = '\0';
        if (cli_parse_double("--slope", text, 0.0, 1e6, &c->slope[i]) != 0)
            return -1;
        item += length + 1;
    }
    return 0;
}

/* "MIN:MAX:N": N log-spaced values of rho_c from MIN to MAX. */
static int parse_rho_sweep(const char *sweep, theory_columns *c)
{
    char text[128];
    if (strlen(sweep) >= sizeof text) {
        fprintf(stderr, "indentmap: --rho: '%.20s...' is too long: expected MIN:MAX:N\n", sweep);
        return -1;
    }
    strcpy(text, sweep);
    char *first_colon = strchr(text, ':'), *second_colon = first_colon ? strchr(first_colon + 1, ':') : NULL;
    if (!second_colon || strchr(second_colon + 1, ':')) {
        fprintf(stderr, "indentmap: --rho: '%s': expected MIN:MAX:N, e.g. 0.1:100:50\n", sweep);
        return -1;
    }
    *first_colon = *second_colon = '\0';
    double lo, hi;
    int count;
    if (cli_parse_double("--rho", text, 1e-300, 1e300, &lo) != 0 ||
        cli_parse_double("--rho", first_colon + 1, 1e-300, 1e300, &hi) != 0 ||
        cli_parse_int("--rho", second_colon + 1, 1, MAX_VALUES, &count) != 0)
        return -1;
    if (hi < lo || (count == 1 && hi != lo)) {
        fprintf(stderr, "indentmap: --rho: '%s': expected MIN <= MAX, and MIN = MAX when N = 1\n", sweep);
        return -1;
    }
    if (columns_alloc(c, count) != 0)
        return -1;
    for (int i = 0; i < count; ++i)
        c->rho_c[i] = count == 1 ? lo : lo * pow(hi / lo, (double)i / (count - 1));
    return 0;
}

/* rho = p_m / p_rough of a sphere or flat punch at the load (+INFINITY on a smooth surface). */
static int punch_rho(const theory_options *o, const im_theory_interface *rough, double *rho)
{
    double p_mean, p_rough;
    int status = im_theory_punch_mean_pressure(o->punch, o->radius, o->load, rough->e_star, &p_mean);
    if (status == IM_OK)
        status = im_theory_p_rough(rough, &p_rough);
    if (status == IM_OK)
        *rho = p_rough > 0.0 ? p_mean / p_rough : INFINITY;
    return status;
}

/* rho_c (from the slopes) and the erf scale beta of every column. */
static int columns_evaluate(const theory_options *o, theory_columns *c)
{
    int status = IM_OK;
    for (int i = 0; i < c->count && status == IM_OK; ++i) {
        if (c->by_slope) {
            im_theory_interface rough = {c->slope[i], 1.0, o->k, o->normalisation};
            status = o->punch == IM_PUNCH_CONE ? im_theory_cone_rho(&rough, o->alpha, &c->rho_c[i])
                                               : punch_rho(o, &rough, &c->rho_c[i]);
        }
        if (status == IM_OK)
            status = im_theory_erf_scale(c->rho_c[i], o->normalisation, o->k, &c->beta[i]);
    }
    return status;
}

static void print_cell(const char *text, int first, int csv)
{
    if (csv)
        printf("%s%s", first ? "" : ",", text);
    else
        printf("%s%*s", first ? "" : " ", COLUMN_WIDTH, text);
}

static void print_number(double value, const char *table_format, int first, int csv)
{
    char text[64];
    snprintf(text, sizeof text, csv ? "%.12g" : table_format, value);
    print_cell(text, first, csv);
}

/* A ratio in [0, 1]: six decimals, but six significant digits below 1e-3, where the decimals would keep
 * too few or none (eq. (6) at rho_c 1.8e-7, h'rms 1e6: "0.000000" for 1.76327e-07). */
static void print_ratio(double value, int first, int csv)
{
    print_number(value, value != 0 && fabs(value) < 1e-3 ? "%.6g" : "%.6f", first, csv);
}

static void print_settings(const theory_options *o)
{
    if (o->csv)
        return;
    printf("# ");
    if (o->punch != IM_PUNCH_CONE)
        printf("punch %s, ", im_punch_name(o->punch));
    if (o->slope_list && o->punch == IM_PUNCH_CONE)
        printf("alpha = %g degrees, ", o->alpha);
    else if (o->slope_list)
        printf("radius = %g delta, load = %g E* delta^2, ", o->radius, o->load);
    printf("k = %g, normalisation %s\n", o->k,
           o->normalisation == IM_THEORY_NORMALISATION_PR ? "pr (p_PR = 2 p_rough / sqrt(pi))"
                                                          : "mg (p_MG = E* h'rms / sqrt(2))");
}

static int print_area_ratios(const theory_options *o, const theory_columns *c)
{
    /* the cone's columns keep the paper's equation numbers */
    static const char *const labels[3][3] = {{"rho_c", "area_ratio_eq6", "area_ratio_eq12"},
                                             {"rho", "area_ratio_eq3", "area_ratio_gamma"},
                                             {"rho", "area_ratio_constant", "area_ratio_gamma"}};
    if (c->by_slope)
        print_cell("slope", 1, o->csv);
    for (int k = 0; k < 3; ++k)
        print_cell(labels[o->punch][k], k == 0 && !c->by_slope, o->csv);
    printf("\n");
    for (int i = 0; i < c->count; ++i) {
        double constant, variable;
        int status = im_theory_cone_area_ratio_constant(c->beta[i], &constant);
        if (status == IM_OK)
            status = im_theory_punch_area_ratio(o->punch, c->beta[i], &variable);
        if (status != IM_OK)
            return status;
        if (c->by_slope)
            print_number(c->slope[i], "%g", 1, o->csv);
        print_number(c->rho_c[i], "%.6g", !c->by_slope, o->csv);
        print_ratio(constant, 0, o->csv);
        print_ratio(variable, 0, o->csv);
        printf("\n");
    }
    return IM_OK;
}

static int print_contact_density(const theory_options *o, const theory_columns *c)
{
    print_cell("r_over_a", 1, o->csv);
    for (int i = 0; i < c->count; ++i) {
        char label[64];
        if (c->by_slope)
            snprintf(label, sizeof label, "gamma_slope_%g", c->slope[i]);
        else
            snprintf(label, sizeof label, o->punch == IM_PUNCH_CONE ? "gamma_rho_c_%g" : "gamma_rho_%g", c->rho_c[i]);
        print_cell(label, 0, o->csv);
    }
    printf("\n");
    for (int j = 0; j < GAMMA_POINTS; ++j) {
        double r_over_a = (double)j / (GAMMA_POINTS - 1);
        print_number(r_over_a, "%.2f", 1, o->csv);
        for (int i = 0; i < c->count; ++i) {
            double gamma;
            int status = im_theory_punch_contact_density(o->punch, c->beta[i], r_over_a, &gamma);
            if (status != IM_OK)
                return status;
            print_ratio(gamma, 0, o->csv);
        }
        printf("\n");
    }
    return IM_OK;
}

int cli_theory(int argc, char **argv)
{
    theory_options o = {.punch = IM_PUNCH_CONE,
                        .k = IM_THEORY_K_DEFAULT,
                        .normalisation = IM_THEORY_NORMALISATION_PR};
    int parsed = parse_options(argc, argv, &o);
    if (parsed != 0)
        return parsed > 0 ? CLI_EXIT_OK : CLI_EXIT_USAGE;
    if (o.fit_k)
        return cli_theory_fit_k(o.fit_k, o.csv);
    theory_columns columns = {0};
    int parsed_values = o.slope_list ? parse_slopes(o.slope_list, &columns) : parse_rho_sweep(o.rho_sweep, &columns);
    if (parsed_values != 0) {
        columns_free(&columns);
        return CLI_EXIT_USAGE;
    }
    int status = columns_evaluate(&o, &columns);
    if (status == IM_OK) {
        print_settings(&o);
        status = o.gamma ? print_contact_density(&o, &columns) : print_area_ratios(&o, &columns);
    }
    columns_free(&columns);
    return status == IM_OK ? CLI_EXIT_OK : cli_report(status);
}
