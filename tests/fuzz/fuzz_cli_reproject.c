/* fuzz_cli_reproject.c - `lanetrace reproject` for the cli fuzz target (fuzz_cli.h):
 * lt_reproject_cli.c itself, then its options and rp_settle without reading a file. Host only.
 */
#include "cli/lt_reproject_cli.c"
#include "fuzz_cli.h" /* after the command source: its feature-test macros come first */

int fuzz_cli_reproject(int argc, char **argv)
{
    static rp_t r; /* large: off the stack */
    int rc, quiet = 0;
    rp_defaults(&r);
    rc = rp_options(&r, &quiet, "lanetrace", argc, argv, NULL);
    if (rc != LT_OPT_OK)
        return rc == LT_OPT_HELP ? 0 : EXIT_USAGE;
    r.path = lt_paths_find(r.enc_names[r.enc], LT_PATHS_SCREEN);
    if (r.path == NULL) {
        fprintf(stderr, "fuzz_cli: reproject accepted --num %d, which names no screen path\n", r.enc);
        abort();
    }
    r.scene_path = NULL; /* not read here */
    rc = rp_settle(&r, "lanetrace");
    if (rc == 0 && (r.depth == NULL || !lt_meter_machine_known(r.machine))) {
        fprintf(stderr, "fuzz_cli: reproject settled without a depth image or a known machine\n");
        abort();
    }
    rp_free(&r);
    return rc;
}
