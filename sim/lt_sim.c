/* lt_sim.c - counters, machine tables, cache hookup and cycle reports of the sim build.
 * The kernels charge through lt_cost.h: LT_COST/LT_EVENT are inline increments of the current
 * phase's counter row (lt__sim_cur), LT_MEM calls lt_sim_mem, which runs the cache model.
 * Cycles = sum over op classes of count x issue cycles + memory stall cycles (cache latency beyond
 * an L1 hit). Host only.
 */
#include "lt_sim.h"
#include "lt_rate.h"
#include "lt_cache.h"

#include <cjson/cJSON.h>
#include <stdlib.h>
#include <string.h>

/* ---- machine tables ------------------------------------------------------------------------ */

/* One static lt_machine_t per file sim/machines/<name>.def (lt_machines.h iterates over them). A
 * repeated op is an error (-Woverride-init, in -Wextra); an unknown one is an undeclared name. */
#define LT_MACHINE_L1(spec, hit) .l1 = (spec), .l1_hit = (hit),
#define LT_MACHINE_L2(spec, hit) .l2 = (spec), .l2_hit = (hit),
#define LT_MACHINE(id, nm, d, mhz, ln)                                                             \
    static const lt_machine_t lt_machine_##id = {.name = (nm), .desc = (d), .clock_mhz = (mhz),   \
                                                 .lanes = (ln),
#define LT_MACHINE_CACHE(level, spec, hit) LT_MACHINE_##level(spec, hit)
#define LT_MACHINE_MEM(cycles) .mem = (cycles),
#define LT_MACHINE_LANEWISE() .lanewise = 1,
#define LT_OP_COST(op, lat, iss) .latency[LT_OP_##op] = (lat), .issue[LT_OP_##op] = (iss),
#define LT_MACHINE_END };
#include "lt_machines.h"
#undef LT_MACHINE_L1
#undef LT_MACHINE_L2

/* Every machine prices every op: count each file's LT_OP_COST lines. A file that misses one fails
 * here with an error naming it: "size of array 'lt_machine_<id>_must_price_every_op_of_lt_ops_def'
 * is negative". */
#define LT_MACHINE(id, nm, d, mhz, ln) enum { lt_machine_##id##_nops = 0
#define LT_OP_COST(op, lat, iss) +1
#define LT_MACHINE_END };
#include "lt_machines.h"
#define LT_MACHINE(id, nm, d, mhz, ln)                                                             \
    typedef char lt_machine_##id##_must_price_every_op_of_lt_ops_def                              \
        [(int)lt_machine_##id##_nops == (int)LT_OP__COUNT ? 1 : -1];
#include "lt_machines.h"

/* NULL-terminated, in file name order. */
const lt_machine_t *const lt_sim_machines[] = {
#define LT_MACHINE(id, nm, d, mhz, ln) &lt_machine_##id,
#include "lt_machines.h"
    NULL};

const lt_machine_t *lt_sim_machine_find(const char *name)
{
    int i;
    for (i = 0; lt_sim_machines[i] != NULL; i++)
        if (strcmp(lt_sim_machines[i]->name, name) == 0)
            return lt_sim_machines[i];
    return NULL;
}

/* ---- state --------------------------------------------------------------------------------- */

static uint64_t ctr[LT_PH__COUNT][LT_CTR__COUNT];
static uint64_t memstall[LT_PH__COUNT];
static lt_phase_t cur_phase = LT_PH_OTHER;
uint64_t *lt__sim_cur = ctr[LT_PH_OTHER];

static const lt_machine_t *mach;

/* LT_LANEWISE() in the simulator build (lt_v16.h): the machine modelled runs the lane-by-lane
 * forms (its file's LT_MACHINE_LANEWISE()); set by lt_sim_init. */
int lt__sim_lanewise;
static lt_cache_t l1, l2;
static int have_l1, have_l2;
static char l1_spec[32], l2_spec[32];

struct region {
    uintptr_t lo, hi;
    uint64_t sim_base;
};
static struct region regions[16];
static int nregions;

lt_phase_t lt_sim_phase(lt_phase_t ph)
{
    lt_phase_t prev = cur_phase;
    cur_phase = ph;
    lt__sim_cur = ctr[ph];
    return prev;
}

void lt_sim_mem(const void *p, uint32_t bytes, int rw)
{
    uintptr_t a = (uintptr_t)p;
    uint64_t addr = (uint64_t)a;
    uint32_t cyc;
    int i;
    for (i = 0; i < nregions; i++) {
        if (a >= regions[i].lo && a < regions[i].hi) {
            addr = regions[i].sim_base + (uint64_t)(a - regions[i].lo);
            break;
        }
    }
    lt__sim_cur[LT_OP__COUNT + (rw ? LT_EV_MEM_WR : LT_EV_MEM_RD)] += bytes;
    if (!have_l1)
        return;
    cyc = lt_cache_access(&l1, addr, bytes, rw);
    if (cyc > mach->l1_hit)
        memstall[cur_phase] += cyc - mach->l1_hit;
}

int lt_sim_region(const void *base, size_t bytes, uint64_t sim_base)
{
    if (nregions == (int)(sizeof regions / sizeof regions[0]))
        return -1;
    regions[nregions].lo = (uintptr_t)base;
    regions[nregions].hi = (uintptr_t)base + bytes;
    regions[nregions].sim_base = sim_base;
    nregions++;
    return 0;
}

void lt_sim_shutdown(void)
{
    if (have_l1)
        lt_cache_free(&l1);
    if (have_l2)
        lt_cache_free(&l2);
    have_l1 = have_l2 = 0;
    nregions = 0;
}

void lt_sim_reset(void)
{
    memset(ctr, 0, sizeof ctr);
    memset(memstall, 0, sizeof memstall);
    lt_sim_phase(LT_PH_OTHER);
    if (have_l1)
        lt_cache_reset(&l1);
    if (have_l2)
        lt_cache_reset(&l2);
}

int lt_sim_init(const lt_machine_t *m, const char *l1s, const char *l2s, lt_diag_t *diag)
{
    lt_cache_cfg_t c1, c2;
    lt_sim_shutdown();
    mach = m;
    lt__sim_lanewise = m->lanewise;
    if (l1s == NULL)
        l1s = m->l1;
    if (l2s == NULL)
        l2s = m->l2;
    if (l1s == NULL) {
        lt_diag_fail(diag, "machine %s: no L1 cache (LT_MACHINE_CACHE(L1, ...) in its .def)",
                     m->name);
        return -1;
    }
    if (lt_cache_parse(l1s, &c1, diag) != 0)
        return -1;
    if (l2s != NULL && lt_cache_parse(l2s, &c2, diag) != 0)
        return -1;
    snprintf(l1_spec, sizeof l1_spec, "%s", l1s);
    snprintf(l2_spec, sizeof l2_spec, "%s", l2s != NULL ? l2s : "none");
    if (l2s != NULL) {
        if (lt_cache_init(&l2, "L2", &c2, m->l2_hit, NULL, m->mem, diag) != 0)
            return -1;
        have_l2 = 1;
    }
    if (lt_cache_init(&l1, "L1", &c1, m->l1_hit, have_l2 ? &l2 : NULL, have_l2 ? 0 : m->mem,
                      diag) != 0) {
        lt_sim_shutdown();
        return -1;
    }
    have_l1 = 1;
    lt_sim_reset();
    return 0;
}

/* ---- results ------------------------------------------------------------------------------- */

static const char *const op_names[] = {
#define LT_OP(name, unit, doc) #name,
#define LT_EV(name, doc)
#define LT_PH(name, doc)
#include "lt/lt_ops.def"
#undef LT_OP
#undef LT_EV
#undef LT_PH
};
static const char *const ev_names[] = {
#define LT_OP(name, unit, doc)
#define LT_EV(name, doc) #name,
#define LT_PH(name, doc)
#include "lt/lt_ops.def"
#undef LT_OP
#undef LT_EV
#undef LT_PH
};
static const char *const ph_names[] = {
#define LT_OP(name, unit, doc)
#define LT_EV(name, doc)
#define LT_PH(name, doc) #name,
#include "lt/lt_ops.def"
#undef LT_OP
#undef LT_EV
#undef LT_PH
};

const char *lt_sim_op_name(int op) { return op_names[op]; }
const char *lt_sim_ev_name(int ev) { return ev_names[ev]; }
const char *lt_sim_phase_name(int ph) { return ph_names[ph]; }

void lt_sim_totals(lt_sim_totals_t *t)
{
    int p, o;
    lt_cache_stats_t s;
    memset(t, 0, sizeof *t);
    memcpy(t->ctr, ctr, sizeof ctr);
    for (p = 0; p < LT_PH__COUNT; p++) {
        uint64_t c = memstall[p];
        for (o = 0; o < LT_OP__COUNT; o++)
            c += ctr[p][o] * mach->issue[o];
        t->memstall[p] = memstall[p];
        t->cycles[p] = c;
        t->total_cycles += c;
    }
    if (have_l1) {
        lt_cache_stats(&l1, &s);
        t->l1_acc = s.accesses;
        t->l1_hit = s.hits;
    }
    if (have_l2) {
        lt_cache_stats(&l2, &s);
        t->l2_acc = s.accesses;
        t->l2_hit = s.hits;
    }
}

uint64_t lt_sim_cycles_total(void)
{
    uint64_t c = 0;
    int p, o;
    if (mach == NULL)
        return 0;
    for (p = 0; p < LT_PH__COUNT; p++) {
        c += memstall[p];
        for (o = 0; o < LT_OP__COUNT; o++)
            c += ctr[p][o] * mach->issue[o];
    }
    return c;
}

const lt_machine_t *lt_sim_machine(void) { return mach; }

uint64_t lt_sim_event_total(int ev)
{
    uint64_t c = 0;
    int p;
    for (p = 0; p < LT_PH__COUNT; p++)
        c += ctr[p][LT_OP__COUNT + ev];
    return c;
}

static uint64_t ev_total(const lt_sim_totals_t *t, int ev)
{
    uint64_t s = 0;
    int p;
    for (p = 0; p < LT_PH__COUNT; p++)
        s += t->ctr[p][LT_OP__COUNT + ev];
    return s;
}

static double pct(uint64_t a, uint64_t b) { return b != 0 ? 100.0 * (double)a / (double)b : 0.0; }

static double utilisation(const lt_sim_totals_t *t)
{
    uint64_t ops = ev_total(t, LT_EV_LANE_OPS);
    return ops != 0 ? (double)ev_total(t, LT_EV_LANES_ON) / (16.0 * (double)ops) : 0.0;
}

void lt_sim_report_text(FILE *f, const char *title, uint64_t rays)
{
    lt_sim_totals_t t;
    int p, o, e;
    double secs;
    lt_sim_totals(&t);
    secs = (double)t.total_cycles / ((double)mach->clock_mhz * 1e6);
    fprintf(f, "== cycle report: %s\n", title);
    fprintf(f, "machine   %s (%s)\n", mach->name, mach->desc);
    fprintf(f, "caches    L1 %s hit %u cy | L2 %s hit %u cy | memory %u cy\n", l1_spec,
            mach->l1_hit, l2_spec, mach->l2_hit, mach->mem);
    fprintf(f, "%-10s %16s %7s %14s\n", "phase", "cycles", "share", "mem stall");
    for (p = 0; p < LT_PH__COUNT; p++) {
        if (t.cycles[p] == 0)
            continue;
        fprintf(f, "%-10s %16llu %6.1f%% %14llu\n", ph_names[p], (unsigned long long)t.cycles[p],
                pct(t.cycles[p], t.total_cycles), (unsigned long long)t.memstall[p]);
    }
    fprintf(f, "%-10s %16llu\n", "total", (unsigned long long)t.total_cycles);
    fprintf(f, "%-10s %16s %16s %7s\n", "op class", "count", "cycles", "share");
    for (o = 0; o < LT_OP__COUNT; o++) {
        uint64_t n = 0;
        for (p = 0; p < LT_PH__COUNT; p++)
            n += t.ctr[p][o];
        if (n == 0)
            continue;
        fprintf(f, "%-10s %16llu %16llu %6.1f%%\n", op_names[o], (unsigned long long)n,
                (unsigned long long)(n * mach->issue[o]), pct(n * mach->issue[o], t.total_cycles));
    }
    fprintf(f, "events   ");
    for (e = 0; e < LT_EV__COUNT; e++) {
        if (e == LT_EV_LANES_ON || e == LT_EV_LANE_OPS)
            continue;
        fprintf(f, " %s=%llu", ev_names[e], (unsigned long long)ev_total(&t, e));
    }
    fprintf(f, "\n");
    fprintf(f, "cache     L1 %llu accesses, %.2f%% hits | L2 %llu accesses, %.2f%% hits\n",
            (unsigned long long)t.l1_acc, pct(t.l1_hit, t.l1_acc), (unsigned long long)t.l2_acc,
            pct(t.l2_hit, t.l2_acc));
    fprintf(f, "lanes     utilisation %.1f%% (active lanes / 16 over %llu masked lane ops)\n",
            100.0 * utilisation(&t), (unsigned long long)ev_total(&t, LT_EV_LANE_OPS));
    if (rays != 0) {
        uint64_t tr = t.total_cycles - t.cycles[LT_PH_BUILD];
        char r1[LT_RATE_TEXT], r2[LT_RATE_TEXT];
        fprintf(f, "rays      %llu rays, %.1f cycles/ray, %s at %u MHz; without the build: %.1f "
                   "cycles/ray, %s\n",
                (unsigned long long)rays, (double)t.total_cycles / (double)rays,
                lt_rate_text(secs > 0 ? (double)rays / secs : 0.0, r1), mach->clock_mhz,
                (double)tr / (double)rays,
                lt_rate_text(tr ? (double)rays / ((double)tr / ((double)mach->clock_mhz * 1e6))
                                : 0.0,
                             r2));
    }
}

char *lt_sim_report_json_string(const char *title, uint64_t rays, const char *extra_json)
{
    lt_sim_totals_t t;
    cJSON *root, *ph, *ops, *evs, *cache;
    char *s;
    int p, o, e;
    double secs;
    lt_sim_totals(&t);
    secs = (double)t.total_cycles / ((double)mach->clock_mhz * 1e6);
    root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "title", title);
    cJSON_AddStringToObject(root, "machine", mach->name);
    cJSON_AddNumberToObject(root, "clock_mhz", mach->clock_mhz);
    cJSON_AddStringToObject(root, "l1", l1_spec);
    cJSON_AddStringToObject(root, "l2", l2_spec);
    cJSON_AddNumberToObject(root, "total_cycles", (double)t.total_cycles);
    cJSON_AddNumberToObject(root, "rays", (double)rays);
    cJSON_AddNumberToObject(root, "cycles_per_ray", rays ? (double)t.total_cycles / (double)rays : 0);
    cJSON_AddNumberToObject(root, "mrays_per_s", rays && secs > 0 ? (double)rays / secs / 1e6 : 0);
    cJSON_AddNumberToObject(root, "trace_cycles_per_ray",
                            rays ? (double)(t.total_cycles - t.cycles[LT_PH_BUILD]) / (double)rays : 0);
    cJSON_AddNumberToObject(root, "lane_utilisation", utilisation(&t));
    ph = cJSON_AddObjectToObject(root, "phases");
    for (p = 0; p < LT_PH__COUNT; p++) {
        cJSON *x;
        if (t.cycles[p] == 0)
            continue;
        x = cJSON_AddObjectToObject(ph, ph_names[p]);
        cJSON_AddNumberToObject(x, "cycles", (double)t.cycles[p]);
        cJSON_AddNumberToObject(x, "mem_stall", (double)t.memstall[p]);
        for (o = 0; o < LT_OP__COUNT; o++)
            if (t.ctr[p][o] != 0)
                cJSON_AddNumberToObject(x, op_names[o], (double)t.ctr[p][o]);
    }
    ops = cJSON_AddObjectToObject(root, "ops");
    for (o = 0; o < LT_OP__COUNT; o++) {
        uint64_t n = 0;
        for (p = 0; p < LT_PH__COUNT; p++)
            n += t.ctr[p][o];
        if (n != 0)
            cJSON_AddNumberToObject(ops, op_names[o], (double)n);
    }
    evs = cJSON_AddObjectToObject(root, "events");
    for (e = 0; e < LT_EV__COUNT; e++)
        cJSON_AddNumberToObject(evs, ev_names[e], (double)ev_total(&t, e));
    cache = cJSON_AddObjectToObject(root, "cache");
    cJSON_AddNumberToObject(cache, "l1_accesses", (double)t.l1_acc);
    cJSON_AddNumberToObject(cache, "l1_hits", (double)t.l1_hit);
    cJSON_AddNumberToObject(cache, "l2_accesses", (double)t.l2_acc);
    cJSON_AddNumberToObject(cache, "l2_hits", (double)t.l2_hit);
    if (extra_json != NULL) {
        cJSON *x = cJSON_Parse(extra_json), *it;
        if (x != NULL) {
            while ((it = x->child) != NULL) {
                cJSON_DetachItemViaPointer(x, it);
                cJSON_AddItemToObject(root, it->string, it);
            }
            cJSON_Delete(x);
        }
    }
    s = cJSON_Print(root);
    cJSON_Delete(root);
    return s;
}

int lt_sim_report_json(const char *path, const char *title, uint64_t rays, const char *extra_json,
                       lt_diag_t *diag)
{
    char tmp[4096];
    char *s = lt_sim_report_json_string(title, rays, extra_json);
    FILE *f;
    if (s == NULL) {
        lt_diag_fail(diag, "%s: out of memory building the JSON report", path);
        return -1;
    }
    /* write to a temporary name, then rename: a report is complete or absent */
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    f = fopen(tmp, "w");
    if (f == NULL || fputs(s, f) < 0 || fputc('\n', f) == EOF || fclose(f) != 0) {
        lt_diag_fail(diag, "%s: cannot write the JSON report", tmp);
        free(s);
        return -1;
    }
    free(s);
    if (rename(tmp, path) != 0) {
        lt_diag_fail(diag, "%s: cannot rename %s into place", path, tmp);
        return -1;
    }
    return 0;
}
