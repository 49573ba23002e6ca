/* fw_slab.c - the slab-test kernel in a loop, for the instruction-count check of the scalar MCU
 * model: QEMU's lt_icount plugin counts instructions inside lt_slab16_q16 and the sim's mcu-m4
 * model predicts them for the same calls (tests/bench/icount.sh). Freestanding.
 */
#include "lt_fw.h"
#include "lt/lt.h"

#ifndef SLAB_CALLS
#define SLAB_CALLS 256
#endif

static lt_ray16_q16_t ray;

int main(void)
{
    uint32_t x = 12345u, hits = 0;
    int i, c;
    for (c = 0; c < SLAB_CALLS; c++) {
        lt_aabb_q16_t b;
        lt_vq16_t tn;
        int a;
        for (i = 0; i < LT_LANES; i++) {
            x = x * 1664525u + 1013904223u;
            ray.ox.l[i] = (int32_t)(x >> 9) - 0x400000;
            ray.oy.l[i] = (int32_t)(x >> 10) - 0x200000;
            ray.oz.l[i] = (int32_t)(x & 0xFFFFF) - 0x80000;
            ray.rx.l[i] = (int32_t)(x >> 12) - 0x80000;
            ray.ry.l[i] = (int32_t)(x >> 13) - 0x40000;
            ray.rz.l[i] = (int32_t)(x >> 14) - 0x20000;
            ray.tmin.l[i] = 0;
            ray.tmax.l[i] = 0x7FFFFFF;
            tn.l[i] = 0;
        }
        for (a = 0; a < 3; a++) {
            x = x * 1664525u + 1013904223u;
            b.lo[a] = (int32_t)(x >> 10) - 0x200000;
            b.hi[a] = b.lo[a] + (int32_t)(x & 0x3FFFF);
        }
        hits += lt_mask16_popcount(lt_slab16_q16(&ray, (lt_mask16_t)(x >> 7), &b, &tn));
    }
    lt_fw_puts("slab calls ");
    lt_fw_put_u32(SLAB_CALLS);
    lt_fw_puts(" lane hits ");
    lt_fw_put_u32(hits);
    lt_fw_puts("\n");
    return 0;
}
