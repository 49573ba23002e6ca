/* fuzz_cli_pack.c - `lanetrace pack` for the cli fuzz target (fuzz_cli.h): lt_pack_cli.c itself,
 * then its options. Host only.
 */
#include "cli/lt_pack_cli.c"
#include "fuzz_cli.h" /* after the command source: its feature-test macros come first */

int fuzz_cli_pack(int argc, char **argv)
{
    pack_t p;
    int rc;
    pack_defaults(&p);
    rc = pack_parse(&p, argc, argv, "lanetrace");
    if (rc != LT_OPT_OK)
        return rc == LT_OPT_HELP ? 0 : EXIT_USAGE;
    if ((p.out == NULL) == (p.in == NULL) || p.leaf < 1 || p.leaf > LT_BVH_MAX_LEAF ||
        (p.seen_res && !fuzz_cli_size_ok(p.wh[0], p.wh[1], LT_SBLOB_MAX_RES))) {
        fprintf(stderr, "fuzz_cli: pack accepted both or neither of --in and --out, or a bad "
                        "--leaf or --res\n");
        abort();
    }
    return 0;
}
