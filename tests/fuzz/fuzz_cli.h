/* fuzz_cli.h - the argument handling of the lanetrace subcommands, as the cli fuzz target
 * (fuzz_cli.c) reaches it: each fuzz_cli_<command>.c includes the command's own source (so its
 * static parse and settle functions are the ones called here, not copies) and runs, on argv,
 * what the command does with its arguments before it opens any file: the defaults, the option
 * table (lt_opt_parse with the command's callbacks), the checks between options, and the steps
 * that settle the flags into the run (machine names and cache geometry, families, budgets). A
 * scene file named on the command line is not read (the scene fuzz target reads scene files).
 * Each returns 0 (the arguments were accepted), 1 or 2 (the command's exit codes for an input
 * or usage error, after its one message) and aborts when an accepted run breaks a documented
 * range. Host only.
 */
#ifndef FUZZ_CLI_H
#define FUZZ_CLI_H

#include <stdint.h>

/* w x h within 1..max per side (an accepted --res). */
static inline int fuzz_cli_size_ok(uint32_t w, uint32_t h, uint32_t max)
{
    return w >= 1 && w <= max && h >= 1 && h <= max;
}

int fuzz_cli_run(int argc, char **argv);
int fuzz_cli_render(int argc, char **argv);
int fuzz_cli_reproject(int argc, char **argv);
int fuzz_cli_shadows(int argc, char **argv);
int fuzz_cli_tune(int argc, char **argv);
int fuzz_cli_pack(int argc, char **argv);

#endif /* FUZZ_CLI_H */
