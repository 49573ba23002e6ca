/* lt_pareto.h - the arithmetic of `lanetrace tune` (docs/tune.md): the budget metrics (fixed names
 * scripts rely on), Pareto dominance and fronts over points with k objectives, and budgets
 * ("wrong<=0.5%,cycles<=2e6"): parsing with one-line messages naming the input, checking a point
 * and picking the cheapest point that meets every bound. No I/O, no globals. Host only.
 */
#ifndef LT_PARETO_H
#define LT_PARETO_H

#include <stddef.h>

#include "io/lt_diag.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The budget metrics, in this order everywhere (CSV columns, JSON keys, --budget names). A value
 * is NaN where a point's family does not measure the metric. */
typedef enum lt_metric {
    LT_M_WRONG = 0, /* % wrong triangle (object) or wrong hit/miss (screen) */
    LT_M_RMSE,      /* depth RMSE, scene units (object, screen) */
    LT_M_REL99,     /* 99th-percentile relative depth error, % (screen) */
    LT_M_PSNR,      /* dB against the 256-spp reference (shadows); higher is better */
    LT_M_CYCLES,    /* simulated cycles of the frame, all phases */
    LT_M_BYTES,     /* bytes of the acceleration structure */
    LT_M__COUNT
} lt_metric_t;

/* "wrong", "rmse", "rel99", "psnr", "cycles", "bytes" (NULL after the last). */
extern const char *const lt_metric_names[];

/* 1 when larger values are better (psnr), else 0. */
int lt_metric_higher_better(int m);

/* 1 when the metric is a percentage (a bound may end with '%'). */
int lt_metric_is_percent(int m);

/* The metric called name (exact, lower case), or -1. */
int lt_metric_find(const char *name);

/* ---- dominance and fronts (every objective minimised; NaN counts as worst) ----------------- */

/* 1 when a is no worse than b in all k objectives and strictly better in one. */
int lt_pareto_dominates(const double *a, const double *b, int k);

/* on_front[i] = 1 for the points of obj (n rows of k objectives, row-major) that no other point
 * dominates (duplicates are all kept), else 0. Only rows with include[i] != 0 take part (include
 * may be NULL: all); excluded rows get 0. Returns the front's size. O(n^2 k). */
size_t lt_pareto_front(const double *obj, size_t n, int k, const unsigned char *include,
                       unsigned char *on_front);

/* ---- budgets ------------------------------------------------------------------------------ */

#define LT_BUDGET_MAX 12

typedef struct lt_budget_term {
    int metric;   /* lt_metric_t */
    int ge;       /* 1: value >= bound, 0: value <= bound */
    double bound; /* finite, >= 0 */
} lt_budget_term_t;

typedef struct lt_budget {
    int n;
    lt_budget_term_t t[LT_BUDGET_MAX];
} lt_budget_t;

/* Parse "METRIC<=X[,METRIC>=Y...]" (spaces around tokens allowed, '%' after X only for percentage
 * metrics, X a finite number >= 0). Returns 0, or -1 with a message naming the term and what is
 * wrong: an unknown metric (the known names listed), a missing operator, a non-numeric or
 * negative bound, an empty term, too many terms. */
int lt_budget_parse(const char *text, lt_budget_t *b, lt_diag_t *diag);

/* The budget as text ("wrong<=0.5%, cycles<=2e+06"). */
void lt_budget_text(const lt_budget_t *b, char *buf, size_t n);

/* 1 when every term holds for v[LT_M__COUNT] (a NaN value fails its term), else 0 with *failed
 * (may be NULL) = the index of the first failing term. */
int lt_budget_meets(const lt_budget_t *b, const double *v, int *failed);

/* The index (0..n-1) of the cheapest row of vals (n rows of LT_M__COUNT values) that meets b among
 * rows with include[i] != 0 (NULL: all): fewest cycles, then fewest bytes, then the lowest index.
 * Returns -1 when none meets it. */
long lt_budget_pick(const lt_budget_t *b, const double *vals, size_t n,
                    const unsigned char *include);

/* The binding term of the pick: the term whose removal lets a row with fewer cycles meet the rest
 * (of several, the one whose removal saves the most cycles). Returns its index; LT_BUDGET_JOINT
 * when no term alone binds but the terms do together (a cheaper row breaks several of them);
 * -1 when none binds (the cheapest row overall meets the budget). */
#define LT_BUDGET_JOINT (-2)

/* A binding as text: the metric's name, "wrong, rel99 together", or "none". */
void lt_budget_binding_text(const lt_budget_t *b, int binding, char *buf, size_t n);
int lt_budget_binding(const lt_budget_t *b, const double *vals, size_t n,
                      const unsigned char *include, long pick);

#ifdef __cplusplus
}
#endif
#endif /* LT_PARETO_H */
