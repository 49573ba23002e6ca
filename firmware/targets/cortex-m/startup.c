/* startup.c - Cortex-M start-up for cm4 (mps2-an386) and cm55 (mps3-an547): vector table,
 * reset handler (FPU/MVE enable, .data copy, .bss zero, UART and SysTick start, main, exit) and
 * one fault handler for every unexpected exception: it prints "FAULT ..." and exits with code 3.
 * Builds: firmware, Armv7-M and Armv8.1-M Mainline (arm-none-eabi-gcc, -mthumb).
 */
#include <stddef.h>
#include <stdint.h>

#include "lt_fw.h"

#define LT__REG(addr) (*(volatile uint32_t *)(addr))
#define LT__SCB_VTOR  LT__REG(0xE000ED08u)
#define LT__SCB_CFSR  LT__REG(0xE000ED28u)
#define LT__SCB_HFSR  LT__REG(0xE000ED2Cu)
#define LT__SCB_MMFAR LT__REG(0xE000ED34u)
#define LT__SCB_BFAR  LT__REG(0xE000ED38u)
#define LT__SCB_CPACR LT__REG(0xE000ED88u)
#define LT__MPU_CTRL  LT__REG(0xE000ED94u)
#define LT__MPU_RBAR  LT__REG(0xE000ED9Cu)
#define LT__MPU_RASR  LT__REG(0xE000EDA0u)

/* 16 system exceptions plus the first 32 external interrupts; none of the IRQs is enabled, so
 * the table only needs to be long enough that a stray one lands in the fault handler. */
#define LT__NUM_VECTORS (16 + 32)

/* Symbols from mps2_an386.ld / mps3_an547.ld. */
extern uint32_t lt__fw_stack_guard[], lt__fw_stack_limit[], lt__fw_stack_top[];
extern uint32_t lt__fw_data_load[], lt__fw_data_start[], lt__fw_data_end[];
extern uint32_t lt__fw_bss_start[], lt__fw_bss_end[];
extern uint32_t lt__fw_ram_start[], lt__fw_ram_end[];

void lt__fw_reset(void);
void lt__fw_fault_entry(void);
LT_NORETURN void lt__fw_fault_report(uint32_t sp, uint32_t exc_return);

/* Entry 0 is the initial stack pointer, the others are handlers: a union avoids converting an
 * object pointer to a function pointer, which ISO C does not allow. */
typedef union {
    void (*fn)(void);
    void *sp;
} lt__fw_vec_t;

static const lt__fw_vec_t lt__fw_vectors[LT__NUM_VECTORS]
    __attribute__((section(".vectors"), used, aligned(256))) = {
        { .sp = lt__fw_stack_top },     /* 0  initial MSP */
        { .fn = lt__fw_reset },         /* 1  Reset */
        { .fn = lt__fw_fault_entry },   /* 2  NMI */
        { .fn = lt__fw_fault_entry },   /* 3  HardFault */
        { .fn = lt__fw_fault_entry },   /* 4  MemManage */
        { .fn = lt__fw_fault_entry },   /* 5  BusFault */
        { .fn = lt__fw_fault_entry },   /* 6  UsageFault */
        { .fn = lt__fw_fault_entry },   /* 7  SecureFault (v8-M) */
        { .fn = lt__fw_fault_entry },   /* 8  reserved */
        { .fn = lt__fw_fault_entry },   /* 9  reserved */
        { .fn = lt__fw_fault_entry },   /* 10 reserved */
        { .fn = lt__fw_fault_entry },   /* 11 SVCall */
        { .fn = lt__fw_fault_entry },   /* 12 DebugMonitor */
        { .fn = lt__fw_fault_entry },   /* 13 reserved */
        { .fn = lt__fw_fault_entry },   /* 14 PendSV */
        { .fn = lt__fw_systick_isr },   /* 15 SysTick: counts wraps for lt_fw_ticks */
        /* IRQ 0..31 */
        { .fn = lt__fw_fault_entry }, { .fn = lt__fw_fault_entry },
        { .fn = lt__fw_fault_entry }, { .fn = lt__fw_fault_entry },
        { .fn = lt__fw_fault_entry }, { .fn = lt__fw_fault_entry },
        { .fn = lt__fw_fault_entry }, { .fn = lt__fw_fault_entry },
        { .fn = lt__fw_fault_entry }, { .fn = lt__fw_fault_entry },
        { .fn = lt__fw_fault_entry }, { .fn = lt__fw_fault_entry },
        { .fn = lt__fw_fault_entry }, { .fn = lt__fw_fault_entry },
        { .fn = lt__fw_fault_entry }, { .fn = lt__fw_fault_entry },
        { .fn = lt__fw_fault_entry }, { .fn = lt__fw_fault_entry },
        { .fn = lt__fw_fault_entry }, { .fn = lt__fw_fault_entry },
        { .fn = lt__fw_fault_entry }, { .fn = lt__fw_fault_entry },
        { .fn = lt__fw_fault_entry }, { .fn = lt__fw_fault_entry },
        { .fn = lt__fw_fault_entry }, { .fn = lt__fw_fault_entry },
        { .fn = lt__fw_fault_entry }, { .fn = lt__fw_fault_entry },
        { .fn = lt__fw_fault_entry }, { .fn = lt__fw_fault_entry },
        { .fn = lt__fw_fault_entry }, { .fn = lt__fw_fault_entry },
};

void lt__fw_reset(void)
{
#if defined(__ARM_FP) || defined(__ARM_FEATURE_MVE)
    /* CP10 and CP11 full access: the FPU and (Armv8.1-M) MVE share this enable. It must come
     * first, since GCC may use FP or MVE registers even in the copy loops below. */
    LT__SCB_CPACR |= 0xFu << 20;
    __asm__ __volatile__("dsb\n\tisb" ::: "memory");
#endif
#if defined(__ARM_ARCH) && (__ARM_ARCH >= 8)
    /* Armv8-M stack limit: an overflow raises a UsageFault (STKOF) instead of corrupting .data. */
    __asm__ __volatile__("msr msplim, %0" : : "r"(lt__fw_stack_limit) : "memory");
#else
    /* Armv7-M has no stack limit register, and on mps2-an386 the space below RAM reads as zero
     * and ignores writes, so an overflow would run on silently. A no-access PMSAv7 MPU region
     * over the 4 KiB guard below the stack (the linker script puts it at the bottom of RAM)
     * makes it fault. PRIVDEFENA keeps the default map everywhere else; HFNMIENA = 0 turns the
     * MPU off inside HardFault, so the fault reporter can run. */
    LT__MPU_RBAR = (uint32_t)(uintptr_t)lt__fw_stack_guard | 0x10u; /* VALID, region 0 */
    LT__MPU_RASR = (1u << 28)    /* XN */
                 | (0u << 24)    /* AP = no access */
                 | (11u << 1)    /* SIZE: 2^(11+1) = 4 KiB */
                 | 1u;           /* ENABLE */
    LT__MPU_CTRL = 0x5u;         /* ENABLE | PRIVDEFENA */
    __asm__ __volatile__("dsb\n\tisb" ::: "memory");
#endif
    LT__SCB_VTOR = (uint32_t)(uintptr_t)lt__fw_vectors;

    /* lt__memcpy/lt__memset touch no .data or .bss themselves, so they are safe to call here. */
    lt__memcpy(lt__fw_data_start, lt__fw_data_load,
               (size_t)((uintptr_t)lt__fw_data_end - (uintptr_t)lt__fw_data_start));
    lt__memset(lt__fw_bss_start, 0,
               (size_t)((uintptr_t)lt__fw_bss_end - (uintptr_t)lt__fw_bss_start));
    __asm__ __volatile__("dsb\n\tisb" ::: "memory");
    lt__fw_stack_paint();

    lt__fw_uart_init();
    lt__fw_ticks_init();
    lt_fw_exit(main());
}

/* Every fault and unexpected exception. The stack may be what faulted (overflow), so this runs
 * without touching it: it picks the stacked frame (MSP or PSP, EXC_RETURN bit 2), then moves MSP
 * to the separate 1 KiB fault stack above the main stack (so the stacked frame is not
 * overwritten) and jumps to the C reporter, which never returns. */
__attribute__((naked)) void lt__fw_fault_entry(void)
{
    __asm__ __volatile__(
        "tst   lr, #4\n\t"
        "ite   eq\n\t"
        "mrseq r0, msp\n\t"
        "mrsne r0, psp\n\t"
        "mov   r1, lr\n\t"
        "movw  r2, #:lower16:lt__fw_fault_stack_top\n\t"
        "movt  r2, #:upper16:lt__fw_fault_stack_top\n\t"
        "mov   sp, r2\n\t"
        "b     lt__fw_fault_report\n\t");
}

/* Prints "FAULT exc=<n> cfsr=.. hfsr=.. mmfar=.. bfar=.. [pc=.. lr=..] sp=.." then exits 3.
 * pc/lr come from the stacked frame, read only if the frame lies inside RAM. */
LT_NORETURN void lt__fw_fault_report(uint32_t sp, uint32_t exc_return)
{
    uint32_t ipsr;

    __asm__ __volatile__("mrs %0, ipsr" : "=r"(ipsr));
    lt_fw_puts("\nFAULT exc=");
    lt_fw_put_u32(ipsr & 0x1FFu);
    lt_fw_puts(" cfsr=");
    lt_fw_put_hex32(LT__SCB_CFSR);
    lt_fw_puts(" hfsr=");
    lt_fw_put_hex32(LT__SCB_HFSR);
    lt_fw_puts(" mmfar=");
    lt_fw_put_hex32(LT__SCB_MMFAR);
    lt_fw_puts(" bfar=");
    lt_fw_put_hex32(LT__SCB_BFAR);
    if (sp >= (uint32_t)(uintptr_t)lt__fw_ram_start &&
        sp + 32u <= (uint32_t)(uintptr_t)lt__fw_ram_end && (sp & 3u) == 0) {
        const volatile uint32_t *frame = (const volatile uint32_t *)(uintptr_t)sp;
        lt_fw_puts(" pc=");
        lt_fw_put_hex32(frame[6]);
        lt_fw_puts(" lr=");
        lt_fw_put_hex32(frame[5]);
    }
    lt_fw_puts(" sp=");
    lt_fw_put_hex32(sp);
    lt_fw_puts(" exc_return=");
    lt_fw_put_hex32(exc_return);
    lt_fw_puts("\n");
    lt_fw_exit(3);
}
