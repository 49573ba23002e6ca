/* fw_tri_f32.c - the float32 twin of fw_tri.c: lt_tri_loop_f32 on a firmware target, for the
 * instruction-count check of the soft-float kernel on rv32 (tests/bench/opcal.sh rv32).
 * Freestanding.
 */
#include "lt_fw.h"
#include "lt_tri_loop.h"

#ifndef TRI_CALLS
#define TRI_CALLS 256
#endif

int main(void)
{
    uint32_t hits = lt_tri_loop_f32(TRI_CALLS);
    lt_fw_puts("tri f32 calls ");
    lt_fw_put_u32(TRI_CALLS);
    lt_fw_puts(" lane hits ");
    lt_fw_put_u32(hits);
    lt_fw_puts("\n");
    return 0;
}
