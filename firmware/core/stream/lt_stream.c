/* lt_stream.c - the stream protocol of lt_stream.h: 64-byte frames with a CRC-32C trailer, a
 * streaming decoder that resynchronises on the next 'L' 'T' magic after garbage, the typed payload
 * packers, and the device-side batcher that models a 64,000 B/s full-speed HID link against the
 * device's tick clock (one report slot per period; drops by class; DROP records).
 * Layouts and policies: docs/stream.md. Builds: all (freestanding, no heap, no float; not charged
 * to the cost model: the counters a device reports measure the tracer, not its reporting).
 */
#include "lt/lt_stream.h"

/* ---- little-endian field access (byte by byte: no alignment or endianness assumptions) ------- */

static void put16(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v & 0xFFu);
    p[1] = (uint8_t)((v >> 8) & 0xFFu);
}

static void put32(uint8_t *p, uint32_t v)
{
    put16(p, v & 0xFFFFu);
    put16(p + 2, v >> 16);
}

static void put64(uint8_t *p, uint64_t v)
{
    put32(p, (uint32_t)(v & 0xFFFFFFFFu));
    put32(p + 4, (uint32_t)(v >> 32));
}

static uint16_t get16(const uint8_t *p) { return (uint16_t)(p[0] | (p[1] << 8)); }

static uint32_t get32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}

static uint64_t get64(const uint8_t *p)
{
    return (uint64_t)get32(p) | ((uint64_t)get32(p + 4) << 32);
}

/* ---- CRC-32C --------------------------------------------------------------------------------- */

/* Nibble table of the reflected Castagnoli polynomial: T[i] = CRC of the 4-bit value i shifted
 * through 4 steps of the bitwise algorithm (the unit test rebuilds it bitwise). 64 bytes instead
 * of the 1 KiB byte table; two lookups per byte. */
static const uint32_t crc32c_nib[16] = {
    0x00000000u, 0x105EC76Fu, 0x20BD8EDEu, 0x30E349B1u, 0x417B1DBCu, 0x5125DAD3u,
    0x61C69362u, 0x7198540Du, 0x82F63B78u, 0x92A8FC17u, 0xA24BB5A6u, 0xB21572C9u,
    0xC38D26C4u, 0xD3D3E1ABu, 0xE330A81Au, 0xF36E6F75u,
};

uint32_t lt_stream_crc32c(uint32_t crc, const void *p, uint32_t n)
{
    const uint8_t *b = (const uint8_t *)p;
    uint32_t i;
    crc = ~crc;
    for (i = 0; i < n; i++) {
        crc ^= b[i];
        crc = (crc >> 4) ^ crc32c_nib[crc & 0xFu];
        crc = (crc >> 4) ^ crc32c_nib[crc & 0xFu];
    }
    return ~crc;
}

/* ---- frames ---------------------------------------------------------------------------------- */

static const uint8_t payload_len[LT_STREAM_TYPE_MAX + 1] = {0, 52, 40, 52, 24, 0, 32};

uint32_t lt_stream_payload_len(uint32_t type)
{
    return type <= LT_STREAM_TYPE_MAX ? payload_len[type] : 0u;
}

lt_status_t lt_stream_encode(const lt_stream_frame_t *f, uint8_t out[LT_STREAM_FRAME_BYTES])
{
    uint32_t i, crc;
    if (f == NULL || out == NULL || f->type == 0 || f->type > LT_STREAM_TYPE_MAX ||
        f->len > LT_STREAM_PAYLOAD_MAX)
        return LT_E_ARG;
    out[0] = LT_STREAM_MAGIC0;
    out[1] = LT_STREAM_MAGIC1;
    out[2] = LT_STREAM_VERSION;
    out[3] = f->type;
    put16(out + 4, f->seq);
    out[6] = f->len;
    out[7] = 0;
    /* padding is zero so that a frame has exactly one encoding (the decoder checks it) */
    for (i = 0; i < LT_STREAM_PAYLOAD_MAX; i++)
        out[LT_STREAM_HEADER_BYTES + i] = (uint8_t)(i < f->len ? f->payload[i] : 0u);
    crc = lt_stream_crc32c(0, out, LT_STREAM_FRAME_BYTES - LT_STREAM_CRC_BYTES);
    put32(out + LT_STREAM_FRAME_BYTES - LT_STREAM_CRC_BYTES, crc);
    return LT_OK;
}

/* Header checks only (bytes 0..7 present): the first failed check, or OK. */
static lt_stream_why_t check_header(const uint8_t *in)
{
    if (in[0] != LT_STREAM_MAGIC0 || in[1] != LT_STREAM_MAGIC1)
        return LT_STREAM_WHY_MAGIC;
    if (in[2] != LT_STREAM_VERSION)
        return LT_STREAM_WHY_VERSION;
    if (in[3] == 0 || in[3] > LT_STREAM_TYPE_MAX)
        return LT_STREAM_WHY_TYPE;
    if (in[6] > LT_STREAM_PAYLOAD_MAX)
        return LT_STREAM_WHY_LENGTH;
    if (in[7] != 0)
        return LT_STREAM_WHY_RESERVED;
    return LT_STREAM_WHY_OK;
}

lt_status_t lt_stream_decode(const uint8_t *in, uint32_t n, lt_stream_frame_t *f, uint32_t *need,
                             lt_stream_why_t *why)
{
    lt_stream_why_t w;
    uint32_t i, len;
    if (why != NULL)
        *why = LT_STREAM_WHY_OK;
    if (in == NULL || f == NULL)
        return LT_E_ARG;
    if (n < LT_STREAM_FRAME_BYTES) {
        if (need != NULL)
            *need = LT_STREAM_FRAME_BYTES;
        return LT_E_SPACE;
    }
    w = check_header(in);
    if (w == LT_STREAM_WHY_OK &&
        lt_stream_crc32c(0, in, LT_STREAM_FRAME_BYTES - LT_STREAM_CRC_BYTES) !=
            get32(in + LT_STREAM_FRAME_BYTES - LT_STREAM_CRC_BYTES))
        w = LT_STREAM_WHY_CRC;
    len = in[6];
    for (i = len; w == LT_STREAM_WHY_OK && i < LT_STREAM_PAYLOAD_MAX; i++)
        if (in[LT_STREAM_HEADER_BYTES + i] != 0)
            w = LT_STREAM_WHY_PADDING;
    if (w != LT_STREAM_WHY_OK) {
        if (why != NULL)
            *why = w;
        return LT_E_FORMAT;
    }
    f->type = in[3];
    f->seq = get16(in + 4);
    f->len = (uint8_t)len;
    for (i = 0; i < LT_STREAM_PAYLOAD_MAX; i++)
        f->payload[i] = in[LT_STREAM_HEADER_BYTES + i];
    return LT_OK;
}

/* ---- streaming decoder ----------------------------------------------------------------------- */

void lt_stream_dec_init(lt_stream_dec_t *d)
{
    if (d != NULL)
        lt__memset(d, 0, sizeof *d);
}

/* Discard the first k window bytes as garbage and slide the rest down. */
static void dec_skip(lt_stream_dec_t *d, uint32_t k)
{
    uint32_t i;
    if (k == 0)
        return;
    if (!d->in_garbage) {
        d->garbage_runs++;
        d->in_garbage = 1;
    }
    d->garbage_bytes += k;
    for (i = k; i < d->have; i++)
        d->win[i - k] = d->win[i];
    d->have -= k;
}

/* Bytes before the next position of the window (after 0) that could start a frame: a MAGIC0
 * followed by MAGIC1, or a MAGIC0 in the last byte (its partner may still come). */
static uint32_t next_candidate(const lt_stream_dec_t *d)
{
    uint32_t j;
    for (j = 1; j < d->have; j++)
        if (d->win[j] == LT_STREAM_MAGIC0 &&
            (j + 1 == d->have || d->win[j + 1] == LT_STREAM_MAGIC1))
            return j;
    return d->have;
}

lt_status_t lt_stream_dec_push(lt_stream_dec_t *d, const uint8_t *in, uint32_t n, uint32_t *used,
                               lt_stream_frame_t *f)
{
    uint32_t take = 0;
    if (d == NULL || used == NULL || f == NULL || (in == NULL && n != 0))
        return LT_E_ARG;
    for (;;) {
        lt_stream_why_t w;
        /* Normalise the window: it must start with a possible frame start. A window that does
         * not is cut to the next candidate; while no header is complete, only the magic is known.
         */
        if (d->have > 0 && d->win[0] != LT_STREAM_MAGIC0) {
            dec_skip(d, next_candidate(d));
            continue;
        }
        if (d->have > 1 && d->win[1] != LT_STREAM_MAGIC1) {
            dec_skip(d, next_candidate(d));
            continue;
        }
        if (d->have >= LT_STREAM_HEADER_BYTES && check_header(d->win) != LT_STREAM_WHY_OK) {
            d->bad_header++;
            dec_skip(d, next_candidate(d));
            continue;
        }
        if (d->have == LT_STREAM_FRAME_BYTES) {
            if (lt_stream_decode(d->win, d->have, f, NULL, &w) == LT_OK) {
                d->have = 0;
                d->in_garbage = 0;
                d->frames++;
                *used = take;
                return LT_OK;
            }
            d->bad_crc++;
            dec_skip(d, next_candidate(d));
            continue;
        }
        if (take == n)
            break;
        /* Fill up to a full frame. Bytes of a following frame that enter the window behind a bad
         * candidate are not lost: the window is cut to the next candidate, never emptied. */
        {
            uint32_t room = LT_STREAM_FRAME_BYTES - d->have, k;
            if (room > n - take)
                room = n - take;
            for (k = 0; k < room; k++)
                d->win[d->have + k] = in[take + k];
            d->have += room;
            d->bytes += room;
            take += room;
        }
    }
    *used = take;
    return LT_E_SPACE;
}

uint32_t lt_stream_dec_finish(lt_stream_dec_t *d)
{
    uint32_t k;
    if (d == NULL)
        return 0;
    k = d->have;
    dec_skip(d, k);
    d->in_garbage = 0;
    return k;
}

/* ---- payload packers ------------------------------------------------------------------------- */

static lt_status_t start(lt_stream_frame_t *f, uint32_t type, uint32_t len)
{
    if (f == NULL)
        return LT_E_ARG;
    f->type = (uint8_t)type;
    f->len = (uint8_t)len;
    lt__memset(f->payload, 0, sizeof f->payload);
    return LT_OK;
}

static lt_status_t check(const lt_stream_frame_t *f, const void *p, uint32_t type)
{
    if (f == NULL || p == NULL)
        return LT_E_ARG;
    if (f->type != type || (type != LT_STREAM_IMAGE && f->len != payload_len[type]))
        return LT_E_FORMAT;
    return LT_OK;
}

lt_status_t lt_stream_pack_hello(const lt_stream_hello_t *p, lt_stream_frame_t *f)
{
    uint8_t *b;
    uint32_t i;
    if (p == NULL || start(f, LT_STREAM_HELLO, 52) != LT_OK)
        return LT_E_ARG;
    b = f->payload;
    b[0] = p->source;
    b[1] = p->tile_w;
    b[2] = p->tile_h;
    b[3] = p->flags;
    put32(b + 4, p->session);
    put32(b + 8, p->tick_hz);
    put32(b + 12, p->link_bytes_per_s);
    put32(b + 16, p->ticks_per_report);
    put16(b + 20, p->width);
    put16(b + 22, p->height);
    put16(b + 24, p->ntris);
    put16(b + 26, p->frames);
    put32(b + 28, p->valid);
    put32(b + 32, p->scene_hash);
    for (i = 0; i < 16; i++)
        b[36 + i] = (uint8_t)p->name[i];
    return LT_OK;
}

lt_status_t lt_stream_unpack_hello(const lt_stream_frame_t *f, lt_stream_hello_t *p)
{
    const uint8_t *b;
    uint32_t i;
    lt_status_t s = check(f, p, LT_STREAM_HELLO);
    if (s != LT_OK)
        return s;
    b = f->payload;
    p->source = b[0];
    p->tile_w = b[1];
    p->tile_h = b[2];
    p->flags = b[3];
    p->session = get32(b + 4);
    p->tick_hz = get32(b + 8);
    p->link_bytes_per_s = get32(b + 12);
    p->ticks_per_report = get32(b + 16);
    p->width = get16(b + 20);
    p->height = get16(b + 22);
    p->ntris = get16(b + 24);
    p->frames = get16(b + 26);
    p->valid = get32(b + 28);
    p->scene_hash = get32(b + 32);
    for (i = 0; i < 16; i++)
        p->name[i] = (char)b[36 + i];
    return LT_OK;
}

lt_status_t lt_stream_pack_tile(const lt_stream_tile_t *p, lt_stream_frame_t *f)
{
    uint8_t *b;
    if (p == NULL || start(f, LT_STREAM_TILE, 40) != LT_OK)
        return LT_E_ARG;
    b = f->payload;
    put16(b + 0, p->frame);
    put16(b + 2, p->tile);
    put16(b + 4, p->rays);
    put16(b + 6, p->hits);
    put32(b + 8, p->ticks);
    put32(b + 12, p->cycles);
    put32(b + 16, p->aabb);
    put32(b + 20, p->aabb_rays);
    put32(b + 24, p->tris);
    put32(b + 28, p->tri_rays);
    put32(b + 32, p->hash);
    put32(b + 36, p->t_end);
    return LT_OK;
}

lt_status_t lt_stream_unpack_tile(const lt_stream_frame_t *f, lt_stream_tile_t *p)
{
    const uint8_t *b;
    lt_status_t s = check(f, p, LT_STREAM_TILE);
    if (s != LT_OK)
        return s;
    b = f->payload;
    p->frame = get16(b + 0);
    p->tile = get16(b + 2);
    p->rays = get16(b + 4);
    p->hits = get16(b + 6);
    p->ticks = get32(b + 8);
    p->cycles = get32(b + 12);
    p->aabb = get32(b + 16);
    p->aabb_rays = get32(b + 20);
    p->tris = get32(b + 24);
    p->tri_rays = get32(b + 28);
    p->hash = get32(b + 32);
    p->t_end = get32(b + 36);
    return LT_OK;
}

lt_status_t lt_stream_pack_summary(const lt_stream_summary_t *p, lt_stream_frame_t *f)
{
    uint8_t *b;
    if (p == NULL || start(f, LT_STREAM_SUMMARY, 52) != LT_OK)
        return LT_E_ARG;
    b = f->payload;
    put16(b + 0, p->frame);
    put16(b + 2, p->tiles);
    put32(b + 4, p->rays);
    put32(b + 8, p->hits);
    put64(b + 12, p->ticks);
    put64(b + 20, p->cycles);
    put32(b + 28, p->aabb);
    put32(b + 32, p->aabb_rays);
    put32(b + 36, p->tris);
    put32(b + 40, p->tri_rays);
    put32(b + 44, p->hash);
    put32(b + 48, p->dropped);
    return LT_OK;
}

lt_status_t lt_stream_unpack_summary(const lt_stream_frame_t *f, lt_stream_summary_t *p)
{
    const uint8_t *b;
    lt_status_t s = check(f, p, LT_STREAM_SUMMARY);
    if (s != LT_OK)
        return s;
    b = f->payload;
    p->frame = get16(b + 0);
    p->tiles = get16(b + 2);
    p->rays = get32(b + 4);
    p->hits = get32(b + 8);
    p->ticks = get64(b + 12);
    p->cycles = get64(b + 20);
    p->aabb = get32(b + 28);
    p->aabb_rays = get32(b + 32);
    p->tris = get32(b + 36);
    p->tri_rays = get32(b + 40);
    p->hash = get32(b + 44);
    p->dropped = get32(b + 48);
    return LT_OK;
}

lt_status_t lt_stream_pack_drop(const lt_stream_drop_t *p, lt_stream_frame_t *f)
{
    uint8_t *b;
    if (p == NULL || start(f, LT_STREAM_DROP, 24) != LT_OK)
        return LT_E_ARG;
    b = f->payload;
    put32(b + 0, p->dropped);
    put32(b + 4, p->tile);
    put32(b + 8, p->image);
    put32(b + 12, p->total);
    put64(b + 16, p->t);
    return LT_OK;
}

lt_status_t lt_stream_unpack_drop(const lt_stream_frame_t *f, lt_stream_drop_t *p)
{
    const uint8_t *b;
    lt_status_t s = check(f, p, LT_STREAM_DROP);
    if (s != LT_OK)
        return s;
    b = f->payload;
    p->dropped = get32(b + 0);
    p->tile = get32(b + 4);
    p->image = get32(b + 8);
    p->total = get32(b + 12);
    p->t = get64(b + 16);
    return LT_OK;
}

lt_status_t lt_stream_pack_image(const lt_stream_image_t *p, lt_stream_frame_t *f)
{
    uint8_t *b;
    uint32_t i;
    if (p == NULL || p->count == 0 || p->count > LT_STREAM_IMAGE_MAX ||
        start(f, LT_STREAM_IMAGE, 8u + p->count) != LT_OK)
        return LT_E_ARG;
    b = f->payload;
    put16(b + 0, p->frame);
    put16(b + 2, p->tile);
    put16(b + 4, p->offset);
    b[6] = p->count;
    b[7] = p->format;
    for (i = 0; i < p->count; i++)
        b[8 + i] = p->data[i];
    return LT_OK;
}

lt_status_t lt_stream_unpack_image(const lt_stream_frame_t *f, lt_stream_image_t *p)
{
    const uint8_t *b;
    uint32_t i;
    lt_status_t s = check(f, p, LT_STREAM_IMAGE);
    if (s != LT_OK)
        return s;
    b = f->payload;
    if (b[6] == 0 || b[6] > LT_STREAM_IMAGE_MAX || f->len != 8u + b[6])
        return LT_E_FORMAT;
    p->frame = get16(b + 0);
    p->tile = get16(b + 2);
    p->offset = get16(b + 4);
    p->count = b[6];
    p->format = b[7];
    for (i = 0; i < LT_STREAM_IMAGE_MAX; i++)
        p->data[i] = (uint8_t)(i < p->count ? b[8 + i] : 0u);
    return LT_OK;
}

lt_status_t lt_stream_pack_end(const lt_stream_end_t *p, lt_stream_frame_t *f)
{
    uint8_t *b;
    if (p == NULL || start(f, LT_STREAM_END, 32) != LT_OK)
        return LT_E_ARG;
    b = f->payload;
    put32(b + 0, p->frames_sent);
    put32(b + 4, p->dropped);
    put64(b + 8, p->ticks);
    put64(b + 16, p->link_done);
    put32(b + 24, p->status);
    put32(b + 28, p->frames);
    return LT_OK;
}

lt_status_t lt_stream_unpack_end(const lt_stream_frame_t *f, lt_stream_end_t *p)
{
    const uint8_t *b;
    lt_status_t s = check(f, p, LT_STREAM_END);
    if (s != LT_OK)
        return s;
    b = f->payload;
    p->frames_sent = get32(b + 0);
    p->dropped = get32(b + 4);
    p->ticks = get64(b + 8);
    p->link_done = get64(b + 16);
    p->status = get32(b + 24);
    p->frames = get32(b + 28);
    return LT_OK;
}

/* ---- batcher --------------------------------------------------------------------------------- */

void lt_stream_link_default(lt_stream_link_t *l, uint32_t tick_hz)
{
    if (l == NULL)
        return;
    l->tick_hz = tick_hz;
    l->link_bytes_per_s = LT_STREAM_HID_BYTES_PER_S;
    l->cap = 16;
    l->limit[LT_STREAM_CLASS_CTRL] = 16;
    l->limit[LT_STREAM_CLASS_TILE] = 12;
    l->limit[LT_STREAM_CLASS_IMAGE] = 8;
}

lt_status_t lt_stream_tx_size(uint32_t cap, uint32_t *bytes)
{
    if (bytes == NULL || cap < 2 || cap > 4096)
        return LT_E_ARG;
    *bytes = cap * LT_STREAM_FRAME_BYTES;
    return LT_OK;
}

lt_status_t lt_stream_tx_init(lt_stream_tx_t *tx, const lt_stream_link_t *l, void *ring,
                              uint32_t ring_bytes, lt_stream_sink_fn sink, void *ctx)
{
    uint32_t need;
    if (tx == NULL || l == NULL || ring == NULL || sink == NULL || l->tick_hz == 0 ||
        l->link_bytes_per_s == 0 || lt_stream_tx_size(l->cap, &need) != LT_OK ||
        l->limit[0] != l->cap || l->limit[2] < 1 || l->limit[2] > l->limit[1] ||
        l->limit[1] > l->cap)
        return LT_E_ARG;
    if (ring_bytes < need)
        return LT_E_SPACE;
    lt__memset(tx, 0, sizeof *tx);
    tx->ring = (uint8_t *)ring;
    tx->sink = sink;
    tx->sink_ctx = ctx;
    tx->link = *l;
    /* one report per slot: period = report bytes / budget, in ticks, rounded up so the modelled
     * link is never faster than the budget */
    tx->period = ((uint64_t)l->tick_hz * LT_STREAM_FRAME_BYTES + l->link_bytes_per_s - 1u) /
                 l->link_bytes_per_s;
    if (tx->period == 0)
        tx->period = 1;
    return LT_OK;
}

/* Hand the head frame to the sink at slot tick t. */
static void send_head(lt_stream_tx_t *tx, uint64_t t)
{
    tx->last_tx = t; /* set first: a sink may read it as the frame's slot time */
    tx->sink(tx->sink_ctx, tx->ring + (size_t)tx->head * LT_STREAM_FRAME_BYTES,
             LT_STREAM_FRAME_BYTES);
    tx->head = tx->head + 1u == tx->link.cap ? 0u : tx->head + 1u;
    tx->count--;
    tx->sent_frames++;
    tx->sent_bytes += LT_STREAM_FRAME_BYTES;
}

void lt_stream_tx_poll(lt_stream_tx_t *tx, uint64_t now)
{
    if (tx == NULL)
        return;
    while (tx->count > 0 && tx->next_slot <= now) {
        send_head(tx, tx->next_slot);
        tx->next_slot += tx->period;
    }
}

/* Encode f with the next sequence number into the ring's tail (room checked by the caller). */
static lt_status_t enqueue(lt_stream_tx_t *tx, lt_stream_frame_t *f, uint64_t now)
{
    uint32_t tail = tx->head + tx->count;
    if (tail >= tx->link.cap)
        tail -= tx->link.cap;
    f->seq = (uint16_t)(tx->seq & 0xFFFFu);
    if (lt_stream_encode(f, tx->ring + (size_t)tail * LT_STREAM_FRAME_BYTES) != LT_OK)
        return LT_E_ARG;
    /* An idle link wastes its slots: the first frame after idleness waits for the next slot at or
     * after now (slots are the multiples of period, as USB frames are every 1 ms). */
    if (tx->count == 0 && tx->next_slot < now)
        tx->next_slot = (now + tx->period - 1u) / tx->period * tx->period;
    tx->seq++;
    tx->count++;
    if (tx->count > tx->max_depth)
        tx->max_depth = tx->count;
    return LT_OK;
}

/* Queue the DROP record for the pending drops. */
static lt_status_t queue_drop(lt_stream_tx_t *tx, uint64_t now)
{
    lt_stream_drop_t d;
    lt_stream_frame_t f;
    d.tile = tx->pend[LT_STREAM_CLASS_TILE];
    d.image = tx->pend[LT_STREAM_CLASS_IMAGE];
    d.dropped = d.tile + d.image + tx->pend[LT_STREAM_CLASS_CTRL];
    d.total = tx->dropped[0] + tx->dropped[1] + tx->dropped[2];
    d.t = now;
    (void)lt_stream_pack_drop(&d, &f);
    if (enqueue(tx, &f, now) != LT_OK)
        return LT_E_ARG;
    tx->pend[0] = tx->pend[1] = tx->pend[2] = 0;
    tx->drop_records++;
    tx->drop_next = now + LT_STREAM_DROP_GAP * tx->period;
    return LT_OK;
}

static int have_pending(const lt_stream_tx_t *tx)
{
    return (tx->pend[0] | tx->pend[1] | tx->pend[2]) != 0;
}

lt_status_t lt_stream_tx_push(lt_stream_tx_t *tx, lt_stream_frame_t *f, lt_stream_class_t cls,
                              uint64_t now, uint64_t *retry_at)
{
    uint32_t limit;
    if (tx == NULL || f == NULL || (uint32_t)cls > 2u || f->type == 0 ||
        f->type > LT_STREAM_TYPE_MAX || f->len > LT_STREAM_PAYLOAD_MAX)
        return LT_E_ARG;
    lt_stream_tx_poll(tx, now);
    limit = tx->link.limit[cls];
    /* The DROP record goes out once the ring has room for it and the frame that follows, but at
     * most once per LT_STREAM_DROP_GAP slots (lt_stream_tx_finish reports the rest): under steady
     * overload the records cost at most 1/16 of the link, never one record per dropped report. */
    if (have_pending(tx) && tx->count + 2u <= limit && now >= tx->drop_next) {
        if (queue_drop(tx, now) != LT_OK)
            return LT_E_ARG;
    }
    if (tx->count < limit)
        return enqueue(tx, f, now);
    if (cls == LT_STREAM_CLASS_CTRL) {
        tx->full_waits++;
        if (retry_at != NULL)
            *retry_at = tx->next_slot;
        return LT_E_SPACE;
    }
    tx->dropped[cls]++;
    tx->pend[cls]++;
    return LT_E_SPACE;
}

lt_status_t lt_stream_tx_finish(lt_stream_tx_t *tx, const lt_stream_end_t *e, uint64_t now,
                                uint64_t *link_done)
{
    lt_stream_end_t end;
    lt_stream_frame_t f;
    uint64_t done;
    if (tx == NULL || e == NULL)
        return LT_E_ARG;
    lt_stream_tx_poll(tx, now);
    /* Make room for the DROP and END records by sending at the coming slots (computed, since a
     * finished device has nothing else to do while the link drains). */
    while (tx->count + 2u > tx->link.cap) {
        send_head(tx, tx->next_slot);
        tx->next_slot += tx->period;
    }
    if (have_pending(tx) && queue_drop(tx, now) != LT_OK)
        return LT_E_ARG;
    end = *e;
    end.frames_sent = tx->seq + 1u;
    end.dropped = tx->dropped[0] + tx->dropped[1] + tx->dropped[2];
    if (tx->count == 0 && tx->next_slot < now)
        done = (now + tx->period - 1u) / tx->period * tx->period;
    else
        done = tx->next_slot + (uint64_t)tx->count * tx->period;
    end.link_done = done;
    (void)lt_stream_pack_end(&end, &f);
    if (enqueue(tx, &f, now) != LT_OK)
        return LT_E_ARG;
    while (tx->count > 0) {
        send_head(tx, tx->next_slot);
        tx->next_slot += tx->period;
    }
    if (link_done != NULL)
        *link_done = done;
    return LT_OK;
}
