/* lt_vec.c - cross-target test vectors (see lt_vec.h). Freestanding C99: no libc, no float in the
 * fixed-point groups; the float32 groups exist with LT_CFG_FLOAT32 and hash IEEE bit patterns.
 */
#include "lt_vec.h"
#include "lt/lt.h"

#define N_RANDOM 600

static uint32_t rng_state;

static uint32_t rnd(void)
{
    uint32_t x = rng_state;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    rng_state = x;
    return x;
}

static const int32_t extremes[] = {0, 1, -1, 2, -2, 0x7FFF, 0x8000, -0x8000, 0xFFFF, 0x10000,
                                   -0x10000, 0x10001, 0x7FFFFFFF, (int32_t)0x80000000,
                                   0x7FFFFFFE, -0x7FFFFFFF, 0x40000000, -0x40000000, 0x00018000,
                                   -0x00018000};
#define N_EXT ((int)(sizeof extremes / sizeof extremes[0]))

/* input i of a stream: first the extremes, then random values of mixed magnitude */
static int32_t input(int i)
{
    uint32_t r;
    if (i < N_EXT)
        return extremes[i];
    r = rnd();
    r >>= r & 31u;
    /* negate in unsigned arithmetic: -INT32_MIN would overflow */
    return (int32_t)((rng_state & 0x40u) ? 0u - r : r);
}

typedef struct hash {
    uint32_t h, n;
} hash_t;

static void h_init(hash_t *h)
{
    h->h = 2166136261u;
    h->n = 0;
}

static void h_u32(hash_t *h, uint32_t v)
{
    int i;
    for (i = 0; i < 4; i++) {
        h->h ^= (v >> (8 * i)) & 0xFFu;
        h->h *= 16777619u;
    }
}

static void h_case(hash_t *h, uint32_t v)
{
    h_u32(h, v);
    h->n++;
}

static char *put_u32(char *p, uint32_t v)
{
    char t[10];
    int n = 0;
    do {
        t[n++] = (char)('0' + v % 10u);
        v /= 10u;
    } while (v != 0);
    while (n > 0)
        *p++ = t[--n];
    return p;
}

static void emit(void (*put)(const char *), const char *name, const hash_t *h)
{
    char line[96], *p = line;
    const char *s = name;
    int i;
    while (*s != '\0')
        *p++ = *s++;
    while (p < line + 22)
        *p++ = ' ';
    p = put_u32(p, h->n);
    *p++ = ' ';
    *p++ = 'c';
    *p++ = 'a';
    *p++ = 's';
    *p++ = 'e';
    *p++ = 's';
    *p++ = ' ';
    *p++ = '0';
    *p++ = 'x';
    for (i = 7; i >= 0; i--)
        *p++ = "0123456789abcdef"[(h->h >> (4 * i)) & 0xFu];
    *p++ = '\n';
    *p = '\0';
    put(line);
}

typedef int32_t (*bin_fn)(int32_t, int32_t);
typedef int32_t (*un_fn)(int32_t);

static int32_t f_add_sat(int32_t a, int32_t b) { return lt_q16_add_sat(a, b); }
static int32_t f_sub_sat(int32_t a, int32_t b) { return lt_q16_sub_sat(a, b); }
static int32_t f_add_wrap(int32_t a, int32_t b) { return lt_q16_add_wrap(a, b); }
static int32_t f_sub_wrap(int32_t a, int32_t b) { return lt_q16_sub_wrap(a, b); }
static int32_t f_mul_sat(int32_t a, int32_t b) { return lt_q16_mul_sat(a, b); }
static int32_t f_mul_rd(int32_t a, int32_t b) { return lt_q16_mul_sat_rd(a, b); }
static int32_t f_mul_q30(int32_t a, int32_t b) { return lt_q16_mul_q30_sat(a, b); }
static int32_t f_div_sat(int32_t a, int32_t b) { return lt_q16_div_sat(a, b); }
static int32_t f_q30_mul(int32_t a, int32_t b) { return lt_q30_mul_sat(a, b); }
static int32_t f_minmax(int32_t a, int32_t b)
{
    /* results are mixed in unsigned arithmetic: signed overflow would be undefined */
    return (int32_t)((uint32_t)lt_q16_min(a, b) ^ ((uint32_t)lt_q16_max(a, b) * 3u) ^
                     (uint32_t)lt_q16_clamp(a, -0x30000, b | 1));
}
static int32_t f_h8(int32_t a, int32_t b)
{
    lt_h8_t x = lt_h8_from_q16_sat(a), y = lt_h8_from_q16_sat(b);
    return (int32_t)((uint32_t)lt_h8_add_sat(x, y) * 65536u + (uint32_t)lt_h8_mul_sat(x, y) +
                     (uint32_t)lt_h8_sub_sat(x, y) * 7u + (uint32_t)lt_q16_from_h8(x));
}
static int32_t f_recip(int32_t a) { return lt_q16_recip_sat(a); }
static int32_t f_sqrt(int32_t a) { return lt_q16_sqrt(a); }
static int32_t f_rsqrt(int32_t a) { return lt_q16_rsqrt_sat(a); }
static int32_t f_absneg(int32_t a)
{
    return (int32_t)((uint32_t)lt_q16_abs_sat(a) ^ ((uint32_t)lt_q16_neg_sat(a) * 5u));
}
static int32_t f_conv(int32_t a)
{
    return lt_q30_from_q16_sat(a) ^ lt_q16_from_q30(a) ^ (int32_t)lt_h14_from_q30_sat(a) ^
           lt_q30_from_h14((lt_h14_t)a);
}

static void run_bin(void (*put)(const char *), const char *name, bin_fn f, uint32_t seed)
{
    hash_t h;
    int i, j;
    h_init(&h);
    rng_state = seed;
    for (i = 0; i < N_EXT; i++)
        for (j = 0; j < N_EXT; j++)
            h_case(&h, (uint32_t)f(extremes[i], extremes[j]));
    for (i = 0; i < N_RANDOM; i++) {
        int32_t a = input(N_EXT + i), b = input(N_EXT + i);
        h_case(&h, (uint32_t)f(a, b));
    }
    emit(put, name, &h);
}

static void run_un(void (*put)(const char *), const char *name, un_fn f, uint32_t seed)
{
    hash_t h;
    int i;
    h_init(&h);
    rng_state = seed;
    for (i = 0; i < N_EXT + N_RANDOM; i++)
        h_case(&h, (uint32_t)f(input(i)));
    emit(put, name, &h);
}

static void run_vec3(void (*put)(const char *))
{
    hash_t h;
    int i, j;
    h_init(&h);
    rng_state = 0x1234567u;
    for (i = 0; i < N_RANDOM; i++) {
        lt_q16_t a[3], b[3], c[3];
        lt_q30_t u[3] = {0, 0, 0};
        for (j = 0; j < 3; j++) {
            a[j] = input(i < N_EXT ? i : N_EXT + i);
            uint32_t r1 = rnd(), r2 = rnd(); /* two statements: argument order is unspecified */
            b[j] = (int32_t)(r1 >> (r2 & 15u)) - 0x7FFF;
        }
        lt_q16_cross3_sat(a, b, c);
        h_case(&h, (uint32_t)lt_q16_dot3_sat(a, b));
        h_case(&h, (uint32_t)c[0] ^ ((uint32_t)c[1] * 3u) ^ ((uint32_t)c[2] * 7u));
        h_case(&h, (uint32_t)lt_q16_normalize3(a, u));
        h_case(&h, (uint32_t)u[0] ^ ((uint32_t)u[1] * 3u) ^ ((uint32_t)u[2] * 7u));
    }
    emit(put, "q16_vec3", &h);
}

static lt_mask16_t rmask(int i)
{
    static const lt_mask16_t fixed[] = {0, 0xFFFF, 1, 0x8000, 0x5555, 0xAAAA};
    return i < 6 ? fixed[i] : (lt_mask16_t)rnd();
}

static void h_vq16(hash_t *h, lt_vq16_t v)
{
    int i;
    for (i = 0; i < LT_LANES; i++)
        h_u32(h, (uint32_t)v.l[i]);
    h->n++;
}

static void run_lanes(void (*put)(const char *))
{
    hash_t h;
    int i, j;
    static int32_t mem[LT_LANES];
    h_init(&h);
    rng_state = 0xC0FFEEu;
    for (i = 0; i < 200; i++) {
        lt_vq16_t a, b, s;
        lt_vq30_t q;
        lt_vi32_t idx;
        lt_mask16_t k = rmask(i), m;
        for (j = 0; j < LT_LANES; j++) {
            a.l[j] = input(N_EXT + i);
            b.l[j] = input(j < N_EXT ? j : N_EXT + j);
            s.l[j] = (int32_t)rnd();
            q.l[j] = (int32_t)rnd();
            idx.l[j] = (int32_t)(rnd() & 15u);
            mem[j] = (int32_t)rnd();
        }
        h_vq16(&h, lt_vq16_add_sat_m(s, k, a, b));
        h_vq16(&h, lt_vq16_sub_sat_z(k, a, b));
        h_vq16(&h, lt_vq16_mul_sat_m(s, k, a, b));
        h_vq16(&h, lt_vq16_div_sat_z(k, a, b));
        h_vq16(&h, lt_vq16_recip_sat_m(s, k, a));
        h_vq16(&h, lt_vq16_min(a, b));
        h_vq16(&h, lt_vq16_max_m(s, k, a, b));
        h_vq16(&h, lt_vq16_abs_sat_z(k, a));
        h_vq16(&h, lt_vq16_mul_q30_sat(a, q));
        h_vq16(&h, lt_vq16_from_q30(q));
        h_vq16(&h, lt_vq16_gather_m(s, k, mem, idx));
        h_vq16(&h, lt_vq16_from_h8(lt_vh8_mul_sat(lt_vh8_from_q16_sat(a), lt_vh8_from_q16_sat(b))));
        {
            lt_vql_t w = lt_vql_sub_wrap(lt_vql_mul(lt_vi32_from_q16(a), lt_vi32_from_q30(q)),
                                         lt_vql_mul(lt_vi32_from_q16(b), lt_vi32_from_q16(s)));
            lt_vi32_t r = lt_vql_round_sat(w, 16);
            for (j = 0; j < LT_LANES; j++)
                h_u32(&h, (uint32_t)r.l[j]);
        }
        m = lt_vq16_cmplt_m(k, a, b);
        h_case(&h, (uint32_t)m | ((uint32_t)lt_vq16_cmpge(a, b) << 16));
        h_case(&h, (uint32_t)lt_vq16_hmin(k, a, LT_Q16_MAX) ^ (uint32_t)lt_vq16_hmax(k, b, LT_Q16_MIN));
        h_case(&h, lt_mask16_popcount(k) * 256u + lt_mask16_first(k));
    }
    emit(put, "lanes", &h);
}

/* Random rays from a box corner region towards random boxes; origin/box coordinates within
 * +-64 units, directions normalised in fixed point. */
static void rand_ray_q16(lt_ray16_q16_t *r)
{
    int i;
    for (i = 0; i < LT_LANES; i++) {
        lt_q16_t o[3], d[3];
        lt_q30_t u[3];
        int a;
        for (a = 0; a < 3; a++) {
            o[a] = (int32_t)(rnd() & 0x7FFFFFu) - 0x400000;
            d[a] = (int32_t)(rnd() & 0x1FFFFu) - 0x10000;
        }
        /* one lane in four gets an axis-parallel direction */
        if ((i & 3) == 0)
            d[rnd() % 3u] = 0;
        if ((i & 3) == 0)
            d[(rnd() % 3u)] = 0;
        if (lt_q16_normalize3(d, u) != LT_OK) {
            u[0] = LT_Q30_ONE;
            u[1] = u[2] = 0;
        }
        r->ox.l[i] = o[0];
        r->oy.l[i] = o[1];
        r->oz.l[i] = o[2];
        r->dx.l[i] = u[0];
        r->dy.l[i] = u[1];
        r->dz.l[i] = u[2];
        r->tmin.l[i] = 0;
        r->tmax.l[i] = 0x7FFFFFF;
    }
    lt_ray16_q16_setup(r);
}

#define N_MESH 48
static lt_tri_q16_t mesh_q[N_MESH];
static lt_aabb_q16_t boxes_q[LT_CHUNK_COUNT(N_MESH)];

static void run_kernels_q16(void (*put)(const char *))
{
    hash_t h;
    int i, j;
    static lt_ray16_q16_t r;
    h_init(&h);
    rng_state = 0xBADC0DEu;
    for (i = 0; i < 100; i++) {
        lt_aabb_q16_t b;
        lt_vq16_t tn = lt_vq16_set1(0);
        lt_mask16_t k = rmask(i);
        int a;
        rand_ray_q16(&r);
        for (a = 0; a < 3; a++) {
            int32_t c = (int32_t)(rnd() & 0x3FFFFFu) - 0x200000;
            int32_t w = (int32_t)(rnd() & 0x1FFFFFu) * (int32_t)((i % 7) != 0);
            b.lo[a] = c - w;
            b.hi[a] = c + w;
        }
        h_case(&h, lt_slab16_q16(&r, k, &b, &tn));
        h_vq16(&h, tn);
    }
    emit(put, "slab16_q16", &h);

    h_init(&h);
    rng_state = 0x5EED5EEDu;
    for (i = 0; i < N_MESH; i++) {
        int a;
        for (a = 0; a < 3; a++) {
            mesh_q[i].v0[a] = (int32_t)(rnd() & 0x3FFFFFu) - 0x200000;
            mesh_q[i].e1[a] = (int32_t)(rnd() & 0x7FFFFu) - 0x40000;
            mesh_q[i].e2[a] = (i % 11 == 0) ? mesh_q[i].e1[a] * 2 /* zero area */
                                            : (int32_t)(rnd() & 0x7FFFFu) - 0x40000;
        }
    }
    for (i = 0; i < 60; i++) {
        lt_hit16_t hit;
        hit.id = lt_vi32_set1(-1);
        rand_ray_q16(&r);
        /* aim half of the lanes at triangle vertices and edge midpoints */
        for (j = 0; j < LT_LANES; j += 2) {
            const lt_tri_q16_t *t = &mesh_q[rnd() % N_MESH];
            lt_q16_t d[3];
            lt_q30_t u[3];
            int a;
            for (a = 0; a < 3; a++) {
                lt_q16_t o = a == 0 ? r.ox.l[j] : (a == 1 ? r.oy.l[j] : r.oz.l[j]);
                lt_q16_t p = t->v0[a] + ((j & 2) ? t->e1[a] / 2 : 0);
                d[a] = p - o;
            }
            if (lt_q16_normalize3(d, u) == LT_OK) {
                r.dx.l[j] = u[0];
                r.dy.l[j] = u[1];
                r.dz.l[j] = u[2];
            }
        }
        lt_ray16_q16_setup(&r);
        for (j = 0; j < N_MESH; j++)
            h_case(&h, lt_tri16_q16(&r, LT_MASK_ALL, &mesh_q[j], j, &hit));
        h_vq16(&h, r.tmax);
        for (j = 0; j < LT_LANES; j++)
            h_u32(&h, (uint32_t)hit.id.l[j]);
    }
    emit(put, "tri16_q16", &h);

    h_init(&h);
    h_case(&h, (uint32_t)lt_chunks_build_q16(mesh_q, N_MESH, boxes_q));
    for (i = 0; i < (int)LT_CHUNK_COUNT(N_MESH); i++)
        for (j = 0; j < 3; j++) {
            h_u32(&h, (uint32_t)boxes_q[i].lo[j]);
            h_u32(&h, (uint32_t)boxes_q[i].hi[j]);
        }
    rng_state = 0xFACADEu;
    for (i = 0; i < 40; i++) {
        lt_hit16_t hit;
        rand_ray_q16(&r);
        h_case(&h, lt_chunks_trace16_q16(mesh_q, N_MESH, boxes_q, LT_ISECT_WT, &r, rmask(i), &hit));
        for (j = 0; j < LT_LANES; j++)
            h_u32(&h, (uint32_t)hit.id.l[j]);
        h_vq16(&h, r.tmax);
    }
    emit(put, "chunks_q16", &h);
}

/* BVH over the 48-triangle mesh: the tree layout and packet, single-ray and any-hit traversals,
 * and the watertight triangle test on the same rays. The arena is static (no heap here). */
static uint64_t bvh_arena[4096];

static void run_bvh_q16(void (*put)(const char *))
{
    hash_t h;
    lt_bvh_t bvh;
    lt_bvh_desc_t desc;
    size_t bytes = 0;
    int i, j;
    static lt_ray16_q16_t r;
    static lt_wt16_q16_t w;
    h_init(&h);
    lt__memset(&desc, 0, sizeof desc);
    h_case(&h, (uint32_t)lt_bvh_size(N_MESH, &desc, &bytes));
    h_case(&h, (uint32_t)bytes);
    h_case(&h, (uint32_t)lt_bvh_build_q16(&bvh, &desc, mesh_q, N_MESH, bvh_arena, sizeof bvh_arena));
    h_case(&h, bvh.nnodes * 65536u + bvh.depth * 256u + bvh.leaves);
    for (i = 0; i < (int)bvh.nnodes; i++) {
        const lt_bvh_node_q16_t *nd = &((const lt_bvh_node_q16_t *)bvh.nodes)[i];
        for (j = 0; j < 3; j++) {
            h_u32(&h, (uint32_t)nd->b.lo[j]);
            h_u32(&h, (uint32_t)nd->b.hi[j]);
        }
        h_u32(&h, nd->left_first);
        h_u32(&h, nd->count);
    }
    rng_state = 0xB1BB1Eu;
    for (i = 0; i < 40; i++) {
        lt_hit16_t hit;
        lt_mask16_t occ = 0, k = rmask(i);
        rand_ray_q16(&r);
        h_case(&h, (uint32_t)lt_bvh_trace16_q16(&bvh, mesh_q, &r, k, &hit));
        for (j = 0; j < LT_LANES; j++)
            h_u32(&h, (uint32_t)hit.id.l[j]);
        h_vq16(&h, r.tmax);
        rand_ray_q16(&r);
        h_case(&h, (uint32_t)lt_bvh_occluded16_q16(&bvh, mesh_q, &r, k, &occ));
        h_case(&h, occ);
        for (j = 0; j < LT_LANES; j++) {
            lt_ray1_q16_t r1;
            int32_t id = -1;
            int a;
            lt__memset(&r1, 0, sizeof r1);
            r1.o[0] = r.ox.l[j];
            r1.o[1] = r.oy.l[j];
            r1.o[2] = r.oz.l[j];
            r1.d[0] = r.dx.l[j];
            r1.d[1] = r.dy.l[j];
            r1.d[2] = r.dz.l[j];
            r1.tmin = 0;
            r1.tmax = 0x7FFFFFF;
            lt_ray1_q16_setup(&r1);
            h_case(&h, (uint32_t)lt_bvh_trace1_q16(&bvh, mesh_q, &r1, &id));
            h_u32(&h, (uint32_t)id);
            h_u32(&h, (uint32_t)r1.tmax);
            for (a = 0; a < 3; a++)
                h_u32(&h, (uint32_t)r1.rd[a]);
        }
        /* the watertight test on every triangle for a fresh packet */
        rand_ray_q16(&r);
        hit.id = lt_vi32_set1(-1);
        h_case(&h, lt_ray16_wt_setup_q16(&r, &w));
        for (j = 0; j < N_MESH; j++)
            h_case(&h, lt_tri16_wt_q16(&r, &w, k, &mesh_q[j], j, &hit));
        h_vq16(&h, r.tmax);
    }
    emit(put, "bvh_wt_q16", &h);
}

/* LT_ISECT_WT32's kernels (lt_tri16_wt32_q16, lt_tri1_wt32_q16, compiled whatever LT_CFG_WT32):
 * the mesh's grid shift, then for that grid, the finest (2^0: most vertices off the grid's range)
 * and the coarsest (2^13) the packet test on every triangle and each lane's single-ray test, some
 * lanes with short directions (the wide arithmetic). The walks that dispatch to them are checked
 * on the targets by scene-bunny-wt32.elf (tests/run.d/fwscene.sh). */
static void run_wt32_q16(void (*put)(const char *))
{
    hash_t h;
    int i, j, gi;
    unsigned gs;
    static lt_ray16_q16_t r, r0;
    static lt_wt16_q16_t w;
    h_init(&h);
    gs = lt_wt32_shift_q16(mesh_q, N_MESH);
    h_case(&h, gs);
    rng_state = 0x3232u;
    for (gi = 0; gi < 3; gi++) {
        unsigned g = gi == 0 ? gs : (gi == 1 ? 0u : LT_WT32_SHIFT_MAX);
        for (i = 0; i < 12; i++) {
            lt_hit16_t hit;
            lt_mask16_t k = rmask(i);
            rand_ray_q16(&r);
            for (j = 0; j < LT_LANES; j += 5) { /* short directions: sh > 0 */
                r.dx.l[j] = lt__asr32(r.dx.l[j], (unsigned)(1 + j % 7));
                r.dy.l[j] = lt__asr32(r.dy.l[j], (unsigned)(1 + j % 7));
                r.dz.l[j] = lt__asr32(r.dz.l[j], (unsigned)(1 + j % 7));
            }
            lt_ray16_q16_setup(&r);
            r0 = r;
            h_case(&h, lt_ray16_wt_setup_q16(&r, &w));
            hit.id = lt_vi32_set1(-1);
            for (j = 0; j < N_MESH; j++)
                h_case(&h, lt_tri16_wt32_q16(&r, &w, g, k, &mesh_q[j], j, &hit));
            h_vq16(&h, r.tmax);
            for (j = 0; j < LT_LANES; j++)
                h_u32(&h, (uint32_t)hit.id.l[j]);
            for (j = 0; j < LT_LANES; j++) {
                lt_wt1_q16_t w1;
                lt_q16_t o[3], tmax = r0.tmax.l[j];
                lt_q30_t d[3];
                int t;
                o[0] = r0.ox.l[j], o[1] = r0.oy.l[j], o[2] = r0.oz.l[j];
                d[0] = r0.dx.l[j], d[1] = r0.dy.l[j], d[2] = r0.dz.l[j];
                h_case(&h, (uint32_t)lt_ray1_wt_setup_q16(o, d, &w1));
                for (t = 0; t < N_MESH; t++)
                    h_case(&h, (uint32_t)lt_tri1_wt32_q16(&w1, g, &mesh_q[t], 0, &tmax));
                h_u32(&h, (uint32_t)tmax);
            }
        }
    }
    emit(put, "wt32_q16", &h);
}

/* kd-tree and uniform grid over the same mesh: sizes, the built arenas byte for byte, and the
 * closest-hit and any-hit packet traversals on random rays with every mask class. */
static uint32_t kd_arena[8192];
static uint32_t grid_arena[8192];

static void h_words(hash_t *h, const uint32_t *w, size_t bytes)
{
    size_t i;
    for (i = 0; i < bytes / 4u; i++)
        h_u32(h, w[i]);
}

static void run_kdgrid_q16(void (*put)(const char *))
{
    hash_t h;
    lt_kd_q16_t kd;
    lt_grid_q16_t g;
    size_t kb = 0, gb = 0;
    int i, j, pass;
    static lt_ray16_q16_t r;
    h_init(&h);
    h_case(&h, (uint32_t)lt_kd_size(N_MESH, NULL, &kb));
    h_case(&h, (uint32_t)kb);
    kb = sizeof kd_arena;
    h_case(&h, (uint32_t)lt_kd_build_q16(&kd, mesh_q, N_MESH, NULL, kd_arena, &kb));
    h_case(&h, kd.nnodes * 65536u + kd.depth * 256u + kd.nleaves);
    h_u32(&h, kd.nrefs);
    h_words(&h, kd_arena, kd.bytes);
    h_case(&h, (uint32_t)lt_grid_size_q16(mesh_q, N_MESH, NULL, &gb));
    h_case(&h, (uint32_t)gb);
    h_case(&h, (uint32_t)lt_grid_build_q16(&g, mesh_q, N_MESH, NULL, grid_arena, &gb));
    h_case(&h, g.res[0] * 65536u + g.res[1] * 256u + g.res[2]);
    for (j = 0; j < 3; j++)
        h_u32(&h, (uint32_t)g.cell[j]);
    h_words(&h, grid_arena, g.bytes);
    rng_state = 0x6D1Du;
    for (i = 0; i < 40; i++)
        for (pass = 0; pass < 2; pass++) {
            lt_hit16_t hit;
            lt_mask16_t k = rmask(i);
            rand_ray_q16(&r);
            h_case(&h, pass == 0 ? lt_kd_trace16_q16(&kd, &r, k, &hit)
                                 : lt_grid_trace16_q16(&g, &r, k, &hit));
            for (j = 0; j < LT_LANES; j++)
                h_u32(&h, (uint32_t)hit.id.l[j]);
            h_vq16(&h, r.tmax);
            rand_ray_q16(&r);
            h_case(&h, pass == 0 ? lt_kd_occluded16_q16(&kd, &r, k)
                                 : lt_grid_occluded16_q16(&g, &r, k));
            h_vq16(&h, r.tmax);
        }
    emit(put, "kd_grid_q16", &h);
}

#if LT_CFG_FLOAT32
static uint32_t fbits(float f)
{
    uint32_t u;
    lt__memcpy(&u, &f, sizeof u);
    return u;
}

static float rndf(float scale)
{
    /* exact: an integer in [-2^23, 2^23) times a power of two */
    return (float)((int32_t)(rnd() & 0xFFFFFFu) - 0x800000) * scale;
}

static void run_f32(void (*put)(const char *))
{
    hash_t h;
    int i, j;
    static lt_ray16_f32_t r;
    static lt_tri_f32_t tris[N_MESH];
    static lt_aabb_f32_t bx[LT_CHUNK_COUNT(N_MESH)];
    h_init(&h);
    rng_state = 0xF10A7u;
    for (i = 0; i < 200; i++) {
        lt_vf32_t a, b, s, v[6];
        lt_mask16_t k = rmask(i);
        for (j = 0; j < LT_LANES; j++) {
            a.l[j] = rndf(1.0f / 65536.0f);
            b.l[j] = (j & 7) == 0 ? 0.0f : rndf(1.0f / 1024.0f);
            s.l[j] = rndf(1.0f);
        }
        v[0] = lt_vf32_add_m(s, k, a, b);
        v[1] = lt_vf32_mul_z(k, a, b);
        v[2] = lt_vf32_div_m(s, k, a, b);
        v[3] = lt_vf32_rcp(b);
        v[4] = lt_vf32_min_m(s, k, a, b);
        v[5] = lt_vf32_sub(lt_vf32_max(a, b), lt_vf32_abs(a));
        for (j = 0; j < 6 * LT_LANES; j++)
            h_u32(&h, fbits(v[j / LT_LANES].l[j % LT_LANES]));
        h_case(&h, lt_vf32_cmple_m(k, a, b) | ((uint32_t)lt_vf32_cmpeq(a, b) << 16));
    }
    emit(put, "lanes_f32", &h);

    h_init(&h);
    rng_state = 0x7E57u;
    for (i = 0; i < N_MESH; i++)
        for (j = 0; j < 3; j++) {
            tris[i].v0[j] = rndf(1.0f / 65536.0f);
            tris[i].e1[j] = rndf(1.0f / 1048576.0f);
            tris[i].e2[j] = (i % 11 == 0) ? tris[i].e1[j] * 2.0f : rndf(1.0f / 1048576.0f);
        }
    h_case(&h, (uint32_t)lt_chunks_build_f32(tris, N_MESH, bx));
    for (i = 0; i < 40; i++) {
        lt_hit16_t hit;
        lt_aabb_f32_t b;
        lt_vf32_t tn = lt_vf32_set1(0.0f);
        for (j = 0; j < LT_LANES; j++) {
            float d[3], l2;
            int a;
            for (a = 0; a < 3; a++)
                d[a] = rndf(1.0f / 8388608.0f);
            if ((j & 3) == 0)
                d[j % 3] = 0.0f;
            l2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            if (l2 == 0.0f)
                d[0] = l2 = 1.0f;
            r.ox.l[j] = rndf(1.0f / 65536.0f);
            r.oy.l[j] = rndf(1.0f / 65536.0f);
            r.oz.l[j] = rndf(1.0f / 65536.0f);
            /* unnormalised directions are fine for the hash: t is then in units of |d| */
            r.dx.l[j] = d[0];
            r.dy.l[j] = d[1];
            r.dz.l[j] = d[2];
            r.tmin.l[j] = 0.0f;
            r.tmax.l[j] = 1e30f;
        }
        lt_ray16_f32_setup(&r);
        for (j = 0; j < 3; j++) {
            b.lo[j] = rndf(1.0f / 131072.0f);
            b.hi[j] = b.lo[j] + (i % 5 ? 20.0f : 0.0f);
        }
        h_case(&h, lt_slab16_f32(&r, rmask(i), &b, &tn));
        for (j = 0; j < LT_LANES; j++)
            h_u32(&h, fbits(tn.l[j]));
        h_case(&h, lt_chunks_trace16_f32(tris, N_MESH, bx, LT_ISECT_WT, &r, rmask(i), &hit));
        for (j = 0; j < LT_LANES; j++) {
            h_u32(&h, (uint32_t)hit.id.l[j]);
            h_u32(&h, fbits(r.tmax.l[j]));
        }
    }
    emit(put, "kernels_f32", &h);
}
#endif

int lt_vec_run(void (*put)(const char *line))
{
    int groups = 0;
    run_bin(put, "q16_add_sat", f_add_sat, 1u), groups++;
    run_bin(put, "q16_sub_sat", f_sub_sat, 2u), groups++;
    run_bin(put, "q16_add_wrap", f_add_wrap, 3u), groups++;
    run_bin(put, "q16_sub_wrap", f_sub_wrap, 4u), groups++;
    run_bin(put, "q16_mul_sat", f_mul_sat, 5u), groups++;
    run_bin(put, "q16_mul_sat_rd", f_mul_rd, 6u), groups++;
    run_bin(put, "q16_mul_q30_sat", f_mul_q30, 7u), groups++;
    run_bin(put, "q16_div_sat", f_div_sat, 8u), groups++;
    run_bin(put, "q30_mul_sat", f_q30_mul, 9u), groups++;
    run_bin(put, "q16_min_max_clamp", f_minmax, 10u), groups++;
    run_bin(put, "h8_ops", f_h8, 11u), groups++;
    run_un(put, "q16_recip_sat", f_recip, 12u), groups++;
    run_un(put, "q16_sqrt", f_sqrt, 13u), groups++;
    run_un(put, "q16_rsqrt_sat", f_rsqrt, 14u), groups++;
    run_un(put, "q16_abs_neg_sat", f_absneg, 15u), groups++;
    run_un(put, "q30_h14_conv", f_conv, 16u), groups++;
    run_vec3(put), groups++;
    run_lanes(put), groups++;
    run_kernels_q16(put), groups += 3;
    run_bvh_q16(put), groups++;
    run_wt32_q16(put), groups++;
    run_kdgrid_q16(put), groups++;
#if LT_CFG_FLOAT32
    run_f32(put), groups += 2;
#endif
    return groups;
}
