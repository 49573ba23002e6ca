/* reproj_blob_host.c - the host runner of the reprojection app (firmware/apps/reproj_app.h):
 * reads a blob file into 64-byte aligned memory and runs the app over it with exactly the memory
 * lt_rpapp_mem_bytes asks for (or --mem BYTES), so its lines can be compared with the firmware
 * images' (tests/run.d/reproj_blob.sh). It traces packets (lt_qt_trace16_q30), or single rays
 * with --single (lt_qt_trace1_q30, the images' default walk). The memory is poisoned with 0xA5 and followed by a 64-byte
 * guard that must stay untouched. Exit status: the app's (0 ok, LT_RPAPP_E_* otherwise), 1 when
 * the file cannot be read, 2 usage, 3 when the guard was written. Builds: host, asan.
 */
#include "reproj_app.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define GUARD 64u

static void host_puts(void *ctx, const char *s)
{
    (void)ctx;
    fputs(s, stdout);
}

int main(int argc, char **argv)
{
    lt_rpapp_port_t port;
    void *blob = NULL, *mem = NULL;
    size_t len = 0, need = 0, give = 0, i;
    long sz;
    FILE *f;
    int rc, have_mem = 0, single = 0;
    if (argc >= 3 && strcmp(argv[argc - 1], "--single") == 0) {
        single = 1;
        argc--;
    }
    if (argc == 4 && strcmp(argv[2], "--mem") == 0) {
        give = (size_t)strtoul(argv[3], NULL, 10);
        have_mem = 1;
    } else if (argc != 2) {
        fprintf(stderr, "usage: %s BLOB [--mem BYTES] [--single]\n", argv[0]);
        return 2;
    }
    f = fopen(argv[1], "rb");
    if (f == NULL || fseek(f, 0, SEEK_END) != 0 || (sz = ftell(f)) < 0 ||
        fseek(f, 0, SEEK_SET) != 0) {
        fprintf(stderr, "%s: cannot read\n", argv[1]);
        if (f != NULL)
            fclose(f);
        return 1;
    }
    len = (size_t)sz;
    if (posix_memalign(&blob, 64, len > 0 ? len : 1) != 0 || fread(blob, 1, len, f) != len) {
        fprintf(stderr, "%s: cannot read %zu bytes\n", argv[1], len);
        fclose(f);
        free(blob);
        return 1;
    }
    fclose(f);
    /* a blob the app refuses still goes through lt_rpapp_run, which prints the error line */
    (void)lt_rpapp_mem_bytes(blob, len, &need);
    if (!have_mem)
        give = need;
    if (posix_memalign(&mem, 64, give + GUARD) != 0) {
        fprintf(stderr, "out of memory for %zu bytes\n", give);
        free(blob);
        return 1;
    }
    memset(mem, 0xA5, give + GUARD);
    port.puts = host_puts;
    port.ticks = NULL;
    port.ctx = NULL;
    port.name = "host";
    port.single = single;
    rc = lt_rpapp_run(&port, blob, len, mem, give);
    for (i = 0; i < GUARD; i++)
        if (((const unsigned char *)mem)[give + i] != 0xA5u) {
            fprintf(stderr, "the app wrote past the %zu bytes it was given (byte %zu)\n", give, i);
            rc = 3;
            break;
        }
    free(mem);
    free(blob);
    return rc;
}
