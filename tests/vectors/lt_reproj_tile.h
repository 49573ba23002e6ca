/* lt_reproj_tile.h - a deterministic 64 x 64 reprojection shared by the unit test (host, sim,
 * asan) and the firmware image tests/fw/fw_reproj.c (cm4, cm55, rv32 under QEMU), so that one hash
 * proves every build generates the same reprojected segments and traces them the same, bit for bit
 * (docs/reproject.md): two depth layers in s1.30 from integer code (a tilted background, a tilted
 * card in front of it, a pyramid bump, a hole at infinity), an n64 quadtree, the s1.30 mapping of a
 * moved and rotated target camera (stored here; lt_reproj_setup reproduces it from the cameras
 * below, which the unit test checks and the firmware reports), every 4 x 4 target tile through
 * lt_reproj_rays16_q30 and lt_qt_trace16_q30. Header only (static functions); freestanding.
 */
#ifndef LT_REPROJ_TILE_H
#define LT_REPROJ_TILE_H

#include "lt/lt_reproj.h"

#define LTRT_W 64u
#define LTRT_LAYERS 2u
/* n64 nodes of a 64 x 64 layer: 4096 + 1024 + 256 + 64 + 16 + 4 + 1 = 5461, x 8 bytes x 2 */
#define LTRT_ARENA (5461u * 8u * LTRT_LAYERS)

/* The stored mapping: lt_reproj_setup(&ltrt_src_cam, &ltrt_dst_cam, {z_ref 1}) (see below). */
static const lt_reproj_q30_t ltrt_map = {
    {{0, 0, 226492416}, {0, 0, 37748736}, {0, 0, 536870912}, {0, 0, 201326592}},
    {{539120415, -11337633, 34594553}, {-15502153, 544722151, 18610836}, {0, 0, 0},
     {-31004306, -20646452, 561472358}},
    64u, 64u, 64u, 64u, 6u, 6u, 1073741824, 0};

#if LT_CFG_FLOAT32
/* The cameras it came from: source at the origin looking down +z, f = 60 px; target moved by
 * (0.25, -0.125, 0.375), yawed 3 degrees and pitched -2 degrees (rotation entries printed with
 * %.17g from cos/sin in double), f = 58 px, principal point (31.5, 32.25). */
static const lt_reproj_cam_t ltrt_src_cam = {
    60.0, 60.0, 32.0, 32.0, {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {0, 0, 0}, 64u, 64u};
static const lt_reproj_cam_t ltrt_dst_cam = {
    58.0, 58.0, 31.5, 32.25,
    {{0.99862953475457383, 0, -0.052335956242943828},
     {-0.0018264985323228531, 0.99939082701909576, -0.034851668155187324},
     {0.052304074592470842, 0.034899496702500969, 0.99802119662406841}},
    {0.25, -0.125, 0.375}, 64u, 64u};

/* 1 when lt_reproj_setup reproduces ltrt_map exactly on this target. */
static int ltrt_setup_matches(void)
{
    lt_reproj_opts_t o = {1.0, 0.0, 0.0, 0.0};
    lt_reproj_q30_t m;
    const int32_t *a = &m.ma[0][0], *b = &ltrt_map.ma[0][0];
    int i;
    if (lt_reproj_setup(&ltrt_src_cam, &ltrt_dst_cam, &o, &m, (lt_reproj_f32_t *)0) != LT_OK)
        return 0;
    for (i = 0; i < 24; i++)
        if (a[i] != b[i])
            return 0;
    return m.src_w == ltrt_map.src_w && m.src_h == ltrt_map.src_h && m.dst_w == ltrt_map.dst_w &&
           m.dst_h == ltrt_map.dst_h && m.src_log2 == ltrt_map.src_log2 &&
           m.dst_log2 == ltrt_map.dst_log2 && m.w_near == ltrt_map.w_near &&
           m.w_far == ltrt_map.w_far;
}
#endif

static lt_q30_t ltrt_w[LTRT_LAYERS * LTRT_W * LTRT_W];
static uint64_t ltrt_arena[LTRT_ARENA / 8u];

/* w = z_ref / z in s1.30 (z_ref = 1): layer 0 the front surface, layer 1 the background where the
 * card covers it, else a hole (w = 0). */
static void ltrt_depth(void)
{
    int32_t x, y;
    for (y = 0; y < (int32_t)LTRT_W; y++) {
        for (x = 0; x < (int32_t)LTRT_W; x++) {
            int32_t bg = (1 << 28) + x * (1 << 20) - y * (1 << 19); /* z ~ 4, tilted */
            int32_t front = bg, back = 0;
            uint32_t p = (uint32_t)y * LTRT_W + (uint32_t)x;
            if (x >= 20 && x < 40 && y >= 16 && y < 44) {
                front = (1 << 29) + x * (1 << 21) + y * (1 << 20); /* card, z ~ 1.8 */
                back = bg;
            } else if (x >= 44 && x < 60 && y >= 44 && y < 60) {
                int32_t dx = x - 52 < 0 ? 52 - x : x - 52, dy = y - 52 < 0 ? 52 - y : y - 52;
                front = bg + (8 - (dx > dy ? dx : dy)) * (1 << 22); /* pyramid bump */
            } else if (x < 8 && y < 8) {
                front = 0; /* background at infinity */
            }
            ltrt_w[p] = front;
            ltrt_w[LTRT_W * LTRT_W + p] = back;
        }
    }
}

static uint32_t ltrt_fnv(uint32_t h, uint32_t v)
{
    unsigned i;
    for (i = 0; i < 4; i++) {
        h ^= (v >> (8 * i)) & 0xFFu;
        h *= 16777619u;
    }
    return h;
}

/* The hash over every tile: the mask, the segments and the trace results of the kept lanes.
 * counts (may be NULL) receives the lanes per LT_QT_* status (5 entries) and the kept lanes (6th).
 * Returns 0 when a step failed. */
static uint32_t ltrt_hash(uint32_t counts[6])
{
    static lt_qray16_q30_t r;
    static lt_qhit16_q30_t hit;
    lt_qt_desc_t d;
    lt_qt_t qt;
    size_t bytes = sizeof ltrt_arena;
    uint32_t h = 2166136261u, tx, ty;
    int i;
    if (counts != 0)
        for (i = 0; i < 6; i++)
            counts[i] = 0;
    ltrt_depth();
    d.width = d.height = LTRT_W;
    d.layers = LTRT_LAYERS;
    d.enc = LT_QT_N64;
    if (lt_qt_build_q30(&qt, &d, 0, ltrt_w, ltrt_arena, &bytes) != LT_OK)
        return 0;
    for (ty = 0; ty < LTRT_W; ty += 4) {
        for (tx = 0; tx < LTRT_W; tx += 4) {
            lt_mask16_t k = 0xFFFF;
            if (lt_reproj_rays16_q30(&ltrt_map, tx, ty, &r, &k) != LT_OK)
                return 0;
            h = ltrt_fnv(h, k);
            if (k == 0)
                continue;
            if (lt_qt_trace16_q30(&qt, &r, k, 0, &hit) != LT_OK)
                return 0;
            for (i = 0; i < LT_LANES; i++) {
                if ((((unsigned)k >> i) & 1u) == 0u)
                    continue;
                h = ltrt_fnv(h, (uint32_t)r.x.l[i]);
                h = ltrt_fnv(h, (uint32_t)r.y.l[i]);
                h = ltrt_fnv(h, (uint32_t)r.w.l[i]);
                h = ltrt_fnv(h, (uint32_t)r.dx.l[i]);
                h = ltrt_fnv(h, (uint32_t)r.dy.l[i]);
                h = ltrt_fnv(h, (uint32_t)r.dw.l[i]);
                h = ltrt_fnv(h, (uint32_t)hit.status.l[i]);
                h = ltrt_fnv(h, (uint32_t)hit.t.l[i]);
                h = ltrt_fnv(h, (uint32_t)hit.w.l[i]);
                h = ltrt_fnv(h, (uint32_t)hit.layer.l[i]);
                h = ltrt_fnv(h, (uint32_t)hit.nodes.l[i]);
                if (counts != 0) {
                    if (hit.status.l[i] >= 0 && hit.status.l[i] < 5)
                        counts[hit.status.l[i]]++;
                    counts[5]++;
                }
            }
        }
    }
    return h;
}

#endif /* LT_REPROJ_TILE_H */
