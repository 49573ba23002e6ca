/* fuzz_scene.c - fuzz target of the scene-file parser (host/io/lt_scenefile.c): any bytes must give
 * either a valid scene or a one-line error message, never a crash, a hang or an unterminated
 * message.
 * Built with libFuzzer by `make fuzz-scene` when clang has it, and replayed over
 * tests/fuzz/corpus/scene/ by tests/fuzz/fuzz_main.c in `make test`. Host only.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "fuzz_util.h"
#include "io/lt_scenefile.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    lt_diag_t diag;
    lt_scenefile_t sf;
    int r;
    if (text == NULL)
        return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    memset(diag.msg, 'x', sizeof diag.msg); /* no NUL: the parser must write one */
    /* relative paths resolve against a folder that does not exist: file checks fail cleanly */
    r = lt_sf_parse(text, "fuzz.json", "/nonexistent-fuzz-dir", &sf, &diag);
    if (r != 0) {
        fuzz_check_message(diag.msg, sizeof diag.msg); /* terminated, non-empty, one line */
        if (strncmp(diag.msg, "fuzz.json: ", 11) != 0)
            abort(); /* it names the file */
    }
    if (r == 0 && (sf.width < 1 || sf.height < 1 || sf.width > LT_SF_MAX_RES ||
                   sf.height > LT_SF_MAX_RES || sf.nlights > LT_SF_MAX_LIGHTS))
        abort(); /* an accepted scene is within its documented limits */
    free(text);
    return 0;
}
