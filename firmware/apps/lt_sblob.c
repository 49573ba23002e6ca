/* lt_sblob.c - open (check) and trace a scene blob; see lt_sblob.h. Builds: firmware
 * (freestanding), host, sim.
 */
#include "lt_sblob.h"

uint32_t lt_sblob_fnv(uint32_t h, const void *p, size_t n)
{
    const uint8_t *b = (const uint8_t *)p;
    size_t i;
    for (i = 0; i < n; i++) {
        h ^= b[i];
        h *= 16777619u;
    }
    return h;
}

static uint32_t fnv_word(uint32_t h, uint32_t w)
{
    unsigned i;
    for (i = 0; i < 4u; i++) {
        h ^= (w >> (8u * i)) & 0xFFu;
        h *= 16777619u;
    }
    return h;
}

const char *lt_sblob_err_str(lt_sblob_err_t e)
{
    switch (e) {
    case LT_SBLOB_OK: return "ok";
    case LT_SBLOB_E_SHORT: return "shorter than its header or its byte count";
    case LT_SBLOB_E_MAGIC: return "not a scene blob (magic LTSB missing)";
    case LT_SBLOB_E_VERSION: return "another format version";
    case LT_SBLOB_E_LAYOUT: return "a section lies outside the blob or is misaligned";
    case LT_SBLOB_E_SUM: return "checksum differs: the blob was damaged";
    case LT_SBLOB_E_IMAGE: return "image size, eps or flags out of range";
    case LT_SBLOB_E_CAMERA:
        return "a pixel direction overflows, or a corner's is 90 degrees or more from the centre "
               "pixel's";
    case LT_SBLOB_E_GEOMETRY: return "a vertex, the eye or the light outside the geometry bound";
    case LT_SBLOB_E_TREE: return "a BVH node or index out of range";
    }
    return "unknown error";
}

static void put32(uint8_t *p, uint32_t w)
{
    p[0] = (uint8_t)w;
    p[1] = (uint8_t)(w >> 8);
    p[2] = (uint8_t)(w >> 16);
    p[3] = (uint8_t)(w >> 24);
}

static size_t align64(size_t n)
{
    return (n + 63u) & ~(size_t)63u;
}

/* section offsets: triangles right after the header, nodes and indices 64-byte aligned */
static size_t off_nodes(uint32_t nt)
{
    return align64(LT_SBLOB_HEADER_BYTES + (size_t)nt * sizeof(lt_tri_q16_t));
}

static size_t off_idx(uint32_t nt, uint32_t nn)
{
    return align64(off_nodes(nt) + (size_t)nn * sizeof(lt_bvh_node_q16_t));
}

size_t lt_sblob_size(uint32_t ntris, uint32_t nnodes)
{
    return align64(off_idx(ntris, nnodes) + (size_t)ntris * 4u);
}

/* The triangle, node and index sections at their offsets, little-endian. */
static void write_scene(uint8_t *b, const lt_tri_q16_t *tris, const lt_bvh_t *bvh, size_t ot,
                        size_t on, size_t oi)
{
    uint32_t i, k;
    unsigned a;
    for (i = 0; i < bvh->ntris; i++) {
        const lt_tri_q16_t *t = &tris[i];
        uint8_t *q = b + ot + (size_t)i * sizeof *t;
        for (a = 0; a < 3u; a++) {
            put32(q + 4u * a, (uint32_t)t->v0[a]);
            put32(q + 12u + 4u * a, (uint32_t)t->e1[a]);
            put32(q + 24u + 4u * a, (uint32_t)t->e2[a]);
        }
        put32(b + oi + 4u * i, bvh->idx[i]);
    }
    for (k = 0; k < bvh->nnodes; k++) {
        const lt_bvh_node_q16_t *nd = (const lt_bvh_node_q16_t *)bvh->nodes + k;
        uint8_t *q = b + on + (size_t)k * sizeof *nd;
        for (a = 0; a < 3u; a++) {
            put32(q + 4u * a, (uint32_t)nd->b.lo[a]);
            put32(q + 12u + 4u * a, (uint32_t)nd->b.hi[a]);
        }
        put32(q + 24, nd->left_first);
        put32(q + 28, nd->count);
    }
}

lt_status_t lt_sblob_write(const lt_tri_q16_t *tris, const lt_bvh_t *bvh, uint32_t max_leaf,
                           const lt_sblob_view_t *v, void *out, size_t bytes)
{
    uint8_t *b = (uint8_t *)out;
    uint32_t n, k, h[32];
    size_t total, i;
    unsigned a;
    if (tris == (const lt_tri_q16_t *)0 || bvh == (const lt_bvh_t *)0 || v == (const lt_sblob_view_t *)0 ||
        b == (uint8_t *)0 || bvh->num != LT_BVH_NUM_Q16 || bvh->ntris == 0 || bvh->nnodes == 0)
        return LT_E_ARG;
    n = bvh->ntris;
    total = lt_sblob_size(n, bvh->nnodes);
    if (bytes < total)
        return LT_E_SPACE;
    for (i = 0; i < total; i++)
        b[i] = 0;
    write_scene(b, tris, bvh, LT_SBLOB_HEADER_BYTES, off_nodes(n), off_idx(n, bvh->nnodes));
    for (k = 0; k < 32u; k++)
        h[k] = 0;
    h[LT_SB_MAGIC] = LT_SBLOB_MAGIC;
    h[LT_SB_VERSION] = LT_SBLOB_VERSION;
    h[LT_SB_HEADER] = LT_SBLOB_HEADER_BYTES;
    h[LT_SB_BYTES] = (uint32_t)total;
    h[LT_SB_NTRIS] = n;
    h[LT_SB_NNODES] = bvh->nnodes;
    h[LT_SB_OFF_TRIS] = LT_SBLOB_HEADER_BYTES;
    h[LT_SB_OFF_NODES] = (uint32_t)off_nodes(n);
    h[LT_SB_OFF_IDX] = (uint32_t)off_idx(n, bvh->nnodes);
    h[LT_SB_WIDTH] = v->width;
    h[LT_SB_HEIGHT] = v->height;
    h[LT_SB_FLAGS] = v->flags;
    h[LT_SB_EPS] = (uint32_t)v->eps;
    for (a = 0; a < 3u; a++) {
        h[LT_SB_EYE + a] = (uint32_t)v->eye[a];
        h[LT_SB_D00 + a] = (uint32_t)v->d00[a];
        h[LT_SB_DX + a] = (uint32_t)v->dx[a];
        h[LT_SB_DY + a] = (uint32_t)v->dy[a];
        h[LT_SB_LIGHT + a] = (uint32_t)v->light[a];
    }
    h[LT_SB_DEPTH] = bvh->depth;
    h[LT_SB_LEAF] = max_leaf;
    h[LT_SB_SCALE] = v->scale;
    for (k = 0; k < 32u; k++)
        put32(b + 4u * k, h[k]);
    put32(b + 4u * LT_SB_SUM, lt_sblob_sum(b, total));
    return LT_OK;
}

/* FNV-1a of bytes with word w taken as zero. */
static uint32_t sum_without(const void *p, size_t bytes, unsigned w)
{
    const uint8_t *b = (const uint8_t *)p;
    static const uint8_t zero[4] = {0, 0, 0, 0};
    uint32_t h = lt_sblob_fnv(LT_SBLOB_FNV0, b, 4u * w);
    h = lt_sblob_fnv(h, zero, 4);
    return lt_sblob_fnv(h, b + 4u * (w + 1u), bytes - 4u * (w + 1u));
}

uint32_t lt_sblob_sum(const void *p, size_t bytes)
{
    return sum_without(p, bytes, LT_SB_SUM);
}

/* |x| <= 2^LT_CFG_GEOM_MAX_LOG2 units, in s15.16 raw */
#define GEOM_RAW ((int64_t)1 << (LT_CFG_GEOM_MAX_LOG2 + 16))
#define DIR_PART ((int64_t)1 << 29)

static int in_geom(int64_t x)
{
    return x >= -GEOM_RAW && x <= GEOM_RAW;
}

static int64_t abs64(int64_t x)
{
    return x < 0 ? -x : x;
}

/* A section of n items of `size` bytes at word w's offset: inside the blob, after the header,
 * 4-byte aligned. */
static int section_ok(const uint32_t *h, unsigned w, uint32_t n, uint32_t size)
{
    uint64_t off = h[w], end = off + (uint64_t)n * size;
    return off >= LT_SBLOB_HEADER_BYTES && (off & 3u) == 0 && end <= h[LT_SB_BYTES];
}

static lt_sblob_err_t fail(lt_sblob_t *s, lt_sblob_err_t e, uint32_t where)
{
    s->bad = where;
    return e;
}

/* The triangle, node and index sections (their layout already checked): every vertex inside the
 * geometry bound, every index below nt, every node slot but the unused 1 a leaf whose triangles
 * lie inside idx[] or an interior node whose children come after it (no cycle) inside the node
 * array; then the tree handle. */
static lt_sblob_err_t check_scene(const uint8_t *b, uint32_t nt, uint32_t nn, uint32_t off_tris,
                                  uint32_t off_nodes, uint32_t off_idx, uint32_t depth,
                                  uint32_t leaf, lt_bvh_t *bvh, const lt_tri_q16_t **tris,
                                  uint32_t *bad)
{
    const lt_tri_q16_t *t0 = (const lt_tri_q16_t *)(const void *)(b + off_tris);
    const lt_bvh_node_q16_t *nodes = (const lt_bvh_node_q16_t *)(const void *)(b + off_nodes);
    const uint32_t *idx = (const uint32_t *)(const void *)(b + off_idx);
    uint32_t i, a;
    for (i = 0; i < nt; i++) {
        const lt_tri_q16_t *t = &t0[i];
        *bad = i;
        for (a = 0; a < 3u; a++)
            if (!in_geom(t->v0[a]) || !in_geom((int64_t)t->v0[a] + t->e1[a]) ||
                !in_geom((int64_t)t->v0[a] + t->e2[a]))
                return LT_SBLOB_E_GEOMETRY;
        if (idx[i] >= nt)
            return LT_SBLOB_E_TREE;
    }
    *bad = 0;
    if (depth > LT_BVH_MAX_DEPTH || leaf == 0 || leaf > LT_BVH_MAX_LEAF)
        return LT_SBLOB_E_TREE;
    for (i = 0; i < nn; i++) {
        const lt_bvh_node_q16_t *n = &nodes[i];
        if (i == 1u)
            continue;
        *bad = i;
        if (n->count != 0u) {
            if (n->count > leaf || n->left_first > nt || n->count > nt - n->left_first)
                return LT_SBLOB_E_TREE;
        } else if (n->left_first <= i || n->left_first >= nn - 1u || n->left_first == 1u) {
            return LT_SBLOB_E_TREE;
        }
    }
    *bad = 0;
    *tris = t0;
    bvh->nodes = nodes;
    bvh->idx = idx;
    bvh->nnodes = nn;
    bvh->ntris = nt;
    bvh->depth = depth;
    bvh->leaves = 0;
    bvh->num = LT_BVH_NUM_Q16;
    bvh->bad_tri = 0;
    bvh->isect = LT_ISECT_WT;
    bvh->bytes = (size_t)nn * sizeof(lt_bvh_node_q16_t) + (size_t)nt * 4u;
    bvh->stats = (lt_bvh_stats_t *)0;
    return LT_SBLOB_OK;
}

/* The checks every blob kind shares, in this order: the header's length, magic, version and size,
 * the byte count against the buffer, the checksum (word w_sum taken as 0), and the triangle and
 * node counts (words 4 and 5 of both kinds). *bad names the word or value concerned. */
static lt_sblob_err_t check_head(const void *p, size_t bytes, uint32_t magic, uint32_t version,
                                 uint32_t hdr, unsigned w_sum, uint32_t *bad)
{
    const uint32_t *h = (const uint32_t *)p;
    uint32_t nt, nn;
    *bad = 0;
    if (bytes < hdr)
        return *bad = (uint32_t)bytes, LT_SBLOB_E_SHORT;
    if (h[0] != magic)
        return *bad = h[0], LT_SBLOB_E_MAGIC;
    if (h[1] != version)
        return *bad = h[1], LT_SBLOB_E_VERSION;
    if (h[2] != hdr)
        return *bad = 2, LT_SBLOB_E_LAYOUT;
    if (h[3] > bytes || h[3] < hdr)
        return *bad = h[3], LT_SBLOB_E_SHORT;
    if (sum_without(p, h[3], w_sum) != h[w_sum])
        return *bad = h[w_sum], LT_SBLOB_E_SUM;
    nt = h[4];
    nn = h[5];
    if (nt == 0 || nt > LT_BVH_MAX_TRIS || nn == 0 || nn > 2u * nt)
        return *bad = nt == 0 || nt > LT_BVH_MAX_TRIS ? 4u : 5u, LT_SBLOB_E_TREE;
    return LT_SBLOB_OK;
}

/* the flags a blob may carry in this build */
#define SB_FLAGS (LT_SBLOB_F_SHADOWS | (LT_CFG_WT32 ? LT_SBLOB_F_WT32 : 0u))

lt_sblob_err_t lt_sblob_open(const void *p, size_t bytes, lt_sblob_t *s)
{
    const uint32_t *h = (const uint32_t *)p;
    const uint8_t *b = (const uint8_t *)p;
    lt_sblob_err_t e;
    uint32_t nt, nn, a;
    s->bad = 0;
    e = check_head(p, bytes, LT_SBLOB_MAGIC, LT_SBLOB_VERSION, LT_SBLOB_HEADER_BYTES, LT_SB_SUM,
                   &s->bad);
    if (e != LT_SBLOB_OK)
        return e;
    nt = h[LT_SB_NTRIS];
    nn = h[LT_SB_NNODES];
    if (!section_ok(h, LT_SB_OFF_TRIS, nt, (uint32_t)sizeof(lt_tri_q16_t)))
        return fail(s, LT_SBLOB_E_LAYOUT, LT_SB_OFF_TRIS);
    if (!section_ok(h, LT_SB_OFF_NODES, nn, (uint32_t)sizeof(lt_bvh_node_q16_t)))
        return fail(s, LT_SBLOB_E_LAYOUT, LT_SB_OFF_NODES);
    if (!section_ok(h, LT_SB_OFF_IDX, nt, 4u))
        return fail(s, LT_SBLOB_E_LAYOUT, LT_SB_OFF_IDX);

    s->width = h[LT_SB_WIDTH];
    s->height = h[LT_SB_HEIGHT];
    s->flags = h[LT_SB_FLAGS];
    s->eps = (lt_q16_t)h[LT_SB_EPS];
    if (s->width == 0 || s->width > LT_SBLOB_MAX_RES || s->height == 0 ||
        s->height > LT_SBLOB_MAX_RES || (s->flags & ~SB_FLAGS) != 0 || s->eps <= 0 ||
        s->eps > (lt_q16_t)LT_Q16_ONE * 256)
        return fail(s, LT_SBLOB_E_IMAGE, 0);
    s->tiles_x = (s->width + LT_SBLOB_TILE - 1u) / LT_SBLOB_TILE;
    s->tiles_y = (s->height + LT_SBLOB_TILE - 1u) / LT_SBLOB_TILE;
    for (a = 0; a < 3u; a++) {
        s->eye[a] = (lt_q16_t)h[LT_SB_EYE + a];
        s->light[a] = (lt_q16_t)h[LT_SB_LIGHT + a];
        s->d00[a] = (int32_t)h[LT_SB_D00 + a];
        s->dx[a] = (int32_t)h[LT_SB_DX + a];
        s->dy[a] = (int32_t)h[LT_SB_DY + a];
        if (!in_geom(s->eye[a]) || !in_geom(s->light[a]))
            return fail(s, LT_SBLOB_E_GEOMETRY, LT_SB_EYE);
        /* each part of d00 + x dx + y dy within 2^29: the sum stays inside int32 */
        if (abs64(s->d00[a]) > DIR_PART || abs64(s->dx[a]) * (s->width - 1u) > DIR_PART ||
            abs64(s->dy[a]) * (s->height - 1u) > DIR_PART)
            return fail(s, LT_SBLOB_E_CAMERA, LT_SB_D00 + a);
    }
    {
        /* no pixel direction is zero: at the four corners, the direction's component along the
           centre pixel's direction keeps one sign (a plane through the origin cannot separate
           the corners of a convex pixel rectangle from its interior, and every pixel's direction
           is an average of the corners'). Exact in 64 bits: with m2 = 2 d00 + (w - 1) dx +
           (h - 1) dy (twice the centre direction, |.| <= 2^31 per axis, each part within 2^29)
           and a corner's parts below 2^30.6, each product is below 2^62 and two of them sum
           inside int64; the third is added only when its sign differs (no overflow), else the
           sum's sign is already that sign. Along d00 instead, views whose corners are 90
           degrees or more apart (the teapot's default view at 13x4) were refused although none
           of their directions is zero. */
        int64_t dot[4], m2[3];
        unsigned c;
        for (a = 0; a < 3u; a++)
            m2[a] = 2 * (int64_t)s->d00[a] + ((int64_t)s->width - 1) * s->dx[a] +
                    ((int64_t)s->height - 1) * s->dy[a];
        for (c = 0; c < 4u; c++) {
            int64_t x = (c & 1u) ? (int64_t)s->width - 1 : 0, y = (c & 2u) ? (int64_t)s->height - 1 : 0;
            int64_t pr[3];
            for (a = 0; a < 3u; a++)
                pr[a] = ((int64_t)s->d00[a] + x * s->dx[a] + y * s->dy[a]) * m2[a];
            dot[c] = pr[0] + pr[1];
            if ((dot[c] > 0) != (pr[2] > 0) || dot[c] == 0)
                dot[c] += pr[2];
        }
        for (c = 0; c < 4u; c++)
            if (dot[c] <= 0)
                return fail(s, LT_SBLOB_E_CAMERA, c);
    }

    e = check_scene(b, nt, nn, h[LT_SB_OFF_TRIS], h[LT_SB_OFF_NODES], h[LT_SB_OFF_IDX],
                    h[LT_SB_DEPTH], h[LT_SB_LEAF], &s->bvh, &s->tris, &s->bad);
    if (LT_CFG_WT32 && e == LT_SBLOB_OK && (s->flags & LT_SBLOB_F_WT32) != 0)
        s->bvh.isect = LT_ISECT_WT32_G(lt_wt32_shift_q16(s->tris, s->bvh.ntris));
    return e;
}

/* The unit direction through pixel (x, y) inside the image (never zero: lt_sblob_open checked). */
static void pixel_dir(const lt_sblob_t *s, uint32_t x, uint32_t y, lt_q30_t n[3])
{
    lt_q16_t d[3];
    unsigned a;
    for (a = 0; a < 3u; a++)
        d[a] = (lt_q16_t)(s->d00[a] + (int32_t)x * s->dx[a] + (int32_t)y * s->dy[a]);
    if (lt_q16_normalize3(d, n) != LT_OK) {
        n[0] = LT_Q30_ONE;
        n[1] = n[2] = 0;
    }
}

/* The shadow ray of a hit at distance t along the unit direction d from the eye: origin p, unit
 * direction n to the light, interval [eps, distance - eps]. Returns 1, or 0 when the light is
 * within 2 eps of the hit point (no ray). */
static int shadow_ray(const lt_sblob_t *s, const lt_q30_t d[3], lt_q16_t t, lt_q16_t p[3],
                      lt_q30_t n[3], lt_q16_t *tmax)
{
    lt_q16_t v[3], len = 0;
    unsigned a;
    for (a = 0; a < 3u; a++) {
        p[a] = lt_q16_add_sat(s->eye[a], lt_q16_mul_q30_sat(t, d[a]));
        v[a] = lt_q16_sub_sat(s->light[a], p[a]);
    }
    n[0] = LT_Q30_ONE;
    n[1] = n[2] = 0;
    *tmax = s->eps;
    if (lt_q16_normalize3(v, n) != LT_OK)
        return 0;
    for (a = 0; a < 3u; a++)
        len = lt_q16_add_sat(len, lt_q16_mul_q30_sat(v[a], n[a]));
    if (len <= 2 * s->eps)
        return 0;
    *tmax = len - s->eps;
    return 1;
}

/* The primary packet of the 4x4 pixels at (px, py): lanes outside the image are left out of the
 * returned mask (and given a harmless ray). */
static lt_mask16_t primary_packet(const lt_sblob_t *s, uint32_t px, uint32_t py,
                                  lt_ray16_q16_t *r)
{
    lt_mask16_t k = 0;
    int i;
    for (i = 0; i < LT_LANES; i++) {
        uint32_t x = px + (uint32_t)(i % 4), y = py + (uint32_t)(i / 4);
        lt_q30_t n[3] = {LT_Q30_ONE, 0, 0};
        if (x < s->width && y < s->height) {
            pixel_dir(s, x, y, n);
            k = (lt_mask16_t)(k | (1u << i));
        }
        r->ox.l[i] = s->eye[0];
        r->oy.l[i] = s->eye[1];
        r->oz.l[i] = s->eye[2];
        r->dx.l[i] = n[0];
        r->dy.l[i] = n[1];
        r->dz.l[i] = n[2];
        r->tmin.l[i] = 0;
        r->tmax.l[i] = LT_Q16_MAX - 1;
    }
    lt_ray16_q16_setup(r);
    return k;
}

/* Shadow rays from the hits of pr (lanes of k with an id) towards the light. Returns the lanes
 * that have one. */
static lt_mask16_t shadow_packet(const lt_sblob_t *s, const lt_ray16_q16_t *pr,
                                 const lt_hit16_t *hit, lt_mask16_t k, lt_ray16_q16_t *r)
{
    lt_mask16_t m = 0;
    int i;
    for (i = 0; i < LT_LANES; i++) {
        lt_q16_t p[3], tmax;
        lt_q30_t n[3];
        const lt_q30_t d[3] = {pr->dx.l[i], pr->dy.l[i], pr->dz.l[i]};
        if (shadow_ray(s, d, pr->tmax.l[i], p, n, &tmax) && (((unsigned)k >> i) & 1u) &&
            hit->id.l[i] >= 0)
            m = (lt_mask16_t)(m | (1u << i));
        r->ox.l[i] = p[0];
        r->oy.l[i] = p[1];
        r->oz.l[i] = p[2];
        r->dx.l[i] = n[0];
        r->dy.l[i] = n[1];
        r->dz.l[i] = n[2];
        r->tmin.l[i] = s->eps;
        r->tmax.l[i] = ((unsigned)m >> i) & 1u ? tmax : s->eps;
    }
    lt_ray16_q16_setup(r);
    return m;
}

/* One 4x4 group of pixels as 16-ray packets: the results of the lanes of the returned mask into
 * id/dist/occ (indexed by lane). */
static lt_status_t group_packets(const lt_sblob_t *s, uint32_t px, uint32_t py,
                                 lt_sblob_clock_fn ticks, lt_sblob_tile_t *out, lt_mask16_t *km,
                                 int32_t id[16], lt_q16_t dist[16], uint8_t occ[16])
{
    lt_ray16_q16_t r, sr;
    lt_hit16_t hit;
    lt_mask16_t k, m, o = 0;
    uint64_t t0 = 0, t1 = 0;
    lt_status_t st;
    int i;
    if (ticks != (lt_sblob_clock_fn)0)
        t0 = ticks(LT_STAGE_PRIMARY);
    *km = k = primary_packet(s, px, py, &r);
    if (k == 0) {
        if (ticks != (lt_sblob_clock_fn)0)
            (void)ticks(LT_STAGE_UNTIMED);
        return LT_OK;
    }
    st = lt_bvh_trace16_q16(&s->bvh, s->tris, &r, k, &hit);
    if (st != LT_OK)
        return st;
    if (ticks != (lt_sblob_clock_fn)0) {
        t1 = ticks((s->flags & LT_SBLOB_F_SHADOWS) ? LT_STAGE_SHADOW : LT_STAGE_UNTIMED);
        out->t_primary += t1 - t0;
    }
    if (s->flags & LT_SBLOB_F_SHADOWS) {
        m = shadow_packet(s, &r, &hit, k, &sr);
        if (m != 0) {
            out->srays += lt__popcount32(m);
            st = lt_bvh_occluded16_q16(&s->bvh, s->tris, &sr, m, &o);
            if (st != LT_OK)
                return st;
        }
        if (ticks != (lt_sblob_clock_fn)0)
            out->t_shadow += ticks(LT_STAGE_UNTIMED) - t1;
    }
    for (i = 0; i < LT_LANES; i++) {
        id[i] = hit.id.l[i];
        dist[i] = hit.id.l[i] >= 0 ? r.tmax.l[i] : 0;
        occ[i] = (uint8_t)(((unsigned)o >> i) & 1u);
    }
    return LT_OK;
}

/* The same 4x4 group ray by ray (lt_bvh_trace1_q16 / lt_bvh_occluded1_q16: bit-identical to a
 * packet lane, so the results equal group_packets'). */
static lt_status_t group_single(const lt_sblob_t *s, uint32_t px, uint32_t py,
                                lt_sblob_clock_fn ticks, lt_sblob_tile_t *out, lt_mask16_t *km,
                                int32_t id[16], lt_q16_t dist[16], uint8_t occ[16])
{
    int i;
    *km = 0;
    for (i = 0; i < LT_LANES; i++) {
        uint32_t x = px + (uint32_t)(i % 4), y = py + (uint32_t)(i / 4);
        lt_ray1_q16_t r;
        uint64_t t0 = 0, t1 = 0;
        int32_t hid = -1;
        int o = 0;
        lt_status_t st;
        if (x >= s->width || y >= s->height)
            continue;
        *km = (lt_mask16_t)(*km | (1u << i));
        if (ticks != (lt_sblob_clock_fn)0)
            t0 = ticks(LT_STAGE_PRIMARY1);
        r.o[0] = s->eye[0];
        r.o[1] = s->eye[1];
        r.o[2] = s->eye[2];
        pixel_dir(s, x, y, r.d);
        r.tmin = 0;
        r.tmax = LT_Q16_MAX - 1;
        lt_ray1_q16_setup(&r);
        st = lt_bvh_trace1_q16(&s->bvh, s->tris, &r, &hid);
        if (st != LT_OK)
            return st;
        if (ticks != (lt_sblob_clock_fn)0) {
            t1 = ticks((s->flags & LT_SBLOB_F_SHADOWS) && hid >= 0 ? LT_STAGE_SHADOW1 : LT_STAGE_UNTIMED);
            out->t_primary += t1 - t0;
        }
        id[i] = hid;
        dist[i] = hid >= 0 ? r.tmax : 0;
        if ((s->flags & LT_SBLOB_F_SHADOWS) && hid >= 0) {
            lt_ray1_q16_t sr;
            lt_q30_t d[3];
            d[0] = r.d[0];
            d[1] = r.d[1];
            d[2] = r.d[2];
            if (shadow_ray(s, d, r.tmax, sr.o, sr.d, &sr.tmax)) {
                out->srays++;
                sr.tmin = s->eps;
                lt_ray1_q16_setup(&sr);
                st = lt_bvh_occluded1_q16(&s->bvh, s->tris, &sr, &o);
                if (st != LT_OK)
                    return st;
            }
            if (ticks != (lt_sblob_clock_fn)0)
                out->t_shadow += ticks(LT_STAGE_UNTIMED) - t1;
        }
        occ[i] = (uint8_t)o;
    }
    return LT_OK;
}

lt_status_t lt_sblob_trace_tile(const lt_sblob_t *s, uint32_t t, int single,
                                lt_sblob_clock_fn ticks, lt_sblob_tile_t *out)
{
    uint32_t tx, ty;
    uint32_t h = LT_SBLOB_FNV0;
    unsigned p, q, i;
    /* the tile's results in raster order: id, distance and shadow bit of each pixel */
    int32_t id[LT_SBLOB_TILE * LT_SBLOB_TILE];
    lt_q16_t dist[LT_SBLOB_TILE * LT_SBLOB_TILE];
    uint8_t occ[LT_SBLOB_TILE * LT_SBLOB_TILE];
    out->hash = 0;
    out->rays = out->hits = out->srays = out->occluded = 0;
    out->t_primary = out->t_shadow = 0;
    if (t >= s->tiles_x * s->tiles_y)
        return LT_E_ARG;
    tx = (t % s->tiles_x) * LT_SBLOB_TILE;
    ty = (t / s->tiles_x) * LT_SBLOB_TILE;
    for (p = 0; p < 16u; p++) {
        int32_t gid[16];
        lt_q16_t gdist[16];
        uint8_t gocc[16];
        lt_mask16_t k;
        uint32_t px = tx + 4u * (p % 4u), py = ty + 4u * (p / 4u);
        lt_status_t st = single ? group_single(s, px, py, ticks, out, &k, gid, gdist, gocc)
                                : group_packets(s, px, py, ticks, out, &k, gid, gdist, gocc);
        if (st != LT_OK)
            return st;
        for (i = 0; i < (unsigned)LT_LANES; i++) {
            unsigned at = (4u * (p / 4u) + i / 4u) * LT_SBLOB_TILE + 4u * (p % 4u) + i % 4u;
            if (!(((unsigned)k >> i) & 1u))
                continue;
            out->rays++;
            id[at] = gid[i];
            dist[at] = gdist[i];
            occ[at] = gocc[i];
            out->hits += gid[i] >= 0;
            out->occluded += gocc[i];
        }
    }
    /* hash the pixels inside the image in raster order */
    for (q = 0; q < LT_SBLOB_TILE; q++)
        for (p = 0; p < LT_SBLOB_TILE; p++) {
            unsigned at = q * LT_SBLOB_TILE + p;
            if (tx + p >= s->width || ty + q >= s->height)
                continue;
            h = fnv_word(h, (uint32_t)id[at]);
            h = fnv_word(h, (uint32_t)dist[at]);
            h = fnv_word(h, occ[at]);
            if (out->ids != (int32_t *)0)
                out->ids[at] = id[at];
        }
    out->hash = h;
    return LT_OK;
}

/* ---- frusta blobs ------------------------------------------------------------------------- */

static size_t fb_off_nodes(uint32_t nt)
{
    return align64(LT_FBLOB_HEADER_BYTES + (size_t)nt * sizeof(lt_tri_q16_t));
}

static size_t fb_off_idx(uint32_t nt, uint32_t nn)
{
    return align64(fb_off_nodes(nt) + (size_t)nn * sizeof(lt_bvh_node_q16_t));
}

static size_t fb_off_org(uint32_t nt, uint32_t nn)
{
    return align64(fb_off_idx(nt, nn) + (size_t)nt * 4u);
}

size_t lt_fblob_size(uint32_t ntris, uint32_t nnodes)
{
    return align64(fb_off_org(ntris, nnodes) + 256u * 12u);
}

lt_status_t lt_fblob_write(const lt_tri_q16_t *tris, const lt_bvh_t *bvh, const lt_q16_t org[768],
                           uint32_t h[64], void *out, size_t bytes)
{
    uint8_t *b = (uint8_t *)out;
    size_t total, i;
    uint32_t n, k;
    if (tris == (const lt_tri_q16_t *)0 || bvh == (const lt_bvh_t *)0 || org == (const lt_q16_t *)0 ||
        h == (uint32_t *)0 || b == (uint8_t *)0 || bvh->num != LT_BVH_NUM_Q16 || bvh->ntris == 0 ||
        bvh->nnodes == 0)
        return LT_E_ARG;
    n = bvh->ntris;
    total = lt_fblob_size(n, bvh->nnodes);
    if (bytes < total)
        return LT_E_SPACE;
    for (i = 0; i < total; i++)
        b[i] = 0;
    write_scene(b, tris, bvh, LT_FBLOB_HEADER_BYTES, fb_off_nodes(n), fb_off_idx(n, bvh->nnodes));
    for (i = 0; i < 768u; i++)
        put32(b + fb_off_org(n, bvh->nnodes) + 4u * i, (uint32_t)org[i]);
    h[LT_FB_MAGIC] = LT_FBLOB_MAGIC;
    h[LT_FB_VERSION] = LT_FBLOB_VERSION;
    h[LT_FB_HEADER] = LT_FBLOB_HEADER_BYTES;
    h[LT_FB_BYTES] = (uint32_t)total;
    h[LT_FB_NTRIS] = n;
    h[LT_FB_NNODES] = bvh->nnodes;
    h[LT_FB_OFF_TRIS] = LT_FBLOB_HEADER_BYTES;
    h[LT_FB_OFF_NODES] = (uint32_t)fb_off_nodes(n);
    h[LT_FB_OFF_IDX] = (uint32_t)fb_off_idx(n, bvh->nnodes);
    h[LT_FB_OFF_ORG] = (uint32_t)fb_off_org(n, bvh->nnodes);
    h[LT_FB_DEPTH] = bvh->depth;
    h[LT_FB_SUM] = 0;
    for (k = 0; k < 64u; k++)
        put32(b + 4u * k, h[k]);
    put32(b + 4u * LT_FB_SUM, sum_without(b, total, LT_FB_SUM));
    return LT_OK;
}

lt_sblob_err_t lt_fblob_open(const void *p, size_t bytes, lt_fblob_t *f)
{
    const uint32_t *h = (const uint32_t *)p;
    const uint8_t *b = (const uint8_t *)p;
    lt_frusta_light_q16_t l;
    lt_qmc_sets_t sets;
    lt_sblob_err_t e;
    uint32_t nt, nn, i;
    e = check_head(p, bytes, LT_FBLOB_MAGIC, LT_FBLOB_VERSION, LT_FBLOB_HEADER_BYTES, LT_FB_SUM,
                   &f->bad);
    if (e != LT_SBLOB_OK)
        return e;
    nt = h[LT_FB_NTRIS];
    nn = h[LT_FB_NNODES];
    if (h[LT_FB_OFF_TRIS] < LT_FBLOB_HEADER_BYTES || h[LT_FB_OFF_NODES] < LT_FBLOB_HEADER_BYTES ||
        h[LT_FB_OFF_IDX] < LT_FBLOB_HEADER_BYTES || h[LT_FB_OFF_ORG] < LT_FBLOB_HEADER_BYTES ||
        !section_ok(h, LT_FB_OFF_TRIS, nt, (uint32_t)sizeof(lt_tri_q16_t)) ||
        !section_ok(h, LT_FB_OFF_NODES, nn, (uint32_t)sizeof(lt_bvh_node_q16_t)) ||
        !section_ok(h, LT_FB_OFF_IDX, nt, 4u) || !section_ok(h, LT_FB_OFF_ORG, 768u, 4u))
        return LT_SBLOB_E_LAYOUT;
    f->spp = h[LT_FB_SPP];
    if ((f->spp != 4u && f->spp != 8u && f->spp != 16u) || h[LT_FB_QMC] > (uint32_t)LT_QMC_LP)
        return LT_SBLOB_E_IMAGE;
    f->org = (const lt_q16_t *)(const void *)(b + h[LT_FB_OFF_ORG]);
    for (i = 0; i < 768u; i++)
        if (!in_geom(f->org[i])) {
            f->bad = i / 3u;
            return LT_SBLOB_E_GEOMETRY;
        }
    for (i = 0; i < 8u; i++)
        f->lit[i] = h[LT_FB_LIT + i];
    for (i = 0; i < 3u; i++) {
        l.c[i] = (lt_q16_t)h[LT_FB_LIGHT + i];
        l.eu[i] = (lt_q16_t)h[LT_FB_LIGHT + 3u + i];
        l.ev[i] = (lt_q16_t)h[LT_FB_LIGHT + 6u + i];
    }
    l.flags = h[LT_FB_LFLAGS];
    l.end_shift = h[LT_FB_END_SHIFT];
    if (lt_qmc_interleave4x4((lt_qmc_kind_t)h[LT_FB_QMC], h[LT_FB_SCRAMBLE], &sets) != LT_OK ||
        lt_frusta_table_q16(&l, &sets, &f->tb) != LT_OK)
        return LT_SBLOB_E_IMAGE;
    f->ref = h[LT_FB_REF];
    f->scene_tris = h[LT_FB_SCENE_TRIS];
    f->bx = h[LT_FB_BX];
    f->by = h[LT_FB_BY];
    e = check_scene(b, nt, nn, h[LT_FB_OFF_TRIS], h[LT_FB_OFF_NODES], h[LT_FB_OFF_IDX],
                    h[LT_FB_DEPTH], h[LT_FB_LEAF], &f->bvh, &f->tris, &f->bad);
    if (e == LT_SBLOB_OK)
        f->bvh.isect = LT_ISECT_WT;
    return e;
}

uint32_t lt_fblob_tile_hash(const uint8_t lit[16], const uint16_t occl[16])
{
    uint32_t h = LT_SBLOB_FNV0;
    unsigned i;
    for (i = 0; i < 16u; i++) {
        h = fnv_word(h, lit[i]);
        h = fnv_word(h, lit[i] ? occl[i] : 0u);
    }
    return h;
}

uint32_t lt_fblob_block_hash(const uint32_t tile_hash[16])
{
    uint32_t h = LT_SBLOB_FNV0;
    unsigned t;
    for (t = 0; t < 16u; t++)
        h = fnv_word(h, tile_hash[t]);
    return h;
}

lt_status_t lt_fblob_trace_tile(const lt_fblob_t *f, uint32_t t, lt_sblob_clock_fn ticks,
                                lt_fblob_tile_t *out)
{
    lt_frusta16_q16_t F;
    uint8_t lit[16];
    uint16_t occl[16];
    lt_mask16_t k = 0;
    uint64_t t0 = 0;
    lt_status_t st;
    unsigned i;
    out->hash = 0;
    out->lit = out->occluded = 0;
    out->ticks = 0;
    if (t >= 16u)
        return LT_E_ARG;
    if (ticks != (lt_sblob_clock_fn)0)
        t0 = ticks(LT_STAGE_FRUSTA);
    for (i = 0; i < 16u; i++) {
        unsigned x = 4u * (t % 4u) + i % 4u, y = 4u * (t / 4u) + i / 4u, q = y * 16u + x;
        lit[i] = (uint8_t)((f->lit[q / 32u] >> (q % 32u)) & 1u);
        if (lit[i])
            k = (lt_mask16_t)(k | (1u << i));
        F.ox.l[i] = lit[i] ? f->org[3u * q] : 0;
        F.oy.l[i] = lit[i] ? f->org[3u * q + 1u] : 0;
        F.oz.l[i] = lit[i] ? f->org[3u * q + 2u] : 0;
    }
    (void)lt_frusta_setup16_q16(&f->tb, k, &F);
    if (f->spp < 16u)
        (void)lt_frusta_restrict16_q16(&f->tb, (uint16_t)((1u << f->spp) - 1u), &F);
    st = lt_frusta_occluded16_q16(&f->bvh, f->tris, &f->tb, &F);
    if (st != LT_OK)
        return st;
    if (ticks != (lt_sblob_clock_fn)0)
        out->ticks = ticks(LT_STAGE_UNTIMED) - t0;
    for (i = 0; i < 16u; i++) {
        occl[i] = lit[i] ? F.occl[i] : 0u;
        out->lit += lit[i];
        out->occluded += lt__popcount32(occl[i]);
    }
    out->hash = lt_fblob_tile_hash(lit, occl);
    return LT_OK;
}
