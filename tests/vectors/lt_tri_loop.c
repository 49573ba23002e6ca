/* lt_tri_loop.c - see lt_tri_loop.h. Freestanding. */
#include "lt_tri_loop.h"
#include "lt/lt.h"
#include "lt_f32_bits.h"

static lt_ray16_q16_t ray;
static lt_hit16_t hit;

static uint32_t lcg(uint32_t *x)
{
    *x = *x * 1664525u + 1013904223u;
    return *x;
}

uint32_t lt_tri_loop(int calls)
{
    uint32_t x = 777u, hits = 0;
    int i, c;
    for (c = 0; c < calls; c++) {
        lt_tri_q16_t t;
        lt_mask16_t k;
        int a;
        if ((c & 3) == 0) {
            /* Origins around (0, 0, -16) +- 4 units; directions mostly +z, |d| < 1, s1.30. */
            for (i = 0; i < LT_LANES; i++) {
                ray.ox.l[i] = (int32_t)(lcg(&x) >> 13) - 0x40000;
                ray.oy.l[i] = (int32_t)(lcg(&x) >> 13) - 0x40000;
                ray.oz.l[i] = -16 * 65536 + (int32_t)(lcg(&x) >> 14) - 0x20000;
                ray.dx.l[i] = (int32_t)(lcg(&x) >> 3) - 0x10000000;  /* +-0.25 */
                ray.dy.l[i] = (int32_t)(lcg(&x) >> 3) - 0x10000000;
                ray.dz.l[i] = 0x39999999;                             /* 0.9 */
                ray.rx.l[i] = ray.ry.l[i] = ray.rz.l[i] = 0;
                ray.tmin.l[i] = 0;
                ray.tmax.l[i] = 0x7FFFFFF;
                hit.id.l[i] = -1;
            }
        }
        /* A triangle near z = 0 with legs of 2..18 units from a corner at (-6, -6) +- 4 units
         * (some miss every lane); every other one back-facing (edges swapped). */
        for (a = 0; a < 3; a++) {
            t.v0[a] = a < 2 ? (int32_t)(lcg(&x) >> 13) - 0x40000 - 6 * 65536
                            : (int32_t)(lcg(&x) >> 14) - 0x20000;
            t.e1[a] = (int32_t)(lcg(&x) >> 14) - 0x20000;
            t.e2[a] = (int32_t)(lcg(&x) >> 14) - 0x20000;
        }
        t.e1[0] += 2 * 65536 + (int32_t)(lcg(&x) >> 13) * 2;
        t.e2[1] += 2 * 65536 + (int32_t)(lcg(&x) >> 13) * 2;
        if (c & 1) {
            for (a = 0; a < 3; a++) {
                int32_t s = t.e1[a];
                t.e1[a] = t.e2[a];
                t.e2[a] = s;
            }
        }
        k = (lt_mask16_t)(lcg(&x) >> 16 | ((c & 2) ? 0xFFFFu : 0u));
        hits += lt__popcount32(lt_tri16_q16(&ray, k, &t, c, &hit));
    }
    return hits;
}

#if LT_CFG_FLOAT32
static lt_ray16_f32_t fray;

/* The same packets and triangles as lt_tri_loop, each s15.16 or s1.30 value converted to the
 * nearest float by integer operations (lt_f32_bits.h): no float helper runs outside the kernel. */
uint32_t lt_tri_loop_f32(int calls)
{
    uint32_t x = 777u, hits = 0;
    int i, c;
    for (c = 0; c < calls; c++) {
        lt_tri_f32_t t;
        lt_mask16_t k;
        int32_t v0[3], e1[3], e2[3];
        int a;
        if ((c & 3) == 0) {
            for (i = 0; i < LT_LANES; i++) {
                fray.ox.l[i] = lt_loop_f32_from_fx((int32_t)(lcg(&x) >> 13) - 0x40000, 16u);
                fray.oy.l[i] = lt_loop_f32_from_fx((int32_t)(lcg(&x) >> 13) - 0x40000, 16u);
                fray.oz.l[i] = lt_loop_f32_from_fx(-16 * 65536 + (int32_t)(lcg(&x) >> 14) - 0x20000,
                                                   16u);
                fray.dx.l[i] = lt_loop_f32_from_fx((int32_t)(lcg(&x) >> 3) - 0x10000000, 30u);
                fray.dy.l[i] = lt_loop_f32_from_fx((int32_t)(lcg(&x) >> 3) - 0x10000000, 30u);
                fray.dz.l[i] = lt_loop_f32_from_fx(0x39999999, 30u);
                fray.rx.l[i] = fray.ry.l[i] = fray.rz.l[i] = lt_loop_f32_from_fx(0, 16u);
                fray.tmin.l[i] = lt_loop_f32_from_fx(0, 16u);
                fray.tmax.l[i] = lt_loop_f32_from_fx(0x7FFFFFF, 16u);
                hit.id.l[i] = -1;
            }
        }
        for (a = 0; a < 3; a++) {
            v0[a] = a < 2 ? (int32_t)(lcg(&x) >> 13) - 0x40000 - 6 * 65536
                          : (int32_t)(lcg(&x) >> 14) - 0x20000;
            e1[a] = (int32_t)(lcg(&x) >> 14) - 0x20000;
            e2[a] = (int32_t)(lcg(&x) >> 14) - 0x20000;
        }
        e1[0] += 2 * 65536 + (int32_t)(lcg(&x) >> 13) * 2;
        e2[1] += 2 * 65536 + (int32_t)(lcg(&x) >> 13) * 2;
        for (a = 0; a < 3; a++) {
            t.v0[a] = lt_loop_f32_from_fx(v0[a], 16u);
            t.e1[a] = lt_loop_f32_from_fx((c & 1) ? e2[a] : e1[a], 16u);
            t.e2[a] = lt_loop_f32_from_fx((c & 1) ? e1[a] : e2[a], 16u);
        }
        k = (lt_mask16_t)(lcg(&x) >> 16 | ((c & 2) ? 0xFFFFu : 0u));
        hits += lt__popcount32(lt_tri16_f32(&fray, k, &t, c, &hit));
    }
    return hits;
}
#endif
