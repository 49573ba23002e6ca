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
    lt_sblob_err_t wide = LT_SBLOB_OK;
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
        /* a camera whose directions pass through zero inside the image (the words above are
           zero): d00 = (-2^26, 0, 0), a column step of 2^26 / 19 and a row step along y, 39
           columns: row 0's x part is -9 at column 19 and 3532036 at column 20 */
        put_word(b, LT_SB_WIDTH, RES - 1u);
        put_word(b, LT_SB_D00, (uint32_t)-(1 << 26));
        put_word(b, LT_SB_DX, (1u << 26) / 19u);
        put_word(b, LT_SB_DY + 1u, 1u << 20);
        reseal(b, fx->bytes);
        n += lt_sblob_open(b, fx->bytes, &s) == LT_SBLOB_E_CAMERA;
        n += lt_sblob_open(b, 100, &s) == LT_SBLOB_E_SHORT;
        n += lt_sblob_open(fx->blob, fx->bytes - 1, &s) == LT_SBLOB_E_SHORT;
        /* a wide view with no zero direction is taken: corners about (-+2^27, +-2^26, 2^26),
           the left and right ones 109 degrees apart, the diagonal ones 132 (measured along the
           top-left direction, as the check did before stop 37, the right corners were behind
           it and the view was refused) */
        put_word(b, LT_SB_D00, (uint32_t)-(1 << 27));
        put_word(b, LT_SB_D00 + 1u, 1u << 26);
        put_word(b, LT_SB_D00 + 2u, 1u << 26);
        put_word(b, LT_SB_DX, (1u << 28) / 38u);
        put_word(b, LT_SB_DY + 1u, (uint32_t)-(int32_t)((1u << 27) / 39u));
        reseal(b, fx->bytes);
        wide = lt_sblob_open(b, fx->bytes, &s);
        free(b);
    }
    ltt_report("sblob: %u of %u crafted blobs refused with the expected reason (a zero camera, "
               "a camera whose directions pass through zero, short buffers, each header field out "
               "of range, a damaged byte, a bad node and index)\n",
               n, (unsigned)(sizeof c / sizeof c[0]) + 4u);
    assert_int_equal(n, sizeof c / sizeof c[0] + 4u);
    ltt_report("sblob: a 39x40 view 132 degrees wide (no zero direction) opens: %s\n",
               lt_sblob_err_str(wide));
    assert_int_equal(wide, LT_SBLOB_OK);
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

/* ---- frusta blobs ---- */

/* A frusta blob of the fixture's floor: 16 x 16 origins on the floor under and around the blocker
 * (every other one lit), a 4 x 4 unit light at y = 30, the default culling, 16 or 4 samples. */
static void make_fblob(const fixture_t *fx, uint32_t spp, uint8_t **blob, size_t *bytes,
                       lt_bvh_t *bvh, void **arena)
{
    lt_bvh_desc_t desc = {0, 8, 4, 0, 0};
    lt_q16_t org[768];
    uint32_t h[64], i;
    size_t ab;
    memset(h, 0, sizeof h);
    for (i = 0; i < 256u; i++) {
        double x = -12.0 + 1.5 * (i % 16u), z = -12.0 + 1.5 * (i / 16u);
        org[3 * i] = q(x);
        org[3 * i + 1] = q(0.3 * sin(x) + 0.01); /* the floor's height there (a sin in x only) */
        org[3 * i + 2] = q(z);
        if (i % 3u != 1u)
            h[LT_FB_LIT + i / 32u] |= 1u << (i % 32u);
    }
    h[LT_FB_LIGHT + 0] = (uint32_t)q(-2);
    h[LT_FB_LIGHT + 1] = (uint32_t)q(30);
    h[LT_FB_LIGHT + 2] = (uint32_t)q(-2);
    h[LT_FB_LIGHT + 3] = (uint32_t)q(4); /* eu = (4, 0, 0), ev = (0, 0, 4): multiples of 512 raw */
    h[LT_FB_LIGHT + 8] = (uint32_t)q(4);
    h[LT_FB_LFLAGS] = LT_FRUSTA_BACKFACE | LT_FRUSTA_CORNER | LT_FRUSTA_CR | LT_FRUSTA_LEAFRAY |
                      LT_FRUSTA_SPLIT | LT_FRUSTA_FS;
    h[LT_FB_QMC] = LT_QMC_LP;
    h[LT_FB_SPP] = spp;
    h[LT_FB_LEAF] = 8;
    assert_int_equal(lt_bvh_size(NT, &desc, &ab), LT_OK);
    assert_int_equal(posix_memalign(arena, 64, ab), 0);
    assert_int_equal(lt_bvh_build_q16(bvh, &desc, fx->tris, NT, *arena, ab), LT_OK);
    *bytes = lt_fblob_size(NT, bvh->nnodes);
    assert_int_equal(posix_memalign((void **)blob, 64, *bytes), 0);
    assert_int_equal(lt_fblob_write(fx->tris, bvh, org, h, *blob, *bytes - 4), LT_E_SPACE);
    assert_int_equal(lt_fblob_write(fx->tris, bvh, org, h, *blob, *bytes), LT_OK);
}

/* S-Frusta of the blob against the per-pixel packet baseline (lt_frusta_packet_occluded16_q16 with
 * the same culling flags) over the same tree: equal sample masks on every lit pixel. */
static void test_fblob_trace(void **state)
{
    fixture_t *fx = *state;
    uint32_t spps[2] = {16, 4}, k, agree = 0, lit = 0, occ = 0;
    for (k = 0; k < 2u; k++) {
        lt_fblob_t *f = malloc(sizeof *f);
        uint8_t *blob;
        size_t bytes;
        lt_bvh_t bvh;
        void *arena;
        uint32_t t, i;
        make_fblob(fx, spps[k], &blob, &bytes, &bvh, &arena);
        assert_int_equal(lt_fblob_open(blob, bytes, f), LT_SBLOB_OK);
        for (t = 0; t < 16u; t++) {
            lt_fblob_tile_t r;
            uint32_t tocc = 0;
            assert_int_equal(lt_fblob_trace_tile(f, t, NULL, &r), LT_OK);
            for (i = 0; i < 16u; i++) {
                uint32_t x = 4u * (t % 4u) + i % 4u, y = 4u * (t / 4u) + i / 4u, p = y * 16u + x;
                lt_ray16_q16_t ray;
                lt_mask16_t pk = 0, o = 0;
                if (!((f->lit[p / 32u] >> (p % 32u)) & 1u))
                    continue;
                lit++;
                assert_int_equal(lt_frusta_rays16_q16(&f->tb, &f->org[3u * p], i, &ray, &pk), LT_OK);
                pk = (lt_mask16_t)(pk & ((1u << f->spp) - 1u));
                assert_int_equal(lt_frusta_packet_occluded16_q16(&f->bvh, f->tris, f->tb.flags,
                                                                 &f->org[3u * p], &ray, pk, &o),
                                 LT_OK);
                tocc += lt__popcount32(o);
            }
            agree += tocc == r.occluded;
            occ += r.occluded;
        }
        assert_int_equal(lt_fblob_trace_tile(f, 16, NULL, &(lt_fblob_tile_t){0, 0, 0, 0}), LT_E_ARG);
        free(blob);
        free(arena);
        free(f);
    }
    ltt_report("fblob: S-Frusta of a 16x16 block (16 and 4 spp, every culling flag) = the packet "
               "baseline's occluded samples on %u of 32 tiles; %u lit pixels, %u occluded samples\n",
               agree, lit, occ);
    assert_int_equal(agree, 32u);
    assert_true(occ > 0 && occ < lit * 16u);
}

static void test_fblob_refusals(void **state)
{
    fixture_t *fx = *state;
    uint8_t *blob, *b;
    size_t bytes;
    lt_bvh_t bvh;
    void *arena;
    lt_fblob_t *f = malloc(sizeof *f);
    ltt_rng_t r;
    unsigned i, n = 0, refused = 0, traced = 0;
    struct {
        unsigned word;
        uint32_t v;
        lt_sblob_err_t want;
    } c[] = {
        {LT_FB_SPP, 5u, LT_SBLOB_E_IMAGE},
        {LT_FB_QMC, 7u, LT_SBLOB_E_IMAGE},
        {LT_FB_LIGHT + 3, 100u, LT_SBLOB_E_IMAGE},       /* eu off the 512-raw grid */
        {LT_FB_OFF_ORG, 0u, LT_SBLOB_E_LAYOUT},
        {LT_FB_NNODES, 0u, LT_SBLOB_E_TREE},
        {LT_FB_VERSION, 9u, LT_SBLOB_E_VERSION},
        {LT_FB_LIT, 5u, LT_SBLOB_E_SUM},                /* not resealed: damaged */
    };
    make_fblob(fx, 16, &blob, &bytes, &bvh, &arena);
    b = malloc(bytes);
    for (i = 0; i < sizeof c / sizeof c[0]; i++) {
        uint32_t z = 0, w;
        memcpy(b, blob, bytes);
        memcpy(b + 4u * c[i].word, &c[i].v, 4);
        if (c[i].want != LT_SBLOB_E_SUM && c[i].want != LT_SBLOB_E_VERSION) {
            memcpy(b + 4u * LT_FB_SUM, &z, 4);
            w = lt_sblob_fnv(LT_SBLOB_FNV0, b, bytes);
            memcpy(b + 4u * LT_FB_SUM, &w, 4);
        }
        {
            lt_sblob_err_t e = lt_fblob_open(b, bytes, f);
            if (e != c[i].want)
                printf("  word %u = %u: got %d (%s), want %d\n", c[i].word, c[i].v, (int)e,
                       lt_sblob_err_str(e), (int)c[i].want);
            n += e == c[i].want;
        }
    }
    {
        uint32_t z = 0, w, bad = 0x7FFFFFFFu, off;
        memcpy(b, blob, bytes);
        memcpy(&off, b + 4u * LT_FB_OFF_ORG, 4);
        memcpy(b + off + 40u, &bad, 4);
        memcpy(b + 4u * LT_FB_SUM, &z, 4);
        w = lt_sblob_fnv(LT_SBLOB_FNV0, b, bytes);
        memcpy(b + 4u * LT_FB_SUM, &w, 4);
        n += lt_fblob_open(b, bytes, f) == LT_SBLOB_E_GEOMETRY;
        n += lt_fblob_open(blob, 200, f) == LT_SBLOB_E_SHORT;
    }
    ltt_rng_seed(&r, 11);
    for (i = 0; i < 1000u; i++) {
        size_t w = ltt_rng_below(&r, (uint32_t)(bytes / 4u));
        uint32_t v = ltt_rng_below(&r, 2) ? ltt_rng_u32(&r) : ltt_rng_below(&r, 64), z = 0, s;
        memcpy(b, blob, bytes);
        memcpy(b + 4u * w, &v, 4);
        memcpy(b + 4u * LT_FB_SUM, &z, 4);
        s = lt_sblob_fnv(LT_SBLOB_FNV0, b, bytes);
        memcpy(b + 4u * LT_FB_SUM, &s, 4);
        if (lt_fblob_open(b, bytes, f) != LT_SBLOB_OK) {
            refused++;
        } else {
            lt_fblob_tile_t o;
            lt_status_t st = lt_fblob_trace_tile(f, (uint32_t)(i % 16u), NULL, &o);
            traced += st == LT_OK || st == LT_E_DEPTH;
        }
    }
    ltt_report("fblob: %u of %u crafted blobs refused with the expected reason; 1000 resealed "
               "one-word mutations: %u refused, %u traced a tile without a fault\n", n,
               (unsigned)(sizeof c / sizeof c[0]) + 2u, refused, traced);
    assert_int_equal(n, sizeof c / sizeof c[0] + 2u);
    assert_int_equal(refused + traced, 1000u);
    free(b);
    free(blob);
    free(arena);
    free(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_trace, setup, teardown),
        cmocka_unit_test_setup_teardown(test_refusals, setup, teardown),
        cmocka_unit_test_setup_teardown(test_mutations, setup, teardown),
        cmocka_unit_test_setup_teardown(test_fblob_trace, setup, teardown),
        cmocka_unit_test_setup_teardown(test_fblob_refusals, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
