/* lt_diag.c - the one diagnostic type (lt_diag.h): printf-style messages into a fixed buffer,
 * never silently cut. Host only (the host programs and the cycle model).
 */
#include "io/lt_diag.h"

#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

/* End a message that did not fit with LT_DIAG_CUT (msg holds LT_DIAG_MAX - 1 bytes then). */
static void mark_cut(lt_diag_t *diag)
{
    const size_t k = sizeof LT_DIAG_CUT; /* "..." and its NUL */
    memcpy(diag->msg + sizeof diag->msg - k, LT_DIAG_CUT, k);
}

/* Format into buf (n bytes, n >= 1); returns 1 when the text did not fit. An encoding error (a
 * wide string that has no multibyte form, say) leaves the format itself as the message. A message
 * is one line: a control byte in it - names and texts often come from the input file (a newline
 * in an EXR attribute name, an escape sequence in a JSON key) - is shown as '?'. */
static int diag_format(char *buf, size_t n, const char *fmt, va_list ap) LT_DIAG_PRINTF(3, 0);
static int diag_format(char *buf, size_t n, const char *fmt, va_list ap)
{
    char *p;
    int r = vsnprintf(buf, n, fmt, ap);
    if (r < 0) {
        r = snprintf(buf, n, "%s (message could not be formatted)", fmt);
        if (r < 0) {
            buf[0] = '\0';
            return 0;
        }
    }
    for (p = buf; *p != '\0'; p++)
        if ((unsigned char)*p < 0x20 || *p == 0x7F)
            *p = '?';
    return (size_t)r >= n;
}

int lt_diag_vfail(lt_diag_t *diag, const char *fmt, va_list ap)
{
    if (diag == NULL)
        return -1;
    if (diag_format(diag->msg, sizeof diag->msg, fmt, ap))
        mark_cut(diag);
    return -1;
}

int lt_diag_fail(lt_diag_t *diag, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    (void)lt_diag_vfail(diag, fmt, ap);
    va_end(ap);
    return -1;
}

int lt_diag_prefix(lt_diag_t *diag, const char *fmt, ...)
{
    char old[LT_DIAG_MAX];
    size_t n, m;
    int cut;
    va_list ap;
    if (diag == NULL)
        return -1;
    memcpy(old, diag->msg, sizeof old);
    old[sizeof old - 1] = '\0';
    va_start(ap, fmt);
    cut = diag_format(diag->msg, sizeof diag->msg, fmt, ap);
    va_end(ap);
    if (!cut) {
        n = strlen(diag->msg);
        m = strlen(old);
        cut = n + m >= sizeof diag->msg;
        memcpy(diag->msg + n, old, cut ? sizeof diag->msg - 1 - n : m);
        diag->msg[cut ? sizeof diag->msg - 1 : n + m] = '\0';
    }
    if (cut)
        mark_cut(diag);
    return -1;
}

const char *lt_diag_not_regular(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0 || S_ISREG(st.st_mode))
        return NULL;
    return S_ISDIR(st.st_mode) ? "a directory" : "a device, FIFO or socket";
}
