/* lt_rx_hid.h - an lt_rx byte source on a USB HID device through hidapi (hidraw backend by
 * default, libusb with `make STREAM_HID=hidapi-libusb`): each 64-byte input report is one stream
 * frame, handed to the shared receiver as bytes. Linked only into lt-stream (host/usb/ is outside
 * the host library, so other programs need no hidapi). Host only.
 */
#ifndef LT_RX_HID_H
#define LT_RX_HID_H

#include <stddef.h>
#include "stream/lt_rx.h"

/* Open by "VID:PID" (hex, e.g. "1209:0001"; the first matching device) or, when vidpid is NULL,
 * by a hidapi path (hidraw: "/dev/hidraw0"). Returns NULL with a message naming the device and
 * hidapi's reason (on this machine: "No HID devices found in the system."). */
lt_rx_src_t *lt_rx_src_hid(const char *vidpid, const char *path, lt_diag_t *diag);

#endif /* LT_RX_HID_H */
