/* fuzz_main.c - replay driver for the fuzz targets (stb's pattern): runs LLVMFuzzerTestOneInput on
 * every file named on the command line, or in a directory named there, so that the corpora are
 * exercised by `make test` without libFuzzer. Each input is copied into a buffer of exactly its
 * size, so ASan catches a read past its end. Prints one line: inputs and bytes replayed.
 * Exit: 0 ok (a failing input aborts), 1 unreadable input, 2 usage. Builds: host, asan.
 */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static unsigned long inputs, bytes;

static int run_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    uint8_t *buf;
    long n;
    if (f == NULL || fseek(f, 0, SEEK_END) != 0 || (n = ftell(f)) < 0 ||
        fseek(f, 0, SEEK_SET) != 0) {
        fprintf(stderr, "fuzz replay: %s: cannot read\n", path);
        if (f != NULL)
            fclose(f);
        return -1;
    }
    buf = malloc(n > 0 ? (size_t)n : 1u);
    if (buf == NULL || fread(buf, 1, (size_t)n, f) != (size_t)n) {
        fprintf(stderr, "fuzz replay: %s: cannot read %ld bytes\n", path, n);
        free(buf);
        fclose(f);
        return -1;
    }
    fclose(f);
    LLVMFuzzerTestOneInput(buf, (size_t)n);
    free(buf);
    inputs++;
    bytes += (unsigned long)n;
    return 0;
}

static int run_path(const char *path)
{
    struct stat sb;
    DIR *d;
    struct dirent *e;
    int rc = 0;
    if (stat(path, &sb) != 0) {
        fprintf(stderr, "fuzz replay: %s: no such file or directory\n", path);
        return -1;
    }
    if (!S_ISDIR(sb.st_mode))
        return run_file(path);
    d = opendir(path);
    if (d == NULL) {
        fprintf(stderr, "fuzz replay: %s: cannot list\n", path);
        return -1;
    }
    while ((e = readdir(d)) != NULL) {
        char p[4096];
        if (e->d_name[0] == '.')
            continue;
        snprintf(p, sizeof p, "%s/%s", path, e->d_name);
        if (run_path(p) != 0)
            rc = -1;
    }
    closedir(d);
    return rc;
}

int main(int argc, char **argv)
{
    int i, rc = 0;
    if (argc < 2) {
        fprintf(stderr, "usage: %s FILE|DIR...  (replays each input through the fuzz target)\n",
                argv[0]);
        return 2;
    }
    for (i = 1; i < argc; i++)
        if (run_path(argv[i]) != 0)
            rc = 1;
    printf("fuzz replay %s: %lu inputs, %lu bytes, no failure\n", argv[0], inputs, bytes);
    return rc;
}
