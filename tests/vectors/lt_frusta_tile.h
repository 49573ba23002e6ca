/* lt_frusta_tile.h - a deterministic multi-frusta workload shared by the unit test (host, sim,
 * asan) and the firmware image tests/fw/fw_frusta.c (cm4, cm55, rv32 under QEMU), so that one
 * hash proves every build traces the same shadow tiles bit for bit: 300 triangles from an integer
 * PRNG, BVH leaf 8, a 48 x 48 unit light on the 2^-7 grid, LP sample sets, 4 tiles of 16 frusta
 * per flag set (none, b, c, bc, cr, bcr, ls, bcrls; the shadow tiles bcrfls for the last); plus
 * primary frusta (P-Frusta) and their packet
 * baseline (P-Packet) on a 22 x 18 view of the same scene (4 blocks, partial tiles) per flag set,
 * closest-hit t and id of every pixel. Header only (static functions); freestanding.
 */
#ifndef LT_FRUSTA_TILE_H
#define LT_FRUSTA_TILE_H

#include "lt/lt_frusta.h"

#define LTFT_TRIS 300u
#define LTFT_ARENA (64u * 1024u)

static uint32_t ltft_next(uint32_t *s)
{
    /* xorshift32 (Marsaglia): integer only, the same sequence on every target */
    uint32_t x = *s;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    *s = x;
    return x;
}

/* A value in [lo, hi) world units as s15.16 raw (hi - lo <= 1024). */
static int32_t ltft_coord(uint32_t *s, int32_t lo, int32_t hi)
{
    uint32_t span = (uint32_t)(hi - lo) * 65536u;
    return lo * 65536 + (int32_t)(ltft_next(s) % span);
}

static uint32_t ltft_fnv(uint32_t h, uint32_t v)
{
    unsigned i;
    for (i = 0; i < 4; i++) {
        h ^= (v >> (8 * i)) & 0xFFu;
        h *= 16777619u;
    }
    return h;
}

static lt_tri_q16_t ltft_tq[LTFT_TRIS];
static uint64_t ltft_arena_q[LTFT_ARENA / 8];
#define LTFT_NFLAGS 8
static const uint32_t ltft_flags[LTFT_NFLAGS] = {
    0u, LT_FRUSTA_BACKFACE, LT_FRUSTA_CORNER, LT_FRUSTA_CORNER | LT_FRUSTA_BACKFACE,
    LT_FRUSTA_CORNER | LT_FRUSTA_CR, LT_FRUSTA_CORNER | LT_FRUSTA_CR | LT_FRUSTA_BACKFACE,
    LT_FRUSTA_LEAFRAY | LT_FRUSTA_SPLIT,
    LT_FRUSTA_CORNER | LT_FRUSTA_CR | LT_FRUSTA_BACKFACE | LT_FRUSTA_LEAFRAY | LT_FRUSTA_SPLIT};

/* The scene: blockers in y [-60, 60] over origins at y ~ -100, a light at y = 120. */
static void ltft_scene(void)
{
    uint32_t s = 0x2545F491u, i;
    unsigned a;
    for (i = 0; i < LTFT_TRIS; i++) {
        for (a = 0; a < 3; a++) {
            ltft_tq[i].v0[a] = ltft_coord(&s, a == 1 ? -60 : -120, a == 1 ? 60 : 120);
            ltft_tq[i].e1[a] = ltft_coord(&s, -12, 12);
            ltft_tq[i].e2[a] = ltft_coord(&s, -12, 12);
        }
    }
}

static void ltft_light(lt_frusta_light_q16_t *l, uint32_t flags)
{
    unsigned a;
    for (a = 0; a < 3; a++) {
        l->c[a] = a == 1 ? 120 * 65536 : -24 * 65536;
        l->eu[a] = a == 0 ? 48 * 65536 : 0;
        l->ev[a] = a == 2 ? 48 * 65536 : 0;
    }
    l->flags = flags;
    l->end_shift = 0;
}


/* The primary view: eye below the blockers looking up (+y), 22 x 18 pixels; directions in s1.30
 * raw, multiples of 128 (= 2^-23, so the float32 view is the same rays exactly), below 2^30 over
 * the 24 x 20 pixels of the tiles touching the image. */
static void ltft_view_q16(lt_frusta_view_q16_t *v, uint32_t flags)
{
    v->o[0] = 3 * 65536;
    v->o[1] = -100 * 65536;
    v->o[2] = -2 * 65536;
    v->d0[0] = -587202560;
    v->d0[1] = 536870912;
    v->d0[2] = -486539264;
    v->dx[0] = 50331648;
    v->dx[1] = 128000;
    v->dx[2] = 0;
    v->dy[0] = 38400;
    v->dy[1] = 0;
    v->dy[2] = 50331648;
    v->width = 22;
    v->height = 18;
    v->flags = flags;
}

/* Closest hits of every pixel by P-Frusta (4 blocks of 16 frusta) and by P-Packet (one packet per
 * 4x4 tile) into the hash, s15.16. Returns 0 on an error. */
static uint32_t ltft_prim_q16(uint32_t h, const lt_bvh_t *bvh)
{
    static lt_frusta_prim16_q16_t P;
    static lt_frusta_vtable_q16_t vt;
    static lt_ray16_q16_t r;
    lt_frusta_view_q16_t v;
    lt_hit16_t hit;
    lt_mask16_t k;
    unsigned fl, b, f, j;
    for (fl = 0; fl < LTFT_NFLAGS; fl++) {
        ltft_view_q16(&v, ltft_flags[fl]);
        if (lt_frusta_vtable_q16(&v, &vt) != LT_OK)
            return 0;
        for (b = 0; b < 4; b++) {
            if (lt_frusta_psetup16_q16(&vt, 16u * (b & 1u), 16u * (b >> 1), &P) != LT_OK ||
                lt_frusta_trace16_q16(bvh, ltft_tq, &vt, &P) != LT_OK)
                return 0;
            for (f = 0; f < 16; f++)
                for (j = 0; j < 16; j++)
                    if (((unsigned)P.live[f] >> j) & 1u) {
                        h = ltft_fnv(h, (uint32_t)P.t[f].l[j]);
                        h = ltft_fnv(h, (uint32_t)P.id[f].l[j]);
                    }
        }
        for (b = 0; b < 30; b++) {
            uint32_t tx = 4u * (b % 6u), ty = 4u * (b / 6u);
            if (lt_frusta_prays16_q16(&vt, tx, ty, &r, &k) != LT_OK ||
                lt_frusta_packet_trace16_q16(bvh, ltft_tq, v.flags, vt.o, &r, k, &hit) != LT_OK)
                return 0;
            for (j = 0; j < 16; j++)
                if (((unsigned)k >> j) & 1u) {
                    h = ltft_fnv(h, (uint32_t)r.tmax.l[j]);
                    h = ltft_fnv(h, (uint32_t)hit.id.l[j]);
                }
        }
    }
    return h;
}

/* Hash of the occlusion bits of every frustum of 4 tiles x 8 flag sets and of the primary
 * closest hits (ltft_prim_q16), s15.16. Returns 0 on a setup error (never for this fixed
 * input). */
static uint32_t ltft_hash_q16(void)
{
    static lt_frusta_table_q16_t tb;
    static lt_frusta16_q16_t F;
    lt_bvh_desc_t d;
    lt_bvh_t bvh;
    lt_frusta_light_q16_t l;
    lt_qmc_sets_t sets;
    size_t bytes;
    uint32_t h = 2166136261u, s = 0x9E3779B9u;
    unsigned fl, t, f;
    ltft_scene();
    d.bins = 0;
    d.max_leaf = 8;
    d.min_leaf = 4;
    d.max_depth = 0;
    d.flags = 0;
    if (lt_bvh_size(LTFT_TRIS, &d, &bytes) != LT_OK || bytes > sizeof ltft_arena_q ||
        lt_bvh_build_q16(&bvh, &d, ltft_tq, LTFT_TRIS, ltft_arena_q, sizeof ltft_arena_q) != LT_OK ||
        lt_qmc_interleave4x4(LT_QMC_LP, 0, &sets) != LT_OK)
        return 0;
    for (fl = 0; fl < LTFT_NFLAGS; fl++) {
        ltft_light(&l, ltft_flags[fl] | (fl + 1u == LTFT_NFLAGS ? LT_FRUSTA_FS : 0u));
        if (lt_frusta_table_q16(&l, &sets, &tb) != LT_OK)
            return 0;
        for (t = 0; t < 4; t++) {
            int32_t cx = ltft_coord(&s, -100, 100), cz = ltft_coord(&s, -100, 100);
            for (f = 0; f < 16; f++) {
                F.ox.l[f] = cx + (int32_t)(f % 4) * 65536 * (int32_t)(1 + t);
                F.oy.l[f] = ltft_coord(&s, -110, -90);
                F.oz.l[f] = cz + (int32_t)(f / 4) * 65536 * (int32_t)(1 + t);
            }
            if (lt_frusta_setup16_q16(&tb, LT_MASK_ALL, &F) != LT_OK ||
                lt_frusta_occluded16_q16(&bvh, ltft_tq, &tb, &F) != LT_OK)
                return 0;
            for (f = 0; f < 16; f++)
                h = ltft_fnv(h, F.occl[f]);
        }
    }
    return ltft_prim_q16(h, &bvh);
}

#if LT_CFG_FLOAT32
/* ltft_prim_q16 in float32 (the view converted exactly). */
static uint32_t ltft_prim_f32(uint32_t h, const lt_bvh_t *bvh, const lt_tri_f32_t *tris)
{
    static lt_frusta_prim16_f32_t P;
    static lt_frusta_vtable_f32_t vt;
    static lt_ray16_f32_t r;
    lt_frusta_view_q16_t vq;
    lt_frusta_view_f32_t v;
    lt_hit16_t hit;
    lt_mask16_t k;
    unsigned fl, b, f, j, a;
    union {
        float f;
        uint32_t u;
    } c;
    for (fl = 0; fl < LTFT_NFLAGS; fl++) {
        ltft_view_q16(&vq, ltft_flags[fl]);
        for (a = 0; a < 3; a++) {
            v.o[a] = (float)vq.o[a] / 65536.0f;
            v.d0[a] = (float)vq.d0[a] / 1073741824.0f;
            v.dx[a] = (float)vq.dx[a] / 1073741824.0f;
            v.dy[a] = (float)vq.dy[a] / 1073741824.0f;
        }
        v.width = vq.width;
        v.height = vq.height;
        v.flags = vq.flags;
        if (lt_frusta_vtable_f32(&v, &vt) != LT_OK)
            return 0;
        for (b = 0; b < 4; b++) {
            if (lt_frusta_psetup16_f32(&vt, 16u * (b & 1u), 16u * (b >> 1), &P) != LT_OK ||
                lt_frusta_trace16_f32(bvh, tris, &vt, &P) != LT_OK)
                return 0;
            for (f = 0; f < 16; f++)
                for (j = 0; j < 16; j++)
                    if (((unsigned)P.live[f] >> j) & 1u) {
                        c.f = P.t[f].l[j];
                        h = ltft_fnv(h, c.u);
                        h = ltft_fnv(h, (uint32_t)P.id[f].l[j]);
                    }
        }
        for (b = 0; b < 30; b++) {
            uint32_t tx = 4u * (b % 6u), ty = 4u * (b / 6u);
            if (lt_frusta_prays16_f32(&vt, tx, ty, &r, &k) != LT_OK ||
                lt_frusta_packet_trace16_f32(bvh, tris, v.flags, vt.o, &r, k, &hit) != LT_OK)
                return 0;
            for (j = 0; j < 16; j++)
                if (((unsigned)k >> j) & 1u) {
                    c.f = r.tmax.l[j];
                    h = ltft_fnv(h, c.u);
                    h = ltft_fnv(h, (uint32_t)hit.id.l[j]);
                }
        }
    }
    return h;
}

static lt_tri_f32_t ltft_tf[LTFT_TRIS];
static uint64_t ltft_arena_f[LTFT_ARENA / 8];

/* The same workload in float32 (triangles and origins converted from the s15.16 values). */
static uint32_t ltft_hash_f32(void)
{
    static lt_frusta_table_f32_t tb;
    static lt_frusta16_f32_t F;
    lt_bvh_desc_t d;
    lt_bvh_t bvh;
    lt_frusta_light_q16_t lq;
    lt_frusta_light_f32_t l;
    lt_qmc_sets_t sets;
    size_t bytes;
    uint32_t h = 2166136261u, s = 0x9E3779B9u, i;
    unsigned fl, t, f, a;
    ltft_scene();
    for (i = 0; i < LTFT_TRIS; i++)
        for (a = 0; a < 3; a++) {
            ltft_tf[i].v0[a] = (float)ltft_tq[i].v0[a] / 65536.0f;
            ltft_tf[i].e1[a] = (float)ltft_tq[i].e1[a] / 65536.0f;
            ltft_tf[i].e2[a] = (float)ltft_tq[i].e2[a] / 65536.0f;
        }
    d.bins = 0;
    d.max_leaf = 8;
    d.min_leaf = 4;
    d.max_depth = 0;
    d.flags = 0;
    if (lt_bvh_size(LTFT_TRIS, &d, &bytes) != LT_OK || bytes > sizeof ltft_arena_f ||
        lt_bvh_build_f32(&bvh, &d, ltft_tf, LTFT_TRIS, ltft_arena_f, sizeof ltft_arena_f) != LT_OK ||
        lt_qmc_interleave4x4(LT_QMC_LP, 0, &sets) != LT_OK)
        return 0;
    for (fl = 0; fl < LTFT_NFLAGS; fl++) {
        ltft_light(&lq, ltft_flags[fl] | (fl + 1u == LTFT_NFLAGS ? LT_FRUSTA_FS : 0u));
        for (a = 0; a < 3; a++) {
            l.c[a] = (float)lq.c[a] / 65536.0f;
            l.eu[a] = (float)lq.eu[a] / 65536.0f;
            l.ev[a] = (float)lq.ev[a] / 65536.0f;
        }
        l.flags = lq.flags;
        l.end_shift = 0;
        if (lt_frusta_table_f32(&l, &sets, &tb) != LT_OK)
            return 0;
        for (t = 0; t < 4; t++) {
            int32_t cx = ltft_coord(&s, -100, 100), cz = ltft_coord(&s, -100, 100);
            for (f = 0; f < 16; f++) {
                F.ox.l[f] = (float)(cx + (int32_t)(f % 4) * 65536 * (int32_t)(1 + t)) / 65536.0f;
                F.oy.l[f] = (float)ltft_coord(&s, -110, -90) / 65536.0f;
                F.oz.l[f] = (float)(cz + (int32_t)(f / 4) * 65536 * (int32_t)(1 + t)) / 65536.0f;
            }
            if (lt_frusta_setup16_f32(&tb, LT_MASK_ALL, &F) != LT_OK ||
                lt_frusta_occluded16_f32(&bvh, ltft_tf, &tb, &F) != LT_OK)
                return 0;
            for (f = 0; f < 16; f++)
                h = ltft_fnv(h, F.occl[f]);
        }
    }
    return ltft_prim_f32(h, &bvh, ltft_tf);
}
#endif

#endif /* LT_FRUSTA_TILE_H */
