/* kdgrid_sweep.c - parameter sweep of the kd-tree and the uniform grid on one scene, in the sim
 * build: for each kd parameter set and each grid lambda, the structure's size and the lrb16
 * counters per packet and per ray over the default camera view (4x4-pixel s15.16 packets).
 * Prints the numbers docs/kdtree-grid.md quotes for its defaults. Host + sim only.
 * Usage: kdgrid-sweep [scene.obj [resolution]]   (defaults: scenes/teapot.obj 128)
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lt/lt_grid.h"
#include "lt/lt_kd.h"
#include "render/lt_scene.h"
#include "lt_sim.h"

/* NODES, TRIS, TRI_RAYS summed over phases, and modelled cycles. */
static void totals(uint64_t *nodes, uint64_t *tris, uint64_t *tri_rays, uint64_t *cycles)
{
    lt_sim_totals_t t;
    int ph;
    lt_sim_totals(&t);
    *nodes = *tris = *tri_rays = 0;
    for (ph = 0; ph < LT_PH__COUNT; ph++) {
        *nodes += t.ctr[ph][LT_OP__COUNT + LT_EV_NODES];
        *tris += t.ctr[ph][LT_OP__COUNT + LT_EV_TRIS];
        *tri_rays += t.ctr[ph][LT_OP__COUNT + LT_EV_TRI_RAYS];
    }
    *cycles = t.total_cycles;
}

/* Trace the camera view with the kd-tree (kd != NULL) or the grid; print one line. */
static void run(const char *label, const lt_camera_t *cam, uint32_t res, const lt_kd_q16_t *kd,
                const lt_grid_q16_t *g, size_t bytes)
{
    uint64_t rays = 0, packets = 0, nd, tr, trr, cy;
    uint32_t tx, ty;
    lt_sim_reset();
    for (ty = 0; ty < res; ty += 4)
        for (tx = 0; tx < res; tx += 4) {
            lt_ray16_q16_t r;
            lt_hit16_t h;
            lt_mask16_t k = lt_camera_packet_q16(cam, tx, ty, &r);
            rays += lt__popcount32(k);
            packets++;
            if (kd != NULL)
                (void)lt_kd_trace16_q16(kd, &r, k, &h);
            else
                (void)lt_grid_trace16_q16(g, &r, k, &h);
        }
    totals(&nd, &tr, &trr, &cy);
    printf("%-40s %9zu B | per packet %6.2f %s %6.2f tri tests | per ray %5.2f tri tests %6.1f "
           "cycles\n",
           label, bytes, (double)nd / (double)packets, kd != NULL ? "nodes" : "cells",
           (double)tr / (double)packets, (double)trr / (double)rays, (double)cy / (double)rays);
}

int main(int argc, char **argv)
{
    static const uint32_t kdp[][4] = {/* leaf_tris, ref_factor, cost_trav, cost_isect */
                                      {2, 4, 15, 20}, {2, 8, 15, 20}, {2, 16, 15, 20},
                                      {1, 4, 15, 20}, {4, 4, 15, 20}, {2, 4, 10, 20},
                                      {2, 4, 30, 20}};
    static const uint32_t q4[] = {16, 32, 48, 64, 128};
    const char *path = argc > 1 ? argv[1] : "scenes/teapot.obj";
    uint32_t res = argc > 2 ? (uint32_t)atoi(argv[2]) : 128u, i;
    lt_mesh_t m;
    lt_scene_t s;
    lt_camera_t cam;
    char label[64];
    lt_diag_t diag;
    if (res == 0 || res > 4096) {
        fprintf(stderr, "kdgrid-sweep: resolution %u outside 1..4096\n", res);
        return 2;
    }
    if (lt_mesh_load(path, &m, &diag) != 0 ||
        lt_scene_prepare(&m, &s, &diag) != 0) {
        fprintf(stderr, "kdgrid-sweep: %s\n", diag.msg);
        return 1;
    }
    lt_mesh_free(&m);
    if (lt_sim_init(lt_sim_machine_find("lrb16"), NULL, NULL, &diag) != 0) {
        fprintf(stderr, "kdgrid-sweep: %s\n", diag.msg);
        return 1;
    }
    lt_camera_default(&s, res, res, &cam);
    printf("%s: %u triangles, %ux%u camera, lrb16, s15.16\n", path, s.ntris, res, res);
    for (i = 0; i < sizeof kdp / sizeof kdp[0]; i++) {
        lt_kd_params_t p;
        lt_kd_q16_t kd;
        size_t sz;
        void *mem;
        lt_kd_params_default(&p);
        p.leaf_tris = kdp[i][0];
        p.ref_factor = kdp[i][1];
        p.cost_trav = kdp[i][2];
        p.cost_isect = kdp[i][3];
        if (lt_kd_size(s.ntris, &p, &sz) != LT_OK || (mem = malloc(sz)) == NULL ||
            lt_kd_build_q16(&kd, s.tq, s.ntris, &p, mem, &sz) != LT_OK) {
            fprintf(stderr, "kdgrid-sweep: kd build failed\n");
            return 1;
        }
        snprintf(label, sizeof label, "kd leaf %u refs x%u trav %u isect %u", p.leaf_tris,
                 p.ref_factor, p.cost_trav, p.cost_isect);
        run(label, &cam, res, &kd, NULL, kd.bytes);
        free(mem);
    }
    for (i = 0; i < sizeof q4 / sizeof q4[0]; i++) {
        lt_grid_params_t p;
        lt_grid_q16_t g;
        size_t sz;
        void *mem;
        p.cells_per_tri_q4 = q4[i];
        if (lt_grid_size_q16(s.tq, s.ntris, &p, &sz) != LT_OK || (mem = malloc(sz)) == NULL ||
            lt_grid_build_q16(&g, s.tq, s.ntris, &p, mem, &sz) != LT_OK) {
            fprintf(stderr, "kdgrid-sweep: grid build failed\n");
            return 1;
        }
        snprintf(label, sizeof label, "grid lambda %.4g (%ux%ux%u)", q4[i] / 16.0, g.res[0],
                 g.res[1], g.res[2]);
        run(label, &cam, res, NULL, &g, g.bytes);
        free(mem);
    }
    lt_sim_shutdown();
    lt_scene_free(&s);
    return 0;
}
