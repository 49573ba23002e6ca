/* lt_paths.c - see lt_paths.h. */
#include "render/lt_paths.h"
#include "io/lt_fx_float.h"
#include "io/lt_scenefile.h"
#include "lt/lt_bvh.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

const lt_path_info_t lt_paths[] = {
    {"q16", "s15.16",
     "fixed point: s15.16 positions and distances, s1.30 directions, exact int64 products",
     LT_PATHS_OBJECT | LT_PATHS_FRUSTA, 16, &lt_render_ops_q16, (int)LT_BVH_NUM_Q16, LT_SF_NUM_Q16,
     -1, -1},
    {"n64", "s1.30",
     "screen space in s1.30 (w = z_ref / z, rays), 64-bit quadtree nodes (24-bit C)",
     LT_PATHS_SCREEN, 30, NULL, 0, 0, LT_QT_N64, LT_SSB_Q30},
    {"n32", "s1.30", "screen space in s1.30, 32-bit quadtree nodes (12-bit C, minifloat boxes)",
     LT_PATHS_SCREEN, 30, NULL, 0, 0, LT_QT_N32, LT_SSB_Q30},
    {"f32", "float32", "IEEE binary32, no FMA contraction (bit-identical on every build)",
     LT_PATHS_OBJECT | LT_PATHS_FRUSTA | LT_PATHS_SCREEN, 0, &lt_render_ops_f32,
     (int)LT_BVH_NUM_F32, LT_SF_NUM_F32, LT_QT_F32, LT_SSB_F32},
    {NULL, NULL, NULL, 0, 0, NULL, 0, 0, -1, -1},
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
