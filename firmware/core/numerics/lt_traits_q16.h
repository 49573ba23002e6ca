/* lt_traits_q16.h - the s15.16 numeric path for kernels written once (lt_*.inc): lane type, scalar
 * type and the basic lane ops under generic LTN_* names. A kernel module includes this, then its
 * .inc, then lt_traits_undef.h, then lt_traits_f32.h and the .inc again. Module-specific traits
 * (e.g. the triangle test's products) are defined by the module next to the include.
 * Builds: all.
 */
#define LTN_FN(name) name##_q16
#define LTN_T lt_q16_t
#define LTN_V lt_vq16_t
#define LTN_RAY lt_ray16_q16_t
#define LTN_AABB lt_aabb_q16_t
#define LTN_TRI lt_tri_q16_t
#define LTN_SET1 lt_vq16_set1
#define LTN_SUB lt_vq16_sub_sat
#define LTN_ADD lt_vq16_add_sat
#define LTN_MULR lt_vq16_mul_sat
#define LTN_MIN lt_vq16_min
#define LTN_MAX lt_vq16_max
#define LTN_BLEND lt_vq16_blend
#define LTN_CMPLE_M lt_vq16_cmple_m
#define LTN_CMPLT_M lt_vq16_cmplt_m
#define LTN_CMPGT_M lt_vq16_cmpgt_m
#define LTN_CMPGE_M lt_vq16_cmpge_m
#define LTN_HMIN lt_vq16_hmin
#define LTN_HMAX lt_vq16_hmax
#define LTN_SADD lt__q16_add_sat
#define LTN_SSUB lt__q16_sub_sat
#define LTN_SMIN lt__q16_min
#define LTN_SMAX lt__q16_max
#define LTN_TMAX_INF LT_Q16_MAX   /* "infinite" distance: larger than any valid tmax */
