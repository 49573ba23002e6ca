/* lt_cache.c: set-associative LRU cache model for the lanetrace simulator (sim/ only, host C99).
 * Each set is a move-to-front array of line numbers, so the LRU line is the last slot and a lookup
 * is one pass that shifts entries down until it meets the line. Index math is shifts and masks
 * only; the last line looked up at a level is kept, so repeating it costs one compare.
 * Model and limits: docs/cache-model.md.
 */
#include "lt_cache.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Invalid tag and "no MRU line". Line numbers are addr >> log2(line) with line >= 4, so they are
 * < 2^62 and can never equal this value. */
#define INVALID_LINE UINT64_MAX

/* Keeps the slow paths out of lt_cache_access, so its one-line path saves no registers (GCC
 * otherwise inlines them and pushes six registers on every call). A speed hint only: empty on
 * other compilers. */
#if defined(__GNUC__)
#define NOINLINE __attribute__((noinline))
#else
#define NOINLINE
#endif

static int is_pow2(uint32_t v)
{
    return v != 0 && (v & (v - 1u)) == 0;
}

static uint32_t log2_pow2(uint32_t v)
{
    uint32_t s = 0;
    while ((1u << s) < v) {
        s++;
    }
    return s;
}

/* Check a geometry against the documented limits; `what` names the input in the message
 * (e.g. `cache spec "64:8:63"` or `cache "L1"`). */
static int check_cfg(const char *what, const lt_cache_cfg_t *cfg, lt_diag_t *diag)
{
    uint64_t total;
    if (!is_pow2(cfg->sets)) {
        lt_diag_fail(diag, "%s: sets %lu is not a power of two >= 1", what,
                     (unsigned long)cfg->sets);
        return -1;
    }
    if (cfg->ways < 1u || cfg->ways > LT_CACHE_MAX_WAYS) {
        lt_diag_fail(diag, "%s: ways %lu outside 1..%u", what, (unsigned long)cfg->ways,
                     LT_CACHE_MAX_WAYS);
        return -1;
    }
    if (!is_pow2(cfg->line)) {
        lt_diag_fail(diag, "%s: line %lu is not a power of two", what, (unsigned long)cfg->line);
        return -1;
    }
    if (cfg->line < LT_CACHE_MIN_LINE || cfg->line > LT_CACHE_MAX_LINE) {
        lt_diag_fail(diag, "%s: line %lu outside %u..%u bytes", what, (unsigned long)cfg->line,
                     LT_CACHE_MIN_LINE, LT_CACHE_MAX_LINE);
        return -1;
    }
    /* Each factor is < 2^32 and ways <= 64, line <= 4096, so the product fits in 64 bits. */
    total = (uint64_t)cfg->sets * cfg->ways * cfg->line;
    if (total > LT_CACHE_MAX_BYTES) {
        lt_diag_fail(diag, "%s: total size %llu bytes exceeds 64 MiB (%u bytes)", what,
                     (unsigned long long)total, LT_CACHE_MAX_BYTES);
        return -1;
    }
    return 0;
}

/* Read one decimal field at *p into *out and advance *p. Returns 0, -1 if there is no digit,
 * -2 if the value exceeds UINT32_MAX. */
static int parse_u32(const char **p, uint32_t *out)
{
    const char *s = *p;
    uint64_t v = 0;
    if (*s < '0' || *s > '9') {
        return -1;
    }
    while (*s >= '0' && *s <= '9') {
        v = (v * 10u) + (uint64_t)(*s - '0');
        if (v > UINT32_MAX) {
            return -2;
        }
        s++;
    }
    *p = s;
    *out = (uint32_t)v;
    return 0;
}

int lt_cache_parse(const char *spec, lt_cache_cfg_t *cfg, lt_diag_t *diag)
{
    static const char *const field[3] = { "sets", "ways", "line" };
    char what[96];
    uint32_t v[3];
    const char *p = spec;
    int i;

    if (spec == NULL || cfg == NULL) {
        lt_diag_fail(diag, "cache spec (null): expected S:W:B (sets:ways:line bytes)");
        return -1;
    }
    (void)snprintf(what, sizeof what, "cache spec \"%.64s\"", spec);
    for (i = 0; i < 3; i++) {
        int r;
        if (i > 0) {
            if (*p == '\0') {
                lt_diag_fail(diag, "%s: missing %s field, expected S:W:B (sets:ways:line bytes)",
                             what, field[i]);
                return -1;
            }
            if (*p != ':') {
                lt_diag_fail(diag, "%s: expected ':' after %s field, expected S:W:B", what,
                             field[i - 1]);
                return -1;
            }
            p++;
        }
        r = parse_u32(&p, &v[i]);
        if (r == -1) {
            lt_diag_fail(diag, "%s: %s field is not a decimal number, expected S:W:B "
                         "(sets:ways:line bytes)", what, field[i]);
            return -1;
        }
        if (r == -2) {
            lt_diag_fail(diag, "%s: %s field exceeds %lu", what, field[i],
                         (unsigned long)UINT32_MAX);
            return -1;
        }
    }
    if (*p != '\0') {
        lt_diag_fail(diag, "%s: unexpected text after line field, expected S:W:B", what);
        return -1;
    }
    {
        lt_cache_cfg_t t;
        t.sets = v[0];
        t.ways = v[1];
        t.line = v[2];
        if (check_cfg(what, &t, diag) != 0) {
            return -1;
        }
        *cfg = t;
    }
    return 0;
}

int lt_cache_init(lt_cache_t *c, const char *name, const lt_cache_cfg_t *cfg, uint32_t hit_cycles,
                  lt_cache_t *next, uint32_t mem_cycles, lt_diag_t *diag)
{
    char what[LT_CACHE_NAME_LEN + 16];
    const lt_cache_t *n;
    size_t count;
    int depth;

    if (c == NULL) {
        lt_diag_fail(diag, "cache: lt_cache_init called with a NULL cache");
        return -1;
    }
    memset(c, 0, sizeof *c);
    c->mru = INVALID_LINE;
    (void)snprintf(c->name, sizeof c->name, "%s", name != NULL ? name : "cache");
    (void)snprintf(what, sizeof what, "cache \"%s\"", c->name);
    if (cfg == NULL) {
        lt_diag_fail(diag, "%s: NULL geometry", what);
        return -1;
    }
    if (check_cfg(what, cfg, diag) != 0) {
        return -1;
    }
    /* A chain that leads back to c would recurse forever on a miss. */
    for (n = next, depth = 0; n != NULL; n = n->next, depth++) {
        if (n == c || depth >= 64) {
            lt_diag_fail(diag, "%s: next-level chain loops back to this cache or exceeds 64 levels",
                         what);
            return -1;
        }
    }
    count = (size_t)cfg->sets * cfg->ways;
    c->tags = (uint64_t *)malloc(count * sizeof *c->tags);
    if (c->tags == NULL) {
        lt_diag_fail(diag, "%s: out of memory for %lu tags", what, (unsigned long)count);
        return -1;
    }
    c->cfg = *cfg;
    c->next = next;
    c->set_mask = (uint64_t)cfg->sets - 1u;
    c->line_shift = log2_pow2(cfg->line);
    c->ways = cfg->ways;
    c->hit_cycles = hit_cycles;
    c->mem_cycles = mem_cycles;
    lt_cache_reset(c);
    return 0;
}

void lt_cache_free(lt_cache_t *c)
{
    if (c == NULL) {
        return;
    }
    free(c->tags);
    c->tags = NULL;
    c->mru = INVALID_LINE;
}

void lt_cache_reset(lt_cache_t *c)
{
    if (c == NULL) {
        return;
    }
    if (c->tags != NULL) {
        /* All-ones bytes make every tag INVALID_LINE. */
        memset(c->tags, 0xFF, (size_t)c->cfg.sets * c->ways * sizeof *c->tags);
    }
    c->mru = INVALID_LINE;
    c->hits = 0;
    c->misses = 0;
    c->writes = 0;
}

/* Look up one line that is not the MRU line and return its latency. One pass shifts each slot
 * down by one until it meets the line (hit: the line's old slot is overwritten) or an invalid slot
 * or the end of the set (miss: the value pushed out is an invalid tag or the LRU line). The line
 * then sits in slot 0. Invalid slots are always at the tail, so stopping at the first is exact.
 * A branch-free scan of all ways plus a masked or memmove shift was tried and measured slower on
 * the host (8-way random hits about 17-19 ns against 11 ns; sequential 64 B sweeps 12-16 ns
 * against 3-6 ns), so the early exit stays. */
static NOINLINE uint32_t access_line(lt_cache_t *c, uint64_t ln, int write)
{
    uint64_t *set = c->tags + ((size_t)(ln & c->set_mask) * c->ways);
    uint64_t carry = ln;
    uint32_t i, n = c->ways;

    c->mru = ln;
    for (i = 0; i < n; i++) {
        uint64_t t = set[i];
        set[i] = carry;
        if (t == ln) {
            c->hits++;
            return c->hit_cycles;
        }
        if (t == INVALID_LINE) {
            break;
        }
        carry = t;
    }
    c->misses++;
    if (c->next == NULL) {
        return c->mem_cycles;
    }
    /* Inclusive fill: the next level sees this level's whole line, as the same kind of access. */
    return lt_cache_access(c->next, ln << c->line_shift, c->cfg.line, write);
}

/* Accesses that touch several lines, or none. Kept out of lt_cache_access so that its one-line
 * path needs no saved registers. */
static NOINLINE uint32_t access_span(lt_cache_t *c, uint64_t addr, uint32_t bytes, int write)
{
    uint64_t end, ln, last;
    uint32_t cost = 0, lat;

    if (bytes == 0) {
        return 0;
    }
    end = addr + (bytes - 1u);
    if (end < addr) {
        end = UINT64_MAX; /* range wraps past 2^64 - 1: clamp (unsigned wrap is defined) */
    }
    last = end >> c->line_shift;
    for (ln = addr >> c->line_shift;; ln++) {
        c->writes += (write != 0);
        if (ln == c->mru) {
            c->hits++;
            lat = c->hit_cycles;
        } else {
            lat = access_line(c, ln, write);
        }
        cost = lat > cost ? lat : cost;
        if (ln == last) {
            break;
        }
    }
    return cost;
}

uint32_t lt_cache_access(lt_cache_t *c, uint64_t addr, uint32_t bytes, int write)
{
    uint64_t ln = addr >> c->line_shift;

    /* One line: first and last byte share the line number. bytes == 0 must not pass (its "last
     * byte" is addr - 1); a range wrapping past 2^64 - 1 never passes (its ends differ in the top
     * bits). */
    if (bytes != 0 && ((addr + (bytes - 1u)) >> c->line_shift) == ln) {
        c->writes += (write != 0);
        if (ln == c->mru) {
            /* Already MRU in its set: a hit with no LRU change. */
            c->hits++;
            return c->hit_cycles;
        }
        return access_line(c, ln, write);
    }
    return access_span(c, addr, bytes, write);
}

void lt_cache_stats(const lt_cache_t *c, lt_cache_stats_t *out)
{
    out->hits = c->hits;
    out->misses = c->misses;
    out->accesses = c->hits + c->misses;
    out->writes = c->writes;
    out->reads = out->accesses - c->writes;
}

const char *lt_cache_name(const lt_cache_t *c)
{
    return c->name;
}

const lt_cache_cfg_t *lt_cache_cfg(const lt_cache_t *c)
{
    return &c->cfg;
}
