/* test_tmpfiles.c - cmocka tests of host/io/lt_tmpfiles: a fatal signal (SIGINT, SIGTERM, SIGHUP,
 * SIGXFSZ, SIGPIPE) during a write leaves no temporary behind - registered ones directly, and
 * those of the EXR and PNG writers, killed in the middle of a large write - the process still dies
 * of the signal; over-long output names are refused, not cut; an output set replaces its files all
 * together or not at all (a failure before the commit, a directory in the way), and its members
 * are written by the writers directly, named as the outputs in messages. Builds: host,
 * sim, asan.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <dirent.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <sys/wait.h>
#include <unistd.h>

#include "io/lt_exr.h"
#include "io/lt_png.h"
#include "io/lt_tmpfiles.h"

static char g_dir[256];

static void sleep_us(long us)
{
    struct timespec ts;
    ts.tv_sec = us / 1000000;
    ts.tv_nsec = (us % 1000000) * 1000;
    (void)nanosleep(&ts, NULL);
}

static int setup(void **state)
{
    (void)state;
    snprintf(g_dir, sizeof g_dir, "/tmp/lt_tmpfiles_XXXXXX");
    return mkdtemp(g_dir) != NULL ? 0 : -1;
}

static int teardown(void **state)
{
    char cmd[300];
    (void)state;
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", g_dir);
    return system(cmd) == 0 ? 0 : -1;
}

/* files in g_dir whose name contains ".tmp." */
static int count_tmp(void)
{
    DIR *d = opendir(g_dir);
    struct dirent *e;
    int n = 0;
    assert_non_null(d);
    while ((e = readdir(d)) != NULL)
        n += strstr(e->d_name, ".tmp.") != NULL;
    closedir(d);
    return n;
}

static void write_text(const char *p, const char *t)
{
    FILE *f = fopen(p, "w");
    assert_non_null(f);
    fputs(t, f);
    fclose(f);
}

static int same_text(const char *p, const char *t)
{
    char buf[256];
    size_t n;
    FILE *f = fopen(p, "r");
    if (f == NULL)
        return 0;
    n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = '\0';
    return strcmp(buf, t) == 0;
}

/* a child registers a temporary, creates it and raises sig: the file is gone, the child died of
 * sig (the handler re-raises) */
static void test_registered_removed_on_signals(void **state)
{
    static const int sigs[] = {SIGINT, SIGTERM, SIGHUP, SIGXFSZ, SIGPIPE};
    size_t i;
    (void)state;
    for (i = 0; i < sizeof sigs / sizeof sigs[0]; i++) {
        int st;
        pid_t pid = fork();
        assert_true(pid >= 0);
        if (pid == 0) {
            char out[LT_TMP_PATH_MAX], p[300];
            lt_diag_t d;
            snprintf(p, sizeof p, "%s/o%zu.bin", g_dir, i);
            lt_tmp_handle_signals();
            if (lt_tmp_begin(p, out, &d) != 0)
                _exit(3);
            write_text(out, "partial");
            raise(sigs[i]);
            _exit(4);
        }
        assert_int_equal(waitpid(pid, &st, 0), pid);
        assert_true(WIFSIGNALED(st));
        assert_int_equal(WTERMSIG(st), sigs[i]);
        assert_int_equal(count_tmp(), 0);
    }
    printf("tmpfiles: SIGINT, SIGTERM, SIGHUP, SIGXFSZ, SIGPIPE: the registered temporary removed, "
           "the process died of the signal (5 of 5)\n");
}

/* the writers killed in the middle of a large write: no temporary left (timer signals at several
 * delays so some land inside the write) */
static void test_writers_killed_midway(void **state)
{
    int k, killed = 0;
    (void)state;
    for (k = 0; k < 12; k++) {
        int st;
        pid_t pid = fork();
        assert_true(pid >= 0);
        if (pid == 0) {
            enum { W = 2048, H = 1024 };
            static float z[W * H];
            static uint8_t px[W * H * 3];
            char p[300];
            lt_diag_t d;
            lt_exr_channel_t ch[2];
            lt_exr_image_t im;
            size_t j;
            for (j = 0; j < (size_t)W * H; j++) {
                z[j] = (float)((j * 2654435761u) % 1000003u);
                px[3 * j] = (uint8_t)(j * 7);
                px[3 * j + 1] = (uint8_t)(j * 13);
                px[3 * j + 2] = (uint8_t)(j >> 3);
            }
            lt_tmp_handle_signals();
            /* a helper process sends SIGTERM after a delay that grows with k */
            if (fork() == 0) {
                sleep_us(2000 + 6000 * k);
                kill(getppid(), SIGTERM);
                _exit(0);
            }
            memset(&im, 0, sizeof im);
            ch[0].name = "Z";
            ch[0].type = LT_EXR_FLOAT;
            ch[0].data = z;
            ch[1].name = "id";
            ch[1].type = LT_EXR_FLOAT;
            ch[1].data = z;
            im.width = W;
            im.height = H;
            im.nchannels = 2;
            im.channels = ch;
            for (;;) {
                snprintf(p, sizeof p, "%s/k%d.exr", g_dir, k);
                (void)lt_exr_write(p, &im, &d);
                snprintf(p, sizeof p, "%s/k%d.png", g_dir, k);
                (void)lt_png_write(p, px, W, H, 3, 3 * W, &d);
            }
        }
        assert_int_equal(waitpid(pid, &st, 0), pid);
        killed += WIFSIGNALED(st) && WTERMSIG(st) == SIGTERM;
        /* the helper may still be running for a moment; it only sends a signal */
        sleep_us(1000);
        if (count_tmp() != 0)
            printf("  FAIL: a temporary left after SIGTERM at %d us\n", 2000 + 6000 * k);
        assert_int_equal(count_tmp(), 0);
    }
    assert_int_equal(killed, 12);
    printf("tmpfiles: EXR and PNG writers (2048x1024) killed by SIGTERM at 12 moments: 0 "
           "temporaries left (bound 0)\n");
}

static void test_long_names_refused(void **state)
{
    char out[LT_TMP_PATH_MAX], *p = malloc(LT_TMP_PATH_MAX + 10);
    lt_diag_t d;
    lt_outset_t *s = calloc(1, sizeof *s);
    const char *dst;
    (void)state;
    assert_non_null(p);
    assert_non_null(s);
    memset(p, 'a', LT_TMP_PATH_MAX + 9);
    p[LT_TMP_PATH_MAX + 9] = '\0';
    assert_int_equal(lt_tmp_begin(p, out, &d), -1);
    assert_non_null(strstr(d.msg, "longer than"));
    assert_int_equal(lt_outset_add(s, p, &dst, &d), -1);
    assert_non_null(strstr(d.msg, "longer than"));
    p[LT_TMP_PATH_MAX - 5] = '\0'; /* fits itself, not with the suffix */
    assert_int_equal(lt_tmp_begin(p, out, &d), -1);
    printf("tmpfiles: names over LT_TMP_PATH_MAX (%d) with the temporary suffix refused: %s\n",
           LT_TMP_PATH_MAX, d.msg + strlen(d.msg) - 60);
    free(p);
    free(s);
}

/* a, b and c added to the set, "new a/b/c" written to their temporaries */
static void prepare3(lt_outset_t *s, const char *a, const char *b, const char *c)
{
    const char *const p[3] = {a, b, c};
    static const char *const text[3] = {"new a", "new b", "new c"};
    const char *t;
    lt_diag_t d;
    int i;
    for (i = 0; i < 3; i++) {
        assert_int_equal(lt_outset_add(s, p[i], &t, &d), 0);
        write_text(t, text[i]);
    }
}

static void test_outset_all_or_nothing(void **state)
{
    lt_outset_t *s = calloc(1, sizeof *s);
    char a[300], b[300], c[300];
    const char *ta, *tb;
    lt_diag_t d;
    (void)state;
    assert_non_null(s);
    snprintf(a, sizeof a, "%s/set.exr", g_dir);
    snprintf(b, sizeof b, "%s/set.png", g_dir);
    snprintf(c, sizeof c, "%s/set.json", g_dir);
    write_text(a, "old a");
    write_text(b, "old b");
    /* a failure before the commit: nothing replaced, no temporary left */
    assert_int_equal(lt_outset_add(s, a, &ta, &d), 0);
    assert_int_equal(lt_outset_add(s, b, &tb, &d), 0);
    write_text(ta, "new a");
    write_text(tb, "new b");
    lt_outset_abort(s);
    assert_true(same_text(a, "old a") && same_text(b, "old b"));
    assert_int_equal(count_tmp(), 0);
    /* the same path twice is refused */
    assert_int_equal(lt_outset_add(s, a, &ta, &d), 0);
    assert_int_equal(lt_outset_add(s, a, &tb, &d), -1);
    assert_non_null(strstr(d.msg, "named twice"));
    lt_outset_abort(s);
    /* a directory where the third output goes: refused before any rename */
    assert_int_equal(mkdir(c, 0755), 0);
    prepare3(s, a, b, c);
    assert_int_equal(lt_outset_commit(s, &d), -1);
    assert_non_null(strstr(d.msg, "is a directory"));
    assert_true(same_text(a, "old a") && same_text(b, "old b"));
    assert_int_equal(count_tmp(), 0);
    rmdir(c);
    /* the commit: all new */
    prepare3(s, a, b, c);
    assert_int_equal(lt_outset_commit(s, &d), 0);
    assert_true(same_text(a, "new a") && same_text(b, "new b") && same_text(c, "new c"));
    assert_int_equal(count_tmp(), 0);
    printf("tmpfiles: output set: abort keeps the old files, a directory in the way fails before "
           "any rename (old files kept), a commit replaces all three; 0 temporaries left\n");
    free(s);
}

/* A writer handed a set member's temporary writes it directly (no "<tmp>.tmp.<pid>" beside it)
 * and names the member's output in its messages; the set's commit then moves it into place. */
static void test_outset_member_written_directly(void **state)
{
    lt_outset_t *s = calloc(1, sizeof *s);
    static const uint8_t px[3 * 4] = {0};
    char a[300], tnest[LT_TMP_PATH_MAX];
    const char *ta;
    lt_diag_t d;
    (void)state;
    assert_non_null(s);
    snprintf(a, sizeof a, "%s/member.png", g_dir);
    assert_int_equal(lt_outset_add(s, a, &ta, &d), 0);
    assert_string_equal(lt_tmp_target(ta), a);
    assert_string_equal(lt_tmp_target(a), a); /* not a temporary: itself */
    assert_int_equal(lt_tmp_begin(ta, tnest, &d), 0);
    assert_string_equal(tnest, ta);
    assert_int_equal(lt_png_write(ta, px, 2, 2, 3, 0, &d), 0);
    assert_int_equal(count_tmp(), 1); /* the member's temporary only */
    /* an invalid image: the message names the output, not its temporary */
    assert_int_equal(lt_png_write(ta, px, 0, 2, 3, 0, &d), -1);
    assert_true(strncmp(d.msg, a, strlen(a)) == 0 && d.msg[strlen(a)] == ':');
    assert_int_equal(lt_outset_commit(s, &d), 0);
    assert_int_equal(count_tmp(), 0);
    assert_int_equal(access(a, F_OK), 0);
    unlink(a);
    printf("tmpfiles: a set member's temporary is written directly (1 temporary, not 2) and "
           "messages name the output\n");
    free(s);
}

/* lt_tmp_commit over a symbolic link (to a file here, and to a FIFO with a reader): the link
 * stays a link, its target gets the bytes, the temporary is in $TMPDIR and removed; over a
 * regular file it is renamed into place. */
static void test_commit_through_links(void **state)
{
    char f[300], l[300], fifo[300], lf[300], tmp[LT_TMP_PATH_MAX], got[64];
    struct stat st;
    lt_diag_t d;
    pid_t pid;
    int status;
    (void)state;
    snprintf(f, sizeof f, "%s/target.txt", g_dir);
    snprintf(l, sizeof l, "%s/link.txt", g_dir);
    snprintf(fifo, sizeof fifo, "%s/pipe", g_dir);
    snprintf(lf, sizeof lf, "%s/link-to-pipe", g_dir);
    write_text(f, "old");
    assert_int_equal(symlink("target.txt", l), 0);
    assert_int_equal(lt_tmp_begin(l, tmp, &d), 0);
    assert_null(strstr(tmp, g_dir)); /* not beside the link */
    write_text(tmp, "through the link");
    assert_int_equal(lt_tmp_commit(tmp, l, &d), 0);
    assert_int_equal(lstat(l, &st), 0);
    assert_true(S_ISLNK(st.st_mode));
    assert_true(same_text(f, "through the link"));
    assert_int_not_equal(access(tmp, F_OK), 0);
    /* a FIFO behind a link, read by a child */
    assert_int_equal(mkfifo(fifo, 0600), 0);
    assert_int_equal(symlink("pipe", lf), 0);
    pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        FILE *in = fopen(fifo, "r");
        size_t n = in != NULL ? fread(got, 1, sizeof got - 1, in) : 0;
        got[n] = '\0';
        _exit(in != NULL && strcmp(got, "into the fifo") == 0 ? 0 : 1);
    }
    assert_int_equal(lt_tmp_begin(lf, tmp, &d), 0);
    write_text(tmp, "into the fifo");
    assert_int_equal(lt_tmp_commit(tmp, lf, &d), 0);
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_true(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    assert_int_equal(lstat(fifo, &st), 0);
    assert_true(S_ISFIFO(st.st_mode));
    assert_int_not_equal(access(tmp, F_OK), 0);
    /* a regular file: renamed into place */
    assert_int_equal(lt_tmp_begin(f, tmp, &d), 0);
    assert_non_null(strstr(tmp, g_dir));
    write_text(tmp, "renamed");
    assert_int_equal(lt_tmp_commit(tmp, f, &d), 0);
    assert_true(same_text(f, "renamed"));
    assert_int_equal(lstat(l, &st), 0);
    assert_true(S_ISLNK(st.st_mode));
    assert_int_equal(count_tmp(), 0);
    unlink(l);
    unlink(lf);
    unlink(fifo);
    unlink(f);
    printf("tmpfiles: commit through a link to a file and a link to a FIFO (read by a child): "
           "links and FIFO kept, bytes delivered, temporaries in $TMPDIR removed; a regular file "
           "renamed into place\n");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_registered_removed_on_signals),
        cmocka_unit_test(test_writers_killed_midway),
        cmocka_unit_test(test_long_names_refused),
        cmocka_unit_test(test_outset_all_or_nothing),
        cmocka_unit_test(test_outset_member_written_directly),
        cmocka_unit_test(test_commit_through_links),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
