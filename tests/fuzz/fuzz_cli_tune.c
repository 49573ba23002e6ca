/* fuzz_cli_tune.c - `lanetrace tune` for the cli fuzz target (fuzz_cli.h): lt_tune_cli.c itself,
 * then its options and the settle steps of families, machines and budget (not settle_input,
 * which reads the input). Host only.
 */
#include "cli/lt_tune_cli.c"
#include "fuzz_cli.h" /* after the command source: its feature-test macros come first */

int fuzz_cli_tune(int argc, char **argv)
{
    static tune_t t; /* large: off the stack */
    int rc, i;
    tune_defaults(&t);
    rc = tune_parse(&t, argc, argv, "lanetrace");
    if (rc != LT_OPT_OK)
        return rc == LT_OPT_HELP ? 0 : EXIT_USAGE;
    if (t.merge)
        return 0; /* the folders are read by tune_merge */
    if ((rc = settle_family(&t)) != 0 || (rc = settle_machines(&t)) != 0 ||
        (rc = settle_budget(&t)) != 0)
        return rc;
    if (t.o.families == 0 || (t.o.families & ~(unsigned)LT_TUNE_ALL) != 0 || t.o.nmach < 1 ||
        t.o.nmach > MAX_MACH) {
        fprintf(stderr, "fuzz_cli: tune settled on families 0x%x and %d machines\n",
                t.o.families, t.o.nmach);
        abort();
    }
    for (i = 0; i < t.o.nmach; i++)
        if (t.o.machines[i] < 0 || lt_meter_machine_name(t.o.machines[i]) == NULL) {
            fprintf(stderr, "fuzz_cli: tune settled on machine index %d\n", t.o.machines[i]);
            abort();
        }
    return 0;
}
