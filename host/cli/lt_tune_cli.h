/* lt_tune_cli.h - the `lanetrace tune` subcommand (docs/tune.md): options, the search
 * (host/tune/lt_tune.h), the summary, the budget's pick and its verification, the outputs, and
 * the distributed mode (--plan, --job, --merge). Dispatched from lanetrace_main.c. Host only.
 */
#ifndef LT_TUNE_CLI_H
#define LT_TUNE_CLI_H

#ifdef __cplusplus
extern "C" {
#endif

/* argv[1] == "tune"; prog names the program in messages. Returns the exit code: 0 ok, 1 input or
 * runtime error or an impossible budget, 2 usage (a bad budget included). */
int lt_tune_cli(int argc, char **argv, const char *prog);

#ifdef __cplusplus
}
#endif
#endif /* LT_TUNE_CLI_H */
