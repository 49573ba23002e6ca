/* lt_pack_cli.c - `lanetrace pack`: a mesh or scene file made into a scene blob for a firmware
 * target (firmware/apps/lt_sblob.h: s15.16 triangles, their BVH, an integer camera, a point
 * light), and the blob's trace on the host: the same tile lines a target prints, for a bit-exact
 * comparison (docs/firmware.md, "Scene blobs"). Host only.
 */
#include "cli/lt_pack_cli.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli/lt_opt.h"
#include "io/lt_diag.h"
#include "io/lt_mesh.h"
#include "io/lt_scenefile.h"
#include "io/lt_tmpfiles.h"
#include "lt_sblob.h"
#include "render/lt_scene.h"

#define EXIT_INPUT 1
#define EXIT_USAGE 2

typedef struct pack {
    const char *scene_path, *mesh_over, *out, *in;
    uint32_t wh[2];
    double lf[3];
    int seen_res, seen_light, leaf, no_shadows, trace, npos, isect;
    lt_scenefile_t sf;
    lt_mesh_t mesh;
    lt_scene_t sc;
    lt_camera_t cam;
    double light[3]; /* scaled units */
    uint8_t *blob;
    size_t bytes;
} pack_t;

static const char *who_g = "lanetrace pack";
static const char *const pack_isects[] = {"wt", "wt32", NULL};

static size_t align64(size_t n)
{
    return (n + 63u) & ~(size_t)63u;
}

/* s15.16 raw of a scaled coordinate, or an error when outside the geometry bound. */
static int to_q16(double x, int32_t *q)
{
    double r = floor(x * 65536.0 + 0.5);
    if (!(fabs(x) <= ldexp(1.0, LT_CFG_GEOM_MAX_LOG2)))
        return -1;
    *q = (int32_t)r;
    return 0;
}

/* The integer camera: direction(x, y) = d00 + x dx + y dy, the double camera's pixel-centre
 * direction scaled so each of the three parts stays within 2^29 (lt_sblob_open's rule). */
static void camera_words(const lt_camera_t *c, int32_t d00[3], int32_t dx[3], int32_t dy[3])
{
    double w = (double)c->width, h = (double)c->height, t = c->tan_half_fov, asp = w / h;
    double u0 = (1.0 / w - 1.0) * t * asp, v0 = (1.0 - 1.0 / h) * t;
    double a0[3], ax[3], ay[3], m = 0.0, s;
    int a;
    for (a = 0; a < 3; a++) {
        a0[a] = c->fwd[a] + u0 * c->right[a] + v0 * c->up[a];
        ax[a] = 2.0 * t * asp / w * c->right[a];
        ay[a] = -2.0 * t / h * c->up[a];
        m = fmax(m, fmax(fabs(a0[a]), fmax(fabs(ax[a]) * (w - 1.0), fabs(ay[a]) * (h - 1.0))));
    }
    s = 0.999 * ldexp(1.0, 29) / m;
    for (a = 0; a < 3; a++) {
        d00[a] = (int32_t)floor(a0[a] * s + 0.5);
        dx[a] = (int32_t)floor(ax[a] * s + 0.5);
        dy[a] = (int32_t)floor(ay[a] * s + 0.5);
    }
}

/* p before the options: nothing given, the defaults of a pack. */
static void pack_defaults(pack_t *p)
{
    memset(p, 0, sizeof *p);
    lt_sf_defaults(&p->sf);
    p->leaf = 4;
}

static int pack_parse(pack_t *p, int argc, char **argv, const char *prog)
{
    static char who[64];
    const lt_opt_t opts[] = {
        LT_OPT_OUT("--out", "PATH.ltsb", &p->out, "ltsb",
                   "write the scene blob there (all or nothing)"),
        LT_OPT_IN("--in", "PATH.ltsb",
                  &p->in, "trace an existing blob instead (checks it first; implies --trace)"),
        LT_OPT_IN("--mesh", "PATH", &p->mesh_over,
                  "mesh file (overrides the scene's \"mesh\"; default scenes/teapot.obj)"),
        {.name = "--res", .kind = LT_OPT_SIZE, .dest = p->wh, .seen = &p->seen_res,
         .meta = "WxH|N", .help = "image size ({range} per side; default: the scene file's, else 64)",
         .lo = 1, .hi = LT_SBLOB_MAX_RES},
        {.name = "--light", .kind = LT_OPT_VEC, .dest = p->lf, .seen = &p->seen_light,
         .meta = "X,Y,Z", .lo = -HUGE_VAL, .hi = HUGE_VAL, .n = 3,
         .help = "point light in mesh file units (default: the scene's first light,\n"
                 "else centre + 2 radius normalize(-0.5, 1.5, 0.8), as render)"},
        LT_OPT_INT("--leaf", "N", &p->leaf, 1, LT_BVH_MAX_LEAF,
                   "BVH leaf size, {range} (default 4: the 1-lane machines' pick)"),
        LT_OPT_FLAG_("--no-shadows", &p->no_shadows, "primary rays only"),
        LT_OPT_ENUM_("--isect", &p->isect, pack_isects,
                     "the targets' ray/triangle test: wt (watertight, default) or wt32\n"
                     "(the s15.16 grid test, LT_ISECT_WT32: a blob flag; firmware built\n"
                     "with LT_CFG_WT32 0 refuses it)"),
        LT_OPT_FLAG_("--trace", &p->trace,
                     "trace the blob here and print the lines a target prints"),
        LT_OPT_END_};
    lt_opt_cmd_t cmd = {
        who, "[SCENE.json] (--out PATH.ltsb | --in PATH.ltsb) [options]",
        "Make a scene blob for a firmware target: the mesh in s15.16, its BVH, an integer\n"
        "pinhole camera and a point light, position-independent (docs/firmware.md). With\n"
        "--trace, trace it on the host in 16x16 tiles (primary rays and hard shadows, 16-ray\n"
        "packets, watertight) and print a line per tile: a target running the same blob\n"
        "(build/fw/<T>/scene-*.elf) prints the same lines.\n"
        "options:\n",
        NULL, opts, &p->scene_path, 1, &p->npos};
    int rc;
    (void)prog;
    snprintf(who, sizeof who, "%s pack", prog);
    who_g = who;
    rc = lt_opt_parse(&cmd, argc, argv, 2);
    if (rc == LT_OPT_OK && (p->out == NULL) == (p->in == NULL)) {
        fprintf(stderr, "%s: give one of --out PATH.ltsb (make a blob) and --in PATH.ltsb (trace "
                        "one)\n", who_g);
        return LT_OPT_USAGE;
    }
    return rc;
}

/* The scene file under the flags, the mesh, the prepared scene, the camera and the light.
 * Returns 0 or an exit code. */
static int pack_load(pack_t *p)
{
    lt_scenefile_t *sf = &p->sf;
    lt_diag_t diag;
    if (p->scene_path != NULL && lt_sf_load(p->scene_path, sf, &diag) != 0) {
        fprintf(stderr, "%s: %s\n", who_g, diag.msg);
        return EXIT_INPUT;
    }
    if (p->seen_res) {
        sf->width = p->wh[0];
        sf->height = p->wh[1];
    } else if (p->scene_path == NULL) {
        sf->width = sf->height = 64;
    }
    if (sf->width > LT_SBLOB_MAX_RES || sf->height > LT_SBLOB_MAX_RES) {
        fprintf(stderr, "%s: %s: %ux%u pixels: a blob holds at most %ux%u\n", who_g,
                p->scene_path, sf->width, sf->height, LT_SBLOB_MAX_RES, LT_SBLOB_MAX_RES);
        return EXIT_INPUT;
    }
    if (p->mesh_over != NULL)
        snprintf(sf->mesh, sizeof sf->mesh, "%s", p->mesh_over);
    if (sf->mesh[0] == '\0')
        snprintf(sf->mesh, sizeof sf->mesh, "scenes/teapot.obj");
    if (!p->seen_light && sf->nlights > 0) {
        memcpy(p->lf, sf->lights[0].position, sizeof p->lf);
        p->seen_light = 1;
    }
    if (lt_mesh_load(sf->mesh, &p->mesh, &diag) != 0) {
        fprintf(stderr, "%s: %s\n", who_g, diag.msg);
        return EXIT_INPUT;
    }
    if (lt_scene_prepare(&p->mesh, &p->sc, &diag) != 0) {
        fprintf(stderr, "%s: %s: %s\n", who_g, sf->mesh, diag.msg);
        return EXIT_INPUT;
    }
    /* a blob is s15.16 only: a scene that path cannot represent is refused */
    if (lt_scene_check_q16(&p->sc, sf->mesh, &diag) != 0) {
        fprintf(stderr, "%s: %s\n", who_g, diag.msg);
        return EXIT_INPUT;
    }
    if (sf->has_camera) {
        if (lt_camera_look(&p->sc, sf->eye, sf->target, sf->up, sf->fov_y_deg, sf->width,
                           sf->height, &p->cam, &diag) != 0) {
            fprintf(stderr, "%s: %s: %s\n", who_g, sf->path, diag.msg);
            return EXIT_INPUT;
        }
    } else {
        lt_camera_default(&p->sc, sf->width, sf->height, &p->cam);
    }
    lt_scene_light(&p->sc, p->seen_light ? p->lf : NULL, p->light);
    return 0;
}

/* The blob in memory (p->blob, p->bytes). Returns 0 or an exit code. */
static int pack_build(pack_t *p)
{
    lt_bvh_desc_t desc = {0, 0, 0, 0, 0};
    lt_bvh_t bvh;
    void *arena = NULL;
    lt_sblob_view_t v;
    size_t ab = 0, total;
    uint32_t n = p->sc.ntris;
    int32_t eye[3], light[3], d00[3], dx[3], dy[3], eps;
    uint8_t *b;
    lt_status_t st;
    int a;
    desc.max_leaf = (uint32_t)p->leaf;
    if (n == 0 || n > LT_BVH_MAX_TRIS) {
        fprintf(stderr, "%s: %s: %u triangles: a blob holds 1..%u\n", who_g, p->sf.mesh, n,
                LT_BVH_MAX_TRIS);
        return EXIT_INPUT;
    }
    for (a = 0; a < 3; a++)
        if (to_q16(p->cam.eye[a], &eye[a]) != 0 || to_q16(p->light[a], &light[a]) != 0) {
            fprintf(stderr, "%s: the %s lies outside the fixed-point range (|x| <= %g scaled "
                            "units)\n", who_g, to_q16(p->cam.eye[a], &eye[a]) != 0 ? "eye" : "light",
                    ldexp(1.0, LT_CFG_GEOM_MAX_LOG2));
            return EXIT_INPUT;
        }
    eps = (int32_t)fmax(1.0, floor(1e-4 * p->sc.radius * 65536.0 + 0.5));
    camera_words(&p->cam, d00, dx, dy);
    if (lt_bvh_size(n, &desc, &ab) != LT_OK || posix_memalign(&arena, 64, align64(ab)) != 0) {
        fprintf(stderr, "%s: %s: out of memory for the BVH of %u triangles\n", who_g, p->sf.mesh,
                n);
        return EXIT_INPUT;
    }
    st = lt_bvh_build_q16(&bvh, &desc, p->sc.tq, n, arena, ab);
    if (st != LT_OK) {
        fprintf(stderr, "%s: %s: BVH build: %s\n", who_g, p->sf.mesh, lt_status_str(st));
        free(arena);
        return EXIT_INPUT;
    }
    for (a = 0; a < 3; a++) {
        v.eye[a] = eye[a];
        v.light[a] = light[a];
        v.d00[a] = d00[a];
        v.dx[a] = dx[a];
        v.dy[a] = dy[a];
    }
    v.width = p->cam.width;
    v.height = p->cam.height;
    v.flags = (p->no_shadows ? 0u : LT_SBLOB_F_SHADOWS) | (p->isect == 1 ? LT_SBLOB_F_WT32 : 0u);
    v.eps = eps;
    v.scale = (uint32_t)fmin(4294967295.0, floor(p->sc.scale * 65536.0 + 0.5));
    total = lt_sblob_size(n, bvh.nnodes);
    b = malloc(total);
    if (b == NULL || lt_sblob_write(p->sc.tq, &bvh, desc.max_leaf, &v, b, total) != LT_OK) {
        fprintf(stderr, "%s: out of memory for a %zu-byte blob\n", who_g, total);
        free(b);
        free(arena);
        return EXIT_INPUT;
    }
    free(arena);
    {
        /* the target's check before the file is written: a blob that lt_sblob_open refuses
           is not written (it was, and only --trace or the target said so) */
        lt_sblob_t s;
        lt_sblob_err_t e = lt_sblob_open(b, total, &s);
        if (e != LT_SBLOB_OK) {
            fprintf(stderr, "%s: %s: the %ux%u blob made of it fails the target's check (item %u): "
                            "%s\n", who_g, p->sf.mesh, v.width, v.height, s.bad,
                    lt_sblob_err_str(e));
            free(b);
            return EXIT_INPUT;
        }
    }
    p->blob = b;
    p->bytes = total;
    return 0;
}

static int pack_write(const pack_t *p)
{
    lt_diag_t diag;
    if (lt_write_file_atomic(p->out, p->blob, p->bytes, &diag) != 0) {
        fprintf(stderr, "%s: --out: %s\n", who_g, diag.msg);
        return EXIT_INPUT;
    }
    return 0;
}

/* Read PATH into p->blob (64-byte aligned). Returns 0 or an exit code. */
static int pack_read(pack_t *p)
{
    struct stat st;
    FILE *f;
    long n;
    if (stat(p->in, &st) == 0 && !S_ISREG(st.st_mode)) {
        fprintf(stderr, "%s: --in %s: not a regular file\n", who_g, p->in);
        return EXIT_INPUT;
    }
    f = fopen(p->in, "rb");
    if (f == NULL || fseek(f, 0, SEEK_END) != 0 || (n = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0) {
        fprintf(stderr, "%s: --in %s: cannot read\n", who_g, p->in);
        if (f != NULL)
            fclose(f);
        return EXIT_INPUT;
    }
    if ((unsigned long)n > 0x7FFFFFFFul) {
        fprintf(stderr, "%s: --in %s: %ld bytes: a blob holds at most 2^31 - 1\n", who_g, p->in, n);
        fclose(f);
        return EXIT_INPUT;
    }
    p->bytes = (size_t)n;
    {
        void *m = NULL;
        p->blob = posix_memalign(&m, 64, align64(p->bytes + 1u)) == 0 ? m : NULL;
    }
    if (p->blob == NULL || fread(p->blob, 1, p->bytes, f) != p->bytes) {
        fprintf(stderr, "%s: --in %s: cannot read %zu bytes\n", who_g, p->in, p->bytes);
        fclose(f);
        return EXIT_INPUT;
    }
    fclose(f);
    return 0;
}

/* Trace the blob tile by tile, in packets and then in single rays, and print the lines a firmware
 * target prints (firmware/apps/scene_fw.c). */
static int pack_trace(const pack_t *p, const char *name)
{
    int32_t ids[LT_SBLOB_TILE * LT_SBLOB_TILE];
    uint64_t same = 0, px = 0, hm = 0;
    lt_sblob_t s;
    lt_sblob_err_t e = lt_sblob_open(p->blob, p->bytes, &s);
    int single;
    if (e != LT_SBLOB_OK) {
        /* what lt_sblob_open's "bad" holds for this error (lt_sblob.h) */
        char at[64] = "";
        if (e == LT_SBLOB_E_MAGIC)
            snprintf(at, sizeof at, " (its first word is 0x%08x)", s.bad);
        else if (e == LT_SBLOB_E_VERSION)
            snprintf(at, sizeof at, " (version %u)", s.bad);
        else if (e == LT_SBLOB_E_SHORT)
            snprintf(at, sizeof at, " (the file has %zu bytes)", p->bytes);
        else if (e != LT_SBLOB_E_SUM && e != LT_SBLOB_E_IMAGE)
            snprintf(at, sizeof at, " (item %u)", s.bad);
        fprintf(stderr, "%s: %s: not a usable scene blob: %s%s\n", who_g, name,
                lt_sblob_err_str(e), at);
        return EXIT_INPUT;
    }
    printf("sblob %u triangles, %u nodes, %ux%u pixels, %u tiles, %s, %zu bytes\n",
           s.bvh.ntris, s.bvh.nnodes, s.width, s.height, s.tiles_x * s.tiles_y,
           (s.flags & LT_SBLOB_F_SHADOWS) ? "shadows" : "no shadows", p->bytes);
    if ((s.flags & LT_SBLOB_F_WT32) != 0)
        printf("isect wt32: the s15.16 grid test, grid 2^%u raw\n",
               (unsigned)LT_ISECT_WT32_SHIFT(s.bvh.isect));
    for (single = 0; single < 2; single++) {
        uint32_t t, hash = LT_SBLOB_FNV0, rays = 0, hits = 0, srays = 0, occ = 0;
        for (t = 0; t < s.tiles_x * s.tiles_y; t++) {
            lt_sblob_tile_t r;
            lt_status_t st;
            r.ids = ids;
            st = lt_sblob_trace_tile(&s, t, single, NULL, &r);
            if (st != LT_OK) {
                fprintf(stderr, "%s: %s: tile %u: %s\n", who_g, name, t, lt_status_str(st));
                return EXIT_INPUT;
            }
            if (!single && p->sc.ntris > 0) {
                /* against the double-precision reference tracer along the double camera's rays
                   (the blob's integer camera rounds them: a pixel may differ at an edge) */
                uint32_t x, y, x0 = (t % s.tiles_x) * LT_SBLOB_TILE, y0 = (t / s.tiles_x) * LT_SBLOB_TILE;
                for (y = y0; y < y0 + LT_SBLOB_TILE && y < s.height; y++)
                    for (x = x0; x < x0 + LT_SBLOB_TILE && x < s.width; x++) {
                        double d[3], tr;
                        int32_t ref, got = ids[(y - y0) * LT_SBLOB_TILE + (x - x0)];
                        lt_camera_dir(&p->cam, x, y, d);
                        ref = lt_ref_trace(&p->sc, p->cam.eye, d, &tr);
                        px++;
                        same += ref == got;
                        hm += (ref < 0) != (got < 0);
                    }
            }
            if (!single)
                printf("tile %u hash 0x%08x rays %u hits %u shadow %u occluded %u\n", t, r.hash,
                       r.rays, r.hits, r.srays, r.occluded);
            hash = lt_sblob_fnv(hash, &r.hash, 4);
            rays += r.rays;
            hits += r.hits;
            srays += r.srays;
            occ += r.occluded;
        }
        printf("image%s hash 0x%08x rays %u hits %u shadow %u occluded %u\n",
               single ? " single rays" : "", hash, rays, hits, srays, occ);
    }
    if (px > 0)
        printf("accuracy against the double reference tracer: same triangle %.3f%% (%llu of %llu "
               "pixels), hit/miss differs on %llu\n", 100.0 * (double)same / (double)px,
               (unsigned long long)same, (unsigned long long)px, (unsigned long long)hm);
    return 0;
}

int lt_pack_cli(int argc, char **argv, const char *prog)
{
    pack_t p;
    int rc;
    pack_defaults(&p);
    rc = pack_parse(&p, argc, argv, prog);
    if (rc != LT_OPT_OK)
        return rc == LT_OPT_HELP ? 0 : EXIT_USAGE;
    if (p.in != NULL) {
        rc = pack_read(&p);
        if (rc == 0)
            rc = pack_trace(&p, p.in);
    } else {
        rc = pack_load(&p);
        if (rc == 0)
            rc = pack_build(&p);
        if (rc == 0)
            rc = pack_write(&p);
        if (rc == 0)
            printf("pack  %s: %u triangles, %ux%u pixels, leaf %d, %s%s -> %s (%zu bytes)\n",
                   p.sf.mesh, p.sc.ntris, p.cam.width, p.cam.height, p.leaf,
                   p.no_shadows ? "no shadows" : "hard shadows",
                   p.isect == 1 ? ", isect wt32" : "", p.out, p.bytes);
        if (rc == 0 && p.trace)
            rc = pack_trace(&p, p.out);
        lt_scene_free(&p.sc);
        lt_mesh_free(&p.mesh);
    }
    free(p.blob);
    return rc;
}
