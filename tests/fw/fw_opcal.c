/* fw_opcal.c - op-class microbenchmarks for calibrating the scalar machine models from QEMU
 * instruction counts: sim/machines/mcu_m4.def (cm4) and sim/machines/rv32imac.def (rv32).
 * One noinline wrapper per lane op; each calls exactly ONE lane op of lt_v16.h. main() runs every
 * wrapper OPCAL_K times on fresh pseudo-random inputs (mixed magnitudes with some saturating lanes,
 * random masks with ~half the lanes on), then prints the numbers the counts are divided by.
 * tests/bench/opcal.sh counts the instructions inside each wrapper symbol (and the libgcc helpers
 * it calls: the 64-bit divide; on rv32, soft float, every float op) with the lt_icount QEMU plugin
 * and subtracts the matching empty wrapper. On a soft-float target the float inputs are made with
 * integer operations only (lt_f32_bits.h), so main calls no float helper a wrapper also calls.
 *
 * Wrappers take pointers (operands in memory, result stored to memory): in the kernels a 16-lane
 * vector does not fit in the M4's registers, so each lane op there also loads its operands and
 * stores its result; passing 64/128-byte structs by value would add argument copies that the
 * inlined kernels do not have. Two by-value wrappers (w_byval_*) show that difference.
 * noipa keeps GCC from specialising a wrapper for its (known) arguments. Freestanding.
 */
#include "lt_fw.h"
#include "lt/lt.h"
#include "lt_f32_bits.h"

/* Soft float: float arithmetic is a libgcc call (rv32 -mabi=ilp32; Arm -mfloat-abi=soft). */
#if defined(__SOFTFP__) || (defined(__riscv) && !defined(__riscv_flen))
#define OPCAL_SOFT_FLOAT 1
#else
#define OPCAL_SOFT_FLOAT 0
#endif

#ifndef OPCAL_K
#define OPCAL_K 64
#endif

#define W __attribute__((noinline, noipa))

/* ---- empty wrappers: call overhead of each signature ------------------------------------------ */
void w_base_p3(void *r, const void *a, const void *b);
void w_base_pk3(void *r, lt_mask16_t k, const void *a, const void *b);
void w_base_p2(void *r, const void *a);
lt_mask16_t w_base_kp2(lt_mask16_t k, const void *a, const void *b);
int32_t w_base_kp1(lt_mask16_t k, const void *a);
void w_base_px(void *r, int32_t x);
void w_base_pl(void *r, int64_t x);
unsigned w_base_k(lt_mask16_t k);
void w_base_pkpp(void *r, lt_mask16_t k, const void *base, const void *idx);
lt_vq16_t w_base_byval(lt_vq16_t a, lt_vq16_t b);

W void w_base_p3(void *r, const void *a, const void *b) { (void)r; (void)a; (void)b; }
W void w_base_pk3(void *r, lt_mask16_t k, const void *a, const void *b)
{
    (void)r; (void)k; (void)a; (void)b;
}
W void w_base_p2(void *r, const void *a) { (void)r; (void)a; }
W lt_mask16_t w_base_kp2(lt_mask16_t k, const void *a, const void *b)
{
    (void)a; (void)b;
    return k;
}
W int32_t w_base_kp1(lt_mask16_t k, const void *a)
{
    (void)a;
    return (int32_t)k;
}
W void w_base_px(void *r, int32_t x) { (void)r; (void)x; }
W void w_base_pl(void *r, int64_t x) { (void)r; (void)x; }
W unsigned w_base_k(lt_mask16_t k) { return k; }
W void w_base_pkpp(void *r, lt_mask16_t k, const void *base, const void *idx)
{
    (void)r; (void)k; (void)base; (void)idx;
}
W lt_vq16_t w_base_byval(lt_vq16_t a, lt_vq16_t b)
{
    (void)b;
    return a;
}

/* ---- one lane op each ------------------------------------------------------------------------- */
#define WBIN(name, VT, op)                                                                         \
    void name(VT *r, const VT *a, const VT *b);                                                    \
    W void name(VT *r, const VT *a, const VT *b) { *r = op(*a, *b); }

WBIN(w_valu_add, lt_vq16_t, lt_vq16_add_sat)
WBIN(w_valu_sub, lt_vq16_t, lt_vq16_sub_sat)
WBIN(w_valu_min, lt_vq16_t, lt_vq16_min)
WBIN(w_valu_max, lt_vq16_t, lt_vq16_max)
WBIN(w_vmul_q16, lt_vq16_t, lt_vq16_mul_sat)
WBIN(w_vmulw_add, lt_vql_t, lt_vql_add_wrap)
WBIN(w_vmulw_sub, lt_vql_t, lt_vql_sub_wrap)
WBIN(w_fadd_add, lt_vf32_t, lt_vf32_add)
WBIN(w_fadd_min, lt_vf32_t, lt_vf32_min)
WBIN(w_fmul, lt_vf32_t, lt_vf32_mul)
WBIN(w_fdiv, lt_vf32_t, lt_vf32_div)

void w_vmul_ql(lt_vql_t *r, const lt_vi32_t *a, const lt_vi32_t *b);
W void w_vmul_ql(lt_vql_t *r, const lt_vi32_t *a, const lt_vi32_t *b) { *r = lt_vql_mul(*a, *b); }

void w_valu_blend(lt_vq16_t *r, lt_mask16_t k, const lt_vq16_t *a, const lt_vq16_t *b);
W void w_valu_blend(lt_vq16_t *r, lt_mask16_t k, const lt_vq16_t *a, const lt_vq16_t *b)
{
    *r = lt_vq16_blend(k, *a, *b);
}

/* Merge-masked divide: src = *r, as lt_tri16's t = tnum / det on the candidate lanes. */
void w_vdiv_m(lt_vq16_t *r, lt_mask16_t k, const lt_vq16_t *a, const lt_vq16_t *b);
W void w_vdiv_m(lt_vq16_t *r, lt_mask16_t k, const lt_vq16_t *a, const lt_vq16_t *b)
{
    *r = lt_vq16_div_sat_m(*r, k, *a, *b);
}

/* Merge-masked 64-bit subtract: lt_tri16's two-sided flip (0 - x on back-facing lanes). */
void w_vmulw_sub_m(lt_vql_t *r, lt_mask16_t k, const lt_vql_t *a, const lt_vql_t *b);
W void w_vmulw_sub_m(lt_vql_t *r, lt_mask16_t k, const lt_vql_t *a, const lt_vql_t *b)
{
    *r = lt_vql_sub_wrap_m(*r, k, *a, *b);
}

#if OPCAL_SOFT_FLOAT
/* Soft float only, where the float ops differ in price (on an FPU they are one instruction each):
 * the rest of the FADD class the float kernels use (sub, max, the blend and lt_tri16_f32's
 * merge-masked negate, the two-sided flip) and the merge-masked divide, lt_tri16_f32's
 * t = tnum / det on the candidate lanes (a libgcc call per active lane). */
WBIN(w_fadd_sub, lt_vf32_t, lt_vf32_sub)
WBIN(w_fadd_max, lt_vf32_t, lt_vf32_max)

void w_fadd_blend(lt_vf32_t *r, lt_mask16_t k, const lt_vf32_t *a, const lt_vf32_t *b);
W void w_fadd_blend(lt_vf32_t *r, lt_mask16_t k, const lt_vf32_t *a, const lt_vf32_t *b)
{
    *r = lt_vf32_blend(k, *a, *b);
}

void w_fadd_neg_m(lt_vf32_t *r, lt_mask16_t k, const lt_vf32_t *a, const lt_vf32_t *b);
W void w_fadd_neg_m(lt_vf32_t *r, lt_mask16_t k, const lt_vf32_t *a, const lt_vf32_t *b)
{
    (void)b;
    *r = lt_vf32_neg_m(*r, k, *a);
}

void w_fdiv_m(lt_vf32_t *r, lt_mask16_t k, const lt_vf32_t *a, const lt_vf32_t *b);
W void w_fdiv_m(lt_vf32_t *r, lt_mask16_t k, const lt_vf32_t *a, const lt_vf32_t *b)
{
    *r = lt_vf32_div_m(*r, k, *a, *b);
}
#endif

void w_vshift_round(lt_vi32_t *r, const lt_vql_t *a);
W void w_vshift_round(lt_vi32_t *r, const lt_vql_t *a) { *r = lt_vql_round_sat(*a, 30u); }

void w_vshift_asr(lt_vql_t *r, const lt_vql_t *a);
W void w_vshift_asr(lt_vql_t *r, const lt_vql_t *a) { *r = lt_vql_asr(*a, 4u); }

void w_vcvt(lt_vq16_t *r, const lt_vq30_t *a);
W void w_vcvt(lt_vq16_t *r, const lt_vq30_t *a) { *r = lt_vq16_from_q30(*a); }

lt_mask16_t w_vcmp_q16(lt_mask16_t k, const lt_vq16_t *a, const lt_vq16_t *b);
W lt_mask16_t w_vcmp_q16(lt_mask16_t k, const lt_vq16_t *a, const lt_vq16_t *b)
{
    return lt_vq16_cmple_m(k, *a, *b);
}

lt_mask16_t w_vcmp_ql(lt_mask16_t k, const lt_vql_t *a, const lt_vql_t *b);
W lt_mask16_t w_vcmp_ql(lt_mask16_t k, const lt_vql_t *a, const lt_vql_t *b)
{
    return lt_vql_cmpge_m(k, *a, *b);
}

lt_mask16_t w_fcmp(lt_mask16_t k, const lt_vf32_t *a, const lt_vf32_t *b);
W lt_mask16_t w_fcmp(lt_mask16_t k, const lt_vf32_t *a, const lt_vf32_t *b)
{
    return lt_vf32_cmple_m(k, *a, *b);
}

int32_t w_vred(lt_mask16_t k, const lt_vq16_t *a);
W int32_t w_vred(lt_mask16_t k, const lt_vq16_t *a) { return lt_vq16_hmin(k, *a, LT_Q16_MAX); }

void w_vbcast(lt_vq16_t *r, int32_t x);
W void w_vbcast(lt_vq16_t *r, int32_t x) { *r = lt_vq16_set1(x); }

void w_vbcast_ql(lt_vql_t *r, int64_t x);
W void w_vbcast_ql(lt_vql_t *r, int64_t x) { *r = lt_vql_set1(x); }

void w_vload(lt_vq16_t *r, const int32_t *p);
W void w_vload(lt_vq16_t *r, const int32_t *p) { *r = lt_vq16_load(p); }

void w_vstore(int32_t *p, const lt_vq16_t *a);
W void w_vstore(int32_t *p, const lt_vq16_t *a) { lt_vq16_store(p, *a); }

unsigned w_mask_any(lt_mask16_t k);
W unsigned w_mask_any(lt_mask16_t k) { return (unsigned)lt_mask16_any(k); }

unsigned w_mask_popcount(lt_mask16_t k);
W unsigned w_mask_popcount(lt_mask16_t k) { return lt_mask16_popcount(k); }

unsigned w_mask_first(lt_mask16_t k);
W unsigned w_mask_first(lt_mask16_t k) { return lt_mask16_first(k); }

void w_vgather(lt_vq16_t *r, lt_mask16_t k, const int32_t *base, const lt_vi32_t *idx);
W void w_vgather(lt_vq16_t *r, lt_mask16_t k, const int32_t *base, const lt_vi32_t *idx)
{
    *r = lt_vq16_gather_m(*r, k, base, *idx);
}

/* By value, as lt_v16.h's signatures: for comparison with the pointer wrappers only. */
lt_vq16_t w_byval_add(lt_vq16_t a, lt_vq16_t b);
W lt_vq16_t w_byval_add(lt_vq16_t a, lt_vq16_t b) { return lt_vq16_add_sat(a, b); }
lt_vq16_t w_byval_mul(lt_vq16_t a, lt_vq16_t b);
W lt_vq16_t w_byval_mul(lt_vq16_t a, lt_vq16_t b) { return lt_vq16_mul_sat(a, b); }

/* ---- inputs ----------------------------------------------------------------------------------- */
static uint32_t seed = 0x2545F491u;
static uint32_t rnd(void)
{
    seed = seed * 1664525u + 1013904223u;
    return seed;
}

/* A s15.16 value: 1 lane in 4 near the int32 limits (saturates add/sub/mul), others |x| < 2^23
 * (up to 128 units, as in the scenes), a few small ones. */
static int32_t rnd_q16(void)
{
    uint32_t x = rnd();
    int32_t v;
    switch (x >> 30) {
    case 0:
        v = (int32_t)((x >> 2) & 0x3FFFFFFFu) + 0x3FFFFFFF;  /* large positive */
        return (x & 2u) ? v : -v;
    case 1:
        v = (int32_t)((x >> 8) & 0xFFFFu);                   /* below one unit */
        break;
    default:
        v = (int32_t)((x >> 6) & 0x7FFFFFu);                 /* up to 128 units */
        break;
    }
    return (x & 1u) ? -v : v;
}

static lt_mask16_t rnd_mask(void) { return (lt_mask16_t)(rnd() >> 16); }

/* Exactly 8 of 16 lanes on. */
static lt_mask16_t half_mask(void)
{
    unsigned m = 0, n = 0;
    while (n < 8) {
        unsigned b = 1u << (rnd() >> 28);
        if ((m & b) == 0) {
            m |= b;
            n++;
        }
    }
    return (lt_mask16_t)m;
}

static lt_vq16_t qa, qb, qr, qdiv_den;
static lt_vq30_t q30a;
static lt_vi32_t ia, ib, gidx;
static lt_vql_t la, lb, lr;
static lt_vi32_t ir;
static lt_vf32_t fa, fb, fr;
static int32_t mem[LT_LANES], table[64];

/* -DOPCAL_ONLY=\"w_name\" runs only that wrapper (and the empty ones): opcal.sh uses it to charge
 * a helper that several wrappers call (memcpy) to each of them. */
#ifdef OPCAL_ONLY
static int streq(const char *a, const char *b)
{
    while (*a != '\0' && *a == *b) {
        a++;
        b++;
    }
    return *a == *b;
}
#define RUN(w) streq(#w, OPCAL_ONLY)
#else
#define RUN(w) 1
#endif

/* Pointers through volatiles: main cannot see what the wrappers get. */
static void *volatile vp_qa = &qa, *volatile vp_qb = &qb, *volatile vp_qr = &qr;

int main(void)
{
    int it, i;
    uint32_t sink = 0, gather_lanes = 0, div_lanes = 0, vmulw_m_lanes = 0, blend_lanes = 0;
    for (i = 0; i < 64; i++)
        table[i] = (int32_t)rnd();
    for (it = 0; it < OPCAL_K; it++) {
        lt_mask16_t k = rnd_mask(), kh = half_mask();
        lt_vq16_t *pa = (lt_vq16_t *)vp_qa, *pb = (lt_vq16_t *)vp_qb, *pr = (lt_vq16_t *)vp_qr;
        for (i = 0; i < LT_LANES; i++) {
            uint32_t x;
            qa.l[i] = rnd_q16();
            qb.l[i] = rnd_q16();
            x = rnd();
            qdiv_den.l[i] = (int32_t)((x >> 8) | 0x1000u) * ((x & 1u) ? -1 : 1); /* nonzero */
            q30a.l[i] = (int32_t)rnd();
            ia.l[i] = (int32_t)rnd() >> (rnd() & 15u);
            ib.l[i] = (int32_t)rnd() >> (rnd() & 15u);
            la.l[i] = (int64_t)ia.l[i] * ib.l[i];
            lb.l[i] = (int64_t)(int32_t)rnd() * (int32_t)rnd() >> (rnd() & 31u);
#if OPCAL_SOFT_FLOAT
            /* the same values without a float helper (fb: one rounding instead of two) */
            fa.l[i] = lt_loop_f32_from_fx(qa.l[i], 16u);
            fb.l[i] = lt_loop_f32_from_fx((int64_t)qb.l[i] + 32768, 16u);
#else
            fa.l[i] = (float)qa.l[i] * (1.0f / 65536.0f);
            fb.l[i] = (float)qb.l[i] * (1.0f / 65536.0f) + 0.5f;
#endif
            mem[i] = (int32_t)rnd();
            gidx.l[i] = (int32_t)(rnd() >> 26);
        }
        /* saturating mixes for the 64-bit ops: a few lanes beyond +-2^62 */
        la.l[it & 15] = (int64_t)0x7000000000000000;
        lb.l[(it + 5) & 15] = -(int64_t)0x6000000000000000;

        w_base_p3(pr, pa, pb);
        w_base_pk3(pr, k, pa, pb);
        w_base_p2(pr, pa);
        sink += w_base_kp2(k, pa, pb);
        sink += (uint32_t)w_base_kp1(k, pa);
        w_base_px(pr, qa.l[0]);
        w_base_pl(&lr, lb.l[0]);
        sink += w_base_k(k);
        w_base_pkpp(pr, k, table, &gidx);
        qr = w_base_byval(qa, qb);

        if (RUN(w_valu_add))
            w_valu_add(pr, pa, pb);
        if (RUN(w_valu_sub))
            w_valu_sub(pr, pa, pb);
        if (RUN(w_valu_min))
            w_valu_min(pr, pa, pb);
        if (RUN(w_valu_max))
            w_valu_max(pr, pa, pb);
        if (RUN(w_valu_blend))
            w_valu_blend(pr, k, pa, pb);
        blend_lanes += lt__popcount32(k);
        if (RUN(w_vmul_q16))
            w_vmul_q16(pr, pa, pb);
        if (RUN(w_vmul_ql))
            w_vmul_ql(&lr, &ia, &ib);
        if (RUN(w_vmulw_add))
            w_vmulw_add(&lr, &la, &lb);
        if (RUN(w_vmulw_sub))
            w_vmulw_sub(&lr, &la, &lb);
        if (RUN(w_vmulw_sub_m))
            w_vmulw_sub_m(&lr, k, &la, &lb);
        vmulw_m_lanes += lt__popcount32(k);
        if (RUN(w_vshift_round))
            w_vshift_round(&ir, &la);
        if (RUN(w_vshift_asr))
            w_vshift_asr(&lr, &lb);
        if (RUN(w_vdiv_m))
            w_vdiv_m(pr, kh, pa, &qdiv_den);
        div_lanes += lt__popcount32(kh);
        if (RUN(w_vcmp_q16))
            sink += w_vcmp_q16(k, pa, pb);
        if (RUN(w_vcmp_ql))
            sink += w_vcmp_ql(k, &la, &lb);
        if (RUN(w_vcvt))
            w_vcvt(pr, &q30a);
        if (RUN(w_vred))
            sink += (uint32_t)w_vred(k, pa);
        if (RUN(w_vbcast))
            w_vbcast(pr, qb.l[it & 15]);
        if (RUN(w_vbcast_ql))
            w_vbcast_ql(&lr, lb.l[it & 15]);
        if (RUN(w_fadd_add))
            w_fadd_add(&fr, &fa, &fb);
        if (RUN(w_fadd_min))
            w_fadd_min(&fr, &fa, &fb);
        if (RUN(w_fmul))
            w_fmul(&fr, &fa, &fb);
        if (RUN(w_fdiv))
            w_fdiv(&fr, &fa, &fb);
        if (RUN(w_fcmp))
            sink += w_fcmp(k, &fa, &fb);
#if OPCAL_SOFT_FLOAT
        if (RUN(w_fadd_sub))
            w_fadd_sub(&fr, &fa, &fb);
        if (RUN(w_fadd_max))
            w_fadd_max(&fr, &fa, &fb);
        if (RUN(w_fadd_blend))
            w_fadd_blend(&fr, k, &fa, &fb);
        if (RUN(w_fadd_neg_m))
            w_fadd_neg_m(&fr, k, &fa, &fb);
        if (RUN(w_fdiv_m))
            w_fdiv_m(&fr, kh, &fa, &fb);
#endif
        if (RUN(w_vload))
            w_vload(pr, mem);
        if (RUN(w_vstore))
            w_vstore(mem, pa);
        if (RUN(w_mask_any))
            sink += w_mask_any(k);
        if (RUN(w_mask_popcount))
            sink += w_mask_popcount(k);
        if (RUN(w_mask_first))
            sink += w_mask_first(k);
        if (RUN(w_vgather))
            w_vgather(pr, k, table, &gidx);
        gather_lanes += lt__popcount32(k);
        if (RUN(w_byval_add))
            qr = w_byval_add(qa, qb);
        if (RUN(w_byval_mul))
            qr = w_byval_mul(qa, qb);
        sink += (uint32_t)qr.l[it & 15] + (uint32_t)ir.l[0] + (uint32_t)lr.l[3] + (uint32_t)fr.l[1];
    }
    lt_fw_puts("opcal K ");
    lt_fw_put_u32(OPCAL_K);
    lt_fw_puts(" gather_lanes ");
    lt_fw_put_u32(gather_lanes);
    lt_fw_puts(" div_lanes ");
    lt_fw_put_u32(div_lanes);
    lt_fw_puts(" masked_lanes ");
    lt_fw_put_u32(vmulw_m_lanes);
    lt_fw_puts(" blend_lanes ");
    lt_fw_put_u32(blend_lanes);
    lt_fw_puts(" sink ");
    lt_fw_put_hex32(sink);
    lt_fw_puts("\n");
    return 0;
}
