/* lt_shadows_cli.h - the `lanetrace shadows` subcommand: soft shadows of a quad area light by
 * multi-frusta and by 16-ray packets (Benthin & Wald), the Table-1-style report, images and the
 * 256-sample reference (docs/frusta.md). Dispatched from lanetrace_main.c. Host only.
 */
#ifndef LT_SHADOWS_CLI_H
#define LT_SHADOWS_CLI_H

#ifdef __cplusplus
extern "C" {
#endif

/* argv[1] == "shadows"; prog names the program in messages. Returns the exit code: 0 ok, 1 input
   or runtime error (including frusta != packet visibility), 2 usage. */
int lt_shadows_cli(int argc, char **argv, const char *prog);

#ifdef __cplusplus
}
#endif
#endif /* LT_SHADOWS_CLI_H */
