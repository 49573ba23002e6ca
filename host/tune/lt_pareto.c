/* lt_pareto.c - budget metrics, dominance, fronts and budgets of lanetrace tune (lt_pareto.h).
 * Host only.
 */
#include "tune/lt_pareto.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *const lt_metric_names[] = {"wrong", "rmse", "rel99", "psnr", "cycles", "bytes", NULL};

int lt_metric_higher_better(int m) { return m == LT_M_PSNR; }

int lt_metric_is_percent(int m) { return m == LT_M_WRONG || m == LT_M_REL99; }

int lt_metric_find(const char *name)
{
    int i;
    for (i = 0; lt_metric_names[i] != NULL; i++)
        if (strcmp(lt_metric_names[i], name) == 0)
            return i;
    return -1;
}

/* NaN is worse than any number. */
static int worse(double a, double b)
{
    if (isnan(a))
        return !isnan(b);
    if (isnan(b))
        return 0;
    return a > b;
}

int lt_pareto_dominates(const double *a, const double *b, int k)
{
    int i, strict = 0;
    for (i = 0; i < k; i++) {
        if (worse(a[i], b[i]))
            return 0;
        if (worse(b[i], a[i]))
            strict = 1;
    }
    return strict;
}

size_t lt_pareto_front(const double *obj, size_t n, int k, const unsigned char *include,
                       unsigned char *on_front)
{
    size_t i, j, m = 0;
    for (i = 0; i < n; i++) {
        int dom = 0;
        on_front[i] = 0;
        if (include != NULL && !include[i])
            continue;
        for (j = 0; j < n && !dom; j++)
            if (j != i && (include == NULL || include[j]) &&
                lt_pareto_dominates(obj + j * (size_t)k, obj + i * (size_t)k, k))
                dom = 1;
        if (!dom) {
            on_front[i] = 1;
            m++;
        }
    }
    return m;
}

/* ---- budgets ------------------------------------------------------------------------------- */

static void metric_list(char *buf, size_t n)
{
    size_t len = 0;
    int i;
    buf[0] = '\0';
    for (i = 0; lt_metric_names[i] != NULL && len < n; i++)
        len += (size_t)snprintf(buf + len, n - len, "%s%s", i ? ", " : "", lt_metric_names[i]);
}

/* One term "name OP number[%]" of length len at s. */
static int parse_term(const char *s, size_t len, lt_budget_term_t *t, lt_diag_t *diag)
{
    char term[128], name[64], *p, *end, list[96];
    size_t nl;
    double v;
    if (len >= sizeof term)
        return lt_diag_fail(diag, "--budget: term '%.40s...' is too long", s);
    memcpy(term, s, len);
    term[len] = '\0';
    p = term;
    while (isspace((unsigned char)*p))
        p++;
    nl = 0;
    while (islower((unsigned char)p[nl]) || isdigit((unsigned char)p[nl]))
        nl++;
    if (nl == 0 && *p == '\0')
        return lt_diag_fail(diag, "--budget: empty term (expected METRIC<=X or METRIC>=X, "
                                  "comma-separated)");
    if (nl >= sizeof name)
        nl = sizeof name - 1;
    memcpy(name, p, nl);
    name[nl] = '\0';
    metric_list(list, sizeof list);
    if (nl == 0 || (t->metric = lt_metric_find(name)) < 0)
        return lt_diag_fail(diag, "--budget: '%s': unknown metric '%s' (known: %s)", term,
                            nl ? name : "", list);
    p += nl;
    while (isspace((unsigned char)*p))
        p++;
    if ((p[0] == '<' || p[0] == '>') && p[1] == '=') {
        t->ge = p[0] == '>';
        p += 2;
    } else {
        return lt_diag_fail(diag, "--budget: '%s': expected <= or >= after '%s'", term, name);
    }
    while (isspace((unsigned char)*p))
        p++;
    v = strtod(p, &end);
    if (end == p || !isfinite(v))
        return lt_diag_fail(diag, "--budget: '%s': the bound of %s is not a number", term, name);
    while (isspace((unsigned char)*end))
        end++;
    if (*end == '%') {
        if (!lt_metric_is_percent(t->metric))
            return lt_diag_fail(diag, "--budget: '%s': %s is not a percentage ('%%' is for wrong "
                                      "and rel99)", term, name);
        end++;
        while (isspace((unsigned char)*end))
            end++;
    }
    if (*end != '\0')
        return lt_diag_fail(diag, "--budget: '%s': trailing '%s' after the bound of %s", term,
                            end, name);
    if (v < 0.0)
        return lt_diag_fail(diag, "--budget: '%s': the bound of %s is negative (bounds are >= 0)",
                            term, name);
    t->bound = v;
    return 0;
}

int lt_budget_parse(const char *text, lt_budget_t *b, lt_diag_t *diag)
{
    const char *s = text, *comma;
    memset(b, 0, sizeof *b);
    if (text == NULL || text[strspn(text, " \t")] == '\0')
        return lt_diag_fail(diag, "--budget: empty (expected METRIC<=X or METRIC>=X, "
                                  "comma-separated)");
    for (;;) {
        size_t len;
        comma = strchr(s, ',');
        len = comma != NULL ? (size_t)(comma - s) : strlen(s);
        if (b->n == LT_BUDGET_MAX)
            return lt_diag_fail(diag, "--budget: more than %d terms", LT_BUDGET_MAX);
        if (parse_term(s, len, &b->t[b->n], diag) != 0)
            return -1;
        b->n++;
        if (comma == NULL)
            break;
        s = comma + 1;
    }
    return 0;
}

void lt_budget_text(const lt_budget_t *b, char *buf, size_t n)
{
    size_t len = 0;
    int i;
    buf[0] = '\0';
    for (i = 0; i < b->n && len < n; i++) {
        const lt_budget_term_t *t = &b->t[i];
        len += (size_t)snprintf(buf + len, n - len, "%s%s%s%g%s", i ? ", " : "",
                                lt_metric_names[t->metric], t->ge ? ">=" : "<=", t->bound,
                                lt_metric_is_percent(t->metric) ? "%" : "");
    }
}

int lt_budget_meets(const lt_budget_t *b, const double *v, int *failed)
{
    int i;
    for (i = 0; i < b->n; i++) {
        double x = v[b->t[i].metric];
        int ok = !isnan(x) && (b->t[i].ge ? x >= b->t[i].bound : x <= b->t[i].bound);
        if (!ok) {
            if (failed != NULL)
                *failed = i;
            return 0;
        }
    }
    return 1;
}

/* 1 when row a is cheaper than row b: fewer cycles, then fewer bytes. */
static int cheaper(const double *a, const double *b)
{
    if (a[LT_M_CYCLES] != b[LT_M_CYCLES])
        return a[LT_M_CYCLES] < b[LT_M_CYCLES];
    return a[LT_M_BYTES] < b[LT_M_BYTES];
}

long lt_budget_pick(const lt_budget_t *b, const double *vals, size_t n,
                    const unsigned char *include)
{
    long best = -1;
    size_t i;
    for (i = 0; i < n; i++) {
        const double *v = vals + i * LT_M__COUNT;
        if ((include != NULL && !include[i]) || isnan(v[LT_M_CYCLES]) || !lt_budget_meets(b, v, NULL))
            continue;
        if (best < 0 || cheaper(v, vals + (size_t)best * LT_M__COUNT))
            best = (long)i;
    }
    return best;
}

int lt_budget_binding(const lt_budget_t *b, const double *vals, size_t n,
                      const unsigned char *include, long pick)
{
    int i, bind = -1;
    double best_save = 0.0, c0;
    if (pick < 0)
        return -1;
    c0 = vals[(size_t)pick * LT_M__COUNT + LT_M_CYCLES];
    for (i = 0; i < b->n; i++) {
        lt_budget_t rest = *b;
        long p;
        memmove(&rest.t[i], &rest.t[i + 1], (size_t)(b->n - i - 1) * sizeof rest.t[0]);
        rest.n--;
        p = lt_budget_pick(&rest, vals, n, include);
        if (p >= 0 && vals[(size_t)p * LT_M__COUNT + LT_M_CYCLES] < c0 &&
            c0 - vals[(size_t)p * LT_M__COUNT + LT_M_CYCLES] > best_save) {
            best_save = c0 - vals[(size_t)p * LT_M__COUNT + LT_M_CYCLES];
            bind = i;
        }
    }
    if (bind < 0 && b->n > 1) {
        /* no term alone: do they bind together (a cheaper row meets none of them)? */
        lt_budget_t none;
        long p;
        memset(&none, 0, sizeof none);
        p = lt_budget_pick(&none, vals, n, include);
        if (p >= 0 && vals[(size_t)p * LT_M__COUNT + LT_M_CYCLES] < c0)
            bind = LT_BUDGET_JOINT;
    }
    return bind;
}

void lt_budget_binding_text(const lt_budget_t *b, int binding, char *buf, size_t n)
{
    size_t len = 0;
    int i;
    if (binding >= 0 && binding < b->n) {
        snprintf(buf, n, "%s", lt_metric_names[b->t[binding].metric]);
    } else if (binding == LT_BUDGET_JOINT) {
        buf[0] = '\0';
        for (i = 0; i < b->n && len < n; i++)
            len += (size_t)snprintf(buf + len, n - len, "%s%s", i ? ", " : "",
                                    lt_metric_names[b->t[i].metric]);
        if (len < n)
            snprintf(buf + len, n - len, " together (no bound alone)");
    } else {
        snprintf(buf, n, "none");
    }
}
