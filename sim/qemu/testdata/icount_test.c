/* icount_test.c: guest program for sim/qemu/test_plugin.sh (lt_icount plugin test).
 * count_me runs a loop whose instruction count test_plugin.sh derives from the disassembly;
 * main is straight-line (calls only) so its count is its instruction count. Built for
 * Cortex-M4 (start_cm4.c) and RV32IMAC (start_rv32.c); -O2, freestanding, no libc.
 */
#include <stdint.h>

#ifndef COUNT_ME_N
#define COUNT_ME_N 1000u /* loop trips; test_plugin.sh passes the same value with -D */
#endif

void lt_test_putc(char c);       /* one MMIO store, no polling: start_<target>.c */
int main(void);
uint32_t count_me(uint32_t n);

volatile uint32_t lt_test_sink;  /* keeps the loop result live */

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

int main(void)
{
    /* UART stores mid-block exercise QEMU's -icount I/O restart path. */
    lt_test_putc('o');
    lt_test_putc('k');
    lt_test_putc('\n');
    lt_test_sink = count_me(COUNT_ME_N);
    return 0;
}
