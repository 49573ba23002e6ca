/* fw_stream.c - the streaming device (stream_dev.c) as a firmware image: frames go out binary on
 * the board UART (QEMU -serial: stdout, a file, a pipe or a TCP socket). The device clock is
 * lt_fw_ticks, QEMU's virtual nanoseconds, which under -icount shift=0 count instructions: the
 * assumed core is LT_SDEV_CPU_HZ = 1 GHz at one instruction per cycle (QEMU's own virtual clock;
 * -DLT_SDEV_CPU_HZ=168000000 models a 168 MHz Cortex-M4 part instead), so the 64,000 B/s link
 * gives one report slot per 1,000,000 instructions and drops are deterministic. stream.elf's core
 * has no cost counting (LT_COST_OFF): it reports rays, hits, hashes and ticks. stream-count.elf is
 * the same program over a core built with LT_COST_HANDLER (lt_fw_count.h): its reports also carry
 * the modelled cycles of the target's machine model and the box and triangle tests, counted on
 * the target.
 * Exit status: lt_sdev_run's (0 ok). Builds: firmware (cm4, cm55, rv32).
 */
#include "lt/lt_cost.h"
#include "lt_fw.h"
#include "lt_uart_tx.h"
#include "stream_dev.h"
#if LT_COST_MODE == LT_COST_HANDLER
#include "lt_fw_count.h"

static void fw_counters(void *ctx, lt_sdev_ctr_t *c)
{
    (void)ctx;
    c->cycles = lt_fwc.cycles;
    c->aabb = lt_fwc.aabb;
    c->aabb_rays = lt_fwc.aabb_rays;
    c->tris = lt_fwc.tris;
    c->tri_rays = lt_fwc.tri_rays;
}
#endif

#ifndef LT_SDEV_CPU_HZ
#define LT_SDEV_CPU_HZ 1000000000u
#endif

static uint64_t fw_ticks(void *ctx)
{
    (void)ctx;
    return lt_fw_ticks();
}

static void fw_idle_until(void *ctx, uint64_t t)
{
    (void)ctx;
    while (lt_fw_ticks() < t) {
    }
}

int main(void)
{
    static lt_sdev_result_t res;
    lt_sdev_cfg_t cfg;
    lt_sdev_port_t port;
    lt_fw_ram_report(0); /* the UART carries frames only */
    lt_sdev_cfg_default(&cfg);
    port.ticks = fw_ticks;
    port.idle_until = fw_idle_until;
#if LT_COST_MODE == LT_COST_HANDLER
    port.counters = fw_counters;
#else
    port.counters = 0;
#endif
    port.region = 0;
    port.sink = lt_uart_tx_sink;
    port.ctx = 0;
    port.tick_hz = LT_SDEV_CPU_HZ;
#if LT_COST_MODE == LT_COST_HANDLER
    port.valid = LT_STREAM_F_TICKS | LT_STREAM_F_CYCLES | LT_STREAM_F_AABB | LT_STREAM_F_TRIS;
#else
    port.valid = LT_STREAM_F_TICKS;
#endif
    port.source = LT_STREAM_SRC_FIRMWARE;
    port.name = LT_FW_TARGET_NAME;
    return lt_sdev_run(&port, &cfg, &res);
}
