/* fw_tri.c - the ray-triangle loop of lt_tri_loop.c on a firmware target, for the instruction-count
 * check of the scalar MCU model (tests/bench/opcal.sh). Freestanding.
 */
#include "lt_fw.h"
#include "lt_tri_loop.h"

#ifndef TRI_CALLS
#define TRI_CALLS 256
#endif

int main(void)
{
    uint32_t hits = lt_tri_loop(TRI_CALLS);
    lt_fw_puts("tri calls ");
    lt_fw_put_u32(TRI_CALLS);
    lt_fw_puts(" lane hits ");
    lt_fw_put_u32(hits);
    lt_fw_puts("\n");
    return 0;
}
