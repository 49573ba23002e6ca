/* lt_path_q16.h - the host's s15.16 numeric path (registry entry "q16"): the generic LTH_* names
 * of the host's per-path templates (lt_render_path.inc, lt_softshadow_path.inc) mapped onto the
 * core's _q16 entry points and types by token pasting, and the few conversions and lane helpers
 * whose arithmetic differs between fixed point and float. Include it, then a template, then
 * lt_path_undef.h (lt_render_paths.c shows the pattern). Host only.
 */
#define LTH_FN(name) name##_q16   /* a core entry point, or a host name generated per path */
#define LTH_TY(name) name##_q16_t /* a core type */
#define LTH_MID(a, b) a##_q16##b  /* a core name with the suffix inside: lt_ray16_q16_setup */
#define LTH_TRIS(s) ((s)->tq)     /* the scene's triangles in this path */
#define LTH_T lt_q16_t            /* positions, distances, irradiance: s15.16 */
#define LTH_D lt_q30_t            /* directions, normals: s1.30 */
/* double -> the path (half up, saturating) and back (exact) */
#define LTH_POS(x) lt_q16_from_double_sat(x)
#define LTH_DIR(x) lt_q30_from_double_sat(x)
#define LTH_POS_D(x) ((double)(x) / 65536.0)
#define LTH_DIR_D(x) ((double)(x) / 1073741824.0)
/* a single ray's initial tmax ("infinite") */
#define LTH_TMAX1 (LT_Q16_MAX - 1)
/* object space: the BVH with quantised nodes exists (1) or not (0); the scene check (or NULL) */
#define LTH_IF_BVHQ(x) x
#define LTH_HAS_BVHQ 1
#define LTH_SCENE_CHECK lt_scene_check_q16
