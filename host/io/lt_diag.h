/* lt_diag.h - the one diagnostic type of the host programs and the cycle model. A function that
 * can fail takes `lt_diag_t *diag` (may be NULL: no message wanted) and, when it fails, returns -1
 * (or NULL) with one line in diag->msg that names the input (file, option, key) and the rule or
 * limit it broke, e.g. "scenes/x.json: 'resolution' = 0 is out of range [1, 8192]". The message
 * carries no trailing newline and no program name; the caller decides where it goes and which
 * exit code follows (0 ok, 1 input or runtime error, 2 usage). The core (firmware/) never sees
 * this type: it returns lt_status_t and never prints. docs/architecture.md, "Errors".
 *
 * A message is one line: control bytes in it (from file names, keys, library texts) show as '?'.
 * A message is never silently cut: one longer than LT_DIAG_MAX - 1 bytes keeps its first
 * LT_DIAG_MAX - 4 bytes and ends with "..." (LT_DIAG_CUT), so a reader can tell.
 */
#ifndef LT_DIAG_H
#define LT_DIAG_H

#include <stdarg.h>

#define LT_DIAG_MAX 1024 /* bytes of msg, the terminating NUL included */
#define LT_DIAG_CUT "..." /* the end of a message that did not fit */

typedef struct lt_diag {
    char msg[LT_DIAG_MAX]; /* NUL-terminated; set by the failing function */
} lt_diag_t;

#if defined(__GNUC__)
#define LT_DIAG_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define LT_DIAG_PRINTF(f, a)
#endif

/* Set diag->msg from a printf format (a longer message is cut and ends with "..."). Returns -1,
 * so a failing function can end with `return lt_diag_fail(diag, ...);`. diag may be NULL. */
int lt_diag_fail(lt_diag_t *diag, const char *fmt, ...) LT_DIAG_PRINTF(2, 3);

/* What a path that exists but is not a regular file is, for messages: "a directory" or "a
 * device, FIFO or socket"; NULL for a regular file or a path stat cannot see. The readers refuse
 * such inputs before opening them (a FIFO without a writer would block the open). */
const char *lt_diag_not_regular(const char *path);

/* The same with a va_list (for a module's own wrapper). Returns -1. */
int lt_diag_vfail(lt_diag_t *diag, const char *fmt, va_list ap) LT_DIAG_PRINTF(2, 0);

/* Put formatted context in front of the message already in diag->msg (e.g. `"%s: ", path` over
 * a callee's message), cutting the result with "..." as lt_diag_fail does. Returns -1. diag
 * may be NULL. */
int lt_diag_prefix(lt_diag_t *diag, const char *fmt, ...) LT_DIAG_PRINTF(2, 3);

#endif /* LT_DIAG_H */
