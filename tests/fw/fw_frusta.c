/* fw_frusta.c - the shared multi-frusta workload (tests/vectors/lt_frusta_tile.h) on a firmware
 * target: prints "frusta fw tile hash: q16 0x........ f32 0x........", which tests/run.d/frusta.sh
 * compares with the host unit test's line (bit-exact across host, sim, asan, cm4, cm55, rv32).
 * Exit 0, or 1 if a setup step failed. Freestanding.
 */
#include "lt_fw.h"
#include "lt_frusta_tile.h"

int main(void)
{
    uint32_t hq = ltft_hash_q16();
    lt_fw_puts("frusta fw tile hash: q16 ");
    lt_fw_put_hex32(hq);
#if LT_CFG_FLOAT32
    {
        uint32_t hf = ltft_hash_f32();
        lt_fw_puts(" f32 ");
        lt_fw_put_hex32(hf);
        lt_fw_puts("\n");
        return hq != 0 && hf != 0 ? 0 : 1;
    }
#else
    lt_fw_puts("\n");
    return hq != 0 ? 0 : 1;
#endif
}
