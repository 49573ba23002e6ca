/* reproj_fw.c - the reprojection app (reproj_app.h) as a firmware image,
 * build/fw/<T>/reproj-bb.elf: the blob that `lanetrace fwblob` made from the Beachball EXR
 * (firmware.mk, FW_BLOB_reproj-bb) is linked as read-only data (lt_fw_blob.S); the quadtree arena
 * and the packet are one static buffer (counted in the "ram:" line's .bss); the lines go to the
 * UART; the instruction clock is lt_fw_ticks. Exit status: lt_rpapp_run's (0 ok, LT_RPAPP_E_*
 * otherwise). Builds: firmware (cm4, cm55, rv32).
 */
#include "lt_fw.h"
#include "lt_fw_blob.h"
#include "reproj_app.h"

/* The memory the app is given: the 2-layer 128 x 128 n64 quadtree of firmware.mk's blob,
 * 2 x 21,845 nodes x 8 bytes = 349,520, plus 1,024 for a packet and its results. A blob that needs
 * more is refused with LT_RPAPP_E_MEMORY, which prints the size it needs. */
#ifndef LT_RPFW_MEM_BYTES
#define LT_RPFW_MEM_BYTES 350544u
#endif

/* The walk: one ray at a time (lt_qt_trace1_q30) by default; -DLT_RPFW_SINGLE=0 traces packets
 * of 16 through the lane model (lt_qt_trace16_q30). Same hashes either way; docs/firmware.md has
 * the instructions per ray of both on every target. */
#ifndef LT_RPFW_SINGLE
#define LT_RPFW_SINGLE 1
#endif

static uint64_t rp_mem[LT_RPFW_MEM_BYTES / 8u] LT_ALIGN(64);

static void fw_puts(void *ctx, const char *s)
{
    (void)ctx;
    lt_fw_puts(s);
}

/* Marks the stage for the QEMU plugin's cycle model (lt_fw_stage), then reads the clock. */
static uint64_t fw_ticks(void *ctx, uint32_t stage)
{
    (void)ctx;
    lt_fw_stage(stage);
    return lt_fw_ticks();
}

int main(void)
{
    lt_rpapp_port_t port;
    port.puts = fw_puts;
    port.ticks = fw_ticks;
    port.ctx = 0;
    port.name = LT_FW_TARGET_NAME;
    port.single = LT_RPFW_SINGLE;
    return lt_rpapp_run(&port, lt_fw_blob, lt_fw_blob_size(), rp_mem, sizeof rp_mem);
}
