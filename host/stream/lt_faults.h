/* lt_faults.h - fault injection on a frame stream (lt_stream.h) for testing receivers: each input
 * frame independently gets at most one fault, drawn with the given rates from a seeded PRNG
 * (xorshift64*, splitmix64-seeded): dropped, corrupted (1..max_flips distinct bit flips),
 * duplicated (sent twice), reordered (swapped with the next frame, which itself stays intact) or
 * truncated (cut to 1..63 bytes; never where the removed bytes would equal the bytes that follow,
 * which would make the cut invisible). The ground truth of what was done is kept for the caller to
 * compare with a receiver's report. Host only.
 */
#ifndef LT_FAULTS_H
#define LT_FAULTS_H

#include <stddef.h>
#include <stdint.h>

#include "io/lt_diag.h"
#include "lt/lt_stream.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct lt_faults_cfg {
    double drop, corrupt, dup, reorder, trunc; /* per-frame probabilities, each >= 0, sum <= 1 */
    uint32_t max_flips;                        /* corrupt: 1..max_flips bit flips (1..8; CRC-32C
                                                  detects every pattern of up to 5 in 512 bits) */
    uint64_t seed;
} lt_faults_cfg_t;

/* What the injector did. */
typedef struct lt_faults_truth {
    uint64_t frames_in;      /* frames read */
    uint64_t frames_out;     /* intact frames written (duplicates counted twice) */
    uint64_t bytes_out;      /* bytes written */
    uint64_t dropped, corrupted, duplicated, reordered, truncated;
    uint64_t flipped_bits;   /* bits flipped in total */
    uint64_t damaged_bytes; /* bytes of corrupted and truncated frames written (the garbage a
                               receiver must skip: 64 per corruption + the kept part of each cut) */
    uint64_t tail_destroyed; /* destroyed (dropped/corrupted/truncated) frames at the very end:
                                a receiver cannot know these without the END record */
    uint64_t input_garbage;  /* bytes of the input that were not valid frames (not passed on) */
} lt_faults_truth_t;

typedef struct lt_faults lt_faults_t;

typedef void (*lt_faults_out_fn)(void *ctx, const uint8_t *b, size_t n);

/* Check a configuration. Returns 0, or -1 with a message naming the bad value. */
int lt_faults_check(const lt_faults_cfg_t *c, lt_diag_t *diag);

/* A new injector writing to out (cfg checked first; NULL with a message in diag on failure). */
lt_faults_t *lt_faults_new(const lt_faults_cfg_t *c, lt_faults_out_fn out, void *ctx,
                           lt_diag_t *diag);

/* Feed the input stream in any chunking (frames are found with the core decoder). */
void lt_faults_feed(lt_faults_t *fi, const uint8_t *b, size_t n);

/* End of input: a frame held for a reorder goes out unchanged (that reorder is not counted). */
void lt_faults_finish(lt_faults_t *fi);

const lt_faults_truth_t *lt_faults_truth(const lt_faults_t *fi);

void lt_faults_free(lt_faults_t *fi);

#ifdef __cplusplus
}
#endif
#endif /* LT_FAULTS_H */
