/* lt_paths.c - see lt_paths.h. */
#include "render/lt_paths.h"
#include "io/lt_fx_float.h"
#include "io/lt_scenefile.h"
#include "lt/lt_bvh.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

const lt_path_info_t lt_paths[] = {
    {.name = "q16", .format = "s15.16",
     .desc = "fixed point: s15.16 positions and distances, s1.30 directions, exact int64 products",
     .families = LT_PATHS_OBJECT | LT_PATHS_FRUSTA, .frac_bits = 16,
     .render = &lt_render_ops_q16, .frusta = &lt_ss_ops_q16,
     .bvh_num = (int)LT_BVH_NUM_Q16, .sf_num = LT_SF_NUM_Q16, .qt_enc = -1, .ssb_enc = -1},
    {.name = "n64", .format = "s1.30",
     .desc = "screen space in s1.30 (w = z_ref / z, rays), 64-bit quadtree nodes (24-bit C)",
     .families = LT_PATHS_SCREEN, .frac_bits = 30, .screen = &lt_rp_ops_n64,
     .qt_enc = LT_QT_N64, .ssb_enc = LT_SSB_Q30},
    {.name = "n32", .format = "s1.30",
     .desc = "screen space in s1.30, 32-bit quadtree nodes (12-bit C, minifloat boxes)",
     .note = "32-bit nodes",
     .families = LT_PATHS_SCREEN, .frac_bits = 30, .screen = &lt_rp_ops_n32,
     .qt_enc = LT_QT_N32, .ssb_enc = LT_SSB_Q30},
    {.name = "f32", .format = "float32",
     .desc = "IEEE binary32, no FMA contraction (bit-identical on every build)",
     .families = LT_PATHS_OBJECT | LT_PATHS_FRUSTA | LT_PATHS_SCREEN, .frac_bits = 0,
     .render = &lt_render_ops_f32, .frusta = &lt_ss_ops_f32, .screen = &lt_rp_ops_f32,
     .bvh_num = (int)LT_BVH_NUM_F32, .sf_num = LT_SF_NUM_F32, .qt_enc = LT_QT_F32,
     .ssb_enc = LT_SSB_F32},
    {.name = NULL, .qt_enc = -1, .ssb_enc = -1},
};

const lt_path_info_t *lt_paths_find(const char *name, unsigned families)
{
    const lt_path_info_t *p;
    if (name == NULL)
        return NULL;
    for (p = lt_paths; p->name != NULL; p++)
        if (strcmp(p->name, name) == 0 && (families == 0 || (p->families & families) != 0))
            return p;
    return NULL;
}

int lt_paths_index(const lt_path_info_t *p) { return (int)(p - lt_paths); }

const lt_path_info_t *lt_paths_of_qt_enc(lt_qt_enc_t e)
{
    const lt_path_info_t *p;
    for (p = lt_paths; p->name != NULL; p++)
        if (p->qt_enc >= 0 && p->qt_enc == (int)e)
            return p;
    return NULL;
}

const lt_path_info_t *lt_paths_fallback(const lt_scene_t *s, unsigned families,
                                        const lt_path_info_t *except)
{
    const lt_path_info_t *p;
    lt_diag_t diag;
    for (p = lt_paths; p->name != NULL; p++)
        if (p != except && (p->families & families) != 0 && p->render != NULL &&
            (p->render->scene_check == NULL || p->render->scene_check(s, "", &diag) == 0))
            return p;
    return NULL;
}

int lt_paths_names(unsigned families, const char **names, int max)
{
    const lt_path_info_t *p;
    int n = 0;
    if (max < 1)
        return 0;
    for (p = lt_paths; p->name != NULL && n < max - 1; p++)
        if ((p->families & families) != 0)
            names[n++] = p->name;
    names[n] = NULL;
    return n;
}

void lt_paths_list(unsigned families, char *buf, size_t n)
{
    const char *names[16];
    size_t len = 0;
    int i, k = lt_paths_names(families, names, 16);
    if (n == 0)
        return;
    buf[0] = '\0';
    for (i = 0; i < k && len < n; i++) {
        int w = snprintf(buf + len, n - len, "%s%s", i == 0 ? "" : (i + 1 == k ? " or " : ", "),
                         names[i]);
        if (w < 0)
            break;
        len += (size_t)w;
    }
}

double lt_path_to_double(const lt_path_info_t *p, int64_t raw)
{
    if (p->frac_bits > 0)
        return ldexp((double)raw, -p->frac_bits);
    {
        uint32_t bits = (uint32_t)raw;
        float f;
        memcpy(&f, &bits, sizeof f);
        return (double)f;
    }
}

int64_t lt_path_from_double(const lt_path_info_t *p, double v)
{
    if (p->frac_bits > 0)
        return lt__fxf_from_double(v, p->frac_bits, INT32_MIN, INT32_MAX, NULL);
    {
        float f = (float)v;
        uint32_t bits;
        memcpy(&bits, &f, sizeof bits);
        return (int64_t)bits;
    }
}
