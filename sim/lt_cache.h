/* lt_cache.h: set-associative cache model for the lanetrace simulator (sim/ build only, host C99).
 * One lt_cache_t is one level: sets:ways:line geometry (Spike's "S:W:B" string), true LRU kept as a
 * move-to-front array of line numbers per set, write-allocate, levels chained through `next`.
 * Latency model and limits: docs/cache-model.md. Build modes: sim only (host code, uses malloc).
 */
#ifndef LT_CACHE_H
#define LT_CACHE_H

#include <stddef.h>
#include <stdint.h>

#include "io/lt_diag.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LT_CACHE_MAX_WAYS  64u                   /* ways per set, inclusive upper limit */
#define LT_CACHE_MIN_LINE  4u                    /* bytes; line must be a power of two */
#define LT_CACHE_MAX_LINE  4096u                 /* bytes */
#define LT_CACHE_MAX_BYTES (64u * 1024u * 1024u) /* sets * ways * line, inclusive upper limit */
#define LT_CACHE_NAME_LEN  16u                   /* bytes kept of a level's name, NUL included */

/* Geometry of one level. 12 bytes, 4-byte aligned. */
typedef struct lt_cache_cfg {
    uint32_t sets; /* number of sets, power of two >= 1 */
    uint32_t ways; /* lines per set, 1..LT_CACHE_MAX_WAYS (any value, not only powers of two) */
    uint32_t line; /* line size in bytes, power of two, LT_CACHE_MIN_LINE..LT_CACHE_MAX_LINE */
} lt_cache_cfg_t;

/* Per-level counters; each line touched by an access counts once. 40 bytes, 8-byte aligned. */
typedef struct lt_cache_stats {
    uint64_t accesses; /* lines looked up at this level (= hits + misses) */
    uint64_t hits;     /* lookups that found the line */
    uint64_t misses;   /* lookups that allocated the line (and went to the next level or memory) */
    uint64_t reads;    /* lookups caused by loads (= accesses - writes) */
    uint64_t writes;   /* lookups caused by stores (lower levels: store misses filled from here) */
} lt_cache_stats_t;

typedef struct lt_cache lt_cache_t;

/* One cache level. The caller allocates it (it may be embedded); all fields are private: use the
 * functions below. Tag storage is a separate malloc'ed block of sets * ways * 8 bytes. */
struct lt_cache {
    uint64_t *tags;        /* private: [sets][ways] line numbers, MRU first; UINT64_MAX = invalid */
    uint64_t mru;          /* private: last line number looked up here (UINT64_MAX = none) */
    uint64_t hits;         /* private: hit count */
    uint64_t misses;       /* private: miss count */
    uint64_t writes;       /* private: store lookups */
    lt_cache_t *next;      /* private: next level, or NULL for memory */
    uint64_t set_mask;     /* private: sets - 1 */
    uint32_t line_shift;   /* private: log2(line) */
    uint32_t ways;         /* private: ways per set */
    uint32_t hit_cycles;   /* private: cycles for a hit at this level */
    uint32_t mem_cycles;   /* private: cycles for a miss when next == NULL */
    lt_cache_cfg_t cfg;    /* private: geometry as given */
    char name[LT_CACHE_NAME_LEN]; /* private: label for messages and reports, NUL-terminated */
};

/* Parse a "S:W:B" (sets:ways:line bytes) string, e.g. "64:8:64" = 32 KiB, into *cfg.
 * Fields are plain decimal digits; no signs, spaces or trailing text. Limits: sets and line are
 * powers of two, ways 1..64, line 4..4096, sets*ways*line <= 64 MiB.
 * Cost: none (host only). *cfg is written only on success, diag only on failure.
 * Returns: 0, or -1 with a message naming the string and the violated limit in diag (diag may be
 * NULL). */
int lt_cache_parse(const char *spec, lt_cache_cfg_t *cfg, lt_diag_t *diag);

/* Initialise one level named `name` (truncated to LT_CACHE_NAME_LEN-1 chars) with geometry *cfg
 * (checked against the same limits as lt_cache_parse). A hit here costs hit_cycles. A miss fills
 * this level and looks the line up in `next`; if next is NULL the miss costs mem_cycles. `next`
 * must be an initialised level not already chaining back to c. All lines start invalid, stats zero.
 * c is overwritten, not freed: lt_cache_free it first if it was initialised before.
 * Cost: mallocs sets*ways*8 bytes. On failure c is left so that lt_cache_free(c) is safe.
 * Returns: 0, or -1 with a message (naming the level and the limit, no errno text) in diag. */
int lt_cache_init(lt_cache_t *c, const char *name, const lt_cache_cfg_t *cfg, uint32_t hit_cycles,
                  lt_cache_t *next, uint32_t mem_cycles, lt_diag_t *diag);

/* Release the tag storage of c (not of the next levels). Safe to call twice or after failed init.
 * Cost: none. */
void lt_cache_free(lt_cache_t *c);

/* Invalidate every line of c and zero its stats (this level only; reset each level of a chain).
 * Cost: O(sets * ways). */
void lt_cache_reset(lt_cache_t *c);

/* Look up every line of [addr, addr + bytes) in c (write != 0: store). Each line: hit -> moved to
 * MRU; miss -> allocated here (LRU way evicted, no write-back modelled) and looked up in the next
 * level as the range of this level's line. bytes == 0 touches nothing; a range running past
 * 2^64 - 1 is clamped there.
 * Returns: cycles = max over the lines touched of that line's latency, where a line's latency is
 * the hit_cycles of the first level that hits, or the last level's mem_cycles if none does (lines
 * of one access are fetched in parallel).
 * Cost: O(ways) per line touched; a repeat of the MRU line is O(1). */
uint32_t lt_cache_access(lt_cache_t *c, uint64_t addr, uint32_t bytes, int write);

/* Copy the counters of c (this level only) into *out. Cost: none. */
void lt_cache_stats(const lt_cache_t *c, lt_cache_stats_t *out);

/* The level's name as given to lt_cache_init (possibly truncated). Cost: none. */
const char *lt_cache_name(const lt_cache_t *c);

/* The level's geometry as given to lt_cache_init. Cost: none. */
const lt_cache_cfg_t *lt_cache_cfg(const lt_cache_t *c);

#ifdef __cplusplus
}
#endif

#endif /* LT_CACHE_H */
