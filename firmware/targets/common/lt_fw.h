/* lt_fw.h - the board API every lanetrace firmware program uses: UART output, exit, tick counter.
 * Implemented per target under firmware/targets/{cortex-m,riscv}/; the target-independent output
 * helpers live in common/lt_rt.c. Targets: cm4 (mps2-an386), cm55 (mps3-an547), rv32 (virt).
 * Builds: freestanding firmware only (-ffreestanding -nostdlib, QEMU); see docs/firmware.md.
 */
#ifndef LT_FW_H
#define LT_FW_H

#include <stdint.h>
#include "lt/lt_port.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Target name string ("cm4", "cm55", "rv32"), set by firmware/targets/targets.mk. */
#ifndef LT_FW_TARGET_NAME
#define LT_FW_TARGET_NAME "unknown"
#endif

/* Write one byte to the board UART (QEMU -serial stdio), waiting while the TX FIFO is full.
 * No newline translation: "\n" goes out as a single LF. */
void lt_fw_putc(int c);

/* Write a NUL-terminated string; no newline is added. */
void lt_fw_puts(const char *s);

/* Write v in decimal, no padding, no sign ("0" .. "4294967295"). */
void lt_fw_put_u32(uint32_t v);

/* Write v as "0x" followed by exactly 8 lowercase hex digits (printf "0x%08x"). */
void lt_fw_put_hex32(uint32_t v);

/* Flush the UART and end the QEMU run with exit status code & 0xFF (0..255 pass through; the host
 * sees only 8 bits anyway). Arm: semihosting SYS_EXIT_EXTENDED (0x20) with {0x20026, code}, which
 * needs -semihosting-config enable=on. RISC-V: the sifive_test device at 0x100000.
 * Never returns. */
LT_NORETURN void lt_fw_exit(int code);

/* Monotonic 64-bit tick count since reset, in virtual nanoseconds of QEMU's icount clock. Under
 * `-icount shift=0` one guest instruction is exactly 1 ns, so this counts retired instructions and
 * is identical from run to run; without -icount it follows wall time and is not reproducible.
 *   rv32:  mcycle/mcycleh (QEMU derives it from icount), resolution 1 instruction.
 *   Arm:   SysTick on the processor clock (CLKSOURCE = 1, 24-bit, reload 0xFFFFFF) scaled by
 *          1e9 / LT_FW_SYSTICK_HZ; resolution 40 instructions on cm4 (25 MHz), 31.25 on cm55
 *          (32 MHz). Wraps (every 2^24 clocks, ~0.5-0.7 s virtual) are counted by the SysTick
 *          exception, so interrupts must stay enabled (PRIMASK = 0); with interrupts masked for
 *          more than one wrap period, wraps are lost.
 * Cost: a few tens of instructions (Arm: includes a 64-bit multiply). */
uint64_t lt_fw_ticks(void);

/* Mark the start of stage k (0..15) of a program for the lt_icount QEMU plugin's cycle model
 * (docs/qemu-plugin.md, "Stages"): one store of k to lt_fw_stage_slots[k]. Run with the plugin's
 * stage=ADDR (the address of lt_fw_stage_slots, from nm), it credits every instruction from this
 * call to the next mark to stage k; without the plugin it is a store and nothing else. Stage 0 is
 * "untimed" and is where every program starts. Cost: a call and a store. */
void lt_fw_stage(uint32_t k);
extern volatile uint32_t lt_fw_stage_slots[16];

/* Bytes of the main stack used so far (its high-water mark) and its size. The start-up code
 * paints the stack below its own frame with a pattern before main; the high-water mark is the
 * distance from the stack's top to the lowest word no longer holding it. lt_fw_exit prints
 * "ram: stack USED of SIZE bytes, static N bytes (.data + .bss)" before it ends the run, so every
 * firmware program reports the RAM it needed (tests/run.d/fwram.sh checks it against budgets).
 * Cost: a scan of the stack (lt_fw_stack_used). */
uint32_t lt_fw_stack_used(void);
uint32_t lt_fw_stack_size(void);

/* Turn the "ram:" line at exit off (on = 0) or on: a program whose UART carries a binary stream
 * (firmware/apps/stream_fw.c) keeps it clean. */
void lt_fw_ram_report(int on);

/* ---- target-internal (lt__fw_*): shared between the files of one target, not for programs ---- */

/* Paint the stack from its limit up to 256 bytes below the caller's frame (start-up, before
 * main), and print the "ram:" line (lt_fw_exit). */
void lt__fw_stack_paint(void);
void lt__fw_report_ram(void);

/* Called by the start-up code before main: UART set-up and tick counter start. */
void lt__fw_uart_init(void);
void lt__fw_ticks_init(void);

/* Wait until the UART has sent everything (called by lt_fw_exit). */
void lt__fw_uart_flush(void);

/* Arm only: the SysTick exception handler that extends the counter (cortex-m/ticks.c). */
void lt__fw_systick_isr(void);

/* The program entry the start-up code calls. */
int main(void);

#ifdef __cplusplus
}
#endif
#endif /* LT_FW_H */
