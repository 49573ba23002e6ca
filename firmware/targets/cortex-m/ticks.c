/* ticks.c - lt_fw_ticks for Cortex-M: SysTick on the processor clock, extended to 64 bits by
 * counting wraps in the SysTick exception, scaled to virtual nanoseconds (= instructions under
 * QEMU -icount shift=0). DWT CYCCNT is not used: QEMU does not implement it (reads 0).
 * Builds: firmware, cm4 and cm55; LT_FW_SYSTICK_HZ is the board clock QEMU feeds SysTick.
 */
#include <stdint.h>

#include "lt_fw.h"

#ifndef LT_FW_SYSTICK_HZ
#error "LT_FW_SYSTICK_HZ must be set by the target's CFLAGS (firmware/targets/targets.mk)"
#endif

#define LT__REG(addr)   (*(volatile uint32_t *)(addr))
#define LT__SYST_CSR    LT__REG(0xE000E010u)
#define LT__SYST_RVR    LT__REG(0xE000E014u)
#define LT__SYST_CVR    LT__REG(0xE000E018u)
#define LT__SCB_ICSR    LT__REG(0xE000ED04u)
#define LT__ICSR_PENDSTSET (1u << 26)
#define LT__SYST_ENABLE    0x1u
#define LT__SYST_TICKINT   0x2u
#define LT__SYST_CLKSOURCE 0x4u /* processor clock, not the 1 MHz reference */
#define LT__SYST_PERIOD    (1u << 24) /* reload 0xFFFFFF: period 2^24 clocks */

/* ns per clock is 1e9 / HZ: 40 at 25 MHz, 31.25 at 32 MHz. Scaling by 4/4 keeps both exact
 * in integers (160/4, 125/4); the assertion rejects a clock where it would not. */
#define LT__NS_PER_4CLK (4000000000ull / (uint64_t)(LT_FW_SYSTICK_HZ))
LT_STATIC_ASSERT((4000000000ull % (uint64_t)(LT_FW_SYSTICK_HZ)) == 0,
                 "1e9/LT_FW_SYSTICK_HZ must be a multiple of 1/4");

static volatile uint32_t wraps; /* SysTick periods completed (counter reached 0) */

void lt__fw_ticks_init(void)
{
    LT__SYST_CSR = 0;
    LT__SYST_RVR = LT__SYST_PERIOD - 1u;
    LT__SYST_CVR = 0; /* any write clears the counter; it reloads on the next clock */
    wraps = 0;
    LT__SYST_CSR = LT__SYST_ENABLE | LT__SYST_TICKINT | LT__SYST_CLKSOURCE;
}

void lt__fw_systick_isr(void)
{
    wraps = wraps + 1u;
}

uint64_t lt_fw_ticks(void)
{
    uint32_t hi, cur, pend0, pend1;
    uint64_t clocks;

    /* A consistent (wraps, counter) pair: retry if the ISR ran or the SysTick became pending
     * during the read. If it is pending but has not run (interrupts masked, or not yet taken),
     * the counter already belongs to the next period, so one more wrap is added. */
    do {
        hi = wraps;
        pend0 = LT__SCB_ICSR & LT__ICSR_PENDSTSET;
        cur = LT__SYST_CVR;
        pend1 = LT__SCB_ICSR & LT__ICSR_PENDSTSET;
    } while (hi != wraps || pend0 != pend1);
    if (pend0 != 0)
        hi += 1u;

    /* The counter runs PERIOD-1 .. 1, 0; the wrap is counted when it reaches 0, so the clocks
     * into the current period are (PERIOD - cur) mod PERIOD. */
    clocks = ((uint64_t)hi << 24) + ((LT__SYST_PERIOD - cur) & (LT__SYST_PERIOD - 1u));
    return (clocks * LT__NS_PER_4CLK) >> 2;
}
