/* reproj_app.c - the reprojection app (reproj_app.h): blob validation, quadtree build
 * (lt_qt_build_q30) in the caller's memory, then per output tile its 4x4 packets through
 * lt_reproj_rays16_q30 and lt_qt_trace16_q30 (Widmer et al. 2015, section 5), a line per finished
 * tile. Integer only; lines are formatted here, so every build prints the same bytes.
 * Builds: firmware (freestanding), host.
 */
#include "reproj_app.h"

#include "lt/lt_fx.h"

/* packets at the start of the caller's memory, then the quadtree arena */
#define RP_RAY_OFF 0u
#define RP_HIT_OFF 512u
#define RP_ARENA_OFF 1024u
LT_STATIC_ASSERT(sizeof(lt_qray16_q30_t) <= RP_HIT_OFF - RP_RAY_OFF, "ray packet fits");
LT_STATIC_ASSERT(sizeof(lt_qhit16_q30_t) <= RP_ARENA_OFF - RP_HIT_OFF, "hit packet fits");

#define FNV_BASIS 2166136261u
#define FNV_PRIME 16777619u

/* the value's 4 bytes, least significant first (tests/vectors/lt_reproj_tile.h's ltrt_fnv) */
static uint32_t fnv_u32(uint32_t h, uint32_t v)
{
    unsigned i;
    for (i = 0; i < 4; i++) {
        h ^= (v >> (8u * i)) & 0xFFu;
        h *= FNV_PRIME;
    }
    return h;
}

/* ---- output lines ---------------------------------------------------------------------------- */

typedef struct line {
    char b[192];
    unsigned n;
} line_t;

static void l_str(line_t *l, const char *s)
{
    while (*s != '\0' && l->n + 2u < sizeof l->b)
        l->b[l->n++] = *s++;
}

static void l_u64(line_t *l, uint64_t v)
{
    char t[24];
    unsigned n = 0;
    do {
        t[n++] = (char)('0' + (int)(v % 10u));
        v /= 10u;
    } while (v != 0u);
    while (n > 0u && l->n + 2u < sizeof l->b)
        l->b[l->n++] = t[--n];
}

static void l_hex(line_t *l, uint32_t v)
{
    static const char dig[] = "0123456789abcdef";
    int i;
    l_str(l, "0x");
    for (i = 28; i >= 0; i -= 4)
        if (l->n + 2u < sizeof l->b)
            l->b[l->n++] = dig[(v >> (unsigned)i) & 0xFu];
}

/* v / 100 with two decimals */
static void l_cent(line_t *l, uint64_t v)
{
    l_u64(l, v / 100u);
    l_str(l, ".");
    l_u64(l, (v / 10u) % 10u);
    l_u64(l, v % 10u);
}

static void l_out(const lt_rpapp_port_t *port, line_t *l)
{
    l->b[l->n++] = '\n';
    l->b[l->n] = '\0';
    port->puts(port->ctx, l->b);
    l->n = 0;
}

static int fail(const lt_rpapp_port_t *port, int code, const char *what)
{
    line_t l;
    l.n = 0;
    l_str(&l, "error ");
    l_u64(&l, (uint64_t)code);
    l_str(&l, ": ");
    l_str(&l, what);
    l_out(port, &l);
    return code;
}

/* ---- validation ------------------------------------------------------------------------------ */

static const char *const e_text[] = {
    "blob shorter than its header",                           /* E_SHORT */
    "blob or memory not 64-byte aligned",                     /* E_ALIGN */
    "bad magic: not a reprojection blob",                     /* E_MAGIC */
    "magic byte-swapped: a blob of the other byte order",     /* E_ENDIAN */
    "unsupported blob version",                               /* E_VERSION */
    "header or blob length differs from the bytes given",     /* E_LENGTH */
    "width, height, layers, node format, depth format or tile out of range", /* E_SIZES */
    "depth array misaligned, overlapping the header or past the end",       /* E_OFFSETS */
    "checksum mismatch: the blob is corrupt",                 /* E_CHECKSUM */
    "the mapping does not fit the depth image",               /* E_MAP */
    "memory too small",                                       /* E_MEMORY */
    "quadtree build failed",                                  /* E_BUILD */
    "trace failed",                                           /* E_TRACE */
};

static const char *err_text(int code)
{
    return code >= LT_RPAPP_E_SHORT && code <= LT_RPAPP_E_TRACE
               ? e_text[code - LT_RPAPP_E_SHORT]
               : "unknown error";
}

/* The header's checks in order; the quadtree's arena bytes into *qt_bytes. Nothing past len is
 * read, and the header is read only after the length and alignment checks. */
static int check_blob(const void *blob, size_t len, size_t *qt_bytes)
{
    const lt_rpb_hdr_t *h = (const lt_rpb_hdr_t *)blob;
    const uint8_t *p = (const uint8_t *)blob;
    uint64_t need, end;
    lt_qt_desc_t d;
    if (blob == 0 || len < (size_t)LT_RPB_HDR_BYTES)
        return LT_RPAPP_E_SHORT;
    if (((uintptr_t)blob & (LT_RPB_ALIGN - 1u)) != 0u)
        return LT_RPAPP_E_ALIGN;
    if (h->magic == LT_RPB_MAGIC_SWAPPED)
        return LT_RPAPP_E_ENDIAN;
    if (h->magic != LT_RPB_MAGIC)
        return LT_RPAPP_E_MAGIC;
    if (h->version != LT_RPB_VERSION)
        return LT_RPAPP_E_VERSION;
    if (h->hdr_bytes != LT_RPB_HDR_BYTES || (uint64_t)h->blob_bytes != (uint64_t)len)
        return LT_RPAPP_E_LENGTH;
    if (h->width < 1u || h->width > LT_QT_MAX_DIM || h->height < 1u ||
        h->height > LT_QT_MAX_DIM || h->layers < 1u || h->layers > LT_QT_MAX_LAYERS ||
        (h->enc != (uint32_t)LT_QT_N64 && h->enc != (uint32_t)LT_QT_N32) ||
        h->depth_format != LT_RPB_DEPTH_W_Q30 || h->tile < 4u || h->tile > 256u ||
        (h->tile & 3u) != 0u || h->reserved != 0u)
        return LT_RPAPP_E_SIZES;
    /* 64-bit sums: a 32-bit size_t cannot wrap here */
    need = (uint64_t)h->width * h->height * h->layers * 4u;
    end = (uint64_t)h->depth_off + h->depth_bytes;
    if ((h->depth_off & (LT_RPB_ALIGN - 1u)) != 0u || h->depth_off < LT_RPB_HDR_BYTES ||
        (uint64_t)h->depth_bytes != need || end > (uint64_t)h->blob_bytes)
        return LT_RPAPP_E_OFFSETS;
    if (lt_rpb_fnv(FNV_BASIS, p + LT_RPB_SUM_FROM, len - LT_RPB_SUM_FROM) != h->checksum)
        return LT_RPAPP_E_CHECKSUM;
    /* the core checks the rest of the mapping (log2 sizes, planes) when it makes the first
       packet; these are what ties it to this depth image */
    if (h->map.src_w != h->width || h->map.src_h != h->height || h->map.dst_w < 1u ||
        h->map.dst_w > LT_QT_MAX_DIM || h->map.dst_h < 1u || h->map.dst_h > LT_QT_MAX_DIM)
        return LT_RPAPP_E_MAP;
    d.width = h->width;
    d.height = h->height;
    d.layers = h->layers;
    d.enc = h->enc;
    if (lt_qt_size(&d, qt_bytes) != LT_OK || *qt_bytes > (size_t)-1 - RP_ARENA_OFF)
        return LT_RPAPP_E_SIZES;
    return LT_RPAPP_OK;
}

int lt_rpapp_mem_bytes(const void *blob, size_t blob_len, size_t *bytes)
{
    size_t qb = 0;
    int e = check_blob(blob, blob_len, &qb);
    if (bytes != 0)
        *bytes = e == LT_RPAPP_OK ? RP_ARENA_OFF + qb : 0u;
    return e;
}

/* ---- the run --------------------------------------------------------------------------------- */

/* Per tile (and summed for the total). */
typedef struct counts {
    uint32_t rays, kept, st[5]; /* pixels, lanes with a segment, per LT_QT_* status */
    uint32_t hit_back;          /* hits on a layer behind layer 0 */
    uint64_t nodes;             /* node visits over the kept lanes */
} counts_t;

static void add_counts(counts_t *a, const counts_t *b)
{
    int i;
    a->rays += b->rays;
    a->kept += b->kept;
    for (i = 0; i < 5; i++)
        a->st[i] += b->st[i];
    a->hit_back += b->hit_back;
    a->nodes += b->nodes;
}

static void l_counts(line_t *l, const counts_t *c, int outside)
{
    l_str(l, "rays ");
    l_u64(l, c->rays);
    l_str(l, " kept ");
    l_u64(l, c->kept);
    l_str(l, " hit ");
    l_u64(l, c->st[LT_QT_HIT]);
    if (outside) {
        l_str(l, " (behind layer 0: ");
        l_u64(l, c->hit_back);
        l_str(l, ")");
    }
    l_str(l, " miss ");
    l_u64(l, c->st[LT_QT_MISS]);
    l_str(l, " disoccluded ");
    l_u64(l, c->st[LT_QT_OCCLUDED]);
    l_str(l, " unknown ");
    l_u64(l, c->st[LT_QT_UNKNOWN]);
    if (c->st[LT_QT_BADRAY] != 0u) {
        l_str(l, " badray ");
        l_u64(l, c->st[LT_QT_BADRAY]);
    }
    if (outside) {
        l_str(l, " outside ");
        l_u64(l, (uint64_t)(c->rays - c->kept));
    }
    l_str(l, " nodes ");
    l_u64(l, c->nodes);
}

/* One tile: its packets row by row, the lanes' results into the hash and the counts; *tk gets
 * the ticks spent in the core's segment and trace calls. Returns OK or an error code. */
static int run_tile(const lt_rpb_hdr_t *h, const lt_qt_t *qt, lt_qray16_q30_t *r,
                    lt_qhit16_q30_t *hit, const lt_rpapp_port_t *port, uint32_t x0, uint32_t y0,
                    uint32_t *hash, counts_t *c, uint64_t *tk)
{
    const lt_reproj_q30_t *m = &h->map;
    uint32_t px, py, hh = FNV_BASIS;
    for (py = y0; py < y0 + h->tile && py < m->dst_h; py += 4u) {
        for (px = x0; px < x0 + h->tile && px < m->dst_w; px += 4u) {
            lt_mask16_t kon = 0, k;
            uint64_t t0 = 0;
            int i;
            for (i = 0; i < LT_LANES; i++)
                if (px + ((uint32_t)i & 3u) < m->dst_w && py + ((uint32_t)i >> 2) < m->dst_h)
                    kon = (lt_mask16_t)(kon | (1u << i));
            k = kon;
            if (port->ticks != 0)
                t0 = port->ticks(port->ctx, LT_STAGE_REPROJ);
            if (lt_reproj_rays16_q30(m, px, py, r, &k) != LT_OK)
                return LT_RPAPP_E_MAP;
            if (k != 0u && (port->single ? lt_qt_trace1_q30(qt, r, k, h->max_steps, hit)
                                         : lt_qt_trace16_q30(qt, r, k, h->max_steps, hit)) != LT_OK)
                return LT_RPAPP_E_TRACE;
            if (port->ticks != 0)
                *tk += port->ticks(port->ctx, LT_STAGE_UNTIMED) - t0;
            hh = fnv_u32(hh, k);
            c->rays += (uint32_t)lt__popcount32(kon);
            c->kept += (uint32_t)lt__popcount32(k);
            for (i = 0; i < LT_LANES; i++) {
                int32_t s;
                if ((((unsigned)k >> i) & 1u) == 0u)
                    continue;
                hh = fnv_u32(hh, (uint32_t)r->x.l[i]);
                hh = fnv_u32(hh, (uint32_t)r->y.l[i]);
                hh = fnv_u32(hh, (uint32_t)r->w.l[i]);
                hh = fnv_u32(hh, (uint32_t)r->dx.l[i]);
                hh = fnv_u32(hh, (uint32_t)r->dy.l[i]);
                hh = fnv_u32(hh, (uint32_t)r->dw.l[i]);
                hh = fnv_u32(hh, (uint32_t)hit->status.l[i]);
                hh = fnv_u32(hh, (uint32_t)hit->t.l[i]);
                hh = fnv_u32(hh, (uint32_t)hit->w.l[i]);
                hh = fnv_u32(hh, (uint32_t)hit->layer.l[i]);
                hh = fnv_u32(hh, (uint32_t)hit->nodes.l[i]);
                s = hit->status.l[i];
                if (s >= 0 && s < 5)
                    c->st[s]++;
                if (s == LT_QT_HIT && hit->layer.l[i] > 0)
                    c->hit_back++;
                c->nodes += (uint32_t)hit->nodes.l[i];
            }
        }
    }
    *hash = hh;
    return LT_RPAPP_OK;
}

int lt_rpapp_run(const lt_rpapp_port_t *port, const void *blob, size_t blob_len, void *mem,
                 size_t mem_bytes)
{
    const lt_rpb_hdr_t *h = (const lt_rpb_hdr_t *)blob;
    lt_qray16_q30_t *r;
    lt_qhit16_q30_t *hit;
    const lt_q30_t *w;
    uint8_t *arena;
    lt_qt_desc_t d;
    lt_qt_params_t prm;
    lt_qt_t qt;
    counts_t tot;
    line_t l;
    size_t qb = 0;
    uint64_t t_build = 0, t_rp = 0;
    uint32_t tx, ty, th = FNV_BASIS;
    int e = check_blob(blob, blob_len, &qb);
    l.n = 0;
    if (e != LT_RPAPP_OK)
        return fail(port, e, err_text(e));
    if (mem == 0 || ((uintptr_t)mem & (LT_RPB_ALIGN - 1u)) != 0u)
        return fail(port, LT_RPAPP_E_ALIGN, err_text(LT_RPAPP_E_ALIGN));
    if (mem_bytes < RP_ARENA_OFF + qb) {
        l_str(&l, "error ");
        l_u64(&l, LT_RPAPP_E_MEMORY);
        l_str(&l, ": memory too small: ");
        l_u64(&l, mem_bytes);
        l_str(&l, " bytes given, ");
        l_u64(&l, RP_ARENA_OFF + qb);
        l_str(&l, " needed");
        l_out(port, &l);
        return LT_RPAPP_E_MEMORY;
    }
    r = (lt_qray16_q30_t *)mem;
    hit = (lt_qhit16_q30_t *)(void *)((uint8_t *)mem + RP_HIT_OFF);
    arena = (uint8_t *)mem + RP_ARENA_OFF;
    /* the depth array stays where it is (read-only data on the boards) */
    w = (const lt_q30_t *)(const void *)((const uint8_t *)blob + h->depth_off);

    l_str(&l, "reproj-blob: source ");
    l_u64(&l, h->width);
    l_str(&l, "x");
    l_u64(&l, h->height);
    l_str(&l, " x ");
    l_u64(&l, h->layers);
    l_str(&l, h->layers == 1u ? " layer " : " layers ");
    l_str(&l, h->enc == (uint32_t)LT_QT_N64 ? "n64" : "n32");
    l_str(&l, ", target ");
    l_u64(&l, h->map.dst_w);
    l_str(&l, "x");
    l_u64(&l, h->map.dst_h);
    l_str(&l, ", tiles ");
    l_u64(&l, h->tile);
    l_str(&l, "x");
    l_u64(&l, h->tile);
    l_str(&l, ", quadtree ");
    l_u64(&l, qb);
    l_str(&l, " bytes, blob ");
    l_u64(&l, blob_len);
    l_str(&l, " bytes checksum ");
    l_hex(&l, h->checksum);
    l_out(port, &l);

    d.width = h->width;
    d.height = h->height;
    d.layers = h->layers;
    d.enc = h->enc;
    prm = h->params;
    if (port->ticks != 0)
        t_build = port->ticks(port->ctx, LT_STAGE_QT_BUILD);
    if (lt_qt_build_q30(&qt, &d, &prm, w, arena, &qb) != LT_OK)
        return fail(port, LT_RPAPP_E_BUILD, err_text(LT_RPAPP_E_BUILD));
    if (port->ticks != 0)
        t_build = port->ticks(port->ctx, LT_STAGE_UNTIMED) - t_build;

    tot.rays = tot.kept = tot.hit_back = 0;
    tot.nodes = 0;
    for (e = 0; e < 5; e++)
        tot.st[e] = 0;
    for (ty = 0; ty < h->map.dst_h; ty += h->tile) {
        for (tx = 0; tx < h->map.dst_w; tx += h->tile) {
            counts_t c;
            uint32_t hh = 0;
            int i;
            c.rays = c.kept = c.hit_back = 0;
            c.nodes = 0;
            for (i = 0; i < 5; i++)
                c.st[i] = 0;
            e = run_tile(h, &qt, r, hit, port, tx, ty, &hh, &c, &t_rp);
            if (e != LT_RPAPP_OK)
                return fail(port, e, err_text(e));
            add_counts(&tot, &c);
            th = fnv_u32(th, hh);
            /* streamed: the tile's line leaves before the next tile starts */
            l_str(&l, "tile ");
            l_u64(&l, tx / h->tile);
            l_str(&l, " ");
            l_u64(&l, ty / h->tile);
            l_str(&l, ": ");
            l_counts(&l, &c, 0);
            l_str(&l, " hash ");
            l_hex(&l, hh);
            l_out(port, &l);
        }
    }
    l_str(&l, "total: ");
    l_counts(&l, &tot, 1);
    l_str(&l, " hash ");
    l_hex(&l, th);
    l_out(port, &l);
    if (port->ticks != 0) {
        l_str(&l, "ticks (");
        l_str(&l, port->name != 0 ? port->name : "?");
        l_str(&l, "): build ");
        l_u64(&l, t_build);
        l_str(&l, ", reproject ");
        l_u64(&l, t_rp);
        l_str(&l, ", per traced ray ");
        l_cent(&l, tot.kept != 0u ? t_rp * 100u / tot.kept : 0u);
        l_str(&l, ", per pixel ");
        l_cent(&l, tot.rays != 0u ? t_rp * 100u / tot.rays : 0u);
        l_str(&l, port->single ? ", walk single" : ", walk packets");
        l_out(port, &l);
    }
    return LT_RPAPP_OK;
}
