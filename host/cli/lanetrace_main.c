/* lanetrace_main.c - the lanetrace command line: subcommands run, render, reproject, info, diff,
 * machines, stream (docs/user-guide.md).
 * Built twice from this source: build/sim/lanetrace (the kernels charged to a machine model: cycle
 * reports) and build/host/lanetrace-native (LT_COST_OFF: native speed); `lanetrace run --native`
 * hands over to the native build. Exit codes: 0 ok, 1 input or runtime error, 2 usage. Host only.
 */
#include "lt/lt.h"
#include "cli/lt_cliutil.h"
#include "io/lt_exr.h"
#include "io/lt_heatmap.h"
#include "io/lt_mesh.h"
#include "lt_meter.h"
#include "io/lt_png.h"
#include "render/lt_render.h"
#include "cli/lt_reproject_cli.h"
#include "cli/lt_shadows_cli.h"
#include "render/lt_scene.h"
#include "io/lt_scenefile.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define EXIT_INPUT 1
#define EXIT_USAGE 2

static int quiet;
static const char *prog = "lanetrace";

/* ---- progress bar (stderr, only on a TTY, only after the first second) ------------------------ */

static double t_start;

static const char *progress_label = "";
static int progress_shown;

static void progress(double done)
{
    double el = lt_now_s() - t_start;
    int i, w = 30, fill;
    if (quiet || !isatty(2) || el < 1.0)
        return;
    if (done > 1.0)
        done = 1.0;
    fill = (int)(done * w);
    fprintf(stderr, "\r%-10s [", progress_label);
    for (i = 0; i < w; i++)
        fputc(i < fill ? '#' : ' ', stderr);
    fprintf(stderr, "] %3.0f%% ETA %.1fs ", 100.0 * done, done > 0 ? el * (1.0 - done) / done : 0.0);
    progress_shown = 1;
}

static void progress_begin(const char *label)
{
    progress_label = label;
    t_start = lt_now_s();
    progress_shown = 0;
}

static void progress_end(void)
{
    if (progress_shown)
        fprintf(stderr, "\r%60s\r", "");
    progress_shown = 0;
}

/* ---- atomic outputs: a temporary name renamed into place; Ctrl-C removes the temporary ---------- */

static char pending_tmp[1100]; /* the atomic write in progress */
static char csv_tmp[1100];     /* the CSV being written row by row */

static void on_signal(int sig)
{
    if (pending_tmp[0] != '\0')
        unlink(pending_tmp);
    if (csv_tmp[0] != '\0')
        unlink(csv_tmp);
    signal(sig, SIG_DFL);
    raise(sig);
}

static int write_atomic(const char *path, const char *text, lt_diag_t *diag)
{
    FILE *f;
    snprintf(pending_tmp, sizeof pending_tmp, "%s.tmp%ld", path, (long)getpid());
    f = fopen(pending_tmp, "w");
    if (f == NULL) {
        lt_diag_fail(diag, "%s: cannot create the output (directory missing or not writable)",
                     path);
        pending_tmp[0] = '\0';
        return -1;
    }
    if (fputs(text, f) < 0 || fclose(f) != 0) {
        lt_diag_fail(diag, "%s: write failed (disk full?)", path);
        unlink(pending_tmp);
        pending_tmp[0] = '\0';
        return -1;
    }
    if (rename(pending_tmp, path) != 0) {
        lt_diag_fail(diag, "%s: cannot rename the output into place", path);
        unlink(pending_tmp);
        pending_tmp[0] = '\0';
        return -1;
    }
    pending_tmp[0] = '\0';
    return 0;
}

/* ---- run ------------------------------------------------------------------------------------ */

static void run_usage(FILE *f)
{
    fprintf(f,
            "usage: %s run [SCENE.json] [options]\n"
            "Trace primary rays of a scene in s15.16 and/or float32, print accuracy against a\n"
            "double-precision reference and (simulator build) the cycle report.\n"
            "  --mesh PATH        mesh file (overrides the scene's \"mesh\"; default scenes/teapot.obj)\n"
            "  --res WxH|N        image size (1..%d per side)\n"
            "  --num q16|f32|both numeric path\n"
            "  --structure NAME   acceleration structure (chunks)\n"
            "  --machine NAME     machine model: %s (lanetrace machines)\n"
            "  --l1 S:W:B --l2 S:W:B  cache geometry overrides (sets:ways:line)\n"
            "  --report PATH      write the report JSON (PATH.q16 / PATH.f32 with both paths)\n"
            "  --csv PATH         write one CSV row per path\n"
            "  --depth PATH.exr   write distance and triangle id per pixel (EXR, FLOAT channels\n"
            "                     <path>.Z and <path>.id)\n"
            "  --heatmap PREFIX   (sim build) per-pixel simulated cycles: PREFIX.<path>.png with a\n"
            "                     legend and PREFIX.<path>.exr with the values; traversal steps:\n"
            "                     PREFIX.<path>.steps.png / .steps.exr\n"
            "  --repeat N         trace the frame N times (timing)\n"
            "  --no-ref           skip the reference and the accuracy figures\n"
            "  --native           run the native build (no cycle model; wall-clock speed)\n"
            "  --json             machine-readable JSON on stdout\n"
            "  -q                 quiet: summary lines only\n",
            prog, LT_SF_MAX_RES, lt_meter_machine_names());
}

/* The simulator build's kernels charge every op (LT_COST_SIM is a compile-time mode): native
 * speed is the other binary, build/host/lanetrace-native, which this hands over to. */
static int exec_native(int argc, char **argv)
{
    char path[1200];
    const char *slash = strrchr(argv[0], '/');
    char **nargv = calloc((size_t)argc + 2, sizeof *nargv);
    int i, n = 0;
    if (nargv == NULL)
        return EXIT_INPUT;
    if (slash != NULL)
        snprintf(path, sizeof path, "%.*s/../host/lanetrace-native", (int)(slash - argv[0]), argv[0]);
    else
        snprintf(path, sizeof path, "lanetrace-native");
    nargv[n++] = path;
    for (i = 1; i < argc; i++)
        if (strcmp(argv[i], "--native") != 0)
            nargv[n++] = argv[i];
    nargv[n] = NULL;
    execv(path, nargv);
    fprintf(stderr, "%s: --native: cannot run %s (build it with `make all`)\n", prog, path);
    free(nargv);
    return EXIT_INPUT;
}

static int cmd_run(int argc, char **argv)
{
    lt_scenefile_t sf;
    lt_mesh_t mesh;
    lt_scene_t sc;
    lt_camera_t cam;
    lt_frame_t ref, fr;
    lt_diag_t diag;
    int a, json = 0, repeat = 1, do_ref = 1, status = 0, path;
    const char *scene_path = NULL, *mesh_over = NULL, *report = NULL, *csv = NULL;
    const char *depth_out = NULL, *heat_out = NULL;
    float *zbuf[2] = {NULL, NULL}, *idbuf[2] = {NULL, NULL};
    cJSON *jout = cJSON_CreateArray();
    FILE *csvf = NULL;

    lt_sf_defaults(&sf);
    for (a = 2; a < argc; a++) {
        const char *o = argv[a], *v = a + 1 < argc ? argv[a + 1] : NULL;
        if (strcmp(o, "--help") == 0 || strcmp(o, "-h") == 0) {
            run_usage(stdout);
            return 0;
        }
        if (strcmp(o, "--native") == 0) {
            if (lt_meter_available())
                return exec_native(argc, argv);
            continue;
        }
        if (strcmp(o, "-q") == 0) {
            quiet = 1;
            continue;
        }
        if (strcmp(o, "--json") == 0) {
            json = 1;
            quiet = 1;
            continue;
        }
        if (strcmp(o, "--no-ref") == 0) {
            do_ref = 0;
            continue;
        }
        if (o[0] != '-') {
            if (scene_path != NULL) {
                fprintf(stderr, "%s run: more than one scene file ('%s', '%s')\n", prog,
                        scene_path, o);
                return EXIT_USAGE;
            }
            scene_path = o;
            continue;
        }
        if (v == NULL) {
            fprintf(stderr, "%s run: unknown option '%s' or missing value\n", prog, o);
            run_usage(stderr);
            return EXIT_USAGE;
        }
        a++;
        if (strcmp(o, "--mesh") == 0) {
            mesh_over = v;
        } else if (strcmp(o, "--res") == 0) {
            if (lt_parse_wh(v, LT_SF_MAX_RES, &sf.width, &sf.height) != 0) {
                fprintf(stderr, "%s run: --res %s: expected WxH or N, 1..%d\n", prog, v,
                        LT_SF_MAX_RES);
                return EXIT_USAGE;
            }
        } else if (strcmp(o, "--num") == 0) {
            if (strcmp(v, "q16") == 0)
                sf.numeric = LT_SF_NUM_Q16;
            else if (strcmp(v, "f32") == 0)
                sf.numeric = LT_SF_NUM_F32;
            else if (strcmp(v, "both") == 0)
                sf.numeric = LT_SF_NUM_BOTH;
            else {
                fprintf(stderr, "%s run: --num %s: expected q16, f32 or both\n", prog, v);
                return EXIT_USAGE;
            }
        } else if (strcmp(o, "--structure") == 0) {
            snprintf(sf.structure, sizeof sf.structure, "%s", v);
        } else if (strcmp(o, "--machine") == 0) {
            snprintf(sf.machine, sizeof sf.machine, "%s", v);
        } else if (strcmp(o, "--l1") == 0) {
            snprintf(sf.l1, sizeof sf.l1, "%s", v);
        } else if (strcmp(o, "--l2") == 0) {
            snprintf(sf.l2, sizeof sf.l2, "%s", v);
        } else if (strcmp(o, "--report") == 0) {
            report = v;
        } else if (strcmp(o, "--csv") == 0) {
            csv = v;
        } else if (strcmp(o, "--depth") == 0) {
            depth_out = v;
        } else if (strcmp(o, "--heatmap") == 0) {
            heat_out = v;
        } else if (strcmp(o, "--repeat") == 0) {
            repeat = atoi(v);
            if (repeat < 1 || repeat > 100000) {
                fprintf(stderr, "%s run: --repeat %s: expected 1..100000\n", prog, v);
                return EXIT_USAGE;
            }
        } else {
            fprintf(stderr, "%s run: unknown option '%s'\n", prog, o);
            run_usage(stderr);
            return EXIT_USAGE;
        }
    }
    /* the scene file first, then the flags given on the command line override it */
    if (scene_path != NULL) {
        lt_scenefile_t fl = sf;
        if (lt_sf_load(scene_path, &sf, &diag) != 0) {
            fprintf(stderr, "%s\n", diag.msg);
            return EXIT_INPUT;
        }
        for (a = 2; a < argc; a++) {
            if (strcmp(argv[a], "--res") == 0) {
                sf.width = fl.width;
                sf.height = fl.height;
            }
            if (strcmp(argv[a], "--num") == 0)
                sf.numeric = fl.numeric;
            if (strcmp(argv[a], "--structure") == 0)
                memcpy(sf.structure, fl.structure, sizeof sf.structure);
            if (strcmp(argv[a], "--machine") == 0)
                memcpy(sf.machine, fl.machine, sizeof sf.machine);
            if (strcmp(argv[a], "--l1") == 0)
                memcpy(sf.l1, fl.l1, sizeof sf.l1);
            if (strcmp(argv[a], "--l2") == 0)
                memcpy(sf.l2, fl.l2, sizeof sf.l2);
        }
    }
    if (mesh_over != NULL)
        snprintf(sf.mesh, sizeof sf.mesh, "%s", mesh_over);
    if (sf.mesh[0] == '\0')
        snprintf(sf.mesh, sizeof sf.mesh, "scenes/teapot.obj");
    if (report == NULL && sf.out_report[0] != '\0')
        report = sf.out_report;
    if (csv == NULL && sf.out_csv[0] != '\0')
        csv = sf.out_csv;
    if (!lt_meter_machine_known(sf.machine)) {
        fprintf(stderr, "%s run: machine '%s' unknown (known: %s)\n", prog, sf.machine,
                lt_meter_machine_names());
        return EXIT_USAGE;
    }
    if (lt_meter_init(sf.machine, sf.l1[0] ? sf.l1 : NULL, sf.l2[0] ? sf.l2 : NULL, &diag) != 0) {
        fprintf(stderr, "%s run: %s\n", prog, diag.msg);
        return EXIT_USAGE;
    }
    if (lt_mesh_load(sf.mesh, &mesh, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        return EXIT_INPUT;
    }
    if (lt_scene_prepare(&mesh, &sc, &diag) != 0) {
        fprintf(stderr, "%s: %s\n", sf.mesh, diag.msg);
        lt_mesh_free(&mesh);
        return EXIT_INPUT;
    }
    if (((unsigned)sf.numeric & (1u << LT_PATH_Q16)) && lt_scene_check_q16(&sc, sf.mesh, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        lt_scene_free(&sc);
        lt_mesh_free(&mesh);
        return EXIT_INPUT;
    }
    if (sf.has_camera) {
        if (lt_camera_look(&sc, sf.eye, sf.target, sf.up, sf.fov_y_deg, sf.width, sf.height, &cam,
                           &diag) != 0) {
            fprintf(stderr, "%s: %s\n", sf.path[0] ? sf.path : sf.mesh, diag.msg);
            lt_scene_free(&sc);
            lt_mesh_free(&mesh);
            return EXIT_INPUT;
        }
    } else {
        lt_camera_default(&sc, sf.width, sf.height, &cam);
    }
    if (!quiet)
        printf("scene     %s: %u triangles, scale %g (file units -> s15.16 units), radius %.1f, "
               "%ux%u pixels, %u packets, structure %s\n",
               sf.mesh, sc.ntris, sc.scale, sc.radius, sf.width, sf.height,
               ((sf.width + 3) / 4) * ((sf.height + 3) / 4), sf.structure);
    if (lt_frame_alloc(&ref, sf.width, sf.height, &diag) != 0 ||
        lt_frame_alloc(&fr, sf.width, sf.height, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        return EXIT_INPUT;
    }
    if (do_ref) {
        progress_begin("reference");
        lt_render_reference(&sc, &cam, &ref, progress);
        progress_end();
    }
    if (csv != NULL) {
        snprintf(csv_tmp, sizeof csv_tmp, "%s.tmp%ld", csv, (long)getpid());
        csvf = fopen(csv_tmp, "w");
        if (csvf == NULL) {
            fprintf(stderr, "%s: cannot create the CSV output\n", csv);
            csv_tmp[0] = '\0';
            status = EXIT_INPUT;
            goto done;
        }
        fprintf(csvf, "scene,structure,path,machine,width,height,rays,total_cycles,cycles_per_ray,"
                      "mrays_per_s_modelled,lane_utilisation,host_ms,same_triangle_pct,depth_rmse,"
                      "depth_max_err,cycles_build,cycles_setup,cycles_traverse,cycles_intersect,"
                      "cycles_shade,l1_hit_pct,nodes_per_ray,aabb_tests_per_ray,tri_tests_per_ray,"
                      "structure_bytes\n");
    }
    for (path = 0; path < 2; path++) {
        lt_accel_t *acc;
        lt_accuracy_t ac;
        const char *pname = path == 0 ? "q16" : "f32";
        double t0, ms;
        int rep;
        cJSON *jr = NULL;
        char extra[2048];
        size_t acc_bytes;
        uint64_t rays = (uint64_t)sf.width * sf.height * (uint64_t)repeat;
        if (!((unsigned)sf.numeric & (1u << path)))
            continue;
        lt_meter_reset();
        acc = lt_accel_build(&sc, sf.structure, (lt_path_t)path, &diag);
        if (acc == NULL) {
            fprintf(stderr, "%s: %s\n", sf.path[0] ? sf.path : prog, diag.msg);
            status = EXIT_INPUT;
            break;
        }
        progress_begin(pname);
        t0 = lt_now_s();
        for (rep = 0; rep < repeat; rep++)
            lt_render_primary(&sc, acc, &cam, &fr, progress);
        ms = 1e3 * (lt_now_s() - t0);
        progress_end();
        acc_bytes = lt_accel_bytes(acc);
        lt_accel_free(acc);
        if (depth_out != NULL) {
            size_t i, np = (size_t)sf.width * sf.height;
            zbuf[path] = malloc(np * sizeof(float));
            idbuf[path] = malloc(np * sizeof(float));
            if (zbuf[path] == NULL || idbuf[path] == NULL) {
                fprintf(stderr, "%s: out of memory for the depth output\n", depth_out);
                status = EXIT_INPUT;
                break;
            }
            /* misses: distance +inf, id -1 (ids up to 2^24 are exact in float) */
            for (i = 0; i < np; i++) {
                zbuf[path][i] = fr.id[i] >= 0 ? (float)fr.t[i] : (float)INFINITY;
                idbuf[path][i] = (float)fr.id[i];
            }
        }
        if (!lt_meter_available() && heat_out != NULL && path == 0)
            fprintf(stderr, "%s run: --heatmap needs the simulator build (build/sim/lanetrace); "
                            "ignored\n", prog);
        if (lt_meter_available() && heat_out != NULL) {
            char hp[1100];
            lt_heatmap_opts_t ho = LT_HEATMAP_OPTS_DEFAULT;
            snprintf(hp, sizeof hp, "%s.%s.png", heat_out, pname);
            if (lt_heatmap_write_png(hp, fr.cost, (int32_t)sf.width, (int32_t)sf.height, &ho,
                                     &diag) != 0) {
                fprintf(stderr, "%s\n", diag.msg);
                status = EXIT_INPUT;
            } else {
                if (!quiet)
                    printf("heatmap   %s (simulated cycles per pixel)\n", hp);
                snprintf(hp, sizeof hp, "%s.%s.exr", heat_out, pname);
                if (lt_heatmap_write_exr(hp, fr.cost, (int32_t)sf.width, (int32_t)sf.height,
                                         "cycles", &diag) != 0) {
                    fprintf(stderr, "%s\n", diag.msg);
                    status = EXIT_INPUT;
                }
                snprintf(hp, sizeof hp, "%s.%s.steps.png", heat_out, pname);
                if (lt_heatmap_write_png(hp, fr.steps, (int32_t)sf.width, (int32_t)sf.height, &ho,
                                         &diag) != 0 ||
                    (snprintf(hp, sizeof hp, "%s.%s.steps.exr", heat_out, pname),
                     lt_heatmap_write_exr(hp, fr.steps, (int32_t)sf.width, (int32_t)sf.height,
                                          "steps", &diag)) != 0) {
                    fprintf(stderr, "%s\n", diag.msg);
                    status = EXIT_INPUT;
                } else if (!quiet) {
                    printf("heatmap   %s.%s.steps.png (traversal steps per pixel's packet)\n",
                           heat_out, pname);
                }
            }
        }
        memset(&ac, 0, sizeof ac);
        if (do_ref)
            lt_frame_compare(&fr, &ref, 1e-4 * sc.radius, &ac);
        if (!json) {
            printf("time      %-4s %.3f ms for %d frame(s) of %u rays (%s, %.2f Mrays/s host)\n",
                   pname, ms, repeat, sf.width * sf.height,
                   lt_meter_available() ? "counted" : "native",
                   (double)rays / (ms * 1e-3) / 1e6);
            printf("result    %-4s hash 0x%08x\n", pname, lt_frame_hash(&fr));
            if (do_ref)
                printf("accuracy  %-4s vs double: same triangle %.3f%% of %u pixels, depth RMSE "
                       "%.3g, max %.3g (scene radius %.1f), %.2f%% of common hits within 1e-4 "
                       "radius\n",
                       pname, 100.0 * ac.same_id / ac.pixels, ac.pixels, ac.rmse, ac.max_err,
                       sc.radius, ac.both_hit ? 100.0 * ac.within_tol / ac.both_hit : 100.0);
        }
        {
            /* run facts merged into the report; cJSON escapes the path */
            cJSON *x = cJSON_CreateObject();
            char *xs;
            cJSON_AddStringToObject(x, "path", pname);
            cJSON_AddStringToObject(x, "structure", sf.structure);
            cJSON_AddStringToObject(x, "scene", sf.mesh);
            cJSON_AddNumberToObject(x, "width", sf.width);
            cJSON_AddNumberToObject(x, "height", sf.height);
            cJSON_AddNumberToObject(x, "host_ms", ms);
            cJSON_AddNumberToObject(x, "frame_hash", lt_frame_hash(&fr));
            cJSON_AddNumberToObject(x, "structure_bytes", (double)acc_bytes);
            if (do_ref) {
                cJSON *y = cJSON_AddObjectToObject(x, "accuracy");
                cJSON_AddNumberToObject(y, "same_triangle_pct", 100.0 * ac.same_id / ac.pixels);
                cJSON_AddNumberToObject(y, "depth_rmse", ac.rmse);
                cJSON_AddNumberToObject(y, "depth_max_err", ac.max_err);
                cJSON_AddNumberToObject(y, "scene_radius", sc.radius);
            }
            xs = cJSON_PrintUnformatted(x);
            snprintf(extra, sizeof extra, "%s", xs != NULL ? xs : "{}");
            free(xs);
            cJSON_Delete(x);
        }
        if (lt_meter_available()) {
            char title[512], *js;
            snprintf(title, sizeof title, "%s %ux%u %s, %s, %d frame(s)", sf.mesh, sf.width,
                     sf.height, pname, sf.structure, repeat);
            if (!quiet) {
                lt_meter_report_text(stdout, title, rays);
            } else if (!json) {
                lt_meter_totals_t tt;
                lt_meter_totals(&tt);
                printf("cycles    %-4s %llu total, %.1f cycles/ray on %s\n", pname,
                       (unsigned long long)tt.total_cycles, (double)tt.total_cycles / (double)rays,
                       sf.machine);
            }
            js = lt_meter_report_json(title, rays, extra);
            jr = js != NULL ? cJSON_Parse(js) : NULL;
            if (report != NULL && js != NULL) {
                char p[1100];
                snprintf(p, sizeof p, "%s%s%s", report, sf.numeric == LT_SF_NUM_BOTH ? "." : "",
                         sf.numeric == LT_SF_NUM_BOTH ? pname : "");
                if (write_atomic(p, js, &diag) != 0) {
                    fprintf(stderr, "%s\n", diag.msg);
                    status = EXIT_INPUT;
                } else if (!quiet) {
                    printf("report    %s\n", p);
                }
            }
            free(js);
        } else {
            /* native build: the report holds the run facts and accuracy, no cycle counts */
            jr = cJSON_Parse(extra);
            if (report != NULL) {
                char p[1100];
                snprintf(p, sizeof p, "%s%s%s", report, sf.numeric == LT_SF_NUM_BOTH ? "." : "",
                         sf.numeric == LT_SF_NUM_BOTH ? pname : "");
                if (write_atomic(p, extra, &diag) != 0) {
                    fprintf(stderr, "%s\n", diag.msg);
                    status = EXIT_INPUT;
                } else if (!quiet) {
                    printf("report    %s\n", p);
                }
            }
        }
        if (csvf != NULL && lt_meter_available()) {
            lt_meter_machine_t mi;
            lt_meter_totals_t tt;
            double util = 0.0;
            (void)lt_meter_machine_info(sf.machine, &mi);
            lt_meter_totals(&tt);
            if (jr != NULL && cJSON_GetObjectItem(jr, "lane_utilisation") != NULL)
                util = cJSON_GetObjectItem(jr, "lane_utilisation")->valuedouble;
            fprintf(csvf,
                    "%s,%s,%s,%s,%u,%u,%llu,%llu,%.3f,%.4f,%.4f,%.3f,%.4f,%.6g,%.6g,%llu,%llu,"
                    "%llu,%llu,%llu,%.3f,%.3f,%.3f,%.3f,%zu\n",
                    sf.mesh, sf.structure, pname, sf.machine, sf.width, sf.height,
                    (unsigned long long)rays, (unsigned long long)tt.total_cycles,
                    (double)tt.total_cycles / (double)rays,
                    (double)rays / ((double)tt.total_cycles / (mi.clock_mhz * 1e6)) / 1e6,
                    util, ms, do_ref ? 100.0 * ac.same_id / ac.pixels : 0.0, ac.rmse, ac.max_err,
                    (unsigned long long)tt.cycles[LT_PH_BUILD],
                    (unsigned long long)tt.cycles[LT_PH_SETUP],
                    (unsigned long long)tt.cycles[LT_PH_TRAVERSE],
                    (unsigned long long)tt.cycles[LT_PH_INTERSECT],
                    (unsigned long long)tt.cycles[LT_PH_SHADE],
                    tt.l1_acc ? 100.0 * (double)tt.l1_hit / (double)tt.l1_acc : 0.0,
                    (double)tt.events[LT_EV_NODES] / (double)rays,
                    (double)tt.events[LT_EV_AABB_RAYS] / (double)rays,
                    (double)tt.events[LT_EV_TRI_RAYS] / (double)rays, acc_bytes);
        } else if (csvf != NULL) {
            fprintf(csvf, "%s,%s,%s,native,%u,%u,%llu,,,,,%.3f,%.4f,%.6g,%.6g,,,,,,,,,,%zu\n", sf.mesh,
                    sf.structure, pname, sf.width, sf.height, (unsigned long long)rays, ms,
                    do_ref ? 100.0 * ac.same_id / ac.pixels : 0.0, ac.rmse, ac.max_err, acc_bytes);
        }
        if (jr != NULL)
            cJSON_AddItemToArray(jout, jr);
    }
    if (depth_out != NULL && status == 0) {
        lt_exr_channel_t ch[4];
        lt_exr_image_t im;
        int nch = 0;
        static const char *const zn[2] = {"q16.Z", "f32.Z"}, *const idn[2] = {"q16.id", "f32.id"};
        for (path = 0; path < 2; path++) {
            if (zbuf[path] == NULL)
                continue;
            ch[nch].name = zn[path];
            ch[nch].type = LT_EXR_FLOAT;
            ch[nch++].data = zbuf[path];
            ch[nch].name = idn[path];
            ch[nch].type = LT_EXR_FLOAT;
            ch[nch++].data = idbuf[path];
        }
        memset(&im, 0, sizeof im);
        im.width = (int32_t)sf.width;
        im.height = (int32_t)sf.height;
        im.nchannels = nch;
        im.channels = ch;
        im.compression = LT_EXR_COMP_ZIP;
        if (lt_exr_write(depth_out, &im, &diag) != 0) {
            fprintf(stderr, "%s\n", diag.msg);
            status = EXIT_INPUT;
        } else if (!quiet) {
            printf("depth     %s (%d channels)\n", depth_out, nch);
        }
    }
    for (path = 0; path < 2; path++) {
        free(zbuf[path]);
        free(idbuf[path]);
    }
    if (csvf != NULL) {
        if (fclose(csvf) != 0 || rename(csv_tmp, csv) != 0) {
            fprintf(stderr, "%s: cannot write the CSV output\n", csv);
            unlink(csv_tmp);
            status = EXIT_INPUT;
        } else if (!quiet) {
            printf("csv       %s\n", csv);
        }
        csv_tmp[0] = '\0';
    }
    if (json) {
        char *s = cJSON_Print(jout);
        if (s != NULL)
            puts(s);
        free(s);
    }
done:
    cJSON_Delete(jout);
    lt_frame_free(&fr);
    lt_frame_free(&ref);
    lt_scene_free(&sc);
    lt_mesh_free(&mesh);
    lt_meter_shutdown();
    return status;
}

/* ---- info ----------------------------------------------------------------------------------- */

/* EXR: the header (parts, storage, windows, channels) and statistics of the depth channel. */
static int info_exr(const char *path, int json)
{
    static const char *const storage[] = {"scanline", "tiled", "deep scanline", "deep tiled"};
    static const char *const types[] = {"?", "HALF", "FLOAT", "UINT"};
    lt_exr_probe_t pr;
    lt_exr_depth_t d;
    lt_exr_read_opts_t ro = LT_EXR_READ_OPTS_DEFAULT;
    lt_diag_t diag;
    int c, have_depth;
    double mn = INFINITY, mx = -INFINITY, sum = 0.0;
    size_t k, n = 0, holes = 0;
    if (lt_exr_probe(path, &pr, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        return EXIT_INPUT;
    }
    ro.deep = LT_EXR_DEEP_FRONT;
    have_depth = lt_exr_read_depth(path, NULL, &ro, &d, &diag) == 0;
    if (have_depth) {
        for (k = 0; k < (size_t)d.width * (size_t)d.height; k++) {
            double z = d.z[k];
            if (!isfinite(z) || z <= 0.0) {
                holes++;
                continue;
            }
            n++;
            sum += z;
            mn = z < mn ? z : mn;
            mx = z > mx ? z : mx;
        }
    }
    if (json) {
        printf("{\"file\":\"%s\",\"parts\":%d,\"storage\":\"%s\",\"data_window\":[%d,%d,%d,%d],"
               "\"display_window\":[%d,%d,%d,%d],\"channels\":%d",
               path, pr.parts, storage[pr.storage & 3], pr.data_window.x0, pr.data_window.y0,
               pr.data_window.x1, pr.data_window.y1, pr.display_window.x0, pr.display_window.y0,
               pr.display_window.x1, pr.display_window.y1, pr.nchannels);
        if (have_depth)
            printf(",\"depth\":{\"channel\":\"%s\",\"pixels\":%zu,\"holes\":%zu,\"min\":%g,"
                   "\"max\":%g,\"mean\":%g}",
                   d.channel, n, holes, n ? mn : 0.0, n ? mx : 0.0, n ? sum / (double)n : 0.0);
        printf("}\n");
    } else {
        printf("%s: OpenEXR, %d part(s), %s, data window (%d,%d)-(%d,%d), display window "
               "(%d,%d)-(%d,%d)\n",
               path, pr.parts, storage[pr.storage & 3], pr.data_window.x0, pr.data_window.y0,
               pr.data_window.x1, pr.data_window.y1, pr.display_window.x0, pr.display_window.y0,
               pr.display_window.x1, pr.display_window.y1);
        printf("channels  %d:", pr.nchannels);
        for (c = 0; c < pr.nchannels && c < LT_EXR_PROBE_CHANNELS; c++)
            printf(" %s(%s)", pr.name[c], types[pr.type[c] & 3]);
        printf("\n");
        if (have_depth)
            printf("depth     %s%s: %zu pixels with depth, %zu holes (0, negative, NaN or inf), "
                   "min %g max %g mean %g\n",
                   d.channel, d.deep ? " (deep: front-most sample)" : "", n, holes,
                   n ? mn : 0.0, n ? mx : 0.0, n ? sum / (double)n : 0.0);
        else
            printf("depth     none readable: %s\n", diag.msg);
    }
    if (have_depth)
        lt_exr_depth_free(&d);
    return 0;
}

static int cmd_info(int argc, char **argv)
{
    lt_mesh_t m;
    lt_scene_t sc;
    lt_diag_t diag;
    uint32_t i, zero = 0;
    int json = 0, a;
    const char *path = NULL;
    for (a = 2; a < argc; a++) {
        if (strcmp(argv[a], "--help") == 0 || strcmp(argv[a], "-h") == 0) {
            printf("usage: %s info FILE [--json]\nDescribe a mesh (triangles, zero-area "
                   "triangles, bounds, the fixed-point scale lanetrace picks) or an EXR file\n"
                   "(parts, windows, channels, depth statistics).\n",
                   prog);
            return 0;
        } else if (strcmp(argv[a], "--json") == 0) {
            json = 1;
        } else if (argv[a][0] == '-' || path != NULL) {
            fprintf(stderr, "%s info: unexpected argument '%s'\n", prog, argv[a]);
            return EXIT_USAGE;
        } else {
            path = argv[a];
        }
    }
    if (path == NULL) {
        fprintf(stderr, "%s info: a FILE is required\n", prog);
        return EXIT_USAGE;
    }
    {
        size_t l = strlen(path);
        if (l > 4 && strcmp(path + l - 4, ".exr") == 0)
            return info_exr(path, json);
    }
    if (lt_mesh_load(path, &m, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        return EXIT_INPUT;
    }
    for (i = 0; i < m.ntris; i++) {
        const double *v = &m.v[i * 9];
        double e1[3], e2[3], c[3];
        int k;
        for (k = 0; k < 3; k++) {
            e1[k] = v[3 + k] - v[k];
            e2[k] = v[6 + k] - v[k];
        }
        c[0] = e1[1] * e2[2] - e1[2] * e2[1];
        c[1] = e1[2] * e2[0] - e1[0] * e2[2];
        c[2] = e1[0] * e2[1] - e1[1] * e2[0];
        zero += c[0] == 0.0 && c[1] == 0.0 && c[2] == 0.0;
    }
    if (lt_scene_prepare(&m, &sc, &diag) != 0) {
        fprintf(stderr, "%s: %s\n", path, diag.msg);
        lt_mesh_free(&m);
        return EXIT_INPUT;
    }
    if (json)
        printf("{\"file\":\"%s\",\"triangles\":%u,\"zero_area\":%u,\"lo\":[%g,%g,%g],"
               "\"hi\":[%g,%g,%g],\"scale\":%g,\"radius_scaled\":%g,\"collapsed_q16\":%u,"
               "\"q16_representable\":%s}\n",
               path, m.ntris, zero, m.lo[0], m.lo[1], m.lo[2], m.hi[0], m.hi[1], m.hi[2],
               sc.scale, sc.radius, sc.collapsed_q16,
               lt_scene_check_q16(&sc, path, &diag) == 0 ? "true" : "false");
    else
        printf("%s: mesh, %u triangles (%u zero-area), bounds [%g %g %g] .. [%g %g %g]\n"
               "fixed point: scale %g (a power of two), scene radius %.2f units of s15.16, "
               "resolution %.3g file units\n"
               "s15.16: %u of %u non-degenerate triangles collapse to zero area (limit %.1f%%: %s), "
               "shortest edge %.3g units\n",
               path, m.ntris, zero, m.lo[0], m.lo[1], m.lo[2], m.hi[0], m.hi[1], m.hi[2], sc.scale,
               sc.radius, 1.0 / 65536.0 / sc.scale, sc.collapsed_q16, sc.nonzero,
               LT_SCENE_MAX_COLLAPSED_PPM / 1e4,
               lt_scene_check_q16(&sc, path, &diag) == 0 ? "representable"
                                                                 : "NOT representable, float32 only",
               sc.min_edge);
    lt_scene_free(&sc);
    lt_mesh_free(&m);
    return 0;
}

/* ---- diff ----------------------------------------------------------------------------------- */

static cJSON *load_json(const char *path, lt_diag_t *diag)
{
    FILE *f = fopen(path, "rb");
    char *buf;
    long n;
    cJSON *j;
    if (f == NULL) {
        lt_diag_fail(diag, "%s: cannot open", path);
        return NULL;
    }
    fseek(f, 0, SEEK_END);
    n = ftell(f);
    fseek(f, 0, SEEK_SET);
    if (n < 0 || n > (64L << 20)) {
        fclose(f);
        lt_diag_fail(diag, "%s: not a report (size %ld, limit 64 MiB)", path, n);
        return NULL;
    }
    buf = malloc((size_t)n + 1);
    if (buf == NULL || fread(buf, 1, (size_t)n, f) != (size_t)n) {
        fclose(f);
        free(buf);
        lt_diag_fail(diag, "%s: cannot read", path);
        return NULL;
    }
    fclose(f);
    buf[n] = '\0';
    j = cJSON_Parse(buf);
    free(buf);
    if (j == NULL || !cJSON_IsObject(j)) {
        cJSON_Delete(j);
        lt_diag_fail(diag, "%s: not a JSON report object", path);
        return NULL;
    }
    return j;
}

/* Walk both reports' numeric members (nested objects flattened as a.b.c) and print changes. */
static void diff_walk(const cJSON *a, const cJSON *b, const char *prefix, double threshold,
                      cJSON *out, int *changed, int *total)
{
    const cJSON *x;
    cJSON_ArrayForEach(x, a) {
        char key[256];
        const cJSON *y = cJSON_GetObjectItemCaseSensitive(b, x->string);
        snprintf(key, sizeof key, "%s%s%s", prefix, *prefix ? "." : "", x->string);
        if (cJSON_IsObject(x) && cJSON_IsObject(y)) {
            diff_walk(x, y, key, threshold, out, changed, total);
        } else if (cJSON_IsNumber(x)) {
            double va = x->valuedouble, vb = cJSON_IsNumber(y) ? y->valuedouble : 0.0;
            double rel = va != 0.0 ? 100.0 * (vb - va) / fabs(va) : (vb != 0.0 ? (double)INFINITY : 0.0);
            (*total)++;
            if (y == NULL || fabs(rel) > threshold) {
                cJSON *row = cJSON_CreateObject();
                (*changed)++;
                cJSON_AddStringToObject(row, "counter", key);
                cJSON_AddNumberToObject(row, "a", va);
                if (y != NULL)
                    cJSON_AddNumberToObject(row, "b", vb);
                cJSON_AddNumberToObject(row, "delta", vb - va);
                if (isfinite(rel))
                    cJSON_AddNumberToObject(row, "pct", rel);
                cJSON_AddItemToArray(out, row);
            }
        }
    }
    cJSON_ArrayForEach(x, b) {
        char key[256];
        snprintf(key, sizeof key, "%s%s%s", prefix, *prefix ? "." : "", x->string);
        if (cJSON_IsNumber(x) && cJSON_GetObjectItemCaseSensitive(a, x->string) == NULL) {
            cJSON *row = cJSON_CreateObject();
            (*changed)++;
            (*total)++;
            cJSON_AddStringToObject(row, "counter", key);
            cJSON_AddNumberToObject(row, "b", x->valuedouble);
            cJSON_AddNumberToObject(row, "delta", x->valuedouble);
            cJSON_AddItemToArray(out, row);
        }
    }
}

static int cmd_diff(int argc, char **argv)
{
    const char *pa = NULL, *pb = NULL;
    double threshold = 0.0;
    int json = 0, a, changed = 0, total = 0;
    lt_diag_t diag;
    cJSON *ja, *jb, *rows;
    const cJSON *r;
    for (a = 2; a < argc; a++) {
        if (strcmp(argv[a], "--help") == 0 || strcmp(argv[a], "-h") == 0) {
            printf("usage: %s diff A.json B.json [--threshold PCT] [--json]\nCompare two JSON "
                   "reports: every numeric counter that moved by more than PCT%% (default 0).\n",
                   prog);
            return 0;
        } else if (strcmp(argv[a], "--json") == 0) {
            json = 1;
        } else if (strcmp(argv[a], "--threshold") == 0 && a + 1 < argc) {
            char *end;
            threshold = strtod(argv[++a], &end);
            if (*end != '\0' || !(threshold >= 0.0)) {
                fprintf(stderr, "%s diff: --threshold %s: expected a percentage >= 0\n", prog,
                        argv[a]);
                return EXIT_USAGE;
            }
        } else if (argv[a][0] == '-') {
            fprintf(stderr, "%s diff: unknown option '%s'\n", prog, argv[a]);
            return EXIT_USAGE;
        } else if (pa == NULL) {
            pa = argv[a];
        } else if (pb == NULL) {
            pb = argv[a];
        } else {
            fprintf(stderr, "%s diff: more than two reports\n", prog);
            return EXIT_USAGE;
        }
    }
    if (pb == NULL) {
        fprintf(stderr, "%s diff: two reports are required\n", prog);
        return EXIT_USAGE;
    }
    if ((ja = load_json(pa, &diag)) == NULL ||
        (jb = load_json(pb, &diag)) == NULL) {
        fprintf(stderr, "%s\n", diag.msg);
        return EXIT_INPUT;
    }
    rows = cJSON_CreateArray();
    diff_walk(ja, jb, "", threshold, rows, &changed, &total);
    if (json) {
        char *s;
        cJSON *o = cJSON_CreateObject();
        cJSON_AddNumberToObject(o, "counters", total);
        cJSON_AddNumberToObject(o, "changed", changed);
        cJSON_AddItemToObject(o, "rows", rows);
        s = cJSON_Print(o);
        puts(s);
        free(s);
        cJSON_Delete(o);
    } else {
        printf("%-40s %16s %16s %14s %9s\n", "counter", "a", "b", "delta", "change");
        cJSON_ArrayForEach(r, rows) {
            const cJSON *va = cJSON_GetObjectItem(r, "a"), *vb = cJSON_GetObjectItem(r, "b");
            const cJSON *p = cJSON_GetObjectItem(r, "pct");
            char sa[32] = "-", sb[32] = "-", sp[32] = "new";
            if (va)
                snprintf(sa, sizeof sa, "%.6g", va->valuedouble);
            if (vb)
                snprintf(sb, sizeof sb, "%.6g", vb->valuedouble);
            if (p)
                snprintf(sp, sizeof sp, "%+.2f%%", p->valuedouble);
            else if (va && !vb)
                snprintf(sp, sizeof sp, "gone");
            printf("%-40s %16s %16s %14.6g %9s\n", cJSON_GetObjectItem(r, "counter")->valuestring,
                   sa, sb, cJSON_GetObjectItem(r, "delta")->valuedouble, sp);
        }
        printf("%d of %d counters changed (threshold %g%%)\n", changed, total, threshold);
        cJSON_Delete(rows);
    }
    cJSON_Delete(ja);
    cJSON_Delete(jb);
    return 0;
}


/* ---- render --------------------------------------------------------------------------------- */

static void render_usage(FILE *f)
{
    fprintf(f,
            "usage: %s render [SCENE.json] --out PREFIX [options]\n"
            "Render a mesh through a structure in one numeric path and write images:\n"
            "  PREFIX.exr  FLOAT channels Z (distance), id, N.x N.y N.z (normal), R G B (shaded:\n"
            "              one point light, hard shadows) and, with --layers K, layer0.Z ..\n"
            "              layer<K-1>.Z (the first K surfaces along each primary ray)\n"
            "  PREFIX.png  the shaded image; PREFIX.depth.png, PREFIX.normals.png, PREFIX.ids.png\n"
            "  --mesh PATH  --res WxH|N  --num q16|f32 (default q16)\n"
            "  --structure bvh|bvhq|kd|grid|chunks (default bvh; chunks: no shadows, no peels)\n"
            "  --layers K   depth peels, 1..16 (default 1)\n"
            "  --report PATH  (simulator build) write the cycle report of the whole render as JSON;\n"
            "               the text report is printed unless -q or --json\n"
            "  --light X,Y,Z  point light in mesh file units (default: the scene's first light,\n"
            "               else centre + 2 radius normalize(-0.5, 1.5, 0.8))\n"
            "  --json       print what was written as JSON on stdout\n"
            "  -q           quiet\n",
            prog);
}

static uint64_t count_hits(const lt_frame_t *f)
{
    size_t i, n = (size_t)f->width * f->height;
    uint64_t c = 0;
    for (i = 0; i < n; i++)
        c += f->id[i] >= 0;
    return c;
}

static int cmd_render(int argc, char **argv)
{
    lt_scenefile_t sf;
    lt_mesh_t mesh;
    lt_scene_t sc;
    lt_camera_t cam;
    lt_frame_t fr, lay[16];
    lt_accel_t *acc = NULL;
    char path[1200];
    lt_diag_t diag;
    const char *scene_path = NULL, *mesh_over = NULL, *out = NULL, *structure = "bvh";
    const char *report = NULL;
    uint64_t nrays = 0;
    int a, layers = 1, l, status = 0, have_light = 0, json = 0;
    double light[3], lf[3];
    lt_path_t np = LT_PATH_Q16;
    uint32_t w = 0, h = 0, nshadow = 0, nocc = 0;
    size_t i, n;
    float *ch[10];
    uint8_t *occ = NULL, *rgb = NULL;

    memset(&fr, 0, sizeof fr);
    memset(lay, 0, sizeof lay);
    memset(ch, 0, sizeof ch);
    lt_sf_defaults(&sf);
    for (a = 2; a < argc; a++) {
        const char *o = argv[a], *v = a + 1 < argc ? argv[a + 1] : NULL;
        if (strcmp(o, "--help") == 0 || strcmp(o, "-h") == 0) {
            render_usage(stdout);
            return 0;
        }
        if (strcmp(o, "-q") == 0) {
            quiet = 1;
            continue;
        }
        if (strcmp(o, "--json") == 0) {
            json = quiet = 1;
            continue;
        }
        if (o[0] != '-') {
            scene_path = o;
            continue;
        }
        if (v == NULL) {
            fprintf(stderr, "%s render: unknown option '%s' or missing value\n", prog, o);
            return EXIT_USAGE;
        }
        a++;
        if (strcmp(o, "--mesh") == 0) {
            mesh_over = v;
        } else if (strcmp(o, "--out") == 0) {
            out = v;
        } else if (strcmp(o, "--report") == 0) {
            report = v;
        } else if (strcmp(o, "--res") == 0) {
            if (lt_parse_wh(v, LT_SF_MAX_RES, &w, &h) != 0) {
                fprintf(stderr, "%s render: --res %s: expected WxH or N, 1..%d\n", prog, v,
                        LT_SF_MAX_RES);
                return EXIT_USAGE;
            }
        } else if (strcmp(o, "--num") == 0) {
            if (strcmp(v, "q16") != 0 && strcmp(v, "f32") != 0) {
                fprintf(stderr, "%s render: --num %s: expected q16 or f32\n", prog, v);
                return EXIT_USAGE;
            }
            np = strcmp(v, "q16") == 0 ? LT_PATH_Q16 : LT_PATH_F32;
        } else if (strcmp(o, "--structure") == 0) {
            structure = v;
        } else if (strcmp(o, "--layers") == 0) {
            layers = atoi(v);
            if (layers < 1 || layers > 16) {
                fprintf(stderr, "%s render: --layers %s: expected 1..16\n", prog, v);
                return EXIT_USAGE;
            }
        } else if (strcmp(o, "--light") == 0) {
            if (sscanf(v, "%lf,%lf,%lf", &lf[0], &lf[1], &lf[2]) != 3 || !isfinite(lf[0]) ||
                !isfinite(lf[1]) || !isfinite(lf[2])) {
                fprintf(stderr, "%s render: --light %s: expected X,Y,Z\n", prog, v);
                return EXIT_USAGE;
            }
            have_light = 1;
        } else {
            fprintf(stderr, "%s render: unknown option '%s'\n", prog, o);
            render_usage(stderr);
            return EXIT_USAGE;
        }
    }
    if (out == NULL) {
        fprintf(stderr, "%s render: --out PREFIX is required\n", prog);
        return EXIT_USAGE;
    }
    if (!lt_meter_available() && report != NULL) {
        fprintf(stderr, "%s render: --report needs the simulator build (build/sim/lanetrace); "
                        "this is the native build\n", prog);
        return EXIT_USAGE;
    }
    if (scene_path != NULL && lt_sf_load(scene_path, &sf, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        return EXIT_INPUT;
    }
    if (w != 0) {
        sf.width = w;
        sf.height = h;
    }
    if (mesh_over != NULL)
        snprintf(sf.mesh, sizeof sf.mesh, "%s", mesh_over);
    if (sf.mesh[0] == '\0')
        snprintf(sf.mesh, sizeof sf.mesh, "scenes/teapot.obj");
    if (!have_light && sf.nlights > 0) {
        memcpy(lf, sf.lights[0].position, sizeof lf);
        have_light = 1;
    }
    if (lt_meter_init(sf.machine, NULL, NULL, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        return EXIT_USAGE;
    }
    if (lt_mesh_load(sf.mesh, &mesh, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        return EXIT_INPUT;
    }
    if (lt_scene_prepare(&mesh, &sc, &diag) != 0) {
        fprintf(stderr, "%s: %s\n", sf.mesh, diag.msg);
        lt_mesh_free(&mesh);
        return EXIT_INPUT;
    }
    if (np == LT_PATH_Q16 && lt_scene_check_q16(&sc, sf.mesh, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        status = EXIT_INPUT;
        goto done;
    }
    if (sf.has_camera) {
        if (lt_camera_look(&sc, sf.eye, sf.target, sf.up, sf.fov_y_deg, sf.width, sf.height, &cam,
                           &diag) != 0) {
            fprintf(stderr, "%s: %s\n", sf.path, diag.msg);
            status = EXIT_INPUT;
            goto done;
        }
    } else {
        lt_camera_default(&sc, sf.width, sf.height, &cam);
    }
    if (have_light) {
        for (a = 0; a < 3; a++)
            light[a] = (lf[a] - sc.center[a]) * sc.scale;
    } else {
        double d[3] = {-0.5, 1.5, 0.8}, ln = sqrt(0.25 + 2.25 + 0.64);
        for (a = 0; a < 3; a++)
            light[a] = 2.0 * sc.radius * d[a] / ln;
    }
    for (a = 0; a < 3; a++) {
        if (fabs(light[a]) > ldexp(1.0, LT_CFG_GEOM_MAX_LOG2)) {
            fprintf(stderr, "%s render: the light lies outside the fixed-point range (|x| <= %g "
                            "scaled units, %.3g scene radii)\n",
                    prog, ldexp(1.0, LT_CFG_GEOM_MAX_LOG2), ldexp(1.0, LT_CFG_GEOM_MAX_LOG2) / sc.radius);
            status = EXIT_INPUT;
            goto done;
        }
    }
    memset(lay, 0, sizeof lay);
    memset(ch, 0, sizeof ch);
    if (lt_frame_alloc(&fr, sf.width, sf.height, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        status = EXIT_INPUT;
        goto done;
    }
    acc = lt_accel_build(&sc, structure, np, &diag);
    if (acc == NULL) {
        fprintf(stderr, "%s render: %s\n", prog, diag.msg);
        status = EXIT_USAGE;
        goto done;
    }
    progress_begin("render");
    lt_render_primary(&sc, acc, &cam, &fr, progress);
    progress_end();
    n = (size_t)sf.width * sf.height;
    occ = calloc(n, 1);
    rgb = malloc(n * 3);
    for (a = 0; a < 10; a++)
        ch[a] = malloc(n * sizeof(float));
    for (a = 0; a < 10; a++)
        if (ch[a] == NULL || occ == NULL || rgb == NULL) {
            fprintf(stderr, "%s render: out of memory for %ux%u images\n", prog, sf.width,
                    sf.height);
            status = EXIT_INPUT;
            goto done;
        }
    if (strcmp(structure, "chunks") != 0 &&
        lt_render_shadows(&sc, acc, &cam, &fr, light, &nshadow, &nocc, occ, &diag) != 0) {
        fprintf(stderr, "%s render: %s\n", prog, diag.msg);
        status = EXIT_INPUT;
        goto done;
    }
    /* channels: Z id N.x N.y N.z R G B, then layer K.Z as needed */
    for (i = 0; i < n; i++) {
        uint32_t x = (uint32_t)(i % sf.width), y = (uint32_t)(i / sf.width);
        int32_t id = fr.id[i];
        double nrm[3] = {0, 0, 0}, d[3], shade = 0.0;
        if (id >= 0) {
            const double *v = &sc.vd[(size_t)id * 9];
            double e1[3], e2[3], ln, p[3], L[3], ll;
            int k;
            for (k = 0; k < 3; k++) {
                e1[k] = v[3 + k] - v[k];
                e2[k] = v[6 + k] - v[k];
            }
            nrm[0] = e1[1] * e2[2] - e1[2] * e2[1];
            nrm[1] = e1[2] * e2[0] - e1[0] * e2[2];
            nrm[2] = e1[0] * e2[1] - e1[1] * e2[0];
            ln = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
            lt_camera_dir(&cam, x, y, d);
            if (ln > 0.0) {
                /* two-sided: the normal faces the camera */
                double s1 = (nrm[0] * d[0] + nrm[1] * d[1] + nrm[2] * d[2]) > 0.0 ? -1.0 : 1.0;
                for (k = 0; k < 3; k++)
                    nrm[k] *= s1 / ln;
            }
            for (k = 0; k < 3; k++) {
                p[k] = cam.eye[k] + fr.t[i] * d[k];
                L[k] = light[k] - p[k];
            }
            ll = sqrt(L[0] * L[0] + L[1] * L[1] + L[2] * L[2]);
            shade = 0.08 + (occ[i] ? 0.0
                                   : 0.92 * fmax(0.0, (nrm[0] * L[0] + nrm[1] * L[1] + nrm[2] * L[2]) / ll));
        }
        ch[0][i] = id >= 0 ? (float)fr.t[i] : (float)INFINITY;
        ch[1][i] = (float)id;
        ch[2][i] = (float)nrm[0];
        ch[3][i] = (float)nrm[1];
        ch[4][i] = (float)nrm[2];
        ch[5][i] = ch[6][i] = ch[7][i] = (float)shade;
        rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = id >= 0 ? lt_gamma8(shade) : 24;
    }
    {
        lt_exr_channel_t ec[8 + 16];
        lt_exr_image_t im;
        static const char *const names[8] = {"Z", "id", "N.x", "N.y", "N.z", "R", "G", "B"};
        static char lname[16][16];
        int nc = 0;
        for (a = 0; a < 8; a++) {
            ec[nc].name = names[a];
            ec[nc].type = LT_EXR_FLOAT;
            ec[nc++].data = ch[a];
        }
        /* depth peels: layer 0 is the primary hit */
        for (l = 0; l < layers && layers > 1; l++) {
            float *z = malloc(n * sizeof(float));
            if (z == NULL || lt_frame_alloc(&lay[l], sf.width, sf.height, &diag) != 0) {
                free(z);
                fprintf(stderr, "%s render: out of memory for layer %d\n", prog, l);
                status = EXIT_INPUT;
                goto done;
            }
            if (l == 0) {
                memcpy(lay[0].id, fr.id, n * sizeof *fr.id);
                memcpy(lay[0].t, fr.t, n * sizeof *fr.t);
            } else if ((nrays += count_hits(&lay[l - 1]), 0) ||
                       lt_render_peel(&sc, acc, &cam, &lay[l - 1], &lay[l], &diag) != 0) {
                free(z);
                fprintf(stderr, "%s render: %s\n", prog, diag.msg);
                status = EXIT_USAGE;
                goto done;
            }
            for (i = 0; i < n; i++)
                z[i] = lay[l].id[i] >= 0 ? (float)lay[l].t[i] : (float)INFINITY;
            snprintf(lname[l], sizeof lname[l], "layer%d.Z", l);
            ec[nc].name = lname[l];
            ec[nc].type = LT_EXR_FLOAT;
            ec[nc++].data = z;
        }
        memset(&im, 0, sizeof im);
        im.width = (int32_t)sf.width;
        im.height = (int32_t)sf.height;
        im.nchannels = nc;
        im.channels = ec;
        snprintf(path, sizeof path, "%s.exr", out);
        if (lt_exr_write(path, &im, &diag) != 0) {
            fprintf(stderr, "%s\n", diag.msg);
            status = EXIT_INPUT;
        } else if (!quiet) {
            printf("exr       %s (%d channels%s)\n", path, nc, layers > 1 ? ", depth peels" : "");
        }
        for (a = 8; a < nc; a++)
            free((void *)ec[a].data);
        if (status != 0)
            goto done;
    }
    nrays += n + nshadow;
    if (lt_meter_available()) {
        /* every ray of the render: primary packets, shadow packets, peels (and the build) */
        char title[1400], extra[256], *js;
        snprintf(title, sizeof title, "render %s %ux%u %s, %s, %d layer(s), shadows", sf.mesh,
                 sf.width, sf.height, np == LT_PATH_Q16 ? "q16" : "f32", structure, layers);
        if (!quiet)
            lt_meter_report_text(stdout, title, nrays);
        snprintf(extra, sizeof extra, "{\"primary_rays\": %zu, \"shadow_rays\": %u, \"peel_rays\": %llu}",
                 n, nshadow, (unsigned long long)(nrays - n - nshadow));
        js = lt_meter_report_json(title, nrays, extra);
        if (report != NULL) {
            if (js == NULL || write_atomic(report, js, &diag) != 0) {
                fprintf(stderr, "%s\n", js == NULL ? "render: out of memory for the report" : diag.msg);
                free(js);
                status = EXIT_INPUT;
                goto done;
            }
            if (!quiet)
                printf("report    %s\n", report);
        }
        free(js);
    }
    snprintf(path, sizeof path, "%s.png", out);
    if (lt_png_write(path, rgb, (int32_t)sf.width, (int32_t)sf.height, 3, 3 * sf.width,
                     &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        status = EXIT_INPUT;
        goto done;
    }
    {
        /* quick looks: depth (near bright), normals (0.5 + 0.5 n), ids (hashed colours) */
        double zmin = INFINITY, zmax = 0.0;
        static const char *const kinds[3] = {"depth", "normals", "ids"};
        int kk;
        for (i = 0; i < n; i++)
            if (fr.id[i] >= 0) {
                zmin = fmin(zmin, fr.t[i]);
                zmax = fmax(zmax, fr.t[i]);
            }
        for (kk = 0; kk < 3; kk++) {
            for (i = 0; i < n; i++) {
                uint8_t *px = &rgb[3 * i];
                if (fr.id[i] < 0) {
                    px[0] = px[1] = px[2] = 0;
                } else if (kk == 0) {
                    double v = zmax > zmin ? 1.0 - (fr.t[i] - zmin) / (zmax - zmin) : 1.0;
                    px[0] = px[1] = px[2] = (uint8_t)(40.0 + 215.0 * v);
                } else if (kk == 1) {
                    px[0] = (uint8_t)(127.5 + 127.0 * (double)ch[2][i]);
                    px[1] = (uint8_t)(127.5 + 127.0 * (double)ch[3][i]);
                    px[2] = (uint8_t)(127.5 + 127.0 * (double)ch[4][i]);
                } else {
                    uint32_t hsh = (uint32_t)fr.id[i] * 2654435761u;
                    px[0] = (uint8_t)(64 + (hsh >> 24) % 192);
                    px[1] = (uint8_t)(64 + (hsh >> 16) % 192);
                    px[2] = (uint8_t)(64 + (hsh >> 8) % 192);
                }
            }
            snprintf(path, sizeof path, "%s.%s.png", out, kinds[kk]);
            if (lt_png_write(path, rgb, (int32_t)sf.width, (int32_t)sf.height, 3, 3 * sf.width,
                             &diag) != 0) {
                fprintf(stderr, "%s\n", diag.msg);
                status = EXIT_INPUT;
                goto done;
            }
        }
    }
    if (!quiet)
        printf("png       %s.png (shaded), %s.depth.png, %s.normals.png, %s.ids.png; %u shadow "
               "rays, %u occluded\n",
               out, out, out, out, nshadow, nocc);
    if (json) {
        cJSON *o = cJSON_CreateObject(), *files = cJSON_AddArrayToObject(o, "files");
        static const char *const sfx[5] = {".exr", ".png", ".depth.png", ".normals.png", ".ids.png"};
        char *js;
        for (a = 0; a < 5; a++) {
            snprintf(path, sizeof path, "%s%s", out, sfx[a]);
            cJSON_AddItemToArray(files, cJSON_CreateString(path));
        }
        cJSON_AddStringToObject(o, "mesh", sf.mesh);
        cJSON_AddStringToObject(o, "structure", structure);
        cJSON_AddStringToObject(o, "path", np == LT_PATH_Q16 ? "q16" : "f32");
        cJSON_AddNumberToObject(o, "width", sf.width);
        cJSON_AddNumberToObject(o, "height", sf.height);
        cJSON_AddNumberToObject(o, "layers", layers);
        cJSON_AddNumberToObject(o, "shadow_rays", nshadow);
        cJSON_AddNumberToObject(o, "occluded", nocc);
        cJSON_AddNumberToObject(o, "rays", (double)nrays);
        if (lt_meter_available()) {
            lt_meter_totals_t tt;
            lt_meter_totals(&tt);
            cJSON_AddNumberToObject(o, "cycles", (double)tt.total_cycles);
            if (report != NULL)
                cJSON_AddStringToObject(o, "report", report);
        }
        js = cJSON_Print(o);
        if (js != NULL)
            puts(js);
        free(js);
        cJSON_Delete(o);
    }
done:
    for (a = 0; a < 10; a++)
        free(ch[a]);
    for (l = 0; l < 16; l++)
        if (lay[l].id != NULL)
            lt_frame_free(&lay[l]);
    free(occ);
    free(rgb);
    lt_accel_free(acc);
    if (fr.id != NULL)
        lt_frame_free(&fr);
    lt_scene_free(&sc);
    lt_mesh_free(&mesh);
    lt_meter_shutdown();
    return status;
}

/* ---- stream: the receiver is its own program (host/stream/lt_stream_main.c); hand over to it ---------- */

static int cmd_stream(int argc, char **argv)
{
    char path[1200];
    const char *slash = strrchr(argv[0], '/');
    char **nargv = calloc((size_t)argc + 1, sizeof *nargv);
    int i;
    if (nargv == NULL)
        return EXIT_INPUT;
    /* the CLI lives in build/sim or build/host; lt-stream in build/host */
    if (slash != NULL)
        snprintf(path, sizeof path, "%.*s/../host/lt-stream", (int)(slash - argv[0]), argv[0]);
    else
        snprintf(path, sizeof path, "lt-stream");
    nargv[0] = path;
    for (i = 2; i < argc; i++)
        nargv[i - 1] = argv[i];
    nargv[argc - 1] = NULL;
    execv(path, nargv);
    if (slash == NULL)
        execvp("lt-stream", nargv);
    fprintf(stderr, "%s stream: cannot run %s (build it with `make test-build`)\n", prog, path);
    free(nargv);
    return EXIT_INPUT;
}

/* ---- reproject: view synthesis from a depth EXR (host/cli/lt_reproject_cli.c) -------------------- */

static int cmd_reproject(int argc, char **argv)
{
    lt_rp_cli_hooks_t h;
    h.begin = progress_begin;
    h.progress = progress;
    h.end = progress_end;
    h.quiet = &quiet;
    h.write_text = write_atomic;
    return lt_rp_cli(argc, argv, prog, &h);
}

/* ---- machines: the machine models (sim/machines/<name>.def) ------------------------------- */

static const char *const op_names[] = {
#define LT_OP(name, unit, doc) #name,
#define LT_EV(name, doc)
#define LT_PH(name, doc)
#include "lt/lt_ops.def"
#undef LT_OP
#undef LT_EV
#undef LT_PH
};

static const char *const op_units[] = {
#define LT_OP(name, unit, doc) #unit,
#define LT_EV(name, doc)
#define LT_PH(name, doc)
#include "lt/lt_ops.def"
#undef LT_OP
#undef LT_EV
#undef LT_PH
};

/* "64:8:64 32 KiB, 3 cy" or "none" */
static void cache_text(char *buf, size_t n, const char *spec, uint32_t hit)
{
    unsigned sets, ways, line;
    char c;
    if (spec == NULL) {
        snprintf(buf, n, "none");
    } else if (sscanf(spec, "%u:%u:%u%c", &sets, &ways, &line, &c) == 3) {
        unsigned long long b = (unsigned long long)sets * ways * line;
        if (b >= 1024 && b % 1024 == 0)
            snprintf(buf, n, "%s %llu KiB, %u cy", spec, b / 1024, hit);
        else
            snprintf(buf, n, "%s %llu B, %u cy", spec, b, hit);
    } else {
        snprintf(buf, n, "%s, %u cy", spec, hit);
    }
}

static int cmd_machines(int argc, char **argv)
{
    int a, i, o, json = 0, ops = 0, nm;
    size_t wn = strlen("machine"), w1 = strlen("L1"), w2 = strlen("L2");
    const char *name;
    char c1[96], c2[96];
    lt_meter_machine_t m;
    for (a = 2; a < argc; a++) {
        if (strcmp(argv[a], "--help") == 0 || strcmp(argv[a], "-h") == 0) {
            printf("usage: %s machines [--ops] [--json]\n"
                   "The machine models of the cycle model, one per file sim/machines/<name>.def:\n"
                   "name, clock, lanes, caches (sets:ways:line, size, hit latency), memory\n"
                   "latency, description; --ops adds the price of every op class (latency/issue\n"
                   "cycles; issue is what is charged); --json prints all of it as JSON. The native\n"
                   "build knows the names only.\n",
                   prog);
            return 0;
        } else if (strcmp(argv[a], "--json") == 0) {
            json = 1;
        } else if (strcmp(argv[a], "--ops") == 0) {
            ops = 1;
        } else {
            fprintf(stderr, "%s machines: unknown option '%s'\n", prog, argv[a]);
            return EXIT_USAGE;
        }
    }
    for (nm = 0; lt_meter_machine_name(nm) != NULL; nm++)
        ;
    if (json) {
        cJSON *root = cJSON_CreateObject(), *arr;
        char *js;
        cJSON_AddStringToObject(root, "build", lt_meter_available() ? "simulator" : "native");
        arr = cJSON_AddArrayToObject(root, "machines");
        for (i = 0; i < nm; i++) {
            cJSON *x = cJSON_CreateObject(), *y;
            name = lt_meter_machine_name(i);
            cJSON_AddStringToObject(x, "name", name);
            if (lt_meter_machine_info(name, &m) == 0) {
                cJSON_AddStringToObject(x, "description", m.desc);
                cJSON_AddNumberToObject(x, "clock_mhz", m.clock_mhz);
                cJSON_AddNumberToObject(x, "lanes", m.lanes);
                y = cJSON_AddObjectToObject(x, "l1");
                cJSON_AddStringToObject(y, "spec", m.l1);
                cJSON_AddNumberToObject(y, "hit_cycles", m.l1_hit);
                if (m.l2 != NULL) {
                    y = cJSON_AddObjectToObject(x, "l2");
                    cJSON_AddStringToObject(y, "spec", m.l2);
                    cJSON_AddNumberToObject(y, "hit_cycles", m.l2_hit);
                } else {
                    cJSON_AddNullToObject(x, "l2");
                }
                cJSON_AddNumberToObject(x, "memory_cycles", m.mem);
                y = cJSON_AddObjectToObject(x, "ops");
                for (o = 0; o < LT_OP__COUNT; o++) {
                    cJSON *z = cJSON_AddObjectToObject(y, op_names[o]);
                    cJSON_AddNumberToObject(z, "latency", m.latency[o]);
                    cJSON_AddNumberToObject(z, "issue", m.issue[o]);
                }
            }
            cJSON_AddItemToArray(arr, x);
        }
        js = cJSON_Print(root);
        if (js != NULL)
            puts(js);
        free(js);
        cJSON_Delete(root);
        return js != NULL ? 0 : EXIT_INPUT;
    }
    if (!lt_meter_available()) {
        /* names only, one per line; where the rest is on stderr */
        for (i = 0; i < nm; i++)
            printf("%s\n", lt_meter_machine_name(i));
        fprintf(stderr, "%s machines: the native build has no cycle model; build/sim/lanetrace "
                        "machines prints clocks, caches and op prices\n", prog);
        return 0;
    }
    for (i = 0; i < nm; i++) {
        name = lt_meter_machine_name(i);
        (void)lt_meter_machine_info(name, &m);
        cache_text(c1, sizeof c1, m.l1, m.l1_hit);
        cache_text(c2, sizeof c2, m.l2, m.l2_hit);
        wn = strlen(name) > wn ? strlen(name) : wn;
        w1 = strlen(c1) > w1 ? strlen(c1) : w1;
        w2 = strlen(c2) > w2 ? strlen(c2) : w2;
    }
    printf("%-*s %9s %5s  %-*s  %-*s %7s  %s\n", (int)wn, "machine", "clock", "lanes", (int)w1,
           "L1", (int)w2, "L2", "memory", "description");
    for (i = 0; i < nm; i++) {
        char clk[32], mem[32];
        name = lt_meter_machine_name(i);
        (void)lt_meter_machine_info(name, &m);
        cache_text(c1, sizeof c1, m.l1, m.l1_hit);
        cache_text(c2, sizeof c2, m.l2, m.l2_hit);
        snprintf(clk, sizeof clk, "%u MHz", m.clock_mhz);
        snprintf(mem, sizeof mem, "%u cy", m.mem);
        printf("%-*s %9s %5u  %-*s  %-*s %7s  %s\n", (int)wn, name, clk, m.lanes, (int)w1, c1,
               (int)w2, c2, mem, m.desc);
    }
    if (!ops) {
        printf("(caches: sets:ways:line, size, load-to-use cycles of a hit; op prices: %s "
               "machines --ops)\n", prog);
        return 0;
    }
    printf("\nop prices, latency/issue cycles (a phase's cycles = sum of count x issue + memory "
           "stalls)\n");
    printf("%-10s %-7s", "op class", "unit");
    for (i = 0; i < nm; i++)
        printf(" %12s", lt_meter_machine_name(i));
    printf("\n");
    for (o = 0; o < LT_OP__COUNT; o++) {
        printf("%-10s %-7s", op_names[o], op_units[o]);
        for (i = 0; i < nm; i++) {
            char cell[32];
            (void)lt_meter_machine_info(lt_meter_machine_name(i), &m);
            snprintf(cell, sizeof cell, "%u/%u", m.latency[o], m.issue[o]);
            printf(" %12s", cell);
        }
        printf("\n");
    }
    return 0;
}

/* ---- main ----------------------------------------------------------------------------------- */

static void usage(FILE *f)
{
    fprintf(f,
            "usage: %s COMMAND [options]   (%s build)\n"
            "commands:\n"
            "  run [SCENE.json]   trace a scene; accuracy and (sim build) the cycle report\n"
            "  render [SCENE.json] --out PREFIX  images: depth, normals, ids, shaded (hard\n"
            "                     shadows), k-layer depth peels (EXR + PNG)\n"
            "  reproject --depth FILE.exr  a new view of a depth image (screen-space quadtree,\n"
            "                     inpainting; EXR + PNG + heatmaps; sim build: cycle report)\n"
            "  shadows --mesh FILE  soft shadows by multi-frusta and 16-ray packets, Table-1\n"
            "                     report (sim build: cycles per stage), images, reference\n"
            "  info FILE          describe a mesh or EXR file\n"
            "  stream [SOURCE]    receive a device's report frames (see lt-stream --help)\n"
            "  diff A.json B.json compare two JSON reports\n"
            "  machines [--ops]   the machine models: clock, lanes, caches, op prices (--json)\n"
            "  help               this text\n"
            "Every command takes --help. Exit codes: 0 ok, 1 input or runtime error, 2 usage.\n",
            prog, lt_meter_available() ? "simulator" : "native");
}

int main(int argc, char **argv)
{
    signal(SIGINT, on_signal);
    signal(SIGTERM, on_signal);
    if (argc < 2 || strcmp(argv[1], "help") == 0 || strcmp(argv[1], "--help") == 0 ||
        strcmp(argv[1], "-h") == 0) {
        usage(argc < 2 ? stderr : stdout);
        return argc < 2 ? EXIT_USAGE : 0;
    }
    if (strcmp(argv[1], "run") == 0)
        return cmd_run(argc, argv);
    if (strcmp(argv[1], "stream") == 0)
        return cmd_stream(argc, argv);
    if (strcmp(argv[1], "render") == 0)
        return cmd_render(argc, argv);
    if (strcmp(argv[1], "info") == 0)
        return cmd_info(argc, argv);
    if (strcmp(argv[1], "reproject") == 0)
        return cmd_reproject(argc, argv);
    if (strcmp(argv[1], "diff") == 0)
        return cmd_diff(argc, argv);
    if (strcmp(argv[1], "shadows") == 0)
        return lt_shadows_cli(argc, argv, prog);
    if (strcmp(argv[1], "machines") == 0)
        return cmd_machines(argc, argv);
    fprintf(stderr, "%s: unknown command '%s'\n", prog, argv[1]);
    usage(stderr);
    return EXIT_USAGE;
}
