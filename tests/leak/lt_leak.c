/* lt_leak.c - leaks through the whole pipeline on closed meshes (issue 11): a mesh is closed when
 * every edge is shared by exactly two faces that use it in opposite directions (checked: boundary,
 * non-manifold and inconsistently oriented edges are counted and the mesh is refused). Then, for
 * the benchmark view at N x N, each numeric path, each structure (chunks, bvh, bvhq, kd, grid:
 * 16-ray packets; bvh and bvhq also single rays) and each intersector asked for:
 *   primary: a pixel leaks when its ray, which the double reference sees enter the silhouette,
 *            does not hit the front surface: its first hit faces away (the inside of the far wall)
 *            or it misses while its four neighbours hit, and it lies beyond the reference's front
 *            hit by more than 1e-4 radii (or misses): a crack, not a coplanar twin face;
 *   shadow:  from a point 1e-3 radii behind the front surface (along the pixel's ray) back to the
 *            eye, any hit (lt_render_shadows: occluded16 of bvh, bvhq, kd, grid): the ray must be
 *            blocked by the front surface; a leak is an unblocked ray.
 * A candidate counts only if the double-precision brute force (lt_ref_trace) confirms it: its first
 * hit is a front face whose hit point does not lie within 1e-7 radii of a silhouette edge (an edge
 * whose other face looks away: a grazing ray may miss there without a crack).
 * Usage: lt-leak MESH [--res N] [--subdiv K] [--isect wt|mt|wt32|both|all] [--num q16|f32|both]
 *        [--structures LIST] [--max-leaks N] [--allow-open] (trace a mesh that fails the check)
 * Prints one line per (path, structure, intersector, ray kind) and exits 1 when a watertight run
 * leaks more than --max-leaks (default 0) or the mesh is not closed. Host only (tests/).
 */
#include "render/lt_render.h"
#include "render/lt_paths.h"
#include "render/lt_path_ops.h"
#include "render/lt_scene.h"
#include "io/lt_mesh.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- closedness ---------------------------------------------------------------------------- */

typedef struct {
    uint32_t a, b;   /* vertex ids, directed a -> b */
    uint32_t tri;    /* triangle */
} edge_t;


/* Vertex ids by exact coordinates (sorted index of the 3 n positions). */
static const double *g_v;
static int cmp_pos(const void *x, const void *y)
{
    const double *p = g_v + 3 * (size_t)*(const uint32_t *)x, *q = g_v + 3 * (size_t)*(const uint32_t *)y;
    int a;
    for (a = 0; a < 3; a++)
        if (p[a] != q[a])
            return p[a] < q[a] ? -1 : 1;
    return 0;
}

static int cmp_edge(const void *x, const void *y)
{
    const edge_t *e = x, *f = y;
    if (e->a != f->a)
        return e->a < f->a ? -1 : 1;
    if (e->b != f->b)
        return e->b < f->b ? -1 : 1;
    return 0;
}

typedef struct {
    uint32_t n;       /* triangles */
    uint32_t *vid;    /* 3 per triangle */
    edge_t *edges;    /* 3 n, sorted */
    uint32_t *nbr;    /* 3 per triangle: the triangle across edge k (v_k, v_k+1), or UINT32_MAX */
    unsigned long boundary, nonmanifold, misoriented;
    double volume;    /* signed volume (> 0: outward normals) */
} topo_t;

static const edge_t *find_edge(const topo_t *t, uint32_t a, uint32_t b)
{
    edge_t key;
    key.a = a;
    key.b = b;
    key.tri = 0;
    return bsearch(&key, t->edges, 3u * t->n, sizeof key, cmp_edge);
}

static void topo_build(const lt_mesh_t *m, topo_t *t)
{
    uint32_t n = m->ntris, i, k, *ord = malloc(3u * n * sizeof *ord);
    memset(t, 0, sizeof *t);
    t->n = n;
    t->vid = malloc(3u * n * sizeof *t->vid);
    t->edges = malloc(3u * n * sizeof *t->edges);
    t->nbr = malloc(3u * n * sizeof *t->nbr);
    for (i = 0; i < 3u * n; i++)
        ord[i] = i;
    g_v = m->v;
    qsort(ord, 3u * n, sizeof *ord, cmp_pos);
    for (i = 0, k = 0; i < 3u * n; i++) {
        if (i > 0 && cmp_pos(&ord[i - 1], &ord[i]) != 0)
            k++;
        t->vid[ord[i]] = k;
    }
    for (i = 0; i < n; i++)
        for (k = 0; k < 3; k++) {
            edge_t *e = &t->edges[3 * i + k];
            e->a = t->vid[3 * i + k];
            e->b = t->vid[3 * i + (k + 1) % 3];
            e->tri = i;
        }
    qsort(t->edges, 3u * n, sizeof *t->edges, cmp_edge);
    for (i = 0; i < 3u * n; i++) {
        const edge_t *e = &t->edges[i], *r;
        if (i + 1 < 3u * n && cmp_edge(e, &t->edges[i + 1]) == 0)
            t->misoriented++; /* the same directed edge twice: flipped face or non-manifold */
        r = find_edge(t, e->b, e->a);
        if (r == NULL)
            t->boundary++;
        else if ((r > t->edges && cmp_edge(r, r - 1) == 0) ||
                 (r + 1 < t->edges + 3u * n && cmp_edge(r, r + 1) == 0))
            t->nonmanifold++;
    }
    for (i = 0; i < n; i++)
        for (k = 0; k < 3; k++) {
            const edge_t *r = find_edge(t, t->vid[3 * i + (k + 1) % 3], t->vid[3 * i + k]);
            t->nbr[3 * i + k] = r != NULL ? r->tri : UINT32_MAX;
        }
    for (i = 0; i < n; i++) {
        const double *a = &m->v[9 * (size_t)i], *b = a + 3, *c = a + 6;
        t->volume += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                      a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0;
    }
    free(ord);
}

static void topo_free(topo_t *t)
{
    free(t->vid);
    free(t->edges);
    free(t->nbr);
}

/* 4-to-1 midpoint subdivision (shared midpoints are the same doubles: 0.5 (a + b) is symmetric). */
static void subdivide(lt_mesh_t *m)
{
    double *v = malloc((size_t)m->ntris * 4u * 9u * sizeof *v);
    uint32_t i;
    int a;
    for (i = 0; i < m->ntris; i++) {
        const double *p = &m->v[9 * (size_t)i];
        double q[6][3];
        static const int tri[4][3] = {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}, {3, 4, 5}};
        int t, j;
        for (a = 0; a < 3; a++) {
            q[0][a] = p[a];
            q[1][a] = p[3 + a];
            q[2][a] = p[6 + a];
            q[3][a] = 0.5 * (p[a] + p[3 + a]);
            q[4][a] = 0.5 * (p[3 + a] + p[6 + a]);
            q[5][a] = 0.5 * (p[6 + a] + p[a]);
        }
        for (t = 0; t < 4; t++)
            for (j = 0; j < 3; j++)
                for (a = 0; a < 3; a++)
                    v[(size_t)(4 * i + (uint32_t)t) * 9 + 3 * (size_t)j + (size_t)a] = q[tri[t][j]][a];
    }
    free(m->v);
    m->v = v;
    m->ntris *= 4u;
}

/* ---- classification ------------------------------------------------------------------------ */

static double facing(const lt_scene_t *s, int32_t id, const double d[3])
{
    const double *v = &s->vd[9 * (size_t)id];
    double e1[3], e2[3], n[3];
    int a;
    for (a = 0; a < 3; a++) {
        e1[a] = v[3 + a] - v[a];
        e2[a] = v[6 + a] - v[a];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    return n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
}

/* Front (1) for outward normals (orient = +1; -1 flips). */
static int is_front(const lt_scene_t *s, int orient, int32_t id, const double d[3])
{
    return orient * facing(s, id, d) < 0.0;
}

/* The double reference confirms that the ray o + t d enters the mesh through a front face away
 * from any silhouette edge (within tol of an edge whose other face looks away: grazing). */
static int ref_enters(const lt_scene_t *s, const topo_t *tp, int orient, const double o[3],
                      const double d[3], double tol, double *tref)
{
    double t, p[3];
    int32_t id = lt_ref_trace(s, o, d, &t);
    int k, a;
    if (id < 0 || !is_front(s, orient, id, d))
        return 0;
    *tref = t;
    for (a = 0; a < 3; a++)
        p[a] = o[a] + t * d[a];
    for (k = 0; k < 3; k++) {
        const double *v0 = &s->vd[9 * (size_t)id + 3 * (size_t)k];
        const double *v1 = &s->vd[9 * (size_t)id + 3 * (size_t)((k + 1) % 3)];
        double e[3], w[3], c[3], l2 = 0.0, dist;
        uint32_t nb = tp->nbr[3 * (size_t)id + (size_t)k];
        for (a = 0; a < 3; a++) {
            e[a] = v1[a] - v0[a];
            w[a] = p[a] - v0[a];
            l2 += e[a] * e[a];
        }
        c[0] = e[1] * w[2] - e[2] * w[1];
        c[1] = e[2] * w[0] - e[0] * w[2];
        c[2] = e[0] * w[1] - e[1] * w[0];
        dist = sqrt((c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) / l2);
        if (dist <= tol && (nb == UINT32_MAX || !is_front(s, orient, (int32_t)nb, d)))
            return 0;
    }
    return 1;
}

/* ---- main ---------------------------------------------------------------------------------- */

int main(int argc, char **argv)
{
    const char *path = NULL, *structs = "chunks,bvh,bvhq,kd,grid", *isects = "wt", *nums = "both";
    uint32_t res = 512, subdiv = 0, x, y;
    unsigned long max_leaks = 0;
    int allow_open = 0;
    lt_mesh_t m;
    lt_scene_t s;
    lt_camera_t cam;
    topo_t tp;
    lt_diag_t diag;
    int i, orient, fail = 0, pi, ii;
    double tol;
    for (i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--res") == 0 && i + 1 < argc)
            res = (uint32_t)atoi(argv[++i]);
        else if (strcmp(argv[i], "--subdiv") == 0 && i + 1 < argc)
            subdiv = (uint32_t)atoi(argv[++i]);
        else if (strcmp(argv[i], "--isect") == 0 && i + 1 < argc)
            isects = argv[++i];
        else if (strcmp(argv[i], "--num") == 0 && i + 1 < argc)
            nums = argv[++i];
        else if (strcmp(argv[i], "--structures") == 0 && i + 1 < argc)
            structs = argv[++i];
        else if (strcmp(argv[i], "--max-leaks") == 0 && i + 1 < argc)
            max_leaks = strtoul(argv[++i], NULL, 10);
        else if (strcmp(argv[i], "--allow-open") == 0)
            allow_open = 1;
        else if (strcmp(argv[i], "--help") == 0) {
            printf("usage: lt-leak MESH [--res N] [--subdiv K] [--isect wt|mt|wt32|both|all] "
                   "[--num q16|f32|both] [--structures LIST] [--max-leaks N]\n");
            return 0;
        } else if (argv[i][0] != '-' && path == NULL)
            path = argv[i];
        else {
            fprintf(stderr, "lt-leak: unknown argument '%s'\n", argv[i]);
            return 2;
        }
    }
    if (path == NULL || res < 4 || res > 4096) {
        fprintf(stderr, "usage: lt-leak MESH [--res N] [--subdiv K] [--isect wt|mt|wt32|both|all] ...\n");
        return 2;
    }
    if (lt_mesh_load(path, &m, &diag) != 0) {
        fprintf(stderr, "lt-leak: %s\n", diag.msg);
        return 1;
    }
    while (subdiv-- > 0)
        subdivide(&m);
    topo_build(&m, &tp);
    printf("mesh      %s: %u triangles, %lu boundary, %lu non-manifold, %lu misoriented edges, "
           "volume %s\n", path, m.ntris, tp.boundary, tp.nonmanifold, tp.misoriented,
           tp.volume > 0.0 ? "positive (outward)" : "negative (inward)");
    if (tp.boundary != 0 || tp.nonmanifold != 0 || tp.misoriented != 0) {
        printf("NOT CLOSED %s: every edge must be shared by exactly two faces in opposite "
               "directions%s\n", path, allow_open ? " (--allow-open: traced anyway; only leaks "
               "the double reference confirms at consistently oriented front faces count)" : "");
        if (!allow_open)
            return 1;
    }
    orient = tp.volume > 0.0 ? 1 : -1;
    if (lt_scene_prepare(&m, &s, &diag) != 0) {
        fprintf(stderr, "lt-leak: %s\n", diag.msg);
        return 1;
    }
    lt_camera_default(&s, res, res, &cam);
    tol = 1e-7 * s.radius;
    for (pi = 0; pi < 2; pi++) {
        const lt_path_info_t *p = lt_paths_find(pi == 0 ? "q16" : "f32", LT_PATHS_OBJECT);
        if (strcmp(nums, "both") != 0 && strcmp(nums, pi == 0 ? "q16" : "f32") != 0)
            continue;
        for (ii = 0; ii < 3; ii++) {
            static const char *const inames[3] = {"wt", "mt", "wt32"};
            char list[256], *tok, *save = NULL;
            /* wt32 (the s15.16 grid test) must be watertight too; mt is the before figure */
            int must = ii != 1;
            if (!(strcmp(isects, inames[ii]) == 0 || (strcmp(isects, "both") == 0 && ii < 2) ||
                  strcmp(isects, "all") == 0) ||
                (ii == 2 && pi != 0))
                continue;
            snprintf(list, sizeof list, "%s", structs);
            for (tok = strtok_r(list, ",", &save); tok != NULL; tok = strtok_r(NULL, ",", &save)) {
                int single;
                if (p->render->bvhq_build == NULL && strcmp(tok, "bvhq") == 0)
                    continue;
                for (single = 0; single < 2; single++) {
                    lt_accel_t *acc;
                    lt_frame_t f, g;
                    unsigned long inside = 0, leaks = 0, cand = 0, srays = 0, sleaks = 0;
                    uint32_t nr = 0, nocc = 0;
                    uint8_t *occ;
                    double light[3];
                    if (single && strcmp(tok, "bvh") != 0 && strcmp(tok, "bvhq") != 0)
                        continue;
                    acc = lt_accel_build(&s, tok, p, &diag);
                    if (acc == NULL) {
                        fprintf(stderr, "lt-leak: %s\n", diag.msg);
                        return 1;
                    }
                    if (lt_accel_set_isect_name(acc, inames[ii], NULL, &diag) != 0) {
                        fprintf(stderr, "lt-leak: %s\n", diag.msg);
                        return 1;
                    }
                    if (lt_frame_alloc(&f, res, res, &diag) != 0 ||
                        lt_frame_alloc(&g, res, res, &diag) != 0)
                        return 1;
                    if (single)
                        (void)lt_render_primary1(&s, acc, &cam, &f, &diag);
                    else
                        lt_render_primary(&s, acc, &cam, &f, NULL);
                    /* primary: candidates, then the reference */
                    for (y = 0; y < res; y++)
                        for (x = 0; x < res; x++) {
                            size_t q = (size_t)y * res + x;
                            double d[3], tr;
                            int c = 0;
                            lt_camera_dir(&cam, x, y, d);
                            if (f.id[q] >= 0)
                                c = !is_front(&s, orient, f.id[q], d);
                            else if (x > 0 && y > 0 && x + 1 < res && y + 1 < res)
                                c = f.id[q - 1] >= 0 && f.id[q + 1] >= 0 && f.id[q - res] >= 0 &&
                                    f.id[q + res] >= 0;
                            if (f.id[q] >= 0 && !c)
                                inside++;
                            if (!c)
                                continue;
                            cand++;
                            if (ref_enters(&s, &tp, orient, cam.eye, d, tol, &tr) &&
                                (f.id[q] < 0 || f.t[q] > tr + 1e-4 * s.radius)) {
                                inside++;
                                leaks++;
                            }
                        }
                    printf("leak      %s %s %-6s %-6s %s primary: %lu pixels enter the mesh, %lu "
                           "candidates, %lu leaks\n", p->name,
                           inames[ii], tok, single ? "single" : "packet",
                           path, inside, cand, leaks);
                    if (must && leaks > max_leaks)
                        fail = 1;
                    /* shadow (packets, any hit): from behind the front surface back to the eye */
                    if (!single && strcmp(tok, "chunks") != 0) {
                        occ = calloc((size_t)res * res, 1);
                        for (y = 0; y < res * res; y++) {
                            g.id[y] = -1;
                            if (f.id[y] >= 0) {
                                double d[3];
                                lt_camera_dir(&cam, y % res, y / res, d);
                                if (is_front(&s, orient, f.id[y], d)) {
                                    g.id[y] = f.id[y];
                                    g.t[y] = f.t[y] + 1e-3 * s.radius;
                                }
                            }
                        }
                        light[0] = cam.eye[0];
                        light[1] = cam.eye[1];
                        light[2] = cam.eye[2];
                        if (lt_render_shadows(&s, acc, &cam, &g, light, &nr, &nocc, occ, &diag) != 0) {
                            fprintf(stderr, "lt-leak: %s\n", diag.msg);
                            return 1;
                        }
                        for (y = 0; y < res * res; y++) {
                            double d[3], tr;
                            if (g.id[y] < 0)
                                continue;
                            srays++;
                            if (occ[y])
                                continue;
                            lt_camera_dir(&cam, y % res, y / res, d);
                            if (ref_enters(&s, &tp, orient, cam.eye, d, tol, &tr))
                                sleaks++;
                        }
                        printf("leak      %s %s %-6s %-6s %s shadow: %lu rays from behind the "
                               "front surface, %lu occluded, %lu leaks\n",
                               p->name, inames[ii],
                               tok, "packet", path, srays, (unsigned long)nocc, sleaks);
                        if (must && sleaks > max_leaks)
                            fail = 1;
                        free(occ);
                    }
                    fflush(stdout);
                    lt_frame_free(&f);
                    lt_frame_free(&g);
                    lt_accel_free(acc);
                }
            }
        }
    }
    topo_free(&tp);
    lt_scene_free(&s);
    lt_mesh_free(&m);
    printf("%s\n", fail ? "FAIL: watertight runs leak" : "OK: no watertight leaks");
    return fail;
}
