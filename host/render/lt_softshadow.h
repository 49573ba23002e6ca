/* lt_softshadow.h - the soft-shadow renderer of Benthin & Wald 2009 [Benthin09] on the core's
 * kernels: primary visibility (16-ray packets over 4x4 tiles: P-Packet, or 16 frusta per 16x16
 * block: P-Frusta, from one linear camera), hit points and normals, the direct term toward a quad
 * area light's centre, soft-shadow visibility with 16 samples per pixel either by multi-frusta
 * tracing (one frustum per pixel, 16 per tile: S-Frusta) or by 16-ray packets (one per pixel:
 * S-Packet), shading with fractional visibility, the 4x4 discontinuity filter, a
 * 256-samples-per-pixel packet reference and quality metrics, PNG output. The same code runs in the
 * host and sim builds (the sim charges every lane op; the driver reads counters per stage). Host
 * only; see docs/frusta.md.
 */
#ifndef LT_SOFTSHADOW_H
#define LT_SOFTSHADOW_H

#include "lt/lt_frusta.h"
#include "io/lt_diag.h"
#include "io/lt_mesh.h"
#include "render/lt_render.h"
#include "render/lt_scene.h"

/* A quad light in scaled scene units: points c + u eu + v ev, u, v in [0, 1]. */
typedef struct lt_ss_light {
    double c[3], eu[3], ev[3];
} lt_ss_light_t;

typedef struct lt_ss_opts {
    const lt_path_info_t *path; /* numeric path of every stage (serving LT_PATHS_FRUSTA) */
    uint32_t leaf;       /* frusta BVH: max_leaf (min_leaf = leaf / 2); 1..LT_BVH_MAX_LEAF */
    uint32_t flags;      /* LT_FRUSTA_BACKFACE | LT_FRUSTA_CORNER | LT_FRUSTA_CR */
    lt_qmc_kind_t qmc;   /* sample set */
    uint32_t scramble;   /* digital shift of the 256-point set */
    double depth_rel;    /* filter: relative depth threshold */
    double cos_min;      /* filter: normal cosine threshold */
    double eps;          /* shadow-ray origin offset along the normal, scaled units */
    int filter_vis;      /* 0: filter the irradiance E = G V ([Benthin09]); 1: filter the visibility
                            V and multiply by the unfiltered direct term G afterwards */
    uint32_t pflags;     /* primary rays (both methods): LT_FRUSTA_BACKFACE (cull back faces; the
                            packets skip them per triangle too), LT_FRUSTA_CORNER and LT_FRUSTA_CR
                            (P-Frusta only) */
    uint32_t isect;      /* ray/triangle test of every stage and of the reference: LT_ISECT_WT
                            (watertight, the default: 0) or LT_ISECT_MT (Moller-Trumbore) */
    uint32_t spp;        /* shadow samples per pixel: 4, 8, 16 (the default) or 32. Pixel lane i
                            of a 4x4 tile takes set i of the interleaved sets; 4 and 8 take the
                            first samples of it (the frusta bound only those:
                            lt_frusta_restrict16), 32 adds a second pass with set i ^ 8 */
} lt_ss_opts_t;

/* The accepted values of lt_ss_opts_t.spp, and log2 of one (-1: not accepted). */
#define LT_SS_SPP_LIST "4, 8, 16 or 32"
int lt_ss_spp_log2(uint32_t spp);

/* The default culling sets (--cull bcrflst, --pcull bcrlst): one definition for the renderer's
 * defaults, the shadows CLI and tune's default set. */
#define LT_SS_PFLAGS_DEFAULT                                                                       \
    (LT_FRUSTA_BACKFACE | LT_FRUSTA_CORNER | LT_FRUSTA_CR | LT_FRUSTA_LEAFRAY | LT_FRUSTA_SPLIT |  \
     LT_FRUSTA_TRIPAR)
#define LT_SS_FLAGS_DEFAULT (LT_SS_PFLAGS_DEFAULT | LT_FRUSTA_FS)

/* A culling set as `lanetrace shadows --cull` / `--pcull` spell it into *flags: any of the
 * letters b (back-face), c (corner rays), r (CR), l (ray-AABB leaf culling), s (wide frusta split
 * into packets), t (triangle-parallel leaves), or "none"; with shadow also f (FS: shrink the
 * shadow frusta's direction intervals with their corner rays; implies r) and p (the paper's
 * 256-ray packet walk). Returns 0, or -1 with the first letter not taken in *bad (*flags
 * untouched). */
int lt_ss_parse_cull(const char *text, int shadow, uint32_t *flags, char *bad);

/* Defaults: q16, leaf 8, the default culling sets above, LP samples, no scramble, depth 5%, cos 0.9 (25.8 deg), eps = 2^-12 of the scene
 * radius (rounded to a power of two). */
void lt_ss_opts_default(const lt_scene_t *s, lt_ss_opts_t *o);

/* A horizontal square light (normal -y) of side `size` centred at `centre`, both in mesh file
 * units, converted to scaled units and snapped so its s15.16 edges are multiples of 2^-7 units
 * (LT_FRUSTA_GRID raw). Returns 0, or -1 with a message (outside the geometry bound). */
int lt_ss_light_square(const lt_scene_t *s, const double centre[3], double size, lt_ss_light_t *l,
                       lt_diag_t *diag);

/* Append a ground quad (2 triangles, facing +y) at the mesh's lowest y, spanning its x/z extent
 * grown by `grow` times the extent on each side. Returns 0 or -1 (out of memory). */
int lt_ss_add_ground(lt_mesh_t *m, double grow, lt_diag_t *diag);

/* The view and light used for a shared scene, chosen by the mesh file's base name (bunny,
 * dragon_res3, teapot: default camera, ground quad, light above; sibenik, sponza, conference: an
 * interior camera and a light inside), in mesh file units. */
typedef struct lt_ss_view {
    int has_camera;                   /* 0: lt_camera_default */
    double eye[3], target[3], fov;    /* camera, file units, vertical field of view in degrees */
    double light[3], size;            /* square light centre and side, file units */
    int ground;                       /* add a ground quad (lt_ss_add_ground, grow 0.6) */
} lt_ss_view_t;

/* Returns 1 and fills v when the base name of mesh_path has a view, else 0. */
int lt_ss_view_for(const char *mesh_path, lt_ss_view_t *v);

/* The linear-camera views of a pinhole camera for primary frusta and their packet baseline
 * (lt_frusta_view_*): pixel (x, y) gets the direction fwd + u(x) right + v(y) up of
 * lt_camera_dir (not normalised: d0 + x dx + y dy), scaled by a power of two so that every
 * component stays below 0.75 over the 4x4 tiles touching the image, then rounded to s1.30 raw
 * (q16) and to multiples of 2^-23 (f32, so the float generator is exact). Either output may be
 * NULL. Returns 0, or -1 with a message (eye outside the fixed-point range, degenerate camera). */
int lt_ss_pview(const lt_camera_t *c, uint32_t flags, lt_frusta_view_q16_t *vq,
                lt_frusta_view_f32_t *vf, lt_diag_t *diag);

typedef struct lt_softshadow lt_softshadow_t;

/* Build both trees (the default deep one for packets, the shallow one for frusta), the sample
 * table and per-pixel buffers. In sim builds the scene arrays are registered as sim regions.
 * Returns NULL with a message on error. */
lt_softshadow_t *lt_ss_create(const lt_scene_t *s, const lt_camera_t *cam, const lt_ss_light_t *l,
                              const lt_ss_opts_t *o, lt_diag_t *diag);
void lt_ss_free(lt_softshadow_t *ss);

/* A kernel hit at t (tk) of the ray o + s d against triangle v (9 doubles) is genuine when the
 * exact ray meets the triangle's plane at a parameter within pad of tk, inside the triangle's box
 * padded by pad: every box-pruning traversal provably finds those (docs/frusta.md). The primary
 * audits use pad = LT_SS_GENUINE_PAD, a quarter of the BVH's pad. */
#define LT_SS_GENUINE_PAD ((double)LT_BVH_PAD_Q16 / 65536.0 / 4.0)
int lt_ss_hit_genuine(const double o[3], const double d[3], const double v[9], double pad,
                      double tk);

/* Stages. primary: P-Packet traversal (16-ray packets of 4x4 tiles, deep tree, closest hit),
 * hit points, normals, origins, direct term (SHADE). primary_frusta: the same by P-Frusta (16
 * frusta of 4x4 rays per 16x16 block, shallow tree); both trace the same rays (the linear camera
 * of lt_ss_pview), and each keeps its answer per pixel for lt_ss_counts' prim_mismatch.
 * shadows_frusta / shadows_packet: 16 samples per lit pixel. shade: E = G x visible fraction of
 * the given result. filter: 4x4 discontinuity filter of E. reference: 256 samples per pixel by
 * packets (all 16 sets), E_ref = G x visible fraction. */
void lt_ss_primary(lt_softshadow_t *ss);
void lt_ss_primary_frusta(lt_softshadow_t *ss);
void lt_ss_shadows_frusta(lt_softshadow_t *ss);
void lt_ss_shadows_packet(lt_softshadow_t *ss);
#define LT_SS_FRUSTA 0
#define LT_SS_PACKET 1
void lt_ss_shade(lt_softshadow_t *ss, int which);
void lt_ss_filter(lt_softshadow_t *ss);
void lt_ss_reference(lt_softshadow_t *ss, void (*progress)(double done));

typedef struct lt_ss_counts {
    uint64_t pixels;        /* pixels in the image */
    uint64_t primary_rays;  /* primary rays traced */
    uint64_t hits;          /* pixels with a primary hit */
    uint64_t lit;           /* pixels with a positive direct term (they get shadow rays) */
    uint64_t shadow_rays;   /* 16 per lit pixel */
    uint64_t occluded;      /* shadow rays occluded (of the last shadow stage) */
    uint64_t partial;       /* lit pixels with 1..15 occluded samples */
    uint64_t mismatch;      /* pixels where frusta and packet visibility differ (both run) */
    uint64_t prim_mismatch; /* pixels where P-Frusta and P-Packet differ in id or t (both run) */
    uint64_t shadow_skipped; /* pixels left out of `mismatch` and the audit: their primary hits
                                differ, so S-Packet and S-Frusta started from different points */
} lt_ss_counts_t;

void lt_ss_counts(const lt_softshadow_t *ss, lt_ss_counts_t *c);

typedef struct lt_ss_quality {
    double psnr_filtered;   /* E filtered vs E_ref over hit pixels, dB (peak 1) */
    double psnr_raw;        /* E (16 samples, unfiltered) vs E_ref */
    double psnr_filtered_ref; /* E_ref filtered by the same filter vs E_ref (the filter's bias) */
    double psnr_vs_filtered_ref; /* E filtered vs E_ref filtered: what interleaving loses */
    uint64_t penumbra;      /* hit pixels with 0 < V_ref < 1 */
    uint64_t penumbra_ok;   /* of those, |E_filtered - E_ref| <= tol */
    uint64_t penumbra_raw_ok; /* of those, |E - E_ref| <= tol */
    double tol;
} lt_ss_quality_t;

/* Needs reference, shade and filter to have run. */
void lt_ss_quality(const lt_softshadow_t *ss, double tol, lt_ss_quality_t *q);

/* Shaded image (albedo 0.75, ambient 0.08, gamma 2.2; misses dark blue) from the filtered E
 * (which = 0), the unfiltered E (1) or E_ref (2) to an RGB PNG. Returns 0 or -1 with a message. */
int lt_ss_write_png(const lt_softshadow_t *ss, const char *path, int which, lt_diag_t *diag);

/* The S-Frusta work of the 16x16 block at (bx, by) (multiples of 4, inside the image; both
 * UINT32_MAX: the block with the most penumbra pixels) as a frusta blob for a firmware target
 * (firmware/apps/lt_sblob.h): its origins, lit pixels, light, sample sets, and the triangles that
 * can stand between them and the light (a crop: every triangle whose projection on one of 22
 * directions misses the projection of the origins and light corners is left out, which cannot
 * change an answer) under a shallow BVH of the renderer's leaf size. Needs the s15.16 path, spp
 * <= 16 and lt_ss_shadows_frusta to have run; LT_FB_REF holds the whole scene's block hash.
 * *blob is malloc'ed. Returns 0, or -1 with a message. */
int lt_ss_pack_block(const lt_softshadow_t *ss, uint32_t bx, uint32_t by, uint8_t **blob,
                     size_t *bytes, lt_diag_t *diag);

/* FNV-1a over the per-pixel occlusion bits of the last shadow stage and the filtered E: equal
 * across the host and sim builds. */
uint32_t lt_ss_hash(const lt_softshadow_t *ss);

/* Audit of the samples where frusta and packet visibility differ (both stages run; pixels whose
 * primary hits differ are left out, see shadow_skipped): each such
 * sample is re-traced by brute force with the single-ray kernel over every triangle. A kernel hit
 * is "genuine" when the exact ray meets the triangle's plane inside the triangle's box padded by
 * LT_BVH_PAD_Q16 (what a box-pruning traversal must find) and "spurious" otherwise (a grazing ray
 * whose rounded barycentrics accept a point off the triangle: a box traversal may prune it).
 * A method is right on a sample when a genuine hit implies occluded and occluded implies some
 * kernel hit; `errors` counts samples where frusta or packet is not. */
typedef struct lt_ss_audit {
    uint64_t samples;  /* differing samples */
    uint64_t spurious; /* of those, explained by spurious kernel hits only */
    uint64_t errors;   /* of those, a method is wrong */
    uint64_t ref[2];   /* primary audit: of those, P-Packet (0) / P-Frusta (1) equal to the
                          brute-force closest hit (the other method pruned a non-genuine hit) */
} lt_ss_audit_t;

void lt_ss_audit(const lt_softshadow_t *ss, lt_ss_audit_t *a);

/* The same for primary rays: each pixel where P-Frusta and P-Packet differ is re-traced by brute
 * force; a method is right when its answer is a kernel hit of the ray (or a miss) and every
 * kernel hit before it in (t, id) order is spurious. */
void lt_ss_primary_audit(const lt_softshadow_t *ss, lt_ss_audit_t *a);

/* FNV-1a over the primary buffers of the last primary stage (id, valid, lit, t, G, shadow
 * origin, normal per pixel): P-Frusta and P-Packet give the same value when their images agree. */
uint32_t lt_ss_primary_hash(const lt_softshadow_t *ss);

/* Per-pixel occlusion bits of the frusta / packet stage (NULL before it ran), w x h. */
const uint16_t *lt_ss_occlusion(const lt_softshadow_t *ss, int which);

/* Primary hit origins (offset shadow-ray origins) in double scaled units and the lit mask, for
 * external benchmarks (Embree race): o[3 * pixel], lit[pixel]. */
void lt_ss_origins(const lt_softshadow_t *ss, double *o, uint8_t *lit);

/* The light as used (scaled units, snapped) and one sample point (set s, sample j). */
void lt_ss_sample_point(const lt_softshadow_t *ss, unsigned set, unsigned j, double p[3]);

#endif /* LT_SOFTSHADOW_H */
