/* lt_frusta_tile.h - a deterministic multi-frusta workload shared by the unit test (host, sim,
 * asan) and the firmware image tests/fw/fw_frusta.c (cm4, cm55, rv32 under QEMU), so that one
 * hash proves every build traces the same shadow tiles bit for bit: 300 triangles from an integer
 * PRNG, BVH leaf 8, a 48 x 48 unit light on the 2^-7 grid, LP sample sets, 4 tiles of 16 frusta
 * per flag set (none, b, c, bc, cr, bcr). Header only (static functions); freestanding.
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
static const uint32_t ltft_flags[6] = {
    0u, LT_FRUSTA_BACKFACE, LT_FRUSTA_CORNER, LT_FRUSTA_CORNER | LT_FRUSTA_BACKFACE,
    LT_FRUSTA_CORNER | LT_FRUSTA_CR, LT_FRUSTA_CORNER | LT_FRUSTA_CR | LT_FRUSTA_BACKFACE};

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

/* Hash of the occlusion bits of every frustum of 4 tiles x 6 flag sets, s15.16. Returns 0 on a
 * setup error (never for this fixed input). */
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
    for (fl = 0; fl < 6; fl++) {
        ltft_light(&l, ltft_flags[fl]);
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
    return h;
}

#if LT_CFG_FLOAT32
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
    for (fl = 0; fl < 6; fl++) {
        ltft_light(&lq, ltft_flags[fl]);
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
    return h;
}
#endif

#endif /* LT_FRUSTA_TILE_H */
