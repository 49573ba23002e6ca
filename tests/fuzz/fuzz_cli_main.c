/* fuzz_cli_main.c - `lanetrace run` and `lanetrace render` for the cli fuzz target (fuzz_cli.h):
 * lanetrace_main.c itself, its main renamed, and the two commands' argument handling. Host only.
 */
int fuzz_cli_lanetrace_main(int argc, char **argv);
#define main fuzz_cli_lanetrace_main
#include "cli/lanetrace_main.c"
#undef main

#include "fuzz_cli.h" /* after the command source: its feature-test macros come first */

/* A broken promise of an accepted command line: say which, then abort (the fuzzer's crash). */
static void cli_broken(const char *cmd, const char *what)
{
    fprintf(stderr, "fuzz_cli: %s accepted its arguments but %s\n", cmd, what);
    abort();
}

int fuzz_cli_run(int argc, char **argv)
{
    run_t r;
    int rc;
    run_defaults(&r);
    rc = run_parse(&r, argc, argv);
    quiet = 0;
    if (rc != LT_OPT_OK)
        return rc == LT_OPT_HELP ? 0 : EXIT_USAGE;
    if (r.repeat < 1 || r.repeat > 100000)
        cli_broken("run", "--repeat is outside 1..100000");
    r.scene_path = NULL; /* not read here */
    rc = run_settle(&r);
    if (rc == 0) {
        const lt_scenefile_t *sf = &r.sf;
        if (!fuzz_cli_size_ok(sf->width, sf->height, LT_SF_MAX_RES))
            cli_broken("run", "the image size is outside 1..LT_SF_MAX_RES");
        if (!lt_meter_machine_known(sf->machine) || sf->mesh[0] == '\0')
            cli_broken("run", "the machine is unknown or the mesh empty");
        if (run_npaths(sf) < 1)
            cli_broken("run", "no numeric path is selected");
    }
    lt_meter_shutdown();
    return rc;
}

int fuzz_cli_render(int argc, char **argv)
{
    static render_t r; /* 100 KB: off the stack */
    int rc;
    render_defaults(&r);
    rc = render_parse(&r, argc, argv);
    quiet = 0;
    if (rc != LT_OPT_OK)
        return rc == LT_OPT_HELP ? 0 : EXIT_USAGE;
    if (r.out == NULL || r.layers < 1 || r.layers > 16 || r.path == NULL ||
        (r.seen_res && !fuzz_cli_size_ok(r.wh[0], r.wh[1], LT_SF_MAX_RES)))
        cli_broken("render", "--out is missing, or --layers, --num or --res out of range");
    if (r.seen_light && !(isfinite(r.lf[0]) && isfinite(r.lf[1]) && isfinite(r.lf[2])))
        cli_broken("render", "--light is not finite");
    return 0;
}
