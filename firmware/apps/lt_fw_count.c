/* lt_fw_count.c - see lt_fw_count.h. Builds: firmware (the counting stream image). */
#include "lt_fw_count.h"
#include "lt/lt_cost.h"

lt_fwc_t lt_fwc;

void lt_fwc_cost(int op, uint64_t n)
{
    if (op >= 0 && op < (int)LT_OP__COUNT)
        lt_fwc.cycles += n * lt_fwc_issue[op];
}

void lt_fwc_event(int ev, uint64_t n)
{
    if (ev == (int)LT_EV_AABB)
        lt_fwc.aabb += n;
    else if (ev == (int)LT_EV_AABB_RAYS)
        lt_fwc.aabb_rays += n;
    else if (ev == (int)LT_EV_TRIS)
        lt_fwc.tris += n;
    else if (ev == (int)LT_EV_TRI_RAYS)
        lt_fwc.tri_rays += n;
}

int lt_fwc_phase(int ph)
{
    (void)ph;
    return (int)LT_PH_OTHER;
}
