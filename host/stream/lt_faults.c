/* lt_faults.c - the fault injector of lt_faults.h. Input frames are found with the core streaming
 * decoder and re-encoded (the encoding is unique: zero padding, fixed header), one fault at most is
 * drawn per frame, and a frame chosen for reordering is held until the next one has gone out.
 * Host only.
 */
#include "stream/lt_faults.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct lt_faults {
    lt_faults_cfg_t cfg;
    lt_faults_out_fn out;
    void *ctx;
    uint64_t rng;
    lt_stream_dec_t dec;
    uint8_t held[LT_STREAM_FRAME_BYTES]; /* frame waiting to go out after the next one */
    int have_held;
    uint8_t cut[LT_STREAM_FRAME_BYTES];  /* truncated frame waiting for the byte that follows */
    uint32_t cut_keep;                   /* bytes of it to keep */
    int have_cut;
    lt_faults_truth_t t;
};

static uint64_t rng_next(lt_faults_t *fi)
{
    uint64_t x = fi->rng;
    x ^= x >> 12;
    x ^= x << 25;
    x ^= x >> 27;
    fi->rng = x;
    return x * 0x2545F4914F6CDD1Du;
}

/* Uniform in [0, 1) with 53 bits. */
static double rng_unit(lt_faults_t *fi)
{
    return (double)(rng_next(fi) >> 11) * (1.0 / 9007199254740992.0);
}

/* Uniform in [0, n), n >= 1. */
static uint32_t rng_below(lt_faults_t *fi, uint32_t n)
{
    return (uint32_t)(((rng_next(fi) >> 32) * (uint64_t)n) >> 32);
}

int lt_faults_check(const lt_faults_cfg_t *c, lt_diag_t *diag)
{
    const double r[5] = {c->drop, c->corrupt, c->dup, c->reorder, c->trunc};
    const char *n[5] = {"drop", "corrupt", "dup", "reorder", "trunc"};
    double sum = 0.0;
    int i;
    for (i = 0; i < 5; i++) {
        if (!(r[i] >= 0.0 && r[i] <= 1.0)) {
            lt_diag_fail(diag, "--%s %g: a rate must be in [0, 1]", n[i], r[i]);
            return -1;
        }
        sum += r[i];
    }
    if (sum > 1.0 + 1e-12) {
        lt_diag_fail(diag, "rates sum to %g: at most one fault per frame, so the sum must be "
                     "<= 1", sum);
        return -1;
    }
    if (c->max_flips < 1 || c->max_flips > 8) {
        lt_diag_fail(diag, "--flips %u: expected 1..8", c->max_flips);
        return -1;
    }
    return 0;
}

lt_faults_t *lt_faults_new(const lt_faults_cfg_t *c, lt_faults_out_fn out, void *ctx,
                           lt_diag_t *diag)
{
    lt_faults_t *fi;
    uint64_t z;
    if (lt_faults_check(c, diag) != 0)
        return NULL;
    fi = calloc(1, sizeof *fi);
    if (fi == NULL) {
        lt_diag_fail(diag, "out of memory");
        return NULL;
    }
    fi->cfg = *c;
    fi->out = out;
    fi->ctx = ctx;
    z = c->seed + 0x9E3779B97F4A7C15u;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9u;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBu;
    z ^= z >> 31;
    fi->rng = z != 0 ? z : 0x2545F4914F6CDD1Du;
    lt_stream_dec_init(&fi->dec);
    return fi;
}

/* Write the pending truncated frame, now that the next byte is known (next < 0: end of output).
 * A cut whose first removed byte equals the byte that follows is no cut at all: the receiver's
 * window would hold the original frame again (and the following frame would lose its first byte
 * instead). So the cut is moved one byte earlier until the removed part starts differently;
 * byte 1 ('T') always remains. This keeps the ground truth exact at the byte level. */
static void flush_cut(lt_faults_t *fi, int next)
{
    uint32_t keep = fi->cut_keep;
    if (!fi->have_cut)
        return;
    fi->have_cut = 0;
    while (next >= 0 && keep > 1 && fi->cut[keep] == (uint8_t)next)
        keep--;
    fi->out(fi->ctx, fi->cut, keep);
    fi->t.bytes_out += keep;
    fi->t.damaged_bytes += keep;
}

static void emit(lt_faults_t *fi, const uint8_t *b, size_t n)
{
    flush_cut(fi, b[0]);
    fi->out(fi->ctx, b, n);
    fi->t.bytes_out += n;
}

/* An intact frame goes out. */
static void emit_frame(lt_faults_t *fi, const uint8_t *b)
{
    emit(fi, b, LT_STREAM_FRAME_BYTES);
    fi->t.frames_out++;
    fi->t.tail_destroyed = 0;
}

static void one_frame(lt_faults_t *fi, const uint8_t *fr)
{
    double u = rng_unit(fi), c = 0.0;
    const lt_faults_cfg_t *g = &fi->cfg;
    fi->t.frames_in++;
    if (fi->have_held) {
        /* the partner of a reorder: goes first and intact, then the held frame */
        fi->have_held = 0;
        emit_frame(fi, fr);
        emit_frame(fi, fi->held);
        return;
    }
    if (u < (c += g->drop)) {
        fi->t.dropped++;
        fi->t.tail_destroyed++;
    } else if (u < (c += g->corrupt)) {
        uint8_t b[LT_STREAM_FRAME_BYTES];
        uint32_t flips = 1 + rng_below(fi, g->max_flips), done = 0, pos[8];
        memcpy(b, fr, sizeof b);
        while (done < flips) {
            uint32_t p = rng_below(fi, LT_STREAM_FRAME_BYTES * 8), i;
            for (i = 0; i < done && pos[i] != p; i++) {
            }
            if (i < done)
                continue; /* distinct positions: a bit flipped twice would be no flip */
            pos[done++] = p;
            b[p / 8] ^= (uint8_t)(1u << (p % 8));
        }
        emit(fi, b, sizeof b);
        fi->t.corrupted++;
        fi->t.flipped_bits += flips;
        fi->t.damaged_bytes += sizeof b;
        fi->t.tail_destroyed++;
    } else if (u < (c += g->dup)) {
        emit_frame(fi, fr);
        emit_frame(fi, fr);
        fi->t.duplicated++;
    } else if (u < (c += g->reorder)) {
        memcpy(fi->held, fr, LT_STREAM_FRAME_BYTES);
        fi->have_held = 1;
        fi->t.reordered++;
    } else if (u < (c += g->trunc)) {
        flush_cut(fi, fr[0]);
        memcpy(fi->cut, fr, LT_STREAM_FRAME_BYTES);
        fi->cut_keep = 1 + rng_below(fi, LT_STREAM_FRAME_BYTES - 1);
        fi->have_cut = 1;
        fi->t.truncated++;
        fi->t.tail_destroyed++;
    } else {
        emit_frame(fi, fr);
    }
}

void lt_faults_feed(lt_faults_t *fi, const uint8_t *b, size_t n)
{
    while (n > 0) {
        lt_stream_frame_t f;
        uint8_t enc[LT_STREAM_FRAME_BYTES];
        uint32_t used = 0, chunk = n > 0x10000000u ? 0x10000000u : (uint32_t)n;
        lt_status_t s = lt_stream_dec_push(&fi->dec, b, chunk, &used, &f);
        b += used;
        n -= used;
        if (s != LT_OK)
            continue;
        if (lt_stream_encode(&f, enc) == LT_OK)
            one_frame(fi, enc);
    }
    fi->t.input_garbage = fi->dec.garbage_bytes;
}

void lt_faults_finish(lt_faults_t *fi)
{
    lt_stream_dec_finish(&fi->dec);
    fi->t.input_garbage = fi->dec.garbage_bytes;
    if (fi->have_held) {
        fi->have_held = 0;
        fi->t.reordered--;
        emit_frame(fi, fi->held);
    }
    flush_cut(fi, -1);
}

const lt_faults_truth_t *lt_faults_truth(const lt_faults_t *fi) { return &fi->t; }

void lt_faults_free(lt_faults_t *fi) { free(fi); }
