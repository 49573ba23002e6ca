/* lt_tri_loop.c - see lt_tri_loop.h. Freestanding. */
#include "lt_tri_loop.h"
#include "lt/lt.h"

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
