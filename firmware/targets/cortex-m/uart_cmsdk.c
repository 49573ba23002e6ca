/* uart_cmsdk.c - Arm CMSDK APB UART transmit, polled (mps2-an386 UART0 0x40004000, mps3-an547
 * UART0 0x49303000). The base address comes from -DLT_FW_UART_BASE (firmware/targets/targets.mk).
 * Registers: DATA +0x00, STATE +0x04 (bit 0 TX full), CTRL +0x08 (bit 0 TX enable), BAUDDIV +0x10.
 * Builds: firmware, cm4 and cm55.
 */
#include <stdint.h>

#include "lt_fw.h"

#ifndef LT_FW_UART_BASE
#error "LT_FW_UART_BASE must be set by the target's CFLAGS (firmware/targets/targets.mk)"
#endif

#define LT__UART_REG(off)  (*(volatile uint32_t *)((uintptr_t)(LT_FW_UART_BASE) + (off)))
#define LT__UART_DATA      LT__UART_REG(0x00u)
#define LT__UART_STATE     LT__UART_REG(0x04u)
#define LT__UART_CTRL      LT__UART_REG(0x08u)
#define LT__UART_BAUDDIV   LT__UART_REG(0x10u)
#define LT__UART_TX_FULL   0x1u
#define LT__UART_TX_EN     0x1u

/* QEMU keeps TX full forever once its stdout is gone (e.g. piped into `head`): after this many
 * polls the UART is taken as dead and bytes are dropped without waiting, so the program still
 * reaches its exit (and exit code) instead of hanging. */
#define LT__UART_MAX_POLLS (1u << 20)

static uint32_t tx_dead; /* 1 once a wait has timed out */

static void wait_tx_not_full(void)
{
    uint32_t n, max = tx_dead ? 1u : LT__UART_MAX_POLLS;

    for (n = 0; n < max; n++) {
        if ((LT__UART_STATE & LT__UART_TX_FULL) == 0) {
            tx_dead = 0;
            return;
        }
    }
    tx_dead = 1;
}

void lt__fw_uart_init(void)
{
    /* 16 is the smallest divider the CMSDK UART accepts; QEMU ignores the rate itself. */
    LT__UART_BAUDDIV = 16u;
    LT__UART_CTRL = LT__UART_TX_EN;
}

void lt_fw_putc(int c)
{
    wait_tx_not_full();
    LT__UART_DATA = (uint32_t)c & 0xFFu;
}

void lt__fw_uart_flush(void)
{
    /* The CMSDK UART has a one-byte buffer and no "shift register empty" flag: not-full is as
     * close to drained as it reports. */
    wait_tx_not_full();
}
