/* lt_shadows_cli.c - `lanetrace shadows`: soft shadows of a quad area light with 16 samples per
 * pixel, by multi-frusta tracing (S-Frusta) and by 16-ray packets (S-Packet), after primary
 * visibility by 16-ray packets (P-Packet) and by primary frusta (P-Frusta; S-Frusta uses them as
 * the paper does, S-Packet the packets); shading, 4x4 discontinuity filter, 256-sample reference
 * and quality, PNGs, and the Table-1-style comparison of Benthin & Wald 2009 [Benthin09]. A
 * subcommand of both CLIs: build/sim/lanetrace shadows (every lane op charged to a machine model:
 * counts and cycles per stage) and build/host/lanetrace-native shadows (native timing). Exit codes:
 * 0 ok, 1 input or runtime error (including frusta != packet visibility), 2 usage. Host only;
 * docs/frusta.md.
 */
#include "render/lt_softshadow.h"
#include "cli/lt_cliutil.h"
#include "cli/lt_shadows_cli.h"
#include "lt_meter.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define EXIT_INPUT 1
#define EXIT_USAGE 2

/* "PROG shadows", the name messages start with */
static char who[256];

static void usage(const char *prog, FILE *f)
{
    fprintf(f,
            "usage: %s shadows --mesh PATH [options]\n"
            "  --res N            image N x N (default 128; multiples of 4 keep tiles full)\n"
            "  --num q16|f32      numeric path (default q16)\n"
            "  --leaf N           frusta BVH leaf size (max_leaf N, min_leaf N/2; default 8)\n"
            "  --cull LIST        shadow culling: any of b (back-face), c (corner rays), r (CR),\n"
            "                     or none (default bcr)\n"
            "  --prim packet|frusta|both  primary method(s) (default both: P-Packet feeds\n"
            "                     S-Packet and P-Frusta S-Frusta; with one, both S rows use it)\n"
            "  --pcull LIST       primary culling: b (back faces, both methods), c (corner rays),\n"
            "                     r (corner rays through the on-image pixels), or none\n"
            "                     (default bcr)\n"
            "  --qmc lp|hammersley  sample set (default lp)\n"
            "  --light X,Y,Z,S    square light (normal -y) centred at X,Y,Z of side S, file units\n"
            "  --eye X,Y,Z --target X,Y,Z --fov DEG   camera (file units)\n"
            "  --ground | --no-ground   add a ground quad below the mesh (default: per scene)\n"
            "  --depth-rel R --cos-min C  filter thresholds (default 0.05, 0.9)\n"
            "  --filter irradiance|visibility  filter E = G V (default, as Benthin & Wald\n"
            "                     2009 do) or V alone\n"
            "  --tol T            penumbra tolerance on irradiance (default 0.05)\n"
            "  --no-ref           skip the 256-sample reference and the quality metrics\n"
            "  --png PATH         filtered image; --raw-png PATH unfiltered; --ref-png PATH reference\n"
            "  --only frusta|packet  run one shadow method (default both, compared)\n"
            "  --machine NAME     sim builds: machine model (%s; default lrb16)\n"
            "  --report           sim builds: the full cycle report of each shadow stage and the filter\n"
            "  -q                 only the result lines\n",
            prog, lt_meter_machine_names());
}

static int parse3(const char *s, double v[3], double *extra)
{
    int n = extra != NULL ? sscanf(s, "%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2], extra)
                          : sscanf(s, "%lf,%lf,%lf", &v[0], &v[1], &v[2]);
    return n == (extra != NULL ? 4 : 3) ? 0 : -1;
}

/* Counters of one stage (sim builds; zeros natively). */
typedef struct stage {
    const char *name;
    double seconds;
    uint64_t ev[LT_EV__COUNT];
    uint64_t cyc[LT_PH__COUNT];
    uint64_t cycles;
} stage_t;

static void stage_begin(void) { lt_meter_reset(); }

static void stage_end(stage_t *st, const char *name, double t0)
{
    memset(st, 0, sizeof *st);
    st->name = name;
    st->seconds = lt_now_s() - t0;
    if (lt_meter_available()) {
        lt_meter_totals_t t;
        lt_meter_totals(&t);
        memcpy(st->ev, t.events, sizeof st->ev);
        memcpy(st->cyc, t.cycles, sizeof st->cyc);
        st->cycles = t.total_cycles;
    }
}

static void stage_add(stage_t *d, const stage_t *a)
{
    int e, p;
    d->seconds += a->seconds;
    for (e = 0; e < LT_EV__COUNT; e++)
        d->ev[e] += a->ev[e];
    for (p = 0; p < LT_PH__COUNT; p++)
        d->cyc[p] += a->cyc[p];
    d->cycles += a->cycles;
}

static double ratio(uint64_t a, uint64_t b) { return b != 0 ? (double)a / (double)b : 0.0; }

static double k_(uint64_t v) { return (double)v / 1000.0; }

int lt_shadows_cli(int argc, char **argv, const char *prog)
{
    const char *mesh_path = NULL, *png = NULL, *raw_png = NULL, *ref_png = NULL, *only = NULL;
    const char *machine = "lrb16";
    uint32_t res = 128;
    int quiet = 0, report = 0, no_ref = 0, ground = -1, i, have_light = 0, have_eye = 0, have_target = 0;
    double light_c[3] = {0, 0, 0}, light_s = 0, eye[3], target[3], fov = 60, tol = 0.05;
    double up[3] = {0, 1, 0};
    lt_ss_opts_t o;
    int num_f32 = 0, cull_set = 0, filter_vis = 0, run_pp = 1, run_pf = 1;
    uint32_t leaf = 8, flags = LT_FRUSTA_BACKFACE | LT_FRUSTA_CORNER | LT_FRUSTA_CR;
    uint32_t pflags = LT_FRUSTA_BACKFACE | LT_FRUSTA_CORNER | LT_FRUSTA_CR;
    uint32_t hash_pp = 0, hash_pf = 0;
    lt_qmc_kind_t qmc = LT_QMC_LP;
    double depth_rel = 0.05, cos_min = 0.9;
    lt_ss_view_t view;
    const lt_ss_view_t *pre = NULL;
    lt_mesh_t m;
    lt_scene_t sc;
    lt_camera_t cam;
    lt_ss_light_t light;
    lt_softshadow_t *ss;
    lt_ss_counts_t cnt;
    lt_diag_t diag;
    stage_t sp, spf, sshp, sshf, sshade, sfilt, tot_p, tot_f, tot_fo;
    double t0;
    int run_fr, run_pk, rc = 0;

    snprintf(who, sizeof who, "%s shadows", prog);
    for (i = 2; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
#define NEED()                                                                                     \
    do {                                                                                           \
        if (v == NULL) {                                                                           \
            fprintf(stderr, "%s: %s needs a value\n", who, a);                                \
            return EXIT_USAGE;                                                                     \
        }                                                                                          \
        i++;                                                                                       \
    } while (0)
        if (strcmp(a, "--mesh") == 0) {
            NEED();
            mesh_path = v;
        } else if (strcmp(a, "--res") == 0) {
            char *end;
            unsigned long r;
            NEED();
            r = strtoul(v, &end, 10);
            if (*end != '\0' || r < 4 || r > 8192) {
                fprintf(stderr, "%s: --res %s: need 4..8192\n", who, v);
                return EXIT_USAGE;
            }
            res = (uint32_t)r;
        } else if (strcmp(a, "--num") == 0) {
            NEED();
            if (strcmp(v, "q16") != 0 && strcmp(v, "f32") != 0) {
                fprintf(stderr, "%s: --num %s: need q16 or f32\n", who, v);
                return EXIT_USAGE;
            }
            num_f32 = strcmp(v, "f32") == 0;
        } else if (strcmp(a, "--leaf") == 0) {
            char *end;
            unsigned long l;
            NEED();
            l = strtoul(v, &end, 10);
            if (*end != '\0' || l < 1 || l > LT_BVH_MAX_LEAF) {
                fprintf(stderr, "%s: --leaf %s: need 1..%d (LT_BVH_MAX_LEAF)\n", who, v,
                        LT_BVH_MAX_LEAF);
                return EXIT_USAGE;
            }
            leaf = (uint32_t)l;
        } else if (strcmp(a, "--cull") == 0) {
            const char *c;
            NEED();
            flags = 0;
            cull_set = 1;
            if (strcmp(v, "none") != 0)
                for (c = v; *c != '\0'; c++) {
                    if (*c == 'b')
                        flags |= LT_FRUSTA_BACKFACE;
                    else if (*c == 'c')
                        flags |= LT_FRUSTA_CORNER;
                    else if (*c == 'r')
                        flags |= LT_FRUSTA_CR;
                    else {
                        fprintf(stderr, "%s: --cull %s: letters b, c, r or none\n", who,
                                v);
                        return EXIT_USAGE;
                    }
                }
        } else if (strcmp(a, "--pcull") == 0) {
            const char *c;
            NEED();
            pflags = 0;
            if (strcmp(v, "none") != 0)
                for (c = v; *c != '\0'; c++) {
                    if (*c == 'b')
                        pflags |= LT_FRUSTA_BACKFACE;
                    else if (*c == 'c')
                        pflags |= LT_FRUSTA_CORNER;
                    else if (*c == 'r')
                        pflags |= LT_FRUSTA_CR;
                    else {
                        fprintf(stderr, "%s: --pcull %s: letters b, c, r or none\n", who,
                                v);
                        return EXIT_USAGE;
                    }
                }
        } else if (strcmp(a, "--prim") == 0) {
            NEED();
            if (strcmp(v, "packet") != 0 && strcmp(v, "frusta") != 0 && strcmp(v, "both") != 0) {
                fprintf(stderr, "%s: --prim %s: need packet, frusta or both\n", who, v);
                return EXIT_USAGE;
            }
            run_pp = strcmp(v, "frusta") != 0;
            run_pf = strcmp(v, "packet") != 0;
        } else if (strcmp(a, "--qmc") == 0) {
            NEED();
            if (strcmp(v, "lp") == 0)
                qmc = LT_QMC_LP;
            else if (strcmp(v, "hammersley") == 0)
                qmc = LT_QMC_HAMMERSLEY;
            else {
                fprintf(stderr, "%s: --qmc %s: need lp or hammersley\n", who, v);
                return EXIT_USAGE;
            }
        } else if (strcmp(a, "--light") == 0) {
            NEED();
            if (parse3(v, light_c, &light_s) != 0 || !(light_s >= 0.0)) {
                fprintf(stderr, "%s: --light %s: need X,Y,Z,SIZE (size >= 0)\n", who, v);
                return EXIT_USAGE;
            }
            have_light = 1;
        } else if (strcmp(a, "--eye") == 0 || strcmp(a, "--target") == 0) {
            int is_eye = strcmp(a, "--eye") == 0;
            NEED();
            if (parse3(v, is_eye ? eye : target, NULL) != 0) {
                fprintf(stderr, "%s: %s %s: need X,Y,Z\n", who, a, v);
                return EXIT_USAGE;
            }
            if (is_eye)
                have_eye = 1;
            else
                have_target = 1;
        } else if (strcmp(a, "--fov") == 0) {
            NEED();
            fov = atof(v);
            if (!(fov > 1.0 && fov < 179.0)) {
                fprintf(stderr, "%s: --fov %s: need (1, 179)\n", who, v);
                return EXIT_USAGE;
            }
        } else if (strcmp(a, "--ground") == 0) {
            ground = 1;
        } else if (strcmp(a, "--no-ground") == 0) {
            ground = 0;
        } else if (strcmp(a, "--depth-rel") == 0) {
            NEED();
            depth_rel = atof(v);
            if (!(depth_rel >= 0.0 && depth_rel < 1000.0)) {
                fprintf(stderr, "%s: --depth-rel %s: need [0, 1000)\n", who, v);
                return EXIT_USAGE;
            }
        } else if (strcmp(a, "--cos-min") == 0) {
            NEED();
            cos_min = atof(v);
            if (!(cos_min >= -1.0 && cos_min <= 1.0)) {
                fprintf(stderr, "%s: --cos-min %s: need [-1, 1]\n", who, v);
                return EXIT_USAGE;
            }
        } else if (strcmp(a, "--filter") == 0) {
            NEED();
            if (strcmp(v, "irradiance") != 0 && strcmp(v, "visibility") != 0) {
                fprintf(stderr, "%s: --filter %s: need irradiance or visibility\n", who,
                        v);
                return EXIT_USAGE;
            }
            filter_vis = strcmp(v, "visibility") == 0;
        } else if (strcmp(a, "--tol") == 0) {
            NEED();
            tol = atof(v);
        } else if (strcmp(a, "--no-ref") == 0) {
            no_ref = 1;
        } else if (strcmp(a, "--png") == 0) {
            NEED();
            png = v;
        } else if (strcmp(a, "--raw-png") == 0) {
            NEED();
            raw_png = v;
        } else if (strcmp(a, "--ref-png") == 0) {
            NEED();
            ref_png = v;
        } else if (strcmp(a, "--only") == 0) {
            NEED();
            if (strcmp(v, "frusta") != 0 && strcmp(v, "packet") != 0) {
                fprintf(stderr, "%s: --only %s: need frusta or packet\n", who, v);
                return EXIT_USAGE;
            }
            only = v;
        } else if (strcmp(a, "--machine") == 0) {
            NEED();
            machine = v;
        } else if (strcmp(a, "--report") == 0) {
            report = 1;
        } else if (strcmp(a, "-q") == 0) {
            quiet = 1;
        } else if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            usage(prog, stdout);
            return 0;
        } else {
            fprintf(stderr, "%s: unknown option %s\n", who, a);
            usage(prog, stderr);
            return EXIT_USAGE;
        }
#undef NEED
    }
    if (mesh_path == NULL) {
        usage(prog, stderr);
        return EXIT_USAGE;
    }
    (void)cull_set;
    (void)report;
    if (lt_ss_view_for(mesh_path, &view))
        pre = &view;
    if (lt_mesh_load(mesh_path, &m, &diag) != 0) {
        fprintf(stderr, "%s: %s\n", who, diag.msg);
        return EXIT_INPUT;
    }
    if (ground < 0)
        ground = pre != NULL ? pre->ground : 1;
    if (!have_light) {
        if (pre != NULL) {
            memcpy(light_c, pre->light, sizeof light_c);
            light_s = pre->size;
        } else {
            /* above the bounding box, a tenth of its x extent wide */
            light_c[0] = 0.5 * (m.lo[0] + m.hi[0]);
            light_c[1] = m.hi[1] + (m.hi[1] - m.lo[1]);
            light_c[2] = 0.5 * (m.lo[2] + m.hi[2]);
            light_s = 0.2 * (m.hi[0] - m.lo[0]);
        }
    }
    if (ground && lt_ss_add_ground(&m, 0.6, &diag) != 0) {
        fprintf(stderr, "%s: %s\n", who, diag.msg);
        lt_mesh_free(&m);
        return EXIT_INPUT;
    }
    if (lt_scene_prepare(&m, &sc, &diag) != 0) {
        fprintf(stderr, "%s: %s: %s\n", who, mesh_path, diag.msg);
        lt_mesh_free(&m);
        return EXIT_INPUT;
    }
    if (have_eye || (pre != NULL && pre->has_camera)) {
        if (!have_eye)
            memcpy(eye, pre->eye, sizeof eye);
        if (!have_target)
            memcpy(target, pre != NULL && pre->has_camera ? pre->target : sc.center,
                   sizeof target);
        if (pre != NULL && pre->has_camera && fov == 60)
            fov = pre->fov;
        if (lt_camera_look(&sc, eye, target, up, fov, res, res, &cam, &diag) != 0) {
            fprintf(stderr, "%s: %s\n", who, diag.msg);
            rc = EXIT_INPUT;
            goto out_scene;
        }
    } else {
        lt_camera_default(&sc, res, res, &cam);
    }
    if (lt_ss_light_square(&sc, light_c, light_s, &light, &diag) != 0) {
        fprintf(stderr, "%s: %s\n", who, diag.msg);
        rc = EXIT_INPUT;
        goto out_scene;
    }
    if (!lt_meter_machine_known(machine)) {
        fprintf(stderr, "%s: --machine %s: unknown machine (known: %s)\n", who, machine,
                lt_meter_machine_names());
        rc = EXIT_USAGE;
        goto out_scene;
    }
    if (lt_meter_init(machine, NULL, NULL, &diag) != 0) {
        fprintf(stderr, "%s: %s\n", who, diag.msg);
        rc = EXIT_INPUT;
        goto out_scene;
    }
    lt_ss_opts_default(&sc, &o);
    o.path = num_f32 ? LT_PATH_F32 : LT_PATH_Q16;
    o.leaf = leaf;
    o.flags = flags;
    o.qmc = qmc;
    o.depth_rel = depth_rel;
    o.cos_min = cos_min;
    o.filter_vis = filter_vis;
    o.pflags = pflags;
    ss = lt_ss_create(&sc, &cam, &light, &o, &diag);
    if (ss == NULL) {
        fprintf(stderr, "%s: %s\n", who, diag.msg);
        rc = EXIT_INPUT;
        goto out_scene;
    }
    run_fr = only == NULL || strcmp(only, "frusta") == 0;
    run_pk = only == NULL || strcmp(only, "packet") == 0;
    if (!quiet)
        printf("scene     %s: %u triangles%s, radius %.1f units (scale %g), %ux%u, %s, light "
               "%.3g x %.3g units at (%.1f, %.1f, %.1f), frusta leaf %u, culling %s%s%s%s, "
               "primary culling %s%s%s%s, %s samples\n",
               mesh_path, sc.ntris, ground ? " (with ground quad)" : "", sc.radius, sc.scale, res,
               res, num_f32 ? "float32" : "s15.16", light.eu[0], light.ev[2],
               light.c[0] + 0.5 * light.eu[0], light.c[1], light.c[2] + 0.5 * light.ev[2], leaf,
               flags == 0 ? "none" : "", flags & LT_FRUSTA_BACKFACE ? "b" : "",
               flags & LT_FRUSTA_CORNER ? "c" : "", flags & LT_FRUSTA_CR ? "r" : "",
               pflags == 0 ? "none" : "", pflags & LT_FRUSTA_BACKFACE ? "b" : "",
               pflags & LT_FRUSTA_CORNER ? "c" : "", pflags & LT_FRUSTA_CR ? "r" : "",
               qmc == LT_QMC_LP ? "Larcher-Pillichshammer" : "Hammersley");
    /* stages, each measured alone: P-Packet then S-Packet on its hit points, P-Frusta then
     * S-Frusta on its hit points (the same points when the two primary methods agree) */
    memset(&sp, 0, sizeof sp);
    memset(&spf, 0, sizeof spf);
    memset(&sshp, 0, sizeof sshp);
    memset(&sshf, 0, sizeof sshf);
    if (run_pp) {
        stage_begin();
        t0 = lt_now_s();
        lt_ss_primary(ss);
        stage_end(&sp, "P-Packet (+shad)", t0);
        hash_pp = lt_ss_primary_hash(ss);
        if (report)
            lt_meter_report_text(stdout, "P-Packet primary stage", 0);
    }
    for (i = 0; i < 2; i++) {
        /* S-Packet right after P-Packet (or, without P-Packet, after P-Frusta) */
        if (run_pk && (i == 0) == (run_pp != 0)) {
            stage_begin();
            t0 = lt_now_s();
            lt_ss_shadows_packet(ss);
            stage_end(&sshp, "S-Packet shadows", t0);
            if (report)
                lt_meter_report_text(stdout, "S-Packet shadow stage", 0);
        }
        if (i == 0 && run_pf) {
            stage_begin();
            t0 = lt_now_s();
            lt_ss_primary_frusta(ss);
            stage_end(&spf, "P-Frusta (+shad)", t0);
            hash_pf = lt_ss_primary_hash(ss);
            if (report)
                lt_meter_report_text(stdout, "P-Frusta primary stage", 0);
        }
    }
    if (run_fr) {
        stage_begin();
        t0 = lt_now_s();
        lt_ss_shadows_frusta(ss);
        stage_end(&sshf, "S-Frusta shadows", t0);
        if (report)
            lt_meter_report_text(stdout, "S-Frusta shadow stage", 0);
    }
    stage_begin();
    t0 = lt_now_s();
    lt_ss_shade(ss, run_fr ? LT_SS_FRUSTA : LT_SS_PACKET);
    stage_end(&sshade, "shade", t0);
    stage_begin();
    t0 = lt_now_s();
    lt_ss_filter(ss);
    stage_end(&sfilt, "filter", t0);
    if (report)
        lt_meter_report_text(stdout, "filter stage", 0);
    lt_ss_counts(ss, &cnt);

    printf("rays      %llu primary (%llu hits), %llu lit pixels x 16 = %llu shadow rays, %llu "
           "occluded, %llu penumbra pixels\n",
           (unsigned long long)cnt.primary_rays, (unsigned long long)cnt.hits,
           (unsigned long long)cnt.lit, (unsigned long long)cnt.shadow_rays,
           (unsigned long long)cnt.occluded, (unsigned long long)cnt.partial);
    if (run_pp && run_pf) {
        printf("check     P-Frusta = P-Packet closest hit on %llu of %llu pixels (%llu differ); "
               "primary hash P-Packet %08x, P-Frusta %08x\n",
               (unsigned long long)(cnt.pixels - cnt.prim_mismatch), (unsigned long long)cnt.pixels,
               (unsigned long long)cnt.prim_mismatch, hash_pp, hash_pf);
        if (cnt.prim_mismatch != 0) {
            lt_ss_audit_t au;
            lt_ss_primary_audit(ss, &au);
            printf("audit     %llu differing primary rays re-traced by brute force: %llu explained "
                   "by spurious kernel hits (not genuine: off the triangle's padded box or t), %llu "
                   "errors; brute force = P-Packet on %llu, = P-Frusta on %llu\n",
                   (unsigned long long)au.samples, (unsigned long long)au.spurious,
                   (unsigned long long)au.errors, (unsigned long long)au.ref[0],
                   (unsigned long long)au.ref[1]);
            if (au.errors != 0)
                rc = EXIT_INPUT;
        }
    }
    if (run_fr && run_pk) {
        printf("check     frusta = packet visibility on %llu of %llu pixels (%llu differ)",
               (unsigned long long)(cnt.pixels - cnt.shadow_skipped - cnt.mismatch),
               (unsigned long long)(cnt.pixels - cnt.shadow_skipped),
               (unsigned long long)cnt.mismatch);
        if (cnt.shadow_skipped != 0)
            printf("; %llu pixels whose primary hits differ left out",
                   (unsigned long long)cnt.shadow_skipped);
        printf("\n");
        if (cnt.mismatch != 0) {
            lt_ss_audit_t au;
            lt_ss_audit(ss, &au);
            printf("audit     %llu differing samples re-traced by brute force: %llu explained by "
                   "spurious kernel hits of grazing rays (off the triangle's padded box), %llu "
                   "errors\n", (unsigned long long)au.samples, (unsigned long long)au.spurious,
                   (unsigned long long)au.errors);
            if (au.errors != 0)
                rc = EXIT_INPUT;
        }
    }
    printf("result    %s hash %08x\n", num_f32 ? "f32" : "q16", lt_ss_hash(ss));

    /* totals: the paper's S rows include primary rays, shading and filtering; S-Packet on
     * P-Packet primaries, S-Frusta on P-Frusta primaries (each on the other when only one ran),
     * and S-Frusta on P-Packet primaries (the previous table's combination) */
    tot_p = run_pp ? sp : spf;
    stage_add(&tot_p, &sshp);
    stage_add(&tot_p, &sshade);
    stage_add(&tot_p, &sfilt);
    tot_f = run_pf ? spf : sp;
    stage_add(&tot_f, &sshf);
    stage_add(&tot_f, &sshade);
    stage_add(&tot_f, &sfilt);
    tot_fo = sp;
    stage_add(&tot_fo, &sshf);
    stage_add(&tot_fo, &sshade);
    stage_add(&tot_fo, &sfilt);
    if (lt_meter_available()) {
        lt_meter_machine_t mm;
        double mhz;
        const stage_t *rows[5];
        const char *names[5] = {"P-Packet (+shad)", "P-Frusta (+shad)", "S-Packet", "S-Frusta",
                                "S-Frusta/P-Packet"};
        int r, show[5];
        (void)lt_meter_machine_info(machine, &mm);
        mhz = (double)mm.clock_mhz;
        rows[0] = &sp;
        rows[1] = &spf;
        rows[2] = &tot_p;
        rows[3] = &tot_f;
        rows[4] = &tot_fo;
        show[0] = run_pp;
        show[1] = run_pf;
        show[2] = run_pk;
        show[3] = run_fr;
        show[4] = run_fr && run_pp && run_pf;
        printf("\nTable 1 (simulated, %s at %.0f MHz, one core; P rows: cycles without shading "
               "(with it), as the paper's; S rows include primary rays, shading and filtering as "
               "in the paper)\n", mm.name, mhz);
        printf("%-18s %21s %10s %10s %22s %8s  %s\n", "", "#tris (+culling)", "#AABB", "#isec",
               "cycles", "lanes", "cycles: setup/traverse/intersect/shade/filter");
        for (r = 0; r < 5; r++) {
            const stage_t *st = rows[r];
            char cyc[64];
            if (!show[r])
                continue;
            if (r < 2)
                snprintf(cyc, sizeof cyc, "%.2fM (%.2fM)",
                         (double)(st->cycles - st->cyc[LT_PH_SHADE]) / 1e6,
                         (double)st->cycles / 1e6);
            else
                snprintf(cyc, sizeof cyc, "%.2fM", (double)st->cycles / 1e6);
            printf("%-18s %9.0fK / %8.0fK %9.0fK %9.0fK %22s %7.1f%%  %.1fM/%.1fM/%.1fM/%.1fM/"
                   "%.1fM\n",
                   names[r], k_(st->ev[LT_EV_TRI_FETCH]), k_(st->ev[LT_EV_TRI_KEPT]),
                   k_(st->ev[LT_EV_AABB]), k_(st->ev[LT_EV_TRIS]), cyc,
                   100.0 * ratio(st->ev[LT_EV_LANES_ON], 16u * st->ev[LT_EV_LANE_OPS]),
                   (double)st->cyc[LT_PH_SETUP] / 1e6, (double)st->cyc[LT_PH_TRAVERSE] / 1e6,
                   (double)st->cyc[LT_PH_INTERSECT] / 1e6, (double)st->cyc[LT_PH_SHADE] / 1e6,
                   (double)st->cyc[LT_PH_FILTER] / 1e6);
            if (r == 1 && run_pp) {
                char red[64];
                snprintf(red, sizeof red, "%.2fx (%.2fx)",
                         ratio(sp.cycles - sp.cyc[LT_PH_SHADE], spf.cycles - spf.cyc[LT_PH_SHADE]),
                         ratio(sp.cycles, spf.cycles));
                printf("%-18s %8.2fx / %7.2fx %9.2fx %9.2fx %22s            (paper: 1.45-2.3x / "
                       "2.98-9.5x, 11.8-21x, 1.67-3.1x, 3.42-7.83x (2.98-6.09x))\n",
                       "P Reduction", ratio(sp.ev[LT_EV_TRI_FETCH], spf.ev[LT_EV_TRI_FETCH]),
                       ratio(sp.ev[LT_EV_TRI_KEPT], spf.ev[LT_EV_TRI_KEPT]),
                       ratio(sp.ev[LT_EV_AABB], spf.ev[LT_EV_AABB]),
                       ratio(sp.ev[LT_EV_TRIS], spf.ev[LT_EV_TRIS]), red);
            }
            if ((r == 3 && run_pk) || (r == 4 && run_pk)) {
                const stage_t *fr = rows[r];
                printf("%-18s %8.2fx / %7.2fx %9.2fx %9.2fx %21.2fx            %s\n",
                       r == 3 ? "S Reduction" : "  reduction", ratio(tot_p.ev[LT_EV_TRI_FETCH],
                                                                     fr->ev[LT_EV_TRI_FETCH]),
                       ratio(tot_p.ev[LT_EV_TRI_KEPT], fr->ev[LT_EV_TRI_KEPT]),
                       ratio(tot_p.ev[LT_EV_AABB], fr->ev[LT_EV_AABB]),
                       ratio(tot_p.ev[LT_EV_TRIS], fr->ev[LT_EV_TRIS]),
                       ratio(tot_p.cycles, fr->cycles),
                       r == 3 ? "(paper: 1.89-3.67x / 4.96-10.06x, 14.1-23.8x, 1.01-1.44x, "
                                "3.94-6.11x)"
                              : "(S-Frusta on P-Packet primaries, the previous combination)");
            }
        }
        if (run_pk && run_fr)
            printf("%-18s %8.2fx / %7.2fx %9.2fx %9.2fx %21.2fx            (shadow stage alone: "
                   "S-Packet %.2fM vs S-Frusta %.2fM cycles)\n",
                   "S shadows only:", ratio(sshp.ev[LT_EV_TRI_FETCH], sshf.ev[LT_EV_TRI_FETCH]),
                   ratio(sshp.ev[LT_EV_TRI_KEPT], sshf.ev[LT_EV_TRI_KEPT]),
                   ratio(sshp.ev[LT_EV_AABB], sshf.ev[LT_EV_AABB]),
                   ratio(sshp.ev[LT_EV_TRIS], sshf.ev[LT_EV_TRIS]), ratio(sshp.cycles, sshf.cycles),
                   (double)sshp.cycles / 1e6, (double)sshf.cycles / 1e6);
        if (run_pk && run_fr)
            printf("why       fewer cycles saved than the paper: the s15.16 kernels keep products "
                   "in int64 (VMUL/VMULW cost 2 on lrb16), so MFT's extra intersection and culling "
                   "work is dearer than in float (try --num f32); both S rows carry the same "
                   "shade and filter cycles; frusta wider than the occluders' triangles "
                   "(large lights, fine meshes) cull little (docs/frusta.md)\n");
        printf("stages    P-Packet %.2fM, P-Frusta %.2fM, shade %.2fM, filter %.2fM cycles (%.1f "
               "cycles/pixel); culled pairs: P-Packet back-face %.0fK; P-Frusta back-face %.0fK, "
               "corner %.0fK; S-Packet back-face %.0fK; S-Frusta back-face %.0fK, corner %.0fK\n",
               (double)sp.cycles / 1e6, (double)spf.cycles / 1e6, (double)sshade.cycles / 1e6,
               (double)sfilt.cycles / 1e6, ratio(sfilt.cycles, cnt.pixels),
               k_(sp.ev[LT_EV_CULL_BACK]), k_(spf.ev[LT_EV_CULL_BACK]),
               k_(spf.ev[LT_EV_CULL_CORNER]), k_(sshp.ev[LT_EV_CULL_BACK]),
               k_(sshf.ev[LT_EV_CULL_BACK]), k_(sshf.ev[LT_EV_CULL_CORNER]));
        if (run_pp || run_pf)
            printf("speed     primary rays per simulated %.0f MHz core: P-Packet %.1f Mrays/s "
                   "(%.1f with shading), P-Frusta %.1f Mrays/s (%.1f with shading)\n", mhz,
                   ratio(cnt.primary_rays, sp.cycles - sp.cyc[LT_PH_SHADE]) * mhz,
                   ratio(cnt.primary_rays, sp.cycles) * mhz,
                   ratio(cnt.primary_rays, spf.cycles - spf.cyc[LT_PH_SHADE]) * mhz,
                   ratio(cnt.primary_rays, spf.cycles) * mhz);
        if (run_fr)
            printf("speed     S-Frusta: %.1f Mrays/s per simulated %.0f MHz core (primary + shadow "
                   "rays over all stages); shadow stage alone %.1f Mrays/s\n",
                   ratio(cnt.primary_rays + cnt.shadow_rays, tot_f.cycles) * mhz,
                   mhz, ratio(cnt.shadow_rays, sshf.cycles) * mhz);
        if (run_pk)
            printf("speed     S-Packet: %.1f Mrays/s per simulated core; shadow stage alone "
                   "%.1f Mrays/s\n",
                   ratio(cnt.primary_rays + cnt.shadow_rays, tot_p.cycles) * mhz,
                   ratio(cnt.shadow_rays, sshp.cycles) * mhz);
    } else {
        if (run_pp)
            printf("native    P-Packet %.3f s (%.2f Mrays/s with shading)", sp.seconds,
                   (double)cnt.primary_rays / sp.seconds / 1e6);
        if (run_pf)
            printf("%s P-Frusta %.3f s (%.2f Mrays/s with shading)", run_pp ? "," : "native   ",
                   spf.seconds, (double)cnt.primary_rays / spf.seconds / 1e6);
        if (run_pk)
            printf(", S-Packet shadows %.3f s (%.2f Mrays/s)", sshp.seconds,
                   (double)cnt.shadow_rays / sshp.seconds / 1e6);
        if (run_fr)
            printf(", S-Frusta shadows %.3f s (%.2f Mrays/s)", sshf.seconds,
                   (double)cnt.shadow_rays / sshf.seconds / 1e6);
        printf(", shade %.3f s, filter %.3f s (one thread)\n", sshade.seconds, sfilt.seconds);
        if (run_pk && run_fr)
            printf("native    S-Frusta / S-Packet shadow speed-up %.2fx\n",
                   sshp.seconds / sshf.seconds);
        if (run_pp && run_pf)
            printf("native    P-Frusta / P-Packet primary speed-up %.2fx (with shading)\n",
                   sp.seconds / spf.seconds);
    }
    if (!no_ref) {
        lt_ss_quality_t q;
        t0 = lt_now_s();
        lt_ss_reference(ss, NULL);
        lt_ss_quality(ss, tol, &q);
        printf("quality   vs 256 samples/pixel (%.1f s): PSNR filtered %.2f dB, unfiltered 16 spp "
               "%.2f dB, reference through the same filter %.2f dB, filtered vs filtered reference "
               "%.2f dB; penumbra pixels %llu, within %.3g: %.1f%% filtered, %.1f%% unfiltered\n",
               lt_now_s() - t0, q.psnr_filtered, q.psnr_raw, q.psnr_filtered_ref,
               q.psnr_vs_filtered_ref,
               (unsigned long long)q.penumbra, q.tol, 100.0 * ratio(q.penumbra_ok, q.penumbra),
               100.0 * ratio(q.penumbra_raw_ok, q.penumbra));
        if (ref_png != NULL && lt_ss_write_png(ss, ref_png, 2, &diag) != 0) {
            fprintf(stderr, "%s: %s\n", who, diag.msg);
            rc = EXIT_INPUT;
        }
    }
    if (png != NULL && lt_ss_write_png(ss, png, 0, &diag) != 0) {
        fprintf(stderr, "%s: %s\n", who, diag.msg);
        rc = EXIT_INPUT;
    }
    if (raw_png != NULL && lt_ss_write_png(ss, raw_png, 1, &diag) != 0) {
        fprintf(stderr, "%s: %s\n", who, diag.msg);
        rc = EXIT_INPUT;
    }
    lt_ss_free(ss);
out_scene:
    lt_scene_free(&sc);
    lt_mesh_free(&m);
    return rc;
}
