/* lt_path_q30.h - the host's s1.30 screen-space numeric path (registry entries "n64" and "n32",
 * the quadtree's 64- and 32-bit node encodings of one ray format): the generic LTH_* names of
 * lt_reproject_path.inc mapped onto the core's _q30 entry points and types; see lt_path_q16.h.
 * Host only.
 */
#define LTH_FN(name) name##_q30
#define LTH_TY(name) name##_q30_t
#define LTH_MID(a, b) a##_q30##b
/* screen space: the w buffer's element (0 bytes: the float copy is the path's buffer), segment
 * positions (s15.16 pixels) and inverse depths / parameters (s1.30) to double, the mapping */
#define LTH_W lt_q30_t
#define LTH_W_BYTES sizeof(lt_q30_t)
#define LTH_XY_D(x) ((double)(x) / 65536.0)
#define LTH_W_D(x) ((double)(x) / 1073741824.0)
#define LTH_REPROJ_SETUP(src, dst, o, map) lt_reproj_setup((src), (dst), (o), (map), NULL)
/* the quadtree's single-ray walk (lt_qt_trace1_q30) */
#define LTH_IF_QT1(x) x
#define LTH_HAS_QT1 1
