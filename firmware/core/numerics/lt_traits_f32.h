/* lt_traits_f32.h - the float32 numeric path under the generic LTN_* names (see
 * lt_traits_q16.h). Builds: all with LT_CFG_FLOAT32.
 */
LT_INLINE float lt__f32_sadd(float a, float b) { return a + b; }
LT_INLINE float lt__f32_ssub(float a, float b) { return a - b; }
#define LTN_FN(name) name##_f32
#define LTN_T float
#define LTN_V lt_vf32_t
#define LTN_RAY lt_ray16_f32_t
#define LTN_AABB lt_aabb_f32_t
#define LTN_TRI lt_tri_f32_t
#define LTN_SET1 lt_vf32_set1
#define LTN_SUB lt_vf32_sub
#define LTN_ADD lt_vf32_add
#define LTN_MULR lt_vf32_mul
#define LTN_MIN lt_vf32_min
#define LTN_MAX lt_vf32_max
#define LTN_BLEND lt_vf32_blend
#define LTN_CMPLE_M lt_vf32_cmple_m
#define LTN_CMPLT_M lt_vf32_cmplt_m
#define LTN_CMPGT_M lt_vf32_cmpgt_m
#define LTN_CMPGE_M lt_vf32_cmpge_m
#define LTN_HMIN lt_vf32_hmin
#define LTN_HMAX lt_vf32_hmax
#define LTN_SADD lt__f32_sadd
#define LTN_SSUB lt__f32_ssub
#define LTN_SMIN lt__f32_min
#define LTN_SMAX lt__f32_max
#define LTN_TMAX_INF 3.40282347e38f
