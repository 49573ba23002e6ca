/* lt_scenefile.c - scene description parsing and validation with cJSON (Debian libcjson).
 * Every error names the file, the key path (e.g. "camera.fov_y_deg") and the rule. Host only.
 */
#include "io/lt_scenefile.h"
#include "lt_cache.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <errno.h>
#include <sys/stat.h>

const char *const lt_sf_structures[] = {"chunks", "bvh", "bvhq", "kd", "grid", NULL};
const char *const lt_sf_isects[] = {"wt", "mt", "wt32", NULL};

/* The machine models' names, from the same generated list as the simulator's table
 * (sim/lt_machines.h): names only, so the validator links without the simulator. */
const char *const lt_sf_machines[] = {
#define LT_MACHINE(id, name, desc, clock_mhz, lanes) name,
#include "lt_machines.h"
    NULL};

static const char machine_list[] = ""
#define LT_MACHINE(id, name, desc, clock_mhz, lanes) ", " name
#include "lt_machines.h"
    ;

const char *lt_sf_machine_list(void)
{
    return sizeof machine_list > 2 ? machine_list + 2 : machine_list;
}

int lt_sf_machine_known(const char *name)
{
    int i;
    for (i = 0; lt_sf_machines[i] != NULL; i++)
        if (strcmp(lt_sf_machines[i], name) == 0)
            return 1;
    return 0;
}

typedef struct ctx {
    const char *name;
    const char *base;
    lt_diag_t *diag;
} ctx_t;

/* The message, with the scene file's name in front. Returns -1. */
static int fail(ctx_t *c, const char *fmt, ...) LT_DIAG_PRINTF(2, 3);
static int fail(ctx_t *c, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    (void)lt_diag_vfail(c->diag, fmt, ap);
    va_end(ap);
    return lt_diag_prefix(c->diag, "%s: ", c->name);
}

void lt_sf_defaults(lt_scenefile_t *sf)
{
    memset(sf, 0, sizeof *sf);
    sf->fov_y_deg = 40.0;
    sf->up[1] = 1.0;
    sf->width = sf->height = 128;
    snprintf(sf->structure, sizeof sf->structure, "bvh");
    snprintf(sf->isect, sizeof sf->isect, "wt");
    sf->numeric = LT_SF_NUM_BOTH;
    snprintf(sf->machine, sizeof sf->machine, "lrb16");
    sf->rp_gamma_norm = sf->rp_gamma_dist = -1.0;
    sf->sh_filter = 1;
}

/* Every member of obj must be one of the names in known (NULL-terminated), and appear once (JSON
 * leaves duplicates to the reader; cJSON would silently take the first). */
static int check_keys(ctx_t *c, const cJSON *obj, const char *where, const char *const *known)
{
    const cJSON *it, *prev;
    cJSON_ArrayForEach(it, obj) {
        int i, ok = 0;
        for (prev = obj->child; prev != it; prev = prev->next)
            if (strcmp(prev->string, it->string) == 0)
                return fail(c, "key '%s%s%s' appears more than once (each key at most once)",
                            where, *where ? "." : "", it->string);
        for (i = 0; known[i] != NULL; i++)
            ok |= strcmp(it->string, known[i]) == 0;
        if (!ok) {
            char list[512] = "";
            for (i = 0; known[i] != NULL; i++) {
                strncat(list, known[i], sizeof list - strlen(list) - 3);
                if (known[i + 1] != NULL)
                    strncat(list, ", ", sizeof list - strlen(list) - 1);
            }
            return fail(c, "unknown key '%s%s%s' (known: %s)", where, *where ? "." : "",
                        it->string, list);
        }
    }
    return 0;
}

/* A cache geometry "sets:ways:line" checked by the cycle model's own parser (sim/lt_cache.c,
 * linked in every build), so a bad one is named with the file and key in every build. */
static int check_cache(ctx_t *c, const char *key, const char *spec)
{
    lt_cache_cfg_t cfg;
    lt_diag_t d;
    if (lt_cache_parse(spec, &cfg, &d) == 0)
        return 0;
    return fail(c, "'%s': %s", key, d.msg);
}

static int get_number(ctx_t *c, const cJSON *it, const char *key, double lo, double hi, double *out)
{
    if (!cJSON_IsNumber(it))
        return fail(c, "'%s' must be a number", key);
    if (!isfinite(it->valuedouble) || it->valuedouble < lo || it->valuedouble > hi)
        return fail(c, "'%s' = %g is out of range [%g, %g]", key, it->valuedouble, lo, hi);
    *out = it->valuedouble;
    return 0;
}

static int get_vec3(ctx_t *c, const cJSON *it, const char *key, double out[3])
{
    int i;
    if (!cJSON_IsArray(it) || cJSON_GetArraySize(it) != 3)
        return fail(c, "'%s' must be an array of 3 numbers", key);
    for (i = 0; i < 3; i++) {
        const cJSON *e = cJSON_GetArrayItem(it, i);
        if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble))
            return fail(c, "'%s[%d]' must be a finite number", key, i);
        out[i] = e->valuedouble;
    }
    return 0;
}

static int get_string(ctx_t *c, const cJSON *it, const char *key, char *out, size_t n)
{
    if (!cJSON_IsString(it) || it->valuestring[0] == '\0')
        return fail(c, "'%s' must be a non-empty string", key);
    if (strlen(it->valuestring) >= n)
        return fail(c, "'%s' is longer than %zu characters", key, n - 1);
    snprintf(out, n, "%s", it->valuestring);
    return 0;
}

static int get_choice(ctx_t *c, const cJSON *it, const char *key, const char *const *choices,
                      char *out, size_t n)
{
    int i;
    char list[256] = "";
    if (get_string(c, it, key, out, n) != 0)
        return -1;
    for (i = 0; choices[i] != NULL; i++) {
        if (strcmp(out, choices[i]) == 0)
            return 0;
        strncat(list, choices[i], sizeof list - strlen(list) - 3);
        if (choices[i + 1] != NULL)
            strncat(list, ", ", sizeof list - strlen(list) - 1);
    }
    return fail(c, "'%s' = \"%s\" is not one of: %s", key, out, list);
}

/* Resolve a path relative to the scene file's directory; input files must exist. */
static int get_path(ctx_t *c, const cJSON *it, const char *key, char *out, size_t n, int must_exist)
{
    char raw[LT_SF_PATH_MAX];
    struct stat st;
    if (get_string(c, it, key, raw, sizeof raw) != 0)
        return -1;
    if (raw[0] == '/' || c->base[0] == '\0')
        snprintf(out, n, "%s", raw);
    else if ((size_t)snprintf(out, n, "%s/%s", c->base, raw) >= n)
        return fail(c, "'%s': resolved path longer than %zu characters", key, n - 1);
    if (must_exist && stat(out, &st) != 0)
        return fail(c, "'%s': file '%s' not found (resolved to '%s')", key, raw, out);
    if (must_exist && !S_ISREG(st.st_mode))
        return fail(c, "'%s': '%s' (resolved to '%s') is %s, not a regular file", key, raw, out,
                    lt_diag_not_regular(out));
    return 0;
}

static int parse_camera(ctx_t *c, const cJSON *cam, lt_scenefile_t *sf)
{
    static const char *const keys[] = {"eye", "target", "up", "fov_y_deg", NULL};
    const cJSON *it;
    double f[3];
    if (!cJSON_IsObject(cam))
        return fail(c, "'camera' must be an object");
    if (check_keys(c, cam, "camera", keys) != 0)
        return -1;
    if ((it = cJSON_GetObjectItemCaseSensitive(cam, "eye")) == NULL)
        return fail(c, "'camera.eye' is missing");
    if (get_vec3(c, it, "camera.eye", sf->eye) != 0)
        return -1;
    if ((it = cJSON_GetObjectItemCaseSensitive(cam, "target")) == NULL)
        return fail(c, "'camera.target' is missing");
    if (get_vec3(c, it, "camera.target", sf->target) != 0)
        return -1;
    if ((it = cJSON_GetObjectItemCaseSensitive(cam, "up")) != NULL &&
        get_vec3(c, it, "camera.up", sf->up) != 0)
        return -1;
    if ((it = cJSON_GetObjectItemCaseSensitive(cam, "fov_y_deg")) != NULL &&
        get_number(c, it, "camera.fov_y_deg", 1.0, 179.0, &sf->fov_y_deg) != 0)
        return -1;
    f[0] = sf->target[0] - sf->eye[0];
    f[1] = sf->target[1] - sf->eye[1];
    f[2] = sf->target[2] - sf->eye[2];
    if (!isfinite(f[0]) || !isfinite(f[1]) || !isfinite(f[2]))
        return fail(c, "'camera.target' - 'camera.eye' overflows a double (their distance is "
                       "above 1.8e308)");
    if (f[0] == 0.0 && f[1] == 0.0 && f[2] == 0.0)
        return fail(c, "'camera.target' equals 'camera.eye': no view direction");
    if (sf->up[0] == 0.0 && sf->up[1] == 0.0 && sf->up[2] == 0.0)
        return fail(c, "'camera.up' is the zero vector: no up direction");
    {
        /* both scaled by their largest component first, so that huge and tiny vectors neither
           overflow nor underflow: the sine of their angle */
        double fm = fmax(fabs(f[0]), fmax(fabs(f[1]), fabs(f[2])));
        double um = fmax(fabs(sf->up[0]), fmax(fabs(sf->up[1]), fabs(sf->up[2])));
        double g[3] = {f[0] / fm, f[1] / fm, f[2] / fm};
        double u[3] = {sf->up[0] / um, sf->up[1] / um, sf->up[2] / um};
        double x[3] = {g[1] * u[2] - g[2] * u[1], g[2] * u[0] - g[0] * u[2],
                       g[0] * u[1] - g[1] * u[0]};
        double s2 = (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) /
                    ((g[0] * g[0] + g[1] * g[1] + g[2] * g[2]) * (u[0] * u[0] + u[1] * u[1] +
                                                                  u[2] * u[2]));
        if (!(s2 > 1e-12))
            return fail(c, "'camera.up' [%g, %g, %g] is parallel to the view direction "
                           "('camera.target' - 'camera.eye' = [%g, %g, %g]; the angle between "
                           "them must be above 1e-6 rad)",
                        sf->up[0], sf->up[1], sf->up[2], f[0], f[1], f[2]);
    }
    sf->has_camera = 1;
    return 0;
}

/* "reproject": { "move": [x,y,z], "move_relative": bool, "rot": [yaw,pitch,roll],
 * "encoding": "n64"|"n32"|"f32", "layers": K, "channel": "Z", "color": bool, "distance": bool } */
static int parse_reproject(ctx_t *c, const cJSON *rp, lt_scenefile_t *sf)
{
    static const char *const keys[] = {"move", "move_relative", "rot", "encoding", "layers",
                                       "channel", "color", "distance", "tracer", "gamma_norm",
                                       "gamma_dist", NULL};
    static const char *const encs[] = {"n64", "n32", "f32", NULL};
    static const char *const tracers[] = {"quadtree", "dda", "hiz", NULL};
    const cJSON *it;
    double v;
    if (!cJSON_IsObject(rp))
        return fail(c, "'reproject' must be an object");
    if (check_keys(c, rp, "reproject", keys) != 0)
        return -1;
    if ((it = cJSON_GetObjectItemCaseSensitive(rp, "move")) != NULL &&
        get_vec3(c, it, "reproject.move", sf->rp_move) != 0)
        return -1;
    if ((it = cJSON_GetObjectItemCaseSensitive(rp, "rot")) != NULL) {
        int i;
        if (get_vec3(c, it, "reproject.rot", sf->rp_rot) != 0)
            return -1;
        for (i = 0; i < 3; i++)
            if (fabs(sf->rp_rot[i]) > 180.0)
                return fail(c, "'reproject.rot[%d]' = %g is out of range [-180, 180]", i,
                            sf->rp_rot[i]);
    }
    if ((it = cJSON_GetObjectItemCaseSensitive(rp, "encoding")) != NULL &&
        get_choice(c, it, "reproject.encoding", encs, sf->rp_encoding, sizeof sf->rp_encoding) != 0)
        return -1;
    if ((it = cJSON_GetObjectItemCaseSensitive(rp, "layers")) != NULL) {
        if (get_number(c, it, "reproject.layers", 1, 16, &v) != 0)
            return -1;
        if (v != floor(v))
            return fail(c, "'reproject.layers' must be a whole number");
        sf->rp_layers = (uint32_t)v;
    }
    if ((it = cJSON_GetObjectItemCaseSensitive(rp, "channel")) != NULL &&
        get_string(c, it, "reproject.channel", sf->rp_channel, sizeof sf->rp_channel) != 0)
        return -1;
    if ((it = cJSON_GetObjectItemCaseSensitive(rp, "move_relative")) != NULL) {
        if (!cJSON_IsBool(it))
            return fail(c, "'reproject.move_relative' must be true or false");
        sf->rp_move_rel = cJSON_IsTrue(it);
    }
    if ((it = cJSON_GetObjectItemCaseSensitive(rp, "color")) != NULL) {
        if (!cJSON_IsBool(it))
            return fail(c, "'reproject.color' must be true or false");
        sf->rp_color = cJSON_IsTrue(it);
    }
    if ((it = cJSON_GetObjectItemCaseSensitive(rp, "distance")) != NULL) {
        if (!cJSON_IsBool(it))
            return fail(c, "'reproject.distance' must be true or false");
        sf->rp_distance = cJSON_IsTrue(it);
    }
    if ((it = cJSON_GetObjectItemCaseSensitive(rp, "tracer")) != NULL &&
        get_choice(c, it, "reproject.tracer", tracers, sf->rp_tracer, sizeof sf->rp_tracer) != 0)
        return -1;
    if ((it = cJSON_GetObjectItemCaseSensitive(rp, "gamma_norm")) != NULL &&
        get_number(c, it, "reproject.gamma_norm", 0.0, 1.0, &sf->rp_gamma_norm) != 0)
        return -1;
    if ((it = cJSON_GetObjectItemCaseSensitive(rp, "gamma_dist")) != NULL &&
        get_number(c, it, "reproject.gamma_dist", 0.0, 1.0, &sf->rp_gamma_dist) != 0)
        return -1;
    sf->has_reproject = 1;
    return 0;
}

/* "shadows": { "primary": "packet"|"frusta"|"both", "method": "frusta"|"packet"|"both",
 * "filter": bool, "leaf": N, "cull": "bcrflst" (letters b c r f l s p t), "spp": 4|8|16|32 }
 * (lanetrace shadows; written by lanetrace tune) */
static int parse_shadows(ctx_t *c, const cJSON *sh, lt_scenefile_t *sf)
{
    static const char *const keys[] = {"primary", "method", "filter", "leaf", "cull", "spp", NULL};
    static const char *const both[] = {"packet", "frusta", "both", NULL};
    const cJSON *it;
    double v;
    if (!cJSON_IsObject(sh))
        return fail(c, "'shadows' must be an object");
    if (check_keys(c, sh, "shadows", keys) != 0)
        return -1;
    if ((it = cJSON_GetObjectItemCaseSensitive(sh, "primary")) != NULL &&
        get_choice(c, it, "shadows.primary", both, sf->sh_primary, sizeof sf->sh_primary) != 0)
        return -1;
    if ((it = cJSON_GetObjectItemCaseSensitive(sh, "method")) != NULL &&
        get_choice(c, it, "shadows.method", both, sf->sh_method, sizeof sf->sh_method) != 0)
        return -1;
    if ((it = cJSON_GetObjectItemCaseSensitive(sh, "filter")) != NULL) {
        if (!cJSON_IsBool(it))
            return fail(c, "'shadows.filter' must be true or false");
        sf->sh_filter = cJSON_IsTrue(it);
    }
    if ((it = cJSON_GetObjectItemCaseSensitive(sh, "leaf")) != NULL) {
        if (get_number(c, it, "shadows.leaf", 1, 64, &v) != 0)
            return -1;
        if (v != floor(v))
            return fail(c, "'shadows.leaf' must be a whole number");
        sf->sh_leaf = (uint32_t)v;
    }
    if ((it = cJSON_GetObjectItemCaseSensitive(sh, "spp")) != NULL) {
        if (get_number(c, it, "shadows.spp", 4, 32, &v) != 0)
            return -1;
        if (v != 4 && v != 8 && v != 16 && v != 32)
            return fail(c, "'shadows.spp' = %g: expected 4, 8, 16 or 32 samples per pixel", v);
        sf->sh_spp = (uint32_t)v;
    }
    if ((it = cJSON_GetObjectItemCaseSensitive(sh, "cull")) != NULL) {
        const char *p;
        if (get_string(c, it, "shadows.cull", sf->sh_cull, sizeof sf->sh_cull) != 0)
            return -1;
        for (p = sf->sh_cull; *p != '\0' && strcmp(sf->sh_cull, "none") != 0; p++)
            if (strchr("bcrflspt", *p) == NULL)
                return fail(c, "'shadows.cull' = \"%s\": expected letters of b, c, r, f, l, s, "
                               "p, t or \"none\"", sf->sh_cull);
    }
    sf->has_shadows = 1;
    return 0;
}

static int parse_root(ctx_t *c, const cJSON *root, lt_scenefile_t *sf)
{
    static const char *const keys[] = {"lanetrace", "mesh",   "depth",   "camera",  "resolution",
                                       "structure", "isect",  "numeric", "machine", "caches",
                                       "lights",    "outputs", "reproject", "leaf", "shadows",
                                       NULL};
    static const char *const cache_keys[] = {"l1", "l2", NULL};
    static const char *const light_keys[] = {"type", "position", "intensity", NULL};
    static const char *const out_keys[] = {"report", "csv", NULL};
    static const char *const nums[] = {"q16", "f32", "both", NULL};
    static const char *const light_types[] = {"point", NULL};
    const cJSON *it;
    double v;
    char tmp[32];

    if (!cJSON_IsObject(root))
        return fail(c, "the top level must be a JSON object");
    if (check_keys(c, root, "", keys) != 0)
        return -1;
    if ((it = cJSON_GetObjectItemCaseSensitive(root, "lanetrace")) != NULL) {
        if (get_number(c, it, "lanetrace", 1, 1, &v) != 0)
            return fail(c, "'lanetrace' (format version) must be 1");
    }
    if ((it = cJSON_GetObjectItemCaseSensitive(root, "mesh")) != NULL &&
        get_path(c, it, "mesh", sf->mesh, sizeof sf->mesh, 1) != 0)
        return -1;
    if ((it = cJSON_GetObjectItemCaseSensitive(root, "depth")) != NULL &&
        get_path(c, it, "depth", sf->depth, sizeof sf->depth, 1) != 0)
        return -1;
    if (sf->mesh[0] == '\0' && sf->depth[0] == '\0')
        return fail(c, "needs 'mesh' (object space) or 'depth' (screen space)");
    if ((it = cJSON_GetObjectItemCaseSensitive(root, "camera")) != NULL &&
        parse_camera(c, it, sf) != 0)
        return -1;
    if ((it = cJSON_GetObjectItemCaseSensitive(root, "resolution")) != NULL) {
        double w, h;
        if (cJSON_IsNumber(it)) {
            if (get_number(c, it, "resolution", 1, LT_SF_MAX_RES, &w) != 0)
                return -1;
            h = w;
        } else if (cJSON_IsArray(it) && cJSON_GetArraySize(it) == 2) {
            if (get_number(c, cJSON_GetArrayItem(it, 0), "resolution[0]", 1, LT_SF_MAX_RES, &w) != 0 ||
                get_number(c, cJSON_GetArrayItem(it, 1), "resolution[1]", 1, LT_SF_MAX_RES, &h) != 0)
                return -1;
        } else {
            return fail(c, "'resolution' must be a number or [width, height]");
        }
        if (w != floor(w) || h != floor(h))
            return fail(c, "'resolution' must be whole pixels");
        sf->width = (uint32_t)w;
        sf->height = (uint32_t)h;
    }
    if ((it = cJSON_GetObjectItemCaseSensitive(root, "structure")) != NULL) {
        if (get_choice(c, it, "structure", lt_sf_structures, sf->structure,
                       sizeof sf->structure) != 0)
            return -1;
        sf->given |= LT_SF_GIVEN_STRUCTURE;
    }
    if ((it = cJSON_GetObjectItemCaseSensitive(root, "isect")) != NULL &&
        get_choice(c, it, "isect", lt_sf_isects, sf->isect, sizeof sf->isect) != 0)
        return -1;
    if ((it = cJSON_GetObjectItemCaseSensitive(root, "numeric")) != NULL) {
        if (get_choice(c, it, "numeric", nums, tmp, sizeof tmp) != 0)
            return -1;
        sf->numeric = strcmp(tmp, "q16") == 0 ? LT_SF_NUM_Q16
                      : strcmp(tmp, "f32") == 0 ? LT_SF_NUM_F32 : LT_SF_NUM_BOTH;
        sf->given |= LT_SF_GIVEN_NUMERIC;
    }
    if ((it = cJSON_GetObjectItemCaseSensitive(root, "machine")) != NULL &&
        get_choice(c, it, "machine", lt_sf_machines, sf->machine, sizeof sf->machine) != 0)
        return -1;
    if ((it = cJSON_GetObjectItemCaseSensitive(root, "caches")) != NULL) {
        const cJSON *x;
        if (!cJSON_IsObject(it))
            return fail(c, "'caches' must be an object");
        if (check_keys(c, it, "caches", cache_keys) != 0)
            return -1;
        if ((x = cJSON_GetObjectItemCaseSensitive(it, "l1")) != NULL &&
            (get_string(c, x, "caches.l1", sf->l1, sizeof sf->l1) != 0 ||
             check_cache(c, "caches.l1", sf->l1) != 0))
            return -1;
        if ((x = cJSON_GetObjectItemCaseSensitive(it, "l2")) != NULL &&
            (get_string(c, x, "caches.l2", sf->l2, sizeof sf->l2) != 0 ||
             check_cache(c, "caches.l2", sf->l2) != 0))
            return -1;
    }
    if ((it = cJSON_GetObjectItemCaseSensitive(root, "lights")) != NULL) {
        const cJSON *l;
        if (!cJSON_IsArray(it))
            return fail(c, "'lights' must be an array");
        if (cJSON_GetArraySize(it) > LT_SF_MAX_LIGHTS)
            return fail(c, "'lights' has %d entries (at most %d)", cJSON_GetArraySize(it),
                        LT_SF_MAX_LIGHTS);
        cJSON_ArrayForEach(l, it) {
            char where[32], key[48];
            const cJSON *x;
            lt_sf_light_t *lt = &sf->lights[sf->nlights];
            snprintf(where, sizeof where, "lights[%d]", sf->nlights);
            if (!cJSON_IsObject(l))
                return fail(c, "'%s' must be an object", where);
            if (check_keys(c, l, where, light_keys) != 0)
                return -1;
            snprintf(key, sizeof key, "%s.type", where);
            if ((x = cJSON_GetObjectItemCaseSensitive(l, "type")) != NULL &&
                get_choice(c, x, key, light_types, tmp, sizeof tmp) != 0)
                return -1;
            snprintf(key, sizeof key, "%s.position", where);
            if ((x = cJSON_GetObjectItemCaseSensitive(l, "position")) == NULL)
                return fail(c, "'%s' is missing", key);
            if (get_vec3(c, x, key, lt->position) != 0)
                return -1;
            lt->intensity = 1.0;
            snprintf(key, sizeof key, "%s.intensity", where);
            if ((x = cJSON_GetObjectItemCaseSensitive(l, "intensity")) != NULL &&
                get_number(c, x, key, 0.0, 1e12, &lt->intensity) != 0)
                return -1;
            sf->nlights++;
        }
    }
    if ((it = cJSON_GetObjectItemCaseSensitive(root, "reproject")) != NULL &&
        parse_reproject(c, it, sf) != 0)
        return -1;
    if ((it = cJSON_GetObjectItemCaseSensitive(root, "shadows")) != NULL &&
        parse_shadows(c, it, sf) != 0)
        return -1;
    if ((it = cJSON_GetObjectItemCaseSensitive(root, "leaf")) != NULL) {
        if (get_number(c, it, "leaf", 1, 64, &v) != 0)
            return -1;
        if (v != floor(v))
            return fail(c, "'leaf' must be a whole number");
        sf->leaf = (uint32_t)v;
        sf->given |= LT_SF_GIVEN_LEAF;
    }
    if ((it = cJSON_GetObjectItemCaseSensitive(root, "outputs")) != NULL) {
        const cJSON *x;
        if (!cJSON_IsObject(it))
            return fail(c, "'outputs' must be an object");
        if (check_keys(c, it, "outputs", out_keys) != 0)
            return -1;
        if ((x = cJSON_GetObjectItemCaseSensitive(it, "report")) != NULL &&
            get_path(c, x, "outputs.report", sf->out_report, sizeof sf->out_report, 0) != 0)
            return -1;
        if ((x = cJSON_GetObjectItemCaseSensitive(it, "csv")) != NULL &&
            get_path(c, x, "outputs.csv", sf->out_csv, sizeof sf->out_csv, 0) != 0)
            return -1;
    }
    return 0;
}

int lt_sf_parse(const char *text, const char *name, const char *base_dir, lt_scenefile_t *sf,
                lt_diag_t *diag)
{
    ctx_t c;
    cJSON *root;
    const char *end = NULL;
    int r;
    c.name = name;
    c.base = base_dir != NULL ? base_dir : "";
    c.diag = diag;
    lt_sf_defaults(sf);
    {
        /* cJSON keeps a string only up to a \u0000 escape: a path would be cut short silently */
        const char *q;
        for (q = strstr(text, "\\u"); q != NULL; q = strstr(q + 2, "\\u"))
            if (q[2] == '0' && q[3] == '0' && q[4] == '0' && q[5] == '0') {
                int line = 1;
                const char *p;
                size_t bs = 0;
                for (p = q; p > text && p[-1] == '\\'; p--)
                    bs++;
                if (bs % 2 != 0)
                    continue; /* an escaped backslash before "u0000": plain text */
                for (p = text; p < q; p++)
                    line += *p == '\n';
                return lt_diag_fail(diag, "%s: line %d: a string holds \\u0000 (NUL); no key "
                                    "or value of a scene file may contain it", name, line);
            }
    }
    root = cJSON_ParseWithOpts(text, &end, 1);
    if (root == NULL) {
        /* report line and column of the first byte cJSON could not take */
        int line = 1, col = 1;
        const char *p;
        for (p = text; end != NULL && p < end && *p != '\0'; p++) {
            if (*p == '\n') {
                line++;
                col = 1;
            } else {
                col++;
            }
        }
        {
            /* cJSON stops at CJSON_NESTING_LIMIT levels of arrays and objects: valid JSON, so
             * say so rather than "not valid JSON" (no scene key nests deeper than 3) */
            int depth = 0, in_str = 0;
            for (p = text; end != NULL && p <= end && *p != '\0'; p++) {
                if (in_str) {
                    if (*p == '\\' && p[1] != '\0')
                        p++;
                    else if (*p == '"')
                        in_str = 0;
                } else if (*p == '"') {
                    in_str = 1;
                } else if (*p == '[' || *p == '{') {
                    depth++;
                } else if ((*p == ']' || *p == '}') && depth > 0) {
                    depth--;
                }
            }
            if (depth > CJSON_NESTING_LIMIT)
                return fail(&c, "arrays and objects nested deeper than %d levels at line %d, "
                            "column %d (CJSON_NESTING_LIMIT; a scene file nests at most 3)",
                            CJSON_NESTING_LIMIT, line, col);
        }
        return fail(&c, "not valid JSON at line %d, column %d", line, col);
    }
    r = parse_root(&c, root, sf);
    cJSON_Delete(root);
    return r;
}

int lt_sf_load(const char *path, lt_scenefile_t *sf, lt_diag_t *diag)
{
    FILE *f;
    char *text, base[LT_SF_PATH_MAX];
    const char *slash;
    long n;
    int r;
    /* scene files are small: anything above 1 MiB is not one */
    const long max = 1L << 20;

    f = fopen(path, "rb");
    if (f == NULL) {
        lt_diag_fail(diag, "%s: cannot open the scene file: %s", path, strerror(errno));
        return -1;
    }
    {
        struct stat st;
        int rs = fstat(fileno(f), &st);
        if (rs != 0 || !S_ISREG(st.st_mode)) {
            fclose(f);
            lt_diag_fail(diag, "%s: not a regular file (%s); a scene file is a JSON file", path,
                         rs != 0 ? "cannot stat it" : S_ISDIR(st.st_mode) ? "a directory"
                                                      : "a device, pipe or socket");
            return -1;
        }
    }
    if (fseek(f, 0, SEEK_END) != 0 || (n = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0) {
        fclose(f);
        lt_diag_fail(diag, "%s: cannot read the scene file", path);
        return -1;
    }
    if (n > max) {
        fclose(f);
        lt_diag_fail(diag, "%s: %ld bytes exceeds the scene file limit of %ld", path, n, max);
        return -1;
    }
    text = malloc((size_t)n + 1);
    if (text == NULL || fread(text, 1, (size_t)n, f) != (size_t)n) {
        fclose(f);
        free(text);
        lt_diag_fail(diag, "%s: cannot read the scene file", path);
        return -1;
    }
    fclose(f);
    text[n] = '\0';
    if (memchr(text, '\0', (size_t)n) != NULL) {
        /* the parser would stop at it and ignore the rest of the file */
        const char *z = memchr(text, '\0', (size_t)n), *q;
        int line = 1, col = 1;
        long at = (long)(z - text);
        for (q = text; q < z; q++) {
            col = *q == '\n' ? 1 : col + 1;
            line += *q == '\n';
        }
        free(text);
        lt_diag_fail(diag, "%s: a NUL byte at line %d, column %d (byte %ld of %ld); a scene file "
                     "is JSON text", path, line, col, at, n);
        return -1;
    }
    slash = strrchr(path, '/');
    if (slash == NULL)
        base[0] = '\0';
    else
        snprintf(base, sizeof base, "%.*s", (int)(slash - path), path);
    r = lt_sf_parse(text, path, slash == path ? "/" : base, sf, diag);
    free(text);
    if (r == 0)
        snprintf(sf->path, sizeof sf->path, "%s", path);
    return r;
}
