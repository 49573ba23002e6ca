/* fuzz_blob.c - fuzz target of the firmware blob readers (firmware/apps/lt_sblob.c): scene blobs
 * (lt_sblob_open) and frusta blobs (lt_fblob_open) on arbitrary bytes, each as given and again
 * with its checksum word resealed, so that the structure checks behind the checksum are reached.
 * An accepted blob is traced (a scene blob's first tile in both modes, which must agree; a frusta
 * blob's first 4x4 tile): no read outside the blob, no fault, a defined status. The image is
 * capped at 64 x 64 pixels here so that an execution stays short. make fuzz-blob; replayed over
 * tests/fuzz/corpus/blob in make test. Host only.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "lt_sblob.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define REQUIRE(c)                                                                                 \
    do {                                                                                           \
        if (!(c))                                                                                  \
            abort();                                                                               \
    } while (0)

static void scene(const uint8_t *b, size_t n)
{
    lt_sblob_t s;
    lt_sblob_tile_t p, q;
    lt_status_t a, c;
    if (lt_sblob_open(b, n, &s) != LT_SBLOB_OK)
        return;
    REQUIRE(s.width >= 1 && s.width <= LT_SBLOB_MAX_RES && s.tiles_x >= 1);
    if (s.width > 64 || s.height > 64)
        return;
    p.ids = q.ids = NULL;
    a = lt_sblob_trace_tile(&s, 0, 0, NULL, &p);
    c = lt_sblob_trace_tile(&s, 0, 1, NULL, &q);
    REQUIRE(a == LT_OK || a == LT_E_DEPTH);
    REQUIRE(c == LT_OK || c == LT_E_DEPTH);
    if (a == LT_OK && c == LT_OK)
        REQUIRE(p.hash == q.hash && p.hits == q.hits && p.occluded == q.occluded);
    REQUIRE(lt_sblob_trace_tile(&s, s.tiles_x * s.tiles_y, 0, NULL, &p) == LT_E_ARG);
}

static void frusta(const uint8_t *b, size_t n)
{
    lt_fblob_t *f = malloc(sizeof *f);
    lt_fblob_tile_t r;
    lt_status_t st;
    if (f == NULL)
        return;
    if (lt_fblob_open(b, n, f) == LT_SBLOB_OK) {
        st = lt_fblob_trace_tile(f, 0, NULL, &r);
        REQUIRE(st == LT_OK || st == LT_E_DEPTH);
        REQUIRE(r.lit <= 16u && r.occluded <= 16u * f->spp);
        REQUIRE(lt_fblob_trace_tile(f, 16, NULL, &r) == LT_E_ARG);
    }
    free(f);
}

/* The input in a 64-byte aligned copy (the blobs are read in place as words), padded to a
 * multiple of 4; with `seal`, the checksum word of its kind recomputed. */
static void one(const uint8_t *data, size_t size, int seal)
{
    size_t n = (size + 3u) & ~(size_t)3u;
    uint8_t *b;
    if (posix_memalign((void **)&b, 64, n + 64u) != 0)
        return;
    memset(b, 0, n + 64u);
    memcpy(b, data, size);
    if (seal && size >= LT_SBLOB_HEADER_BYTES) {
        uint32_t bytes, w;
        memcpy(&bytes, b + 4u * LT_SB_BYTES, 4);
        if (bytes <= n && bytes >= LT_SBLOB_HEADER_BYTES) {
            w = lt_sblob_sum(b, bytes);
            memcpy(b + 4u * LT_SB_SUM, &w, 4);
        }
    }
    if (seal && size >= LT_FBLOB_HEADER_BYTES) {
        uint32_t bytes, w = 0, z = 0;
        memcpy(&bytes, b + 4u * LT_FB_BYTES, 4);
        if (bytes <= n && bytes >= LT_FBLOB_HEADER_BYTES) {
            memcpy(b + 4u * LT_FB_SUM, &z, 4);
            w = lt_sblob_fnv(LT_SBLOB_FNV0, b, bytes);
            memcpy(b + 4u * LT_FB_SUM, &w, 4);
        }
    }
    scene(b, n);
    frusta(b, n);
    free(b);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    one(data, size, 0);
    one(data, size, 1);
    return 0;
}
