/* stream_dev.c - the streaming device (stream_dev.h): an embedded 18-triangle scene (a cube, a
 * tetrahedron and a floor quad, two chunks of lt_chunks_build_q16), a pinhole camera built in
 * integer math (lt_q16_cross3_sat, lt_q16_normalize3), 64x64 pixels in 16 tiles of 16x16, traced
 * with lt_chunks_trace16_q16 packet by packet, and the frames of lt_stream.h pushed through the
 * batcher against the device clock. Builds: firmware (freestanding), host, sim (LT_COST_SIM: the
 * same phases and RAYS event as host/cli/lanetrace_main.c, so its counters are the simulator's).
 */
#include "stream_dev.h"

#include "lt/lt_config.h"
#include "lt/lt_cost.h"
#include "lt/lt_fx.h"
#include "lt/lt_isect.h"

/* ---- scene ----------------------------------------------------------------------------------- */

/* Vertices in quarter units (s15.16 value = q * 16384). Cube [-2,0] x [0,2] x [-1,1], tetrahedron
 * on (1..3, 0, -1..1) with apex (2, 2.5, 0), floor quad at y = -1/16 (-0.25 quarters would make it
 * coplanar with nothing; it is below everything). */
#define NTRIS 18
static const int16_t verts[][3] = {
    /* cube 0..7 */
    {-8, 0, -4}, {0, 0, -4}, {0, 8, -4}, {-8, 8, -4},
    {-8, 0, 4}, {0, 0, 4}, {0, 8, 4}, {-8, 8, 4},
    /* tetrahedron 8..11 */
    {4, 0, -4}, {12, 0, -4}, {8, 0, 4}, {8, 10, 0},
    /* floor 12..15 (y in sixteenths: see FLOOR_Y) */
    {-24, 0, -24}, {24, 0, -24}, {24, 0, 24}, {-24, 0, 24},
};
#define FLOOR_Y (-4096) /* -1/16 in s15.16 */
static const uint8_t faces[NTRIS][3] = {
    /* cube: -z, +z, -x, +x, -y, +y */
    {0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 4, 7}, {0, 7, 3},
    {1, 2, 6}, {1, 6, 5}, {0, 1, 5}, {0, 5, 4}, {3, 7, 6}, {3, 6, 2},
    /* tetrahedron */
    {8, 9, 11}, {9, 10, 11}, {10, 8, 11}, {8, 10, 9},
    /* floor */
    {12, 14, 13}, {12, 15, 14},
};

static lt_tri_q16_t tris[NTRIS];
static lt_aabb_q16_t boxes[LT_CHUNK_COUNT(NTRIS)];

static lt_q16_t vcoord(uint32_t v, uint32_t a)
{
    if (v >= 12 && a == 1)
        return FLOOR_Y;
    return (lt_q16_t)verts[v][a] * 16384;
}

static uint32_t fnv_u32(uint32_t h, uint32_t w)
{
    uint32_t i;
    for (i = 0; i < 4; i++) {
        h ^= (w >> (8 * i)) & 0xFFu;
        h *= 16777619u;
    }
    return h;
}

static lt_status_t scene_build(uint32_t *hash)
{
    uint32_t t, a, h = 2166136261u;
    for (t = 0; t < NTRIS; t++)
        for (a = 0; a < 3; a++) {
            lt_q16_t p0 = vcoord(faces[t][0], a);
            tris[t].v0[a] = p0;
            tris[t].e1[a] = vcoord(faces[t][1], a) - p0;
            tris[t].e2[a] = vcoord(faces[t][2], a) - p0;
        }
    for (t = 0; t < NTRIS; t++)
        for (a = 0; a < 3; a++) {
            h = fnv_u32(h, (uint32_t)tris[t].v0[a]);
            h = fnv_u32(h, (uint32_t)tris[t].e1[a]);
            h = fnv_u32(h, (uint32_t)tris[t].e2[a]);
        }
    *hash = h;
    return lt_chunks_build_q16(tris, NTRIS, boxes);
}

/* ---- camera: integer pinhole ----------------------------------------------------------------- */

/* Image-plane distance in half-pixel units: W / tan(fov / 2) for a 50 degree horizontal field
 * (64 / 0.4663 = 137.3), so direction = K f + sx r + sy u with sx, sy in half pixels. */
#define CAM_K 137

typedef struct cam {
    lt_q16_t eye[3];
    lt_q16_t f[3], r[3], u[3]; /* unit basis, s15.16 */
} cam_t;

static lt_status_t cam_build(uint32_t frame, cam_t *c)
{
    lt_q16_t fw[3], rt[3], up[3], wup[3] = {0, LT_Q16_ONE, 0};
    lt_q30_t n[3];
    uint32_t a;
    /* the eye slides right by 1/4 unit per frame, looking at (0, 0.75, 0) */
    c->eye[0] = 32768 + (lt_q16_t)(frame & 15u) * 16384;
    c->eye[1] = 3 * LT_Q16_ONE;
    c->eye[2] = 7 * LT_Q16_ONE;
    fw[0] = 0 - c->eye[0];
    fw[1] = 49152 - c->eye[1];
    fw[2] = 0 - c->eye[2];
    if (lt_q16_normalize3(fw, n) != LT_OK)
        return LT_E_ARG;
    for (a = 0; a < 3; a++)
        c->f[a] = lt_q16_from_q30(n[a]);
    lt_q16_cross3_sat(c->f, wup, rt);
    if (lt_q16_normalize3(rt, n) != LT_OK)
        return LT_E_ARG;
    for (a = 0; a < 3; a++)
        c->r[a] = lt_q16_from_q30(n[a]);
    lt_q16_cross3_sat(c->r, c->f, up);
    if (lt_q16_normalize3(up, n) != LT_OK)
        return LT_E_ARG;
    for (a = 0; a < 3; a++)
        c->u[a] = lt_q16_from_q30(n[a]);
    return LT_OK;
}

/* The 4x4 packet whose top-left pixel is (px, py). All lanes are inside the image. */
static lt_status_t cam_packet(const cam_t *c, uint32_t px, uint32_t py, lt_ray16_q16_t *r)
{
    int i;
    for (i = 0; i < LT_LANES; i++) {
        int32_t sx = 2 * (int32_t)(px + (uint32_t)(i % 4)) + 1 - LT_SDEV_W;
        int32_t sy = LT_SDEV_H - 2 * (int32_t)(py + (uint32_t)(i / 4)) - 1;
        lt_q16_t d[3];
        lt_q30_t n[3];
        uint32_t a;
        for (a = 0; a < 3; a++)
            d[a] = CAM_K * c->f[a] + sx * c->r[a] + sy * c->u[a];
        if (lt_q16_normalize3(d, n) != LT_OK)
            return LT_E_ARG;
        r->ox.l[i] = c->eye[0];
        r->oy.l[i] = c->eye[1];
        r->oz.l[i] = c->eye[2];
        r->dx.l[i] = n[0];
        r->dy.l[i] = n[1];
        r->dz.l[i] = n[2];
        r->tmin.l[i] = 0;
        r->tmax.l[i] = LT_Q16_MAX - 1;
    }
    lt_ray16_q16_setup(r);
    return LT_OK;
}

/* ---- device loop ----------------------------------------------------------------------------- */

#define RING_MAX 64
static uint8_t ring[RING_MAX * LT_STREAM_FRAME_BYTES];

void lt_sdev_cfg_default(lt_sdev_cfg_t *c)
{
    c->frames = 4;
    c->image_from = 2;
    c->direct = 0;
    lt_stream_link_default(&c->link, 1);
}

static uint32_t sat32(uint64_t v) { return v > 0xFFFFFFFFu ? 0xFFFFFFFFu : (uint32_t)v; }

static void ctr_read(const lt_sdev_port_t *p, lt_sdev_ctr_t *c)
{
    if (p->counters != NULL)
        p->counters(p->ctx, c);
    else
        c->cycles = c->aabb = c->aabb_rays = c->tris = c->tri_rays = 0;
}

/* Push a CTRL frame, waiting for a link slot while the ring is full. */
static void push_ctrl(const lt_sdev_port_t *p, lt_stream_tx_t *tx, lt_stream_frame_t *f)
{
    uint64_t retry = 0;
    while (lt_stream_tx_push(tx, f, LT_STREAM_CLASS_CTRL, p->ticks(p->ctx), &retry) == LT_E_SPACE)
        p->idle_until(p->ctx, retry);
}

static void push_image(const lt_sdev_port_t *p, lt_stream_tx_t *tx, uint32_t frame, uint32_t tile,
                       const uint8_t *ids)
{
    uint32_t off = 0, n = LT_SDEV_TILE * LT_SDEV_TILE, i;
    while (off < n) {
        lt_stream_image_t im;
        lt_stream_frame_t f;
        uint32_t k = n - off < LT_STREAM_IMAGE_MAX ? n - off : LT_STREAM_IMAGE_MAX;
        im.frame = (uint16_t)frame;
        im.tile = (uint16_t)tile;
        im.offset = (uint16_t)off;
        im.count = (uint8_t)k;
        im.format = LT_STREAM_IMG_ID8;
        for (i = 0; i < k; i++)
            im.data[i] = ids[off + i];
        (void)lt_stream_pack_image(&im, &f);
        (void)lt_stream_tx_push(tx, &f, LT_STREAM_CLASS_IMAGE, p->ticks(p->ctx), NULL);
        off += k;
    }
}

int lt_sdev_run(const lt_sdev_port_t *p, const lt_sdev_cfg_t *c, lt_sdev_result_t *r)
{
    static lt_ray16_q16_t ray;
    static uint8_t ids[LT_SDEV_TILE * LT_SDEV_TILE];
    lt_stream_frame_t fr;
    lt_stream_link_t link;
    uint32_t scene_hash = 0, frame, tile, i;
    int status = 0;

    if (p == NULL || c == NULL || r == NULL || c->frames == 0 || c->frames > LT_SDEV_MAX_FRAMES ||
        c->link.cap > RING_MAX)
        return 1;
    lt__memset(r, 0, sizeof *r);
    if (p->region != NULL) {
        p->region(p->ctx, tris, sizeof tris, 0x10000000u);
        p->region(p->ctx, boxes, sizeof boxes, 0x20000000u);
    }
    if (scene_build(&scene_hash) != LT_OK)
        status = 2;
    link = c->link;
    link.tick_hz = p->tick_hz;
    if (!c->direct) {
        lt_stream_hello_t h;
        const char *s = p->name;
        if (lt_stream_tx_init(&r->tx, &link, ring, sizeof ring, p->sink, p->ctx) != LT_OK)
            return 1;
        lt__memset(&h, 0, sizeof h);
        h.source = p->source;
        h.tile_w = LT_SDEV_TILE;
        h.tile_h = LT_SDEV_TILE;
        h.flags = c->image_from < c->frames ? 1u : 0u;
        h.tick_hz = p->tick_hz;
        h.link_bytes_per_s = link.link_bytes_per_s;
        h.ticks_per_report = sat32(r->tx.period);
        h.width = LT_SDEV_W;
        h.height = LT_SDEV_H;
        h.ntris = NTRIS;
        h.frames = (uint16_t)c->frames;
        h.valid = p->valid;
        h.scene_hash = scene_hash;
        h.session = 0x5EED0000u;
        for (i = 0; i < 16 && s != NULL && s[i] != '\0'; i++) {
            h.name[i] = s[i];
            h.session = fnv_u32(h.session, (uint8_t)s[i]);
        }
        (void)lt_stream_pack_hello(&h, &fr);
        push_ctrl(p, &r->tx, &fr);
    }
    for (frame = 0; status == 0 && frame < c->frames; frame++) {
        lt_stream_summary_t *sum = &r->sum[frame];
        cam_t cam;
        uint32_t fh = 2166136261u;
        if (cam_build(frame, &cam) != LT_OK) {
            status = 3;
            break;
        }
        sum->frame = (uint16_t)frame;
        for (tile = 0; status == 0 && tile < LT_SDEV_TILES; tile++) {
            uint32_t tx0 = (tile % (LT_SDEV_W / LT_SDEV_TILE)) * LT_SDEV_TILE;
            uint32_t ty0 = (tile / (LT_SDEV_W / LT_SDEV_TILE)) * LT_SDEV_TILE;
            uint32_t px, py, hits = 0, h = 2166136261u;
            lt_sdev_ctr_t c0, c1;
            uint64_t t0, t1;
            lt_stream_tile_t tr;
            ctr_read(p, &c0);
            t0 = p->ticks(p->ctx);
            for (py = ty0; py < ty0 + LT_SDEV_TILE; py += 4)
                for (px = tx0; px < tx0 + LT_SDEV_TILE; px += 4) {
                    lt_hit16_t hit;
                    lt_phase_t prev = LT_PHASE_ENTER(SETUP);
                    if (cam_packet(&cam, px, py, &ray) != LT_OK)
                        status = 3;
                    LT_EVENT(RAYS, LT_LANES);
                    LT_PHASE_LEAVE(prev);
                    (void)lt_chunks_trace16_q16(tris, NTRIS, boxes, LT_ISECT_WT, &ray, LT_MASK_ALL,
                                                &hit);
                    for (i = 0; i < LT_LANES; i++) {
                        int32_t id = hit.id.l[i];
                        uint32_t pix = (py - ty0 + i / 4) * LT_SDEV_TILE + (px - tx0 + i % 4);
                        h = fnv_u32(h, (uint32_t)id);
                        h = fnv_u32(h, (uint32_t)ray.tmax.l[i]);
                        hits += id >= 0;
                        ids[pix] = (uint8_t)(id < 0 ? 0 : id >= 254 ? 255 : id + 1);
                    }
                }
            t1 = p->ticks(p->ctx);
            ctr_read(p, &c1);
            tr.frame = (uint16_t)frame;
            tr.tile = (uint16_t)tile;
            tr.rays = LT_SDEV_TILE * LT_SDEV_TILE;
            tr.hits = (uint16_t)hits;
            tr.ticks = sat32(t1 - t0);
            tr.cycles = sat32(c1.cycles - c0.cycles);
            tr.aabb = sat32(c1.aabb - c0.aabb);
            tr.aabb_rays = sat32(c1.aabb_rays - c0.aabb_rays);
            tr.tris = sat32(c1.tris - c0.tris);
            tr.tri_rays = sat32(c1.tri_rays - c0.tri_rays);
            tr.hash = h;
            tr.t_end = (uint32_t)(t1 & 0xFFFFFFFFu);
            sum->tiles++;
            sum->rays += tr.rays;
            sum->hits += tr.hits;
            sum->ticks += t1 - t0;
            sum->cycles += c1.cycles - c0.cycles;
            sum->aabb += tr.aabb;
            sum->aabb_rays += tr.aabb_rays;
            sum->tris += tr.tris;
            sum->tri_rays += tr.tri_rays;
            fh = fnv_u32(fh, h);
            if (!c->direct) {
                (void)lt_stream_pack_tile(&tr, &fr);
                (void)lt_stream_tx_push(&r->tx, &fr, LT_STREAM_CLASS_TILE, p->ticks(p->ctx), NULL);
                if (frame >= c->image_from)
                    push_image(p, &r->tx, frame, tile, ids);
            }
        }
        sum->hash = fh;
        r->frames = frame + 1;
        if (!c->direct) {
            sum->dropped = r->tx.dropped[0] + r->tx.dropped[1] + r->tx.dropped[2];
            (void)lt_stream_pack_summary(sum, &fr);
            push_ctrl(p, &r->tx, &fr);
        }
    }
    r->ticks_end = p->ticks(p->ctx);
    if (!c->direct) {
        lt_stream_end_t e;
        lt__memset(&e, 0, sizeof e);
        e.ticks = r->ticks_end;
        e.status = (uint32_t)status;
        e.frames = r->frames;
        (void)lt_stream_tx_finish(&r->tx, &e, r->ticks_end, &r->link_done);
    }
    return status;
}
