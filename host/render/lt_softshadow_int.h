/* lt_softshadow_int.h - the soft-shadow renderer's state, shared by the path-independent code
 * (lt_softshadow.c) and the per-path template (lt_softshadow_path.inc, through its ops table
 * lt_ss_ops_t). The path's data sits behind void pointers in the path's own formats; every
 * per-pixel and per-triangle element is 4 bytes in every path (s15.16 / s1.30 raw or binary32),
 * so the shared code allocates, registers, hashes and converts them (lt_path_to_double) without
 * knowing the path. Host only.
 */
#ifndef LT_SOFTSHADOW_INT_H
#define LT_SOFTSHADOW_INT_H

#include <string.h>

#include "render/lt_softshadow.h"

/* The bytes of one element of the path's buffers. */
#define LT_SS_ELEM 4u

struct lt_softshadow {
    const lt_scene_t *s;
    const lt_path_info_t *p;   /* the numeric path (o.path) */
    const lt_ss_ops_t *ops;    /* its frusta ops (p->frusta) */
    const void *tris;          /* the scene's triangles in the path */
    lt_camera_t cam;
    lt_ss_light_t light;
    lt_ss_opts_t o;
    uint32_t w, h;
    size_t n;
    void *adeep, *ashal;
    lt_bvh_t deep, shal;
    lt_qmc_sets_t sets;
    /* the path's data: positions, distances, irradiance and visibility in its position format
       (s15.16 or float), normals in its direction format (s1.30 or float) */
    void *tb;                  /* the light's sample table (lt_frusta_table_<p>_t) */
    void *vt;                  /* the primary view table of both primary methods */
    void *lm, *ln;             /* light centre (3 positions), emitting normal (3 directions) */
    void *tn;                  /* per triangle unit normal (3 directions per triangle) */
    /* per pixel (row-major): shadow origin, hit distance, direct term G, E = G V (e), filtered
       (ef), reference (er) and its filtered (efr), V (v) and the reference's (vr); normal */
    void *org[3], *z, *g, *e, *ef, *er, *efr, *v, *vr;
    void *nrm[3];
    void *ray1;                /* the audits' single ray (ops->ray1_bytes) */
    void *scr0;                /* worker 0's scratch (ops->scratch_bytes; lt_par.h) */
    int32_t *id;
    uint8_t *valid, *lit;
    uint16_t *occ[2];
    uint16_t *occ2[2];         /* spp 32: the second pass's occlusion (set ^ 8), else NULL */
    int have[2], last;
    int32_t *pid[2];           /* per pixel: closest-hit id of P-Packet (0) / P-Frusta (1) */
    uint32_t *pt[2];           /* ... and the bits of its t */
    int have_prim[2];
    double *vref;
    lt_ss_counts_t cnt;
};

/* Pixel of lane i of the 4x4 tile at (tx, ty), or SIZE_MAX outside the image. */
static inline size_t lt_ss__pix(const lt_softshadow_t *ss, uint32_t tx, uint32_t ty, int i)
{
    uint32_t x = tx + (uint32_t)(i % 4), y = ty + (uint32_t)(i / 4);
    return x < ss->w && y < ss->h ? (size_t)y * ss->w + x : (size_t)-1;
}

/* Keep one primary method's answer per pixel (id and the bits of t, 16 lanes of 4 bytes from
 * tmax) for the P-Packet / P-Frusta check; host bookkeeping, not charged. */
static inline void lt_ss__keep_prim(lt_softshadow_t *ss, int which, uint32_t tx, uint32_t ty,
                                    const lt_hit16_t *hit, const void *tmax)
{
    int i;
    for (i = 0; i < LT_LANES; i++) {
        size_t q = lt_ss__pix(ss, tx, ty, i);
        if (q == (size_t)-1)
            continue;
        ss->pid[which][q] = hit->id.l[i];
        memcpy(&ss->pt[which][q], (const char *)tmax + 4 * (size_t)i, 4);
    }
}

#endif /* LT_SOFTSHADOW_INT_H */
