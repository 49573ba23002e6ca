/* fuzz_util.c - see fuzz_util.h. */
#include "fuzz_util.h"

#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define FUZZ_FILES 4

static char made[FUZZ_FILES][512];
static int nmade;

static void remove_files(void)
{
    int i;
    for (i = 0; i < nmade; i++)
        (void)unlink(made[i]);
}

static const char *tmp_dir(void)
{
    struct stat st;
    const char *t = getenv("TMPDIR");
    if (stat("/dev/shm", &st) == 0 && S_ISDIR(st.st_mode) && access("/dev/shm", W_OK) == 0)
        return "/dev/shm";
    return t != NULL && t[0] != '\0' ? t : "/tmp";
}

const char *fuzz_file(const uint8_t *data, size_t size, const char *suffix)
{
    char path[512];
    size_t off = 0;
    int i, fd;
    (void)snprintf(path, sizeof path, "%s/lt-fuzz-%ld-%s", tmp_dir(), (long)getpid(), suffix);
    for (i = 0; i < nmade && strcmp(made[i], path) != 0; i++)
        ;
    if (i == nmade) {
        if (nmade == FUZZ_FILES)
            abort();
        (void)snprintf(made[nmade++], sizeof made[0], "%s", path);
        if (nmade == 1)
            (void)atexit(remove_files);
    }
    fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (fd < 0)
        abort();
    while (off < size) {
        ssize_t w = write(fd, data + off, size - off);
        if (w <= 0)
            abort();
        off += (size_t)w;
    }
    if (close(fd) != 0)
        abort();
    return made[i];
}

void fuzz_check_message(const char *err, size_t cap)
{
    const char *nul = (const char *)memchr(err, '\0', cap);
    if (nul == NULL || nul == err || memchr(err, '\n', (size_t)(nul - err)) != NULL)
        abort();
}

void fuzz_take_message(char *err, size_t cap, int rc, const lt_diag_t *d)
{
    if (rc != 0 && cap > 0)
        (void)snprintf(err, cap, "%s", d->msg);
}
