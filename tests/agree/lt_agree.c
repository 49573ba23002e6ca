/* lt_agree.c - hit agreement of the tracers with the double-precision reference on a real mesh,
 * with every disagreement explained or reported (issue: "same triangle id for >= 99.99% of pixels,
 * differences only at ties/edges").
 *
 * For each structure (grid, kd, bvh, bvhq) and numeric path (s15.16, float32) the benchmark view is
 * traced with 16-ray packets and compared pixel by pixel with lt_render_reference (brute-force
 * Moller-Trumbore in double, lowest id on equal t). A pixel whose triangle differs is re-examined in
 * double on the exact camera ray:
 *   m(X)  signed distance (scaled units) of the ray's point on triangle X's plane to X's border,
 *         positive inside: the smallest barycentric times the matching altitude;
 *   t(X)  the ray parameter of that point.
 * With the tracer's triangle a and the reference's b (-1 = no hit), a difference is
 *   TIE   both hit, a is a genuine hit (m(a) >= -delta) at the reference's depth
 *         (|t(a) - t(b)| <= tau): coplanar duplicates or a shared edge/vertex at one depth;
 *   EDGE  the ray passes within delta of the border of the triangle that one side missed or
 *         wrongly hit: m(a) in [-delta, delta] when the tracer took a the reference did not take
 *         first, m(b) <= delta when the tracer missed b;
 *   UNEXPLAINED otherwise (a wrong hit far outside a triangle, a hit far behind the true one).
 * delta is the path's bound on that border distance at the hit (delta_of below: quantisation of
 * vertices, origins, directions and the kernel's rounded cross products, amplified by the grazing
 * angle and by short edges); tau = 2^-12 + 2^-20 t is the depth tie tolerance.
 * The three structures are also compared with each other per path (same id, same t bits), and
 * each one's single rays (lt_render_primary1) must equal its packet lanes bit for bit.
 *
 * Usage: lt-agree MESH [--res N] [--min PCT] [--structures a,b,..]
 * Exit 0 when every path of every structure has no unexplained difference and at least PCT% same
 * triangle after counting ties as agreement (default 99.99); 1 otherwise or on an input error.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/lt_opt.h"
#include "io/lt_mesh.h"
#include "render/lt_render.h"
#include "render/lt_scene.h"

typedef struct geo {
    double t, m, cosv; /* ray parameter, signed border distance, |cos| ray vs normal */
    double emin;       /* shortest edge */
    double hmin;       /* smallest altitude (twice the area over the longest edge) */
    int ok;            /* the ray meets the plane (not parallel) */
} geo_t;

static void tri_geo(const lt_scene_t *s, int32_t id, const double o[3], const double d[3], geo_t *g)
{
    const double *v = &s->vd[(size_t)id * 9];
    double e1[3], e2[3], n[3], nn, dn, p[3], lam[3], area2;
    int a;
    memset(g, 0, sizeof *g);
    for (a = 0; a < 3; a++) {
        e1[a] = v[3 + a] - v[a];
        e2[a] = v[6 + a] - v[a];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    dn = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
    if (nn == 0.0 || dn == 0.0) {
        g->m = -HUGE_VAL;
        return;
    }
    g->ok = 1;
    g->cosv = fabs(dn) / sqrt(nn);
    g->t = (n[0] * (v[0] - o[0]) + n[1] * (v[1] - o[1]) + n[2] * (v[2] - o[2])) / dn;
    for (a = 0; a < 3; a++)
        p[a] = o[a] + g->t * d[a];
    /* barycentrics from sub-triangle areas signed along n: lam_i = n . ((v_j - p) x (v_k - p)) / nn */
    for (a = 0; a < 3; a++) {
        const double *vj = &v[3 * ((a + 1) % 3)], *vk = &v[3 * ((a + 2) % 3)];
        double x[3], y[3], c[3];
        int k;
        for (k = 0; k < 3; k++) {
            x[k] = vj[k] - p[k];
            y[k] = vk[k] - p[k];
        }
        c[0] = x[1] * y[2] - x[2] * y[1];
        c[1] = x[2] * y[0] - x[0] * y[2];
        c[2] = x[0] * y[1] - x[1] * y[0];
        lam[a] = (n[0] * c[0] + n[1] * c[1] + n[2] * c[2]) / nn;
    }
    /* distance to the edge opposite vertex i = lam_i * altitude_i = lam_i * |n| / |edge_i| */
    area2 = sqrt(nn);
    g->m = HUGE_VAL;
    g->hmin = HUGE_VAL;
    for (a = 0; a < 3; a++) {
        const double *vj = &v[3 * ((a + 1) % 3)], *vk = &v[3 * ((a + 2) % 3)];
        double el = sqrt((vk[0] - vj[0]) * (vk[0] - vj[0]) + (vk[1] - vj[1]) * (vk[1] - vj[1]) +
                         (vk[2] - vj[2]) * (vk[2] - vj[2]));
        double dist = el > 0.0 ? lam[a] * area2 / el : -HUGE_VAL;
        if (a == 0 || el < g->emin)
            g->emin = el;
        if (el > 0.0 && area2 / el < g->hmin)
            g->hmin = area2 / el;
        if (dist < g->m)
            g->m = dist;
    }
}

/* The path's bound on the border distance error of a hit on triangle g at ray parameter t
 * (scaled units), with c = max(|cos|, 2^-8):
 *   s15.16:  (sqrt3 2^-16 + sqrt3 2^-30 t) / c     vertices and origin rounded to 2^-17 per axis,
 *                                                  directions to 2^-31 per component
 *          + sqrt3 2^-7 / (c emin)                 qvec rounded to s25.6 moves v by |d|_1 2^-7 of
 *                                                  det = 2 area cos: a distance of that / (c emin)
 *          + 3 t 2^-17 / (c emin)                  pvec rounded to s15.16 moves u by |tvec|_1 2^-17
 *   float32: 2^-20 (2^11 + t) / c (1 + 1 / emin)   a few roundings of 2^-24 relative on coordinates
 *                                                  up to 2^11 units
 * The classification accepts border distances up to this bound; the largest ratio seen is printed. */
static double delta_of(int path, const geo_t *g, double t)
{
    double c = fmax(g->ok ? g->cosv : 1.0, ldexp(1.0, -8)), e = g->emin > 0.0 ? g->emin : 1.0;
    if (path == 0)
        return (sqrt(3.0) * (ldexp(1.0, -16) + ldexp(t, -30))) / c +
               (sqrt(3.0) * ldexp(1.0, -7) + 3.0 * ldexp(t, -17)) / (c * e);
    return ldexp(ldexp(1.0, 11) + t, -20) / c * (1.0 + 1.0 / e);
}

/* The path's bound on the error of the ray parameter t of a hit on triangle g (|d| = 1, scaled
 * units), with c = max(|cos|, 2^-8) and h the triangle's smallest altitude; the kernel computes
 * t = (e2 . qvec) / det with det = e1 . pvec = 2 area cos:
 *   s15.16:  (sqrt3 2^-16 + sqrt3 2^-30 t) / c     vertices, origin and direction rounded (as above)
 *          + sqrt3 2^-7 / (c h)                    qvec rounded to s25.6 (2^-7 per component) moves
 *                                                  e2 . qvec by |e2|_1 2^-7 of det
 *          + sqrt3 t 2^-17 / (c h)                 pvec rounded to s15.16 moves det by |e1|_1 2^-17
 *   float32: 2^-20 (2^11 + t) / c (1 + 1 / h)      as the border bound, with the altitude
 * Two genuine hits whose depths differ by less than this are a depth tie: their order is below
 * the path's resolution. At least 2^-12 + 2^-20 t (the float32 reference's own rounding). */
static double tau_of(int path, const geo_t *g, double t)
{
    double c = fmax(g->ok ? g->cosv : 1.0, ldexp(1.0, -8));
    double h = g->hmin > 0.0 && g->hmin < HUGE_VAL ? g->hmin : 1.0, b;
    if (path == 0)
        b = sqrt(3.0) * (ldexp(1.0, -16) + ldexp(t, -30)) / c +
            sqrt(3.0) * (ldexp(1.0, -7) + ldexp(t, -17)) / (c * h);
    else
        b = ldexp(ldexp(1.0, 11) + t, -20) / c * (1.0 + 1.0 / h);
    return fmax(b, ldexp(1.0, -12) + ldexp(1.0, -20) * fabs(t));
}

typedef struct verdict {
    uint32_t pixels, same, ties, ties_coplanar, edges, unexplained;
    double max_rel_delta; /* largest |m| / delta among explained pixels */
} verdict_t;

static void classify(const lt_scene_t *s, const lt_camera_t *c, int path, const lt_frame_t *f,
                     const lt_frame_t *ref, const char *label, verdict_t *v)
{
    uint32_t x, y;
    int shown = 0;
    memset(v, 0, sizeof *v);
    for (y = 0; y < c->height; y++)
        for (x = 0; x < c->width; x++) {
            size_t p = (size_t)y * c->width + x;
            int32_t a = f->id[p], b = ref->id[p];
            double d[3], da = 0.0, db = 0.0, tau, t;
            geo_t ga, gb;
            int tie = 0, edge = 0;
            v->pixels++;
            if (a == b) {
                v->same++;
                continue;
            }
            lt_camera_dir(c, x, y, d);
            memset(&ga, 0, sizeof ga);
            memset(&gb, 0, sizeof gb);
            if (a >= 0)
                tri_geo(s, a, c->eye, d, &ga);
            if (b >= 0)
                tri_geo(s, b, c->eye, d, &gb);
            t = b >= 0 ? ref->t[p] : (a >= 0 ? ga.t : 0.0);
            if (a >= 0)
                da = delta_of(path, &ga, t);
            if (b >= 0)
                db = delta_of(path, &gb, t);
            /* depth tie: within the path's depth error bound of either triangle (tau_of) */
            tau = fmax(a >= 0 ? tau_of(path, &ga, t) : 0.0, b >= 0 ? tau_of(path, &gb, t) : 0.0);
            if (a >= 0 && b >= 0) {
                if (ga.ok && ga.m >= -da && fabs(ga.t - ref->t[p]) <= tau)
                    tie = 1;
                else if (ga.ok && ga.m >= -da &&
                         ((ga.t < ref->t[p] && ga.m <= da) || (ga.t > ref->t[p] && gb.m <= db)))
                    edge = 1;
            } else if (a >= 0) {
                edge = ga.ok && ga.m >= -da && ga.m <= da;
            } else {
                edge = gb.m <= db;
            }
            if (tie) {
                v->ties++;
                /* the same plane (duplicate or coplanar faces): depths equal to 1e-9 relative */
                v->ties_coplanar += fabs(ga.t - ref->t[p]) <= 1e-9 * fabs(t);
                if (fabs(ga.m) / da > v->max_rel_delta && ga.m < 0.0)
                    v->max_rel_delta = fabs(ga.m) / da;
            } else if (edge) {
                int use_a = a >= 0 && (b < 0 || ga.t < ref->t[p]);
                double r = fabs(use_a ? ga.m : gb.m) / (use_a ? da : db);
                v->edges++;
                if (r > v->max_rel_delta)
                    v->max_rel_delta = r;
            } else {
                v->unexplained++;
                if (shown++ < 5)
                    printf("  UNEXPLAINED %s pixel (%u,%u): tracer id %d (t %.9g, border %.3g, "
                           "cos %.3g, bound %.3g), reference id %d (t %.9g, border %.3g, bound "
                           "%.3g)\n",
                           label, x, y, a, ga.t, ga.m, ga.cosv, da, b, b >= 0 ? ref->t[p] : 0.0,
                           gb.m, db);
            }
        }
}

/* Whether name is one of the comma-separated words of list. */
static int listed(const char *list, const char *name)
{
    size_t n = strlen(name);
    while (*list != '\0') {
        const char *e = strchr(list, ',');
        size_t l = e != NULL ? (size_t)(e - list) : strlen(list);
        if (l == n && strncmp(list, name, n) == 0)
            return 1;
        list += l + (e != NULL);
    }
    return 0;
}

int main(int argc, char **argv)
{
    static const char *const all[] = {"grid", "kd", "bvh", "bvhq"};
    const char *mesh_path = NULL, *only = NULL;
    uint32_t res = 128;
    double min_pct = 99.99;
    lt_mesh_t m;
    lt_scene_t s;
    lt_camera_t cam;
    lt_frame_t ref, fr[4][2];
    lt_diag_t diag;
    int st, path, bad = 0, ran[4][2];
    char why[1024] = "";
    size_t wl = 0;

    {
        int ires = (int)res;
        const lt_opt_t opts[] = {
            LT_OPT_INT("--res", "N", &ires, 4, 4096, "image size N x N, {range} (default 128)"),
            LT_OPT_DBL("--min", "PCT", &min_pct, 0.0, 100.0,
                       "least share of same triangle or tie per structure and path, {range} "
                       "(default 99.99)"),
            LT_OPT_STR("--structures", "a,b,..", &only,
                       "only these of grid, kd, bvh, bvhq (default all)"),
            LT_OPT_END_};
        const lt_opt_cmd_t cmd = {
            "lt-agree", "MESH [options]",
            "Hit agreement of every structure and numeric path with the double-precision\n"
            "reference on a mesh; every differing pixel is explained (tie, edge) or reported.\n",
            "exit status: 0 agreement, 1 a criterion failed or an input error, 2 usage\n", opts,
            &mesh_path, 1, NULL};
        int rc = lt_opt_parse(&cmd, argc, argv, 1);
        if (rc != LT_OPT_OK)
            return lt_opt_exit_code(rc);
        if (mesh_path == NULL) {
            fprintf(stderr, "lt-agree: no mesh given (usage: lt-agree MESH [options])\n");
            return 2;
        }
        res = (uint32_t)ires;
    }
    if (lt_mesh_load(mesh_path, &m, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        return 1;
    }
    if (lt_scene_prepare(&m, &s, &diag) != 0) {
        fprintf(stderr, "%s: %s\n", mesh_path, diag.msg);
        lt_mesh_free(&m);
        return 1;
    }
    /* the same representability rule as run, render and shadows: a scene s15.16 cannot hold is
     * refused, not traced wrong */
    if (lt_scene_check_q16(&s, mesh_path, &diag) != 0) {
        fprintf(stderr, "lt-agree: %s\n", diag.msg);
        lt_scene_free(&s);
        lt_mesh_free(&m);
        return 1;
    }
    lt_camera_default(&s, res, res, &cam);
    if (lt_frame_alloc(&ref, res, res, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        return 1;
    }
    lt_render_reference(&s, &cam, &ref, NULL);
    memset(ran, 0, sizeof ran);
    for (st = 0; st < 4; st++) {
        if (only != NULL && !listed(only, all[st]))
            continue;
        for (path = 0; path < 2; path++) {
            lt_accel_t *acc;
            verdict_t v;
            char label[64];
            double pct;
            const char *base;
            if (st == 3 && path == 1)
                continue; /* the quantised BVH is s15.16 only */
            acc = lt_accel_build(&s, all[st], lt_paths_find(path ? "f32" : "q16", LT_PATHS_OBJECT),
                                 &diag);
            if (acc == NULL || lt_frame_alloc(&fr[st][path], res, res, &diag) != 0) {
                fprintf(stderr, "%s: %s\n", mesh_path, diag.msg);
                return 1;
            }
            lt_render_primary(&s, acc, &cam, &fr[st][path], NULL);
            {
                /* single rays (scalar BVH kernels; one-lane packets elsewhere) = packet lanes */
                lt_frame_t one;
                size_t p, n = (size_t)res * res, same1 = 0, tie1 = 0;
                if (lt_frame_alloc(&one, res, res, &diag) != 0 ||
                    lt_render_primary1(&s, acc, &cam, &one, &diag) != 0) {
                    fprintf(stderr, "%s: %s\n", mesh_path, diag.msg);
                    return 1;
                }
                for (p = 0; p < n; p++) {
                    int32_t i1 = one.id[p], ip = fr[st][path].id[p];
                    same1 += i1 == ip && (i1 < 0 || one.t[p] == fr[st][path].t[p]);
                    /* an exact tie: both hit at the same t bits, another traversal order */
                    tie1 += i1 != ip && i1 >= 0 && ip >= 0 && one.t[p] == fr[st][path].t[p];
                }
                printf("agree %s %s single rays = 16-ray packets (triangle and t bits) on %zu of %zu "
                       "pixels, %zu exact ties (same t, another of the tied triangles)\n",
                       all[st], path ? "f32" : "q16", same1, n, tie1);
                if (same1 + tie1 != n) {
                    bad = 1;
                    wl += (size_t)snprintf(why + wl, wl < sizeof why ? sizeof why - wl : 0,
                                           "; %s %s single rays differ from packets on %zu pixels",
                                           all[st], path ? "f32" : "q16", n - same1 - tie1);
                }
                lt_frame_free(&one);
            }
            lt_accel_free(acc);
            ran[st][path] = 1;
            snprintf(label, sizeof label, "%s %s", all[st], path ? "f32" : "q16");
            classify(&s, &cam, path, &fr[st][path], &ref, label, &v);
            pct = 100.0 * (v.same + v.ties) / v.pixels;
            base = strrchr(mesh_path, '/') != NULL ? strrchr(mesh_path, '/') + 1 : mesh_path;
            printf("agree %-26s %-5s %ux%u: same triangle %.3f%% of %u pixels, + %u ties (%u coplanar) = "
                   "%.3f%%; %u edge, %u unexplained (border distances within %.3f of the bound)\n",
                   base, label, res, res, 100.0 * v.same / v.pixels, v.pixels, v.ties,
                   v.ties_coplanar, pct, v.edges, v.unexplained, v.max_rel_delta);
            if (v.unexplained > 0) {
                bad = 1;
                wl += (size_t)snprintf(why + wl, wl < sizeof why ? sizeof why - wl : 0,
                                       "; %s: %u unexplained pixel%s", label, v.unexplained,
                                       v.unexplained == 1 ? "" : "s");
            }
            if (pct < min_pct) {
                bad = 1;
                wl += (size_t)snprintf(why + wl, wl < sizeof why ? sizeof why - wl : 0,
                                       "; %s: same triangle or tie %.4f%% < %.4f%%", label, pct,
                                       min_pct);
            }
        }
    }
    /* the structures against each other, per path: same id and the same t bits */
    for (path = 0; path < 2; path++) {
        int first = -1;
        for (st = 0; st < 4; st++) {
            size_t p, n = (size_t)res * res, sid = 0, st_bits = 0;
            if (!ran[st][path])
                continue;
            if (first < 0) {
                first = st;
                continue;
            }
            for (p = 0; p < n; p++) {
                sid += fr[st][path].id[p] == fr[first][path].id[p];
                st_bits += fr[st][path].id[p] == fr[first][path].id[p] &&
                           (fr[st][path].id[p] < 0 || fr[st][path].t[p] == fr[first][path].t[p]);
            }
            printf("agree %s %s vs %s: same triangle %zu of %zu pixels, same triangle and t %zu\n",
                   path ? "f32" : "q16", all[st], all[first], sid, n, st_bits);
        }
    }
    if (bad)
        printf("agree verdict: FAIL%s\n", wl < sizeof why ? why : "; (more criteria failed than fit)");
    else
        printf("agree verdict: ok (no unexplained difference, >= %.2f%% same triangle or tie, single "
               "rays = packets)\n", min_pct);
    return bad;
}
