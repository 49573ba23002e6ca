/* icount_test.c: guest program for sim/qemu/test_plugin.sh (lt_icount plugin test).
 * count_me runs a loop whose instruction count test_plugin.sh derives from the disassembly;
 * main is straight-line (calls only) so its count is its instruction count. lt_fw_stage marks
 * stages as the firmware's does (firmware/targets/common/lt_rt.c): stage 1 is count_me's call.
 * With -DLT_TEST_MVE (Cortex-M55), mve_me runs a low-overhead loop of Helium instructions whose
 * classes test_plugin.sh knows. Built for Cortex-M4 and Cortex-M55 (start_cm4.c) and RV32IMAC
 * (start_rv32.c); -O2, freestanding, no libc.
 */
#include <stdint.h>

#ifndef COUNT_ME_N
#define COUNT_ME_N 1000u /* loop trips; test_plugin.sh passes the same value with -D */
#endif

void lt_test_putc(char c);       /* one MMIO store, no polling: start_<target>.c */
int main(void);
uint32_t count_me(uint32_t n);

volatile uint32_t lt_test_sink;  /* keeps the loop result live */

/* Stage marks for the plugin's stage=ADDR (the address of lt_fw_stage_slots): the same name and
 * the same single store as the firmware's. */
volatile uint32_t lt_fw_stage_slots[16];
void lt_fw_stage(uint32_t k);

__attribute__((noipa)) void lt_fw_stage(uint32_t k)
{
    lt_fw_stage_slots[k & 15u] = k;
}

/* noipa: no inlining, cloning or constant propagation, so the symbol stays "count_me" and the
 * loop bound stays a runtime value. do-while with n >= 1: no zero-trip test, so the code is
 * prologue, one bottom-tested loop, epilogue. acc * 3 + i has no closed form for GCC to fold. */
__attribute__((noipa)) uint32_t count_me(uint32_t n)
{
    uint32_t acc = 0;
    uint32_t i = 0;

    do {
        acc = (acc * 3u) + i;
        i++;
    } while (i != n);
    return acc;
}

#ifdef LT_TEST_MVE
#define MVE_ME_N 10u /* loop trips; test_plugin.sh expects the same */
void mve_me(int32_t *a, uint32_t n);
static int32_t mve_buf[4u * MVE_ME_N];

/* DLS, then per trip: VLDRW (mve_load), VADD, VCMP, VADDT, VPSEL (mve_alu), VMULH (mve_mul),
 * VPST (mve_ctl), VSTRW (mve_store), LE (lob). */
__attribute__((noipa)) void mve_me(int32_t *a, uint32_t n)
{
    __asm__ volatile("dls lr, %[n]\n"
                     "1:\n\t"
                     "vldrw.u32 q0, [%[a]]\n\t"
                     "vadd.i32 q1, q0, q0\n\t"
                     "vmulh.s32 q2, q0, q1\n\t"
                     "vcmp.s32 gt, q0, q1\n\t"
                     "vpst\n\t"
                     "vaddt.i32 q0, q0, q1\n\t"
                     "vpsel q1, q0, q2\n\t"
                     "vstrw.32 q1, [%[a]], #16\n\t"
                     "le lr, 1b\n"
                     : [a] "+r"(a)
                     : [n] "r"(n)
                     : "lr", "d0", "d1", "d2", "d3", "d4", "d5", "memory");
}
#endif

int main(void)
{
    /* UART stores mid-block exercise QEMU's -icount I/O restart path. */
    lt_test_putc('o');
    lt_test_putc('k');
    lt_test_putc('\n');
#ifdef LT_TEST_MVE
    mve_me(mve_buf, MVE_ME_N);
#endif
    lt_fw_stage(1u);
    lt_test_sink = count_me(COUNT_ME_N);
    lt_fw_stage(2u);
    return 0;
}
