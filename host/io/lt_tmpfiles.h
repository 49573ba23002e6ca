/* lt_tmpfiles.h - temporary files that a fatal signal must not leave behind, and output sets that
 * appear all at once. Every writer of the host (EXR, PNG, reports, CSV) writes to a temporary name
 * beside the output and renames it into place; the temporary is registered here while it exists,
 * and lt_tmp_handle_signals() installs handlers for SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGXFSZ and
 * SIGPIPE that unlink every registered temporary (async-signal-safe: unlink only) and then die of
 * the same signal. An output set (the five files of `lanetrace render`) is committed by renaming
 * every member after all were written; a failure before the commit removes the new temporaries and
 * leaves the previous files as they were. Host only.
 */
#ifndef LT_TMPFILES_H
#define LT_TMPFILES_H

#include <stddef.h>

#include "io/lt_diag.h"

#ifdef __cplusplus
extern "C" {
#endif

#define LT_TMP_MAX 32        /* temporaries registered at once */
#define LT_TMP_PATH_MAX 4096 /* longest path, the NUL included (PATH_MAX on Linux) */

/* Install the handlers (once; later calls do nothing). */
void lt_tmp_handle_signals(void);

/* "<path>.tmp.<pid>" into out[LT_TMP_PATH_MAX] and registered ("$TMPDIR/lanetrace.<pid>.<n>.tmp"
 * when path is a link, device, FIFO or socket: see lt_tmp_commit). When path is itself a
 * registered temporary (an output set's member handed to a writer), out is path: the writer
 * writes it directly and its lt_tmp_commit leaves it to lt_outset_commit. Returns 0, or -1 with a
 * message naming path when the name does not fit (nothing is cut) or the registry is full. */
int lt_tmp_begin(const char *path, char out[LT_TMP_PATH_MAX], lt_diag_t *diag);

/* Make the finished temporary tmp the output path, and forget it: renamed into place when path
 * is a regular file or does not exist; written through (its bytes copied into path, then tmp
 * removed) when path is a symbolic link, a device, a FIFO or a socket, which stays what it is
 * (`--out /dev/null`, `--report /dev/stdout`, a link to a file elsewhere). For such a path
 * lt_tmp_begin puts the temporary in $TMPDIR (default /tmp). Returns 0, or -1 with a message
 * naming path (a directory there, a failed rename or write); tmp is removed either way. When tmp
 * is path (lt_tmp_begin on an output set's member) nothing is done: the set's commit moves it. */
int lt_tmp_commit(const char *tmp, const char *path, lt_diag_t *diag);

/* The output that the registered temporary path will become, for messages: a writer handed an
 * output set's temporary names the user's file, not "<file>.tmp.<pid>". path itself when it is
 * no registered temporary. */
const char *lt_tmp_target(const char *path);

/* Forget a temporary (after it was renamed into place or unlinked). */
void lt_tmp_end(const char *tmp);

/* Unlink a registered temporary and forget it. */
void lt_tmp_discard(const char *tmp);

/* An output set: paths whose new contents go to temporaries first. */
#define LT_OUTSET_MAX 16
typedef struct lt_outset {
    int n;
    char path[LT_OUTSET_MAX][LT_TMP_PATH_MAX];
    char tmp[LT_OUTSET_MAX][LT_TMP_PATH_MAX];
} lt_outset_t;

/* Add path; *tmp is where its writer writes (a complete file, by any means). Returns 0, or -1
 * with a message (name too long, more than LT_OUTSET_MAX members, the same path twice). */
int lt_outset_add(lt_outset_t *s, const char *path, const char **tmp, lt_diag_t *diag);

/* Rename every member's temporary into place. Returns 0, or -1 with a message (the members
 * renamed before the failure are new, the rest keep their previous contents; the temporaries
 * left are removed). */
int lt_outset_commit(lt_outset_t *s, lt_diag_t *diag);

/* Remove every member's temporary (the previous files stay as they were). */
void lt_outset_abort(lt_outset_t *s);

/* Write the n bytes at p as the file path, all or nothing (a one-member output set). Returns 0,
 * or -1 with a message naming path (the previous file is unchanged). */
int lt_write_file_atomic(const char *path, const void *p, size_t n, lt_diag_t *diag);

#ifdef __cplusplus
}
#endif
#endif /* LT_TMPFILES_H */
