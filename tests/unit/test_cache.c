/* test_cache.c: cmocka unit tests for sim/lt_cache.c (set-associative LRU cache model).
 * Checks the "S:W:B" parser and its messages, LRU order, conflict and sweep behaviour, multi-level
 * latency, line spanning, and compares stats and per-access cycles against an independent reference
 * model (array of sets with timestamps, division-based indexing) on random streams.
 * Build modes: host and asan (links sim/lt_cache.c directly).
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../../sim/lt_cache.h"

#define POISON 0xA5

/* ---- helpers --------------------------------------------------------------------------------- */

static void cfg_of(const char *spec, lt_cache_cfg_t *cfg)
{
    lt_diag_t diag;
    int r = lt_cache_parse(spec, cfg, &diag);
    if (r != 0) {
        fail_msg("parse %s: %s", spec, diag.msg);
    }
}

static void init_level(lt_cache_t *c, const char *name, const char *spec, uint32_t hit,
                       lt_cache_t *next, uint32_t mem)
{
    lt_cache_cfg_t cfg;
    lt_diag_t diag;
    cfg_of(spec, &cfg);
    if (lt_cache_init(c, name, &cfg, hit, next, mem, &diag) != 0) {
        fail_msg("init %s: %s", name, diag.msg);
    }
}

static lt_cache_stats_t stats_of(const lt_cache_t *c)
{
    lt_cache_stats_t s;
    lt_cache_stats(c, &s);
    return s;
}

/* ---- parser ---------------------------------------------------------------------------------- */

static void test_parse_good(void **state)
{
    static const struct { const char *spec; uint32_t s, w, b; } good[] = {
        { "64:8:64", 64, 8, 64 },       /* 32 KiB */
        { "1:1:4", 1, 1, 4 },           /* smallest */
        { "1:64:4096", 1, 64, 4096 },   /* fully associative, largest line */
        { "16384:64:64", 16384, 64, 64 }, /* exactly 64 MiB */
        { "256:3:64", 256, 3, 64 },     /* ways need not be a power of two */
        { "0064:08:064", 64, 8, 64 },   /* leading zeros are still decimal */
    };
    size_t i;
    (void)state;
    for (i = 0; i < sizeof good / sizeof good[0]; i++) {
        lt_cache_cfg_t cfg;
        lt_diag_t diag;
        memset(diag.msg, POISON, sizeof diag.msg);
        assert_int_equal(lt_cache_parse(good[i].spec, &cfg, &diag), 0);
        assert_int_equal(cfg.sets, good[i].s);
        assert_int_equal(cfg.ways, good[i].w);
        assert_int_equal(cfg.line, good[i].b);
        assert_int_equal((unsigned char)diag.msg[0], POISON); /* diag untouched on success */
    }
    printf("cache: %u good specs parsed to the expected sets/ways/line\n", (unsigned)i);
}

static void test_parse_bad(void **state)
{
    static const struct { const char *spec; const char *want; } bad[] = {
        { "63:8:64", "sets 63 is not a power of two" },
        { "0:8:64", "sets 0 is not a power of two" },
        { "64:8:63", "line 63 is not a power of two" },
        { "64:8:0", "line 0 is not a power of two" },
        { "64:0:64", "ways 0 outside 1..64" },
        { "64:65:64", "ways 65 outside 1..64" },
        { "64:8:2", "line 2 outside 4..4096" },
        { "64:8:8192", "line 8192 outside 4..4096" },
        { "32768:64:64", "exceeds 64 MiB" },
        { "4294967295:1:4", "sets 4294967295 is not a power of two" },
        { "99999999999:8:64", "sets field exceeds 4294967295" },
        { "abc", "sets field is not a decimal number" },
        { "", "sets field is not a decimal number" },
        { "-64:8:64", "sets field is not a decimal number" },
        { "64:x:64", "ways field is not a decimal number" },
        { "64:8", "missing line field" },
        { "64", "missing ways field" },
        { "64:8:", "line field is not a decimal number" },
        { "64;8;64", "expected ':' after sets field" },
        { "64:8:64:1", "unexpected text after line field" },
        { "64:8:64 ", "unexpected text after line field" },
        { " 64:8:64", "sets field is not a decimal number" },
    };
    size_t i;
    (void)state;
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        lt_cache_cfg_t cfg, poison;
        char quoted[80];
        lt_diag_t diag;
        memset(&cfg, POISON, sizeof cfg);
        memcpy(&poison, &cfg, sizeof cfg);
        memset(diag.msg, POISON, sizeof diag.msg);
        assert_int_equal(lt_cache_parse(bad[i].spec, &cfg, &diag), -1);
        /* The message names the string and the limit; cfg is not written on failure. */
        (void)snprintf(quoted, sizeof quoted, "\"%s\"", bad[i].spec);
        if (strstr(diag.msg, quoted) == NULL || strstr(diag.msg, bad[i].want) == NULL) {
            fail_msg("spec %s: message \"%s\" lacks %s or \"%s\"", bad[i].spec, diag.msg, quoted,
                     bad[i].want);
        }
        assert_memory_equal(&cfg, &poison, sizeof cfg);
    }
    printf("cache: %u bad specs rejected, each message names the spec and the limit\n",
           (unsigned)i);
}

static void test_parse_diag(void **state)
{
    lt_cache_cfg_t cfg;
    lt_diag_t diag;
    (void)state;
    /* diag NULL is allowed (no message wanted); spec NULL is an error, not a crash. */
    assert_int_equal(lt_cache_parse("63:8:64", &cfg, NULL), -1);
    memset(diag.msg, POISON, sizeof diag.msg);
    assert_int_equal(lt_cache_parse(NULL, &cfg, &diag), -1);
    assert_non_null(memchr(diag.msg, '\0', sizeof diag.msg));
    assert_non_null(strstr(diag.msg, "cache spec (null)"));
    printf("cache: NULL diag and NULL spec handled, the message is terminated\n");
}

static void test_init_errors(void **state)
{
    lt_cache_t a, b;
    lt_cache_cfg_t cfg = { 63, 8, 64 };
    lt_diag_t diag;
    (void)state;
    assert_int_equal(lt_cache_init(&a, "L1", &cfg, 1, NULL, 100, &diag), -1);
    assert_non_null(strstr(diag.msg, "cache \"L1\": sets 63 is not a power of two"));
    lt_cache_free(&a); /* safe after failed init */
    lt_cache_free(&a); /* and twice */

    init_level(&a, "A", "4:2:64", 1, NULL, 100);
    init_level(&b, "B", "4:2:64", 2, &a, 100);
    /* Re-initialising A to point at B would close a loop A -> B -> A. init takes an uninitialised
     * struct, so free first (init does not free what it overwrites). */
    cfg.sets = 4;
    lt_cache_free(&a);
    assert_int_equal(lt_cache_init(&a, "A", &cfg, 1, &b, 100, &diag), -1);
    assert_non_null(strstr(diag.msg, "loops back"));
    lt_cache_free(&b);
    assert_int_equal(lt_cache_init(&b, "B", &cfg, 1, &b, 100, &diag), -1);
    assert_non_null(strstr(diag.msg, "loops back"));
    lt_cache_free(&a);
    lt_cache_free(&b);
    printf("cache: init rejects bad geometry (names the level) and next-level loops\n");
}

/* ---- behaviour ------------------------------------------------------------------------------- */

static void test_direct_mapped_conflict(void **state)
{
    lt_cache_t c;
    lt_cache_stats_t s;
    const uint64_t base = 0x10000;
    const uint64_t way_span = 64u * 64u; /* 64 sets x 64 B: same set every 4 KiB */
    int i;
    (void)state;
    init_level(&c, "DM", "64:1:64", 1, NULL, 50);
    /* Two lines in the same set evict each other on every access. */
    for (i = 0; i < 100; i++) {
        assert_int_equal(lt_cache_access(&c, base + ((i & 1) ? way_span : 0), 4, 0), 50);
    }
    s = stats_of(&c);
    assert_int_equal(s.hits, 0);
    assert_int_equal(s.misses, 100);
    /* Two lines in adjacent sets coexist: only the two cold misses. */
    lt_cache_reset(&c);
    for (i = 0; i < 100; i++) {
        lt_cache_access(&c, base + ((i & 1) ? 64u : 0u), 4, 0);
    }
    s = stats_of(&c);
    assert_int_equal(s.misses, 2);
    assert_int_equal(s.hits, 98);
    lt_cache_free(&c);
    printf("cache: direct-mapped 64:1:64, same-set ping-pong 100/100 misses, "
           "adjacent sets 2 misses 98 hits\n");
}

static void test_lru_order(void **state)
{
    lt_cache_t c;
    const uint64_t A = 0, B = 64, C = 128, D = 192, E = 256; /* one set: all map to set 0 */
    const uint64_t seq[6] = { A, B, C, D, A, E };
    const uint64_t still[4] = { C, D, A, E };
    int i;
    (void)state;
    init_level(&c, "FA4", "1:4:64", 1, NULL, 9);
    for (i = 0; i < 6; i++) {
        lt_cache_access(&c, seq[i], 1, 0);
    }
    assert_int_equal(stats_of(&c).hits, 1); /* only the second A */
    /* B was LRU when E came in: C D A E are still present (hits cause no evictions) ... */
    for (i = 0; i < 4; i++) {
        assert_int_equal(lt_cache_access(&c, still[i], 1, 0), 1);
    }
    /* ... and B misses. */
    assert_int_equal(lt_cache_access(&c, B, 1, 0), 9);
    /* Now the order (MRU first) is B E A D: C was LRU, so C misses next and D survives. */
    assert_int_equal(lt_cache_access(&c, D, 1, 0), 1);
    assert_int_equal(lt_cache_access(&c, C, 1, 0), 9);
    lt_cache_free(&c);
    printf("cache: 4-way LRU, A B C D A E evicts B; C D A E still hit; then C evicted by B\n");
}

static void test_sweeps(void **state)
{
    lt_cache_t c;
    lt_cache_stats_t s0, s1;
    const uint64_t size = 64u * 8u * 64u; /* 32 KiB */
    uint64_t a;
    int pass;
    (void)state;
    init_level(&c, "L1", "64:8:64", 1, NULL, 100);
    /* 2x the cache, sequential, twice: LRU keeps the wrong half, second pass never hits. */
    for (pass = 0; pass < 2; pass++) {
        s0 = stats_of(&c);
        for (a = 0; a < 2 * size; a += 64) {
            lt_cache_access(&c, 0x100000 + a, 64, 0);
        }
    }
    s1 = stats_of(&c);
    assert_int_equal(s1.hits - s0.hits, 0);
    assert_int_equal(s1.misses - s0.misses, 2 * size / 64);
    /* Exactly the cache size, byte-wise 4 B loads: second pass all hits. */
    lt_cache_reset(&c);
    for (pass = 0; pass < 2; pass++) {
        s0 = stats_of(&c);
        for (a = 0; a < size; a += 4) {
            lt_cache_access(&c, 0x100000 + a, 4, 0);
        }
    }
    s1 = stats_of(&c);
    assert_int_equal(s1.misses - s0.misses, 0);
    assert_int_equal(s1.hits - s0.hits, size / 4);
    assert_int_equal(s1.misses, size / 64);
    lt_cache_free(&c);
    printf("cache: 64:8:64 sweep of 2x size: 0/%u hits on pass 2; sweep of 1x size: %u/%u hits on "
           "pass 2\n", (unsigned)(2 * size / 64), (unsigned)(size / 4), (unsigned)(size / 4));
}

static void test_two_levels(void **state)
{
    lt_cache_t l1, l2;
    lt_cache_stats_t s1, s2;
    const uint64_t A = 0x40000;
    int i;
    (void)state;
    init_level(&l2, "L2", "512:8:64", 10, NULL, 100);
    init_level(&l1, "L1", "64:8:64", 1, &l2, 999); /* mem_cycles ignored when next != NULL */
    assert_int_equal(lt_cache_access(&l1, A, 4, 0), 100); /* miss both: memory */
    assert_int_equal(lt_cache_access(&l1, A, 4, 0), 1);   /* L1 hit (MRU path) */
    /* 8 more lines in A's L1 set (4 KiB stride) push A out of L1; in L2 they spread over sets. */
    for (i = 1; i <= 8; i++) {
        assert_int_equal(lt_cache_access(&l1, A + (uint64_t)i * 4096u, 4, 1), 100);
    }
    assert_int_equal(lt_cache_access(&l1, A, 4, 0), 10); /* L1 miss, L2 hit */
    assert_int_equal(lt_cache_access(&l1, A, 4, 0), 1);  /* filled back into L1 */
    s1 = stats_of(&l1);
    s2 = stats_of(&l2);
    assert_int_equal(s1.accesses, 12);
    assert_int_equal(s1.hits, 2);
    assert_int_equal(s1.misses, 10);
    assert_int_equal(s1.writes, 8);
    assert_int_equal(s1.reads, 4);
    assert_int_equal(s2.accesses, 10); /* only L1 misses reach L2 */
    assert_int_equal(s2.hits, 1);
    assert_int_equal(s2.misses, 9);
    assert_int_equal(s2.writes, 8); /* store misses arrive as stores */
    assert_string_equal(lt_cache_name(&l1), "L1");
    assert_int_equal(lt_cache_cfg(&l2)->sets, 512);
    /* Reset clears lines and the MRU shortcut. */
    lt_cache_reset(&l1);
    lt_cache_reset(&l2);
    assert_int_equal(lt_cache_access(&l1, A, 4, 0), 100);
    lt_cache_free(&l1);
    lt_cache_free(&l2);
    printf("cache: L1+L2 chain: miss both = mem 100, L1 miss + L2 hit = 10, L1 hit = 1; "
           "L2 sees only L1 misses; reset clears MRU\n");
}

static void test_spanning(void **state)
{
    lt_cache_t l1, l2;
    (void)state;
    init_level(&l2, "L2", "64:8:64", 10, NULL, 100);
    init_level(&l1, "L1", "64:8:64", 1, &l2, 0);
    assert_int_equal(lt_cache_access(&l1, 0x1000, 64, 0), 100); /* aligned 64 B: 1 line */
    assert_int_equal(stats_of(&l1).accesses, 1);
    /* 8 B at offset 60: this line (hit, 1) and the next (miss, 100): cost is the max. */
    assert_int_equal(lt_cache_access(&l1, 0x1000 + 60, 8, 0), 100);
    assert_int_equal(stats_of(&l1).accesses, 3);
    assert_int_equal(stats_of(&l1).hits, 1);
    /* Both cached now: 1 cycle, 2 accesses. */
    assert_int_equal(lt_cache_access(&l1, 0x1000 + 63, 2, 1), 1);
    assert_int_equal(stats_of(&l1).accesses, 5);
    assert_int_equal(stats_of(&l1).writes, 2);
    /* 200 B from offset 1 touches 4 lines. */
    lt_cache_access(&l1, 0x2001, 200, 0);
    assert_int_equal(stats_of(&l1).accesses, 9);
    /* bytes == 0 touches nothing. */
    assert_int_equal(lt_cache_access(&l1, 0x9000, 0, 0), 0);
    assert_int_equal(stats_of(&l1).accesses, 9);
    /* A range running past 2^64-1 is clamped: top line only. */
    lt_cache_access(&l1, UINT64_MAX - 3, 16, 0);
    assert_int_equal(stats_of(&l1).accesses, 10);
    lt_cache_free(&l1);
    lt_cache_free(&l2);
    printf("cache: spanning: 64 B aligned = 1 line, 8 B @60 = 2 lines (cost max 100), "
           "200 B @1 = 4 lines, 0 B = none, wrap clamped\n");
}

/* ---- reference model ------------------------------------------------------------------------- */
/* Deliberately naive: array of sets, each way a valid flag, tag and last-use timestamp; victim is
 * the first invalid way, else the smallest timestamp. Indexing uses division and modulo. */

typedef struct ref_way {
    int valid;
    uint64_t tag;   /* line address / line / sets */
    uint64_t stamp; /* global clock at last use */
} ref_way_t;

typedef struct ref_cache {
    uint64_t sets, ways, line;
    uint32_t hit, mem;
    struct ref_cache *next;
    ref_way_t *w; /* sets * ways */
    uint64_t clock, hits, misses, writes;
} ref_cache_t;

static void ref_init(ref_cache_t *r, const char *spec, uint32_t hit, ref_cache_t *next,
                     uint32_t mem)
{
    lt_cache_cfg_t cfg;
    cfg_of(spec, &cfg);
    memset(r, 0, sizeof *r);
    r->sets = cfg.sets;
    r->ways = cfg.ways;
    r->line = cfg.line;
    r->hit = hit;
    r->mem = mem;
    r->next = next;
    r->w = calloc((size_t)(r->sets * r->ways), sizeof *r->w);
    assert_non_null(r->w);
}

static uint32_t ref_access(ref_cache_t *r, uint64_t addr, uint32_t bytes, int write)
{
    uint64_t la, end = addr + bytes - 1, cost = 0;
    if (bytes == 0) {
        return 0;
    }
    for (la = (addr / r->line) * r->line; la <= end; la += r->line) {
        uint64_t lineno = la / r->line;
        ref_way_t *set = &r->w[(lineno % r->sets) * r->ways];
        uint64_t tag = lineno / r->sets, k, victim = 0;
        uint32_t lat = 0;
        int hit = 0;
        r->clock++;
        if (write) {
            r->writes++;
        }
        for (k = 0; k < r->ways; k++) {
            if (set[k].valid && set[k].tag == tag) {
                set[k].stamp = r->clock;
                hit = 1;
                break;
            }
        }
        if (hit) {
            r->hits++;
            lat = r->hit;
        } else {
            r->misses++;
            for (k = 0; k < r->ways; k++) {
                if (!set[k].valid) {
                    victim = k;
                    break;
                }
                if (set[k].stamp < set[victim].stamp) {
                    victim = k;
                }
            }
            set[victim].valid = 1;
            set[victim].tag = tag;
            set[victim].stamp = r->clock;
            lat = r->next != NULL ? ref_access(r->next, la, (uint32_t)r->line, write) : r->mem;
        }
        if (lat > cost) {
            cost = lat;
        }
    }
    return (uint32_t)cost;
}

static uint64_t rng_state;

static uint64_t rng(void)
{
    /* xorshift64*: deterministic, independent of libc rand(). */
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    return rng_state * 0x2545F4914F6CDD1DULL;
}

#define MAX_LEVELS 3

static void run_reference(const char *const *specs, int levels, unsigned n, uint64_t seed)
{
    static const uint32_t hit[MAX_LEVELS] = { 1, 12, 40 };
    lt_cache_t c[MAX_LEVELS];
    ref_cache_t r[MAX_LEVELS];
    uint64_t l1, prev = 0x7f0000001000ULL, base = 0x7f0000000000ULL, cycles = 0;
    unsigned i;
    int l;
    char label[128] = "";

    for (l = levels - 1; l >= 0; l--) {
        init_level(&c[l], "lvl", specs[l], hit[l], l + 1 < levels ? &c[l + 1] : NULL, 300);
        ref_init(&r[l], specs[l], hit[l], l + 1 < levels ? &r[l + 1] : NULL, 300);
    }
    /* Addresses mix near-previous, 2x / 8x the first level and far, so every level sees hits and
     * misses. */
    l1 = (uint64_t)lt_cache_cfg(&c[0])->sets * lt_cache_cfg(&c[0])->ways *
         lt_cache_cfg(&c[0])->line;
    rng_state = seed;
    for (i = 0; i < n; i++) {
        uint64_t x = rng(), addr;
        uint32_t bytes, got, want;
        unsigned kind = (unsigned)(x % 10u);
        if (kind < 5) {
            addr = prev + (x >> 8) % 256u - 128u; /* near the previous access */
        } else if (kind < 8) {
            addr = base + (x >> 8) % (2u * l1); /* working set 2x L1 */
        } else if (kind < 9) {
            addr = base + (x >> 8) % (8u * l1); /* working set 8x L1 (fits many L2s) */
        } else {
            addr = base + (x >> 8) % (64u * l1); /* far */
        }
        switch ((x >> 40) % 4u) {
        case 0: bytes = 4; break;
        case 1: bytes = 64; break; /* a 16-lane vector */
        case 2: bytes = (uint32_t)((x >> 44) % 300u); break; /* includes 0 and multi-line */
        default: bytes = 1u + (uint32_t)((x >> 44) % 16u); break;
        }
        {
            int w = (int)((x >> 60) & 1u);
            got = lt_cache_access(&c[0], addr, bytes, w);
            want = ref_access(&r[0], addr, bytes, w);
        }
        if (got != want) {
            fail_msg("%s: access %u addr %llx bytes %u: cycles %u, reference %u", specs[0], i,
                     (unsigned long long)addr, bytes, got, want);
        }
        cycles += got;
        prev = addr;
    }
    for (l = 0; l < levels; l++) {
        lt_cache_stats_t s = stats_of(&c[l]);
        assert_int_equal(s.hits, r[l].hits);
        assert_int_equal(s.misses, r[l].misses);
        assert_int_equal(s.writes, r[l].writes);
        assert_int_equal(s.accesses, r[l].hits + r[l].misses);
        assert_int_equal(s.reads, r[l].hits + r[l].misses - r[l].writes);
        (void)snprintf(label + strlen(label), sizeof label - strlen(label), "%s%s %llu/%llu hit",
                       l ? " -> " : "", specs[l], (unsigned long long)s.hits,
                       (unsigned long long)s.accesses);
        lt_cache_free(&c[l]);
        free(r[l].w);
    }
    printf("cache: %u random accesses, [%s], hits/misses/writes and every access's cycles "
           "(total %llu) match reference model exactly\n", n, label, (unsigned long long)cycles);
}

static void test_reference(void **state)
{
    static const char *const single[][1] = {
        { "1:1:4" }, { "64:1:64" }, { "64:8:64" }, { "16:3:32" }, { "1:64:64" }, { "8:5:16" },
        { "256:2:128" },
    };
    static const char *const chain2[][2] = {
        { "32:4:32", "128:8:64" },  /* L2 lines larger than L1 */
        { "16:4:64", "256:8:16" },  /* L2 lines smaller: one L1 fill touches 4 L2 lines */
        { "64:8:64", "512:8:64" },  /* lrb16-like */
    };
    static const char *const chain3[3] = { "16:2:32", "64:4:64", "256:7:64" };
    size_t i;
    (void)state;
    for (i = 0; i < sizeof single / sizeof single[0]; i++) {
        run_reference(single[i], 1, 100000, 0x9E3779B97F4A7C15ULL + i);
    }
    for (i = 0; i < sizeof chain2 / sizeof chain2[0]; i++) {
        run_reference(chain2[i], 2, 100000, 0xD1B54A32D192ED03ULL + i);
    }
    run_reference(chain3, 3, 100000, 0x8CB92BA72F3D8DD7ULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_parse_good),
        cmocka_unit_test(test_parse_bad),
        cmocka_unit_test(test_parse_diag),
        cmocka_unit_test(test_init_errors),
        cmocka_unit_test(test_direct_mapped_conflict),
        cmocka_unit_test(test_lru_order),
        cmocka_unit_test(test_sweeps),
        cmocka_unit_test(test_two_levels),
        cmocka_unit_test(test_spanning),
        cmocka_unit_test(test_reference),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
