/* scene_fw.c - the scene-blob firmware: runs the blob linked into the image (lt_fw_blob.S) and
 * prints the lines the host prints for the same blob (tests compare them bit for bit), then the
 * instructions it spent per ray. A scene blob (`lanetrace pack`): its image tile by tile, primary
 * rays and hard shadows in s15.16, as packets and as single rays. A frusta blob (`lanetrace
 * shadows --pack-block`): its 16x16 block's soft shadows by S-Frusta, 4x4 tile by tile, and
 * whether the block equals the whole scene's answer the host stored. The blob stays in read-only
 * memory: the RAM it needs is the stack of one tile (docs/firmware.md, "Scene blobs").
 * Exit 0; 1 when the blob is refused (the line names why); 2 when a traversal fails; 3 when a
 * frusta block differs from the whole scene's. Builds: firmware only.
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

/* The tracers' clock: marks the stage for the QEMU plugin's cycle model (lt_fw_stage), then
 * reads the instruction clock (so the read is charged to the stage that begins). */
static uint64_t fw_clock(uint32_t stage)
{
    lt_fw_stage(stage);
    return lt_fw_ticks();
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
        if (lt_sblob_trace_tile(s, t, single, fw_clock, &r) != LT_OK) {
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

/* The line of a refused blob ("sblob refused: checksum differs..."); returns the exit code 1. */
static int refused(const char *kind, lt_sblob_err_t e)
{
    lt_fw_puts(kind);
    lt_fw_puts(" refused: ");
    lt_fw_puts(lt_sblob_err_str(e));
    lt_fw_puts("\n");
    return 1;
}

/* A frusta blob: the 16 tiles of its block, the block line, instructions per shadow sample. */
static int run_frusta(void)
{
    lt_fblob_t f; /* with its 6.4 KB sample table, on the stack (scene blobs do not need it) */
    uint64_t t0 = lt_fw_ticks(), ticks = 0;
    lt_sblob_err_t e = lt_fblob_open(lt_fw_blob, lt_fw_blob_size(), &f);
    uint32_t t1 = (uint32_t)(lt_fw_ticks() - t0), th[16], t, lit = 0, occ = 0, h;
    if (e != LT_SBLOB_OK)
        return refused("fblob", e);
    lt_fw_puts("fblob ");
    lt_fw_put_u32(f.bvh.ntris);
    lt_fw_puts(" triangles (of ");
    lt_fw_put_u32(f.scene_tris);
    lt_fw_puts("), block ");
    lt_fw_put_u32(f.bx);
    lt_fw_putc(',');
    lt_fw_put_u32(f.by);
    lt_fw_puts(", spp ");
    lt_fw_put_u32(f.spp);
    lt_fw_puts(", ");
    lt_fw_put_u32((uint32_t)lt_fw_blob_size());
    lt_fw_puts(" bytes\n");
    for (t = 0; t < 16u; t++) {
        lt_fblob_tile_t r;
        if (lt_fblob_trace_tile(&f, t, fw_clock, &r) != LT_OK) {
            lt_fw_puts("ftile failed\n");
            return 2;
        }
        lt_fw_puts("ftile ");
        lt_fw_put_u32(t);
        lt_fw_puts(" hash ");
        lt_fw_put_hex32(r.hash);
        lt_fw_puts(" lit ");
        lt_fw_put_u32(r.lit);
        lt_fw_puts(" occluded ");
        lt_fw_put_u32(r.occluded);
        lt_fw_puts("\n");
        th[t] = r.hash;
        lit += r.lit;
        occ += r.occluded;
        ticks += r.ticks;
    }
    h = lt_fblob_block_hash(th);
    lt_fw_puts("block hash ");
    lt_fw_put_hex32(h);
    lt_fw_puts(" lit ");
    lt_fw_put_u32(lit);
    lt_fw_puts(" occluded ");
    lt_fw_put_u32(occ);
    lt_fw_puts(" (whole scene ");
    lt_fw_put_hex32(f.ref);
    lt_fw_puts(h == f.ref ? ": equal)\n" : ": differs)\n");
    lt_fw_puts("instr " LT_FW_TARGET_NAME " open ");
    lt_fw_put_u32(t1);
    lt_fw_puts(" (checks, checksum, sample table)\n");
    lt_fw_puts("instr " LT_FW_TARGET_NAME " frusta per shadow sample ");
    put_ratio(ticks, (uint64_t)lit * f.spp);
    lt_fw_puts(", per lit pixel ");
    put_ratio(ticks, lit);
    lt_fw_puts("\n");
    return h == f.ref ? 0 : 3;
}

int main(void)
{
    lt_sblob_t s;
    uint64_t t0, tp[2], ts[2];
    lt_sblob_err_t e;
    uint32_t t1, rays[2], srays[2];
    int m;
    if (lt_fw_blob_size() >= 4u &&
        ((uint32_t)lt_fw_blob[0] | (uint32_t)lt_fw_blob[1] << 8 | (uint32_t)lt_fw_blob[2] << 16 |
         (uint32_t)lt_fw_blob[3] << 24) == LT_FBLOB_MAGIC)
        return run_frusta();
    t0 = lt_fw_ticks();
    e = lt_sblob_open(lt_fw_blob, lt_fw_blob_size(), &s);
    t1 = (uint32_t)(lt_fw_ticks() - t0);
    if (e != LT_SBLOB_OK)
        return refused("sblob", e);
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
