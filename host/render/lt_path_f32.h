/* lt_path_f32.h - the host's float32 numeric path (registry entry "f32"): the generic LTH_* names
 * of the host's per-path templates mapped onto the core's _f32 entry points and types; see
 * lt_path_q16.h. Host only.
 */
#define LTH_FN(name) name##_f32
#define LTH_TY(name) name##_f32_t
#define LTH_MID(a, b) a##_f32##b
#define LTH_TRIS(s) ((s)->tf)
#define LTH_T float
#define LTH_D float
#define LTH_POS(x) ((float)(x))
#define LTH_DIR(x) ((float)(x))
#define LTH_POS_D(x) ((double)(x))
#define LTH_DIR_D(x) ((double)(x))
#define LTH_TMAX1 3.0e38f
#define LTH_IF_BVHQ(x) NULL
#define LTH_HAS_BVHQ 0
#define LTH_SCENE_CHECK NULL
#define LTH_W float
#define LTH_W_BYTES 0
#define LTH_XY_D(x) ((double)(x))
#define LTH_W_D(x) ((double)(x))
#define LTH_REPROJ_SETUP(src, dst, o, map) lt_reproj_setup((src), (dst), (o), NULL, (map))
