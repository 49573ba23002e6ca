/* test_bvh.c - cmocka tests of the BVH (lt_bvh.h) in s15.16 and float32: the arena size query
 * (exact, poisoned tail untouched, LT_E_SPACE with the needed size), the tree invariants (every
 * triangle exactly once, every stored box = the exact union of its triangles plus the pad, leaf and
 * depth limits), the SAH cost against an object-median tree, and closest hit / any hit of packets
 * and single rays against a brute force over all triangles with the same triangle kernel (the
 * BVH must give the same distance bit for bit and the same id up to exact ties), on random meshes,
 * adversarial ones and the real meshes (scenes/teapot.obj, ../shared/scenes/bunny.obj and
 * dragon_res3.obj when present). Prints node visits per ray, lane utilisation, SAH costs, build
 * times and memory. Builds: host, sim, asan; the float32 half only with LT_CFG_FLOAT32.
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
#include <time.h>

#include "lt/lt_bvh.h"
#include "io/lt_fx_float.h"
#include "io/lt_mesh.h"
#include "render/lt_scene.h"
#include "lt_test_util.h"
#include "lt_isect_oracle.h"
#if LT_COST_MODE == LT_COST_SIM
#include "lt_sim.h"
#endif

#define FMT_Q16 0
#define FMT_F32 1

/* The host build runs the full case counts; the ASan+UBSan build (LT_CFG_ASSERT=1, ~30x slower)
 * runs every path on an eighth of the rays and smaller views: it is there for memory safety. */
#if LT_CFG_ASSERT
#define WORK 8u
#else
#define WORK 1u
#endif

/* ---- meshes ----------------------------------------------------------------------------------- */

/* Fill tq/tf from the double vertices vd as lt_scene_prepare does (s15.16 vertices rounded, edges
 * exact differences; float v0 and edges from float vertices). */
static void mesh_alloc(lt_scene_t *s, uint32_t n)
{
    memset(s, 0, sizeof *s);
    s->ntris = n;
    s->tq = calloc(n + 1u, sizeof *s->tq);
    s->tf = calloc(n + 1u, sizeof *s->tf);
    s->vd = calloc((size_t)n * 9u + 1u, sizeof(double));
    assert_non_null(s->tq);
    assert_non_null(s->tf);
    assert_non_null(s->vd);
}

static void mesh_quantise(lt_scene_t *s)
{
    uint32_t i, a;
    for (i = 0; i < s->ntris; i++)
        for (a = 0; a < 3; a++) {
            const double *v = &s->vd[i * 9u];
            lt_q16_t q0 = lt_q16_from_double_sat(v[a]), q1 = lt_q16_from_double_sat(v[3 + a]);
            lt_q16_t q2 = lt_q16_from_double_sat(v[6 + a]);
            float f0 = (float)v[a];
            s->tq[i].v0[a] = q0;
            s->tq[i].e1[a] = q1 - q0;
            s->tq[i].e2[a] = q2 - q0;
            s->tf[i].v0[a] = f0;
            s->tf[i].e1[a] = (float)v[3 + a] - f0;
            s->tf[i].e2[a] = (float)v[6 + a] - f0;
        }
}

static void set_vert(lt_scene_t *s, uint32_t i, int j, double x, double y, double z)
{
    s->vd[i * 9u + (unsigned)j * 3u + 0u] = x;
    s->vd[i * 9u + (unsigned)j * 3u + 1u] = y;
    s->vd[i * 9u + (unsigned)j * 3u + 2u] = z;
}

enum { MESH_CLUSTERS, MESH_SAME_CENTROID, MESH_EXPONENTIAL, MESH_DEGENERATE, MESH_GRID };

/* Random meshes. CLUSTERS: triangles of 1..30 units, half uniform in a 800-unit cube, half in 8
 * tight clusters (non-uniform, where SAH beats the median). SAME_CENTROID: every triangle's box is
 * centred on one point (vertices c + a, c - a, c + b with |b| <= |a| per axis, a on a 1/64 grid so
 * q16 and f32 keep the symmetry exactly). EXPONENTIAL: triangles at x = 1.15^i (SAH peels a chain).
 * DEGENERATE: points, segments and repeated vertices only. GRID: axis-aligned unit squares (two
 * triangles each) on integer planes: flat boxes whose faces lie on node boundaries. */
static void mesh_random(lt_scene_t *s, uint32_t n, int kind, uint64_t seed)
{
    ltt_rng_t r;
    uint32_t i;
    int a;
    mesh_alloc(s, n);
    ltt_rng_seed(&r, seed);
    for (i = 0; i < n; i++) {
        double c[3], u[3], w[3];
        if (kind == MESH_CLUSTERS) {
            double sz = ltt_rng_uniform(&r, 1.0, 30.0);
            if (ltt_rng_below(&r, 2) == 0) {
                for (a = 0; a < 3; a++)
                    c[a] = ltt_rng_uniform(&r, -400.0, 400.0);
            } else {
                uint32_t k = ltt_rng_below(&r, 8);
                for (a = 0; a < 3; a++)
                    c[a] = -350.0 + 100.0 * (double)((k * 3u + (unsigned)a * 5u) % 8u) +
                           ltt_rng_uniform(&r, -20.0, 20.0);
            }
            for (a = 0; a < 3; a++) {
                u[a] = ltt_rng_uniform(&r, -sz, sz);
                w[a] = ltt_rng_uniform(&r, -sz, sz);
            }
            set_vert(s, i, 0, c[0], c[1], c[2]);
            set_vert(s, i, 1, c[0] + u[0], c[1] + u[1], c[2] + u[2]);
            set_vert(s, i, 2, c[0] + w[0], c[1] + w[1], c[2] + w[2]);
        } else if (kind == MESH_SAME_CENTROID) {
            double av[3], bv[3];
            for (a = 0; a < 3; a++) {
                av[a] = (double)ltt_rng_range(&r, 1, 2000) / 64.0;
                bv[a] = (double)ltt_rng_range(&r, -(int32_t)(av[a] * 64.0), (int32_t)(av[a] * 64.0)) /
                        64.0;
            }
            set_vert(s, i, 0, 3.0 + av[0], -2.0 + av[1], 1.0 + av[2]);
            set_vert(s, i, 1, 3.0 - av[0], -2.0 - av[1], 1.0 - av[2]);
            set_vert(s, i, 2, 3.0 + bv[0], -2.0 + bv[1], 1.0 + bv[2]);
        } else if (kind == MESH_EXPONENTIAL) {
            double x = pow(1.15, (double)i) - 1.0;
            if (x > 3000.0)
                x = 3000.0 - (double)i * 0.001;
            set_vert(s, i, 0, x - 1500.0, 0.0, 0.0);
            set_vert(s, i, 1, x - 1500.0, 2.0, 0.0);
            set_vert(s, i, 2, x - 1500.0, 0.0, 2.0);
        } else if (kind == MESH_DEGENERATE) {
            uint32_t t = ltt_rng_below(&r, 3);
            for (a = 0; a < 3; a++) {
                c[a] = ltt_rng_uniform(&r, -100.0, 100.0);
                u[a] = ltt_rng_uniform(&r, -5.0, 5.0);
            }
            set_vert(s, i, 0, c[0], c[1], c[2]);
            if (t == 0) { /* a point */
                set_vert(s, i, 1, c[0], c[1], c[2]);
                set_vert(s, i, 2, c[0], c[1], c[2]);
            } else if (t == 1) { /* a segment with a repeated vertex */
                set_vert(s, i, 1, c[0] + u[0], c[1] + u[1], c[2] + u[2]);
                set_vert(s, i, 2, c[0], c[1], c[2]);
            } else { /* three collinear vertices (exact in both formats: a power-of-two step) */
                set_vert(s, i, 1, c[0] + 0.25, c[1], c[2]);
                set_vert(s, i, 2, c[0] + 0.5, c[1], c[2]);
            }
        } else { /* MESH_GRID: unit squares on integer planes, two triangles each */
            uint32_t ax = ltt_rng_below(&r, 3), q = i / 2u;
            double p[3];
            (void)q;
            for (a = 0; a < 3; a++)
                p[a] = (double)ltt_rng_range(&r, -12, 12);
            if (i % 2u == 1u) {
                /* the second half of the previous square */
                const double *v = &s->vd[(i - 1u) * 9u];
                set_vert(s, i, 0, v[3], v[4], v[5]);
                set_vert(s, i, 1, v[6], v[7], v[8]);
                set_vert(s, i, 2, v[3] + v[6] - v[0], v[4] + v[7] - v[1], v[5] + v[8] - v[2]);
                continue;
            }
            set_vert(s, i, 0, p[0], p[1], p[2]);
            set_vert(s, i, 1, p[0] + (ax == 0 ? 0 : 1), p[1] + (ax == 0 ? 1 : 0), p[2]);
            set_vert(s, i, 2, p[0], p[1] + (ax == 2 ? 1 : 0), p[2] + (ax == 2 ? 0 : 1));
        }
    }
    mesh_quantise(s);
}

/* ---- building with a poisoned arena ------------------------------------------------------------ */

#define TAIL 64u

typedef struct built {
    lt_bvh_t bvh;
    unsigned char *arena; /* malloc'd: size + TAIL, poisoned */
    size_t size;          /* lt_bvh_size() */
    double ms;            /* build time */
} built_t;

/* Process CPU time: build times stay comparable on a shared, loaded machine. */
static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

/* Build into an arena of exactly lt_bvh_size() bytes followed by TAIL poisoned bytes, and check the
 * tail was not written. Returns the build status. */
static lt_status_t build(built_t *b, const lt_scene_t *s, int fmt, const lt_bvh_desc_t *d)
{
    lt_status_t st;
    double t0;
    memset(b, 0, sizeof *b);
    assert_int_equal(lt_bvh_size(s->ntris, d, &b->size), LT_OK);
    b->arena = malloc(b->size + TAIL);
    assert_non_null(b->arena);
    ltt_poison(b->arena, b->size + TAIL);
    t0 = now_ms();
    if (fmt == FMT_Q16)
        st = lt_bvh_build_q16(&b->bvh, d, s->tq, s->ntris, b->size ? b->arena : NULL, b->size);
#if LT_CFG_FLOAT32
    else
        st = lt_bvh_build_f32(&b->bvh, d, s->tf, s->ntris, b->size ? b->arena : NULL, b->size);
#endif
    b->ms = now_ms() - t0;
    assert_int_equal(ltt_touched(b->arena, b->size, b->size + TAIL), 0);
    return st;
}

static void unbuild(built_t *b)
{
    free(b->arena);
    b->arena = NULL;
}

/* ---- tree invariants ---------------------------------------------------------------------------- */

typedef struct dbox {
    double lo[3], hi[3];
} dbox_t;

/* The triangle's box in the builder's own arithmetic (q16: exact int64 vertex sums; f32: float
 * sums), converted exactly to double. */
static void tri_dbox(const lt_scene_t *s, uint32_t i, int fmt, dbox_t *b)
{
    int a;
    for (a = 0; a < 3; a++) {
        double p[3];
        int j;
        if (fmt == FMT_Q16) {
            p[0] = lt_q16_to_double(s->tq[i].v0[a]);
            p[1] = lt_q16_to_double(s->tq[i].v0[a] + s->tq[i].e1[a]);
            p[2] = lt_q16_to_double(s->tq[i].v0[a] + s->tq[i].e2[a]);
        } else {
            p[0] = (double)s->tf[i].v0[a];
            p[1] = (double)(s->tf[i].v0[a] + s->tf[i].e1[a]);
            p[2] = (double)(s->tf[i].v0[a] + s->tf[i].e2[a]);
        }
        b->lo[a] = b->hi[a] = p[0];
        for (j = 1; j < 3; j++) {
            b->lo[a] = p[j] < b->lo[a] ? p[j] : b->lo[a];
            b->hi[a] = p[j] > b->hi[a] ? p[j] : b->hi[a];
        }
    }
}

static void dbox_grow(dbox_t *d, const dbox_t *s)
{
    int a;
    for (a = 0; a < 3; a++) {
        d->lo[a] = s->lo[a] < d->lo[a] ? s->lo[a] : d->lo[a];
        d->hi[a] = s->hi[a] > d->hi[a] ? s->hi[a] : d->hi[a];
    }
}

static double dbox_area(const dbox_t *b)
{
    double w[3];
    int a;
    for (a = 0; a < 3; a++)
        w[a] = b->hi[a] - b->lo[a];
    return w[0] * w[1] + w[1] * w[2] + w[2] * w[0];
}

/* Node i of either numeric path as doubles. */
typedef struct dnode {
    dbox_t b;
    uint32_t left_first, count;
} dnode_t;

static dnode_t get_node(const lt_bvh_t *t, uint32_t i)
{
    dnode_t d;
    int a;
    if (t->num == LT_BVH_NUM_Q16) {
        const lt_bvh_node_q16_t *n = &((const lt_bvh_node_q16_t *)t->nodes)[i];
        for (a = 0; a < 3; a++) {
            d.b.lo[a] = lt_q16_to_double(n->b.lo[a]);
            d.b.hi[a] = lt_q16_to_double(n->b.hi[a]);
        }
        d.left_first = n->left_first;
        d.count = n->count;
    } else {
#if LT_CFG_FLOAT32
        const lt_bvh_node_f32_t *n = &((const lt_bvh_node_f32_t *)t->nodes)[i];
        for (a = 0; a < 3; a++) {
            d.b.lo[a] = (double)n->b.lo[a];
            d.b.hi[a] = (double)n->b.hi[a];
        }
        d.left_first = n->left_first;
        d.count = n->count;
#else
        memset(&d, 0, sizeof d);
#endif
    }
    return d;
}

/* The stored box expected for a tight box: q16 saturating +-LT_BVH_PAD_Q16, f32 +-pad in float
 * with pad = 2^-18 max|root coordinate|, or the tight box itself for LT_BVH_TIGHT. */
static dbox_t padded(const dbox_t *t, int fmt, double fpad, int tight)
{
    dbox_t p = *t;
    int a;
    if (tight)
        return p;
    for (a = 0; a < 3; a++) {
        if (fmt == FMT_Q16) {
            double pad = lt_q16_to_double(LT_BVH_PAD_Q16);
            p.lo[a] = t->lo[a] - pad;
            p.hi[a] = t->hi[a] + pad; /* no saturation: the geometry bound keeps far inside */
        } else {
            p.lo[a] = (double)((float)t->lo[a] - (float)fpad);
            p.hi[a] = (double)((float)t->hi[a] + (float)fpad);
        }
    }
    return p;
}

typedef struct tree_check {
    unsigned long trees, nodes, bad;
    double sah;          /* last tree's SAH cost (tight boxes, relative to the root area) */
} tree_check_t;

static void tc_fail(tree_check_t *c, const char *fmt, ...)
{
    va_list ap;
    if (c->bad++ >= 8)
        return;
    printf("  FAIL tree: ");
    va_start(ap, fmt);
    vprintf(fmt, ap);
    va_end(ap);
    printf("\n");
}

/* Walk the tree (recursively: depth <= 64); returns the tight box of node i and adds its SAH
 * contribution (area x cost weight) to *sah. */
static dbox_t walk(const lt_bvh_t *t, const lt_scene_t *s, int fmt, const lt_bvh_desc_t *d,
                   uint32_t i, uint32_t depth, double fpad, unsigned char *seen, uint32_t *maxd,
                   uint32_t *leaves, uint32_t *reached, double *sah, tree_check_t *c)
{
    dnode_t n = get_node(t, i);
    dbox_t tight, exp;
    uint32_t max_leaf = d != NULL && d->max_leaf ? d->max_leaf : 4u;
    uint32_t max_depth = d != NULL && d->max_depth ? d->max_depth : 64u;
    int tightf = d != NULL && (d->flags & LT_BVH_TIGHT) != 0;
    int a;
    (*reached)++;
    if (depth > max_depth)
        tc_fail(c, "node %u at depth %u > max_depth %u", i, depth, max_depth);
    if (n.count > 0) {
        uint32_t j;
        (*leaves)++;
        *maxd = depth > *maxd ? depth : *maxd;
        if (n.count > max_leaf)
            tc_fail(c, "leaf %u has %u triangles > max_leaf %u", i, n.count, max_leaf);
        if ((uint64_t)n.left_first + n.count > t->ntris) {
            tc_fail(c, "leaf %u range %u+%u beyond %u triangles", i, n.left_first, n.count,
                    t->ntris);
            return n.b;
        }
        for (j = n.left_first; j < n.left_first + n.count; j++) {
            dbox_t tb;
            uint32_t id = t->idx[j];
            if (id >= t->ntris) {
                tc_fail(c, "idx[%u] = %u out of range", j, id);
                continue;
            }
            seen[id]++;
            tri_dbox(s, id, fmt, &tb);
            if (j == n.left_first)
                tight = tb;
            else
                dbox_grow(&tight, &tb);
        }
        *sah += (double)LT_BVH_C_ISECT * (double)n.count * dbox_area(&tight);
    } else {
        dbox_t lb, rb;
        uint32_t l = n.left_first;
        if (l < 2 || (l & 1u) != 0 || l + 1u >= t->nnodes) {
            tc_fail(c, "interior %u: left child %u not an even slot in [2, %u)", i, l, t->nnodes);
            return n.b;
        }
        lb = walk(t, s, fmt, d, l, depth + 1u, fpad, seen, maxd, leaves, reached, sah, c);
        rb = walk(t, s, fmt, d, l + 1u, depth + 1u, fpad, seen, maxd, leaves, reached, sah, c);
        tight = lb;
        dbox_grow(&tight, &rb);
        *sah += (double)LT_BVH_C_TRAV * dbox_area(&tight);
    }
    /* stored box = exact union of its triangles (tight), padded: so it contains its children and
     * triangles, and is no larger than the pad requires */
    exp = padded(&tight, fmt, fpad, tightf);
    for (a = 0; a < 3; a++)
        if (n.b.lo[a] != exp.lo[a] || n.b.hi[a] != exp.hi[a]) {
            tc_fail(c, "node %u axis %d: box [%.9g, %.9g], expected [%.9g, %.9g]", i, a,
                    n.b.lo[a], n.b.hi[a], exp.lo[a], exp.hi[a]);
            break;
        }
    return tight;
}

/* Every invariant of a built tree; fills c->sah (relative to the root's area). */
static void check_tree(const lt_bvh_t *t, const lt_scene_t *s, int fmt, const lt_bvh_desc_t *d,
                       tree_check_t *c)
{
    unsigned char *seen;
    uint32_t i, maxd = 0, leaves = 0, reached = 0;
    double fpad = 0.0, sah = 0.0;
    dbox_t root;
    c->trees++;
    if (t->ntris == 0) {
        if (t->nnodes != 0 || t->bytes != 0)
            tc_fail(c, "empty tree has %u nodes, %zu bytes", t->nnodes, t->bytes);
        return;
    }
    if (t->nodes != (const void *)t->nodes || t->idx == NULL)
        tc_fail(c, "NULL arrays");
    if ((const unsigned char *)t->idx !=
        (const unsigned char *)t->nodes + (size_t)t->nnodes * 32u)
        tc_fail(c, "idx not right after the %u nodes", t->nnodes);
    if (t->bytes != (size_t)t->nnodes * 32u + (size_t)t->ntris * 4u)
        tc_fail(c, "bytes %zu != nodes + idx", t->bytes);
    seen = calloc(t->ntris, 1);
    assert_non_null(seen);
    /* f32 pad from the tight root box: recompute it from all triangles */
    for (i = 0; i < t->ntris; i++) {
        dbox_t tb;
        tri_dbox(s, i, fmt, &tb);
        if (i == 0)
            root = tb;
        else
            dbox_grow(&root, &tb);
    }
    if (fmt == FMT_F32) {
        float m = 0.0f;
        int a;
        for (a = 0; a < 3; a++) {
            m = fabsf((float)root.lo[a]) > m ? fabsf((float)root.lo[a]) : m;
            m = fabsf((float)root.hi[a]) > m ? fabsf((float)root.hi[a]) : m;
        }
        fpad = (double)(m * 0x1p-18f);
    }
    (void)walk(t, s, fmt, d, 0, 0, fpad, seen, &maxd, &leaves, &reached, &sah, c);
    for (i = 0; i < t->ntris; i++)
        if (seen[i] != 1) {
            tc_fail(c, "triangle %u appears %u times in the leaves", i, seen[i]);
            break;
        }
    if (maxd != t->depth || leaves != t->leaves)
        tc_fail(c, "depth %u / leaves %u, header says %u / %u", maxd, leaves, t->depth, t->leaves);
    if (reached != (t->nnodes > 1 ? t->nnodes - 1u : t->nnodes))
        tc_fail(c, "%u nodes reached of %u slots (slot 1 unused)", reached, t->nnodes);
    c->nodes += reached;
    c->sah = dbox_area(&root) > 0 ? sah / dbox_area(&root) : sah;
    free(seen);
}

/* Object-median tree (longest centroid axis, leaves of <= max_leaf) for the SAH comparison. */
typedef struct cent {
    double c[3];
    dbox_t b;
} cent_t;
static int g_axis;
static int cmp_cent(const void *x, const void *y)
{
    double a = ((const cent_t *)x)->c[g_axis], b = ((const cent_t *)y)->c[g_axis];
    return a < b ? -1 : (a > b ? 1 : 0);
}

static dbox_t median_tree(cent_t *p, uint32_t n, uint32_t max_leaf, double *sah)
{
    dbox_t b = p[0].b, cb;
    uint32_t i;
    int a, ax = 0;
    for (i = 1; i < n; i++)
        dbox_grow(&b, &p[i].b);
    if (n <= max_leaf) {
        *sah += (double)LT_BVH_C_ISECT * (double)n * dbox_area(&b);
        return b;
    }
    for (a = 0; a < 3; a++)
        cb.lo[a] = cb.hi[a] = p[0].c[a];
    for (i = 1; i < n; i++)
        for (a = 0; a < 3; a++) {
            cb.lo[a] = p[i].c[a] < cb.lo[a] ? p[i].c[a] : cb.lo[a];
            cb.hi[a] = p[i].c[a] > cb.hi[a] ? p[i].c[a] : cb.hi[a];
        }
    for (a = 1; a < 3; a++)
        if (cb.hi[a] - cb.lo[a] > cb.hi[ax] - cb.lo[ax])
            ax = a;
    g_axis = ax;
    qsort(p, n, sizeof *p, cmp_cent);
    *sah += (double)LT_BVH_C_TRAV * dbox_area(&b);
    (void)median_tree(p, n / 2u, max_leaf, sah);
    (void)median_tree(p + n / 2u, n - n / 2u, max_leaf, sah);
    return b;
}

static double median_sah(const lt_scene_t *s, int fmt, uint32_t max_leaf)
{
    cent_t *p = malloc(s->ntris * sizeof *p);
    double sah = 0.0;
    dbox_t root;
    uint32_t i;
    int a;
    assert_non_null(p);
    for (i = 0; i < s->ntris; i++) {
        tri_dbox(s, i, fmt, &p[i].b);
        for (a = 0; a < 3; a++)
            p[i].c[a] = p[i].b.lo[a] + p[i].b.hi[a];
    }
    root = median_tree(p, s->ntris, max_leaf, &sah);
    free(p);
    return dbox_area(&root) > 0 ? sah / dbox_area(&root) : sah;
}

/* ---- rays ----------------------------------------------------------------------------------------- */

typedef struct dray {
    double o[3], d[3], tmin, tmax;
} dray_t;

static void normalize(double d[3])
{
    double l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    d[0] /= l;
    d[1] /= l;
    d[2] /= l;
}

static void q16_packet(const dray_t *rs, lt_ray16_q16_t *p)
{
    int i;
    memset(p, 0, sizeof *p);
    for (i = 0; i < LT_LANES; i++) {
        p->ox.l[i] = lt_q16_from_double_sat(rs[i].o[0]);
        p->oy.l[i] = lt_q16_from_double_sat(rs[i].o[1]);
        p->oz.l[i] = lt_q16_from_double_sat(rs[i].o[2]);
        p->dx.l[i] = lt_q30_from_double_sat(rs[i].d[0]);
        p->dy.l[i] = lt_q30_from_double_sat(rs[i].d[1]);
        p->dz.l[i] = lt_q30_from_double_sat(rs[i].d[2]);
        p->tmin.l[i] = lt_q16_from_double_sat(rs[i].tmin);
        p->tmax.l[i] = lt_q16_from_double_sat(rs[i].tmax);
    }
    lt_ray16_q16_setup(p);
}

static void q16_single(const lt_ray16_q16_t *p, int i, lt_ray1_q16_t *r)
{
    memset(r, 0, sizeof *r);
    r->o[0] = p->ox.l[i];
    r->o[1] = p->oy.l[i];
    r->o[2] = p->oz.l[i];
    r->d[0] = p->dx.l[i];
    r->d[1] = p->dy.l[i];
    r->d[2] = p->dz.l[i];
    r->tmin = p->tmin.l[i];
    r->tmax = p->tmax.l[i];
    lt_ray1_q16_setup(r);
}

#if LT_CFG_FLOAT32
static void f32_packet(const dray_t *rs, lt_ray16_f32_t *p)
{
    int i;
    memset(p, 0, sizeof *p);
    for (i = 0; i < LT_LANES; i++) {
        p->ox.l[i] = (float)rs[i].o[0];
        p->oy.l[i] = (float)rs[i].o[1];
        p->oz.l[i] = (float)rs[i].o[2];
        p->dx.l[i] = (float)rs[i].d[0];
        p->dy.l[i] = (float)rs[i].d[1];
        p->dz.l[i] = (float)rs[i].d[2];
        p->tmin.l[i] = (float)rs[i].tmin;
        p->tmax.l[i] = (float)rs[i].tmax;
    }
    lt_ray16_f32_setup(p);
}

static void f32_single(const lt_ray16_f32_t *p, int i, lt_ray1_f32_t *r)
{
    memset(r, 0, sizeof *r);
    r->o[0] = p->ox.l[i];
    r->o[1] = p->oy.l[i];
    r->o[2] = p->oz.l[i];
    r->d[0] = p->dx.l[i];
    r->d[1] = p->dy.l[i];
    r->d[2] = p->dz.l[i];
    r->tmin = p->tmin.l[i];
    r->tmax = p->tmax.l[i];
    lt_ray1_f32_setup(r);
}
#endif

/* ---- comparing the BVH with brute force ----------------------------------------------------------- */

typedef struct cmp {
    unsigned long packets, rays, hits, ties, bad;  /* packet closest hit vs brute force */
    unsigned long single, single_bad;              /* single ray vs brute force */
    unsigned long occl, occl_bad;                  /* any hit vs the brute-force distance */
    unsigned long errs;                            /* traversal calls not returning LT_OK */
    int tight;       /* LT_BVH_TIGHT tree: any-hit is exact only for tmax = original or = closest t */
    lt_bvh_stats_t sp, s1;                         /* packet and single-ray counters */
} cmp_t;

static void cmp_fail(cmp_t *c, unsigned long *ctr, const char *fmt, ...)
{
    va_list ap;
    if ((*ctr)++ >= 6)
        return;
    printf("  FAIL ");
    va_start(ap, fmt);
    vprintf(fmt, ap);
    va_end(ap);
    printf("\n");
    (void)c;
}

/* An exact tie: triangle id on its own gives lane i of p0 exactly the distance t. */
static int tie_q16(const lt_scene_t *s, const lt_ray16_q16_t *p0, int i, int32_t id, lt_q16_t t)
{
    lt_ray16_q16_t pt = *p0;
    lt_hit16_t h;
    h.id = lt_vi32_set1(-1);
    if (id < 0 || (uint32_t)id >= s->ntris)
        return 0;
    return LTT_ON(ltt_tri16_q16(&pt, (lt_mask16_t)(1u << i), &s->tq[id], id, &h), i) &&
           pt.tmax.l[i] == t;
}

#if LT_CFG_FLOAT32
static int tie_f32(const lt_scene_t *s, const lt_ray16_f32_t *p0, int i, int32_t id, float t)
{
    lt_ray16_f32_t pt = *p0;
    lt_hit16_t h;
    h.id = lt_vi32_set1(-1);
    if (id < 0 || (uint32_t)id >= s->ntris)
        return 0;
    return LTT_ON(ltt_tri16_f32(&pt, (lt_mask16_t)(1u << i), &s->tf[id], id, &h), i) &&
           pt.tmax.l[i] == t;
}
#endif

/* One packet in s15.16: BVH packet, BVH single rays and BVH any-hit against the brute force over
 * all triangles (lt_tri16_q16 in id order: the closest computed t, first id among exact ties). */
static void cmp_q16(const lt_bvh_t *bvh0, const lt_scene_t *s, const dray_t *rs, lt_mask16_t k,
                    ltt_rng_t *rng, cmp_t *c)
{
    lt_ray16_q16_t p0, pb, pr, po;
    lt_hit16_t hb, hr;
    lt_bvh_t bp = *bvh0, b1 = *bvh0;
    lt_mask16_t occ, expect = 0;
    uint32_t t;
    int i;
    bp.stats = &c->sp;
    b1.stats = &c->s1;
    q16_packet(rs, &p0);
    pb = pr = p0;
    c->packets++;
    if (lt_bvh_trace16_q16(&bp, s->tq, &pb, k, &hb) != LT_OK)
        c->errs++;
    hr.id = lt_vi32_set1(-1);
    for (t = 0; t < s->ntris; t++)
        (void)ltt_tri16_q16(&pr, k, &s->tq[t], (int32_t)t, &hr);
    po = p0;
    for (i = 0; i < LT_LANES; i++) {
        int32_t got = hb.id.l[i], want = hr.id.l[i], id1;
        lt_ray1_q16_t r1;
        if (!LTT_ON(k, i)) {
            if (got != -1 || pb.tmax.l[i] != p0.tmax.l[i])
                cmp_fail(c, &c->bad, "q16 inactive lane %d changed (id %d)", i, got);
            continue;
        }
        c->rays++;
        c->hits += want >= 0;
        if (pb.tmax.l[i] != pr.tmax.l[i]) {
            cmp_fail(c, &c->bad, "q16 lane %d: bvh t %.9g id %d, brute force t %.9g id %d", i,
                     lt_q16_to_double(pb.tmax.l[i]), got, lt_q16_to_double(pr.tmax.l[i]), want);
        } else if (got != want) {
            /* an exact tie: the other triangle must give the same distance on its own */
            if (tie_q16(s, &p0, i, got, pr.tmax.l[i]))
                c->ties++;
            else
                cmp_fail(c, &c->bad, "q16 lane %d: id %d vs brute force %d at the same t", i,
                         got, want);
        }
        /* the single-ray path: same distance and id */
        q16_single(&p0, i, &r1);
        c->single++;
        if (lt_bvh_trace1_q16(&b1, s->tq, &r1, &id1) != LT_OK)
            c->errs++;
        if (r1.tmax != pr.tmax.l[i] || (id1 != want && !tie_q16(s, &p0, i, id1, pr.tmax.l[i])))
            cmp_fail(c, &c->single_bad, "q16 single lane %d: t %.9g id %d, brute force %.9g %d",
                     i, lt_q16_to_double(r1.tmax), id1, lt_q16_to_double(pr.tmax.l[i]), want);
        else if (id1 != want)
            c->ties++;
        /* any hit with tmax = original, = the closest t, or = closest t + 1 ulp */
        if (want >= 0) {
            uint32_t v = ltt_rng_below(rng, c->tight ? 2u : 3u);
            if (v == 1)
                po.tmax.l[i] = pr.tmax.l[i];
            else if (v == 2)
                po.tmax.l[i] = pr.tmax.l[i] + 1;
            if (pr.tmax.l[i] < po.tmax.l[i])
                expect = (lt_mask16_t)(expect | (1u << i));
        }
    }
    {
        lt_ray16_q16_t pq = po;
        if (lt_bvh_occluded16_q16(&bp, s->tq, &pq, k, &occ) != LT_OK)
            c->errs++;
        c->occl += lt__popcount32(k);
        if (occ != expect)
            cmp_fail(c, &c->occl_bad, "q16 occluded16 %04x, expected %04x", occ, expect);
        for (i = 0; i < LT_LANES; i++) {
            lt_ray1_q16_t r1;
            int o1;
            if (!LTT_ON(k, i))
                continue;
            q16_single(&po, i, &r1);
            if (lt_bvh_occluded1_q16(&b1, s->tq, &r1, &o1) != LT_OK)
                c->errs++;
            if (o1 != LTT_ON(expect, i))
                cmp_fail(c, &c->occl_bad, "q16 occluded1 lane %d: %d, expected %d", i, o1,
                         LTT_ON(expect, i));
        }
    }
}

#if LT_CFG_FLOAT32
static void cmp_f32(const lt_bvh_t *bvh0, const lt_scene_t *s, const dray_t *rs, lt_mask16_t k,
                    ltt_rng_t *rng, cmp_t *c)
{
    lt_ray16_f32_t p0, pb, pr, po;
    lt_hit16_t hb, hr;
    lt_bvh_t bp = *bvh0, b1 = *bvh0;
    lt_mask16_t occ, expect = 0;
    uint32_t t;
    int i;
    bp.stats = &c->sp;
    b1.stats = &c->s1;
    f32_packet(rs, &p0);
    pb = pr = p0;
    c->packets++;
    if (lt_bvh_trace16_f32(&bp, s->tf, &pb, k, &hb) != LT_OK)
        c->errs++;
    hr.id = lt_vi32_set1(-1);
    for (t = 0; t < s->ntris; t++)
        (void)ltt_tri16_f32(&pr, k, &s->tf[t], (int32_t)t, &hr);
    po = p0;
    for (i = 0; i < LT_LANES; i++) {
        int32_t got = hb.id.l[i], want = hr.id.l[i], id1;
        lt_ray1_f32_t r1;
        if (!LTT_ON(k, i)) {
            if (got != -1 || pb.tmax.l[i] != p0.tmax.l[i])
                cmp_fail(c, &c->bad, "f32 inactive lane %d changed (id %d)", i, got);
            continue;
        }
        c->rays++;
        c->hits += want >= 0;
        if (pb.tmax.l[i] != pr.tmax.l[i]) {
            cmp_fail(c, &c->bad, "f32 lane %d: bvh t %.9g id %d, brute force t %.9g id %d", i,
                     (double)pb.tmax.l[i], got, (double)pr.tmax.l[i], want);
        } else if (got != want) {
            if (tie_f32(s, &p0, i, got, pr.tmax.l[i]))
                c->ties++;
            else
                cmp_fail(c, &c->bad, "f32 lane %d: id %d vs brute force %d at the same t", i,
                         got, want);
        }
        f32_single(&p0, i, &r1);
        c->single++;
        if (lt_bvh_trace1_f32(&b1, s->tf, &r1, &id1) != LT_OK)
            c->errs++;
        if (r1.tmax != pr.tmax.l[i] || (id1 != want && !tie_f32(s, &p0, i, id1, pr.tmax.l[i])))
            cmp_fail(c, &c->single_bad, "f32 single lane %d: t %.9g id %d, brute force %.9g %d",
                     i, (double)r1.tmax, id1, (double)pr.tmax.l[i], want);
        else if (id1 != want)
            c->ties++;
        if (want >= 0) {
            uint32_t v = ltt_rng_below(rng, c->tight ? 2u : 3u);
            if (v == 1)
                po.tmax.l[i] = pr.tmax.l[i];
            else if (v == 2)
                po.tmax.l[i] = nextafterf(pr.tmax.l[i], 3e38f);
            if (pr.tmax.l[i] < po.tmax.l[i])
                expect = (lt_mask16_t)(expect | (1u << i));
        }
    }
    {
        lt_ray16_f32_t pq = po;
        if (lt_bvh_occluded16_f32(&bp, s->tf, &pq, k, &occ) != LT_OK)
            c->errs++;
        c->occl += lt__popcount32(k);
        if (occ != expect)
            cmp_fail(c, &c->occl_bad, "f32 occluded16 %04x, expected %04x", occ, expect);
        for (i = 0; i < LT_LANES; i++) {
            lt_ray1_f32_t r1;
            int o1;
            if (!LTT_ON(k, i))
                continue;
            f32_single(&po, i, &r1);
            if (lt_bvh_occluded1_f32(&b1, s->tf, &r1, &o1) != LT_OK)
                c->errs++;
            if (o1 != LTT_ON(expect, i))
                cmp_fail(c, &c->occl_bad, "f32 occluded1 lane %d: %d, expected %d", i, o1,
                         LTT_ON(expect, i));
        }
    }
}
#endif

static void cmp_packet(int fmt, const lt_bvh_t *b, const lt_scene_t *s, const dray_t *rs,
                       lt_mask16_t k, ltt_rng_t *rng, cmp_t *c)
{
    if (fmt == FMT_Q16)
        cmp_q16(b, s, rs, k, rng, c);
#if LT_CFG_FLOAT32
    else
        cmp_f32(b, s, rs, k, rng, c);
#endif
}

static int cmp_report(const char *name, const cmp_t *c)
{
    const lt_bvh_stats_t *p = &c->sp, *q = &c->s1;
    ltt_report("%s: %lu packets, %lu rays, %lu hits; packet = brute force (t bit-exact) except "
               "%lu exact ties, %lu wrong; single rays %lu, %lu wrong; any-hit %lu lanes, %lu "
               "wrong; %lu errors\n",
               name, c->packets, c->rays, c->hits, c->ties, c->bad, c->single, c->single_bad,
               c->occl, c->occl_bad, c->errs);
    if (p->calls != 0 && q->calls != 0)
        ltt_report("  nodes per packet %.1f (lane utilisation %.1f%%), node visits per ray: packet "
                   "lanes %.1f, single ray %.1f; triangle tests per ray: packet %.1f, single "
                   "%.1f\n",
                   (double)p->nodes / (double)p->calls,
                   100.0 * (double)p->node_lanes / (16.0 * (double)(p->nodes ? p->nodes : 1)),
                   (double)p->node_lanes / (double)(p->rays ? p->rays : 1),
                   (double)q->nodes / (double)(q->rays ? q->rays : 1),
                   (double)p->tri_lanes / (double)(p->rays ? p->rays : 1),
                   (double)q->tris / (double)(q->rays ? q->rays : 1));
    return (int)(c->bad + c->single_bad + c->occl_bad + c->errs);
}

/* Random rays: 0 camera-like from a far point into the mesh's box, 1 random origin and direction
 * inside the box, 2 axis-parallel (+-x, +-y, +-z) from random grid points, 3 like 1 with a random
 * tmin/tmax window, 4 from a random origin aimed at a random point of a random triangle (s). */
#define RAY_KINDS 5
static void rand_rays(ltt_rng_t *r, int kind, double ext, const lt_scene_t *s, dray_t *rs, int n)
{
    int i, a;
    double eye[3];
    for (a = 0; a < 3; a++)
        eye[a] = ltt_rng_uniform(r, -ext, ext) * 2.5;
    for (i = 0; i < n; i++) {
        dray_t *q = &rs[i];
        q->tmin = 0.0;
        q->tmax = 30000.0;
        if (kind == 0) {
            double tgt[3];
            for (a = 0; a < 3; a++) {
                q->o[a] = eye[a];
                tgt[a] = ltt_rng_uniform(r, -ext, ext) * 0.6;
                q->d[a] = tgt[a] - eye[a];
            }
        } else if (kind == 2) {
            uint32_t ax = ltt_rng_below(r, 3);
            for (a = 0; a < 3; a++) {
                q->o[a] = (double)ltt_rng_range(r, -(int32_t)ext, (int32_t)ext);
                q->d[a] = 0.0;
            }
            q->d[ax] = ltt_rng_below(r, 2) ? 1.0 : -1.0;
        } else if (kind == 4 && s != NULL && s->ntris > 0) {
            const double *v = &s->vd[ltt_rng_below(r, s->ntris) * 9u];
            double u = ltt_rng_unit(r), w = ltt_rng_unit(r);
            if (u + w > 1.0) {
                u = 1.0 - u;
                w = 1.0 - w;
            }
            for (a = 0; a < 3; a++) {
                q->o[a] = ltt_rng_uniform(r, -ext, ext) * 1.5;
                q->d[a] = v[a] + u * (v[3 + a] - v[a]) + w * (v[6 + a] - v[a]) - q->o[a];
            }
        } else {
            for (a = 0; a < 3; a++) {
                q->o[a] = ltt_rng_uniform(r, -ext, ext) * 1.2;
                q->d[a] = ltt_rng_uniform(r, -1.0, 1.0);
            }
            if (kind == 3) {
                q->tmin = ltt_rng_uniform(r, 0.0, ext * 0.5);
                q->tmax = q->tmin + ltt_rng_uniform(r, 0.0, ext);
            }
        }
        if (kind != 2)
            normalize(q->d);
    }
}

/* ---- tests ------------------------------------------------------------------------------------ */

static void test_size_and_args(void **state)
{
    static const uint32_t ns[] = {1, 2, 3, 7, 64, 1000};
    lt_bvh_desc_t descs[4];
    lt_scene_t s;
    unsigned long cases = 0, exact = 0;
    size_t sz, i;
    unsigned di;
    lt_bvh_t b;
    unsigned char *ar;
    (void)state;
    memset(descs, 0, sizeof descs);
    descs[1].bins = 2;
    descs[1].max_leaf = 1;
    descs[2].bins = 32;
    descs[2].max_leaf = 8;
    descs[2].min_leaf = 3;
    descs[2].max_depth = 20;
    descs[3].flags = LT_BVH_TIGHT;
    descs[3].bins = 7;
    for (i = 0; i < sizeof ns / sizeof ns[0]; i++) {
        mesh_random(&s, ns[i], MESH_CLUSTERS, 100 + i);
        for (di = 0; di < 4; di++) {
            built_t bb;
            lt_bvh_t bs;
            int fmt;
            for (fmt = FMT_Q16; fmt <= (LT_CFG_FLOAT32 ? FMT_F32 : FMT_Q16); fmt++) {
                lt_status_t st;
                assert_int_equal(build(&bb, &s, fmt, &descs[di]), LT_OK);
                /* one byte less: LT_E_SPACE, the needed size written back, arena untouched */
                ltt_poison(bb.arena, bb.size + TAIL);
                memset(&bs, 0, sizeof bs);
                if (fmt == FMT_Q16)
                    st = lt_bvh_build_q16(&bs, &descs[di], s.tq, s.ntris, bb.arena, bb.size - 1);
#if LT_CFG_FLOAT32
                else
                    st = lt_bvh_build_f32(&bs, &descs[di], s.tf, s.ntris, bb.arena, bb.size - 1);
#endif
                assert_int_equal(st, LT_E_SPACE);
                assert_int_equal(bs.bytes, bb.size);
                assert_int_equal(ltt_touched(bb.arena, 0, bb.size + TAIL), 0);
                cases++;
                exact++;
                unbuild(&bb);
            }
        }
        lt_scene_free(&s);
    }
    ltt_report("lt_bvh_size: %lu (n, desc, format) cases: an arena of exactly the reported size "
               "builds with the 0xA5 tail untouched; one byte less -> LT_E_SPACE with the size "
               "written back and the arena untouched (%lu/%lu)\n",
               cases, exact, cases);
    assert_int_equal(lt_bvh_size(1000, NULL, &sz), LT_OK);
    ltt_report("lt_bvh_size: n=1000 default desc -> %zu bytes (%.1f per triangle: 64 node slots, "
               "4 index, 24 scratch box, + bins and stack)\n",
               sz, (double)sz / 1000.0);

    /* argument errors */
    mesh_random(&s, 50, MESH_CLUSTERS, 7);
    ar = malloc(1 << 16);
    assert_non_null(ar);
    assert_int_equal(lt_bvh_size(0, NULL, &sz), LT_OK);
    assert_int_equal(sz, 0);
    assert_int_equal(lt_bvh_size(10, NULL, NULL), LT_E_ARG);
    assert_int_equal(lt_bvh_size(LT_BVH_MAX_TRIS + 1u, NULL, &sz), LT_E_RANGE);
    {
        lt_bvh_desc_t bad[6];
        memset(bad, 0, sizeof bad);
        bad[0].bins = 1;
        bad[1].bins = LT_BVH_MAX_BINS + 1;
        bad[2].max_leaf = LT_BVH_MAX_LEAF + 1;
        bad[3].max_leaf = 2;
        bad[3].min_leaf = 3;
        bad[4].max_depth = LT_BVH_MAX_DEPTH + 1;
        bad[5].flags = 2;
        for (di = 0; di < 6; di++) {
            assert_int_equal(lt_bvh_size(10, &bad[di], &sz), LT_E_ARG);
            assert_int_equal(lt_bvh_build_q16(&b, &bad[di], s.tq, s.ntris, ar, 1 << 16), LT_E_ARG);
        }
    }
    assert_int_equal(lt_bvh_build_q16(NULL, NULL, s.tq, s.ntris, ar, 1 << 16), LT_E_ARG);
    assert_int_equal(lt_bvh_build_q16(&b, NULL, NULL, s.ntris, ar, 1 << 16), LT_E_ARG);
    assert_int_equal(lt_bvh_build_q16(&b, NULL, s.tq, s.ntris, ar + 4, (1 << 16) - 4), LT_E_ARG);
    assert_int_equal(lt_bvh_build_q16(&b, NULL, s.tq, s.ntris, NULL, 1 << 16), LT_E_ARG);
    /* a vertex outside the geometry bound: LT_E_RANGE naming the triangle */
    s.tq[17].e2[1] = (lt_q16_t)(((int32_t)1 << (LT_CFG_GEOM_MAX_LOG2 + 16)) - s.tq[17].v0[1] + 1);
    assert_int_equal(lt_bvh_build_q16(&b, NULL, s.tq, s.ntris, ar, 1 << 16), LT_E_RANGE);
    assert_int_equal(b.bad_tri, 17);
    s.tq[17].e2[1] -= 1; /* exactly on the bound is accepted */
    assert_int_equal(lt_bvh_build_q16(&b, NULL, s.tq, s.ntris, ar, 1 << 16), LT_OK);
#if LT_CFG_FLOAT32
    s.tf[33].v0[2] = NAN;
    assert_int_equal(lt_bvh_build_f32(&b, NULL, s.tf, s.ntris, ar, 1 << 16), LT_E_RANGE);
    assert_int_equal(b.bad_tri, 33);
    s.tf[33].v0[2] = 0x1p49f;
    assert_int_equal(lt_bvh_build_f32(&b, NULL, s.tf, s.ntris, ar, 1 << 16), LT_E_RANGE);
#endif
    /* depth: 50 triangles in leaves of 4 need 4 levels of halving */
    {
        lt_bvh_desc_t d;
        memset(&d, 0, sizeof d);
        d.max_depth = 3;
        mesh_quantise(&s);
        assert_int_equal(lt_bvh_build_q16(&b, &d, s.tq, s.ntris, ar, 1 << 16), LT_E_DEPTH);
        d.max_depth = 4;
        assert_int_equal(lt_bvh_build_q16(&b, &d, s.tq, s.ntris, ar, 1 << 16), LT_OK);
        assert_true(b.depth <= 4);
    }
    /* traversal argument errors, and a tree of the other numeric path */
    {
        lt_ray16_q16_t p;
        lt_hit16_t h;
        lt_mask16_t m;
        lt_ray1_q16_t r1;
        int32_t id;
        memset(&p, 0, sizeof p);
        memset(&r1, 0, sizeof r1);
        assert_int_equal(lt_bvh_trace16_q16(NULL, s.tq, &p, 1, &h), LT_E_ARG);
        assert_int_equal(lt_bvh_trace16_q16(&b, NULL, &p, 1, &h), LT_E_ARG);
        assert_int_equal(lt_bvh_occluded16_q16(&b, s.tq, &p, 1, NULL), LT_E_ARG);
        assert_int_equal(lt_bvh_trace1_q16(&b, s.tq, &r1, NULL), LT_E_ARG);
#if LT_CFG_FLOAT32
        {
            lt_ray16_f32_t pf;
            memset(&pf, 0, sizeof pf);
            assert_int_equal(lt_bvh_trace16_f32(&b, s.tf, &pf, 1, &h), LT_E_ARG);
            (void)m;
            (void)id;
        }
#else
        (void)m;
        (void)id;
#endif
    }
    ltt_report("lt_bvh_build: bad desc (bins 1/33, max_leaf 65, min_leaf > max_leaf, depth 65, "
               "flags) -> LT_E_ARG; NULL out/tris/arena and a misaligned arena -> LT_E_ARG; a vertex "
               "1 ulp past 2^%d units -> LT_E_RANGE naming triangle 17 (on the bound: ok); f32 NaN "
               "and 2^49 -> LT_E_RANGE; 50 tris in leaves of 4 with max_depth 3 -> LT_E_DEPTH, 4 "
               "-> ok; wrong numeric path -> LT_E_ARG\n",
               LT_CFG_GEOM_MAX_LOG2);
    free(ar);
    lt_scene_free(&s);
}

static void test_structure(void **state)
{
    static const uint32_t ns[] = {1, 2, 3, 5, 17, 100, 1000, 3000};
    static const int kinds[] = {MESH_CLUSTERS, MESH_SAME_CENTROID, MESH_EXPONENTIAL,
                                MESH_DEGENERATE, MESH_GRID};
    lt_bvh_desc_t descs[5];
    tree_check_t tc[2];
    unsigned ni, ki, di;
    int fmt;
    (void)state;
    memset(descs, 0, sizeof descs);
    memset(tc, 0, sizeof tc);
    descs[1].bins = 2;
    descs[1].max_leaf = 1;
    descs[2].bins = 32;
    descs[2].max_leaf = 8;
    descs[2].min_leaf = 8;
    descs[3].bins = 5;
    descs[3].max_leaf = 3;
    descs[3].max_depth = 12;
    descs[4].flags = LT_BVH_TIGHT;
    for (ni = 0; ni < sizeof ns / sizeof ns[0]; ni++)
        for (ki = 0; ki < sizeof kinds / sizeof kinds[0]; ki++) {
            lt_scene_t s;
            mesh_random(&s, ns[ni], kinds[ki], 1000u * ni + ki);
            for (di = 0; di < 5; di++)
                for (fmt = FMT_Q16; fmt <= (LT_CFG_FLOAT32 ? FMT_F32 : FMT_Q16); fmt++) {
                    built_t bb;
                    assert_int_equal(build(&bb, &s, fmt, &descs[di]), LT_OK);
                    check_tree(&bb.bvh, &s, fmt, &descs[di], &tc[fmt]);
                    unbuild(&bb);
                }
            lt_scene_free(&s);
        }
    for (fmt = FMT_Q16; fmt <= (LT_CFG_FLOAT32 ? FMT_F32 : FMT_Q16); fmt++)
        ltt_report("lt_bvh_build_%s: %lu trees (n 1..3000, clustered / same-centroid / exponential "
                   "/ degenerate / grid meshes, 5 descs), %lu nodes: every triangle exactly once, "
                   "every box = exact union of its triangles + pad, leaves <= max_leaf, depth <= "
                   "max_depth, idx right after the nodes; %lu violations\n",
                   fmt == FMT_Q16 ? "q16" : "f32", tc[fmt].trees, tc[fmt].nodes, tc[fmt].bad);
    assert_int_equal(tc[0].bad + tc[1].bad, 0);
}

static void test_sah_vs_median(void **state)
{
    lt_scene_t s;
    int fmt, bad = 0;
    (void)state;
    mesh_random(&s, 4000, MESH_CLUSTERS, 4242);
    for (fmt = FMT_Q16; fmt <= (LT_CFG_FLOAT32 ? FMT_F32 : FMT_Q16); fmt++) {
        static const uint32_t bins[] = {4, 8, 16, 32};
        unsigned i;
        double med = median_sah(&s, fmt, 4);
        for (i = 0; i < 4; i++) {
            built_t bb;
            tree_check_t tc;
            lt_bvh_desc_t d;
            memset(&d, 0, sizeof d);
            memset(&tc, 0, sizeof tc);
            d.bins = bins[i];
            assert_int_equal(build(&bb, &s, fmt, &d), LT_OK);
            check_tree(&bb.bvh, &s, fmt, &d, &tc);
            ltt_report("SAH cost %s, 4000 clustered triangles, %2u bins: %.2f (object median "
                       "%.2f, ratio %.3f), %u nodes, depth %u\n",
                       fmt == FMT_Q16 ? "q16" : "f32", bins[i], tc.sah, med, tc.sah / med,
                       bb.bvh.nnodes, bb.bvh.depth);
            bad += tc.bad != 0 || !(tc.sah < med);
            unbuild(&bb);
        }
    }
    lt_scene_free(&s);
    assert_int_equal(bad, 0);
}

static void test_trace_random(void **state)
{
    static const int kinds[] = {MESH_CLUSTERS, MESH_GRID, MESH_SAME_CENTROID};
    static const char *names[] = {"clustered", "grid", "same-centroid"};
    uint16_t masks[LTT_MASK_COUNT];
    unsigned ki;
    int fmt, bad = 0;
    (void)state;
    (void)ltt_masks(masks, 99);
    for (ki = 0; ki < 3; ki++)
        for (fmt = FMT_Q16; fmt <= (LT_CFG_FLOAT32 ? FMT_F32 : FMT_Q16); fmt++) {
            lt_scene_t s;
            built_t bb, bt;
            cmp_t c, ct;
            ltt_rng_t r;
            lt_bvh_desc_t tight;
            double ext = kinds[ki] == MESH_CLUSTERS ? 420.0 : (kinds[ki] == MESH_GRID ? 13.0 : 35.0);
            unsigned pk;
            char name[96];
            memset(&c, 0, sizeof c);
            memset(&ct, 0, sizeof ct);
            ct.tight = 1;
            memset(&tight, 0, sizeof tight);
            tight.flags = LT_BVH_TIGHT;
            mesh_random(&s, kinds[ki] == MESH_CLUSTERS ? 1500u : (kinds[ki] == MESH_GRID ? 1200u : 600u),
                        kinds[ki], 77 + ki);
            ltt_rng_seed(&r, 5150 + ki);
            assert_int_equal(build(&bb, &s, fmt, NULL), LT_OK);
            assert_int_equal(build(&bt, &s, fmt, &tight), LT_OK);
            for (pk = 0; pk < 160u / WORK; pk++) {
                dray_t rs[LT_LANES];
                lt_mask16_t k = pk < LTT_MASK_COUNT ? masks[pk] : LT_MASK_ALL;
                rand_rays(&r, (int)(pk % RAY_KINDS), ext, &s, rs, LT_LANES);
                cmp_packet(fmt, &bb.bvh, &s, rs, k, &r, &c);
                /* axis-parallel rays are exact in the slab test: the tight tree must agree too */
                if (pk % RAY_KINDS == 2u)
                    cmp_packet(fmt, &bt.bvh, &s, rs, k, &r, &ct);
            }
            snprintf(name, sizeof name, "lt_bvh_trace16_%s, %s mesh", fmt == FMT_Q16 ? "q16" : "f32",
                     names[ki]);
            bad += cmp_report(name, &c);
            snprintf(name, sizeof name, "  axis-parallel rays, tight tree (%s)",
                     fmt == FMT_Q16 ? "q16" : "f32");
            bad += cmp_report(name, &ct);
            if (fmt == FMT_Q16) {
                /* the s15.16 grid test (LT_ISECT_WT32) through the packet, single-ray and any-hit
                   walks against the brute force with the same test, at the mesh's grid and 2^0 */
                unsigned gi;
                for (gi = 0; gi < 2; gi++) {
                    cmp_t cw;
                    unsigned g = gi == 0 ? lt_wt32_shift_q16(s.tq, s.ntris) : 0u;
                    memset(&cw, 0, sizeof cw);
                    ltt_isect = LT_ISECT_WT32_G(g);
                    bb.bvh.isect = ltt_isect;
                    for (pk = 0; pk < 80u / WORK; pk++) {
                        dray_t rs[LT_LANES];
                        lt_mask16_t k = pk < LTT_MASK_COUNT ? masks[pk] : LT_MASK_ALL;
                        rand_rays(&r, (int)(pk % RAY_KINDS), ext, &s, rs, LT_LANES);
                        cmp_packet(fmt, &bb.bvh, &s, rs, k, &r, &cw);
                    }
                    snprintf(name, sizeof name, "  isect wt32, grid 2^%u (q16)", g);
                    bad += cmp_report(name, &cw);
                    bad += cw.hits == 0;
                }
                ltt_isect = LT_ISECT_WT;
                bb.bvh.isect = LT_ISECT_WT;
            }
            unbuild(&bb);
            unbuild(&bt);
            lt_scene_free(&s);
        }
    assert_int_equal(bad, 0);
}

/* Rays that start exactly on node box planes and run along them or along an axis. */
static void test_boundaries(void **state)
{
    lt_scene_t s;
    int fmt, bad = 0;
    (void)state;
    mesh_random(&s, 600, MESH_GRID, 31337);
    for (fmt = FMT_Q16; fmt <= (LT_CFG_FLOAT32 ? FMT_F32 : FMT_Q16); fmt++) {
        int tight;
        for (tight = 0; tight < 2; tight++) {
            built_t bb;
            cmp_t c;
            ltt_rng_t r;
            lt_bvh_desc_t d;
            uint32_t pk;
            char name[96];
            memset(&c, 0, sizeof c);
            memset(&d, 0, sizeof d);
            d.flags = tight ? LT_BVH_TIGHT : 0u;
            c.tight = tight;
            ltt_rng_seed(&r, 8080u + (unsigned)tight);
            assert_int_equal(build(&bb, &s, fmt, &d), LT_OK);
            for (pk = 0; pk < 120u / WORK; pk++) {
                dray_t rs[LT_LANES];
                int i, a;
                for (i = 0; i < LT_LANES; i++) {
                    /* origin: a corner of a random node's stored box, moved along one axis */
                    dnode_t n = get_node(&bb.bvh, ltt_rng_below(&r, bb.bvh.nnodes));
                    uint32_t ax = ltt_rng_below(&r, 3), kind = ltt_rng_below(&r, 3);
                    for (a = 0; a < 3; a++) {
                        rs[i].o[a] = ltt_rng_below(&r, 2) ? n.b.lo[a] : n.b.hi[a];
                        rs[i].d[a] = 0.0;
                    }
                    rs[i].o[ax] = ltt_rng_uniform(&r, -16.0, 16.0);
                    rs[i].tmin = 0.0;
                    rs[i].tmax = 30000.0;
                    if (tight)
                        kind = 0; /* a tight box is exact only where the slab test is exact */
                    if (kind == 0) { /* along the axis, inside the box's face planes */
                        rs[i].d[ax] = ltt_rng_below(&r, 2) ? 1.0 : -1.0;
                    } else if (kind == 1) { /* diagonal in a face plane */
                        rs[i].d[ax] = 1.0;
                        rs[i].d[(ax + 1u) % 3u] = ltt_rng_below(&r, 2) ? 1.0 : -1.0;
                        normalize(rs[i].d);
                    } else { /* any direction from a box corner */
                        for (a = 0; a < 3; a++)
                            rs[i].d[a] = ltt_rng_uniform(&r, -1.0, 1.0);
                        normalize(rs[i].d);
                    }
                }
                cmp_packet(fmt, &bb.bvh, &s, rs, LT_MASK_ALL, &r, &c);
            }
            snprintf(name, sizeof name, "origins on node box planes, %s (%s)",
                     tight ? "tight tree, axis-parallel rays" : "padded tree, any direction",
                     fmt == FMT_Q16 ? "q16" : "f32");
            bad += cmp_report(name, &c);
            unbuild(&bb);
        }
    }
    lt_scene_free(&s);
    assert_int_equal(bad, 0);
}

static void test_empty_single_degenerate(void **state)
{
    lt_scene_t s;
    built_t bb;
    ltt_rng_t r;
    int fmt, bad = 0;
    (void)state;
    ltt_rng_seed(&r, 4);
    /* empty scene: a valid tree with no nodes that never hits */
    mesh_alloc(&s, 0);
    for (fmt = FMT_Q16; fmt <= (LT_CFG_FLOAT32 ? FMT_F32 : FMT_Q16); fmt++) {
        cmp_t c;
        unsigned pk;
        memset(&c, 0, sizeof c);
        assert_int_equal(build(&bb, &s, fmt, NULL), LT_OK);
        assert_int_equal(bb.size, 0);
        assert_int_equal(bb.bvh.nnodes, 0);
        for (pk = 0; pk < 8; pk++) {
            dray_t rs[LT_LANES];
            rand_rays(&r, (int)(pk % RAY_KINDS), 100.0, &s, rs, LT_LANES);
            cmp_packet(fmt, &bb.bvh, &s, rs, LT_MASK_ALL, &r, &c);
        }
        bad += cmp_report(fmt == FMT_Q16 ? "empty scene (n = 0, q16): every ray misses"
                                         : "empty scene (n = 0, f32): every ray misses",
                          &c);
        bad += c.hits != 0;
        unbuild(&bb);
    }
    lt_scene_free(&s);
    /* one triangle; all-degenerate meshes */
    {
        static const int kinds[2] = {MESH_CLUSTERS, MESH_DEGENERATE};
        static const uint32_t ns[2] = {1, 500};
        unsigned m;
        for (m = 0; m < 2; m++) {
            mesh_random(&s, ns[m], kinds[m], 12 + m);
            for (fmt = FMT_Q16; fmt <= (LT_CFG_FLOAT32 ? FMT_F32 : FMT_Q16); fmt++) {
                cmp_t c;
                unsigned pk;
                char name[96];
                memset(&c, 0, sizeof c);
                assert_int_equal(build(&bb, &s, fmt, NULL), LT_OK);
                for (pk = 0; pk < 64u / WORK; pk++) {
                    dray_t rs[LT_LANES];
                    rand_rays(&r, (int)(pk % RAY_KINDS), m == 0 ? 30.0 : 100.0, &s, rs, LT_LANES);
                    cmp_packet(fmt, &bb.bvh, &s, rs, LT_MASK_ALL, &r, &c);
                }
                snprintf(name, sizeof name, "%s (%s)",
                         m == 0 ? "single-triangle scene" : "500 degenerate triangles (never hit)",
                         fmt == FMT_Q16 ? "q16" : "f32");
                bad += cmp_report(name, &c);
                if (m == 1)
                    bad += c.hits != 0;
                else
                    bad += c.hits == 0; /* the camera rays aim at it */
                unbuild(&bb);
            }
            lt_scene_free(&s);
        }
    }
    assert_int_equal(bad, 0);
}

static void test_depth_adversarial(void **state)
{
    static const int kinds[2] = {MESH_SAME_CENTROID, MESH_EXPONENTIAL};
    unsigned m;
    int bad = 0;
    (void)state;
    for (m = 0; m < 2; m++) {
        lt_scene_t s;
        uint32_t n = m == 0 ? 5000u / WORK : 120u;
        int fmt;
        mesh_random(&s, n, kinds[m], 900 + m);
        for (fmt = FMT_Q16; fmt <= (LT_CFG_FLOAT32 ? FMT_F32 : FMT_Q16); fmt++) {
            static const uint32_t depths[3] = {0, 12, 6};
            unsigned di;
            for (di = 0; di < 3; di++) {
                built_t bb;
                tree_check_t tc;
                cmp_t c;
                ltt_rng_t r;
                lt_bvh_desc_t d;
                unsigned pk;
                lt_status_t st;
                memset(&d, 0, sizeof d);
                memset(&tc, 0, sizeof tc);
                memset(&c, 0, sizeof c);
                d.max_depth = depths[di];
                st = build(&bb, &s, fmt, &d);
                if (m == 0 && di == 2) {
                    /* 5000 (625 in ASan builds) in leaves of 4 need 11 (8) halvings: depth 6
                     * cannot exist */
                    assert_int_equal(st, LT_E_DEPTH);
                    unbuild(&bb);
                    continue;
                }
                assert_int_equal(st, LT_OK);
                check_tree(&bb.bvh, &s, fmt, &d, &tc);
                ltt_rng_seed(&r, 31 + di);
                for (pk = 0; pk < 24u / WORK; pk++) {
                    dray_t rs[LT_LANES];
                    rand_rays(&r, (int)(pk % RAY_KINDS), m == 0 ? 35.0 : 1500.0, &s, rs, LT_LANES);
                    cmp_packet(fmt, &bb.bvh, &s, rs, LT_MASK_ALL, &r, &c);
                }
                ltt_report("%s, %u triangles, %s, max_depth %u: depth %u, %u leaves, %lu tree "
                           "violations, traces %s\n",
                           m == 0 ? "all boxes centred on one point" : "exponential spacing", n,
                           fmt == FMT_Q16 ? "q16" : "f32", d.max_depth ? d.max_depth : 64,
                           bb.bvh.depth, bb.bvh.leaves, tc.bad,
                           c.bad + c.single_bad + c.occl_bad + c.errs ? "WRONG" : "= brute force");
                bad += (int)tc.bad + (int)(c.bad + c.single_bad + c.occl_bad + c.errs);
                unbuild(&bb);
            }
        }
        lt_scene_free(&s);
    }
    ltt_report("depth bound: %u identical centroids with max_depth 6 -> LT_E_DEPTH (needs %u)\n",
               5000u / WORK, WORK > 1u ? 8u : 11u);
    assert_int_equal(bad, 0);
}

/* A foreign tree deeper than the traversal stack: a chain of 70 interior nodes whose left child
 * continues the chain and whose right child is a leaf, all with the same box, so every level pushes
 * its leaf. The traversal must stop pushing at LT_BVH_MAX_DEPTH (ASan checks the stack), return
 * LT_E_DEPTH, and still report only real hits. */
static void test_stack_overflow(void **state)
{
    enum { CHAIN = 70 };
    lt_bvh_node_q16_t nodes[2 * CHAIN + 2];
    uint32_t idx[CHAIN + 1], i;
    lt_scene_t s;
    lt_bvh_t b;
    lt_bvh_stats_t st;
    lt_ray16_q16_t p;
    lt_hit16_t h;
    dray_t rs[LT_LANES];
    ltt_rng_t r;
    lt_status_t rc;
    int lane, wrong = 0;
    (void)state;
    mesh_random(&s, CHAIN + 1, MESH_CLUSTERS, 55);
    memset(nodes, 0, sizeof nodes);
    for (i = 0; i <= CHAIN; i++)
        idx[i] = i;
    /* node 0 and each chain node c_j at slot 2j (j >= 1); leaf j at slot 2j + 1 */
    for (i = 0; i <= CHAIN; i++) {
        uint32_t slot = i == 0 ? 0 : 2u * i;
        int a;
        for (a = 0; a < 3; a++) {
            nodes[slot].b.lo[a] = LT_Q16(-600.0);
            nodes[slot].b.hi[a] = LT_Q16(600.0);
            nodes[slot + 1u].b = nodes[slot].b;
        }
        if (i < CHAIN) {
            nodes[slot].left_first = 2u * (i + 1u);
            nodes[slot].count = 0;
        } else {
            nodes[slot].left_first = i;
            nodes[slot].count = 1;
        }
        if (i >= 1) { /* the leaf sibling of chain node i */
            nodes[2u * i + 1u].left_first = i - 1u;
            nodes[2u * i + 1u].count = 1;
        }
    }
    memset(&b, 0, sizeof b);
    memset(&st, 0, sizeof st);
    b.nodes = nodes;
    b.idx = idx;
    b.nnodes = 2 * CHAIN + 2;
    b.ntris = CHAIN + 1;
    b.num = LT_BVH_NUM_Q16;
    b.stats = &st;
    ltt_rng_seed(&r, 3);
    rand_rays(&r, 0, 420.0, NULL, rs, LT_LANES);
    q16_packet(rs, &p);
    rc = lt_bvh_trace16_q16(&b, s.tq, &p, LT_MASK_ALL, &h);
    assert_int_equal(rc, LT_E_DEPTH);
    for (lane = 0; lane < LT_LANES; lane++) {
        /* any reported hit must be that triangle at that distance */
        if (h.id.l[lane] >= 0) {
            lt_ray16_q16_t q;
            lt_hit16_t hq;
            q16_packet(rs, &q);
            hq.id = lt_vi32_set1(-1);
            (void)ltt_tri16_q16(&q, (lt_mask16_t)(1u << lane), &s.tq[h.id.l[lane]], h.id.l[lane],
                               &hq);
            wrong += q.tmax.l[lane] != p.tmax.l[lane];
        }
    }
    {
        lt_ray1_q16_t r1;
        int32_t id;
        q16_packet(rs, &p);
        q16_single(&p, 0, &r1);
        assert_int_equal(lt_bvh_trace1_q16(&b, s.tq, &r1, &id), LT_E_DEPTH);
    }
    ltt_report("stack overflow: a foreign chain tree of depth %d -> LT_E_DEPTH from packet and "
               "single-ray traversal, max stack %u of %d (never past it), %llu pushes refused, "
               "%d wrong hits\n",
               CHAIN, st.max_stack, LT_BVH_MAX_DEPTH, (unsigned long long)st.overflows, wrong);
    assert_true(st.max_stack <= LT_BVH_MAX_DEPTH);
    assert_int_equal(wrong, 0);
    lt_scene_free(&s);
}

/* ---- quantised nodes ---------------------------------------------------------------------------------- */

/* The documented decode, written independently: e = smallest e with ceil(ext / 2^e) <= 65535. */
static void q_ref_decode(const int64_t flo[3], const int64_t fhi[3], const lt_bvhq_node_t *n,
                         int64_t lo[3], int64_t hi[3])
{
    int a;
    for (a = 0; a < 3; a++) {
        int64_t ext = fhi[a] - flo[a];
        int e = 0;
        while (((ext + ((int64_t)1 << e) - 1) >> e) > 65535)
            e++;
        lo[a] = flo[a] + ((int64_t)n->qlo[a] << e);
        hi[a] = flo[a] + ((int64_t)n->qhi[a] << e);
    }
}

typedef struct qcheck {
    unsigned long nodes, bad;
    double sah_exact, sah_q; /* SAH over the stored (padded) boxes, and over the decoded ones */
    double max_face;         /* largest face error in units of the parent frame's extent */
} qcheck_t;

static double box_area_i(const int64_t lo[3], const int64_t hi[3])
{
    double w[3];
    int a;
    for (a = 0; a < 3; a++)
        w[a] = (double)(hi[a] - lo[a]);
    return w[0] * w[1] + w[1] * w[2] + w[2] * w[0];
}

/* Walk the quantised tree beside its source: node i has decoded box (lo, hi). */
static void q_walk(const lt_bvhq_t *q, const lt_bvh_t *src, uint32_t i, const int64_t lo[3],
                   const int64_t hi[3], qcheck_t *c)
{
    const lt_bvh_node_q16_t *sn = &((const lt_bvh_node_q16_t *)src->nodes)[i];
    const lt_bvhq_node_t *qn = &q->nodes[i];
    int64_t slo[3], shi[3];
    int a;
    c->nodes++;
    for (a = 0; a < 3; a++) {
        slo[a] = sn->b.lo[a];
        shi[a] = sn->b.hi[a];
        if (lo[a] > slo[a] || hi[a] < shi[a]) {
            if (c->bad++ < 6)
                printf("  FAIL quantised node %u axis %d: [%lld, %lld] does not contain [%lld, "
                       "%lld]\n", i, a, (long long)lo[a], (long long)hi[a], (long long)slo[a],
                       (long long)shi[a]);
        }
    }
    if (LT_BVH_IS_LEAF(sn)) {
        if (LT_BVHQ_COUNT(qn->link) != sn->count || LT_BVHQ_INDEX(qn->link) != sn->left_first)
            c->bad++;
        c->sah_exact += (double)sn->count * box_area_i(slo, shi);
        c->sah_q += (double)sn->count * box_area_i(lo, hi);
        return;
    }
    if (LT_BVHQ_COUNT(qn->link) != 0 || LT_BVHQ_INDEX(qn->link) != sn->left_first) {
        c->bad++;
        return;
    }
    c->sah_exact += box_area_i(slo, shi);
    c->sah_q += box_area_i(lo, hi);
    {
        uint32_t ch;
        for (ch = 0; ch < 2; ch++) {
            int64_t clo[3], chi[3];
            const lt_bvh_node_q16_t *cs = &((const lt_bvh_node_q16_t *)src->nodes)[sn->left_first + ch];
            q_ref_decode(lo, hi, &q->nodes[sn->left_first + ch], clo, chi);
            for (a = 0; a < 3; a++) {
                double ext = (double)(hi[a] - lo[a]);
                double f0 = (double)(cs->b.lo[a] - clo[a]) / (ext > 0 ? ext : 1.0);
                double f1 = (double)(chi[a] - cs->b.hi[a]) / (ext > 0 ? ext : 1.0);
                c->max_face = f0 > c->max_face ? f0 : c->max_face;
                c->max_face = f1 > c->max_face ? f1 : c->max_face;
            }
            q_walk(q, src, sn->left_first + ch, clo, chi, c);
        }
    }
}

typedef struct qbuilt {
    lt_bvhq_t q;
    unsigned char *mem;
    size_t size;
} qbuilt_t;

/* Quantise src into a poisoned buffer of exactly the reported size; check the tail and, with
 * one byte less, LT_E_SPACE. */
static void qbuild(qbuilt_t *qb, const lt_bvh_t *src)
{
    lt_bvhq_t tmp;
    assert_int_equal(lt_bvhq_size(src, &qb->size), LT_OK);
    qb->mem = malloc(qb->size + TAIL);
    assert_non_null(qb->mem);
    ltt_poison(qb->mem, qb->size + TAIL);
    if (qb->size > 0) {
        assert_int_equal(lt_bvhq_build_q16(&tmp, src, qb->mem, qb->size - 1), LT_E_SPACE);
        assert_int_equal(tmp.bytes, qb->size);
        assert_int_equal(ltt_touched(qb->mem, 0, qb->size + TAIL), 0);
    }
    assert_int_equal(lt_bvhq_build_q16(&qb->q, src, qb->size ? qb->mem : NULL, qb->size), LT_OK);
    assert_int_equal(ltt_touched(qb->mem, qb->size, qb->size + TAIL), 0);
}

static void q_check(const qbuilt_t *qb, const lt_bvh_t *src, qcheck_t *c)
{
    int64_t lo[3], hi[3];
    int a;
    if (src->nnodes == 0)
        return;
    for (a = 0; a < 3; a++) {
        lo[a] = qb->q.root.lo[a];
        hi[a] = qb->q.root.hi[a];
    }
    q_walk(&qb->q, src, 0, lo, hi, c);
}

/* Trace one packet through the quantised tree and through the 32-byte tree: same distance bit for
 * bit, same id up to exact ties; also single rays and any hit. Counters in *qs / *es. */
static void q_cmp_packet(const lt_bvhq_t *q0, const lt_bvh_t *b0, const lt_scene_t *s,
                         const lt_ray16_q16_t *p0, lt_mask16_t k, lt_bvh_stats_t *qs,
                         lt_bvh_stats_t *q1s, lt_bvh_stats_t *es, unsigned long *rays,
                         unsigned long *ties, unsigned long *bad)
{
    lt_bvhq_t q = *q0, q1 = *q0;
    lt_bvh_t b = *b0;
    lt_ray16_q16_t pq = *p0, pb = *p0, po = *p0;
    lt_hit16_t hq, hb;
    lt_mask16_t occ, exp = 0;
    int i;
    q.stats = qs;
    q1.stats = q1s;
    b.stats = es;
    *bad += lt_bvhq_trace16_q16(&q, s->tq, &pq, k, &hq) != LT_OK;
    *bad += lt_bvh_trace16_q16(&b, s->tq, &pb, k, &hb) != LT_OK;
    for (i = 0; i < LT_LANES; i++) {
        lt_ray1_q16_t r1;
        int32_t id1;
        if (!LTT_ON(k, i))
            continue;
        (*rays)++;
        if (pq.tmax.l[i] != pb.tmax.l[i] ||
            (hq.id.l[i] != hb.id.l[i] && !tie_q16(s, p0, i, hq.id.l[i], pb.tmax.l[i]))) {
            if ((*bad)++ < 6)
                printf("  FAIL quantised lane %d: t %.9g id %d, 32-byte tree %.9g %d\n", i,
                       lt_q16_to_double(pq.tmax.l[i]), hq.id.l[i], lt_q16_to_double(pb.tmax.l[i]),
                       hb.id.l[i]);
        } else if (hq.id.l[i] != hb.id.l[i]) {
            (*ties)++;
        }
        q16_single(p0, i, &r1);
        *bad += lt_bvhq_trace1_q16(&q1, s->tq, &r1, &id1) != LT_OK;
        if (r1.tmax != pb.tmax.l[i] || (id1 != hb.id.l[i] && !tie_q16(s, p0, i, id1, pb.tmax.l[i])))
            (*bad)++;
        if (hb.id.l[i] >= 0 && (i & 1)) {
            po.tmax.l[i] = pb.tmax.l[i]; /* at the closest t: not occluded */
        } else if (hb.id.l[i] >= 0) {
            po.tmax.l[i] = pb.tmax.l[i] + 1; /* 1 ulp beyond: occluded */
            exp = (lt_mask16_t)(exp | (1u << i));
        }
    }
    q.stats = NULL;
    *bad += lt_bvhq_occluded16_q16(&q, s->tq, &po, k, &occ) != LT_OK;
    if (occ != exp && (*bad)++ < 6)
        printf("  FAIL quantised occluded16 %04x, expected %04x\n", occ, exp);
}

static void test_quantised(void **state)
{
    static const int kinds[] = {MESH_CLUSTERS, MESH_GRID, MESH_SAME_CENTROID, MESH_DEGENERATE};
    static const char *names[] = {"clustered", "grid", "same-centroid", "degenerate"};
    unsigned ki;
    int bad = 0;
    (void)state;
    for (ki = 0; ki < 4; ki++) {
        lt_scene_t s;
        built_t bb;
        qbuilt_t qb;
        qcheck_t qc;
        lt_bvh_stats_t qs, q1s, es;
        unsigned long rays = 0, ties = 0, tb = 0;
        ltt_rng_t r;
        unsigned pk;
        memset(&qc, 0, sizeof qc);
        memset(&qs, 0, sizeof qs);
        memset(&q1s, 0, sizeof q1s);
        memset(&es, 0, sizeof es);
        mesh_random(&s, ki == 2 ? 600u : 1500u, kinds[ki], 610 + ki);
        assert_int_equal(build(&bb, &s, FMT_Q16, NULL), LT_OK);
        qbuild(&qb, &bb.bvh);
        q_check(&qb, &bb.bvh, &qc);
        ltt_rng_seed(&r, 77 + ki);
        for (pk = 0; pk < 120u / WORK; pk++) {
            dray_t rs[LT_LANES];
            lt_ray16_q16_t p;
            double ext = ki == 0 ? 420.0 : (ki == 1 ? 13.0 : (ki == 2 ? 35.0 : 100.0));
            rand_rays(&r, (int)(pk % RAY_KINDS), ext, &s, rs, LT_LANES);
            q16_packet(rs, &p);
            q_cmp_packet(&qb.q, &bb.bvh, &s, &p, LT_MASK_ALL, &qs, &q1s, &es, &rays, &ties, &tb);
        }
        ltt_report("lt_bvhq_build_q16, %s mesh (%u tris): %u nodes x 16 B = %zu B (32-byte "
                   "nodes: %zu B); %lu decoded boxes, %lu not containing the exact box; max face "
                   "error %.2e of the parent extent (bound 2^-15 = 3.05e-5); SAH of the decoded "
                   "boxes +%.3f%% over the exact ones\n",
                   names[ki], s.ntris, qb.q.nnodes, qb.q.bytes, (size_t)bb.bvh.nnodes * 32u,
                   qc.nodes, qc.bad, qc.max_face, 100.0 * (qc.sah_q / qc.sah_exact - 1.0));
        ltt_report("  lt_bvhq_trace16/trace1/occluded16 vs the 32-byte tree: %lu rays, t bit-exact, "
                   "%lu exact ties, %lu wrong; nodes per packet %.1f vs %.1f (+%.1f%%)\n",
                   rays, ties, tb, (double)qs.nodes / (double)qs.calls,
                   (double)es.nodes / (double)es.calls,
                   100.0 * ((double)qs.nodes / (double)es.nodes - 1.0));
        bad += (int)(qc.bad + tb) + !(qc.max_face <= 2.0 / 65535.0);
        free(qb.mem);
        unbuild(&bb);
        lt_scene_free(&s);
    }
    /* empty tree, leaves too large, wrong numeric path */
    {
        lt_scene_t s;
        built_t bb;
        lt_bvh_desc_t d;
        lt_bvhq_t q;
        size_t sz;
        unsigned char mem[64];
        lt_ray16_q16_t p;
        lt_hit16_t h;
        mesh_alloc(&s, 0);
        assert_int_equal(build(&bb, &s, FMT_Q16, NULL), LT_OK);
        assert_int_equal(lt_bvhq_size(&bb.bvh, &sz), LT_OK);
        assert_int_equal(sz, 0);
        assert_int_equal(lt_bvhq_build_q16(&q, &bb.bvh, NULL, 0), LT_OK);
        memset(&p, 0, sizeof p);
        assert_int_equal(lt_bvhq_trace16_q16(&q, s.tq, &p, LT_MASK_ALL, &h), LT_OK);
        assert_int_equal(h.id.l[0], -1);
        unbuild(&bb);
        lt_scene_free(&s);
        mesh_random(&s, 16, MESH_SAME_CENTROID, 5);
        memset(&d, 0, sizeof d);
        d.max_leaf = 16;
        d.min_leaf = 16; /* the root is one leaf of 16 */
        assert_int_equal(build(&bb, &s, FMT_Q16, &d), LT_OK);
        {
            unsigned char *m2;
            assert_int_equal(lt_bvhq_size(&bb.bvh, &sz), LT_OK);
            m2 = malloc(sz);
            assert_non_null(m2);
            assert_int_equal(lt_bvhq_build_q16(&q, &bb.bvh, m2, sz), LT_E_RANGE);
            assert_int_equal(lt_bvhq_build_q16(&q, &bb.bvh, m2 + 1, sz - 1), LT_E_ARG);
            free(m2);
        }
        bb.bvh.num = LT_BVH_NUM_F32;
        assert_int_equal(lt_bvhq_size(&bb.bvh, &sz), LT_E_ARG);
        assert_int_equal(lt_bvhq_build_q16(&q, &bb.bvh, mem, sizeof mem), LT_E_ARG);
        unbuild(&bb);
        lt_scene_free(&s);
    }
    ltt_report("lt_bvhq: empty tree -> no nodes, never hits; leaves of 16 -> LT_E_RANGE; misaligned "
               "buffer or an f32 source -> LT_E_ARG; one byte short -> LT_E_SPACE with the size, "
               "buffer untouched\n");
    assert_int_equal(bad, 0);
}

/* ---- real meshes ------------------------------------------------------------------------------------ */

/* ---- the wide BVH for single rays (lt_bvh8.h) --------------------------------------------------- */

typedef struct wcheck {
    unsigned long nodes, children, leaves, tris, rays, same, ties, occl, occl_bad, bad, errs;
    unsigned long zero_area, clamped;
} wcheck_t;

/* Structure: every node has 1..8 children in its first slots, empty slots inverted, every interior
 * child a later node; every leaf child a range of whole blocks (the blocks used once, in order),
 * every triangle in exactly one lane with its rebuilt vertices (v0, v0 + e1, v0 + e2 as the
 * triangle tests rebuild them) and its id (-2 - id for a zero-area triangle, -1 and zero vertices
 * for the lanes past a leaf's last triangle); a leaf holds at most max(LT_BVH8_MERGE, the
 * binary tree's largest leaf) triangles. */
static void w_structure(const lt_bvh8_t *w, const lt_bvh_t *b, const lt_scene_t *s, int fmt,
                        uint32_t max_leaf, wcheck_t *c)
{
    unsigned char *seen = calloc(b->ntris + 1u, 1);
    uint32_t i, next_block = 0, zero_area = 0;
    unsigned k;
    assert_non_null(seen);
    for (i = 0; i < w->nnodes; i++) {
        const uint32_t *child;
        const uint16_t *cnt;
        unsigned used = 0;
#if LT_CFG_FLOAT32
        if (fmt == FMT_F32) {
            child = ((const lt_bvh8_node_f32_t *)w->nodes)[i].child;
            cnt = ((const lt_bvh8_node_f32_t *)w->nodes)[i].cnt;
        } else
#endif
        {
            child = ((const lt_bvh8_node_q16_t *)w->nodes)[i].child;
            cnt = ((const lt_bvh8_node_q16_t *)w->nodes)[i].cnt;
        }
        c->nodes++;
        for (k = 0; k < LT_BVH8_WIDTH; k++) {
            uint32_t j;
            if (cnt[k] == LT_BVH8_EMPTY)
                continue;
            assert_int_equal(k, used); /* slots in use first */
            used++;
            c->children++;
            if (cnt[k] == 0) {
                assert_true(child[k] > i && child[k] < w->nnodes);
                continue;
            }
            c->leaves++;
            assert_true(cnt[k] <= (max_leaf > LT_BVH8_MERGE ? max_leaf : LT_BVH8_MERGE));
            /* blocks are numbered in the order the breadth-first fill writes the leaves */
            assert_int_equal(child[k], next_block);
            next_block += LT_BVH8_BLOCKS(cnt[k]);
            assert_true(next_block <= w->nblocks);
            for (j = 0; j < LT_BVH8_BLOCKS(cnt[k]) * LT_BVH8_LANES; j++) {
                unsigned l = j % LT_BVH8_LANES, a, v;
                int32_t id;
                int32_t vq[9] = {0};
                float vf[9] = {0};
#if LT_CFG_FLOAT32
                if (fmt == FMT_F32) {
                    const lt_bvh8_tris4_f32_t *bk =
                        (const lt_bvh8_tris4_f32_t *)w->blocks + child[k] + j / LT_BVH8_LANES;
                    id = bk->id[l];
                    for (a = 0; a < 9; a++)
                        vf[a] = bk->v[a][l];
                } else
#endif
                {
                    const lt_bvh8_tris4_q16_t *bk =
                        (const lt_bvh8_tris4_q16_t *)w->blocks + child[k] + j / LT_BVH8_LANES;
                    id = bk->id[l];
                    for (a = 0; a < 9; a++)
                        vq[a] = bk->v[a][l];
                }
                if (j >= cnt[k]) {
                    assert_int_equal(id, -1);
                    for (a = 0; a < 9; a++)
                        assert_true(fmt == FMT_F32 ? vf[a] == 0.0f : vq[a] == 0);
                    continue;
                }
                if (id <= -2) {
                    id = -2 - id;
                    zero_area++;
                }
                assert_true(id >= 0 && (uint32_t)id < b->ntris);
                assert_int_equal(seen[id], 0);
                seen[id] = 1;
                c->tris++;
                for (v = 0; v < 3; v++)
                    for (a = 0; a < 3; a++) {
#if LT_CFG_FLOAT32
                        if (fmt == FMT_F32) {
                            const lt_tri_f32_t *t = &s->tf[id];
                            float want = v == 0 ? t->v0[a] : t->v0[a] + (v == 1 ? t->e1[a] : t->e2[a]);
                            assert_true(memcmp(&vf[3 * v + a], &want, sizeof want) == 0);
                            continue;
                        }
#endif
                        {
                            const lt_tri_q16_t *t = &s->tq[id];
                            lt_q16_t want = v == 0 ? t->v0[a]
                                                   : lt_q16_add_sat(t->v0[a], v == 1 ? t->e1[a] : t->e2[a]);
                            assert_int_equal(vq[3 * v + a], want);
                        }
                    }
            }
        }
        assert_true(used >= 1 && used <= LT_BVH8_WIDTH);
        assert_true(used >= 2 || w->nnodes == 1);
    }
    assert_int_equal(next_block, w->nblocks);
    assert_int_equal(c->leaves, w->leaves);
    assert_int_equal(c->tris, b->ntris);
    assert_int_equal(w->children, c->children);
    c->zero_area = zero_area;
    free(seen);
}

/* One ray through both trees: closest t bits equal, the same triangle or an exact tie (both hit at
 * that t); any hit equal. */
static void w_ray(const lt_bvh8_t *w, const lt_bvh_t *b, const lt_scene_t *s, int fmt,
                  const lt_ray16_q16_t *pq, const void *pf, int lane, wcheck_t *c)
{
    int32_t iw = -1, ib = -1;
    int ow = 0, ob = 0, same_t;
    c->rays++;
#if LT_CFG_FLOAT32
    if (fmt == FMT_F32) {
        lt_ray1_f32_t r0, rw, rb;
        f32_single((const lt_ray16_f32_t *)pf, lane, &r0);
        rw = r0;
        rb = r0;
        c->errs += lt_bvh8_trace1_f32(w, s->tf, &rw, &iw) != LT_OK;
        c->errs += lt_bvh_trace1_f32(b, s->tf, &rb, &ib) != LT_OK;
        same_t = memcmp(&rw.tmax, &rb.tmax, sizeof rw.tmax) == 0;
        rw = r0;
        rb = r0;
        c->errs += lt_bvh8_occluded1_f32(w, s->tf, &rw, &ow) != LT_OK;
        c->errs += lt_bvh_occluded1_f32(b, s->tf, &rb, &ob) != LT_OK;
    } else
#endif
    {
        lt_ray1_q16_t r0, rw, rb;
        (void)pf;
        q16_single(pq, lane, &r0);
        {
            /* a ray whose |origin| + span leaves int32 takes the node test with the clamp */
            int a;
            for (a = 0; a < 3; a++)
                if ((uint64_t)w->span + (uint64_t)(r0.o[a] < 0 ? -(int64_t)r0.o[a] : r0.o[a]) >
                    (uint64_t)INT32_MAX) {
                    c->clamped++;
                    break;
                }
        }
        rw = r0;
        rb = r0;
        c->errs += lt_bvh8_trace1_q16(w, s->tq, &rw, &iw) != LT_OK;
        c->errs += lt_bvh_trace1_q16(b, s->tq, &rb, &ib) != LT_OK;
        same_t = rw.tmax == rb.tmax;
        rw = r0;
        rb = r0;
        c->errs += lt_bvh8_occluded1_q16(w, s->tq, &rw, &ow) != LT_OK;
        c->errs += lt_bvh_occluded1_q16(b, s->tq, &rb, &ob) != LT_OK;
    }
    if (iw == ib && (iw < 0 || same_t))
        c->same++;
    else if (iw >= 0 && ib >= 0 && same_t)
        c->ties++;
    else if (c->bad++ < 5)
        print_message("  wide %d vs binary %d (t %s)\n", iw, ib, same_t ? "equal" : "differs");
    c->occl++;
    if (ow != ob && c->occl_bad++ < 5)
        print_message("  wide any-hit %d vs binary %d\n", ow, ob);
}

/* npk random packets of rand_rays' kinds, every lane through both trees (w_ray). */
static void w_rays(const lt_bvh8_t *w, const lt_bvh_t *b, const lt_scene_t *s, int fmt,
                   ltt_rng_t *r, double ext, unsigned npk, wcheck_t *c)
{
    unsigned pk;
    for (pk = 0; pk < npk; pk++) {
        dray_t rs[LT_LANES];
        lt_ray16_q16_t pq;
        int lane;
#if LT_CFG_FLOAT32
        lt_ray16_f32_t pf;
#else
        int pf = 0;
#endif
        rand_rays(r, (int)(pk % RAY_KINDS), ext, s, rs, LT_LANES);
        q16_packet(rs, &pq);
#if LT_CFG_FLOAT32
        f32_packet(rs, &pf);
#endif
        for (lane = 0; lane < LT_LANES; lane++)
            w_ray(w, b, s, fmt, &pq, &pf, lane, c);
    }
}

/* The meshes of the wide-tree tests: clustered, grid, same-centroid; the fourth the clustered mesh
 * with every 7th triangle collapsed to zero area (a repeated vertex), which the blocks flag and no
 * ray may hit; the fifth the clustered mesh scaled by 9 (planes to +-3,900 units, inside the
 * 4,096-unit geometry bound) with origins to +-32,000, so that plane - origin leaves int32 for
 * some rays: the s15.16 node test's clamp (the other meshes' rays take the register form without
 * it, lt_bvh8_t.span). Mesh ki into *s; returns the extent for rand_rays. */
static const char *const wide_names[] = {"clustered", "grid", "same-centroid",
                                         "clustered, 1/7 zero-area", "clustered x9, far origins"};
static double wide_mesh(unsigned ki, lt_scene_t *s)
{
    static const int kinds[] = {MESH_CLUSTERS, MESH_GRID, MESH_SAME_CENTROID, MESH_CLUSTERS,
                                MESH_CLUSTERS};
    double ext = kinds[ki] == MESH_CLUSTERS ? 420.0 : (kinds[ki] == MESH_GRID ? 13.0 : 35.0);
    uint32_t t;
    mesh_random(s, kinds[ki] == MESH_CLUSTERS ? 1500u : (kinds[ki] == MESH_GRID ? 1200u : 600u),
                kinds[ki], 91 + (uint64_t)ki);
    if (ki == 3) {
        for (t = 0; t < s->ntris; t += 7u)
            set_vert(s, t, 2, s->vd[t * 9u], s->vd[t * 9u + 1u], s->vd[t * 9u + 2u]);
        mesh_quantise(s);
    }
    if (ki == 4) {
        for (t = 0; t < s->ntris * 9u; t++)
            s->vd[t] *= 9.0;
        mesh_quantise(s);
        ext = 12800.0; /* eyes of rand_rays' first kind up to 2.5 ext */
    }
    return ext;
}

static void test_wide(void **state)
{
    /* the five meshes of wide_mesh */
    unsigned ki;
    int fmt;
    (void)state;
    for (ki = 0; ki < 5; ki++)
        for (fmt = FMT_Q16; fmt <= (LT_CFG_FLOAT32 ? FMT_F32 : FMT_Q16); fmt++) {
            static const uint32_t leaves[] = {0, 1, 16};
            unsigned li;
            for (li = 0; li < 3; li++) {
                lt_scene_t s;
                built_t bb;
                lt_bvh_desc_t d;
                lt_bvh8_t w, w2;
                wcheck_t c;
                ltt_rng_t r;
                size_t bytes = 0;
                unsigned char *mem;
                double ext = wide_mesh(ki, &s);
                lt_status_t st;
                memset(&c, 0, sizeof c);
                memset(&d, 0, sizeof d);
                d.max_leaf = leaves[li];
                d.min_leaf = leaves[li] / 2u;
                assert_int_equal(build(&bb, &s, fmt, &d), LT_OK);
                assert_int_equal(lt_bvh8_size(&bb.bvh, &bytes), LT_OK);
                mem = malloc(bytes + TAIL);
                assert_non_null(mem);
                ltt_poison(mem, bytes + TAIL);
                /* too small: LT_E_SPACE naming the size, nothing written */
#if LT_CFG_FLOAT32
                st = fmt == FMT_F32 ? lt_bvh8_build_f32(&w2, &bb.bvh, s.tf, mem, bytes - 8u)
                                    : lt_bvh8_build_q16(&w2, &bb.bvh, s.tq, mem, bytes - 8u);
#else
                st = lt_bvh8_build_q16(&w2, &bb.bvh, s.tq, mem, bytes - 8u);
#endif
                assert_int_equal(st, LT_E_SPACE);
                assert_int_equal(w2.bytes, bytes);
                assert_int_equal(ltt_touched(mem, 0, bytes + TAIL), 0);
#if LT_CFG_FLOAT32
                st = fmt == FMT_F32 ? lt_bvh8_build_f32(&w, &bb.bvh, s.tf, mem, bytes)
                                    : lt_bvh8_build_q16(&w, &bb.bvh, s.tq, mem, bytes);
                /* the other path's tree is refused */
                assert_int_equal(fmt == FMT_F32 ? lt_bvh8_build_q16(&w2, &bb.bvh, s.tq, mem, bytes)
                                                : lt_bvh8_build_f32(&w2, &bb.bvh, s.tf, mem, bytes),
                                 LT_E_ARG);
                /* no triangles: refused */
                assert_int_equal(fmt == FMT_F32 ? lt_bvh8_build_f32(&w2, &bb.bvh, NULL, mem, bytes)
                                                : lt_bvh8_build_q16(&w2, &bb.bvh, NULL, mem, bytes),
                                 LT_E_ARG);
#else
                st = lt_bvh8_build_q16(&w, &bb.bvh, s.tq, mem, bytes);
#endif
                assert_int_equal(st, LT_OK);
                assert_int_equal(w.bytes, bytes);
                assert_int_equal(ltt_touched(mem, bytes, bytes + TAIL), 0);
                w_structure(&w, &bb.bvh, &s, fmt, leaves[li] ? leaves[li] : 4u, &c);
                if (fmt == FMT_Q16) {
                    /* span: the largest |plane| of the children in use */
                    uint32_t smax = 0, ni;
                    unsigned kk, a;
                    for (ni = 0; ni < w.nnodes; ni++) {
                        const lt_bvh8_node_q16_t *nd = (const lt_bvh8_node_q16_t *)w.nodes + ni;
                        for (kk = 0; kk < LT_BVH8_WIDTH; kk++)
                            for (a = 0; a < 3 && nd->cnt[kk] != LT_BVH8_EMPTY; a++) {
                                uint32_t l0 = nd->lo[a][kk] < 0 ? 0u - (uint32_t)nd->lo[a][kk] : (uint32_t)nd->lo[a][kk];
                                uint32_t h0 = nd->hi[a][kk] < 0 ? 0u - (uint32_t)nd->hi[a][kk] : (uint32_t)nd->hi[a][kk];
                                smax = l0 > smax ? l0 : smax;
                                smax = h0 > smax ? h0 : smax;
                            }
                    }
                    assert_int_equal(w.span, smax);
                }
                if (ki == 3)
                    assert_int_equal(c.zero_area, (s.ntris + 6u) / 7u);
                ltt_rng_seed(&r, 777 + ki * 3 + li);
                w_rays(&w, &bb.bvh, &s, fmt, &r, ext, 400u / WORK, &c);
                print_message("wide %s %s leaf %u: %lu nodes from %u binary (%.2f children per "
                              "node), %lu leaves from %u binary, %u blocks (%lu zero-area lanes), "
                              "%lu rays (%lu through the clamped node test): closest hit equal on "
                              "%lu, exact ties %lu, differ %lu; any hit equal on %lu of %lu\n",
                              fmt == FMT_Q16 ? "q16" : "f32", wide_names[ki], leaves[li], c.nodes,
                              bb.bvh.nnodes, (double)c.children / (double)c.nodes, c.leaves,
                              bb.bvh.leaves, w.nblocks, c.zero_area, c.rays, c.clamped, c.same,
                              c.ties, c.bad, c.occl - c.occl_bad, c.occl);
                assert_int_equal(c.bad, 0);
                assert_int_equal(c.occl_bad, 0);
                assert_int_equal(c.errs, 0);
                assert_true(c.same > c.rays * 9 / 10);
                if (ki == 4 && fmt == FMT_Q16)
                    assert_true(c.clamped > c.rays / 50 && c.clamped < c.rays);
                if (li == 0) {
                    /* Moller-Trumbore (--isect mt): the wide walk tests the blocks' triangles one
                       by one, zero-area ones included, as the binary walk */
                    wcheck_t cm;
                    memset(&cm, 0, sizeof cm);
                    bb.bvh.isect = LT_ISECT_MT;
#if LT_CFG_FLOAT32
                    st = fmt == FMT_F32 ? lt_bvh8_build_f32(&w, &bb.bvh, s.tf, mem, bytes)
                                        : lt_bvh8_build_q16(&w, &bb.bvh, s.tq, mem, bytes);
#else
                    st = lt_bvh8_build_q16(&w, &bb.bvh, s.tq, mem, bytes);
#endif
                    assert_int_equal(st, LT_OK);
                    assert_int_equal(w.isect, LT_ISECT_MT);
                    w_rays(&w, &bb.bvh, &s, fmt, &r, ext, 200u / WORK, &cm);
                    print_message("  with Moller-Trumbore: %lu rays, closest hit equal on %lu, "
                                  "exact ties %lu, differ %lu; any hit equal on %lu\n",
                                  cm.rays, cm.same, cm.ties, cm.bad, cm.occl - cm.occl_bad);
                    assert_int_equal(cm.bad, 0);
                    assert_int_equal(cm.occl_bad, 0);
                    assert_int_equal(cm.errs, 0);
                    bb.bvh.isect = LT_ISECT_WT;
                }
                if (li == 0 && fmt == FMT_Q16) {
                    /* the s15.16 grid test (LT_ISECT_WT32): the wide walk tests the blocks'
                       triangles one by one through it, as the binary walk */
                    wcheck_t cg;
                    memset(&cg, 0, sizeof cg);
                    bb.bvh.isect = LT_ISECT_WT32_G(lt_wt32_shift_q16(s.tq, s.ntris));
                    assert_int_equal(lt_bvh8_build_q16(&w, &bb.bvh, s.tq, mem, bytes), LT_OK);
                    assert_int_equal(w.isect, bb.bvh.isect);
                    w_rays(&w, &bb.bvh, &s, fmt, &r, ext, 200u / WORK, &cg);
                    print_message("  with the grid test (wt32, 2^%u): %lu rays, closest hit equal "
                                  "on %lu, exact ties %lu, differ %lu; any hit equal on %lu\n",
                                  (unsigned)LT_ISECT_WT32_SHIFT(bb.bvh.isect), cg.rays, cg.same,
                                  cg.ties, cg.bad, cg.occl - cg.occl_bad);
                    assert_int_equal(cg.bad, 0);
                    assert_int_equal(cg.occl_bad, 0);
                    assert_int_equal(cg.errs, 0);
                    bb.bvh.isect = LT_ISECT_WT;
                }
                free(mem);
                unbuild(&bb);
                lt_scene_free(&s);
            }
        }
    {
        /* the s15.16 node test's clamp, aimed: one leaf of three triangles (min_leaf 3) whose box
           spans x in [-2500, 3800], y and z in [-10, 10]; a ray from (-32000, -1000, -2) towards
           (-2000, 0, 0) crosses the near x plane at t ~ 29,516, enters the y slab at ~29,716 and
           meets triangle 0 (x = -2000) at ~30,017; its far x plane lies 35,800 units from the
           origin, beyond int32 in s15.16: without the clamp plane - origin wraps, the far plane's
           t turns negative, the x interval ends at 29,516 and the box (and the hit) is lost */
        lt_scene_t s;
        built_t bb;
        lt_bvh_desc_t d;
        lt_bvh8_t w;
        lt_ray1_q16_t r, rb;
        int32_t iw = -1, ib = -1;
        size_t bytes = 0;
        unsigned char *mem;
        double dir[3] = {30000.0, 1000.0, 2.0}, len;
        int a;
        memset(&d, 0, sizeof d);
        d.min_leaf = 3;
        mesh_alloc(&s, 3);
        set_vert(&s, 0, 0, -2000.0, -10.0, -10.0);
        set_vert(&s, 0, 1, -2000.0, 10.0, -10.0);
        set_vert(&s, 0, 2, -2000.0, 0.0, 10.0);
        set_vert(&s, 1, 0, 3800.0, -10.0, -10.0);
        set_vert(&s, 1, 1, 3800.0, 10.0, -10.0);
        set_vert(&s, 1, 2, 3800.0, 0.0, 10.0);
        set_vert(&s, 2, 0, -2500.0, -10.0, 5.0);
        set_vert(&s, 2, 1, -2500.0, 10.0, 5.0);
        set_vert(&s, 2, 2, -2500.0, 0.0, 10.0);
        mesh_quantise(&s);
        len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
        assert_int_equal(build(&bb, &s, FMT_Q16, &d), LT_OK);
        assert_int_equal(lt_bvh8_size(&bb.bvh, &bytes), LT_OK);
        mem = malloc(bytes);
        assert_non_null(mem);
        assert_int_equal(lt_bvh8_build_q16(&w, &bb.bvh, s.tq, mem, bytes), LT_OK);
        memset(&r, 0, sizeof r);
        r.o[0] = lt_q16_from_double_sat(-32000.0);
        r.o[1] = lt_q16_from_double_sat(-1000.0);
        r.o[2] = lt_q16_from_double_sat(-2.0);
        for (a = 0; a < 3; a++)
            r.d[a] = lt_q30_from_double_sat(dir[a] / len);
        r.tmax = LT_Q16_MAX - 1;
        lt_ray1_q16_setup(&r);
        assert_int_equal(r.par | r.rsat, 0); /* the register form's case */
        rb = r;
        assert_true((uint64_t)w.span + 32000u * 65536u > (uint64_t)INT32_MAX);
        assert_int_equal(lt_bvh8_trace1_q16(&w, s.tq, &r, &iw), LT_OK);
        assert_int_equal(lt_bvh_trace1_q16(&bb.bvh, s.tq, &rb, &ib), LT_OK);
        print_message("wide: far origin (plane - origin beyond int32): wide %d at t %.1f, binary %d "
                      "at t %.1f (want triangle 0 near 30017)\n", iw, r.tmax / 65536.0, ib,
                      rb.tmax / 65536.0);
        assert_int_equal(iw, 0);
        assert_int_equal(ib, 0);
        assert_int_equal(r.tmax, rb.tmax);
        free(mem);
        unbuild(&bb);
        lt_scene_free(&s);
    }
    {
        /* arguments and the empty tree */
        lt_bvh8_t w;
        lt_bvh_t e;
        lt_ray1_q16_t r;
        int32_t id = 5;
        int o = 1;
        size_t bytes = 1;
        memset(&e, 0, sizeof e);
        e.num = LT_BVH_NUM_Q16;
        assert_int_equal(lt_bvh8_size(NULL, &bytes), LT_E_ARG);
        assert_int_equal(lt_bvh8_size(&e, &bytes), LT_OK);
        assert_int_equal(bytes, 0);
        assert_int_equal(lt_bvh8_build_q16(NULL, &e, NULL, NULL, 0), LT_E_ARG);
        assert_int_equal(lt_bvh8_build_q16(&w, &e, NULL, NULL, 0), LT_OK);
        memset(&r, 0, sizeof r);
        r.d[2] = 1 << 30;
        r.tmax = 1000 << 16;
        lt_ray1_q16_setup(&r);
        assert_int_equal(lt_bvh8_trace1_q16(&w, NULL, &r, &id), LT_OK);
        assert_int_equal(id, -1);
        assert_int_equal(lt_bvh8_occluded1_q16(&w, NULL, &r, &o), LT_OK);
        assert_int_equal(o, 0);
        assert_int_equal(lt_bvh8_trace1_q16(NULL, NULL, &r, &id), LT_E_ARG);
        print_message("wide: NULL arguments LT_E_ARG, empty tree: 0 bytes, no hit\n");
    }
}

/* The float32 leaf blocks' lanes whose float edges are zero (lt__wt_tris4_f32, and its SSE form
 * on x86): a triangle 2e-24 across at the origin, whose sheared edge products (~1e-48) underflow
 * to zero in float, among three ordinary ones. A ray through it has eu = ev = ew = 0, det = 0 in
 * float; the scalar test recomputes the edges in double (every sign exact) and hits it at t = 1,
 * so the block must hand that lane to the tail. Rays along z through the tiny triangle, beside it,
 * and through the other three: the wide walk's closest hit and any hit equal the binary walk's,
 * and the tiny triangle is hit. */
static void test_wide_float_edges(void **state)
{
#if LT_CFG_FLOAT32
    static const double tiny = 1e-24;
    static const double at[4][2] = {{0.0, -0.25}, {0.4, 0.1}, {-0.3, -0.2}, {0.05, 0.0}};
    lt_scene_t s;
    built_t bb;
    lt_bvh_desc_t d;
    lt_bvh8_t w;
    size_t bytes = 0;
    unsigned char *mem;
    unsigned i, tiny_hits = 0, other_hits = 0;
    (void)state;
    mesh_alloc(&s, 4);
    set_vert(&s, 0, 0, -tiny, -tiny, 0.0);
    set_vert(&s, 0, 1, tiny, -tiny, 0.0);
    set_vert(&s, 0, 2, 0.0, tiny, 0.0);
    for (i = 1; i < 4; i++) {
        double cx = 3.0 * (double)i, z = 0.5 * (double)i;
        set_vert(&s, i, 0, cx - 1.0, -1.0, z);
        set_vert(&s, i, 1, cx + 1.0, -1.0, z);
        set_vert(&s, i, 2, cx, 1.0, z);
    }
    mesh_quantise(&s);
    memset(&d, 0, sizeof d);
    assert_int_equal(build(&bb, &s, FMT_F32, &d), LT_OK);
    assert_int_equal(lt_bvh8_size(&bb.bvh, &bytes), LT_OK);
    mem = malloc(bytes);
    assert_non_null(mem);
    assert_int_equal(lt_bvh8_build_f32(&w, &bb.bvh, s.tf, mem, bytes), LT_OK);
    assert_int_equal(w.nblocks, 1); /* the four triangles in one block */
    for (i = 0; i < 4 * 4; i++) {
        /* rays 0..3 through the tiny triangle, 4..7 beside it, then the three others */
        unsigned k = i % 4, g = i / 4;
        lt_ray1_f32_t r0, rw, rb;
        int32_t iw = -1, ib = -1;
        int ow = 0, ob = 0;
        memset(&r0, 0, sizeof r0);
        if (g == 0) {
            r0.o[0] = (float)(at[k][0] * tiny);
            r0.o[1] = (float)(at[k][1] * tiny);
        } else if (g == 1) {
            r0.o[0] = (float)((1.5 + at[k][0]) * tiny);
            r0.o[1] = (float)(at[k][1] * tiny);
        } else {
            r0.o[0] = (float)(3.0 * (double)(g - 1) + at[k][0]);
            r0.o[1] = (float)at[k][1];
        }
        r0.o[2] = -1.0f;
        r0.d[2] = 1.0f;
        r0.tmin = 0.0f;
        r0.tmax = 1e30f;
        lt_ray1_f32_setup(&r0);
        rw = r0;
        rb = r0;
        assert_int_equal(lt_bvh8_trace1_f32(&w, s.tf, &rw, &iw), LT_OK);
        assert_int_equal(lt_bvh_trace1_f32(&bb.bvh, s.tf, &rb, &ib), LT_OK);
        if (iw != ib || memcmp(&rw.tmax, &rb.tmax, sizeof rw.tmax) != 0)
            fail_msg("ray %u: wide walk %d t %g, binary walk %d t %g", i, (int)iw,
                     (double)rw.tmax, (int)ib, (double)rb.tmax);
        rw = r0;
        rb = r0;
        assert_int_equal(lt_bvh8_occluded1_f32(&w, s.tf, &rw, &ow), LT_OK);
        assert_int_equal(lt_bvh_occluded1_f32(&bb.bvh, s.tf, &rb, &ob), LT_OK);
        assert_int_equal(ow, ob);
        assert_int_equal(ow, ib >= 0);
        if (g == 0) {
            assert_int_equal(iw, 0);
            tiny_hits++;
        } else if (g == 1) {
            assert_int_equal(iw, -1);
        } else {
            assert_int_equal(iw, (int32_t)(g - 1));
            other_hits++;
        }
    }
    print_message("wide f32 zero float edges: a triangle 2e-24 across (edge products underflow "
                  "in float) hit by %u of 4 rays through it as the binary walk hits it, 4 rays "
                  "beside it miss, the other lanes hit %u of 8; any hit equal\n", tiny_hits,
                  other_hits);
    free(mem);
    unbuild(&bb);
    lt_scene_free(&s);
#else
    (void)state;
    print_message("wide f32 zero float edges: no float32 path in this build\n");
#endif
}

/* One lane of wp_packet: the wide walk's triangle iw against the binary walk's ib, with the same
 * distance (same_t) and, where they differ, iw verified as an exact tie (tie). */
static void wp_lane(wcheck_t *c, int lane, int32_t iw, int32_t ib, int same_t, int tie)
{
    c->rays++;
    if (iw == ib && same_t)
        c->same++;
    else if (iw >= 0 && ib >= 0 && same_t && tie)
        c->ties++;
    else if (c->bad++ < 5)
        print_message("  wide packet lane %d: %d vs binary %d (t %s)\n", lane, iw, ib,
                      same_t ? "equal" : "differs");
}

/* A packet of lanes k through the wide tree (lt_bvh8_trace16 / occluded16) and the binary tree
 * (lt_bvh_trace16 / occluded16): per lane the same closest distance (bits), the same triangle or
 * an exact tie (the other tree's triangle gives the lane that distance on its own), the same
 * occluded lanes. */
static void wp_packet(const lt_bvh8_t *w, const lt_bvh_t *b, const lt_scene_t *s, int fmt,
                      const dray_t *rs, lt_mask16_t k, wcheck_t *c)
{
    lt_hit16_t hw, hb;
    lt_mask16_t ow = 0, ob = 0;
    int i;
#if LT_CFG_FLOAT32
    if (fmt == FMT_F32) {
        lt_ray16_f32_t p0, pw, pb;
        f32_packet(rs, &p0);
        pw = p0;
        pb = p0;
        c->errs += lt_bvh8_trace16_f32(w, s->tf, &pw, k, &hw) != LT_OK;
        c->errs += lt_bvh_trace16_f32(b, s->tf, &pb, k, &hb) != LT_OK;
        for (i = 0; i < LT_LANES; i++) {
            int same_t = memcmp(&pw.tmax.l[i], &pb.tmax.l[i], sizeof(float)) == 0;
            if ((((unsigned)k >> i) & 1u) != 0)
                wp_lane(c, i, hw.id.l[i], hb.id.l[i], same_t,
                        same_t && tie_f32(s, &p0, i, hw.id.l[i], pw.tmax.l[i]));
        }
        pw = p0;
        pb = p0;
        c->errs += lt_bvh8_occluded16_f32(w, s->tf, &pw, k, &ow) != LT_OK;
        c->errs += lt_bvh_occluded16_f32(b, s->tf, &pb, k, &ob) != LT_OK;
    } else
#endif
    {
        lt_ray16_q16_t p0, pw, pb;
        q16_packet(rs, &p0);
        pw = p0;
        pb = p0;
        c->errs += lt_bvh8_trace16_q16(w, s->tq, &pw, k, &hw) != LT_OK;
        c->errs += lt_bvh_trace16_q16(b, s->tq, &pb, k, &hb) != LT_OK;
        for (i = 0; i < LT_LANES; i++) {
            int same_t = pw.tmax.l[i] == pb.tmax.l[i];
            if ((((unsigned)k >> i) & 1u) != 0)
                wp_lane(c, i, hw.id.l[i], hb.id.l[i], same_t,
                        same_t && tie_q16(s, &p0, i, hw.id.l[i], pw.tmax.l[i]));
        }
        pw = p0;
        pb = p0;
        c->errs += lt_bvh8_occluded16_q16(w, s->tq, &pw, k, &ow) != LT_OK;
        c->errs += lt_bvh_occluded16_q16(b, s->tq, &pb, k, &ob) != LT_OK;
    }
    c->occl++;
    if (ow != ob && c->occl_bad++ < 5)
        print_message("  wide packet any-hit 0x%04x vs binary 0x%04x\n", ow, ob);
}

/* 16-ray packets through the wide tree (lt_bvh8_trace16 / occluded16): against the binary packet
 * walk on the meshes of test_wide, both merge bounds, both intersectors, packets of every
 * rand_rays kind (a camera's coherent packets, incoherent ones, axis-parallel lanes, windows,
 * aimed rays, origins beyond int32 for plane - origin), whole and with random lane subsets. */
static void test_wide_packets(void **state)
{
    unsigned ki;
    int fmt;
    (void)state;
    for (ki = 0; ki < 5; ki++)
        for (fmt = FMT_Q16; fmt <= (LT_CFG_FLOAT32 ? FMT_F32 : FMT_Q16); fmt++) {
            static const uint32_t leaves[] = {0, 16};
            unsigned li, mi, isect;
            for (li = 0; li < 2; li++)
                for (mi = 0; mi < 2; mi++)
                    for (isect = LT_ISECT_WT; isect <= LT_ISECT_MT; isect++) {
                        lt_scene_t s;
                        built_t bb;
                        lt_bvh_desc_t d;
                        lt_bvh8_t w;
                        wcheck_t c;
                        ltt_rng_t r;
                        size_t bytes = 0;
                        unsigned char *mem;
                        unsigned pk;
                        uint32_t merge = mi ? LT_BVH8_MERGE : 0u;
                        unsigned cnear = 0;
                        double ext = wide_mesh(ki, &s);
                        memset(&c, 0, sizeof c);
                        memset(&d, 0, sizeof d);
                        d.max_leaf = leaves[li];
                        d.min_leaf = leaves[li] / 2u;
                        assert_int_equal(build(&bb, &s, fmt, &d), LT_OK);
                        bb.bvh.isect = isect;
                        assert_int_equal(lt_bvh8_size_merge(&bb.bvh, merge, &bytes), LT_OK);
                        mem = malloc(bytes + 8u);
                        assert_non_null(mem);
#if LT_CFG_FLOAT32
                        assert_int_equal(fmt == FMT_F32
                                             ? lt_bvh8_build_merge_f32(&w, &bb.bvh, s.tf, mem, bytes, merge)
                                             : lt_bvh8_build_merge_q16(&w, &bb.bvh, s.tq, mem, bytes, merge),
                                         LT_OK);
#else
                        assert_int_equal(lt_bvh8_build_merge_q16(&w, &bb.bvh, s.tq, mem, bytes, merge),
                                         LT_OK);
#endif
                        assert_int_equal(w.merge, merge);
                        assert_int_equal(w.isect, isect);
                        ltt_rng_seed(&r, 555 + ki * 7 + li * 3 + mi);
                        for (pk = 0; pk < 300u / WORK; pk++) {
                            dray_t rs[LT_LANES];
                            lt_mask16_t k = pk % 3u == 2u ? (lt_mask16_t)ltt_rng_below(&r, 0x10000u)
                                                          : LT_MASK_ALL;
                            rand_rays(&r, (int)(pk % RAY_KINDS), ext, &s, rs, LT_LANES);
                            if (pk % 11u == 10u) {
                                /* near-axis lanes: a direction component of 2^-17..2^-20 (a
                                   saturated s15.16 reciprocal, rsat; float32's huge one), the
                                   frustum's unbounded axis; and one zero component (par) */
                                unsigned l;
                                for (l = 0; l < LT_LANES; l += 2) {
                                    rs[l].d[l % 3u] = ldexp(1.0, -17 - (int)(l % 4u)) *
                                                      (l % 3u == 1u ? -1.0 : 1.0);
                                    rs[l].d[(l + 1u) % 3u] = l == 4u ? 0.0 : rs[l].d[(l + 1u) % 3u];
                                    normalize(rs[l].d);
                                }
                                cnear++;
                            }
                            wp_packet(&w, &bb.bvh, &s, fmt, rs, k, &c);
                        }
                        if (li == 0 && isect == LT_ISECT_WT)
                            print_message("wide packets %s %s leaf %u merge %u: %lu lanes (%u "
                                          "packets with near-axis lanes): closest hit equal on %lu, "
                                          "exact ties %lu, differ %lu; any hit equal on %lu of %lu "
                                          "packets\n",
                                          fmt == FMT_Q16 ? "q16" : "f32", wide_names[ki], leaves[li],
                                          merge, c.rays, cnear, c.same, c.ties, c.bad,
                                          c.occl - c.occl_bad, c.occl);
                        assert_int_equal(c.bad, 0);
                        assert_int_equal(c.occl_bad, 0);
                        assert_int_equal(c.errs, 0);
                        assert_true(c.same > c.rays * 9 / 10);
                        free(mem);
                        unbuild(&bb);
                        lt_scene_free(&s);
                    }
        }
    {
        /* arguments: a bound past LT_BVH8_MERGE, NULLs, the other path's tree; an empty mask */
        lt_bvh_t e;
        lt_bvh8_t w;
        lt_ray16_q16_t p;
        lt_hit16_t h;
        lt_mask16_t o = 1;
        size_t bytes = 1;
        memset(&e, 0, sizeof e);
        memset(&p, 0, sizeof p);
        e.num = LT_BVH_NUM_Q16;
        assert_int_equal(lt_bvh8_size_merge(&e, LT_BVH8_MERGE + 1u, &bytes), LT_E_ARG);
        assert_int_equal(lt_bvh8_build_merge_q16(&w, &e, NULL, NULL, 0, LT_BVH8_MERGE + 1u),
                         LT_E_ARG);
        assert_int_equal(lt_bvh8_build_merge_q16(&w, &e, NULL, NULL, 0, 0), LT_OK);
        assert_int_equal(lt_bvh8_trace16_q16(NULL, NULL, &p, LT_MASK_ALL, &h), LT_E_ARG);
        assert_int_equal(lt_bvh8_trace16_q16(&w, NULL, &p, LT_MASK_ALL, &h), LT_OK);
        assert_int_equal(h.id.l[0], -1);
        assert_int_equal(lt_bvh8_occluded16_q16(&w, NULL, &p, LT_MASK_ALL, &o), LT_OK);
        assert_int_equal(o, 0);
        w.num = LT_BVH_NUM_F32;
        assert_int_equal(lt_bvh8_trace16_q16(&w, NULL, &p, LT_MASK_ALL, &h), LT_E_ARG);
        print_message("wide packets: bad merge bound, NULL and the other path's tree LT_E_ARG; "
                      "empty tree: no hit\n");
    }
}

static int shared_missing(const char *path)
{
    const char *ci = getenv("CI");
    if (ci != NULL && strcmp(ci, "true") == 0) {
        printf("  FAIL %s missing under CI=true\n", path);
        return 1;
    }
    ltt_report("SKIP %s: not found (a fresh clone has no ../shared)\n", path);
    return 0;
}

/* Build both paths, check the trees, trace a res x res view with packets and single rays, compare
 * with brute force (for up to `brute` packets) and with the double reference; print it all. */
static int real_mesh(const char *path, uint32_t res, uint32_t brute)
{
    lt_mesh_t m;
    lt_scene_t s;
    lt_camera_t cam;
    lt_diag_t diag;
    int fmt, bad = 0;
    int32_t *ref;
    uint32_t x, y;
    memset(&m, 0, sizeof m);
    if (lt_mesh_load(path, &m, &diag) != 0)
        return shared_missing(path);
    assert_int_equal(lt_scene_prepare(&m, &s, &diag), 0);
    lt_camera_default(&s, res, res, &cam);
    ref = malloc((size_t)res * res * sizeof *ref);
    assert_non_null(ref);
    for (y = 0; y < res; y++) /* the double-precision reference, once per pixel */
        for (x = 0; x < res; x++) {
            double d[3], t;
            lt_camera_dir(&cam, x, y, d);
            ref[y * res + x] = lt_ref_trace(&s, cam.eye, d, &t);
        }
    for (fmt = FMT_Q16; fmt <= (LT_CFG_FLOAT32 ? FMT_F32 : FMT_Q16); fmt++) {
        built_t bb;
        tree_check_t tc;
        cmp_t c;
        lt_bvh_stats_t sp, s1, qs, q1s, es;
        lt_bvh_t bp, b1;
        qbuilt_t qb;
        qcheck_t qc;
        unsigned long qrays = 0, qties = 0, qbad = 0;
        int rep;
        ltt_rng_t r;
        uint32_t tx, ty, pk = 0, npk = (res / 4u) * (res / 4u);
        unsigned long same = 0, pix = 0, both = 0;
        double med;
        memset(&tc, 0, sizeof tc);
        memset(&c, 0, sizeof c);
        memset(&sp, 0, sizeof sp);
        memset(&s1, 0, sizeof s1);
        memset(&qs, 0, sizeof qs);
        memset(&q1s, 0, sizeof q1s);
        memset(&es, 0, sizeof es);
        memset(&qb, 0, sizeof qb);
        memset(&qc, 0, sizeof qc);
        ltt_rng_seed(&r, 1);
        assert_int_equal(build(&bb, &s, fmt, NULL), LT_OK);
        check_tree(&bb.bvh, &s, fmt, NULL, &tc);
        med = median_sah(&s, fmt, 4);
        for (rep = 1; rep < (WORK > 1u ? 1 : 5); rep++) { /* build time: fastest of 5 (shared host) */
            lt_bvh_t again;
            double t0 = now_ms(), dt;
            lt_status_t st;
            if (fmt == FMT_Q16)
                st = lt_bvh_build_q16(&again, NULL, s.tq, s.ntris, bb.arena, bb.size);
#if LT_CFG_FLOAT32
            else
                st = lt_bvh_build_f32(&again, NULL, s.tf, s.ntris, bb.arena, bb.size);
#endif
            dt = now_ms() - t0;
            assert_int_equal(st, LT_OK);
            assert_int_equal(again.nnodes, bb.bvh.nnodes); /* deterministic */
            bb.ms = dt < bb.ms ? dt : bb.ms;
        }
        ltt_report("%s (%u triangles, %s): build %.2f ms CPU (best of 5), arena %zu bytes (%.1f/tri), "
                   "tree keeps "
                   "%zu bytes (%u nodes x 32 + idx), %u leaves, depth %u; SAH cost %.2f (object "
                   "median %.2f); %lu tree violations\n",
                   path, s.ntris, fmt == FMT_Q16 ? "q16" : "f32", bb.ms, bb.size,
                   (double)bb.size / (double)s.ntris, bb.bvh.bytes, bb.bvh.nnodes, bb.bvh.leaves,
                   bb.bvh.depth, tc.sah, med, tc.bad);
        bad += (int)tc.bad;
        bp = bb.bvh;
        b1 = bb.bvh;
        bp.stats = &sp;
        b1.stats = &s1;
        if (fmt == FMT_Q16) {
            qbuild(&qb, &bb.bvh);
            q_check(&qb, &bb.bvh, &qc);
        }
        for (ty = 0; ty < res; ty += 4)
            for (tx = 0; tx < res; tx += 4, pk++) {
                lt_hit16_t h;
                lt_mask16_t k;
                int i;
                if (fmt == FMT_Q16) {
                    lt_ray16_q16_t p, p0;
                    k = lt_camera_packet_q16(&cam, tx, ty, &p);
                    p0 = p;
                    q_cmp_packet(&qb.q, &bb.bvh, &s, &p0, k, &qs, &q1s, &es, &qrays, &qties, &qbad);
                    if (lt_bvh_trace16_q16(&bp, s.tq, &p, k, &h) != LT_OK)
                        bad++;
                    for (i = 0; i < LT_LANES; i++) {
                        lt_ray1_q16_t r1;
                        int32_t id1;
                        if (!LTT_ON(k, i))
                            continue;
                        q16_single(&p0, i, &r1);
                        if (lt_bvh_trace1_q16(&b1, s.tq, &r1, &id1) != LT_OK)
                            bad++;
                        if (r1.tmax != p.tmax.l[i] || id1 != h.id.l[i])
                            both++;
                    }
                }
#if LT_CFG_FLOAT32
                else {
                    lt_ray16_f32_t p, p0;
                    k = lt_camera_packet_f32(&cam, tx, ty, &p);
                    p0 = p;
                    if (lt_bvh_trace16_f32(&bp, s.tf, &p, k, &h) != LT_OK)
                        bad++;
                    for (i = 0; i < LT_LANES; i++) {
                        lt_ray1_f32_t r1;
                        int32_t id1;
                        if (!LTT_ON(k, i))
                            continue;
                        f32_single(&p0, i, &r1);
                        if (lt_bvh_trace1_f32(&b1, s.tf, &r1, &id1) != LT_OK)
                            bad++;
                        if (r1.tmax != p.tmax.l[i] || id1 != h.id.l[i])
                            both++;
                    }
                }
#endif
                for (i = 0; i < LT_LANES; i++) {
                    if (!LTT_ON(k, i))
                        continue;
                    pix++;
                    same += ref[(ty + (uint32_t)(i / 4)) * res + tx + (uint32_t)(i % 4)] == h.id.l[i];
                }
                /* brute force on `brute` packets spread over the image (37 is prime to npk) */
                if ((pk * 37u) % npk < brute) {
                    dray_t rs[LT_LANES];
                    for (i = 0; i < LT_LANES; i++) {
                        uint32_t px = tx + (uint32_t)(i % 4), py = ty + (uint32_t)(i / 4);
                        int a;
                        lt_camera_dir(&cam, px, py, rs[i].d);
                        for (a = 0; a < 3; a++)
                            rs[i].o[a] = cam.eye[a];
                        rs[i].tmin = 0.0;
                        rs[i].tmax = fmt == FMT_Q16 ? 32767.0 : 3.0e38;
                    }
                    cmp_packet(fmt, &bb.bvh, &s, rs, LT_MASK_ALL, &r, &c);
                }
            }
        ltt_report("  %ux%u view: %.3f%% of %lu pixels hit the same triangle as the double "
                   "reference; packet and single ray disagree on %lu pixels\n",
                   res, res, 100.0 * (double)same / (double)pix, pix, both);
        ltt_report("  nodes visited: %.1f per packet (lane utilisation %.1f%%) = %.2f per ray, vs "
                   "%.1f per single ray; box tests per ray: packet %.2f, single %.1f; triangle "
                   "tests per ray: packet lanes %.1f (%.2f packet tests per ray), single %.1f\n",
                   (double)sp.nodes / (double)sp.calls,
                   100.0 * (double)sp.node_lanes / (16.0 * (double)sp.nodes),
                   (double)sp.nodes / (double)sp.rays, (double)s1.nodes / (double)s1.rays,
                   (double)sp.boxes / (double)sp.rays, (double)s1.boxes / (double)s1.rays,
                   (double)sp.tri_lanes / (double)sp.rays, (double)sp.tris / (double)sp.rays,
                   (double)s1.tris / (double)s1.rays);
        if (fmt == FMT_Q16) {
            ltt_report("  quantised 16-byte nodes: %zu B of nodes (32-byte: %zu B), SAH +%.3f%%, max "
                       "face error %.2e of the parent extent, %lu boxes not containing the exact "
                       "one; traces = 32-byte tree on %lu rays (%lu exact ties, %lu wrong); nodes "
                       "per packet %.2f vs %.2f, per single ray %.2f\n",
                       qb.q.bytes, (size_t)bb.bvh.nnodes * 32u,
                       100.0 * (qc.sah_q / qc.sah_exact - 1.0), qc.max_face, qc.bad, qrays, qties,
                       qbad, (double)qs.nodes / (double)qs.calls,
                       (double)es.nodes / (double)es.calls, (double)q1s.nodes / (double)q1s.rays);
            bad += (int)(qc.bad + qbad);
            free(qb.mem);
        }
        bad += cmp_report("  brute-force subset", &c);
        bad += (int)both;
        bad += !(100.0 * (double)same / (double)pix >= 99.0);
        unbuild(&bb);
    }
    free(ref);
    lt_scene_free(&s);
    lt_mesh_free(&m);
    return bad;
}

static void test_real_meshes(void **state)
{
    int bad = 0;
    (void)state;
    if (WORK > 1u)
        ltt_report("(ASan build: views and brute-force subsets reduced %ux)\n", WORK);
    bad += real_mesh("scenes/teapot.obj", WORK > 1u ? 32u : 64u, 1000u / WORK / WORK);
    bad += real_mesh("../shared/scenes/bunny.obj", WORK > 1u ? 16u : 64u, 1000u / WORK / WORK / 2u);
    bad += real_mesh("../shared/scenes/dragon_res3.obj", WORK > 1u ? 8u : 32u, 8u / WORK);
    assert_int_equal(bad, 0);
}

/* ---- modelled cycles (sim build) ------------------------------------------------------------------ */

#if LT_COST_MODE == LT_COST_SIM
enum { M_CHUNK_Q, M_BVH16_Q, M_BVH1_Q, M_BVHQ16_Q, M_BVHQ1_Q, M_CHUNK_F, M_BVH16_F, M_BVH1_F, M_N };
static const char *const m_names[M_N] = {"chunks16 q16", "bvh16 q16", "bvh1 q16", "bvhq16 q16",
                                         "bvhq1 q16", "chunks16 f32", "bvh16 f32", "bvh1 f32"};

/* Cycles per ray of one method over a res x res view (traversal only: rays are made outside). */
static double sim_method(int meth, const lt_scene_t *s, const lt_camera_t *cam, uint32_t res,
                         const lt_bvh_t *bq, const lt_bvh_t *bf, const lt_bvhq_t *qq,
                         const lt_aabb_q16_t *cq, const lt_aabb_f32_t *cf, uint64_t *hits)
{
    uint32_t tx, ty;
    uint64_t cyc = 0, rays = 0;
    lt_sim_reset();
    for (ty = 0; ty < res; ty += 4)
        for (tx = 0; tx < res; tx += 4) {
            lt_ray16_q16_t p;
            lt_ray16_f32_t pf;
            lt_hit16_t h;
            lt_mask16_t k;
            uint64_t c0;
            int i;
            if (meth < M_CHUNK_F)
                k = lt_camera_packet_q16(cam, tx, ty, &p);
            else
                k = lt_camera_packet_f32(cam, tx, ty, &pf);
            rays += lt__popcount32(k);
            c0 = lt_sim_cycles_total();
            switch (meth) {
            case M_CHUNK_Q: (void)lt_chunks_trace16_q16(s->tq, s->ntris, cq, LT_ISECT_WT, &p, k, &h); break;
            case M_BVH16_Q: (void)lt_bvh_trace16_q16(bq, s->tq, &p, k, &h); break;
            case M_BVHQ16_Q: (void)lt_bvhq_trace16_q16(qq, s->tq, &p, k, &h); break;
            case M_CHUNK_F: (void)lt_chunks_trace16_f32(s->tf, s->ntris, cf, LT_ISECT_WT, &pf, k, &h); break;
            case M_BVH16_F: (void)lt_bvh_trace16_f32(bf, s->tf, &pf, k, &h); break;
            default: /* single rays: setup is part of the ray, as the packet setup is not */
                for (i = 0; i < LT_LANES; i++) {
                    int32_t id;
                    if (!LTT_ON(k, i))
                        continue;
                    if (meth == M_BVH1_F) {
                        lt_ray1_f32_t r1;
                        f32_single(&pf, i, &r1);
                        (void)lt_bvh_trace1_f32(bf, s->tf, &r1, &id);
                    } else {
                        lt_ray1_q16_t r1;
                        q16_single(&p, i, &r1);
                        if (meth == M_BVH1_Q)
                            (void)lt_bvh_trace1_q16(bq, s->tq, &r1, &id);
                        else
                            (void)lt_bvhq_trace1_q16(qq, s->tq, &r1, &id);
                    }
                    h.id.l[i] = id;
                }
                break;
            }
            cyc += lt_sim_cycles_total() - c0;
            for (i = 0; i < LT_LANES; i++)
                *hits += LTT_ON(k, i) && h.id.l[i] >= 0;
        }
    return (double)cyc / (double)rays;
}
#endif

static void test_sim_cycles(void **state)
{
#if LT_COST_MODE != LT_COST_SIM
    (void)state;
    ltt_report("modelled cycles: printed by the sim build (build/sim/test_bvh) only\n");
#else
    static const char *const meshes[2] = {"scenes/teapot.obj", "../shared/scenes/bunny.obj"};
    static const char *const machines[2] = {"lrb16", "mcu-m4"};
    unsigned mi, ma;
    int bad = 0;
    (void)state;
    for (mi = 0; mi < 2; mi++) {
        lt_mesh_t m;
        lt_scene_t s;
        lt_camera_t cam;
        built_t bq, bf;
        qbuilt_t qq;
        lt_aabb_q16_t *cq;
        lt_aabb_f32_t *cf;
        lt_diag_t diag;
        const uint32_t res = 64;
        memset(&m, 0, sizeof m);
        if (lt_mesh_load(meshes[mi], &m, &diag) != 0) {
            bad += shared_missing(meshes[mi]);
            continue;
        }
        assert_int_equal(lt_scene_prepare(&m, &s, &diag), 0);
        lt_camera_default(&s, res, res, &cam);
        assert_int_equal(build(&bq, &s, FMT_Q16, NULL), LT_OK);
        assert_int_equal(build(&bf, &s, FMT_F32, NULL), LT_OK);
        qbuild(&qq, &bq.bvh);
        cq = malloc(LT_CHUNK_COUNT(s.ntris) * sizeof *cq);
        cf = malloc(LT_CHUNK_COUNT(s.ntris) * sizeof *cf);
        assert_non_null(cq);
        assert_non_null(cf);
        assert_int_equal(lt_chunks_build_q16(s.tq, s.ntris, cq), LT_OK);
        assert_int_equal(lt_chunks_build_f32(s.tf, s.ntris, cf), LT_OK);
        for (ma = 0; ma < 2; ma++) {
            double cpr[M_N];
            uint64_t hits[M_N];
            int meth;
            assert_int_equal(lt_sim_init(lt_sim_machine_find(machines[ma]), NULL, NULL, &diag), 0);
            /* fixed simulated addresses: cache results independent of the host allocator */
            (void)lt_sim_region(s.tq, s.ntris * sizeof *s.tq, 0x10000000u);
            (void)lt_sim_region(s.tf, s.ntris * sizeof *s.tf, 0x20000000u);
            (void)lt_sim_region(bq.arena, bq.size, 0x30000000u);
            (void)lt_sim_region(bf.arena, bf.size, 0x40000000u);
            (void)lt_sim_region(qq.mem, qq.size, 0x50000000u);
            (void)lt_sim_region(cq, LT_CHUNK_COUNT(s.ntris) * sizeof *cq, 0x60000000u);
            (void)lt_sim_region(cf, LT_CHUNK_COUNT(s.ntris) * sizeof *cf, 0x70000000u);
            for (meth = 0; meth < M_N; meth++) {
                hits[meth] = 0;
                cpr[meth] = sim_method(meth, &s, &cam, res, &bq.bvh, &bf.bvh, &qq.q, cq, cf,
                                       &hits[meth]);
            }
            ltt_report("modelled cycles per ray, %s %ux%u on %s:", meshes[mi], res, res,
                       machines[ma]);
            for (meth = 0; meth < M_N; meth++)
                ltt_report(" %s %.0f%s", m_names[meth], cpr[meth], meth + 1 < M_N ? "," : "\n");
            ltt_report("  bvh16 q16 is %.1fx faster than the chunk scene, %.2fx the single-ray "
                       "path; quantised nodes cost %+.1f%% (packet)\n",
                       cpr[M_CHUNK_Q] / cpr[M_BVH16_Q], cpr[M_BVH1_Q] / cpr[M_BVH16_Q],
                       100.0 * (cpr[M_BVHQ16_Q] / cpr[M_BVH16_Q] - 1.0));
            for (meth = 1; meth < M_N; meth++) /* every method hits the same pixels */
                bad += hits[meth] != hits[meth < M_CHUNK_F ? M_CHUNK_Q : M_CHUNK_F];
            lt_sim_shutdown();
        }
        free(cq);
        free(cf);
        free(qq.mem);
        unbuild(&bq);
        unbuild(&bf);
        lt_scene_free(&s);
        lt_mesh_free(&m);
    }
    assert_int_equal(bad, 0);
#endif
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_size_and_args),
        cmocka_unit_test(test_structure),
        cmocka_unit_test(test_sah_vs_median),
        cmocka_unit_test(test_trace_random),
        cmocka_unit_test(test_boundaries),
        cmocka_unit_test(test_empty_single_degenerate),
        cmocka_unit_test(test_depth_adversarial),
        cmocka_unit_test(test_stack_overflow),
        cmocka_unit_test(test_quantised),
        cmocka_unit_test(test_wide),
        cmocka_unit_test(test_wide_float_edges),
        cmocka_unit_test(test_wide_packets),
        cmocka_unit_test(test_real_meshes),
        cmocka_unit_test(test_sim_cycles),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
