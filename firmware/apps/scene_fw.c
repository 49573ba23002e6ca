/* scene_fw.c - the scene-blob firmware: traces the scene blob linked into the image
 * (lt_fw_blob.S; made by `lanetrace pack`) tile by tile, primary rays and hard shadows in s15.16,
 * and prints the lines `lanetrace pack --trace` prints on the host for the same blob (tests compare
 * them bit for bit), then the instructions it spent per ray. The scene stays in read-only memory:
 * the RAM it needs is the stack of one tile (docs/firmware.md, "Scene blobs").
 * Exit 0; 1 when the blob is refused (the line names why); 2 when a traversal fails.
 * Builds: firmware only.
 */
#include "lt_fw.h"
#include "lt_fw_blob.h"
#include "lt_sblob.h"

/* n / d with one decimal, "12.3" */
static void put_ratio(uint64_t n, uint64_t d)
{
    uint64_t q = d != 0 ? (10u * n + d / 2u) / d : 0;
    lt_fw_put_u32((uint32_t)(q / 10u));
    lt_fw_putc('.');
    lt_fw_putc('0' + (int)(q % 10u));
}

static void put_counts(uint32_t hash, uint32_t rays, uint32_t hits, uint32_t srays,
                       uint32_t occ)
{
    lt_fw_puts(" hash ");
    lt_fw_put_hex32(hash);
    lt_fw_puts(" rays ");
    lt_fw_put_u32(rays);
    lt_fw_puts(" hits ");
    lt_fw_put_u32(hits);
    lt_fw_puts(" shadow ");
    lt_fw_put_u32(srays);
    lt_fw_puts(" occluded ");
    lt_fw_put_u32(occ);
    lt_fw_puts("\n");
}

/* Every tile in one mode; prints the tile lines (packets only) and the image line. Returns 0, or
 * 2 after a line when a traversal fails. */
static int run(const lt_sblob_t *s, int single, uint64_t *tp, uint64_t *ts, uint32_t *rays,
               uint32_t *srays)
{
    uint32_t t, hash = LT_SBLOB_FNV0, hits = 0, occ = 0;
    *tp = *ts = 0;
    *rays = *srays = 0;
    for (t = 0; t < s->tiles_x * s->tiles_y; t++) {
        lt_sblob_tile_t r;
        r.ids = (int32_t *)0;
        if (lt_sblob_trace_tile(s, t, single, lt_fw_ticks, &r) != LT_OK) {
            lt_fw_puts("tile ");
            lt_fw_put_u32(t);
            lt_fw_puts(" failed\n");
            return 2;
        }
        if (!single) {
            lt_fw_puts("tile ");
            lt_fw_put_u32(t);
            put_counts(r.hash, r.rays, r.hits, r.srays, r.occluded);
        }
        hash = lt_sblob_fnv(hash, &r.hash, 4);
        *rays += r.rays;
        hits += r.hits;
        *srays += r.srays;
        occ += r.occluded;
        *tp += r.t_primary;
        *ts += r.t_shadow;
    }
    lt_fw_puts(single ? "image single rays" : "image");
    put_counts(hash, *rays, hits, *srays, occ);
    return 0;
}

static void put_instr(const char *mode, uint64_t tp, uint64_t ts, uint32_t rays, uint32_t srays)
{
    lt_fw_puts("instr " LT_FW_TARGET_NAME " ");
    lt_fw_puts(mode);
    lt_fw_puts(" primary ");
    put_ratio(tp, rays);
    lt_fw_puts(" shadow ");
    put_ratio(ts, srays);
    lt_fw_puts(" per ray\n");
}

int main(void)
{
    lt_sblob_t s;
    uint64_t t0 = lt_fw_ticks(), tp[2], ts[2];
    lt_sblob_err_t e = lt_sblob_open(lt_fw_blob, lt_fw_blob_size(), &s);
    uint32_t t1 = (uint32_t)(lt_fw_ticks() - t0), rays[2], srays[2];
    int m;
    if (e != LT_SBLOB_OK) {
        lt_fw_puts("sblob refused: ");
        lt_fw_puts(lt_sblob_err_str(e));
        lt_fw_puts("\n");
        return 1;
    }
    lt_fw_puts("sblob ");
    lt_fw_put_u32(s.bvh.ntris);
    lt_fw_puts(" triangles, ");
    lt_fw_put_u32(s.bvh.nnodes);
    lt_fw_puts(" nodes, ");
    lt_fw_put_u32(s.width);
    lt_fw_putc('x');
    lt_fw_put_u32(s.height);
    lt_fw_puts(" pixels, ");
    lt_fw_put_u32(s.tiles_x * s.tiles_y);
    lt_fw_puts(" tiles, ");
    lt_fw_puts((s.flags & LT_SBLOB_F_SHADOWS) ? "shadows, " : "no shadows, ");
    lt_fw_put_u32((uint32_t)lt_fw_blob_size());
    lt_fw_puts(" bytes\n");
    for (m = 0; m < 2; m++)
        if (run(&s, m, &tp[m], &ts[m], &rays[m], &srays[m]) != 0)
            return 2;
    /* instructions under QEMU -icount shift=0 (rv32: mcycle, exact; Arm: SysTick, 40 or 31.25
       instructions per tick, read twice per 4x4 group) */
    lt_fw_puts("instr " LT_FW_TARGET_NAME " open ");
    lt_fw_put_u32(t1);
    lt_fw_puts(" (checks and checksum of the blob)\n");
    put_instr("packets", tp[0], ts[0], rays[0], srays[0]);
    put_instr("single", tp[1], ts[1], rays[1], srays[1]);
    return 0;
}
