/* lt_traits_undef.h - removes the generic LTN_* names of lt_traits_q16.h / lt_traits_f32.h so the
 * next numeric path can define them. Builds: all.
 */
#undef LTN_FN
#undef LTN_T
#undef LTN_V
#undef LTN_RAY
#undef LTN_AABB
#undef LTN_TRI
#undef LTN_SET1
#undef LTN_SUB
#undef LTN_ADD
#undef LTN_MULR
#undef LTN_MIN
#undef LTN_MAX
#undef LTN_BLEND
#undef LTN_CMPLE_M
#undef LTN_CMPLT_M
#undef LTN_CMPGT_M
#undef LTN_CMPGE_M
#undef LTN_HMIN
#undef LTN_HMAX
#undef LTN_SADD
#undef LTN_SSUB
#undef LTN_SMIN
#undef LTN_SMAX
#undef LTN_TMAX_INF
