/* fuzz_cache.c - fuzz target of the cache spec parser (sim/lt_cache.c lt_cache_parse: the
 * `--l1` / `--l2` options and a scene file's "caches" object), then, for geometries it accepts,
 * a two-level chain built from them (lt_cache_init) driven by accesses taken from the input.
 * The input is "L1SPEC\nL2SPEC\n<access bytes>"; any text must parse into a geometry within the
 * documented limits or give a one-line message quoting the spec. make fuzz-cache; replayed over
 * tests/fuzz/corpus/cache in make test. Host only.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_util.h"
#include "lt_cache.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* The parser's and the model's calls, in one place (their error convention may change). */
static int parse(const char *spec, lt_cache_cfg_t *cfg, char *err, size_t cap)
{
    lt_diag_t dg;
    int r = lt_cache_parse(spec, cfg, &dg);
    fuzz_take_message(err, cap, r, &dg);
    return r;
}

static int init(lt_cache_t *c, const char *name, const lt_cache_cfg_t *cfg, lt_cache_t *next,
                char *err, size_t cap)
{
    lt_diag_t dg;
    int r = lt_cache_init(c, name, cfg, 2, next, 50, &dg);
    fuzz_take_message(err, cap, r, &dg);
    return r;
}

static int is_pow2(uint32_t v) { return v != 0 && (v & (v - 1u)) == 0; }

/* Parse one line of the input; 1 with *cfg set when accepted. */
static int one_spec(const uint8_t *p, size_t n, lt_cache_cfg_t *cfg)
{
    char *spec = malloc(n + 1), err[256];
    int ok;
    if (spec == NULL)
        return 0;
    memcpy(spec, p, n);
    spec[n] = '\0';
    memset(err, 'x', sizeof err);
    ok = parse(spec, cfg, err, sizeof err) == 0;
    if (!ok)
        fuzz_check_message(err, sizeof err);
    else if (!is_pow2(cfg->sets) || !is_pow2(cfg->line) || cfg->ways < 1 ||
             cfg->ways > LT_CACHE_MAX_WAYS || cfg->line < LT_CACHE_MIN_LINE ||
             cfg->line > LT_CACHE_MAX_LINE ||
             (uint64_t)cfg->sets * cfg->ways * cfg->line > LT_CACHE_MAX_BYTES)
        abort();
    free(spec);
    return ok;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const uint8_t *nl1 = memchr(data, '\n', size), *nl2, *rest;
    lt_cache_cfg_t c1, c2;
    lt_cache_t l1, l2;
    lt_cache_stats_t s1, s2;
    char err[256];
    int ok1, ok2;
    size_t n1 = nl1 != NULL ? (size_t)(nl1 - data) : size, left;

    ok1 = one_spec(data, n1, &c1);
    if (nl1 == NULL)
        return 0;
    nl2 = memchr(nl1 + 1, '\n', size - n1 - 1);
    ok2 = one_spec(nl1 + 1, nl2 != NULL ? (size_t)(nl2 - nl1 - 1) : size - n1 - 1, &c2);
    /* the model, on geometries small enough to set up per input (at most 64 Ki tags each) */
    if (!ok1 || !ok2 || nl2 == NULL || (uint64_t)c1.sets * c1.ways > 65536u ||
        (uint64_t)c2.sets * c2.ways > 65536u)
        return 0;
    memset(&l1, 0, sizeof l1);
    memset(&l2, 0, sizeof l2);
    if (init(&l2, "L2", &c2, NULL, err, sizeof err) != 0 ||
        init(&l1, "L1", &c1, &l2, err, sizeof err) != 0)
        abort(); /* a parsed geometry is a valid one */
    rest = nl2 + 1;
    left = size - (size_t)(rest - data);
    while (left >= 6) { /* 4 bytes address, 1 byte size, 1 byte write flag */
        uint64_t addr = (uint64_t)rest[0] << 56 | (uint64_t)rest[1] << 24 |
                        (uint64_t)rest[2] << 8 | rest[3];
        uint32_t cy = lt_cache_access(&l1, addr, rest[4], rest[5] & 1);
        if (rest[4] != 0 && cy != 2u && cy != 50u)
            abort(); /* a hit somewhere (2) or memory (50) */
        rest += 6;
        left -= 6;
    }
    lt_cache_stats(&l1, &s1);
    lt_cache_stats(&l2, &s2);
    if (s1.accesses != s1.hits + s1.misses || s2.accesses != s2.hits + s2.misses ||
        s1.reads + s1.writes != s1.accesses || (s1.misses == 0 && s2.accesses != 0))
        abort();
    lt_cache_free(&l1);
    lt_cache_free(&l2);
    return 0;
}
