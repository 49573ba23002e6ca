/* lt_ssdda.c - the perspective-correct screen-space DDA of McGuire & Mara (JCGT 2014) over N layers
 * of an inverse-depth buffer, a baseline for the screen-space quadtree (lt_qt.c): parameters,
 * set-up and the s1.30 and float32 instantiations of lt_ssdda.inc (traits lt_ssb_q30.inc,
 * lt_ssb_f32.inc).
 * The surface model and the walk are documented in lt_ssdda.h and docs/ss-baselines.md.
 * Builds: all; float32 only with LT_CFG_FLOAT32.
 */
#include "lt/lt_ssdda.h"

#include "lt_ssb.h"

void lt_ssb_params_default(lt_ssb_params_t *p)
{
    p->thickness = 1 << 24; /* 2^-6 = 1.6% of the depth */
    p->flags = 0;
}

/* Common checks of the set-up entry points. */
static lt_status_t dda_prepare(lt_ssdda_t *dda, const lt_ssb_desc_t *d, const lt_ssb_params_t *p,
                               const void *w, uint32_t enc)
{
    lt_ssb_params_t dp;
    if (dda == NULL || d == NULL || w == NULL || d->enc != enc)
        return LT_E_ARG;
    if (d->width == 0 || d->height == 0 || d->width > LT_SSB_MAX_DIM ||
        d->height > LT_SSB_MAX_DIM || d->layers == 0 || d->layers > LT_SSB_MAX_LAYERS)
        return LT_E_ARG;
    if (p == NULL) {
        lt_ssb_params_default(&dp);
        p = &dp;
    }
    if (p->thickness < 0 || (p->flags & ~LT_SSB_CONTINUE_BEHIND) != 0u)
        return LT_E_ARG;
    dda->width = d->width;
    dda->height = d->height;
    dda->layers = d->layers;
    dda->enc = enc;
    dda->params = *p;
    dda->kq = lt__ssb_kthick_q30(p->thickness);
#if LT_CFG_FLOAT32
    dda->kf = 1.0f / (1.0f + (float)p->thickness * 9.31322574615478515625e-10f);
#endif
    dda->w = w;
    return LT_OK;
}

lt_status_t lt_ssdda_init_q30(lt_ssdda_t *dda, const lt_ssb_desc_t *d, const lt_ssb_params_t *p,
                              const lt_q30_t *w)
{
    return dda_prepare(dda, d, p, w, LT_SSB_Q30);
}

uint32_t lt_ssdda_default_steps(const lt_ssdda_t *dda)
{
    return (dda->width > dda->height ? dda->width : dda->height) + 2u;
}

#include "lt_ssb_q30.inc"
#include "lt_ssdda.inc"
#include "lt_ssb_undef.inc"

lt_status_t lt_ssdda_trace16_q30(const lt_ssdda_t *dda, const lt_qray16_q30_t *r, lt_mask16_t k,
                                 uint32_t max_steps, lt_qhit16_q30_t *hit)
{
    if (dda == NULL || r == NULL || hit == NULL || dda->w == NULL || dda->enc != LT_SSB_Q30)
        return LT_E_ARG;
    return dda_trace_q30(dda, r, k, max_steps, hit);
}

#if LT_CFG_FLOAT32

lt_status_t lt_ssdda_init_f32(lt_ssdda_t *dda, const lt_ssb_desc_t *d, const lt_ssb_params_t *p,
                              const float *w)
{
    return dda_prepare(dda, d, p, w, LT_SSB_F32);
}

#include "lt_ssb_f32.inc"
#include "lt_ssdda.inc"
#include "lt_ssb_undef.inc"

lt_status_t lt_ssdda_trace16_f32(const lt_ssdda_t *dda, const lt_qray16_f32_t *r, lt_mask16_t k,
                                 uint32_t max_steps, lt_qhit16_f32_t *hit)
{
    if (dda == NULL || r == NULL || hit == NULL || dda->w == NULL || dda->enc != LT_SSB_F32)
        return LT_E_ARG;
    return dda_trace_f32(dda, r, k, max_steps, hit);
}

#endif /* LT_CFG_FLOAT32 */
