/* fuzz_frame.c - fuzz target for the stream protocol: the core streaming decoder (any chunking),
 * the one-shot decoder, the typed unpackers, the host receiver's sequence accounting and the fault
 * injector, on arbitrary bytes. Invariants checked (abort on failure): every byte is either part of
 * a returned frame, garbage or still held; a returned frame re-encodes to the bytes it came from;
 * unpack-pack round-trips; the receiver's totals add up (received + lost = sent, every valid copy
 * classified once). Runs under libFuzzer (make fuzz-frame) and through the replay driver
 * fuzz_main.c (make test). Builds: host, asan, clang -fsanitize=fuzzer.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "lt/lt_stream.h"
#include "stream/lt_faults.h"
#include "stream/lt_rx.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define REQUIRE(c)                                                                                 \
    do {                                                                                           \
        if (!(c))                                                                                  \
            abort();                                                                               \
    } while (0)

/* Typed round trip: a frame that unpacks as its type packs back to the same payload. */
static void roundtrip(const lt_stream_frame_t *f)
{
    lt_stream_frame_t g;
    int ok = 0;
    union {
        lt_stream_hello_t h;
        lt_stream_tile_t t;
        lt_stream_summary_t s;
        lt_stream_drop_t d;
        lt_stream_image_t i;
        lt_stream_end_t e;
    } u;
    switch (f->type) {
    case LT_STREAM_HELLO:
        ok = lt_stream_unpack_hello(f, &u.h) == LT_OK && lt_stream_pack_hello(&u.h, &g) == LT_OK;
        break;
    case LT_STREAM_TILE:
        ok = lt_stream_unpack_tile(f, &u.t) == LT_OK && lt_stream_pack_tile(&u.t, &g) == LT_OK;
        break;
    case LT_STREAM_SUMMARY:
        ok = lt_stream_unpack_summary(f, &u.s) == LT_OK &&
             lt_stream_pack_summary(&u.s, &g) == LT_OK;
        break;
    case LT_STREAM_DROP:
        ok = lt_stream_unpack_drop(f, &u.d) == LT_OK && lt_stream_pack_drop(&u.d, &g) == LT_OK;
        break;
    case LT_STREAM_IMAGE:
        ok = lt_stream_unpack_image(f, &u.i) == LT_OK && lt_stream_pack_image(&u.i, &g) == LT_OK;
        break;
    case LT_STREAM_END:
        ok = lt_stream_unpack_end(f, &u.e) == LT_OK && lt_stream_pack_end(&u.e, &g) == LT_OK;
        break;
    default:
        abort(); /* the decoder never returns an unknown type */
    }
    if (ok) {
        REQUIRE(g.type == f->type && g.len == f->len);
        REQUIRE(memcmp(g.payload, f->payload, f->len) == 0);
    }
}

static void sink(void *ctx, const uint8_t *b, size_t n)
{
    lt_rx_feed((lt_rx_t *)ctx, b, n);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    lt_stream_dec_t d;
    lt_stream_frame_t f;
    uint8_t enc[LT_STREAM_FRAME_BYTES];
    size_t off = 0, chunk = size > 0 ? (size_t)(data[0] % 67u) + 1u : 1u;
    uint64_t held;
    lt_rx_t *rx;
    const lt_rx_stats_t *st;

    /* streaming decoder, chunked */
    lt_stream_dec_init(&d);
    while (off < size) {
        size_t n = size - off < chunk ? size - off : chunk;
        uint32_t used = 0;
        lt_status_t s = lt_stream_dec_push(&d, data + off, (uint32_t)n, &used, &f);
        REQUIRE(used <= n);
        off += used;
        if (s == LT_OK) {
            REQUIRE(lt_stream_encode(&f, enc) == LT_OK);
            REQUIRE(off >= LT_STREAM_FRAME_BYTES);
            REQUIRE(memcmp(enc, data + off - LT_STREAM_FRAME_BYTES, sizeof enc) == 0);
            roundtrip(&f);
        } else {
            REQUIRE(s == LT_E_SPACE && used == n);
        }
    }
    REQUIRE(d.bytes == size);
    held = d.bytes - d.frames * LT_STREAM_FRAME_BYTES - d.garbage_bytes;
    REQUIRE(held < LT_STREAM_FRAME_BYTES);
    REQUIRE(lt_stream_dec_finish(&d) == held);
    REQUIRE(d.frames * LT_STREAM_FRAME_BYTES + d.garbage_bytes == size);

    /* one-shot decoder */
    if (lt_stream_decode(data, (uint32_t)(size > 0xFFFFFFFFu ? 0xFFFFFFFFu : size), &f, NULL,
                         NULL) == LT_OK) {
        REQUIRE(lt_stream_encode(&f, enc) == LT_OK && memcmp(enc, data, sizeof enc) == 0);
    }

    /* receiver accounting */
    rx = lt_rx_new(NULL, NULL);
    REQUIRE(rx != NULL);
    lt_rx_feed(rx, data, size);
    lt_rx_finish(rx);
    st = lt_rx_stats(rx);
    REQUIRE(st->bytes == size);
    REQUIRE(st->received <= st->sent && st->lost == st->sent - st->received);
    REQUIRE(st->valid == st->received + st->duplicates + st->stale);
    REQUIRE(st->damaged <= st->lost);
    lt_rx_free(rx);

    /* fault injector into a receiver: must not crash, totals still add up */
    {
        lt_faults_cfg_t c;
        lt_diag_t diag;
        lt_faults_t *fi;
        memset(&c, 0, sizeof c);
        c.drop = c.corrupt = c.dup = c.reorder = c.trunc = 0.1;
        c.max_flips = 3;
        c.seed = size;
        rx = lt_rx_new(NULL, NULL);
        fi = lt_faults_new(&c, sink, rx, &diag);
        REQUIRE(rx != NULL && fi != NULL);
        lt_faults_feed(fi, data, size);
        lt_faults_finish(fi);
        lt_rx_finish(rx);
        st = lt_rx_stats(rx);
        REQUIRE(st->received <= st->sent && st->lost == st->sent - st->received);
        REQUIRE(lt_faults_truth(fi)->frames_in == d.frames);
        lt_faults_free(fi);
        lt_rx_free(rx);
    }
    return 0;
}
