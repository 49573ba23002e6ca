/* lt_cliutil.h - small helpers shared by the host programs (lanetrace and its subcommands,
 * lanetrace-stream, the benchmarks) and host modules: a monotonic wall clock, WxH size parsing
 * and the 8-bit gamma encoding of linear values for PNG output. Host only.
 */
#ifndef LT_CLIUTIL_H
#define LT_CLIUTIL_H

#include <stddef.h>
#include <stdint.h>

/* Seconds of the monotonic clock (CLOCK_MONOTONIC): for intervals only. */
double lt_now_s(void);

/* "WxH" or "N" (square) -> *w, *h; 0 when both lie in 1..max, else -1 (nothing written). */
int lt_parse_wh(const char *s, uint32_t max, uint32_t *w, uint32_t *h);

/* path with ".tag" put before its extension ("r.json" + "q16" -> "r.q16.json"; no extension:
 * "r" -> "r.q16") into out[n]. Returns 0, or -1 when it does not fit (nothing is cut). */
int lt_path_tagged(char *out, size_t n, const char *path, const char *tag);

/* A linear value clamped to [0, 1] (NaN -> 0) encoded with gamma 2.2 to 0..255, rounded. */
uint8_t lt_gamma8(double v);

/* s for a text line: a copy into out[n] (cut at n - 1 bytes) with every control byte (< 0x20,
 * 0x7F: a newline, an escape sequence) shown as '?', as lt_diag does for messages. Names read
 * from a file (EXR part, view and channel names) go through it before they are printed as text;
 * JSON output escapes them instead. Returns out. */
const char *lt_shown(const char *s, char *out, size_t n);

/* A progress bar on stderr ("label [#####     ]  40% ETA 1.5s"): drawn only when stderr is a
 * TTY, the run has taken more than a second and quiet is 0; lt_progress_end erases it. One bar
 * at a time; lt_progress is called from one thread (lt_par.h calls it on the caller's). */
void lt_progress_begin(const char *label, int quiet);
void lt_progress(double done);
void lt_progress_end(void);

#endif /* LT_CLIUTIL_H */
