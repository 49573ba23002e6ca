/* fw_stream.c - the streaming device (stream_dev.c) as a firmware image: frames go out binary on
 * the board UART (QEMU -serial: stdout, a file, a pipe or a TCP socket). The device clock is
 * lt_fw_ticks, QEMU's virtual nanoseconds, which under -icount shift=0 count instructions: the
 * assumed core is LT_SDEV_CPU_HZ = 1 GHz at one instruction per cycle (QEMU's own virtual clock;
 * -DLT_SDEV_CPU_HZ=168000000 models a 168 MHz Cortex-M4 part instead), so the 64,000 B/s link
 * gives one report slot per 1,000,000 instructions and drops are deterministic. The firmware core
 * has no cost counting (LT_COST_OFF): it reports rays, hits, hashes and ticks.
 * Exit status: lt_sdev_run's (0 ok). Builds: firmware (cm4, cm55, rv32).
 */
#include "lt_fw.h"
#include "lt_uart_tx.h"
#include "stream_dev.h"

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
    port.counters = 0;
    port.region = 0;
    port.sink = lt_uart_tx_sink;
    port.ctx = 0;
    port.tick_hz = LT_SDEV_CPU_HZ;
    port.valid = LT_STREAM_F_TICKS;
    port.source = LT_STREAM_SRC_FIRMWARE;
    port.name = LT_FW_TARGET_NAME;
    return lt_sdev_run(&port, &cfg, &res);
}
