/* lt_v16_x86.h - x86 SIMD sequences for the lane ops whose portable loops the compiler turns into
 * long or stalling code: the s15.16 and s1.30 products with rounding and saturation (32x32 ->
 * 64-bit product, + half, arithmetic shift, clamp to int32), the slab test's and the watertight
 * test's hot op; on AVX-512 also every 32-bit integer add, subtract (saturating and wrapping), min,
 * max, or, xor and compare, the float32 compares, the blends and the 32-bit broadcasts, so that
 * the lane vectors between these ops are written and read 512 bits at a time (lt__x86_load16).
 * Chosen at build time from the compiler's target flags: AVX-512F (one 512-bit register per 16
 * lanes: vpmuldq on the even and odd lanes, vpsraq, vpminsq/vpmaxsq, compares into mask registers,
 * masked blends) or AVX2 (two 8-lane halves: vpmuldq pairs, the 64-bit arithmetic shift and clamp
 * built from compares and blends); anything else, -DLT_LANES_PORTABLE, and every firmware target
 * use the portable loops of lt_v16.h, which stay the reference. Bit-identical to the portable
 * lanes (tests/golden/vectors.txt is compared across the native (backend), asan (portable) and
 * x86-64-v3 (AVX2) builds; test_v16 checks every op against references on the backend it was
 * built with). In sim builds the SAT events are counted per lane as the portable loop counts them.
 * Builds: host x86 only.
 */
#ifndef LT_V16_X86_H
#define LT_V16_X86_H

#if !defined(LT_LANES_PORTABLE) && defined(__AVX512F__)
#define LT_LANES_BACKEND "avx512"
#define LT__X86_LANES 512
#elif !defined(LT_LANES_PORTABLE) && defined(__AVX2__)
#define LT_LANES_BACKEND "avx2"
#define LT__X86_LANES 256
#else
#define LT_LANES_BACKEND "portable"
#define LT__X86_LANES 0
#endif

#if LT__X86_LANES
#include <immintrin.h>

#if LT__X86_LANES == 512
/* The 16 lanes at p as one 512-bit register: lt__x86_load16 in one load, for lanes that the
 * backend's own ops wrote (one 512-bit store each); lt__x86_load16h as two 256-bit halves, for
 * lanes that the portable loops wrote. Where the compiler prefers 256-bit vectors (-march=native
 * on Intel cores: -mprefer-vector-width=256) a loop stores its result 256 bits at a time, and a
 * 512-bit load of two such stores cannot take its data from the store buffer: it waits for both
 * stores to reach the cache (a store-forwarding stall, measured as the slab test's largest cost
 * on a Rocket Lake Xeon). Two 256-bit loads forward from either store width; one 512-bit load
 * is the cheaper where the store was 512 bits wide. */
LT_INLINE __m512i lt__x86_load16(const void *p)
{
    return _mm512_loadu_si512(p);
}
LT_INLINE __m512i lt__x86_load16h(const void *p)
{
    const __m256i *h = (const __m256i *)p;
    return _mm512_inserti64x4(_mm512_castsi256_si512(_mm256_loadu_si256(h)),
                              _mm256_loadu_si256(h + 1), 1);
}
#endif

/* r[i] = sat32((a[i] * b[i] + 2^(f-1)) >> f) for the 16 lanes (1 <= f <= 31); in sim builds the
 * lanes of ev whose result saturated are counted as SAT events. */
/* The SAT events of the lanes of sat that are in ev (sim builds; nothing elsewhere). */
#if LT_COST_MODE == LT_COST_SIM
#define LT__X86_SAT_EVENTS(sat, ev) LT_EVENT(SAT, lt__popcount32((unsigned)(sat) & (unsigned)(ev)))
#else
#define LT__X86_SAT_EVENTS(sat, ev) ((void)(sat), (void)(ev))
#endif
#if LT__X86_LANES == 512

/* sat32((a * b + 2^(f-1)) >> f) on the 16 lanes of two registers: vpmuldq on the even lanes and on
 * the odd lanes shifted down, the rounding constant, vpsraq, the int32 clamp, the two halves
 * merged back; SAT events for the lanes of ev whose result saturated. */
LT_INLINE __m512i lt__x86_mulr(__m512i va, __m512i vb, unsigned f, lt_mask16_t ev)
{
    __m512i rnd = _mm512_set1_epi64((long long)1 << (f - 1u));
    __m128i sh = _mm_cvtsi32_si128((int)f);
    __m512i hi = _mm512_set1_epi64(INT32_MAX), lo = _mm512_set1_epi64(INT32_MIN);
    /* even lanes: the low halves of each 64-bit pair; odd lanes: shifted down into them */
    __m512i pe = _mm512_mul_epi32(va, vb);
    __m512i po = _mm512_mul_epi32(_mm512_srli_epi64(va, 32), _mm512_srli_epi64(vb, 32));
    pe = _mm512_sra_epi64(_mm512_add_epi64(pe, rnd), sh);
    po = _mm512_sra_epi64(_mm512_add_epi64(po, rnd), sh);
#if LT_COST_MODE == LT_COST_SIM
    {
        unsigned se = (unsigned)(_mm512_cmpgt_epi64_mask(pe, hi) | _mm512_cmplt_epi64_mask(pe, lo));
        unsigned so = (unsigned)(_mm512_cmpgt_epi64_mask(po, hi) | _mm512_cmplt_epi64_mask(po, lo));
        unsigned m = 0, i;
        for (i = 0; i < 8; i++)
            m |= ((se >> i) & 1u) << (2 * i) | ((so >> i) & 1u) << (2 * i + 1);
        LT__X86_SAT_EVENTS(m, ev);
    }
#else
    (void)ev;
#endif
    pe = _mm512_max_epi64(_mm512_min_epi64(pe, hi), lo);
    po = _mm512_max_epi64(_mm512_min_epi64(po, hi), lo);
    /* lane 2i = low dword of pe's qword i, lane 2i+1 = low dword of po's qword i */
    return _mm512_mask_blend_epi32((__mmask16)0xAAAA, pe, _mm512_slli_epi64(po, 32));
}

LT_INLINE void lt__x86_mul_round_sat(const int32_t *a, const int32_t *b, int32_t *r, unsigned f,
                                     lt_mask16_t ev)
{
    _mm512_storeu_si512((void *)r, lt__x86_mulr(lt__x86_load16(a), lt__x86_load16(b), f, ev));
}

/* The register bodies of the 32-bit integer lane ops (lt_v16.h's LT__V16_BINV on this backend:
 * every lane vector an op writes is one 512-bit store, read back by lt__x86_load16), each
 * bit-identical to its scalar body in lt_fx.h. The saturating add and subtract clamp where the
 * wrapped result's sign differs from both operands' (add) or from a's where the operands' signs
 * differ (subtract), to INT32_MAX for a >= 0 and INT32_MIN for a < 0; ev: the lanes whose
 * saturations count as SAT events. */
/* r where the lanes of ovf (sign bit set: the wrapped result overflowed) hold the clamp of a's
 * sign instead; SAT events for those of ev. */
LT_INLINE __m512i lt__x86_qsat(__m512i r, __m512i a, __m512i ovf, lt_mask16_t ev)
{
    __mmask16 o = _mm512_cmplt_epi32_mask(ovf, _mm512_setzero_si512());
    LT__X86_SAT_EVENTS(o, ev);
    return _mm512_mask_mov_epi32(
        r, o, _mm512_xor_si512(_mm512_srai_epi32(a, 31), _mm512_set1_epi32(INT32_MAX)));
}
LT_INLINE __m512i lt__x86_qadd(__m512i a, __m512i b, lt_mask16_t ev)
{
    __m512i r = _mm512_add_epi32(a, b);
    return lt__x86_qsat(r, a, _mm512_andnot_si512(_mm512_xor_si512(a, b), _mm512_xor_si512(a, r)),
                        ev);
}
LT_INLINE __m512i lt__x86_qsub(__m512i a, __m512i b, lt_mask16_t ev)
{
    __m512i r = _mm512_sub_epi32(a, b);
    return lt__x86_qsat(r, a, _mm512_and_si512(_mm512_xor_si512(a, b), _mm512_xor_si512(a, r)), ev);
}
/* wrapping add and subtract, min, max, or, xor: no events */
#define LT__X86_BODY(name, expr)                                                                   \
    LT_INLINE __m512i lt__x86_##name(__m512i a, __m512i b, lt_mask16_t ev)                        \
    {                                                                                              \
        (void)ev;                                                                                  \
        return expr;                                                                               \
    }
LT__X86_BODY(add, _mm512_add_epi32(a, b))
LT__X86_BODY(sub, _mm512_sub_epi32(a, b))
LT__X86_BODY(min, _mm512_min_epi32(a, b))
LT__X86_BODY(max, _mm512_max_epi32(a, b))
LT__X86_BODY(or, _mm512_or_si512(a, b))
LT__X86_BODY(xor, _mm512_xor_si512(a, b))
#undef LT__X86_BODY
LT_INLINE __m512i lt__x86_mul16(__m512i a, __m512i b, lt_mask16_t ev) { return lt__x86_mulr(a, b, 16u, ev); }
LT_INLINE __m512i lt__x86_mul30(__m512i a, __m512i b, lt_mask16_t ev) { return lt__x86_mulr(a, b, 30u, ev); }

/* The compares' 16-bit lane masks in one instruction: signed int32 (vpcmpd) and float32
 * (vcmpps, ordered and quiet: a NaN lane compares false, as C's relational operators). */
#define LT__X86_CMP(name, expr)                                                                    \
    LT_INLINE unsigned lt__x86_cmp_##name(__m512i a, __m512i b) { return (unsigned)(expr); }
LT__X86_CMP(lt, _mm512_cmp_epi32_mask(a, b, _MM_CMPINT_LT))
LT__X86_CMP(le, _mm512_cmp_epi32_mask(a, b, _MM_CMPINT_LE))
LT__X86_CMP(gt, _mm512_cmp_epi32_mask(a, b, _MM_CMPINT_NLE))
LT__X86_CMP(ge, _mm512_cmp_epi32_mask(a, b, _MM_CMPINT_NLT))
LT__X86_CMP(eq, _mm512_cmp_epi32_mask(a, b, _MM_CMPINT_EQ))
LT__X86_CMP(flt, _mm512_cmp_ps_mask(_mm512_castsi512_ps(a), _mm512_castsi512_ps(b), _CMP_LT_OQ))
LT__X86_CMP(fle, _mm512_cmp_ps_mask(_mm512_castsi512_ps(a), _mm512_castsi512_ps(b), _CMP_LE_OQ))
LT__X86_CMP(fgt, _mm512_cmp_ps_mask(_mm512_castsi512_ps(a), _mm512_castsi512_ps(b), _CMP_GT_OQ))
LT__X86_CMP(fge, _mm512_cmp_ps_mask(_mm512_castsi512_ps(a), _mm512_castsi512_ps(b), _CMP_GE_OQ))
LT__X86_CMP(feq, _mm512_cmp_ps_mask(_mm512_castsi512_ps(a), _mm512_castsi512_ps(b), _CMP_EQ_OQ))
#undef LT__X86_CMP

/* The lane model's horizontal min (ismax 0) or max (1) of the lanes of k of the 16 int32 or float32
 * (isf) lanes at a, starting from *none, as its loop computes it: *none takes a lane's value
 * only where that value is strictly less (greater) than the current one, lanes in index order.
 * So the result is *none unless the reduction m over the active lanes beats it, and then the
 * first active lane equal to m: of float lanes -0 and +0, the loop keeps the first; NaN lanes
 * never compare and are left out. One masked reduction and a compare instead of a branch per
 * lane. */
LT_INLINE void lt__x86_hred32(lt_mask16_t k, const void *a, void *none, int isf, int ismax)
{
    if (k == 0)
        return;
    if (isf) {
        __m512 v = _mm512_castsi512_ps(lt__x86_load16h(a));
        __mmask16 on = _mm512_mask_cmp_ps_mask((__mmask16)k, v, v, _CMP_ORD_Q);
        float n = *(const float *)none, m;
        __mmask16 eq;
        if (on == 0)
            return;
        m = ismax ? _mm512_mask_reduce_max_ps(on, v) : _mm512_mask_reduce_min_ps(on, v);
        if (!(ismax ? m > n : m < n))
            return;
        eq = _mm512_mask_cmp_ps_mask(on, v, _mm512_set1_ps(m), _CMP_EQ_OQ);
        *(float *)none = ((const float *)a)[lt__ctz32(eq)];
    } else {
        __m512i v = lt__x86_load16h(a);
        int32_t n = *(const int32_t *)none;
        int32_t m = ismax ? _mm512_mask_reduce_max_epi32((__mmask16)k, v)
                          : _mm512_mask_reduce_min_epi32((__mmask16)k, v);
        if (ismax ? m > n : m < n)
            *(int32_t *)none = m;
    }
}

/* The 16 lanes at r set to the 32-bit pattern x in one 512-bit store. */
LT_INLINE void lt__x86_set1_32(int32_t x, void *r) { _mm512_storeu_si512(r, _mm512_set1_epi32(x)); }
#else
/* 64-bit arithmetic shift right by sh and clamp to the int32 range, 4 lanes (AVX2). */
LT_INLINE __m256i lt__x86_sra_sat64(__m256i x, __m128i sh, __m128i shl, __m256i hi, __m256i lo,
                                    unsigned *sat)
{
    __m256i neg = _mm256_cmpgt_epi64(_mm256_setzero_si256(), x);
    __m256i gt, lt;
    x = _mm256_or_si256(_mm256_srl_epi64(x, sh), _mm256_sll_epi64(neg, shl));
    gt = _mm256_cmpgt_epi64(x, hi);
    lt = _mm256_cmpgt_epi64(lo, x);
    *sat = (unsigned)_mm256_movemask_pd(_mm256_castsi256_pd(_mm256_or_si256(gt, lt)));
    x = _mm256_blendv_epi8(x, hi, gt);
    return _mm256_blendv_epi8(x, lo, lt);
}

LT_INLINE __m256i lt__x86_mulr8(__m256i va, __m256i vb, unsigned f, unsigned ev8);
LT_INLINE void lt__x86_mul_round_sat(const int32_t *a, const int32_t *b, int32_t *r, unsigned f,
                                     lt_mask16_t ev)
{
    int h;
    for (h = 0; h < 2; h++)
        _mm256_storeu_si256((__m256i *)(void *)(r + 8 * h),
                            lt__x86_mulr8(_mm256_loadu_si256((const __m256i *)(const void *)(a + 8 * h)),
                                          _mm256_loadu_si256((const __m256i *)(const void *)(b + 8 * h)),
                                          f, ((unsigned)ev >> (8 * h)) & 0xFFu));
}
#endif

#if LT__X86_LANES == 256
/* The register bodies of the 32-bit integer lane ops on AVX2 (lt_v16.h's LT__V16_BINV and
 * LT__V16_CMPV on this backend): 8 lanes each, a 16-lane op as two 256-bit halves, each half one
 * whole 256-bit store that the next op's 256-bit load forwards from (the portable loops' int64
 * saturation became 64-bit lane code); each bit-identical to its scalar body in lt_fx.h. ev8: the
 * half's lanes whose saturations count as SAT events. */
LT_INLINE unsigned lt__x86_bits8(__m256i m)
{
    return (unsigned)_mm256_movemask_ps(_mm256_castsi256_ps(m));
}
LT_INLINE __m256i lt__x86_qsat8(__m256i r, __m256i a, __m256i ovf, unsigned ev8)
{
    __m256i o = _mm256_srai_epi32(ovf, 31);
    LT__X86_SAT_EVENTS(lt__x86_bits8(o), ev8);
    return _mm256_blendv_epi8(
        r, _mm256_xor_si256(_mm256_srai_epi32(a, 31), _mm256_set1_epi32(INT32_MAX)), o);
}
LT_INLINE __m256i lt__x86_qadd8(__m256i a, __m256i b, unsigned ev8)
{
    __m256i r = _mm256_add_epi32(a, b);
    return lt__x86_qsat8(r, a, _mm256_andnot_si256(_mm256_xor_si256(a, b), _mm256_xor_si256(a, r)),
                         ev8);
}
LT_INLINE __m256i lt__x86_qsub8(__m256i a, __m256i b, unsigned ev8)
{
    __m256i r = _mm256_sub_epi32(a, b);
    return lt__x86_qsat8(r, a, _mm256_and_si256(_mm256_xor_si256(a, b), _mm256_xor_si256(a, r)),
                         ev8);
}
#define LT__X86_BODY8(name, expr)                                                                  \
    LT_INLINE __m256i lt__x86_##name##8(__m256i a, __m256i b, unsigned ev8)                       \
    {                                                                                              \
        (void)ev8;                                                                                 \
        return expr;                                                                               \
    }
LT__X86_BODY8(add, _mm256_add_epi32(a, b))
LT__X86_BODY8(sub, _mm256_sub_epi32(a, b))
LT__X86_BODY8(min, _mm256_min_epi32(a, b))
LT__X86_BODY8(max, _mm256_max_epi32(a, b))
LT__X86_BODY8(or, _mm256_or_si256(a, b))
LT__X86_BODY8(xor, _mm256_xor_si256(a, b))
#undef LT__X86_BODY8
/* sat32((a * b + 2^(f-1)) >> f) on 8 lanes without AVX2's missing 64-bit arithmetic shift: with
 * x = a b + 2^(f-1) (vpmuldq on the even lanes and the odd lanes shifted down), t = x + 2^(31+f)
 * lies in [0, 2^(32+f)) exactly when x >> f fits int32, and then the low 32 bits of t >> f (a
 * logical shift) are (x >> f) + 2^31; out of range the result is the clamp of the product's sign,
 * that of a ^ b (the product is not zero there). */
LT_INLINE __m256i lt__x86_mulr8(__m256i va, __m256i vb, unsigned f, unsigned ev8)
{
    __m256i c = _mm256_set1_epi64x((long long)(((uint64_t)1 << (f - 1u)) + ((uint64_t)1 << (31u + f))));
    __m128i sh = _mm_cvtsi32_si128((int)f), shr = _mm_cvtsi32_si128(32 + (int)f);
    __m256i te = _mm256_add_epi64(_mm256_mul_epi32(va, vb), c);
    __m256i to = _mm256_add_epi64(
        _mm256_mul_epi32(_mm256_srli_epi64(va, 32), _mm256_srli_epi64(vb, 32)), c);
    __m256i z = _mm256_setzero_si256();
    __m256i r = _mm256_blend_epi32(_mm256_srl_epi64(te, sh), _mm256_slli_epi64(_mm256_srl_epi64(to, sh), 32),
                                   0xAA);
    __m256i ok = _mm256_blend_epi32(_mm256_cmpeq_epi64(_mm256_srl_epi64(te, shr), z),
                                    _mm256_cmpeq_epi64(_mm256_srl_epi64(to, shr), z), 0xAA);
    __m256i satv = _mm256_xor_si256(_mm256_srai_epi32(_mm256_xor_si256(va, vb), 31),
                                    _mm256_set1_epi32(INT32_MAX));
    LT__X86_SAT_EVENTS(~lt__x86_bits8(ok) & 0xFFu, ev8);
    (void)ev8;
    return _mm256_blendv_epi8(satv, _mm256_xor_si256(r, _mm256_set1_epi32(INT32_MIN)), ok);
}
LT_INLINE __m256i lt__x86_mul168(__m256i a, __m256i b, unsigned ev8) { return lt__x86_mulr8(a, b, 16u, ev8); }
LT_INLINE __m256i lt__x86_mul308(__m256i a, __m256i b, unsigned ev8) { return lt__x86_mulr8(a, b, 30u, ev8); }
/* the lanes of k8 as a lane mask (all ones where on) */
LT_INLINE __m256i lt__x86_mask8(unsigned k8)
{
    const __m256i bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    return _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32((int)k8), bits), bits);
}
/* compares: 8-bit masks; float compares ordered and quiet (a NaN lane compares false) */
#define LT__X86_CMP8(name, expr)                                                                   \
    LT_INLINE unsigned lt__x86_cmp8_##name(__m256i a, __m256i b) { return (expr) & 0xFFu; }
LT__X86_CMP8(lt, lt__x86_bits8(_mm256_cmpgt_epi32(b, a)))
LT__X86_CMP8(le, ~lt__x86_bits8(_mm256_cmpgt_epi32(a, b)))
LT__X86_CMP8(gt, lt__x86_bits8(_mm256_cmpgt_epi32(a, b)))
LT__X86_CMP8(ge, ~lt__x86_bits8(_mm256_cmpgt_epi32(b, a)))
LT__X86_CMP8(eq, lt__x86_bits8(_mm256_cmpeq_epi32(a, b)))
LT__X86_CMP8(flt, (unsigned)_mm256_movemask_ps(_mm256_cmp_ps(_mm256_castsi256_ps(a), _mm256_castsi256_ps(b), _CMP_LT_OQ)))
LT__X86_CMP8(fle, (unsigned)_mm256_movemask_ps(_mm256_cmp_ps(_mm256_castsi256_ps(a), _mm256_castsi256_ps(b), _CMP_LE_OQ)))
LT__X86_CMP8(fgt, (unsigned)_mm256_movemask_ps(_mm256_cmp_ps(_mm256_castsi256_ps(a), _mm256_castsi256_ps(b), _CMP_GT_OQ)))
LT__X86_CMP8(fge, (unsigned)_mm256_movemask_ps(_mm256_cmp_ps(_mm256_castsi256_ps(a), _mm256_castsi256_ps(b), _CMP_GE_OQ)))
LT__X86_CMP8(feq, (unsigned)_mm256_movemask_ps(_mm256_cmp_ps(_mm256_castsi256_ps(a), _mm256_castsi256_ps(b), _CMP_EQ_OQ)))
#undef LT__X86_CMP8
LT_INLINE __m256i lt__x86_load8(const void *p) { return _mm256_loadu_si256((const __m256i *)p); }
#endif

/* r = b in the lanes of k, a elsewhere, for 16 lanes of 32 bits (the lane model's blend): one
 * masked blend with the mask in a mask register (AVX-512), or the mask expanded by one compare per
 * half (AVX2), instead of a loop over the mask's bits. */
LT_INLINE void lt__x86_blend32(lt_mask16_t k, const void *a, const void *b, void *r)
{
#if LT__X86_LANES == 512
    _mm512_storeu_si512(r, _mm512_mask_blend_epi32((__mmask16)k, lt__x86_load16h(a),
                                                   lt__x86_load16h(b)));
#else
    const __m256i bits = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    int h;
    for (h = 0; h < 2; h++) {
        __m256i m = _mm256_and_si256(_mm256_set1_epi32((int)((unsigned)k >> (8 * h))), bits);
        m = _mm256_cmpeq_epi32(m, bits);
        _mm256_storeu_si256((__m256i *)r + h,
                            _mm256_blendv_epi8(_mm256_loadu_si256((const __m256i *)a + h),
                                               _mm256_loadu_si256((const __m256i *)b + h), m));
    }
#endif
}

/* One plane of the wide BVH's node test in s15.16, 8 lanes: t[c] = sat32(round((sat32(p[c] - o)
 * x rd) / 2^16)), half up, as lt__q16_mul_sat(lt__q16_sub_sat(p[c], o), rd) per lane; in sim
 * builds both saturations counted per lane as there. On AVX-512 in a register
 * (lt__x86_plane8r_q16, the wide node test's register form) and stored. */
#if LT__X86_LANES == 512
LT_INLINE __m256i lt__x86_plane8r_q16(const int32_t *p, int32_t o, int32_t rd)
{
    __m512i hi = _mm512_set1_epi64(INT32_MAX), lo = _mm512_set1_epi64(INT32_MIN);
    __m512i d = _mm512_sub_epi64(
        _mm512_cvtepi32_epi64(_mm256_loadu_si256((const __m256i *)(const void *)p)),
        _mm512_set1_epi64(o));
    __m512i q;
#if LT_COST_MODE == LT_COST_SIM
    unsigned sd = (unsigned)(_mm512_cmpgt_epi64_mask(d, hi) | _mm512_cmplt_epi64_mask(d, lo)), sq;
#endif
    d = _mm512_max_epi64(_mm512_min_epi64(d, hi), lo);
    q = _mm512_mul_epi32(d, _mm512_set1_epi64(rd));
    q = _mm512_srai_epi64(_mm512_add_epi64(q, _mm512_set1_epi64((long long)1 << 15)), 16);
#if LT_COST_MODE == LT_COST_SIM
    sq = (unsigned)(_mm512_cmpgt_epi64_mask(q, hi) | _mm512_cmplt_epi64_mask(q, lo));
    LT_EVENT(SAT, lt__popcount32(sd) + lt__popcount32(sq));
#endif
    /* the int32 clamp and the narrowing as one signed saturating narrow (vpmovsqd) */
    return _mm512_cvtsepi64_epi32(q);
}
LT_INLINE void lt__x86_plane8_q16(const int32_t *p, int32_t o, int32_t rd, int32_t *t)
{
    _mm256_storeu_si256((__m256i *)(void *)t, lt__x86_plane8r_q16(p, o, rd));
}
#else
LT_INLINE void lt__x86_plane8_q16(const int32_t *p, int32_t o, int32_t rd, int32_t *t)
{
    __m256i hi = _mm256_set1_epi64x(INT32_MAX), lo = _mm256_set1_epi64x(INT32_MIN);
    __m256i ov = _mm256_set1_epi64x(o), rv = _mm256_set1_epi64x(rd);
    __m256i rnd = _mm256_set1_epi64x((long long)1 << 15);
    __m256i pick = _mm256_setr_epi32(0, 2, 4, 6, 0, 2, 4, 6);
    __m128i sh = _mm_cvtsi32_si128(16), shl = _mm_cvtsi32_si128(48);
    unsigned nsat = 0;
    int h;
    for (h = 0; h < 2; h++) {
        __m256i d = _mm256_sub_epi64(
            _mm256_cvtepi32_epi64(_mm_loadu_si128((const __m128i *)(const void *)(p + 4 * h))), ov);
        __m256i gt = _mm256_cmpgt_epi64(d, hi), lt = _mm256_cmpgt_epi64(lo, d), q;
        unsigned sq;
        nsat += lt__popcount32((unsigned)_mm256_movemask_pd(
            _mm256_castsi256_pd(_mm256_or_si256(gt, lt))));
        d = _mm256_blendv_epi8(_mm256_blendv_epi8(d, hi, gt), lo, lt);
        q = lt__x86_sra_sat64(_mm256_add_epi64(_mm256_mul_epi32(d, rv), rnd), sh, shl, hi, lo, &sq);
        nsat += lt__popcount32(sq);
        _mm_storeu_si128((__m128i *)(void *)(t + 4 * h),
                         _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(q, pick)));
    }
    LT_EVENT(SAT, nsat);
    (void)nsat;
}
#endif

#if LT__X86_LANES == 512
/* The 8-wide node test of a single ray (lt_bvh8.inc's w_test without a parallel or saturated
 * axis, whose fix-ups stay in C) in registers: per axis the two planes as lt__x86_plane8r_q16
 * computes them (s15.16) or (p - o) x 1/d (float32), the interval's min/max, then tnear <= tfar
 * and the slot in use, as one mask; tn gets the 8 tnear. The C loops stored each plane's 8
 * results with a narrowing store (vpmovqd) and read them back, a store the next load cannot
 * forward from on Intel cores. No events: the counting build keeps the C loops. */
/* The same t where plane - o fits int32 (no clamp): round((p - o) rd) = (p rd - (o rd - 2^15)) >> 16
 * exactly in int64 (|p rd|, |o rd| < 2^62), one subtract of a per-axis constant instead of the
 * per-plane subtract and rounding add. */
LT_INLINE __m256i lt__x86_plane8k_q16(const int32_t *p, __m512i vrd, __m512i k)
{
    __m512i q = _mm512_mul_epi32(
        _mm512_cvtepi32_epi64(_mm256_loadu_si256((const __m256i *)(const void *)p)), vrd);
    return _mm512_cvtsepi64_epi32(_mm512_srai_epi64(_mm512_sub_epi64(q, k), 16));
}

LT_INLINE unsigned lt__x86_wtest8_q16_body(const int32_t *lo, const int32_t *hi,
                                           const uint16_t *cnt, const int32_t *o,
                                           const int32_t *rd, int32_t tmin, int32_t tmax,
                                           uint16_t empty, int32_t *tn, int clamp)
{
    __m256i vn = _mm256_set1_epi32(tmin), vf = _mm256_set1_epi32(tmax);
    int a;
    for (a = 0; a < 3; a++) {
        __m256i t0, t1;
        if (clamp) {
            t0 = lt__x86_plane8r_q16(lo + 8 * a, o[a], rd[a]);
            t1 = lt__x86_plane8r_q16(hi + 8 * a, o[a], rd[a]);
        } else {
            __m512i vrd = _mm512_set1_epi64(rd[a]);
            __m512i k = _mm512_set1_epi64((long long)o[a] * rd[a] - ((long long)1 << 15));
            t0 = lt__x86_plane8k_q16(lo + 8 * a, vrd, k);
            t1 = lt__x86_plane8k_q16(hi + 8 * a, vrd, k);
        }
        vn = _mm256_max_epi32(vn, _mm256_min_epi32(t0, t1));
        vf = _mm256_min_epi32(vf, _mm256_max_epi32(t0, t1));
    }
    _mm256_storeu_si256((__m256i *)(void *)tn, vn);
    return (unsigned)(_mm256_cmp_epi32_mask(vn, vf, _MM_CMPINT_LE) &
                      _mm_cmpneq_epi16_mask(_mm_loadu_si128((const __m128i *)(const void *)cnt),
                                            _mm_set1_epi16((short)empty)));
}

/* The wide node test of one ray in s15.16 (lt_bvh8.inc's w_test). noclamp: every |plane - o| of
 * the children in use fits int32 (the tree's span plus |o|), so the subtract's clamp is left out;
 * the empty slots' planes may then give any t, which their slot mask drops. */
LT_INLINE unsigned lt__x86_wtest8_q16(const int32_t *lo, const int32_t *hi, const uint16_t *cnt,
                                      const int32_t *o, const int32_t *rd, int32_t tmin,
                                      int32_t tmax, uint16_t empty, int32_t *tn, int noclamp)
{
    return noclamp ? lt__x86_wtest8_q16_body(lo, hi, cnt, o, rd, tmin, tmax, empty, tn, 0)
                   : lt__x86_wtest8_q16_body(lo, hi, cnt, o, rd, tmin, tmax, empty, tn, 1);
}

/* the wide node tests' final masks (lt__x86_wtest*_f32 and lt__x86_wtest16_q16 below): a <= b per
 * lane, and the slots in use (cnt[c] != empty), as 8 bits */
LT_INLINE unsigned lt__x86_fle8(__m256 a, __m256 b) { return (unsigned)_mm256_cmp_ps_mask(a, b, _CMP_LE_OQ); }
LT_INLINE unsigned lt__x86_ile8(__m256i a, __m256i b)
{
    return (unsigned)_mm256_cmp_epi32_mask(a, b, _MM_CMPINT_LE);
}
LT_INLINE unsigned lt__x86_used8(const uint16_t *cnt, uint16_t empty)
{
    return (unsigned)_mm_cmpneq_epi16_mask(_mm_loadu_si128((const __m128i *)(const void *)cnt),
                                          _mm_set1_epi16((short)empty));
}
#elif LT__X86_LANES == 256
/* The wide BVH's node tests (single ray: lt__x86_wtest8_*, 16-ray packet frustum:
 * lt__x86_wtest16_*) on AVX2, in registers as on AVX-512: each plane's 8 t in one ymm (s15.16: two
 * 4-lane int64 halves, lt__x86_plane8r_q16; always with the clamp of plane - o), the verdicts and
 * the slots in use as an 8-bit mask. No events: the counting build keeps the C loops. */
/* One plane's t = sat32(round(sat32(p - o) x rd / 2^16)) in doubles, 4 lanes: p - o is exact, its
 * clamp too; where |d rd| < 2^53 the product, the rounding add and the power-of-two scale are
 * exact, so the floor is the integer result, and where |d rd| >= 2^53 (beyond the int32 result
 * bound 2^47) the rounded product saturates on the same side: the bits of
 * lt__q16_mul_sat(lt__q16_sub_sat(p, o), rd), without AVX2's 64-bit shift and clamp emulation. */
LT_INLINE __m128i lt__x86_plane4d_q16(__m128i p, __m256d o, __m256d rd)
{
    __m256d hi = _mm256_set1_pd(2147483647.0), lo = _mm256_set1_pd(-2147483648.0);
    __m256d d = _mm256_sub_pd(_mm256_cvtepi32_pd(p), o);
    d = _mm256_max_pd(_mm256_min_pd(d, hi), lo);
    d = _mm256_floor_pd(_mm256_mul_pd(_mm256_add_pd(_mm256_mul_pd(d, rd), _mm256_set1_pd(32768.0)),
                                      _mm256_set1_pd(1.0 / 65536.0)));
    return _mm256_cvttpd_epi32(_mm256_max_pd(_mm256_min_pd(d, hi), lo));
}
LT_INLINE __m256i lt__x86_plane8r_q16(const int32_t *p, int32_t o, int32_t rd)
{
    __m256d od = _mm256_set1_pd((double)o), rdd = _mm256_set1_pd((double)rd);
    __m256i v = _mm256_loadu_si256((const __m256i *)(const void *)p);
    return _mm256_set_m128i(lt__x86_plane4d_q16(_mm256_extracti128_si256(v, 1), od, rdd),
                            lt__x86_plane4d_q16(_mm256_castsi256_si128(v), od, rdd));
}
/* the final masks, as on AVX-512 */
LT_INLINE unsigned lt__x86_fle8(__m256 a, __m256 b)
{
    return (unsigned)_mm256_movemask_ps(_mm256_cmp_ps(a, b, _CMP_LE_OQ));
}
LT_INLINE unsigned lt__x86_ile8(__m256i a, __m256i b)
{
    return ~(unsigned)_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpgt_epi32(a, b))) & 0xFFu;
}
LT_INLINE unsigned lt__x86_used8(const uint16_t *cnt, uint16_t empty)
{
    __m128i e = _mm_cmpeq_epi16(_mm_loadu_si128((const __m128i *)(const void *)cnt),
                                _mm_set1_epi16((short)empty));
    return ~(unsigned)_mm_movemask_epi8(_mm_packs_epi16(e, _mm_setzero_si128())) & 0xFFu;
}
LT_INLINE unsigned lt__x86_wtest8_q16(const int32_t *lo, const int32_t *hi, const uint16_t *cnt,
                                      const int32_t *o, const int32_t *rd, int32_t tmin,
                                      int32_t tmax, uint16_t empty, int32_t *tn, int noclamp)
{
    __m256i vn = _mm256_set1_epi32(tmin), vf = _mm256_set1_epi32(tmax);
    int a;
    (void)noclamp;
    for (a = 0; a < 3; a++) {
        __m256i t0 = lt__x86_plane8r_q16(lo + 8 * a, o[a], rd[a]);
        __m256i t1 = lt__x86_plane8r_q16(hi + 8 * a, o[a], rd[a]);
        vn = _mm256_max_epi32(vn, _mm256_min_epi32(t0, t1));
        vf = _mm256_min_epi32(vf, _mm256_max_epi32(t0, t1));
    }
    _mm256_storeu_si256((__m256i *)(void *)tn, vn);
    return lt__x86_ile8(vn, vf) & lt__x86_used8(cnt, empty);
}
#endif

#if LT__X86_LANES
/* One ray's float32 node test of an 8-wide node (AVX-512 and AVX2 alike: one ymm per plane). */
LT_INLINE unsigned lt__x86_wtest8_f32(const float *lo, const float *hi, const uint16_t *cnt,
                                      const float *o, const float *rd, float tmin, float tmax,
                                      uint16_t empty, float *tn)
{
    __m256 vn = _mm256_set1_ps(tmin), vf = _mm256_set1_ps(tmax);
    int a;
    for (a = 0; a < 3; a++) {
        __m256 vo = _mm256_set1_ps(o[a]), vr = _mm256_set1_ps(rd[a]);
        __m256 t0 = _mm256_mul_ps(_mm256_sub_ps(_mm256_loadu_ps(lo + 8 * a), vo), vr);
        __m256 t1 = _mm256_mul_ps(_mm256_sub_ps(_mm256_loadu_ps(hi + 8 * a), vo), vr);
        /* lt__f32_min / max: a < b ? a : b and a > b ? a : b, vminps / vmaxps operand order */
        vn = _mm256_max_ps(vn, _mm256_min_ps(t0, t1));
        vf = _mm256_min_ps(vf, _mm256_max_ps(t0, t1));
    }
    _mm256_storeu_ps(tn, vn);
    return lt__x86_fle8(vn, vf) & lt__x86_used8(cnt, empty);
}

/* The 16-ray packet walk's node test (lt_bvh8.inc's w_test16) in registers: per axis not in free,
 * each plane's t at the corners of the frustum's origin range [olo, ohi] and reciprocal range
 * [rlo, rhi] (the origin's two corners only when same_o is 0), as lt__x86_plane8r_q16 computes
 * one ray's t (s15.16) or (p - o) x 1/d (float32): their min and max bound every lane's; then
 * the children whose bounds meet over [tmin, tmax] and whose slot is in use, as one mask; tn gets
 * the 8 lower bounds. No events: the counting build keeps the C loops. */
#define LT__X86_WTEST16(T, V, SET1, MIN, MAX, PLANE, LE, STORE)                                    \
    {                                                                                              \
        V vn = SET1(tmin), vf = SET1(tmax);                                                        \
        int a, s;                                                                                  \
        for (a = 0; a < 3; a++) {                                                                  \
            V l[2], h[2];                                                                          \
            if ((free >> a) & 1u)                                                                  \
                continue;                                                                          \
            for (s = 0; s < 2; s++) {                                                              \
                const T *p = (s == 0 ? lo : hi) + 8 * a;                                           \
                V x = PLANE(p, olo[a], rlo[a]), y = PLANE(p, olo[a], rhi[a]);                      \
                l[s] = MIN(x, y);                                                                  \
                h[s] = MAX(x, y);                                                                  \
                if (!same_o) {                                                                     \
                    x = PLANE(p, ohi[a], rlo[a]);                                                  \
                    y = PLANE(p, ohi[a], rhi[a]);                                                  \
                    l[s] = MIN(l[s], MIN(x, y));                                                   \
                    h[s] = MAX(h[s], MAX(x, y));                                                   \
                }                                                                                  \
            }                                                                                      \
            vn = MAX(vn, MIN(l[0], l[1]));                                                         \
            vf = MIN(vf, MAX(h[0], h[1]));                                                         \
        }                                                                                          \
        STORE(tn, vn);                                                                             \
        return LE(vn, vf) & lt__x86_used8(cnt, empty);                                             \
    }
LT_INLINE __m256 lt__x86_plane8_f32(const float *p, float o, float rd)
{
    return _mm256_mul_ps(_mm256_sub_ps(_mm256_loadu_ps(p), _mm256_set1_ps(o)), _mm256_set1_ps(rd));
}
LT_INLINE void lt__x86_store8i(int32_t *t, __m256i v) { _mm256_storeu_si256((__m256i *)(void *)t, v); }
LT_INLINE unsigned lt__x86_wtest16_q16(const int32_t *lo, const int32_t *hi, const uint16_t *cnt,
                                       const int32_t *olo, const int32_t *ohi,
                                       const int32_t *rlo, const int32_t *rhi, int same_o,
                                       unsigned free, int32_t tmin, int32_t tmax, uint16_t empty,
                                       int32_t *tn)
LT__X86_WTEST16(int32_t, __m256i, _mm256_set1_epi32, _mm256_min_epi32, _mm256_max_epi32,
                lt__x86_plane8r_q16, lt__x86_ile8, lt__x86_store8i)
LT_INLINE unsigned lt__x86_wtest16_f32(const float *lo, const float *hi, const uint16_t *cnt,
                                       const float *olo, const float *ohi, const float *rlo,
                                       const float *rhi, int same_o, unsigned free, float tmin,
                                       float tmax, uint16_t empty, float *tn)
LT__X86_WTEST16(float, __m256, _mm256_set1_ps, _mm256_min_ps, _mm256_max_ps,
                lt__x86_plane8_f32, lt__x86_fle8, _mm256_storeu_ps)
#undef LT__X86_WTEST16
#endif

/* The first two stages of the wide tree's float32 leaf block test (lt__wt_tris4_f32, lt_wt.c) in
 * SSE registers, the same operations in the same order per lane as its C loops (so the same bits):
 * v the block's v[9][4], k the ray's axis permutation, o its permuted origin, s its shear. Writes
 * each vertex's sheared x, y and unsheared z (x, y, zk: the tail reads them per lane) and the
 * edges eu, ev, ew; returns the lanes that may meet the ray: signs not mixed and det != 0, or
 * (zero_edges) an edge that is zero, and the lane's id >= 0. Written out per vertex: the C loops,
 * vectorised by the compiler, kept the vertices in stack arrays between the stages and ran at
 * 0.67-0.76x of this (float32 single rays through the wide tree, docs/bvh.md). No events: the
 * counting build keeps the C loops. */
LT_INLINE unsigned lt__x86_tris4_f32(const float (*v)[4], const int32_t *id, unsigned k0,
                                     unsigned k1, unsigned k2, const float o[3], const float s[2],
                                     int zero_edges, float x[3][4], float y[3][4], float zk[3][4],
                                     float eu[4], float ev[4], float ew[4])
{
    const __m128 o0 = _mm_set1_ps(o[0]), o1 = _mm_set1_ps(o[1]), o2 = _mm_set1_ps(o[2]);
    const __m128 s0 = _mm_set1_ps(s[0]), s1 = _mm_set1_ps(s[1]), z = _mm_setzero_ps();
    __m128 x0, x1, x2, y0, y1, y2, eu4, ev4, ew4, neg, pos, det, ok;
#define LT__X86_TRIS4_VERT(j, xj, yj)                                                              \
    do {                                                                                           \
        __m128 zz = _mm_sub_ps(_mm_loadu_ps(v[3 * (j) + k2]), o2);                                 \
        xj = _mm_sub_ps(_mm_sub_ps(_mm_loadu_ps(v[3 * (j) + k0]), o0), _mm_mul_ps(s0, zz));        \
        yj = _mm_sub_ps(_mm_sub_ps(_mm_loadu_ps(v[3 * (j) + k1]), o1), _mm_mul_ps(s1, zz));        \
        _mm_storeu_ps(x[j], xj);                                                                   \
        _mm_storeu_ps(y[j], yj);                                                                   \
        _mm_storeu_ps(zk[j], zz);                                                                  \
    } while (0)
    LT__X86_TRIS4_VERT(0, x0, y0);
    LT__X86_TRIS4_VERT(1, x1, y1);
    LT__X86_TRIS4_VERT(2, x2, y2);
#undef LT__X86_TRIS4_VERT
    eu4 = _mm_sub_ps(_mm_mul_ps(x2, y1), _mm_mul_ps(y2, x1));
    ev4 = _mm_sub_ps(_mm_mul_ps(x0, y2), _mm_mul_ps(y0, x2));
    ew4 = _mm_sub_ps(_mm_mul_ps(x1, y0), _mm_mul_ps(y1, x0));
    _mm_storeu_ps(eu, eu4);
    _mm_storeu_ps(ev, ev4);
    _mm_storeu_ps(ew, ew4);
    neg = _mm_or_ps(_mm_or_ps(_mm_cmplt_ps(eu4, z), _mm_cmplt_ps(ev4, z)), _mm_cmplt_ps(ew4, z));
    pos = _mm_or_ps(_mm_or_ps(_mm_cmpgt_ps(eu4, z), _mm_cmpgt_ps(ev4, z)), _mm_cmpgt_ps(ew4, z));
    det = _mm_add_ps(_mm_add_ps(eu4, ev4), ew4);
    ok = _mm_andnot_ps(_mm_and_ps(neg, pos), _mm_or_ps(_mm_cmplt_ps(det, z), _mm_cmpgt_ps(det, z)));
    if (zero_edges)
        ok = _mm_or_ps(ok, _mm_or_ps(_mm_or_ps(_mm_cmpeq_ps(eu4, z), _mm_cmpeq_ps(ev4, z)),
                                     _mm_cmpeq_ps(ew4, z)));
    ok = _mm_and_ps(ok, _mm_castsi128_ps(_mm_cmpgt_epi32(
                            _mm_loadu_si128((const __m128i *)(const void *)id), _mm_set1_epi32(-1))));
    return (unsigned)_mm_movemask_ps(ok);
}

/* round(2^46 / d) half up for d != 0 (lt__div_round64(2^46, d)), exactly, without a 64-bit integer
 * divide: for d > 0 it is floor((2^47 + b) / 2b), for d < 0 -floor((2^47 + b - 1) / 2b) (b = |d|);
 * numerator < 2^48 and denominator <= 2^32 are exact doubles, the double quotient is within 2^-6
 * of the true one and never below the integer under it, so its truncation is the floor or one
 * more, which the remainder test takes back. Plain C: 16 lanes of it vectorise (vcvtqq2pd,
 * vdivpd, vcvttpd2qq, vpmullq). */
LT_INLINE int64_t lt__x86_recip46(int32_t d)
{
    int64_t b = d < 0 ? -(int64_t)d : (int64_t)d;
    int64_t p = ((int64_t)1 << 47) + b - (int64_t)(d < 0), m = 2 * b;
    int64_t q = (int64_t)((double)p / (double)m);
    int64_t r = p - q * m;
    q += (int64_t)(r >= m) - (int64_t)(r < 0);
    return d < 0 ? -q : q;
}

#if LT__X86_LANES == 512 && defined(__AVX512DQ__)
/* lt__x86_recip46 on 16 lanes at once (AVX-512DQ: int64 <-> double conversions, 64-bit
 * products): the same formula lane for lane, so the same results; r = zero where d == 0. *sat
 * gets the lanes whose quotient saturated (d != 0). */
#define LT__X86_RECIP46_16 1
LT_INLINE void lt__x86_recip46_16(const int32_t *d, int32_t zero, int32_t *r, unsigned *sat)
{
    const __m512i one = _mm512_set1_epi64(1), p47 = _mm512_set1_epi64((long long)1 << 47);
    const __m512i hi = _mm512_set1_epi64(INT32_MAX), lo = _mm512_set1_epi64(INT32_MIN);
    unsigned s = 0;
    int h;
    for (h = 0; h < 2; h++) {
        __m512i dv = _mm512_cvtepi32_epi64(_mm256_loadu_si256((const __m256i *)(const void *)(d + 8 * h)));
        __mmask8 neg = _mm512_cmplt_epi64_mask(dv, _mm512_setzero_si512());
        __mmask8 nz = _mm512_cmpneq_epi64_mask(dv, _mm512_setzero_si512());
        __m512i b = _mm512_abs_epi64(_mm512_mask_mov_epi64(dv, (__mmask8)~nz, one));
        __m512i p = _mm512_mask_sub_epi64(_mm512_add_epi64(p47, b), neg,
                                          _mm512_add_epi64(p47, b), one);
        __m512i m = _mm512_add_epi64(b, b);
        __m512i q = _mm512_cvttpd_epi64(_mm512_div_pd(_mm512_cvtepi64_pd(p), _mm512_cvtepi64_pd(m)));
        __m512i rem = _mm512_sub_epi64(p, _mm512_mullo_epi64(q, m));
        q = _mm512_mask_add_epi64(q, _mm512_cmpge_epi64_mask(rem, m), q, one);
        q = _mm512_mask_sub_epi64(q, _mm512_cmplt_epi64_mask(rem, _mm512_setzero_si512()), q, one);
        q = _mm512_mask_sub_epi64(q, neg, _mm512_setzero_si512(), q);
        s |= (unsigned)((_mm512_cmpgt_epi64_mask(q, hi) | _mm512_cmplt_epi64_mask(q, lo)) & nz) << (8 * h);
        q = _mm512_max_epi64(_mm512_min_epi64(q, hi), lo);
        q = _mm512_mask_mov_epi64(q, (__mmask8)~nz, _mm512_set1_epi64(zero));
        _mm256_storeu_si256((__m256i *)(void *)(r + 8 * h), _mm512_cvtepi64_epi32(q));
    }
    *sat = s;
}
#endif
#endif /* LT__X86_LANES */

#endif /* LT_V16_X86_H */
