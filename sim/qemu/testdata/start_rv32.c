/* start_rv32.c: RV32IMAC (QEMU virt, -bios none) startup for the lt_icount plugin test: _start,
 * NS16550 UART output and exit through the sifive_test device at 0x100000 (docs/firmware.md).
 * No .data or .bss initialisation: the test program has no initialised data.
 */
#include <stdint.h>

#define UART0_THR  (*(volatile uint8_t *)0x10000000u)
#define SIFIVE_TEST (*(volatile uint32_t *)0x00100000u)

int main(void);
void lt_test_putc(char c);
__attribute__((noreturn)) void lt_test_exit(int code);

/* .type/.size give _start a symbol size, which QEMU needs to name its instructions. */
__asm__(".section .text.start, \"ax\", @progbits\n"
        ".globl _start\n"
        ".type _start, @function\n"
        "_start:\n"
        "    la sp, __stack_top\n"
        "    call main\n"
        "    call lt_test_exit\n"
        ".size _start, . - _start\n");

void lt_test_putc(char c)
{
    UART0_THR = (uint8_t)c; /* QEMU's 16550 never reports the holding register full */
}

/* 0x5555 passes (exit 0); (code << 16) | 0x3333 fails with that code. Selected with a mask, not
 * a branch: test_plugin.sh needs count_me's loop to be the program's only conditional branch. */
void lt_test_exit(int code)
{
    uint32_t pass = 0u - (uint32_t)(code == 0); /* all ones when code is 0 */

    SIFIVE_TEST = (0x5555u & pass) | ((((uint32_t)code << 16) | 0x3333u) & ~pass);
    for (;;) {
    }
}
