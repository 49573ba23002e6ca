/* lt_uart_tx.h - the board UART as an lt_stream byte sink (lt_stream_sink_fn): frames written
 * byte by byte through lt_fw_putc, unchanged (binary; no newline translation). A USB board would
 * supply a sink that copies the 64 bytes into its interrupt-IN endpoint buffer instead.
 * Builds: firmware (every target of firmware/targets/targets.mk).
 */
#ifndef LT_UART_TX_H
#define LT_UART_TX_H

#include <stdint.h>
#include "lt_fw.h"

/* Sink: ctx is unused (NULL). Cost: one lt_fw_putc per byte (about 10 instructions each under
 * QEMU, where the UART never throttles). */
static inline void lt_uart_tx_sink(void *ctx, const uint8_t *bytes, uint32_t n)
{
    uint32_t i;
    (void)ctx;
    for (i = 0; i < n; i++)
        lt_fw_putc(bytes[i]);
}

#endif /* LT_UART_TX_H */
