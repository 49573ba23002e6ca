/* test_sblob.c - cmocka tests of the scene blob (firmware/apps/lt_sblob.[ch]): a blob written by
 * lt_sblob_write opens and traces; packets and single rays give the same tile hashes; the ids
 * agree with a brute-force double-precision tracer along the blob's own integer camera rays; every
 * refusal class is hit by a crafted blob; and 3000 resealed random mutations either are refused or
 * trace without a fault (the sanitizer build runs this too).
 * Builds: host, sim, asan.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lt/lt.h"
#include "lt_sblob.h"
#include "lt_test_util.h"

#define GRID 8 /* floor of GRID x GRID quads, a blocker above it */
#define NT (2 * GRID * GRID + 2)
#define RES 40 /* not a multiple of the 16-pixel tile: partial tiles and packets */

typedef struct fixture {
    lt_tri_q16_t tris[NT];
    uint8_t *blob;
    size_t bytes;
} fixture_t;

static lt_q16_t q(double x)
{
    return (lt_q16_t)floor(x * 65536.0 + 0.5);
}

static void tri(lt_tri_q16_t *t, const double a[3], const double b[3], const double c[3])
{
    int k;
    for (k = 0; k < 3; k++) {
        t->v0[k] = q(a[k]);
        t->e1[k] = q(b[k]) - q(a[k]);
        t->e2[k] = q(c[k]) - q(a[k]);
    }
}

/* A bumpy floor of 128 triangles in [-16, 16]^2 at y ~ 0 and a square blocker at y = 6. */
static void scene(lt_tri_q16_t *t)
{
    int i, j, n = 0;
    for (i = 0; i < GRID; i++)
        for (j = 0; j < GRID; j++) {
            double x0 = -16.0 + 4.0 * i, z0 = -16.0 + 4.0 * j;
            double p00[3] = {x0, 0.3 * sin(x0), z0}, p10[3] = {x0 + 4, 0.3 * sin(x0 + 4), z0};
            double p01[3] = {x0, 0.3 * sin(x0), z0 + 4}, p11[3] = {x0 + 4, 0.3 * sin(x0 + 4), z0 + 4};
            tri(&t[n++], p00, p10, p11);
            tri(&t[n++], p00, p11, p01);
        }
    {
        double a[3] = {-5, 6, -5}, b[3] = {5, 6, -5}, c[3] = {5, 6, 5}, d[3] = {-5, 6, 5};
        tri(&t[n++], a, b, c);
        tri(&t[n++], a, c, d);
    }
}

/* A camera at (3, 20, 40) looking at the origin, 50 degrees, as the integer words. */
static void view(lt_sblob_view_t *v)
{
    double eye[3] = {3, 20, 40}, f[3], r[3], u[3], len, t = tan(25.0 * 3.14159265358979323846 / 180.0), s;
    int a;
    memset(v, 0, sizeof *v);
    for (a = 0; a < 3; a++)
        f[a] = -eye[a];
    len = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (a = 0; a < 3; a++)
        f[a] /= len;
    r[0] = -f[2];
    r[1] = 0;
    r[2] = f[0];
    len = sqrt(r[0] * r[0] + r[2] * r[2]);
    r[0] /= len;
    r[2] /= len;
    u[0] = r[1] * f[2] - r[2] * f[1];
    u[1] = r[2] * f[0] - r[0] * f[2];
    u[2] = r[0] * f[1] - r[1] * f[0];
    s = ldexp(1.0, 27);
    for (a = 0; a < 3; a++) {
        double d00 = f[a] + (1.0 / RES - 1.0) * t * r[a] + (1.0 - 1.0 / RES) * t * u[a];
        v->eye[a] = q(eye[a]);
        v->d00[a] = (int32_t)floor(d00 * s + 0.5);
        v->dx[a] = (int32_t)floor(2.0 * t / RES * r[a] * s + 0.5);
        v->dy[a] = (int32_t)floor(-2.0 * t / RES * u[a] * s + 0.5);
    }
    v->light[0] = q(-10);
    v->light[1] = q(40);
    v->light[2] = q(4);
    v->width = v->height = RES;
    v->flags = LT_SBLOB_F_SHADOWS;
    v->eps = q(0.01);
}

static int setup(void **state)
{
    fixture_t *fx = calloc(1, sizeof *fx);
    lt_bvh_desc_t desc = {0, 4, 0, 0, 0};
    lt_sblob_view_t v;
    lt_bvh_t bvh;
    size_t ab;
    void *arena;
    assert_non_null(fx);
    scene(fx->tris);
    view(&v);
    assert_int_equal(lt_bvh_size(NT, &desc, &ab), LT_OK);
    assert_int_equal(posix_memalign(&arena, 64, ab), 0);
    assert_int_equal(lt_bvh_build_q16(&bvh, &desc, fx->tris, NT, arena, ab), LT_OK);
    fx->bytes = lt_sblob_size(NT, bvh.nnodes);
    assert_int_equal(posix_memalign((void **)&fx->blob, 64, fx->bytes), 0);
    assert_int_equal(lt_sblob_write(fx->tris, &bvh, 4, &v, fx->blob, fx->bytes - 1), LT_E_SPACE);
    assert_int_equal(lt_sblob_write(fx->tris, &bvh, 4, &v, fx->blob, fx->bytes), LT_OK);
    free(arena);
    *state = fx;
    return 0;
}

static int teardown(void **state)
{
    fixture_t *fx = *state;
    free(fx->blob);
    free(fx);
    return 0;
}

/* Brute force in double along the blob's integer direction of pixel (x, y): the nearest triangle
 * (Moller-Trumbore in double on the s15.16 vertices), or -1. */
static int32_t ref_trace(const fixture_t *fx, const lt_sblob_t *s, uint32_t x, uint32_t y)
{
    double o[3], d[3], best = HUGE_VAL;
    int32_t id = -1;
    uint32_t i;
    int a;
    for (a = 0; a < 3; a++) {
        o[a] = s->eye[a] / 65536.0;
        d[a] = (double)s->d00[a] + (double)x * s->dx[a] + (double)y * s->dy[a];
    }
    for (i = 0; i < NT; i++) {
        const lt_tri_q16_t *t = &fx->tris[i];
        double v0[3], e1[3], e2[3], p[3], tv[3], qv[3], det, u, v, tt;
        for (a = 0; a < 3; a++) {
            v0[a] = t->v0[a] / 65536.0;
            e1[a] = t->e1[a] / 65536.0;
            e2[a] = t->e2[a] / 65536.0;
        }
        p[0] = d[1] * e2[2] - d[2] * e2[1];
        p[1] = d[2] * e2[0] - d[0] * e2[2];
        p[2] = d[0] * e2[1] - d[1] * e2[0];
        det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
        if (det == 0.0)
            continue;
        for (a = 0; a < 3; a++)
            tv[a] = o[a] - v0[a];
        u = (tv[0] * p[0] + tv[1] * p[1] + tv[2] * p[2]) / det;
        qv[0] = tv[1] * e1[2] - tv[2] * e1[1];
        qv[1] = tv[2] * e1[0] - tv[0] * e1[2];
        qv[2] = tv[0] * e1[1] - tv[1] * e1[0];
        v = (d[0] * qv[0] + d[1] * qv[1] + d[2] * qv[2]) / det;
        tt = (e2[0] * qv[0] + e2[1] * qv[1] + e2[2] * qv[2]) / det;
        if (u >= 0 && v >= 0 && u + v <= 1 && tt > 0 && tt < best) {
            best = tt;
            id = (int32_t)i;
        }
    }
    return id;
}

static void test_trace(void **state)
{
    fixture_t *fx = *state;
    lt_sblob_t s;
    int32_t ids[LT_SBLOB_TILE * LT_SBLOB_TILE];
    uint32_t t, same = 0, px = 0, hits = 0, occ = 0, srays = 0, hm = 0, equal = 0;
    assert_int_equal(lt_sblob_open(fx->blob, fx->bytes, &s), LT_SBLOB_OK);
    assert_int_equal(s.tiles_x, 3);
    for (t = 0; t < s.tiles_x * s.tiles_y; t++) {
        lt_sblob_tile_t a, b;
        uint32_t x, y, x0 = (t % s.tiles_x) * 16u, y0 = (t / s.tiles_x) * 16u;
        a.ids = ids;
        b.ids = NULL;
        assert_int_equal(lt_sblob_trace_tile(&s, t, 0, NULL, &a), LT_OK);
        assert_int_equal(lt_sblob_trace_tile(&s, t, 1, NULL, &b), LT_OK);
        equal += a.hash == b.hash && a.hits == b.hits && a.occluded == b.occluded;
        hits += a.hits;
        occ += a.occluded;
        srays += a.srays;
        for (y = y0; y < y0 + 16u && y < RES; y++)
            for (x = x0; x < x0 + 16u && x < RES; x++) {
                int32_t r = ref_trace(fx, &s, x, y), g = ids[(y - y0) * 16u + (x - x0)];
                px++;
                same += r == g;
                hm += (r < 0) != (g < 0);
            }
    }
    ltt_report("sblob: %u triangles %ux%u: packets = single rays on %u of %u tiles; %u hits, %u "
               "shadow rays, %u occluded; same triangle as a double brute force on %u of %u "
               "pixels (bound >= 99%%), hit/miss differs on %u (bound <= 1%%)\n",
               NT, RES, RES, equal, s.tiles_x * s.tiles_y, hits, srays, occ, same, px, hm);
    assert_int_equal(equal, s.tiles_x * s.tiles_y);
    assert_int_equal(px, RES * RES);
    assert_true(hits > px / 4u && occ > 0 && occ < hits);
    assert_true(same * 100u >= px * 99u);
    assert_true(hm * 100u <= px);
    assert_int_equal(lt_sblob_trace_tile(&s, 9, 0, NULL, &(lt_sblob_tile_t){.ids = NULL}), LT_E_ARG);
}

static void put_word(uint8_t *b, unsigned w, uint32_t v)
{
    memcpy(b + 4u * w, &v, 4);
}

static uint32_t word(const uint8_t *b, size_t off)
{
    uint32_t v;
    memcpy(&v, b + off, 4);
    return v;
}

static void reseal(uint8_t *b, size_t n)
{
    put_word(b, LT_SB_SUM, lt_sblob_sum(b, n));
}

/* A copy of the blob with word w (header word index when off < 0, else a byte offset) set to v,
 * resealed unless raw: what lt_sblob_open says. */
static lt_sblob_err_t try_set(const fixture_t *fx, long off, uint32_t v, int raw)
{
    uint8_t *b = malloc(fx->bytes);
    lt_sblob_t s;
    lt_sblob_err_t e;
    memcpy(b, fx->blob, fx->bytes);
    memcpy(b + off, &v, 4);
    if (!raw)
        reseal(b, fx->bytes);
    e = lt_sblob_open(b, fx->bytes, &s);
    free(b);
    return e;
}

static void test_refusals(void **state)
{
    fixture_t *fx = *state;
    const uint8_t *h = fx->blob;
    size_t on = word(h, 4u * LT_SB_OFF_NODES), oi = word(h, 4u * LT_SB_OFF_IDX);
    lt_sblob_t s;
    unsigned n = 0;
    struct {
        const char *what;
        long off;
        uint32_t v;
        int raw;
        lt_sblob_err_t want;
    } c[] = {
        {"bad magic", 0, 0x4253544Du, 1, LT_SBLOB_E_MAGIC},
        {"version 2", 4 * LT_SB_VERSION, 2u, 1, LT_SBLOB_E_VERSION},
        {"byte count past the end", 4 * LT_SB_BYTES, (uint32_t)fx->bytes + 4u, 1, LT_SBLOB_E_SHORT},
        {"a payload byte flipped", (long)on + 8, word(h, on + 8) ^ 0x100u, 1, LT_SBLOB_E_SUM},
        {"a header word flipped", 4 * LT_SB_WIDTH, RES + 1, 1, LT_SBLOB_E_SUM},
        {"nodes past the end", 4 * LT_SB_OFF_NODES, (uint32_t)fx->bytes, 0, LT_SBLOB_E_LAYOUT},
        {"misaligned triangles", 4 * LT_SB_OFF_TRIS, LT_SBLOB_HEADER_BYTES + 2u, 0, LT_SBLOB_E_LAYOUT},
        {"triangles over the header", 4 * LT_SB_OFF_TRIS, 64u, 0, LT_SBLOB_E_LAYOUT},
        {"width 0", 4 * LT_SB_WIDTH, 0u, 0, LT_SBLOB_E_IMAGE},
        {"width 4097", 4 * LT_SB_WIDTH, 4097u, 0, LT_SBLOB_E_IMAGE},
        {"eps 0", 4 * LT_SB_EPS, 0u, 0, LT_SBLOB_E_IMAGE},
        {"unknown flag", 4 * LT_SB_FLAGS, 6u, 0, LT_SBLOB_E_IMAGE},
        {"d00 of 2^30", 4 * LT_SB_D00, 1u << 30, 0, LT_SBLOB_E_CAMERA},
        {"eye outside the bound", 4 * LT_SB_EYE, (uint32_t)1 << 30, 0, LT_SBLOB_E_GEOMETRY},
        {"a vertex outside the bound", LT_SBLOB_HEADER_BYTES + 36 * 5, 0x7FFFFFFFu, 0,
         LT_SBLOB_E_GEOMETRY},
        {"zero triangles", 4 * LT_SB_NTRIS, 0u, 0, LT_SBLOB_E_TREE},
        {"root child to itself", (long)on + 24, 0u, 0, LT_SBLOB_E_TREE},
        {"root child past the nodes", (long)on + 24, 100000u, 0, LT_SBLOB_E_TREE},
        {"an index out of range", (long)oi + 4, NT, 0, LT_SBLOB_E_TREE},
        {"leaf limit 0", 4 * LT_SB_LEAF, 0u, 0, LT_SBLOB_E_TREE},
        {"depth 65", 4 * LT_SB_DEPTH, 65u, 0, LT_SBLOB_E_TREE},
    };
    unsigned i;
    for (i = 0; i < sizeof c / sizeof c[0]; i++) {
        lt_sblob_err_t e = try_set(fx, c[i].off, c[i].v, c[i].raw);
        if (e != c[i].want)
            printf("  %s: got %d (%s), want %d\n", c[i].what, (int)e, lt_sblob_err_str(e),
                   (int)c[i].want);
        n += e == c[i].want;
    }
    /* no direction can be zero: all three camera vectors zero */
    {
        uint8_t *b = malloc(fx->bytes);
        unsigned w;
        memcpy(b, fx->blob, fx->bytes);
        for (w = LT_SB_D00; w < LT_SB_DY + 3u; w++)
            put_word(b, w, 0);
        reseal(b, fx->bytes);
        n += lt_sblob_open(b, fx->bytes, &s) == LT_SBLOB_E_CAMERA;
        n += lt_sblob_open(b, 100, &s) == LT_SBLOB_E_SHORT;
        n += lt_sblob_open(fx->blob, fx->bytes - 1, &s) == LT_SBLOB_E_SHORT;
        free(b);
    }
    ltt_report("sblob: %u of %u crafted blobs refused with the expected reason (a zero camera, "
               "short buffers, each header field out of range, a damaged byte, a bad node and "
               "index)\n", n, (unsigned)(sizeof c / sizeof c[0]) + 3u);
    assert_int_equal(n, sizeof c / sizeof c[0] + 3u);
}

/* Random single-word mutations, resealed so they pass the checksum: open refuses or the trace
 * runs to the end (LT_OK, or LT_E_DEPTH from a deep foreign tree) without a fault. */
static void test_mutations(void **state)
{
    fixture_t *fx = *state;
    uint8_t *b = malloc(fx->bytes);
    ltt_rng_t r;
    unsigned i, refused = 0, traced = 0;
    ltt_rng_seed(&r, 7);
    for (i = 0; i < 3000u; i++) {
        lt_sblob_t s;
        size_t w = ltt_rng_below(&r, (uint32_t)(fx->bytes / 4u));
        uint32_t v = word(fx->blob, 4u * w), t;
        int ok = 1;
        switch (ltt_rng_below(&r, 4)) {
        case 0: v ^= 1u << ltt_rng_below(&r, 32); break;
        case 1: v = ltt_rng_u32(&r); break;
        case 2: v += ltt_rng_below(&r, 9) - 4u; break;
        default: v = ltt_rng_below(&r, 2) ? 0u : 0xFFFFFFFFu; break;
        }
        memcpy(b, fx->blob, fx->bytes);
        put_word(b, (unsigned)w, v);
        if (w != LT_SB_SUM)
            reseal(b, fx->bytes);
        if (lt_sblob_open(b, fx->bytes, &s) != LT_SBLOB_OK) {
            refused++;
            continue;
        }
        for (t = 0; t < s.tiles_x * s.tiles_y; t++) {
            lt_sblob_tile_t o;
            lt_status_t st;
            o.ids = NULL;
            st = lt_sblob_trace_tile(&s, t, (int)(t & 1u), NULL, &o);
            ok &= st == LT_OK || st == LT_E_DEPTH;
        }
        traced += (unsigned)ok;
        assert_true(ok);
    }
    ltt_report("sblob: 3000 resealed one-word mutations: %u refused by lt_sblob_open, %u traced "
               "every tile without a fault\n", refused, traced);
    assert_int_equal(refused + traced, 3000u);
    free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_trace, setup, teardown),
        cmocka_unit_test_setup_teardown(test_refusals, setup, teardown),
        cmocka_unit_test_setup_teardown(test_mutations, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
