/* lt_reproject_cli.h - the `lanetrace reproject` subcommand (view synthesis from a depth EXR,
 * docs/reproject.md): option parsing, EXR input (depth layers, colour), cameras from flags or a
 * scene file, lt_rp_run, outputs (EXR, PNG, heatmaps, cycle report text/JSON). Kept out of
 * lanetrace_main.c, which dispatches to it and lends its progress bar. Host only.
 */
#ifndef LT_REPROJECT_CLI_H
#define LT_REPROJECT_CLI_H

#include <stdio.h>

#include "io/lt_diag.h"
#include "render/lt_scene.h"
#include "lt/lt_reproj.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The CLI's progress bar (lanetrace_main.c) and its quiet flag. */
typedef struct lt_rp_cli_hooks {
    void (*begin)(const char *label);
    void (*progress)(double done);
    void (*end)(void);
    int *quiet;
    /* write text to path atomically (temporary name, rename; removed on a signal); 0 or -1 with
       a message naming the path */
    int (*write_text)(const char *path, const char *text, lt_diag_t *diag);
} lt_rp_cli_hooks_t;

/* argv[1] == "reproject". Returns the exit code: 0 ok, 1 input or runtime error, 2 usage. */
int lt_rp_cli(int argc, char **argv, const char *prog, const lt_rp_cli_hooks_t *hooks);

/* lanetrace render's camera (eye, fwd, right, up, fov_y over the image height) as the
 * reprojection's pinhole: rows right, -up, fwd; fx = fy = H / (2 tan(fov_y / 2)), centred. */
void lt_rp_cam_from_camera(const lt_camera_t *cam, uint32_t w, uint32_t h, lt_reproj_cam_t *c);

/* Ground truth of a target camera d: the mesh scene rendered by the object-space tracer (float32
 * BVH packets) as z-depths along d's optical axis into ztrue (d->width x d->height), +inf on a
 * miss. d must be centred with square pixels. Returns 0, or -1 with a message. (Also used by
 * lanetrace tune.) */
int lt_rp_render_truth(const lt_scene_t *sc, const lt_reproj_cam_t *d, float *ztrue,
                       lt_diag_t *diag);

/* The --help text. */
void lt_rp_cli_usage(const char *prog, FILE *f);

#ifdef __cplusplus
}
#endif
#endif /* LT_REPROJECT_CLI_H */
