/* fw_slab_f32.c - the float32 twin of fw_slab.c: lt_slab_loop_f32 on a firmware target, for the
 * instruction-count check of the soft-float kernel on rv32 (tests/bench/opcal.sh rv32).
 * Freestanding.
 */
#include "lt_fw.h"
#include "lt_slab_loop.h"

#ifndef SLAB_CALLS
#define SLAB_CALLS 256
#endif

int main(void)
{
    uint32_t hits = lt_slab_loop_f32(SLAB_CALLS);
    lt_fw_puts("slab f32 calls ");
    lt_fw_put_u32(SLAB_CALLS);
    lt_fw_puts(" lane hits ");
    lt_fw_put_u32(hits);
    lt_fw_puts("\n");
    return 0;
}
