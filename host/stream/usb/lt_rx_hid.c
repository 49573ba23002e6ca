/* lt_rx_hid.c - lt_rx_src_hid (lt_rx_hid.h): hid_open / hid_open_path, then hid_read_timeout of
 * 64-byte input reports (the board's descriptor in docs/stream.md has no report ID, so a report is
 * exactly one frame). Built with -DLT_RX_NO_HIDAPI when pkg-config finds no hidapi: the source then
 * fails with a message saying so. Host only.
 */
#include "stream/usb/lt_rx_hid.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <wchar.h>

#ifndef LT_RX_NO_HIDAPI
#include <hidapi.h>

static long hid_src_read(void *ctx, uint8_t *buf, size_t n, int timeout_ms, lt_diag_t *diag)
{
    hid_device *d = ctx;
    int r;
    if (n < LT_STREAM_FRAME_BYTES) {
        lt_diag_fail(diag, "hid: read buffer of %zu bytes is below one report (64)", n);
        return LT_RX_ERROR;
    }
    r = hid_read_timeout(d, buf, LT_STREAM_FRAME_BYTES, timeout_ms);
    if (r < 0) {
        const wchar_t *w = hid_error(d);
        lt_diag_fail(diag, "hid: read failed: %ls", w != NULL ? w : L"(no reason given)");
        return LT_RX_ERROR;
    }
    return r == 0 ? LT_RX_TIMEOUT : (long)r;
}

static void hid_src_close(void *ctx)
{
    hid_close((hid_device *)ctx);
    hid_exit();
}

static const lt_rx_src_ops_t hid_ops = {hid_src_read, hid_src_close};

lt_rx_src_t *lt_rx_src_hid(const char *vidpid, const char *path, lt_diag_t *diag)
{
    hid_device *d;
    unsigned vid = 0, pid = 0;
    char name[128], tail;
    lt_rx_src_t *s;
    if (vidpid != NULL) {
        if (sscanf(vidpid, "%x:%x%c", &vid, &pid, &tail) != 2 || vid > 0xFFFFu || pid > 0xFFFFu) {
            lt_diag_fail(diag, "--hid %s: expected VID:PID in hex, each 0000..ffff", vidpid);
            return NULL;
        }
        snprintf(name, sizeof name, "hid %04x:%04x", vid, pid);
    } else {
        snprintf(name, sizeof name, "hid %s", path);
    }
    if (path != NULL) {
        /* hidraw paths are character devices: say what else the path is before hidapi tries */
        struct stat st;
        if (stat(path, &st) != 0) {
            lt_diag_fail(diag, "%s: %s", name, strerror(errno));
            return NULL;
        }
        if (!S_ISCHR(st.st_mode)) {
            lt_diag_fail(diag, "%s: not a HID device node (%s); --hid-path takes a character "
                         "device such as /dev/hidraw0", name,
                         S_ISDIR(st.st_mode) ? "a directory"
                         : S_ISREG(st.st_mode) ? "a regular file" : "not a character device");
            return NULL;
        }
    }
    if (hid_init() != 0) {
        lt_diag_fail(diag, "%s: hid_init failed", name);
        return NULL;
    }
    d = vidpid != NULL ? hid_open((unsigned short)vid, (unsigned short)pid, NULL)
                       : hid_open_path(path);
    if (d == NULL) {
        const wchar_t *w = hid_error(NULL);
        /* hidapi may report "Success" (errno 0) for a failed open: no reason then */
        if (w != NULL && (w[0] == L'\0' || wcscmp(w, L"Success") == 0))
            w = NULL;
        lt_diag_fail(diag, "%s: cannot open the device (hidapi: %ls); is it plugged in and "
                     "is its /dev/hidraw* node readable?", name,
                     w != NULL ? w : L"no reason given");
        hid_exit();
        return NULL;
    }
    s = lt_rx_src_custom(&hid_ops, d, name, 1);
    if (s == NULL) {
        hid_close(d);
        hid_exit();
        lt_diag_fail(diag, "%s: out of memory", name);
    }
    return s;
}

#else

lt_rx_src_t *lt_rx_src_hid(const char *vidpid, const char *path, lt_diag_t *diag)
{
    lt_diag_fail(diag, "hid %s: lt-stream was built without hidapi (install libhidapi-dev "
                 "and rebuild)", vidpid != NULL ? vidpid : path);
    return NULL;
}

#endif
