/* fuzz_cli_shadows.c - `lanetrace shadows` for the cli fuzz target (fuzz_cli.h): lt_shadows_cli.c
 * itself, then its options and shadows_scene without reading a file. Host only.
 */
#include "cli/lt_shadows_cli.c"
#include "fuzz_cli.h" /* after the command source: its feature-test macros come first */

int fuzz_cli_shadows(int argc, char **argv)
{
    static shadows_t s; /* large: off the stack */
    int rc;
    shadows_defaults(&s, "lanetrace");
    rc = shadows_parse(&s, argc, argv);
    if (rc != LT_OPT_OK)
        return rc == LT_OPT_HELP ? 0 : EXIT_USAGE;
    s.scene_path = NULL; /* not read here */
    rc = shadows_scene(&s);
    if (rc == 0 && (s.mesh_path == NULL || s.machine == NULL ||
                    lt_ss_spp_log2((uint32_t)s.spp) < 0 ||
                    lt_paths_find(s.num_names[s.num], LT_PATHS_FRUSTA) == NULL ||
                    (s.seen_light && !(isfinite(s.light_c[0]) && isfinite(s.light_c[1]) &&
                                       isfinite(s.light_c[2]) && s.light_c[3] >= 0.0)))) {
        fprintf(stderr, "fuzz_cli: shadows accepted a run without a mesh or with a bad --spp, "
                        "--num or --light\n");
        abort();
    }
    return rc;
}
