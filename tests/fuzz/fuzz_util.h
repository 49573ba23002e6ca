/* fuzz_util.h - helpers shared by the fuzz targets (tests/fuzz/fuzz_<name>.c): the input as a file
 * for readers that take a path, and the check that an error message is usable. Host only.
 */
#ifndef FUZZ_UTIL_H
#define FUZZ_UTIL_H

#include <stddef.h>
#include <stdint.h>

#include "io/lt_diag.h"

/* Write data to one file per process and suffix, "<dir>/lt-fuzz-<pid>-<suffix>" (dir: /dev/shm
 * when present, else $TMPDIR or /tmp), rewritten for every input and removed at exit; the suffix
 * keeps the extension the reader looks at ("in.obj", "in.obj.gz"). Aborts when it cannot write. */
const char *fuzz_file(const uint8_t *data, size_t size, const char *suffix);

/* Abort unless err[0..cap) holds a NUL-terminated, non-empty, one-line message (a failing call
 * must say why, in one line). */
void fuzz_check_message(const char *err, size_t cap);

/* A failed call's diagnostic (rc != 0) into err[0..cap), the harnesses' message buffer. */
void fuzz_take_message(char *err, size_t cap, int rc, const lt_diag_t *d);

#endif /* FUZZ_UTIL_H */
