/* semihost.c - Cortex-M program exit through Arm semihosting (QEMU -semihosting-config enable=on).
 * SYS_EXIT_EXTENDED (0x20) with the block {ADP_Stopped_ApplicationExit = 0x20026, code} passes any
 * exit code; plain SYS_EXIT (0x18) on AArch32 can only say success or failure.
 * Builds: firmware, cm4 and cm55.
 */
#include <stdint.h>

#include "lt_fw.h"

#define LT__SH_SYS_EXIT_EXTENDED 0x20u
#define LT__SH_ADP_APP_EXIT      0x20026u

LT_NORETURN void lt_fw_exit(int code)
{
    volatile uint32_t block[2];

    block[0] = LT__SH_ADP_APP_EXIT;
    block[1] = (uint32_t)code & 0xFFu;
    lt__fw_report_ram();
    lt__fw_uart_flush();
    /* r0 = operation, r1 = parameter block; "bkpt 0xAB" is the M-profile semihosting trap.
     * Registers named in the clobber list are never given to the input operands. */
    __asm__ __volatile__("mov r0, %0\n\t"
                         "mov r1, %1\n\t"
                         "bkpt 0xAB"
                         :
                         : "r"(LT__SH_SYS_EXIT_EXTENDED), "r"(block)
                         : "r0", "r1", "memory");
    /* Reached only if the debugger ignores the request. */
    for (;;) {
    }
}
