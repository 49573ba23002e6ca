/* start_cm4.c: Cortex-M4 (QEMU mps2-an386) startup for the lt_icount plugin test: vector table,
 * reset, CMSDK UART0 output and exit through semihosting SYS_EXIT_EXTENDED (docs/firmware.md).
 * No .data or .bss initialisation: the test program has no initialised data. Also the Cortex-M55
 * (mps3-an547) startup, with -DLT_TEST_UART0=0x49303000u -DLT_TEST_MVE (MVE enabled at reset).
 */
#include <stdint.h>

#ifndef LT_TEST_UART0
#define LT_TEST_UART0 0x40004000u /* mps2-an386 */
#endif
#define UART0_DATA (*(volatile uint32_t *)LT_TEST_UART0)
#define UART0_CTRL (*(volatile uint32_t *)(LT_TEST_UART0 + 8u))
#define CPACR      (*(volatile uint32_t *)0xE000ED88u)

extern uint32_t __stack_top;     /* cm4.ld */
int main(void);
void lt_test_putc(char c);
void Reset_Handler(void);
void Fault_Handler(void);
__attribute__((noreturn)) void lt_test_exit(int code);

__attribute__((section(".vectors"), used)) static const void *const vectors[4] = {
    &__stack_top, (const void *)Reset_Handler, (const void *)Fault_Handler,
    (const void *)Fault_Handler
};

void Reset_Handler(void)
{
#ifdef LT_TEST_MVE
    CPACR |= 0xFu << 20; /* CP10, CP11 full access: FP and MVE */
    __asm__ volatile("dsb\n\tisb" ::: "memory");
#endif
    UART0_CTRL = 1u; /* TX enable */
    lt_test_exit(main());
}

void Fault_Handler(void)
{
    lt_test_exit(3);
}

void lt_test_putc(char c)
{
    UART0_DATA = (uint32_t)(unsigned char)c; /* QEMU's UART never reports TX full */
}

/* SYS_EXIT_EXTENDED (0x20): r1 -> {ADP_Stopped_ApplicationExit, code}. */
void lt_test_exit(int code)
{
    static volatile uint32_t block[2];
    register uint32_t r0 __asm__("r0") = 0x20u;
    register volatile uint32_t *r1 __asm__("r1") = block;

    block[0] = 0x20026u;
    block[1] = (uint32_t)code;
    __asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
    for (;;) {
    }
}
