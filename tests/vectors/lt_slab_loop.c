/* lt_slab_loop.c - see lt_slab_loop.h. Freestanding. */
#include "lt_slab_loop.h"
#include "lt/lt.h"

static lt_ray16_q16_t ray;

uint32_t lt_slab_loop(int calls)
{
    uint32_t x = 12345u, hits = 0;
    int i, c;
    for (c = 0; c < calls; c++) {
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
        hits += lt__popcount32(lt_slab16_q16(&ray, (lt_mask16_t)(x >> 7), &b, &tn));
    }
    return hits;
}
