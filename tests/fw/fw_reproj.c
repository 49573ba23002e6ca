/* fw_reproj.c - the shared 64 x 64 reprojection workload (tests/vectors/lt_reproj_tile.h) on a
 * firmware target: prints "reproj fw tile hash: 0x........ setup exact|differs", which
 * tests/run.d/reproject.sh compares with the host unit test's line (bit-exact across host, sim,
 * asan, cm4, cm55, rv32). "setup" says whether lt_reproj_setup (double, soft-double on the MCUs)
 * reproduced the stored s1.30 mapping bit for bit. Exit 0, or 1 if a step failed. Freestanding.
 */
#include "lt_fw.h"
#include "lt_reproj_tile.h"

int main(void)
{
    uint32_t h = ltrt_hash((uint32_t *)0);
    lt_fw_puts("reproj fw tile hash: ");
    lt_fw_put_hex32(h);
#if LT_CFG_FLOAT32
    lt_fw_puts(ltrt_setup_matches() ? " setup exact\n" : " setup differs\n");
#else
    lt_fw_puts("\n");
#endif
    return h != 0 ? 0 : 1;
}
