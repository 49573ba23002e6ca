/* test_kd.c - cmocka tests of the kd-tree (lt_kd.h) in s15.16 and float32: the size query and
 * arena guards, the tree's invariants (every leaf holds exactly the triangles whose bounds touch
 * its box), and closest hits / occlusion of 16-ray packets against lt_chunks_trace16 (the same
 * triangle kernel over a flat list, itself tested against double in test_isect.c) and, for the
 * bundled teapot and ../shared/scenes/bunny.obj, against the double-precision brute force.
 *
 * Numeric bound. The kd-tree and the chunks run the same lt_tri16 kernel, so a triangle's t is
 * bit-identical in both; they can differ only in which triangles a lane gets to test. A lane stops
 * once its hit lies inside the current node's [tnear, tfar], and a node interval ends at a plane
 * distance t = (plane - o) x (1/d), off by at most 2^-17 (1 + |plane - o|) in s15.16
 * (docs/numerics.md, slab bound) or a few ulps of |plane - o| in float32: the plane part of the
 * bound is e = 2^-16 (4 + L) (s15.16) or 2^-20 (4 + L) (float32), L = |origin|_inf + the scene's
 * largest |coordinate|. The kernel's own t and edge errors (test_isect.c's triangle bound,
 * evaluated here in double on the kernel's inputs) make the rest: coplanar triangles whose t
 * differ by their error, or a hit past an edge by less than the error, which may lie outside every
 * node holding the triangle (or outside the reference's chunk box). So a different id is accepted
 * only if (within) both hit, the structure's hit is what lt_tri16 gives alone, and the two t differ
 * by <= e + both triangles' t bounds; or (edge) one side misses and the other side's triangle is
 * neither a sure hit nor a sure miss in double within the kernel's bounds. Same id must mean the
 * same t bit for bit; >= 99.99% of camera rays must get the same id.
 * Builds: host, sim (also prints per-ray counters on the lrb16 model), asan (fewer packets).
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

#include "lt/lt_kd.h"
#include "io/lt_fx_float.h"
#include "io/lt_mesh.h"
#include "render/lt_scene.h"
#include "lt_test_util.h"
#include "lt_kdgrid_testlib.h"
/* Tree invariants: children inside [0, nnodes), splits strictly inside the node box, every node
 * reached once, leaf ranges inside refs[] without repeated ids, the counts in the tree record
 * right, and each leaf holding exactly the triangles whose vertex bounds touch its closed box,
 * which is what the partition rule (lo <= plane -> left, hi >= plane -> right) produces. The
 * last one is checked per triangle: walking down with that rule reaches exactly the leaves that
 * list it, and the reached (triangle, leaf) pairs add up to nrefs. */
typedef struct kdchk {
    unsigned long nodes, refs, bad, leaves, pairs;
    unsigned depth;
} kdchk_t;

#define DEFINE_KD_CHECK(SFX, KD, TRI, T)                                                           \
    static void kd_shape_##SFX(const KD *kd, uint32_t ni, T lo[3], T hi[3], unsigned depth,        \
                               kdchk_t *c)                                                         \
    {                                                                                              \
        uint32_t i, j;                                                                             \
        if (ni >= kd->nnodes) {                                                                    \
            c->bad++;                                                                              \
            return;                                                                                \
        }                                                                                          \
        c->nodes++;                                                                                \
        c->depth = depth > c->depth ? depth : c->depth;                                            \
        if (LT_KD_IS_LEAF(&kd->nodes[ni])) {                                                       \
            uint32_t f = kd->nodes[ni].u.first, n = LT_KD_COUNT(&kd->nodes[ni]);                   \
            c->leaves++;                                                                           \
            if ((uint64_t)f + n > kd->nrefs) {                                                     \
                c->bad++;                                                                          \
                return;                                                                            \
            }                                                                                      \
            c->refs += n;                                                                          \
            for (i = 0; i < n; i++) {                                                              \
                c->bad += kd->refs[f + i] >= kd->ntris;                                            \
                for (j = 0; j < i; j++)                                                            \
                    c->bad += kd->refs[f + j] == kd->refs[f + i];                                  \
            }                                                                                      \
        } else {                                                                                   \
            unsigned a = LT_KD_AXIS(&kd->nodes[ni]);                                               \
            uint32_t ch = LT_KD_CHILD(&kd->nodes[ni]);                                             \
            T s = kd->nodes[ni].u.split, l2[3], h2[3];                                             \
            if (!(s > lo[a] && s < hi[a]))                                                         \
                c->bad++;                                                                          \
            memcpy(l2, lo, sizeof l2);                                                             \
            memcpy(h2, hi, sizeof h2);                                                             \
            h2[a] = s;                                                                             \
            kd_shape_##SFX(kd, ch, lo, h2, depth + 1, c);                                          \
            l2[a] = s;                                                                             \
            kd_shape_##SFX(kd, ch + 1u, l2, hi, depth + 1, c);                                     \
        }                                                                                          \
    }                                                                                              \
    /* Walk triangle t down by the partition rule; every leaf reached must list it. */             \
    static void kd_walk_##SFX(const KD *kd, uint32_t ni, uint32_t t, const T tl[3],                \
                              const T th[3], kdchk_t *c)                                           \
    {                                                                                              \
        const KD *k = kd;                                                                          \
        while (ni < k->nnodes && !LT_KD_IS_LEAF(&k->nodes[ni])) {                                  \
            unsigned a = LT_KD_AXIS(&k->nodes[ni]);                                                \
            uint32_t ch = LT_KD_CHILD(&k->nodes[ni]);                                              \
            T s = k->nodes[ni].u.split;                                                            \
            int l = tl[a] <= s, r = th[a] >= s;                                                    \
            if (l && r)                                                                            \
                kd_walk_##SFX(k, ch + 1u, t, tl, th, c);                                           \
            ni = l ? ch : ch + 1u;                                                                 \
        }                                                                                          \
        if (ni < k->nnodes) {                                                                      \
            uint32_t f = k->nodes[ni].u.first, n = LT_KD_COUNT(&k->nodes[ni]), i, in = 0;          \
            for (i = 0; i < n && f + i < k->nrefs; i++)                                            \
                in |= k->refs[f + i] == t;                                                         \
            c->pairs++;                                                                            \
            if (!in && c->bad++ < 4)                                                               \
                ltt_report("  FAIL kd leaf %u: triangle %u touches its box but is not listed\n",  \
                           ni, t);                                                                 \
        }                                                                                          \
    }                                                                                              \
    static void kd_verify_##SFX(const KD *kd, const char *what, uint32_t rmax, uint32_t maxd)      \
    {                                                                                              \
        kdchk_t c;                                                                                 \
        T lo[3], hi[3];                                                                            \
        uint32_t t;                                                                                \
        memset(&c, 0, sizeof c);                                                                   \
        memcpy(lo, kd->bounds.lo, sizeof lo);                                                      \
        memcpy(hi, kd->bounds.hi, sizeof hi);                                                      \
        kd_shape_##SFX(kd, 0, lo, hi, 0, &c);                                                      \
        for (t = 0; t < kd->ntris; t++) {                                                          \
            const TRI *tr = &kd->tris[t];                                                          \
            T tl[3], th[3];                                                                        \
            int a;                                                                                 \
            for (a = 0; a < 3; a++) {                                                              \
                T p0 = tr->v0[a], p1 = (T)(p0 + tr->e1[a]), p2 = (T)(p0 + tr->e2[a]);              \
                tl[a] = p0 < p1 ? p0 : p1;                                                         \
                th[a] = p0 < p1 ? p1 : p0;                                                         \
                tl[a] = p2 < tl[a] ? p2 : tl[a];                                                   \
                th[a] = p2 > th[a] ? p2 : th[a];                                                   \
                c.bad += tl[a] < lo[a] || th[a] > hi[a];                                           \
            }                                                                                      \
            kd_walk_##SFX(kd, 0, t, tl, th, &c);                                                   \
        }                                                                                          \
        if (c.nodes != kd->nnodes || c.refs != kd->nrefs || c.pairs != kd->nrefs ||               \
            c.leaves != kd->nleaves || c.depth != kd->depth || kd->nrefs > rmax ||                 \
            kd->depth > maxd)                                                                      \
            c.bad++;                                                                               \
        ltt_report("%s: %u nodes (%u leaves, %u empty), %u refs (%.2f per triangle, budget %u), " \
                   "depth %u (max %u), %lu invariant violations\n",                                \
                   what, kd->nnodes, kd->nleaves, kd->nempty, kd->nrefs,                           \
                   kd->ntris ? (double)kd->nrefs / kd->ntris : 0.0, rmax, kd->depth, maxd, c.bad); \
        assert_int_equal(c.bad, 0);                                                                \
    }

DEFINE_KD_CHECK(q16, lt_kd_q16_t, lt_tri_q16_t, lt_q16_t)
#if LT_CFG_FLOAT32
DEFINE_KD_CHECK(f32, lt_kd_f32_t, lt_tri_f32_t, float)
#endif

/* Collect up to 64 split planes (breadth-first from the root) for rays that start on them. */
static void kd_planes(const lt_kd_q16_t *kd, planes_t *pl)
{
    uint32_t queue[64], qh = 0, qt = 0;
    pl->n = 0;
    if (kd->nnodes == 0)
        return;
    queue[qt++] = 0;
    while (qh < qt && pl->n < 64) {
        const lt_kd_node_q16_t *nd = &kd->nodes[queue[qh++]];
        if (LT_KD_IS_LEAF(nd))
            continue;
        pl->axis[pl->n] = (int)LT_KD_AXIS(nd);
        pl->pos[pl->n] = lt_q16_to_double(nd->u.split);
        pl->n++;
        if (qt + 2 <= 64) {
            queue[qt++] = LT_KD_CHILD(nd);
            queue[qt++] = LT_KD_CHILD(nd) + 1u;
        }
    }
}

static uint32_t default_max_depth(uint32_t n)
{
    unsigned l = 0;
    while ((n >> l) > 1)
        l++;
    return 8u + (13u * l) / 10u;
}

/* ---- tests ---------------------------------------------------------------------------------- */

static void test_kd_size_and_arena(void **state)
{
    lt_kd_params_t p, bad;
    ltt_rng_t r;
    double *v;
    mesh_t m;
    size_t sz, got, sz2;
    unsigned char *mem;
    lt_kd_q16_t kd;
    unsigned i, nbadp = 0;
    (void)state;
    ltt_rng_seed(&r, 0x6b64);
    lt_kd_params_default(&p);
    v = gen_soup(&r, 300, 50.0);
    mesh_init(&m, v, 300);
    assert_int_equal(lt_kd_size(300, NULL, &sz), LT_OK);
    assert_int_equal(lt_kd_size(300, &p, &sz2), LT_OK);
    assert_true(sz == sz2);
    /* the stated formula: (2R - 1) x 8 + (R + n) x 4 + (depth + 2) x 48, R = 4n */
    assert_true(sz == (size_t)(2 * 1200 - 1) * 8 + (size_t)(1200 + 300) * 4 +
                          (size_t)(default_max_depth(300) + 2) * 48);
    /* too small: LT_E_SPACE with the needed size, nothing written; a NULL arena asks the size */
    mem = malloc(sz + GUARD);
    assert_non_null(mem);
    ltt_poison(mem, sz + GUARD);
    got = sz - 1;
    assert_int_equal(lt_kd_build_q16(&kd, m.tq, m.n, &p, mem, &got), LT_E_SPACE);
    assert_true(got == sz);
    assert_int_equal(ltt_touched(mem, 0, sz + GUARD), 0);
    got = 0;
    assert_int_equal(lt_kd_build_q16(&kd, m.tq, m.n, &p, NULL, &got), LT_E_SPACE);
    assert_true(got == sz);
    /* exact arena: OK, nothing past sz written, the tree compacted into kd.bytes */
    got = sz;
    assert_int_equal(lt_kd_build_q16(&kd, m.tq, m.n, &p, mem, &got), LT_OK);
    assert_int_equal(ltt_touched(mem, sz, sz + GUARD), 0);
    assert_true(got == kd.bytes && kd.bytes == (size_t)kd.nnodes * 8 + (size_t)kd.nrefs * 4);
    ltt_report("lt_kd_size(300 tris, defaults) = %zu bytes (= (2*4n-1)*8 + 5n*4 + (depth+2)*48); "
               "sz-1 -> LT_E_SPACE needing %zu, arena untouched; exact arena -> LT_OK, 0xA5 tail "
               "untouched, tree compacted to %zu bytes (%u nodes + %u refs)\n",
               sz, sz, kd.bytes, kd.nnodes, kd.nrefs);
    /* argument and parameter errors */
    got = sz;
    assert_int_equal(lt_kd_build_q16(NULL, m.tq, m.n, &p, mem, &got), LT_E_ARG);
    assert_int_equal(lt_kd_build_q16(&kd, NULL, m.n, &p, mem, &got), LT_E_ARG);
    assert_int_equal(lt_kd_build_q16(&kd, m.tq, m.n, &p, mem, NULL), LT_E_ARG);
    assert_int_equal(lt_kd_build_q16(&kd, m.tq, m.n, &p, mem + 1, &got), LT_E_ARG);
    assert_int_equal(lt_kd_size(300, &p, NULL), LT_E_ARG);
    assert_int_equal(lt_kd_size(LT_KD_MAX_TRIS + 1u, &p, &got), LT_E_RANGE);
    for (i = 0; i < 10; i++) {
        bad = p;
        switch (i) {
        case 0: bad.leaf_tris = 0; break;
        case 1: bad.max_depth = LT_KD_MAX_DEPTH + 1; break;
        case 2: bad.cost_trav = 0; break;
        case 3: bad.cost_trav = 256; break;
        case 4: bad.cost_isect = 0; break;
        case 5: bad.cost_isect = 256; break;
        case 6: bad.empty_bonus_q8 = 0; break;
        case 7: bad.empty_bonus_q8 = 257; break;
        case 8: bad.ref_factor = 0; break;
        default: bad.ref_factor = 17; break;
        }
        nbadp += lt_kd_size(300, &bad, &got) == LT_E_ARG;
    }
    assert_int_equal(nbadp, 10);
    /* a vertex outside +-2^LT_CFG_GEOM_MAX_LOG2 units */
    {
        lt_tri_q16_t t = m.tq[0];
        size_t s1;
        t.v0[1] = (lt_q16_t)(((int64_t)1 << (LT_CFG_GEOM_MAX_LOG2 + 16)) + 1);
        assert_int_equal(lt_kd_size(1, &p, &s1), LT_OK);
        got = s1;
        assert_int_equal(lt_kd_build_q16(&kd, &t, 1, &p, mem, &got), LT_E_RANGE);
    }
#if LT_CFG_FLOAT32
    {
        lt_tri_f32_t t = m.tf[0];
        lt_kd_f32_t kf;
        size_t s1;
        assert_int_equal(lt_kd_size(1, &p, &s1), LT_OK);
        t.e1[2] = (float)HUGE_VAL;
        got = s1;
        assert_int_equal(lt_kd_build_f32(&kf, &t, 1, &p, mem, &got), LT_E_RANGE);
    }
#endif
    ltt_report("lt_kd_build: NULL kd/tris/bytes and misaligned arena -> LT_E_ARG; 10 bad parameters "
               "-> LT_E_ARG; n > 2^24 and a vertex beyond 2^%d units (or non-finite) -> "
               "LT_E_RANGE\n",
               LT_CFG_GEOM_MAX_LOG2);
    free(mem);
    mesh_free(&m);
    free(v);
}

/* Random meshes (a soup with degenerate and plane-aligned triangles, a terrain with shared
 * edges and walls), several parameter sets, against the chunks reference. */
static void test_kd_random(void **state)
{
    static const struct {
        const char *name;
        uint32_t leaf, depth, rf;
    } cfgs[] = {{"defaults", 2, 0, 4}, {"leaf 1, depth 40", 1, 40, 16}, {"shallow (depth 3)", 4, 3, 2}};
    ltt_rng_t r;
    unsigned mi, ci, pk, f32;
    (void)state;
    ltt_rng_seed(&r, 0x6b6401);
    for (mi = 0; mi < 2; mi++) {
        uint32_t n = 400;
        double *v = mi == 0 ? gen_soup(&r, n, 60.0) : gen_terrain(&r, 12, 80.0, &n);
        mesh_t m;
        mesh_init(&m, v, n);
        for (ci = 0; ci < sizeof cfgs / sizeof cfgs[0]; ci++) {
            lt_kd_params_t p;
            kdpair_t kp;
            acc_t ak, ac;
            planes_t pl;
            cmp_t cq, cf;
            unsigned long kinds[LANE_KINDS] = {0};
            char what[160];
            lt_kd_params_default(&p);
            p.leaf_tris = cfgs[ci].leaf;
            p.max_depth = cfgs[ci].depth;
            p.ref_factor = cfgs[ci].rf;
            kd_build_pair(&kp, &m, &p);
            snprintf(what, sizeof what, "kd q16 %s (%s)", mi ? "terrain" : "soup", cfgs[ci].name);
            kd_verify_q16(&kp.q, what, p.ref_factor * n,
                          p.max_depth ? p.max_depth : default_max_depth(n));
#if LT_CFG_FLOAT32
            snprintf(what, sizeof what, "kd f32 %s (%s)", mi ? "terrain" : "soup", cfgs[ci].name);
            kd_verify_f32(&kp.f, what, p.ref_factor * n,
                          p.max_depth ? p.max_depth : default_max_depth(n));
#endif
            acc_kd(&ak, &kp);
            acc_chunks(&ac, &m);
            kd_planes(&kp.q, &pl);
            memset(&cq, 0, sizeof cq);
            memset(&cf, 0, sizeof cf);
            for (pk = 0; pk < NPACKETS; pk++) {
                pk_t p16;
                gen_packet(&r, &m, &pl, &p16, kinds);
                for (f32 = 0; f32 < 2; f32++) {
                    res16_t rs, rr;
#if !LT_CFG_FLOAT32
                    if (f32)
                        continue;
#endif
                    (f32 ? &cf : &cq)->contract += run(&ak, (int)f32, &p16, &rs);
                    (void)run(&ac, (int)f32, &p16, &rr);
                    judge(f32 ? &cf : &cq, "kd", &m, (int)f32, &p16, &rs, &rr);
                }
            }
            snprintf(what, sizeof what, "lt_kd_trace16_q16 vs chunks, %s, %s",
                     mi ? "terrain 296 tris" : "soup 400 tris", cfgs[ci].name);
            cmp_print(&cq, what);
            cmp_assert(&cq, 0.0);
#if LT_CFG_FLOAT32
            snprintf(what, sizeof what, "lt_kd_trace16_f32 vs chunks, %s, %s",
                     mi ? "terrain 296 tris" : "soup 400 tris", cfgs[ci].name);
            cmp_print(&cf, what);
            cmp_assert(&cf, 0.0);
#endif
            if (ci == 0)
                ltt_report("  lanes per kind: %s %lu, %s %lu, %s %lu, %s %lu, %s %lu, %s %lu "
                           "(%u split planes used as origins)\n",
                           lane_kind_names[0], kinds[0], lane_kind_names[1], kinds[1],
                           lane_kind_names[2], kinds[2], lane_kind_names[3], kinds[3],
                           lane_kind_names[4], kinds[4], lane_kind_names[5], kinds[5], pl.n);
            kd_free_pair(&kp);
        }
        mesh_free(&m);
        free(v);
    }
}

/* Empty scene, one triangle, only degenerate triangles, rays missing the bounds. */
static void test_kd_edge_cases(void **state)
{
    ltt_rng_t r;
    mesh_t m;
    kdpair_t kp;
    acc_t ak, ac;
    cmp_t c;
    double v[9 * 40] = {0};
    unsigned pk, i, f32;
    unsigned long kinds[LANE_KINDS] = {0}, misses = 0;
    (void)state;
    ltt_rng_seed(&r, 0x6b6402);

    /* n = 0: one empty leaf, every lane misses */
    mesh_init(&m, v, 0);
    kd_build_pair(&kp, &m, NULL);
    assert_int_equal(kp.q.nnodes, 1);
    assert_int_equal(kp.q.nrefs, 0);
    acc_kd(&ak, &kp);
    acc_chunks(&ac, &m);
    memset(&c, 0, sizeof c);
    for (pk = 0; pk < 20; pk++) {
        pk_t p;
        mesh_t box = m;
        res16_t rs, rr;
        box.hi[0] = box.hi[1] = box.hi[2] = 10;
        box.lo[0] = box.lo[1] = box.lo[2] = -10;
        gen_packet(&r, &box, NULL, &p, kinds);
        for (f32 = 0; f32 < 2; f32++) {
            c.contract += run(&ak, (int)f32, &p, &rs);
            (void)run(&ac, (int)f32, &p, &rr);
            judge(&c, "kd empty", &m, (int)f32, &p, &rs, &rr);
            c.contract += rs.hit != 0 || rs.occ != 0;
#if !LT_CFG_FLOAT32
            break;
#endif
        }
    }
    cmp_print(&c, "kd, empty scene (n = 0: 1 node, 0 refs)");
    cmp_assert(&c, 0.0);
    kd_free_pair(&kp);
    mesh_free(&m);

    /* one triangle; 40 degenerate triangles (points, collinear, repeated vertices); a flat scene
     * (40 overlapping triangles in the plane z = 3, so the root box has no depth) */
    for (i = 0; i < 3; i++) {
        static const char *const nm[] = {"kd q16 single triangle", "kd q16 40 degenerate triangles",
                                         "kd q16 flat scene (40 triangles in z = 3)"};
        static const char *const cn[] = {"kd, single triangle (q16 + f32) vs chunks",
                                         "kd, 40 degenerate triangles (q16 + f32, no lane may hit)",
                                         "kd, flat scene (q16 + f32) vs chunks"};
        uint32_t n = i == 0 ? 1u : 40u, t;
        for (t = 0; t < n; t++) {
            double *q = &v[t * 9];
            int a;
            for (a = 0; a < 9; a++)
                q[a] = ltt_rng_uniform(&r, -8, 8);
            if (i == 2)
                q[2] = q[5] = q[8] = 3.0;
            if (i == 1) {
                if (t % 3 == 0)
                    memcpy(&q[3], q, 3 * sizeof *q), memcpy(&q[6], q, 3 * sizeof *q);
                else if (t % 3 == 1)
                    for (a = 0; a < 3; a++)
                        q[6 + a] = q[a] + 2.0 * (q[3 + a] - q[a]);
                else
                    memcpy(&q[6], &q[3], 3 * sizeof *q);
            }
        }
        mesh_init(&m, v, n);
        kd_build_pair(&kp, &m, NULL);
        kd_verify_q16(&kp.q, nm[i], 4 * n, default_max_depth(n));
        acc_kd(&ak, &kp);
        acc_chunks(&ac, &m);
        memset(&c, 0, sizeof c);
        for (pk = 0; pk < NPACKETS; pk++) {
            pk_t p;
            res16_t rs, rr;
            gen_packet(&r, &m, NULL, &p, kinds);
            for (f32 = 0; f32 < 2; f32++) {
                c.contract += run(&ak, (int)f32, &p, &rs);
                (void)run(&ac, (int)f32, &p, &rr);
                judge(&c, "kd", &m, (int)f32, &p, &rs, &rr);
                if (i == 1)
                    c.contract += rs.hit != 0;
#if !LT_CFG_FLOAT32
                break;
#endif
            }
        }
        cmp_print(&c, cn[i]);
        cmp_assert(&c, 0.0);
        kd_free_pair(&kp);
        mesh_free(&m);
    }

    /* rays that miss the scene bounds: nothing is visited past the root span */
    {
        uint32_t n = 60;
        double *sv = gen_soup(&r, n, 20.0);
        mesh_init(&m, sv, n);
        kd_build_pair(&kp, &m, NULL);
        for (pk = 0; pk < 50; pk++) {
            pk_t p;
            lt_hit16_t h;
            lt_ray16_q16_t rq;
            double o[3], d[3];
            int a;
            memset(&p, 0, sizeof p);
            for (i = 0; i < LT_LANES; i++) {
                rng_unit(&r, d);
                for (a = 0; a < 3; a++)
                    o[a] = d[a] * 200.0;
                pk_lane(&p, (int)i, o, d, -1);
            }
            p.k = 0xFFFF;
            pk_setup(&p);
            rq = p.q;
            misses += lt_kd_trace16_q16(&kp.q, &rq, p.k, &h) == 0;
            misses += lt_kd_occluded16_q16(&kp.q, &rq, p.k) == 0;
#if LT_CFG_FLOAT32
            {
                lt_ray16_f32_t rf = p.f;
                misses += lt_kd_trace16_f32(&kp.f, &rf, p.k, &h) == 0;
                misses += lt_kd_occluded16_f32(&kp.f, &rf, p.k) == 0;
            }
#else
            misses += 2;
#endif
        }
        ltt_report("kd, rays from 200 units pointing away from a 20-unit scene: %lu of 200 "
                   "trace/occluded calls miss on every lane\n",
                   misses);
        assert_int_equal(misses, 200);
        kd_free_pair(&kp);
        mesh_free(&m);
        free(sv);
    }
}

/* ---- scenes --------------------------------------------------------------------------------- */

#if LT_COST_MODE == LT_COST_SIM
static void ctr_begin(void)
{
    lt_sim_reset();
}

/* Sum of an event over all phases, and total modelled cycles. */
static void ctr_end(uint64_t *nodes, uint64_t *tris, uint64_t *tri_rays, uint64_t *cycles)
{
    lt_sim_totals_t t;
    int ph;
    lt_sim_totals(&t);
    *nodes = *tris = *tri_rays = 0;
    for (ph = 0; ph < LT_PH__COUNT; ph++) {
        *nodes += t.ctr[ph][LT_OP__COUNT + LT_EV_NODES];
        *tris += t.ctr[ph][LT_OP__COUNT + LT_EV_TRIS];
        *tri_rays += t.ctr[ph][LT_OP__COUNT + LT_EV_TRI_RAYS];
    }
    *cycles = t.total_cycles;
}
#endif

/* Load a scene as the tracer does (lt_mesh_load + lt_scene_prepare). Returns 0, or -1 when the
 * file is missing. */
static int load_scene(const char *path, lt_scene_t *s, mesh_t *m)
{
    lt_mesh_t mesh;
    lt_diag_t diag;
    if (lt_mesh_load(path, &mesh, &diag) != 0) {
        ltt_report("  (%s)\n", diag.msg);
        return -1;
    }
    assert_int_equal(lt_scene_prepare(&mesh, s, &diag), 0);
    lt_mesh_free(&mesh);
    mesh_init(m, s->vd, s->ntris);
    return 0;
}

/* The camera's packets in both paths. */
static lt_mask16_t cam_packet(const lt_camera_t *cam, uint32_t tx, uint32_t ty, pk_t *p)
{
    int i;
    memset(p, 0, sizeof *p);
    p->k = lt_camera_packet_q16(cam, tx, ty, &p->q);
#if LT_CFG_FLOAT32
    (void)lt_camera_packet_f32(cam, tx, ty, &p->f);
#endif
    for (i = 0; i < LT_LANES; i++)
        memcpy(p->o[i], cam->eye, sizeof p->o[i]);
    return p->k;
}

/* A whole camera view: the kd-tree against the chunks (ids, bound) and against the double brute
 * force (share of pixels with the same triangle); per-ray counters in the sim build. */
static void scene_run(const char *path, const char *name, uint32_t res, int bundled)
{
    lt_scene_t s;
    mesh_t m;
    kdpair_t kp;
    acc_t ak, ac;
    lt_camera_t cam;
    cmp_t cq, cf;
    uint32_t tx, ty, x, y;
    unsigned long dsame[2] = {0, 0}, dn = 0;
    char what[200];
    int i;
    if (load_scene(path, &s, &m) != 0) {
        if (bundled) {
            ltt_report("FAIL %s: the bundled %s is missing (run from the repository root)\n",
                       name, path);
            fail();
        }
        if (getenv("CI") != NULL && strcmp(getenv("CI"), "true") == 0) {
            ltt_report("FAIL %s: %s missing under CI=true\n", name, path);
            fail();
        }
        ltt_report("SKIP %s: %s not found (a fresh clone has no ../shared)\n", name, path);
        return;
    }
    kd_build_pair(&kp, &m, NULL);
    snprintf(what, sizeof what, "kd q16 %s", name);
    kd_verify_q16(&kp.q, what, 4 * m.n, default_max_depth(m.n));
    ltt_report("kd %s build memory: lt_kd_size bound %zu bytes, tree q16 %zu bytes (%.1f per "
               "triangle)",
               name, kp.bound, kp.q.bytes, (double)kp.q.bytes / m.n);
#if LT_CFG_FLOAT32
    ltt_report(", f32 %zu bytes (%u nodes, %u refs)", kp.f.bytes, kp.f.nnodes, kp.f.nrefs);
#endif
    ltt_report("\n");
    acc_kd(&ak, &kp);
    acc_chunks(&ac, &m);
    lt_camera_default(&s, res, res, &cam);
    memset(&cq, 0, sizeof cq);
    memset(&cf, 0, sizeof cf);
    for (ty = 0; ty < res; ty += 4)
        for (tx = 0; tx < res; tx += 4) {
            pk_t p;
            res16_t rs[2], rr;
            unsigned f32;
            (void)cam_packet(&cam, tx, ty, &p);
            for (f32 = 0; f32 < 2; f32++) {
#if !LT_CFG_FLOAT32
                if (f32)
                    continue;
#endif
                (f32 ? &cf : &cq)->contract += run(&ak, (int)f32, &p, &rs[f32]);
                (void)run(&ac, (int)f32, &p, &rr);
                judge(f32 ? &cf : &cq, "kd scene", &m, (int)f32, &p, &rs[f32], &rr);
            }
            /* the double brute force, every 2nd pixel in each direction */
            for (i = 0; i < LT_LANES; i++) {
                double d[3], t;
                int32_t id;
                x = tx + (uint32_t)(i % 4);
                y = ty + (uint32_t)(i / 4);
                if (!LTT_ON(p.k, i) || (x % 2) != 0 || (y % 2) != 0)
                    continue;
                lt_camera_dir(&cam, x, y, d);
                id = lt_ref_trace(&s, cam.eye, d, &t);
                dn++;
                dsame[0] += rs[0].id[i] == id;
#if LT_CFG_FLOAT32
                dsame[1] += rs[1].id[i] == id;
#endif
            }
        }
    snprintf(what, sizeof what, "lt_kd_trace16_q16 vs chunks, %s %ux%u camera", name, res, res);
    cmp_print(&cq, what);
#if LT_CFG_FLOAT32
    snprintf(what, sizeof what, "lt_kd_trace16_f32 vs chunks, %s %ux%u camera", name, res, res);
    cmp_print(&cf, what);
#endif
    ltt_report("kd %s vs double brute force (lt_ref_trace, %lu pixels): same triangle q16 %.3f%%, "
               "f32 %.3f%%\n",
               name, dn, 100.0 * (double)dsame[0] / (double)dn,
               LT_CFG_FLOAT32 ? 100.0 * (double)dsame[1] / (double)dn : 0.0);
    cmp_assert(&cq, 0.9999);
#if LT_CFG_FLOAT32
    cmp_assert(&cf, 0.9999);
#endif
    assert_true((double)dsame[0] >= 0.999 * (double)dn);
#if LT_COST_MODE == LT_COST_SIM
    {
        /* counters: packets of the camera, then every ray alone (single-lane packets) */
        uint64_t nd, tr, trr, cy, rays = 0, npk = 0, nd1, tr1, trr1, cy1;
        unsigned f32;
        lt_diag_t d2;
        assert_int_equal(lt_sim_init(lt_sim_machine_find("lrb16"), NULL, NULL, &d2), 0);
        for (f32 = 0; f32 < 2; f32++) {
            rays = npk = 0;
            ctr_begin();
            for (ty = 0; ty < res; ty += 4)
                for (tx = 0; tx < res; tx += 4) {
                    pk_t p;
                    lt_hit16_t h;
                    (void)cam_packet(&cam, tx, ty, &p);
                    rays += lt__popcount32(p.k);
                    npk++;
                    if (!f32)
                        (void)lt_kd_trace16_q16(&kp.q, &p.q, p.k, &h);
#if LT_CFG_FLOAT32
                    else
                        (void)lt_kd_trace16_f32(&kp.f, &p.f, p.k, &h);
#endif
                }
            ctr_end(&nd, &tr, &trr, &cy);
            ctr_begin();
            for (ty = 0; ty < res; ty += 4)
                for (tx = 0; tx < res; tx += 4) {
                    pk_t p;
                    lt_hit16_t h;
                    (void)cam_packet(&cam, tx, ty, &p);
                    for (i = 0; i < LT_LANES; i++) {
                        pk_t q = p;
                        if (!LTT_ON(p.k, i))
                            continue;
                        if (!f32)
                            (void)lt_kd_trace16_q16(&kp.q, &q.q, (lt_mask16_t)(1u << i), &h);
#if LT_CFG_FLOAT32
                        else
                            (void)lt_kd_trace16_f32(&kp.f, &q.f, (lt_mask16_t)(1u << i), &h);
#endif
                    }
                }
            ctr_end(&nd1, &tr1, &trr1, &cy1);
            {
                /* the peer in the same run: the flat chunk list */
                uint64_t cn, ct, ctr_, cc;
                ctr_begin();
                for (ty = 0; ty < res; ty += 4)
                    for (tx = 0; tx < res; tx += 4) {
                        pk_t p;
                        lt_hit16_t h;
                        (void)cam_packet(&cam, tx, ty, &p);
                        if (!f32)
                            (void)lt_chunks_trace16_q16(m.tq, m.n, m.bq, LT_ISECT_WT, &p.q, p.k, &h);
#if LT_CFG_FLOAT32
                        else
                            (void)lt_chunks_trace16_f32(m.tf, m.n, m.bf, LT_ISECT_WT, &p.f, p.k, &h);
#endif
                    }
                ctr_end(&cn, &ct, &ctr_, &cc);
                ltt_report("chunks %s %s %ux%u (lrb16, peer): %.2f boxes and %.2f triangle tests "
                           "per packet, %.2f ray-triangle tests per ray, %.0f cycles per ray\n",
                           name, f32 ? "f32" : "q16", res, res, (double)cn / (double)npk,
                           (double)ct / (double)npk, (double)ctr_ / (double)rays,
                           (double)cc / (double)rays);
            }
            ltt_report("kd %s %s %ux%u (lrb16): packets: %.2f nodes and %.2f triangle tests per "
                       "packet, %.2f ray-triangle tests per ray, %.0f cycles per ray; rays alone: "
                       "%.2f nodes and %.2f triangle tests per ray, %.0f cycles per ray\n",
                       name, f32 ? "f32" : "q16", res, res, (double)nd / (double)npk,
                       (double)tr / (double)npk, (double)trr / (double)rays,
                       (double)cy / (double)rays, (double)nd1 / (double)rays,
                       (double)tr1 / (double)rays, (double)cy1 / (double)rays);
#if !LT_CFG_FLOAT32
            break;
#endif
        }
        lt_sim_shutdown();
    }
#else
    ltt_report("kd %s: per-ray node and triangle-test counts are printed by the sim build "
               "(build/sim/test_kd)\n",
               name);
#endif
    kd_free_pair(&kp);
    mesh_free(&m);
    lt_scene_free(&s);
}

static void test_kd_teapot(void **state)
{
    (void)state;
    scene_run("scenes/teapot.obj", "teapot", 256 / CAM_SCALE, 1);
}

static void test_kd_bunny(void **state)
{
    (void)state;
    scene_run("../shared/scenes/bunny.obj", "bunny", 128 / CAM_SCALE, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_kd_size_and_arena),
        cmocka_unit_test(test_kd_random),
        cmocka_unit_test(test_kd_edge_cases),
        cmocka_unit_test(test_kd_teapot),
        cmocka_unit_test(test_kd_bunny),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
