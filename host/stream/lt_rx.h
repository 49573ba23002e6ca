/* lt_rx.h - the host side of the stream protocol (firmware/include/lt/lt_stream.h): byte sources
 * (file, pipe or stdin; a serial device in termios raw mode; a TCP client; hidapi in
 * host/stream/usb/lt_rx_hid.h) and the receiver, which decodes frames with the core's streaming decoder
 * and accounts for every frame the device sent: received, lost, damaged (corrupt or truncated),
 * duplicated, reordered, plus the device's own DROP records, tile reports and frame summaries.
 * Host only (POSIX). Functions report errors in an lt_diag_t (naming the input and the limit).
 */
#ifndef LT_RX_H
#define LT_RX_H

#include <stddef.h>
#include <stdint.h>

#include "io/lt_diag.h"
#include "lt/lt_stream.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- byte sources ---------------------------------------------------------------------------- */

typedef struct lt_rx_src lt_rx_src_t;

/* Results of lt_rx_src_read besides a byte count > 0. */
#define LT_RX_EOF 0
#define LT_RX_ERROR (-1)
#define LT_RX_TIMEOUT (-2)

/* A transport: read returns bytes (> 0), LT_RX_EOF, LT_RX_ERROR (message in diag) or
 * LT_RX_TIMEOUT after timeout_ms (< 0: wait for ever). close releases ctx. */
typedef struct lt_rx_src_ops {
    long (*read)(void *ctx, uint8_t *buf, size_t n, int timeout_ms, lt_diag_t *diag);
    void (*close)(void *ctx);
} lt_rx_src_ops_t;

/* path "-" is stdin. Returns NULL with a message naming the path on failure. */
lt_rx_src_t *lt_rx_src_file(const char *path, lt_diag_t *diag);

/* A serial device (tty), raw 8N1, no flow control, at baud (0 = leave the speed alone).
 * Supported speeds: 9600 .. 230400 (POSIX), plus 460800 .. 4000000 where <termios.h> has them.
 * Returns NULL with a message naming the device (not a tty, unsupported speed, open failed). */
lt_rx_src_t *lt_rx_src_serial(const char *dev, uint32_t baud, lt_diag_t *diag);

/* A TCP client for "HOST:PORT" (e.g. QEMU's -serial tcp:127.0.0.1:PORT,server=on). A refused
 * connection is retried every 50 ms for up to connect_ms (a just-started server may not listen
 * yet). Returns NULL with a message naming HOST:PORT. */
lt_rx_src_t *lt_rx_src_tcp(const char *hostport, int connect_ms, lt_diag_t *diag);

/* Any other transport (hidapi, tests). live = 1 for sources that never reach EOF (serial, HID):
 * the receiver then stops at the END record. name is copied. */
lt_rx_src_t *lt_rx_src_custom(const lt_rx_src_ops_t *ops, void *ctx, const char *name, int live);

long lt_rx_src_read(lt_rx_src_t *s, uint8_t *buf, size_t n, int timeout_ms, lt_diag_t *diag);
const char *lt_rx_src_name(const lt_rx_src_t *s);
int lt_rx_src_live(const lt_rx_src_t *s);
void lt_rx_src_close(lt_rx_src_t *s);

/* ---- receiver -------------------------------------------------------------------------------- */

/* How an accepted (CRC-valid) frame was classified. */
typedef enum lt_rx_kind {
    LT_RX_NEW = 0,        /* first copy, in order (sequence above every earlier one) */
    LT_RX_REORDERED = 1,  /* first copy, but after a later sequence number */
    LT_RX_DUPLICATE = 2,  /* a sequence number already received */
    LT_RX_STALE = 3       /* older than the 4096-frame window: cannot tell; not used */
} lt_rx_kind_t;

/* Everything the receiver counted. Link fields are totals over all sessions; "sent" comes from
 * the END record (frames_sent) or, without one, from the highest sequence number seen + 1. */
typedef struct lt_rx_stats {
    /* bytes and frames */
    uint64_t bytes;          /* bytes fed */
    uint64_t valid;          /* CRC-valid frames (every copy) */
    uint64_t by_type[LT_STREAM_TYPE_MAX + 1]; /* unique frames per type */
    /* link accounting */
    uint64_t sent;           /* frames the device sent (see above) */
    uint64_t received;       /* distinct sequence numbers received */
    uint64_t lost;           /* sent - received: never arrived intact */
    uint64_t damaged;        /* of lost: estimated destroyed by corruption or truncation (per
                                gap with garbage: max(ceil(garbage / 64), rejected candidates),
                                at most the gap; in total at most lost) */
    uint64_t duplicates;
    uint64_t reordered;
    uint64_t stale;
    uint64_t garbage_bytes;  /* bytes not part of any valid frame (incl. a cut-off tail) */
    uint64_t garbage_runs;
    uint64_t bad_header;     /* magic found, header invalid */
    uint64_t bad_crc;        /* header valid, CRC (or padding) invalid */
    uint64_t tail_bytes;     /* bytes of a frame cut off by the end of the stream */
    uint64_t bad_payload;    /* CRC-valid frames whose payload length does not fit their type */
    char bad_payload_first[128]; /* the first of them: "frame seq S (TYPE): payload of L bytes ..." */
    uint32_t last_seq;       /* sequence number of the last CRC-valid frame (valid > 0) */
    uint64_t bad_record;     /* CRC-valid records whose content contradicts the session's HELLO
                                or itself (lt_rx_check_record): a tile outside the image, a
                                (frame, tile) reported twice, more rays than pixels, more hits
                                than rays, a frame past the session's count, an image or tile
                                size of 0, a second HELLO without END */
    char bad_first[192];     /* the first of them: "frame seq S (TYPE): what, the limit" */
    uint32_t sessions;       /* HELLO records that started a session (1 normally) */
    int have_hello;          /* a HELLO was received (the last session's is in hello) */
    int have_end;            /* the last session's END record was received */
    /* the device's view */
    lt_stream_hello_t hello;
    lt_stream_end_t end;
    uint64_t tiles;          /* TILE reports received (unique) */
    uint64_t images;         /* IMAGE frames received (unique) */
    uint64_t summaries;
    uint64_t drop_records;
    uint64_t dev_dropped;    /* sum of DROP records' "dropped" */
    uint64_t dev_dropped_tile, dev_dropped_image;
    uint64_t rays, hits;     /* from TILE reports */
    uint64_t tile_ticks, tile_cycles;
    uint64_t sum_tiles, sum_rays, sum_hits; /* from SUMMARY records */
    uint64_t sum_ticks, sum_cycles;
} lt_rx_stats_t;

typedef struct lt_rx lt_rx_t;

/* Called for every CRC-valid frame, with its classification. */
typedef void (*lt_rx_frame_fn)(void *ctx, const lt_stream_frame_t *f, lt_rx_kind_t kind);

/* A new receiver; cb may be NULL. Returns NULL only when out of memory. */
lt_rx_t *lt_rx_new(lt_rx_frame_fn cb, void *ctx);

/* Feed bytes in any chunking. */
void lt_rx_feed(lt_rx_t *rx, const uint8_t *b, size_t n);

/* End of stream: a partial frame still held becomes garbage (tail_bytes). A second call without
 * new bytes changes nothing. */
void lt_rx_finish(lt_rx_t *rx);

/* Current counters (up to date after every feed; sent comes from END once it arrived). */
const lt_rx_stats_t *lt_rx_stats(const lt_rx_t *rx);

/* 1 once the current session's END record has been received. */
int lt_rx_done(const lt_rx_t *rx);

void lt_rx_free(lt_rx_t *rx);

/* Name of a frame type ("HELLO", ...; "?" for others). */
const char *lt_rx_type_name(uint32_t type);

#ifdef __cplusplus
}
#endif
#endif /* LT_RX_H */
