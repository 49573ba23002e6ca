/* fuzz_meshcheck.c - fuzz target of the PLY/OFF/STL structural checks (host/io/lt_meshcheck.c)
 * that run before assimp sees those formats: every input is checked as PLY, as OFF and as STL
 * (ascii and binary are told apart inside), and the format is guessed from its first bytes as
 * lt_import does. Each check must accept or give a one-line message, in time and memory bounded by
 * the input, never a crash or a read outside the buffer (the bytes are not NUL-terminated).
 * make fuzz-meshcheck; replayed over tests/fuzz/corpus/meshcheck in make test. Host only.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_util.h"
#include "io/lt_meshcheck.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* The checker's call, in one place (its error convention may change). */
static int check(lt_meshcheck_kind_t kind, const uint8_t *data, size_t size, char *err,
                 size_t cap)
{
    lt_diag_t dg;
    int r = lt_meshcheck(kind, "fuzz.mesh", data, size, &dg);
    fuzz_take_message(err, cap, r, &dg);
    return r;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const lt_meshcheck_kind_t kinds[3] = {LT_MESHCHECK_PLY, LT_MESHCHECK_OFF,
                                                 LT_MESHCHECK_STL};
    char err[512];
    int k;
    lt_meshcheck_kind_t guess = lt_meshcheck_kind("", data, size);
    if (guess != LT_MESHCHECK_NONE && guess != LT_MESHCHECK_PLY)
        abort(); /* only PLY is recognised by content */
    for (k = 0; k < 3; k++) {
        memset(err, 'x', sizeof err);
        if (check(kinds[k], data, size, err, sizeof err) != 0)
            fuzz_check_message(err, sizeof err);
        if (lt_meshcheck_hint(kinds[k])[0] == '\0')
            abort();
    }
    return 0;
}
