/* lt_slab_loop.c - see lt_slab_loop.h. Freestanding. */
#include "lt_slab_loop.h"
#include "lt/lt.h"
#include "lt_f32_bits.h"

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

#if LT_CFG_FLOAT32
static lt_ray16_f32_t fray;

/* The same packets and boxes as lt_slab_loop, converted to the nearest floats by integer
 * operations (lt_f32_bits.h): no float helper runs outside the kernel. */
uint32_t lt_slab_loop_f32(int calls)
{
    uint32_t x = 12345u, hits = 0;
    int i, c;
    for (c = 0; c < calls; c++) {
        lt_aabb_f32_t b;
        lt_vf32_t tn;
        int a;
        for (i = 0; i < LT_LANES; i++) {
            x = x * 1664525u + 1013904223u;
            fray.ox.l[i] = lt_loop_f32_from_fx((int32_t)(x >> 9) - 0x400000, 16u);
            fray.oy.l[i] = lt_loop_f32_from_fx((int32_t)(x >> 10) - 0x200000, 16u);
            fray.oz.l[i] = lt_loop_f32_from_fx((int32_t)(x & 0xFFFFF) - 0x80000, 16u);
            fray.rx.l[i] = lt_loop_f32_from_fx((int32_t)(x >> 12) - 0x80000, 16u);
            fray.ry.l[i] = lt_loop_f32_from_fx((int32_t)(x >> 13) - 0x40000, 16u);
            fray.rz.l[i] = lt_loop_f32_from_fx((int32_t)(x >> 14) - 0x20000, 16u);
            fray.tmin.l[i] = lt_loop_f32_from_fx(0, 16u);
            fray.tmax.l[i] = lt_loop_f32_from_fx(0x7FFFFFF, 16u);
            tn.l[i] = lt_loop_f32_from_fx(0, 16u);
        }
        for (a = 0; a < 3; a++) {
            int32_t lo;
            x = x * 1664525u + 1013904223u;
            lo = (int32_t)(x >> 10) - 0x200000;
            b.lo[a] = lt_loop_f32_from_fx(lo, 16u);
            b.hi[a] = lt_loop_f32_from_fx(lo + (int32_t)(x & 0x3FFFF), 16u);
        }
        hits += lt__popcount32(lt_slab16_f32(&fray, (lt_mask16_t)(x >> 7), &b, &tn));
    }
    return hits;
}
#endif
