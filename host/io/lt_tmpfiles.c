/* lt_tmpfiles.c - temporaries removed on fatal signals, output sets committed together. Host
 * only (POSIX signals, rename, unlink). */
#include "io/lt_tmpfiles.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* the registry: a slot is live while used[i] != 0; the handler reads it, so the flags are
 * sig_atomic_t and a slot's name is written before its flag is set */
static char g_tmp[LT_TMP_MAX][LT_TMP_PATH_MAX];
static char g_owner[LT_TMP_MAX][LT_TMP_PATH_MAX]; /* the output each temporary becomes */
static volatile sig_atomic_t g_used[LT_TMP_MAX];
static int g_installed;

static void on_fatal(int sig)
{
    int i;
    for (i = 0; i < LT_TMP_MAX; i++)
        if (g_used[i])
            (void)unlink(g_tmp[i]);
    (void)signal(sig, SIG_DFL);
    (void)raise(sig);
}

void lt_tmp_handle_signals(void)
{
    static const int sigs[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGXFSZ, SIGPIPE};
    size_t i;
    if (g_installed)
        return;
    g_installed = 1;
    for (i = 0; i < sizeof sigs / sizeof sigs[0]; i++) {
        struct sigaction sa;
        memset(&sa, 0, sizeof sa);
        sa.sa_handler = on_fatal;
        (void)sigemptyset(&sa.sa_mask);
        (void)sigaction(sigs[i], &sa, NULL);
    }
}

/* Whether path exists and is neither a regular file nor a directory (a symbolic link, a device,
 * a FIFO, a socket): such an output is written through, not replaced (lt_tmp_commit). */
static int special_dest(const char *path)
{
    struct stat st;
    return lstat(path, &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode);
}

/* The registry slot of the temporary tmp, or -1. */
static int slot_of(const char *tmp)
{
    int i;
    for (i = 0; i < LT_TMP_MAX; i++)
        if (g_used[i] && strcmp(g_tmp[i], tmp) == 0)
            return i;
    return -1;
}

const char *lt_tmp_target(const char *path)
{
    int i = slot_of(path);
    return i >= 0 ? g_owner[i] : path;
}

int lt_tmp_begin(const char *path, char out[LT_TMP_PATH_MAX], lt_diag_t *diag)
{
    static unsigned serial;
    int i, k;
    if (slot_of(path) >= 0) {
        /* an output set's member (lt_outset_add): its temporary already stands between the
           writer and the output, so the writer writes it directly; a temporary of the temporary
           gained nothing and put "<path>.tmp.<pid>.tmp.<pid>" in the messages */
        memcpy(out, path, strlen(path) + 1);
        return 0;
    }
    if (special_dest(path)) {
        /* not beside it: /dev/null's directory is /dev */
        const char *dir = getenv("TMPDIR");
        if (dir == NULL || dir[0] == '\0')
            dir = "/tmp";
        k = snprintf(out, LT_TMP_PATH_MAX, "%s/lanetrace.%ld.%u.tmp", dir, (long)getpid(),
                     serial++);
    } else {
        k = snprintf(out, LT_TMP_PATH_MAX, "%s.tmp.%ld", path, (long)getpid());
    }
    if (k < 0 || k >= LT_TMP_PATH_MAX) {
        out[0] = '\0';
        return lt_diag_fail(diag, "%.80s...: the output path is %zu bytes, longer than the %d "
                            "allowed (LT_TMP_PATH_MAX, with its temporary suffix)", path,
                            strlen(path), LT_TMP_PATH_MAX - 24);
    }
    for (i = 0; i < LT_TMP_MAX; i++)
        if (!g_used[i]) {
            memcpy(g_tmp[i], out, (size_t)k + 1);
            memcpy(g_owner[i], path, strlen(path) + 1);
            g_used[i] = 1;
            return 0;
        }
    return lt_diag_fail(diag, "%s: more than %d outputs in progress (LT_TMP_MAX)", path,
                        LT_TMP_MAX);
}

void lt_tmp_end(const char *tmp)
{
    int i = slot_of(tmp);
    if (i >= 0)
        g_used[i] = 0;
}

void lt_tmp_discard(const char *tmp)
{
    (void)unlink(tmp);
    lt_tmp_end(tmp);
}

/* tmp's bytes written into path, opened as a shell redirection opens it (the caller removes
 * tmp). */
static int copy_into(const char *tmp, const char *path, lt_diag_t *diag)
{
    char buf[65536];
    int in = open(tmp, O_RDONLY), out = -1, rc = 0;
    ssize_t n = 0;
    if (in < 0)
        return lt_diag_fail(diag, "%s: cannot reopen its temporary %s: %s", path, tmp,
                            strerror(errno));
    out = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0666);
    if (out < 0)
        rc = lt_diag_fail(diag, "%s: cannot open it for writing: %s", path, strerror(errno));
    while (rc == 0 && (n = read(in, buf, sizeof buf)) > 0) {
        ssize_t off = 0;
        while (rc == 0 && off < n) {
            ssize_t w = write(out, buf + off, (size_t)(n - off));
            if (w < 0 && errno == EINTR)
                continue;
            if (w <= 0)
                rc = lt_diag_fail(diag, "%s: writing it failed: %s", path,
                                  w < 0 ? strerror(errno) : "no progress");
            else
                off += w;
        }
    }
    if (rc == 0 && n < 0)
        rc = lt_diag_fail(diag, "%s: reading its temporary %s failed: %s", path, tmp,
                          strerror(errno));
    if (out >= 0 && close(out) != 0 && rc == 0)
        rc = lt_diag_fail(diag, "%s: closing it failed: %s", path, strerror(errno));
    (void)close(in);
    return rc;
}

int lt_tmp_commit(const char *tmp, const char *path, lt_diag_t *diag)
{
    struct stat st;
    int rc = 0, renamed = 0, there;
    if (strcmp(tmp, path) == 0)
        return 0; /* an output set's member, written directly: lt_outset_commit moves it */
    there = lstat(path, &st) == 0;
    if (there && S_ISDIR(st.st_mode))
        rc = lt_diag_fail(diag, "%s: is a directory; the output was not written", path);
    else if (there && !S_ISREG(st.st_mode)) /* special_dest */
        rc = copy_into(tmp, path, diag); /* a link, device or FIFO stays what it is */
    else if (rename(tmp, path) != 0)
        rc = lt_diag_fail(diag, "%s: cannot move the finished output into place: %s", path,
                          strerror(errno));
    else
        renamed = 1;
    if (renamed)
        lt_tmp_end(tmp);
    else
        lt_tmp_discard(tmp); /* copied through, or failed */
    return rc;
}

int lt_outset_add(lt_outset_t *s, const char *path, const char **tmp, lt_diag_t *diag)
{
    int i;
    if (s->n >= LT_OUTSET_MAX)
        return lt_diag_fail(diag, "%s: more than %d outputs in one set", path, LT_OUTSET_MAX);
    if (strlen(path) >= LT_TMP_PATH_MAX)
        return lt_diag_fail(diag, "%.80s...: the output path is %zu bytes, longer than %d",
                            path, strlen(path), LT_TMP_PATH_MAX - 1);
    for (i = 0; i < s->n; i++)
        if (strcmp(s->path[i], path) == 0)
            return lt_diag_fail(diag, "%s: named twice in one output set (two outputs would "
                                "overwrite each other)", path);
    if (!special_dest(path)) {
        /* the directory must take the file: said now, with the output's own name (a link,
           device or FIFO is written through: its directory is not written) */
        char dir[LT_TMP_PATH_MAX];
        const char *slash = strrchr(path, '/');
        struct stat st;
        if (slash == NULL)
            (void)snprintf(dir, sizeof dir, ".");
        else if (slash == path)
            (void)snprintf(dir, sizeof dir, "/");
        else
            (void)snprintf(dir, sizeof dir, "%.*s", (int)(slash - path), path);
        if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode) || access(dir, W_OK | X_OK) != 0)
            return lt_diag_fail(diag, "%s: cannot create the output: directory '%s' %s", path,
                                dir, stat(dir, &st) != 0 ? "does not exist"
                                     : !S_ISDIR(st.st_mode) ? "is not a directory"
                                                            : "is not writable");
    }
    if (lt_tmp_begin(path, s->tmp[s->n], diag) != 0)
        return -1;
    memcpy(s->path[s->n], path, strlen(path) + 1);
    *tmp = s->tmp[s->n];
    s->n++;
    return 0;
}

int lt_outset_commit(lt_outset_t *s, lt_diag_t *diag)
{
    int i, rc = 0;
    /* what would make a rename fail half-way, checked before the first one: a directory where
       a file goes (the temporaries exist, so their directories are writable) */
    for (i = 0; i < s->n && rc == 0; i++) {
        struct stat st;
        if (stat(s->path[i], &st) == 0 && S_ISDIR(st.st_mode))
            rc = lt_diag_fail(diag, "%s: is a directory; no output of the set was written",
                              s->path[i]);
    }
    if (rc != 0) {
        lt_outset_abort(s);
        return rc;
    }
    for (i = 0; i < s->n; i++) {
        if (rc == 0)
            rc = lt_tmp_commit(s->tmp[i], s->path[i], diag);
        else
            lt_tmp_discard(s->tmp[i]);
    }
    s->n = 0;
    return rc;
}

void lt_outset_abort(lt_outset_t *s)
{
    int i;
    for (i = 0; i < s->n; i++)
        lt_tmp_discard(s->tmp[i]);
    s->n = 0;
}

int lt_write_file_atomic(const char *path, const void *p, size_t n, lt_diag_t *diag)
{
    lt_outset_t *set = calloc(1, sizeof *set); /* 128 KB of names: not on the stack */
    const char *tmp;
    FILE *f;
    if (set == NULL) {
        lt_diag_fail(diag, "%s: out of memory", path);
        return -1;
    }
    if (lt_outset_add(set, path, &tmp, diag) != 0) {
        free(set);
        return -1;
    }
    f = fopen(tmp, "wb");
    if (f == NULL || fwrite(p, 1, n, f) != n || fclose(f) != 0) {
        if (f != NULL)
            (void)fclose(f);
        lt_outset_abort(set);
        free(set);
        lt_diag_fail(diag, "%s: cannot write the file (nothing written)", path);
        return -1;
    }
    {
        int rc = lt_outset_commit(set, diag);
        free(set);
        return rc;
    }
}
