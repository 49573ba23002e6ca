/* lt_tri.c - the one 16-lane op of the s15.16 triangle test that is not a lane op of lt_v16w.h:
 * t = tnum / det on the candidate lanes, lt__tri_q16_tdiv1 (lt_tri.h) per lane. Used by the packet
 * kernel lt_tri16_q16 (lt_isect.c) and the frusta hit tests (lt_frusta.c). Builds: all.
 */
#include "lt_tri.h"

lt_vq16_t lt__tri_tdiv16_q16(lt_vq16_t src, lt_mask16_t k, lt_vql22_t tnum, lt_vql32_t det)
{
    int i;
    LT_COST(VDIV, 1);
    LT_UTIL(k);
    for (i = 0; i < LT_LANES; i++) {
        if (!LT__ON(k, i))
            continue;
        src.l[i] = lt__tri_q16_tdiv1(tnum.l[i], det.l[i]);
    }
    return src;
}
