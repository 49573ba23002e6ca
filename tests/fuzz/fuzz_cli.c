/* fuzz_cli.c - fuzz target of the lanetrace subcommands' argument handling past the option
 * parser (fuzz_opt.c fuzzes lt_opt.c alone): the first byte of the input picks a command (run,
 * render, reproject, shadows, tune, pack), the rest, split at NUL and newline bytes, is its
 * arguments after "lanetrace COMMAND". Each command's own defaults, option table, callbacks
 * (--cull, --light, --src-cam, --machine ...), checks between options and settle steps run
 * (fuzz_cli.h: no file is read); the result must be 0, 1 or 2, an accepted command line must
 * keep its documented ranges, and nothing may leak. make fuzz-cli; replayed over
 * tests/fuzz/corpus/cli in make test. Host only.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_cli.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define MAX_ARGS 32

typedef int (*cli_fn)(int argc, char **argv);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const char *const names[] = {"run", "render", "reproject", "shadows", "tune", "pack"};
    static const cli_fn fns[] = {fuzz_cli_run,     fuzz_cli_render, fuzz_cli_reproject,
                                 fuzz_cli_shadows, fuzz_cli_tune,   fuzz_cli_pack};
    char *copy, *argv[MAX_ARGS + 3];
    size_t i, start = 0;
    int argc = 2, which, rc;

    if (size == 0)
        return 0;
    which = data[0] % 6;
    data++;
    size--;
    copy = malloc(size + 1);
    if (copy == NULL)
        return 0;
    memcpy(copy, data, size);
    copy[size] = '\0';
    argv[0] = (char *)"lanetrace";
    argv[1] = (char *)names[which];
    for (i = 0; i < size && argc < MAX_ARGS + 2; i++)
        if (copy[i] == '\0' || copy[i] == '\n') {
            copy[i] = '\0';
            argv[argc++] = copy + start;
            start = i + 1;
        }
    if (start < size && argc < MAX_ARGS + 2)
        argv[argc++] = copy + start;
    argv[argc] = NULL;
    rc = fns[which](argc, argv);
    if (rc < 0 || rc > 2) {
        fprintf(stderr, "fuzz_cli: %s returned %d (not 0, 1 or 2)\n", names[which], rc);
        abort();
    }
    free(copy);
    return 0;
}
