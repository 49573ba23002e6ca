/* fw_slab.c - the slab-test loop of lt_slab_loop.c on a firmware target, for the instruction-count
 * check of the scalar MCU model (tests/bench/icount.sh). Freestanding.
 */
#include "lt_fw.h"
#include "lt_slab_loop.h"

#ifndef SLAB_CALLS
#define SLAB_CALLS 256
#endif

int main(void)
{
    uint32_t hits = lt_slab_loop(SLAB_CALLS);
    lt_fw_puts("slab calls ");
    lt_fw_put_u32(SLAB_CALLS);
    lt_fw_puts(" lane hits ");
    lt_fw_put_u32(hits);
    lt_fw_puts("\n");
    return 0;
}
