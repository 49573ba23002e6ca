/* lt_stream.h - the stream protocol: a device's throughput reports as 64-byte frames, one frame per
 * full-speed USB HID interrupt report (64,000 B/s at one report per 1 ms USB frame). Encoder and
 * decoder (CRC-32C, resynchronisation on the next magic after garbage), typed payload packers, and
 * the device-side batcher: a ring of encoded frames drained at the link's report rate against the
 * device's own tick clock, which drops reports by class when the link is slower than the tracer
 * and says so with a DROP record. Byte layouts, CRC, sequence and drop policy: docs/stream.md.
 * Builds: all (freestanding C99, no heap; the caller hands in the ring memory).
 */
#ifndef LT_STREAM_H
#define LT_STREAM_H

#include <stdint.h>
#include "lt_port.h"
#include "lt_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- frame format ---------------------------------------------------------------------------- */

#define LT_STREAM_FRAME_BYTES 64u   /* every frame, on every transport; = one HID report */
#define LT_STREAM_HEADER_BYTES 8u   /* magic(2) version(1) type(1) seq(2) len(1) reserved(1) */
#define LT_STREAM_CRC_BYTES 4u      /* CRC-32C of bytes 0..59, little-endian at 60..63 */
#define LT_STREAM_PAYLOAD_MAX 52u   /* 64 - 8 - 4; unused payload bytes are zero */
#define LT_STREAM_MAGIC0 0x4Cu      /* 'L' */
#define LT_STREAM_MAGIC1 0x54u      /* 'T' */
#define LT_STREAM_VERSION 1u
#define LT_STREAM_HID_BYTES_PER_S 64000u /* full-speed HID: one 64-byte report per 1 ms frame */

/* Frame types (header byte 3). */
typedef enum lt_stream_type {
    LT_STREAM_HELLO = 1,   /* session start: device, clock, link budget, image, scene */
    LT_STREAM_TILE = 2,    /* per-tile report: rays, hits, ticks, counters, tile hash */
    LT_STREAM_SUMMARY = 3, /* per-image-frame totals */
    LT_STREAM_DROP = 4,    /* "dropped N": reports the batcher discarded since the last DROP */
    LT_STREAM_IMAGE = 5,   /* optional image-tile pixels, up to 44 per frame */
    LT_STREAM_END = 6      /* session end: frames sent, drops, device time */
} lt_stream_type_t;
#define LT_STREAM_TYPE_MAX 6

/* A decoded frame: header fields and the raw payload. 56 bytes, 2-byte aligned. */
typedef struct lt_stream_frame {
    uint16_t seq;                            /* sequence number, wraps at 65536 */
    uint8_t type;                            /* lt_stream_type_t */
    uint8_t len;                             /* payload bytes used, 0..52 */
    uint8_t payload[LT_STREAM_PAYLOAD_MAX];  /* little-endian fields, see the packers */
} lt_stream_frame_t;
LT_STATIC_ASSERT(sizeof(lt_stream_frame_t) == 56, "frame is 4 header bytes + 52 payload");

/* Why a candidate frame was rejected (lt_stream_decode's *why). */
typedef enum lt_stream_why {
    LT_STREAM_WHY_OK = 0,
    LT_STREAM_WHY_MAGIC = 1,    /* bytes 0..1 are not 'L' 'T' */
    LT_STREAM_WHY_VERSION = 2,  /* byte 2 is not LT_STREAM_VERSION */
    LT_STREAM_WHY_TYPE = 3,     /* byte 3 is 0 or above LT_STREAM_TYPE_MAX */
    LT_STREAM_WHY_LENGTH = 4,   /* byte 6 is above 52 */
    LT_STREAM_WHY_RESERVED = 5, /* byte 7 is not 0 */
    LT_STREAM_WHY_CRC = 6,      /* CRC-32C mismatch */
    LT_STREAM_WHY_PADDING = 7   /* CRC good but a payload byte past len is not 0 */
} lt_stream_why_t;

/* CRC-32C (Castagnoli): reflected polynomial 0x82F63B78, init 0xFFFFFFFF, final xor 0xFFFFFFFF,
 * check value 0xE3069283 for "123456789". Nibble-table form (16 x 4 bytes of .rodata, two table
 * steps per byte). Chains like zlib's crc32: crc = lt_stream_crc32c(crc, more, n) with crc = 0 at
 * the start. Format: bytes -> uint32. Range: any n. Rounding: none. Overflow: none. Cost: none
 * charged (protocol code is not part of the modelled tracer). Returns: the CRC so far. */
uint32_t lt_stream_crc32c(uint32_t crc, const void *p, uint32_t n);

/* Encode f into out[64]: header, payload (bytes past f->len written as 0), CRC.
 * Format: fields little-endian. Range: f->type 1..LT_STREAM_TYPE_MAX, f->len <= 52.
 * Rounding: none. Overflow: none. Cost: none charged.
 * Returns: LT_OK, or LT_E_ARG for NULL pointers, a bad type or len > 52 (out untouched). */
lt_status_t lt_stream_encode(const lt_stream_frame_t *f, uint8_t out[LT_STREAM_FRAME_BYTES]);

/* Decode one frame from in[0..n). Checks, in order: n >= 64, magic, version, type, length,
 * reserved byte, CRC, zero padding. why (may be NULL) receives the first failed check.
 * Format: see lt_stream_encode. Range: any bytes. Rounding: none. Overflow: none. Cost: none.
 * Returns: LT_OK (f filled), LT_E_SPACE when n < 64 (64 written to *need if need != NULL),
 * LT_E_FORMAT for a failed check, LT_E_ARG for NULL in or f. */
lt_status_t lt_stream_decode(const uint8_t *in, uint32_t n, lt_stream_frame_t *f, uint32_t *need,
                             lt_stream_why_t *why);

/* ---- streaming decoder: frames out of an arbitrary byte stream ------------------------------- */

/* Decoder state, caller-allocated (120 bytes). A window of up to 64 bytes is kept between calls;
 * bytes that cannot start a valid frame are skipped as garbage (to the next 'L' 'T' candidate).
 * The counters are public and only ever grow. */
typedef struct lt_stream_dec {
    uint8_t win[LT_STREAM_FRAME_BYTES]; /* private: the candidate window */
    uint32_t have;                      /* private: bytes in win */
    uint32_t in_garbage;                /* private: 1 while inside a garbage run */
    uint64_t bytes;                     /* bytes consumed so far */
    uint64_t frames;                    /* valid frames returned */
    uint64_t garbage_bytes;             /* bytes skipped (not part of a valid frame) */
    uint64_t garbage_runs;              /* maximal runs of skipped bytes */
    uint64_t bad_header;                /* candidates with magic whose header failed a check */
    uint64_t bad_crc;                   /* candidates with a good header but bad CRC/padding */
} lt_stream_dec_t;
LT_STATIC_ASSERT(sizeof(lt_stream_dec_t) == 120, "decoder state is 120 bytes");

/* Reset d (counters to zero, window empty). */
void lt_stream_dec_init(lt_stream_dec_t *d);

/* Consume bytes from in[0..n) until one frame is complete. *used receives the bytes taken from in.
 * Format: see lt_stream_encode. Range: any bytes, any n (0 allowed). Rounding: none.
 * Overflow: counters are 64-bit. Cost: none; a garbage byte costs at most one 64-byte window scan.
 * Returns: LT_OK with *f filled (call again with in + *used for more), LT_E_SPACE when all n bytes
 * were taken and no frame completed (feed more), LT_E_ARG for NULL pointers. */
lt_status_t lt_stream_dec_push(lt_stream_dec_t *d, const uint8_t *in, uint32_t n, uint32_t *used,
                               lt_stream_frame_t *f);

/* End of stream: the bytes still held (a frame cut short) become garbage.
 * Returns: the number of bytes so discarded (0..63). */
uint32_t lt_stream_dec_finish(lt_stream_dec_t *d);

/* ---- typed payloads: pack into / unpack from a frame ----------------------------------------- */

/* Source kinds in HELLO. */
#define LT_STREAM_SRC_FIRMWARE 1u
#define LT_STREAM_SRC_SIM 2u
#define LT_STREAM_SRC_HOST 3u

/* Counter fields a device fills (HELLO valid bits); a field whose bit is clear is sent as 0. */
#define LT_STREAM_F_TICKS 0x01u     /* device tick clock (instructions, cycles) */
#define LT_STREAM_F_CYCLES 0x02u    /* modelled cycles (sim) */
#define LT_STREAM_F_AABB 0x04u      /* packet-box and ray-box tests */
#define LT_STREAM_F_TRIS 0x08u      /* packet-triangle and ray-triangle tests */

/* HELLO payload, 52 bytes on the wire. */
typedef struct lt_stream_hello {
    uint8_t source;             /* LT_STREAM_SRC_* */
    uint8_t tile_w, tile_h;     /* tile size in pixels */
    uint8_t flags;              /* bit 0: IMAGE frames may follow */
    uint32_t session;           /* device-chosen session id */
    uint32_t tick_hz;           /* device ticks per device second */
    uint32_t link_bytes_per_s;  /* link budget the batcher models (64000 for FS HID) */
    uint32_t ticks_per_report;  /* device ticks between two report slots */
    uint16_t width, height;     /* image size in pixels */
    uint16_t ntris;             /* scene triangles */
    uint16_t frames;            /* image frames the session will trace (0 = open-ended) */
    uint32_t valid;             /* LT_STREAM_F_* */
    uint32_t scene_hash;        /* FNV-1a of the scene's triangle words */
    char name[16];              /* target or machine, NUL-padded (need not be terminated) */
} lt_stream_hello_t;

/* TILE payload, 40 bytes on the wire. */
typedef struct lt_stream_tile {
    uint16_t frame, tile;       /* image frame number, tile index (row-major) */
    uint16_t rays, hits;        /* rays traced, rays that hit */
    uint32_t ticks;             /* device ticks spent on the tile */
    uint32_t cycles;            /* modelled cycles (LT_STREAM_F_CYCLES) */
    uint32_t aabb, aabb_rays;   /* packet-box tests, ray-box tests (LT_STREAM_F_AABB) */
    uint32_t tris, tri_rays;    /* packet-triangle tests, ray-triangle tests (LT_STREAM_F_TRIS) */
    uint32_t hash;              /* FNV-1a of the tile's (triangle id, t) per pixel */
    uint32_t t_end;             /* device tick (low 32 bits) when the tile finished */
} lt_stream_tile_t;

/* SUMMARY payload, 52 bytes on the wire. */
typedef struct lt_stream_summary {
    uint16_t frame, tiles;      /* image frame number, tiles traced */
    uint32_t rays, hits;
    uint64_t ticks, cycles;     /* device ticks and modelled cycles of the frame's tiles */
    uint32_t aabb, aabb_rays, tris, tri_rays;
    uint32_t hash;              /* FNV-1a over the tile hashes in tile order */
    uint32_t dropped;           /* reports the batcher dropped so far (all classes) */
} lt_stream_summary_t;

/* DROP payload, 24 bytes on the wire. */
typedef struct lt_stream_drop {
    uint32_t dropped;           /* reports dropped since the previous DROP record */
    uint32_t tile, image;       /* of which TILE reports, IMAGE frames */
    uint32_t total;             /* reports dropped since the session began */
    uint64_t t;                 /* device tick when the record was queued */
} lt_stream_drop_t;

/* IMAGE payload, 8 + count bytes on the wire. */
#define LT_STREAM_IMAGE_MAX 44u
#define LT_STREAM_IMG_ID8 1u /* one byte per pixel: triangle id + 1 (0 = miss), 255 = id >= 254 */
typedef struct lt_stream_image {
    uint16_t frame, tile;       /* image frame number, tile index */
    uint16_t offset;            /* first pixel, row-major within the tile */
    uint8_t count;              /* pixels in data, 1..44 */
    uint8_t format;             /* LT_STREAM_IMG_* */
    uint8_t data[LT_STREAM_IMAGE_MAX];
} lt_stream_image_t;

/* END payload, 32 bytes on the wire. */
typedef struct lt_stream_end {
    uint32_t frames_sent;       /* frames the batcher admitted, this END included (= seq count) */
    uint32_t dropped;           /* reports dropped in the session */
    uint64_t ticks;             /* device tick when tracing ended */
    uint64_t link_done;         /* device tick when the last frame left the link */
    uint32_t status;            /* 0 = ok, else a device error code */
    uint32_t frames;            /* image frames traced */
} lt_stream_end_t;

/* Pack a payload into f (type and len set, seq left alone). Format: little-endian fields at the
 * offsets of docs/stream.md. Range: image count 1..44. Rounding: none. Overflow: none. Cost: none.
 * Returns: LT_OK, or LT_E_ARG (NULL, or an image count out of range). */
lt_status_t lt_stream_pack_hello(const lt_stream_hello_t *p, lt_stream_frame_t *f);
lt_status_t lt_stream_pack_tile(const lt_stream_tile_t *p, lt_stream_frame_t *f);
lt_status_t lt_stream_pack_summary(const lt_stream_summary_t *p, lt_stream_frame_t *f);
lt_status_t lt_stream_pack_drop(const lt_stream_drop_t *p, lt_stream_frame_t *f);
lt_status_t lt_stream_pack_image(const lt_stream_image_t *p, lt_stream_frame_t *f);
lt_status_t lt_stream_pack_end(const lt_stream_end_t *p, lt_stream_frame_t *f);

/* Unpack a frame's payload. Format: as the packers. Range: any frame. Rounding: none.
 * Overflow: none. Cost: none.
 * Returns: LT_OK, LT_E_FORMAT when the type differs or len is not the type's length (IMAGE:
 * 8 + count with count 1..44), LT_E_ARG for NULL. */
lt_status_t lt_stream_unpack_hello(const lt_stream_frame_t *f, lt_stream_hello_t *p);
lt_status_t lt_stream_unpack_tile(const lt_stream_frame_t *f, lt_stream_tile_t *p);
lt_status_t lt_stream_unpack_summary(const lt_stream_frame_t *f, lt_stream_summary_t *p);
lt_status_t lt_stream_unpack_drop(const lt_stream_frame_t *f, lt_stream_drop_t *p);
lt_status_t lt_stream_unpack_image(const lt_stream_frame_t *f, lt_stream_image_t *p);
lt_status_t lt_stream_unpack_end(const lt_stream_frame_t *f, lt_stream_end_t *p);

/* Payload length of each fixed-size type (IMAGE: 0, it varies), indexed by lt_stream_type_t. */
uint32_t lt_stream_payload_len(uint32_t type);

/* ---- device-side batcher ------------------------------------------------------------------- */

/* Where sent bytes go (UART, USB endpoint buffer, stdout). Called with whole frames. */
typedef void (*lt_stream_sink_fn)(void *ctx, const uint8_t *bytes, uint32_t n);

/* Admission classes, most important first. */
typedef enum lt_stream_class {
    LT_STREAM_CLASS_CTRL = 0,  /* HELLO, SUMMARY, DROP, END: never dropped; the caller waits */
    LT_STREAM_CLASS_TILE = 1,  /* TILE reports: dropped when the ring holds limit[1] frames */
    LT_STREAM_CLASS_IMAGE = 2  /* IMAGE frames: dropped when the ring holds limit[2] frames */
} lt_stream_class_t;

/* Link and ring parameters. */
typedef struct lt_stream_link {
    uint32_t tick_hz;           /* device ticks per second (the clock `now` is measured in) */
    uint32_t link_bytes_per_s;  /* link budget, e.g. LT_STREAM_HID_BYTES_PER_S */
    uint32_t cap;               /* ring capacity in frames, 2..4096 */
    uint32_t limit[3];          /* per class: admit only while fewer frames are queued;
                                   limit[0] must equal cap, 1 <= limit[2] <= limit[1] <= cap */
} lt_stream_link_t;

/* Minimum distance between two DROP records, in report slots (the END flushes the rest). */
#define LT_STREAM_DROP_GAP 16u

/* Defaults: a 16-frame (1 KiB) ring, TILE reports up to 12 queued, IMAGE frames up to 8. */
void lt_stream_link_default(lt_stream_link_t *l, uint32_t tick_hz);

/* Batcher state, caller-allocated, with the ring in caller memory. Stats are public. */
typedef struct lt_stream_tx {
    uint8_t *ring;              /* private: cap frames of 64 bytes */
    lt_stream_sink_fn sink;     /* private */
    void *sink_ctx;             /* private */
    lt_stream_link_t link;      /* private: copy of the parameters */
    uint64_t period;            /* ticks between report slots: ceil(tick_hz * 64 / bytes_per_s) */
    uint64_t next_slot;         /* private: tick of the next slot a queued frame may use */
    uint32_t head, count;       /* private: ring read index, frames queued */
    uint32_t seq;               /* frames admitted (the next frame's sequence number, unwrapped) */
    uint32_t pend[3];           /* private: drops per class not yet reported by a DROP record */
    uint64_t drop_next;         /* private: earliest tick for the next DROP record */
    uint64_t sent_frames;       /* frames handed to the sink */
    uint64_t sent_bytes;
    uint64_t last_tx;           /* slot tick of the last frame sent (set before the sink call) */
    uint32_t dropped[3];        /* drops per class since init */
    uint32_t drop_records;      /* DROP records queued */
    uint32_t max_depth;         /* most frames ever queued */
    uint32_t full_waits;        /* CTRL pushes refused because the ring was full */
} lt_stream_tx_t;

/* Ring bytes for cap frames. Returns: LT_OK (*bytes = 64 cap), LT_E_ARG (cap outside 2..4096 or
 * NULL). */
lt_status_t lt_stream_tx_size(uint32_t cap, uint32_t *bytes);

/* Set up tx over ring[0..ring_bytes). Format: ticks. Range: see lt_stream_link_t; tick_hz and
 * link_bytes_per_s > 0. Rounding: the slot period rounds up. Overflow: none (64-bit ticks).
 * Returns: LT_OK, LT_E_ARG for a bad parameter, LT_E_SPACE when ring_bytes < 64 cap. */
lt_status_t lt_stream_tx_init(lt_stream_tx_t *tx, const lt_stream_link_t *l, void *ring,
                              uint32_t ring_bytes, lt_stream_sink_fn sink, void *ctx);

/* Send the queued frames whose report slots have come by tick `now` (one frame per slot; slots are
 * multiples of period; a slot with nothing queued is lost, as on USB). */
void lt_stream_tx_poll(lt_stream_tx_t *tx, uint64_t now);

/* Admit f (its seq is set here) in class cls at tick now, after polling. If reports were dropped
 * and the ring has room for both, a DROP record ("dropped N") is queued first, at most once per
 * LT_STREAM_DROP_GAP slots.
 * Returns: LT_OK (queued); LT_E_SPACE when not queued: for TILE/IMAGE the frame is dropped and
 * counted; for CTRL nothing is counted and *retry_at (if not NULL) gets the tick of the next slot:
 * wait until then and push again. LT_E_ARG for NULL or a frame the encoder rejects. */
lt_status_t lt_stream_tx_push(lt_stream_tx_t *tx, lt_stream_frame_t *f, lt_stream_class_t cls,
                              uint64_t now, uint64_t *retry_at);

/* End the session at tick now: queue the pending DROP record and an END record built from e
 * (frames_sent and dropped are filled in here), then send every queued frame at its slot.
 * The device need not wait: slot times are computed, not waited for. *link_done (may be NULL)
 * receives the slot tick of the last frame, also written into the END record.
 * Returns: LT_OK, LT_E_ARG for NULL tx or e. */
lt_status_t lt_stream_tx_finish(lt_stream_tx_t *tx, const lt_stream_end_t *e, uint64_t now,
                                uint64_t *link_done);

#ifdef __cplusplus
}
#endif
#endif /* LT_STREAM_H */
