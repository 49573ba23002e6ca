/* lt_import.c - assimp imports in a forked child process (POSIX fork, pipe, poll, waitpid).
 *
 * assimp 5.2.5 aborts (ai_assert), dereferences NULL or reads past buffers on some inputs, valid
 * ones included (two OpenGEX files of assimp's own test models abort in PretransformVertices), and
 * spins forever on others; none of that may take the program down. The child imports without
 * post-processing, checks the scene graph (mesh and vertex indices, node graph depth and size,
 * face counts against primitive types) and hides cameras and lights from PretransformVertices
 * (it asserts that each has a node of its name: we keep geometry only), applies the
 * post-processing, converts the scene and writes one record to a pipe: a header, then the
 * triangles or the message. Its stdout and stderr go to a second pipe whose last 4 KiB are kept
 * for the crash message. The parent reads both with poll() until the deadline, bounds what it
 * accepts (LT_MESH_MAX_TRIS triangles, a 1 KiB message, nothing after the record), and reads the
 * child's exit status. Host only; docs/io.md.
 */
#include "io/lt_import.h"
#include "io/lt_diag.h"

#include "io/lt_meshcheck.h"

#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#define WIRE_MAGIC 0x4C544D31u /* "LTM1" */
#define MSG_MAX LT_DIAG_MAX    /* longest message from the child */
#define TAIL_MAX 4096u         /* bytes of the child's stdout/stderr kept */
#define NODES_MAX (1u << 24)   /* scene graph nodes visited */
#define DEPTH_MAX 4096u        /* scene graph depth (assimp recurses over it) */

typedef struct wire {
    uint32_t magic;
    int32_t status;  /* 0: triangles follow; -1: msglen bytes of message follow */
    uint32_t ntris;
    uint32_t msglen;
    double lo[3], hi[3];
} wire_t;

/* ---- the child ------------------------------------------------------------------------------- */

static int write_all(int fd, const void *p, size_t n)
{
    const char *c = (const char *)p;
    while (n > 0) {
        ssize_t w = write(fd, c, n);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0)
            return -1;
        c += w;
        n -= (size_t)w;
    }
    return 0;
}

static void child_main(int fd, const char *path, lt_import_child_fn fn, void *ctx)
{
    lt_mesh_t m;
    lt_diag_t d;
    const char *msg = d.msg;
    wire_t w;
    int rc;

    memset(&m, 0, sizeof m);
    d.msg[0] = '\0';
    rc = fn(ctx, &m, &d);
    memset(&w, 0, sizeof w);
    w.magic = WIRE_MAGIC;
    if (rc == 0 && (m.v == NULL || m.ntris == 0 || m.ntris > LT_MESH_MAX_TRIS)) {
        (void)lt_diag_fail(&d, "%s: the importer returned %u triangles (need 1..%u)",
                            path, m.ntris, LT_MESH_MAX_TRIS);
        rc = -1;
    }
    if (rc == 0) {
        w.status = 0;
        w.ntris = m.ntris;
        memcpy(w.lo, m.lo, sizeof w.lo);
        memcpy(w.hi, m.hi, sizeof w.hi);
        if (write_all(fd, &w, sizeof w) != 0 ||
            write_all(fd, m.v, (size_t)m.ntris * 9 * sizeof(double)) != 0)
            _exit(3);
    } else {
        if (msg[0] == '\0')
            (void)lt_diag_fail(&d, "%s: the importer failed without a message", path);
        w.status = -1;
        w.msglen = (uint32_t)strlen(msg);
        if (write_all(fd, &w, sizeof w) != 0 || write_all(fd, msg, w.msglen) != 0)
            _exit(3);
    }
    /* no clean-up: the process ends here, without atexit handlers or stdio flushes */
    _exit(0);
}

/* ---- the parent ------------------------------------------------------------------------------ */

static const char *signal_name(int s)
{
    switch (s) {
    case SIGALRM: return "SIGALRM";
    case SIGABRT: return "SIGABRT";
    case SIGSEGV: return "SIGSEGV";
    case SIGFPE: return "SIGFPE";
    case SIGILL: return "SIGILL";
    case SIGKILL: return "SIGKILL";
    case SIGTERM: return "SIGTERM";
    case SIGINT: return "SIGINT";
    case SIGPIPE: return "SIGPIPE";
#ifdef SIGBUS
    case SIGBUS: return "SIGBUS";
#endif
#ifdef SIGTRAP
    case SIGTRAP: return "SIGTRAP";
#endif
#ifdef SIGSYS
    case SIGSYS: return "SIGSYS";
#endif
#ifdef SIGXCPU
    case SIGXCPU: return "SIGXCPU";
#endif
#ifdef SIGXFSZ
    case SIGXFSZ: return "SIGXFSZ";
#endif
    default: return "signal";
    }
}

/* The import time limit: LT_IMPORT_TIMEOUT seconds (0 = none), default 120. */
static int timeout_seconds(const char *path, unsigned *s, lt_diag_t *diag)
{
    const char *v = getenv(LT_IMPORT_TIMEOUT_ENV);
    unsigned long x = 0;
    const char *c;
    *s = LT_IMPORT_TIMEOUT_DEFAULT;
    if (v == NULL || v[0] == '\0')
        return 0;
    for (c = v; *c != '\0'; c++) {
        if (!isdigit((unsigned char)*c) || x > 1000000ul) {
            lt_diag_fail(diag, "%s: %s='%.40s': expected whole seconds 0..1000000 (0 = no "
                 "limit)", path, LT_IMPORT_TIMEOUT_ENV, v);
            return -1;
        }
        x = x * 10 + (unsigned long)(*c - '0');
    }
    if (x > 1000000ul) {
        lt_diag_fail(diag, "%s: %s='%.40s': expected whole seconds 0..1000000 (0 = no limit)",
             path, LT_IMPORT_TIMEOUT_ENV, v);
        return -1;
    }
    *s = (unsigned)x;
    return 0;
}

static double now_s(void)
{
    struct timespec ts;
    (void)clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* The most telling line of what the child printed: an assertion, a sanitizer report, an uncaught
 * exception, else the last non-empty line; printable ASCII, at most 200 bytes. */
static void last_words(const char *tail, size_t n, char *out, size_t outlen)
{
    static const char *const keys[] = {"ai_assert", "ERROR: AddressSanitizer", "runtime error",
                                       "what():", "terminate called", "Assertion"};
    const size_t nk = sizeof keys / sizeof keys[0];
    const char *best = NULL, *best_end = NULL, *p = tail, *end = tail + n;
    size_t best_rank = nk, k, i, o = 0;
    while (p < end) {
        const char *e = (const char *)memchr(p, '\n', (size_t)(end - p));
        const char *le = e != NULL ? e : end, *q;
        for (q = p; q < le && isspace((unsigned char)*q); q++)
            ;
        if (q < le) {
            size_t r = nk;
            for (k = 0; k < nk && r == nk; k++) {
                size_t kl = strlen(keys[k]);
                const char *s;
                for (s = q; s + kl <= le; s++)
                    if (memcmp(s, keys[k], kl) == 0) {
                        r = k;
                        break;
                    }
            }
            /* the first line of the best-ranked key, else the last line */
            if ((r < nk && r < best_rank) || (r == nk && best_rank == nk)) {
                best = q;
                best_end = le;
                best_rank = r;
            }
        }
        p = le + 1;
    }
    if (outlen == 0)
        return;
    out[0] = '\0';
    if (best == NULL)
        return;
    for (i = 0; i < (size_t)(best_end - best) && o + 1 < outlen && o < 200; i++) {
        unsigned char c = (unsigned char)best[i];
        out[o++] = c >= 0x20 && c < 0x7F ? (char)c : c == '\t' ? ' ' : '?';
    }
    while (o > 0 && (out[o - 1] == ' ' || out[o - 1] == '\r'))
        o--;
    out[o] = '\0';
}

/* The parent's view of the child: its pipes, the record read so far, the tail of its output. */
typedef struct reader {
    int dp, ep;                  /* data and stdout/stderr pipes (read ends) */
    int data_open, err_open;
    wire_t w;                    /* the record's header */
    size_t got_w, got_p, want_p; /* header and payload bytes read, payload expected */
    size_t extra;                /* bytes after the record (or 1: not our record) */
    char *payload;               /* the triangles (malloc) or msg */
    char msg[MSG_MAX + 1];
    char tail[TAIL_MAX];         /* the last TAIL_MAX bytes of the child's output */
    size_t tail_n;
} reader_t;

/* Pipes and fork; the child runs fn and never returns. Returns the child's pid, or -1 with a
 * message. */
static pid_t start_child(const char *path, lt_import_child_fn fn, void *ctx, unsigned limit,
                         int dp[2], int ep[2], lt_diag_t *diag)
{
    static const int crash_signals[] = {SIGSEGV, SIGABRT, SIGFPE, SIGILL,
#ifdef SIGBUS
                                        SIGBUS,
#endif
#ifdef SIGSYS
                                        SIGSYS,
#endif
                                        SIGPIPE, SIGINT, SIGTERM, SIGALRM};
    struct rlimit nocore;
    size_t k;
    pid_t pid;
    if (pipe(dp) != 0) {
        lt_diag_fail(diag, "%s: cannot start the importer process: pipe: %s", path,
                     strerror(errno));
        return -1;
    }
    if (pipe(ep) != 0) {
        lt_diag_fail(diag, "%s: cannot start the importer process: pipe: %s", path,
                     strerror(errno));
        (void)close(dp[0]);
        (void)close(dp[1]);
        return -1;
    }
    (void)fflush(NULL); /* nothing buffered is written twice */
    pid = fork();
    if (pid < 0) {
        lt_diag_fail(diag, "%s: cannot start the importer process: fork: %s", path,
                     strerror(errno));
        (void)close(dp[0]);
        (void)close(dp[1]);
        (void)close(ep[0]);
        (void)close(ep[1]);
        return -1;
    }
    if (pid > 0) {
        (void)close(dp[1]);
        (void)close(ep[1]);
        return pid;
    }
    nocore.rlim_cur = 0;
    nocore.rlim_max = 0;
    (void)setrlimit(RLIMIT_CORE, &nocore); /* a crash leaves no core file */
    /* a crash or an interrupt ends the child: no handler of the parent's (a test framework's, a
     * sanitizer's, the CLI's clean-up on Ctrl-C) may run in here */
    for (k = 0; k < sizeof crash_signals / sizeof crash_signals[0]; k++)
        (void)signal(crash_signals[k], SIG_DFL);
    /* a backstop should the parent die without killing it (SIGKILL): the child ends shortly
     * after the deadline on its own */
    if (limit > 0)
        (void)alarm(limit + 5);
    (void)close(dp[0]);
    (void)close(ep[0]);
    (void)dup2(ep[1], STDOUT_FILENO);
    (void)dup2(ep[1], STDERR_FILENO);
    if (ep[1] > STDERR_FILENO)
        (void)close(ep[1]);
    child_main(dp[1], path, fn, ctx);
    _exit(4); /* not reached */
}

/* The child's output: keep the last TAIL_MAX bytes. */
static void read_tail(reader_t *rd)
{
    char buf[65536];
    ssize_t r = read(rd->ep, buf, sizeof buf);
    if (r > 0) {
        size_t k = (size_t)r;
        if (k >= TAIL_MAX) {
            memcpy(rd->tail, buf + k - TAIL_MAX, TAIL_MAX);
            rd->tail_n = TAIL_MAX;
        } else {
            if (rd->tail_n + k > TAIL_MAX) {
                memmove(rd->tail, rd->tail + (rd->tail_n + k - TAIL_MAX), TAIL_MAX - k);
                rd->tail_n = TAIL_MAX - k;
            }
            memcpy(rd->tail + rd->tail_n, buf, k);
            rd->tail_n += k;
        }
    } else if (r == 0 || (errno != EINTR && errno != EAGAIN)) {
        rd->err_open = 0;
    }
}

/* The record: header, then payload (triangles or message), then end of file. Returns 0, or -1
 * with a message (out of memory). */
static int read_record(reader_t *rd, const char *path, lt_diag_t *diag)
{
    char buf[65536], *dst;
    size_t room;
    ssize_t r;
    if (rd->got_w < sizeof rd->w) {
        dst = (char *)&rd->w + rd->got_w;
        room = sizeof rd->w - rd->got_w;
    } else if (rd->got_p < rd->want_p) {
        dst = rd->payload + rd->got_p;
        room = rd->want_p - rd->got_p;
    } else {
        dst = buf;
        room = sizeof buf;
    }
    r = read(rd->dp, dst, room);
    if (r == 0 || (r < 0 && errno != EINTR && errno != EAGAIN)) {
        rd->data_open = 0;
        return 0;
    }
    if (r < 0)
        return 0;
    if (rd->got_w < sizeof rd->w) {
        const wire_t *w = &rd->w;
        rd->got_w += (size_t)r;
        if (rd->got_w < sizeof rd->w)
            return 0;
        if (w->magic != WIRE_MAGIC || (w->status != 0 && w->status != -1) ||
            (w->status == 0 && (w->ntris == 0 || w->ntris > LT_MESH_MAX_TRIS)) ||
            (w->status != 0 && w->msglen > MSG_MAX)) {
            rd->extra = 1; /* not our record: refused by the verdict */
            rd->data_open = 0;
            return 0;
        }
        rd->want_p = w->status == 0 ? (size_t)w->ntris * 9 * sizeof(double) : w->msglen;
        rd->payload = w->status == 0 ? (char *)malloc(rd->want_p) : rd->msg;
        if (rd->payload == NULL)
            return lt_diag_fail(diag, "%s: out of memory for %u triangles from the importer",
                                path, w->ntris);
    } else if (rd->got_p < rd->want_p) {
        rd->got_p += (size_t)r;
    } else {
        rd->extra += (size_t)r;
    }
    return 0;
}

/* Read both pipes until they close or the deadline passes. Returns 0 (closed), 1 (time-out) or
 * -1 (an error, message set). */
static int pump(reader_t *rd, unsigned limit, double deadline, const char *path, lt_diag_t *diag)
{
    while (rd->data_open || rd->err_open) {
        struct pollfd pf[2];
        nfds_t n = 0;
        int ms = -1, pr, i;
        if (limit > 0) {
            double left = deadline - now_s();
            if (left <= 0)
                return 1;
            ms = left > 3600.0 ? 3600000 : (int)(left * 1000.0) + 1;
        }
        if (rd->data_open) {
            pf[n].fd = rd->dp;
            pf[n].events = POLLIN;
            pf[n].revents = 0;
            n++;
        }
        if (rd->err_open) {
            pf[n].fd = rd->ep;
            pf[n].events = POLLIN;
            pf[n].revents = 0;
            n++;
        }
        pr = poll(pf, n, ms);
        if (pr < 0 && errno == EINTR)
            continue;
        if (pr < 0)
            return lt_diag_fail(diag, "%s: waiting for the importer process: poll: %s", path,
                                strerror(errno));
        for (i = 0; i < (int)n; i++) {
            if (pf[i].revents == 0)
                continue;
            if (pf[i].fd == rd->ep)
                read_tail(rd);
            else if (read_record(rd, path, diag) != 0)
                return -1;
        }
    }
    return 0;
}

/* Wait for the child (killed first when *timed_out != 0), still within the deadline. Returns 0,
 * or -1 with a message. */
static int reap(pid_t pid, int *status, int *timed_out, unsigned limit, double deadline,
                const char *path, lt_diag_t *diag)
{
    if (*timed_out != 0)
        (void)kill(pid, SIGKILL);
    for (;;) {
        pid_t r = waitpid(pid, status, *timed_out != 0 ? 0 : WNOHANG);
        if (r == pid)
            return 0;
        if (r < 0 && errno == EINTR)
            continue;
        if (r < 0)
            return lt_diag_fail(diag, "%s: waiting for the importer process: %s", path,
                                strerror(errno));
        if (limit > 0 && now_s() >= deadline) {
            *timed_out = 1;
            (void)kill(pid, SIGKILL);
            continue;
        }
        {
            struct timespec ts = {0, 2000000}; /* 2 ms */
            (void)nanosleep(&ts, NULL);
        }
    }
}

/* How the child ended, as the result: 0 with the mesh, or -1 with one line. */
static int verdict(reader_t *rd, int status, int timed_out, unsigned limit, const char *path,
                   lt_mesh_t *m, lt_diag_t *diag)
{
    char words[256];
    last_words(rd->tail, rd->tail_n, words, sizeof words);
    if (timed_out > 0)
        return lt_diag_fail(diag, "%s: the importer (assimp) did not finish within %u s (%s); "
                            "stopped it", path, limit, LT_IMPORT_TIMEOUT_ENV);
    if (WIFSIGNALED(status)) {
        int s = WTERMSIG(status);
        return lt_diag_fail(diag, "%s: the importer (assimp) crashed (signal %d, %s) on this "
                            "file%s%s", path, s, signal_name(s),
                            words[0] != '\0' ? ": " : s == SIGKILL ? " (killed: out of memory?)"
                                                                   : "", words);
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        int sanitizer = strstr(words, "Sanitizer") != NULL || strstr(words, "runtime error") != NULL;
        return lt_diag_fail(diag, "%s: the importer (assimp) %s (exit status %d) on this file%s%s",
                            path, sanitizer ? "crashed" : "failed",
                            WIFEXITED(status) ? WEXITSTATUS(status) : -1,
                            words[0] != '\0' ? ": " : "", words);
    }
    if (rd->got_w < sizeof rd->w || rd->got_p < rd->want_p || rd->extra != 0)
        return lt_diag_fail(diag, "%s: the importer process ended with %s (%zu of %zu header "
                            "bytes, %zu of %zu data bytes%s)", path,
                            rd->extra != 0 ? "an invalid record" : "an incomplete record",
                            rd->got_w, sizeof rd->w, rd->got_p, rd->want_p,
                            rd->extra != 0 ? ", unexpected bytes" : "");
    if (rd->w.status != 0) {
        rd->msg[rd->w.msglen] = '\0';
        return lt_diag_fail(diag, "%s", rd->msg);
    }
    m->v = (double *)(void *)rd->payload;
    rd->payload = NULL;
    m->ntris = rd->w.ntris;
    memcpy(m->lo, rd->w.lo, sizeof m->lo);
    memcpy(m->hi, rd->w.hi, sizeof m->hi);
    return 0;
}

int lt_import_isolated(const char *path, lt_import_child_fn fn, void *ctx, lt_mesh_t *m,
                       lt_diag_t *diag)
{
    reader_t *rd;
    int dp[2], ep[2], status = 0, timed_out, rc = -1;
    unsigned limit;
    pid_t pid;
    double deadline;

    memset(m, 0, sizeof *m);
    if (timeout_seconds(path, &limit, diag) != 0)
        return -1;
    rd = calloc(1, sizeof *rd);
    if (rd == NULL)
        return lt_diag_fail(diag, "%s: out of memory", path);
    pid = start_child(path, fn, ctx, limit, dp, ep, diag);
    if (pid < 0) {
        free(rd);
        return -1;
    }
    rd->dp = dp[0];
    rd->ep = ep[0];
    rd->data_open = rd->err_open = 1;
    (void)fcntl(rd->dp, F_SETFL, fcntl(rd->dp, F_GETFL) | O_NONBLOCK);
    (void)fcntl(rd->ep, F_SETFL, fcntl(rd->ep, F_GETFL) | O_NONBLOCK);
    deadline = limit > 0 ? now_s() + (double)limit : 0.0;
    timed_out = pump(rd, limit, deadline, path, diag);
    /* the pipes are closed when the child ends; wait for it, still within the deadline */
    if (reap(pid, &status, &timed_out, limit, deadline, path, diag) == 0 && timed_out >= 0)
        rc = verdict(rd, status, timed_out, limit, path, m, diag);
    (void)close(rd->dp);
    (void)close(rd->ep);
    if (rd->payload != NULL && rd->payload != rd->msg)
        free(rd->payload);
    free(rd);
    return rc;
}

/* ---- assimp in the child --------------------------------------------------------------------- */

typedef struct job {
    const char *path;
    const char *data; /* NULL: import from path */
    size_t len;
    const char *hint;
    unsigned flags;
    lt_import_convert_fn conv;
} job_t;

typedef struct walk {
    unsigned long nodes;
    unsigned nmeshes;
    unsigned char *placed; /* per mesh: referenced by a node */
} walk_t;

/* Walk the node graph as PretransformVertices will (recursively): bounded size and depth, mesh
 * indices in range, no missing child (assimp 5.2.5's RAW reader puts every group's node in the
 * first slot and leaves NULL in the others: its triangles would be lost, so it is refused). */
static int check_node(const struct aiNode *nd, unsigned depth, walk_t *w, const char *path,
                      lt_diag_t *diag)
{
    unsigned i;
    if (++w->nodes > NODES_MAX || depth > DEPTH_MAX) {
        lt_diag_fail(diag, "%s: the imported scene graph has more than %u nodes or is deeper than "
             "%u (a cycle?)", path, NODES_MAX, DEPTH_MAX);
        return -1;
    }
    if ((nd->mNumMeshes > 0 && nd->mMeshes == NULL) ||
        (nd->mNumChildren > 0 && nd->mChildren == NULL)) {
        lt_diag_fail(diag, "%s: the imported scene graph is inconsistent (node '%.60s' lists "
             "meshes or children it does not have)", path, nd->mName.data);
        return -1;
    }
    for (i = 0; i < nd->mNumMeshes; i++) {
        if (nd->mMeshes[i] >= w->nmeshes) {
            lt_diag_fail(diag, "%s: the imported scene graph is inconsistent (node '%.60s' refers "
                 "to mesh %u of %u)", path, nd->mName.data, nd->mMeshes[i], w->nmeshes);
            return -1;
        }
        w->placed[nd->mMeshes[i]] = 1;
    }
    for (i = 0; i < nd->mNumChildren; i++) {
        if (nd->mChildren[i] == NULL) {
            lt_diag_fail(diag, "%s: the imported scene graph is inconsistent (node '%.60s': child "
                 "%u of %u is missing; the importer lost part of the scene)", path,
                 nd->mName.data, i + 1, nd->mNumChildren);
            return -1;
        }
        if (check_node(nd->mChildren[i], depth + 1, w, path, diag) != 0)
            return -1;
    }
    return 0;
}

/* Check and repair what the post-processing steps trust, so that they neither crash nor fail:
 * a failing step makes aiApplyPostProcessing free the scene twice (assimp 5.2.5), so the one
 * failure PretransformVertices has (no placed mesh with faces and vertices) is found here. The
 * primitive-type flags are recomputed from the faces (a mesh that declares polygons but has
 * none trips TriangulateProcess's ai_assert). */
static int check_scene(struct aiScene *sc, const char *path, lt_diag_t *diag)
{
    unsigned i, f, j;
    walk_t w;
    int rc;
    if (sc->mMeshes == NULL) {
        lt_diag_fail(diag, "%s: the imported scene lists %u meshes but has none", path,
             sc->mNumMeshes);
        return -1;
    }
    for (i = 0; i < sc->mNumMeshes; i++) {
        struct aiMesh *me = sc->mMeshes[i];
        unsigned types = 0;
        if (me == NULL || (me->mNumVertices > 0 && me->mVertices == NULL) ||
            (me->mNumFaces > 0 && me->mFaces == NULL)) {
            lt_diag_fail(diag, "%s: the imported scene is inconsistent (mesh %u lacks its "
                 "vertices or faces)", path, i);
            return -1;
        }
        for (f = 0; f < me->mNumFaces; f++) {
            const struct aiFace *fa = &me->mFaces[f];
            if (fa->mNumIndices > 0 && fa->mIndices == NULL) {
                lt_diag_fail(diag, "%s: mesh %u face %u: %u indices missing", path, i, f,
                     fa->mNumIndices);
                return -1;
            }
            for (j = 0; j < fa->mNumIndices; j++)
                if (fa->mIndices[j] >= me->mNumVertices) {
                    lt_diag_fail(diag, "%s: mesh %u face %u: vertex index %u >= %u vertices", path,
                         i, f, fa->mIndices[j], me->mNumVertices);
                    return -1;
                }
            types |= fa->mNumIndices == 0   ? 0u
                     : fa->mNumIndices == 1 ? (unsigned)aiPrimitiveType_POINT
                     : fa->mNumIndices == 2 ? (unsigned)aiPrimitiveType_LINE
                     : fa->mNumIndices == 3 ? (unsigned)aiPrimitiveType_TRIANGLE
                                            : (unsigned)aiPrimitiveType_POLYGON;
        }
        me->mPrimitiveTypes =
            types | (me->mPrimitiveTypes & (unsigned)aiPrimitiveType_NGONEncodingFlag);
    }
    if (sc->mRootNode == NULL) {
        lt_diag_fail(diag, "%s: the imported scene has no root node", path);
        return -1;
    }
    w.nodes = 0;
    w.nmeshes = sc->mNumMeshes;
    w.placed = (unsigned char *)calloc(sc->mNumMeshes, 1);
    if (w.placed == NULL) {
        lt_diag_fail(diag, "%s: out of memory", path);
        return -1;
    }
    rc = check_node(sc->mRootNode, 0, &w, path, diag);
    if (rc == 0) {
        unsigned placed = 0;
        for (i = 0; i < sc->mNumMeshes; i++) {
            const struct aiMesh *me = sc->mMeshes[i];
            placed += w.placed[i];
            if (w.placed[i] && me->mNumFaces > 0 && me->mNumVertices > 0 &&
                me->mMaterialIndex < sc->mNumMaterials)
                break;
        }
        if (i == sc->mNumMeshes) {
            lt_diag_fail(diag, "%s: no triangles: none of the scene's %u meshes is both placed in "
                 "its node graph and has faces (%u placed)", path, sc->mNumMeshes, placed);
            rc = -1;
        }
    }
    free(w.placed);
    return rc;
}

static int child_import(void *ctx, lt_mesh_t *m, lt_diag_t *diag)
{
    const job_t *jb = (const job_t *)ctx;
    const struct aiScene *sc, *pp;
    struct aiScene *msc;

    sc = jb->data != NULL ? aiImportFileFromMemory(jb->data, (unsigned)jb->len, 0, jb->hint)
                          : aiImportFile(jb->path, 0);
    if (sc == NULL || sc->mNumMeshes == 0) {
        lt_diag_fail(diag, "%s: not a readable mesh (assimp: %s)", jb->path,
             sc == NULL ? aiGetErrorString() : "no meshes in the scene");
        return -1;
    }
    msc = (struct aiScene *)(uintptr_t)sc; /* assimp's own, mutable scene */
    if (check_scene(msc, jb->path, diag) != 0)
        return -1;
    /* PretransformVertices asserts that every camera and light has a node of its name; we keep
     * geometry only, so they are hidden from it (and the process ends without releasing them) */
    msc->mNumCameras = 0;
    msc->mNumLights = 0;
    pp = aiApplyPostProcessing(sc, jb->flags);
    if (pp == NULL || pp->mNumMeshes == 0) {
        lt_diag_fail(diag, "%s: not a readable mesh (assimp: %s)", jb->path,
             pp == NULL ? aiGetErrorString() : "no meshes in the scene");
        return -1;
    }
    return jb->conv(pp, jb->path, m, diag);
}

/* The file's extension (after the last '.' of its last component), "" if none. */
static const char *extension(const char *path)
{
    const char *slash = strrchr(path, '/'), *dot = strrchr(path, '.');
    if (dot == NULL || (slash != NULL && dot < slash))
        return "";
    return dot + 1;
}

int lt_import_mesh(const char *path, const char *data, size_t len, const char *hint,
                   unsigned flags, lt_import_convert_fn conv, lt_mesh_t *m, lt_diag_t *diag)
{
    lt_meshcheck_kind_t kind;
    char *own = NULL;
    job_t jb;
    int rc;

    memset(m, 0, sizeof *m);
    if (data == NULL) {
        unsigned char head[8];
        size_t hn = 0;
        FILE *f = fopen(path, "rb");
        if (f != NULL) {
            hn = fread(head, 1, sizeof head, f);
            (void)fclose(f);
        }
        kind = lt_meshcheck_kind(extension(path), head, hn);
        if (kind != LT_MESHCHECK_NONE) {
            if (lt_mesh_read_file(path, &own, &len, diag) != 0)
                return -1;
            data = own;
        }
    } else {
        kind = lt_meshcheck_kind(hint, (const unsigned char *)data, len);
    }
    if (kind != LT_MESHCHECK_NONE) {
        hint = lt_meshcheck_hint(kind);
        if (lt_meshcheck(kind, path, (const unsigned char *)data, len, diag) != 0) {
            free(own);
            return -1;
        }
    }
    jb.path = path;
    jb.data = data;
    jb.len = len;
    jb.hint = hint != NULL ? hint : "";
    jb.flags = flags;
    jb.conv = conv;
    rc = lt_import_isolated(path, child_import, &jb, m, diag);
    free(own);
    return rc;
}
