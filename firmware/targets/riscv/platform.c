/* platform.c - QEMU virt board support for rv32: NS16550 UART output, exit through the
 * sifive_test device, lt_fw_ticks from mcycle, and the trap reporter ("TRAP mcause=..", exit 3).
 * Builds: firmware, rv32 (machine mode, -bios none). CSR reads enable Zicsr locally with
 * .option arch, because -march=rv32imac_zicsr would select the wrong (rv64) multilib.
 */
#include <stdint.h>

#include "lt_fw.h"

#ifndef LT_FW_UART_BASE
#error "LT_FW_UART_BASE must be set by the target's CFLAGS (firmware/targets/targets.mk)"
#endif

/* NS16550: byte registers, QEMU's virt uses reg-shift 0. */
#define LT__UART_REG(off) (*(volatile uint8_t *)((uintptr_t)(LT_FW_UART_BASE) + (off)))
#define LT__UART_THR      LT__UART_REG(0u) /* transmit holding (write) */
#define LT__UART_FCR      LT__UART_REG(2u)
#define LT__UART_LCR      LT__UART_REG(3u)
#define LT__UART_LSR      LT__UART_REG(5u)
#define LT__LSR_THRE      0x20u            /* holding register empty: can take a byte */
#define LT__LSR_TEMT      0x40u            /* holding and shift register empty: all sent */

/* sifive_test: 0x5555 ends QEMU with status 0, (code << 16) | 0x3333 with status code. */
#define LT__TEST_REG      (*(volatile uint32_t *)(uintptr_t)0x00100000u)
#define LT__TEST_PASS     0x5555u
#define LT__TEST_FAIL     0x3333u

LT_NORETURN void lt__fw_trap_report(uint32_t mcause, uint32_t mepc, uint32_t mtval, uint32_t sp);

void lt__fw_uart_init(void)
{
    LT__UART_LCR = 0x03u; /* 8 data bits, no parity, 1 stop bit, DLAB = 0 */
    LT__UART_FCR = 0x01u; /* FIFOs on */
}

void lt_fw_putc(int c)
{
    while ((LT__UART_LSR & LT__LSR_THRE) == 0) {
    }
    LT__UART_THR = (uint8_t)c;
}

void lt__fw_uart_flush(void)
{
    while ((LT__UART_LSR & LT__LSR_TEMT) == 0) {
    }
}

LT_NORETURN void lt_fw_exit(int code)
{
    uint32_t c = (uint32_t)code & 0xFFu;

    lt__fw_report_ram();
    lt__fw_uart_flush();
    LT__TEST_REG = (c == 0) ? LT__TEST_PASS : ((c << 16) | LT__TEST_FAIL);
    for (;;) {
    }
}

static uint64_t ticks_base; /* mcycle at lt__fw_ticks_init */

static uint64_t read_mcycle(void)
{
    uint32_t hi, lo, hi2;

    /* RV32 reads the 64-bit counter in two halves; re-read the high half to catch a carry. */
    do {
        __asm__ __volatile__(".option push\n\t"
                             ".option arch, +zicsr\n\t"
                             "csrr %0, mcycleh\n\t"
                             "csrr %1, mcycle\n\t"
                             "csrr %2, mcycleh\n\t"
                             ".option pop"
                             : "=r"(hi), "=r"(lo), "=r"(hi2));
    } while (hi != hi2);
    return ((uint64_t)hi << 32) | lo;
}

void lt__fw_ticks_init(void)
{
    /* Under -icount QEMU's mcycle is the virtual clock, whose value at reset depends on how long
     * QEMU took to start (it differs run to run); deltas are exact. Counting from here makes
     * absolute values reproducible too. */
    ticks_base = read_mcycle();
}

uint64_t lt_fw_ticks(void)
{
    return read_mcycle() - ticks_base;
}

/* Called by lt__fw_trap_entry (start.S) on its own stack, for every trap: nothing is expected to
 * trap in this firmware, so each one is fatal. mcause 7 at an address in the guard page below
 * lt__fw_stack_limit is a stack overflow. */
LT_NORETURN void lt__fw_trap_report(uint32_t mcause, uint32_t mepc, uint32_t mtval, uint32_t sp)
{
    lt_fw_puts("\nTRAP mcause=");
    lt_fw_put_hex32(mcause);
    lt_fw_puts(" mepc=");
    lt_fw_put_hex32(mepc);
    lt_fw_puts(" mtval=");
    lt_fw_put_hex32(mtval);
    lt_fw_puts(" sp=");
    lt_fw_put_hex32(sp);
    lt_fw_puts("\n");
    lt_fw_exit(3);
}
