/* lt_pack_cli.h - the `lanetrace pack` subcommand: a scene blob for a firmware target and its
 * trace on the host (firmware/apps/lt_sblob.h, docs/firmware.md). Dispatched from
 * lanetrace_main.c. Host only.
 */
#ifndef LT_PACK_CLI_H
#define LT_PACK_CLI_H

#ifdef __cplusplus
extern "C" {
#endif

/* argv[1] == "pack"; prog names the program in messages. Returns the exit code: 0 ok, 1 input or
   runtime error, 2 usage. */
int lt_pack_cli(int argc, char **argv, const char *prog);

#ifdef __cplusplus
}
#endif
#endif /* LT_PACK_CLI_H */
