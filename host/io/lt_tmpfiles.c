/* lt_tmpfiles.c - temporaries removed on fatal signals, output sets committed together. Host
 * only (POSIX signals, rename, unlink). */
#include "io/lt_tmpfiles.h"

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* the registry: a slot is live while used[i] != 0; the handler reads it, so the flags are
 * sig_atomic_t and a slot's name is written before its flag is set */
static char g_tmp[LT_TMP_MAX][LT_TMP_PATH_MAX];
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

int lt_tmp_begin(const char *path, char out[LT_TMP_PATH_MAX], lt_diag_t *diag)
{
    int i, k = snprintf(out, LT_TMP_PATH_MAX, "%s.tmp.%ld", path, (long)getpid());
    if (k < 0 || k >= LT_TMP_PATH_MAX) {
        out[0] = '\0';
        return lt_diag_fail(diag, "%.80s...: the output path is %zu bytes, longer than the %d "
                            "allowed (LT_TMP_PATH_MAX, with its temporary suffix)", path,
                            strlen(path), LT_TMP_PATH_MAX - 24);
    }
    for (i = 0; i < LT_TMP_MAX; i++)
        if (!g_used[i]) {
            memcpy(g_tmp[i], out, (size_t)k + 1);
            g_used[i] = 1;
            return 0;
        }
    return lt_diag_fail(diag, "%s: more than %d outputs in progress (LT_TMP_MAX)", path,
                        LT_TMP_MAX);
}

void lt_tmp_end(const char *tmp)
{
    int i;
    for (i = 0; i < LT_TMP_MAX; i++)
        if (g_used[i] && strcmp(g_tmp[i], tmp) == 0) {
            g_used[i] = 0;
            return;
        }
}

void lt_tmp_discard(const char *tmp)
{
    (void)unlink(tmp);
    lt_tmp_end(tmp);
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
    {
        /* the directory must take the file: said now, with the output's own name */
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
        if (rc == 0 && rename(s->tmp[i], s->path[i]) != 0)
            rc = lt_diag_fail(diag, "%s: cannot rename the output into place: %s", s->path[i],
                              strerror(errno));
        if (rc == 0)
            lt_tmp_end(s->tmp[i]);
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
