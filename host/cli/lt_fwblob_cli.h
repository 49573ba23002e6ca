/* lt_fwblob_cli.h - the `lanetrace fwblob` subcommand: a crop of a real depth EXR, two layers, the
 * s1.30 mapping to a moved camera, written as the position-independent blob that the reprojection
 * app (firmware/apps/reproj_app.h) reads on the firmware targets and on the host
 * (docs/firmware.md, "Reprojection of a real depth image"). Dispatched from lanetrace_main.c.
 * Host only.
 */
#ifndef LT_FWBLOB_CLI_H
#define LT_FWBLOB_CLI_H

#ifdef __cplusplus
extern "C" {
#endif

/* argv[1] == "fwblob"; prog names the program in messages. Returns the exit code: 0 ok, 1 input
   or output error, 2 usage. */
int lt_fwblob_cli(int argc, char **argv, const char *prog);

#ifdef __cplusplus
}
#endif
#endif /* LT_FWBLOB_CLI_H */
