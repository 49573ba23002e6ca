/* test_paths.c - cmocka tests of host/render/lt_paths (the host's registry of numeric paths) and
 * the per-path ops tables it points at (lt_path_ops.h): the names are unique; a path serves a
 * family exactly when it has that family's ops, and every table is complete (all members set; the
 * quantised BVH's four all or none; a frusta path has object ops too); the core's enumeration
 * values (lt_qt_enc_t, LT_BVH_NUM_*, lt_ssb_enc_t) and the scene file's lt_sf_num_t map back to
 * their entries; the scene file accepts exactly the registry's names for "numeric" (plus "both")
 * and "reproject.encoding"; the name lists for options and messages; the fixed-point conversions
 * round trip, and the float path's is the binary32 bit pattern. The ops agree with the core's
 * entry points called directly (the hand dispatch they replace) on the bundled teapot and a small
 * depth image, and the renderers through them give the frame, primary and shadow hashes the
 * hand-dispatched renderers gave. Run from the repository root (scenes/teapot.obj).
 * Builds: host, sim, asan.
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/lt_fx_float.h"
#include "io/lt_mesh.h"
#include "io/lt_scenefile.h"
#include "lt/lt_bvh.h"
#include "render/lt_paths.h"
#include "render/lt_qt_ref.h"
#include "render/lt_render.h"
#include "render/lt_reproject.h"
#include "render/lt_softshadow.h"

static void test_names_unique_and_found(void **state)
{
    const lt_path_info_t *p, *q;
    int n = 0;
    (void)state;
    for (p = lt_paths; p->name != NULL; p++, n++) {
        assert_non_null(p->format);
        assert_non_null(p->desc);
        assert_true(p->families != 0);
        for (q = p + 1; q->name != NULL; q++)
            assert_string_not_equal(p->name, q->name);
        assert_ptr_equal(lt_paths_find(p->name, 0), p);
        assert_ptr_equal(lt_paths_find(p->name, p->families), p);
        /* a family serves: its enumeration value exists */
        assert_int_equal((p->families & LT_PATHS_OBJECT) != 0, p->render != NULL);
        assert_int_equal((p->families & LT_PATHS_SCREEN) != 0, p->screen != NULL);
        assert_int_equal((p->families & LT_PATHS_OBJECT) != 0, p->bvh_num != 0);
        assert_int_equal((p->families & LT_PATHS_OBJECT) != 0, p->sf_num != 0);
        assert_int_equal((p->families & LT_PATHS_SCREEN) != 0, p->qt_enc >= 0);
        assert_int_equal((p->families & LT_PATHS_SCREEN) != 0, p->ssb_enc >= 0);
        assert_int_equal(p->frac_bits == 0, strcmp(p->format, "float32") == 0);
        assert_true(p->qt_enc < LT_PATHS_MAX);
        assert_int_equal(lt_paths_index(p), n);
    }
    assert_int_equal(n, 4);
    assert_true(n < LT_PATHS_MAX);
    assert_null(lt_paths_find("n64", LT_PATHS_OBJECT));
    assert_null(lt_paths_find("q16", LT_PATHS_SCREEN));
    assert_null(lt_paths_find("both", 0));
    assert_null(lt_paths_find(NULL, 0));
}

static void test_enumerations_map_back(void **state)
{
    const lt_path_info_t *q16 = lt_paths_find("q16", 0), *f32 = lt_paths_find("f32", 0);
    const lt_path_info_t *n64 = lt_paths_find("n64", 0), *n32 = lt_paths_find("n32", 0);
    (void)state;
    assert_ptr_equal(lt_paths_of_qt_enc(LT_QT_N64), n64);
    assert_ptr_equal(lt_paths_of_qt_enc(LT_QT_N32), n32);
    assert_ptr_equal(lt_paths_of_qt_enc(LT_QT_F32), f32);
    assert_int_equal(q16->bvh_num, LT_BVH_NUM_Q16);
    assert_int_equal(f32->bvh_num, LT_BVH_NUM_F32);
    assert_int_equal(q16->sf_num | f32->sf_num, LT_SF_NUM_BOTH);
    assert_int_equal(q16->sf_num, LT_SF_NUM_Q16);
    assert_int_equal(n64->ssb_enc, LT_SSB_Q30);
    assert_int_equal(n32->ssb_enc, LT_SSB_Q30);
    assert_int_equal(f32->ssb_enc, LT_SSB_F32);
    assert_string_equal(q16->format, "s15.16");
    assert_string_equal(n64->format, "s1.30");
    assert_string_equal(f32->format, "float32");
}

static void test_lists(void **state)
{
    const char *names[8];
    char buf[128];
    (void)state;
    assert_int_equal(lt_paths_names(LT_PATHS_OBJECT, names, 8), 2);
    assert_string_equal(names[0], "q16");
    assert_string_equal(names[1], "f32");
    assert_null(names[2]);
    assert_int_equal(lt_paths_names(LT_PATHS_SCREEN, names, 8), 3);
    assert_string_equal(names[0], "n64");
    assert_string_equal(names[2], "f32");
    assert_int_equal(lt_paths_names(LT_PATHS_SCREEN, names, 2), 1);
    assert_null(names[1]);
    lt_paths_list(LT_PATHS_SCREEN, buf, sizeof buf);
    assert_string_equal(buf, "n64, n32 or f32");
    lt_paths_list(LT_PATHS_FRUSTA, buf, sizeof buf);
    assert_string_equal(buf, "q16 or f32");
}

/* the scene file's validator keeps its own lists (it links without the renderer): they must be
 * the registry's */
static void test_scene_file_agrees(void **state)
{
    const lt_path_info_t *p;
    lt_scenefile_t sf;
    char text[256];
    lt_diag_t diag;
    (void)state;
    for (p = lt_paths; p->name != NULL; p++) {
        snprintf(text, sizeof text, "{\"mesh\": \"scenes/teapot.obj\", \"numeric\": \"%s\"}",
                 p->name);
        lt_sf_defaults(&sf);
        assert_int_equal(lt_sf_parse(text, "t.json", ".", &sf, &diag) == 0,
                         (p->families & LT_PATHS_OBJECT) != 0);
        if (p->families & LT_PATHS_OBJECT)
            assert_int_equal((int)sf.numeric, p->sf_num);
        snprintf(text, sizeof text,
                 "{\"mesh\": \"scenes/teapot.obj\", \"reproject\": {\"encoding\": \"%s\"}}",
                 p->name);
        lt_sf_defaults(&sf);
        assert_int_equal(lt_sf_parse(text, "t.json", ".", &sf, &diag) == 0,
                         (p->families & LT_PATHS_SCREEN) != 0);
        if (p->families & LT_PATHS_SCREEN)
            assert_ptr_equal(lt_paths_find(sf.rp_encoding, LT_PATHS_SCREEN), p);
    }
    lt_sf_defaults(&sf);
    assert_int_equal(lt_sf_parse("{\"mesh\": \"scenes/teapot.obj\", \"numeric\": \"both\"}",
                                 "t.json", ".", &sf, &diag),
                     0);
    assert_int_equal((int)sf.numeric, LT_SF_NUM_BOTH);
}

static void test_conversions(void **state)
{
    const lt_path_info_t *q16 = lt_paths_find("q16", 0), *n64 = lt_paths_find("n64", 0);
    const lt_path_info_t *f32 = lt_paths_find("f32", 0);
    (void)state;
    assert_true(lt_path_to_double(q16, 65536) == 1.0);
    assert_true(lt_path_to_double(q16, -1) == -ldexp(1.0, -16));
    assert_true(lt_path_to_double(n64, 1 << 30) == 1.0);
    assert_int_equal(lt_path_from_double(q16, 1.5), 98304);
    assert_int_equal(lt_path_from_double(n64, 1e-3), 1073742);
    assert_int_equal(lt_path_from_double(n64, 5.0), INT32_MAX); /* saturates like the core */
    assert_int_equal(lt_path_from_double(q16, -0.5 / 65536.0), 0); /* half up */
    assert_int_equal(lt_path_from_double(f32, 1.0), 0x3f800000);
    assert_true(lt_path_to_double(f32, 0x3f800000) == 1.0);
    assert_true(lt_path_to_double(f32, lt_path_from_double(f32, 0.1)) == (double)0.1f);
}

/* ---- the ops tables ------------------------------------------------------------------------ */

#define SET(f) ((f) != NULL)

/* Every member of every table a path points at is set. */
static void test_ops_complete(void **state)
{
    const lt_path_info_t *p;
    (void)state;
    for (p = lt_paths; p->name != NULL; p++) {
        const lt_render_ops_t *r = p->render;
        const lt_ss_ops_t *f = p->frusta;
        const lt_rp_ops_t *c = p->screen;
        assert_int_equal((p->families & LT_PATHS_FRUSTA) != 0, f != NULL);
        if (r != NULL) {
            int q = r->bvhq_build != NULL;
            assert_int_equal(SET(r->tris) + SET(r->chunks_build) + SET(r->chunks_trace16)
                             + SET(r->bvh_build) + SET(r->bvh_trace16) + SET(r->bvh_occluded16)
                             + SET(r->bvh_trace1) + SET(r->kd_build) + SET(r->kd_trace16)
                             + SET(r->kd_occluded16) + SET(r->grid_size) + SET(r->grid_build)
                             + SET(r->grid_trace16) + SET(r->grid_occluded16)
                             + SET(r->camera_packet) + SET(r->ray16_lane) + SET(r->ray16_tmin)
                             + SET(r->ray16_setup) + SET(r->ray16_t),
                             19);
            assert_int_equal(r->bvhq_trace16 != NULL, q);
            assert_int_equal(r->bvhq_occluded16 != NULL, q);
            assert_int_equal(r->bvhq_trace1 != NULL, q);
            assert_true(r->tri_bytes > 0 && r->box_bytes > 0 && r->kd_bytes > 0 &&
                        r->grid_bytes > 0 && r->ray16_bytes > 0);
        }
        if (f != NULL) {
            assert_non_null(r); /* its BVH and triangles */
            assert_int_equal(SET(f->init) + SET(f->primary_tile) + SET(f->primary_block)
                             + SET(f->shadows_tile) + SET(f->packet) + SET(f->shade_tile)
                             + SET(f->filter) + SET(f->normal_word) + SET(f->shadow_ray1)
                             + SET(f->primary_ray1) + SET(f->tri1) + SET(f->tri_vertices),
                             12);
            assert_true(f->table_bytes > 0 && f->vtable_bytes > 0 && f->ray1_bytes > 0);
        }
        if (c != NULL) {
            assert_int_equal(SET(c->w_from_depth) + SET(c->qt_build) + SET(c->dda_init)
                             + SET(c->hiz_build) + SET(c->qt_planes) + SET(c->setup)
                             + SET(c->rays16) + SET(c->qt_trace16) + SET(c->dda_trace16)
                             + SET(c->hiz_trace16) + SET(c->lane),
                             11);
            assert_true(c->map_bytes > 0 && c->ray_bytes > 0 && c->hit_bytes > 0);
        }
    }
}

/* The bundled teapot, prepared, and the benchmark view at 40x24. */
static void teapot(lt_mesh_t *m, lt_scene_t *s, lt_camera_t *c)
{
    lt_diag_t diag;
    memset(m, 0, sizeof *m);
    assert_int_equal(lt_mesh_load("scenes/teapot.obj", m, &diag), 0);
    assert_int_equal(lt_scene_prepare(m, s, &diag), 0);
    lt_camera_default(s, 40, 24, c);
}

static void *zalloc64(size_t bytes)
{
    void *p = NULL;
    assert_int_equal(posix_memalign(&p, 64, bytes), 0);
    memset(p, 0, bytes);
    return p;
}

/* A BVH built through ops->bvh_build equals the direct build (same bytes). */
static void check_bvh_build(const lt_render_ops_t *ops, const lt_scene_t *s, lt_bvh_t *a,
                            void **arena, lt_bvh_t *b, void **arena_b, int q16)
{
    lt_bvh_desc_t d;
    size_t bytes = 0;
    memset(&d, 0, sizeof d);
    assert_int_equal(lt_bvh_size(s->ntris, &d, &bytes), LT_OK);
    *arena = zalloc64(bytes);
    *arena_b = zalloc64(bytes);
    assert_int_equal(ops->bvh_build(a, &d, ops->tris(s), s->ntris, *arena, bytes), LT_OK);
    assert_int_equal(q16 ? lt_bvh_build_q16(b, &d, s->tq, s->ntris, *arena_b, bytes)
                         : lt_bvh_build_f32(b, &d, s->tf, s->ntris, *arena_b, bytes),
                     LT_OK);
    assert_int_equal(a->bytes, b->bytes);
    assert_memory_equal(*arena, *arena_b, a->bytes);
}

/* s15.16: camera packets, lanes from doubles, the BVH's packet, any-hit and single-ray traces and
 * the kd-tree's build and trace through the ops equal the direct calls. */
static void check_render_q16(const lt_render_ops_t *ops, const lt_scene_t *s, const lt_camera_t *c)
{
    static lt_ray16_q16_t ra, rb;
    lt_bvh_t ba, bb;
    void *aa, *ab;
    lt_hit16_t ha, hb;
    lt_mask16_t k;
    double o[3] = {1.0, -2.5, 3.25}, d[3] = {0.6, 0.0, -0.8}, t;
    int32_t id = -1;
    lt_ray1_q16_t r1;
    int i;
    assert_ptr_equal(ops->tris(s), s->tq);
    assert_int_equal(ops->tri_bytes, sizeof(lt_tri_q16_t));
    check_bvh_build(ops, s, &ba, &aa, &bb, &ab, 1);
    k = ops->camera_packet(c, NULL, 16, 8, &ra);
    assert_int_equal(k, lt_camera_packet_q16(c, 16, 8, &rb));
    assert_memory_equal(&ra, &rb, sizeof ra);
    ops->bvh_trace16(&ba, ops->tris(s), &ra, k, &ha);
    (void)lt_bvh_trace16_q16(&bb, s->tq, &rb, k, &hb);
    assert_memory_equal(&ra, &rb, sizeof ra);
    assert_memory_equal(&ha, &hb, sizeof ha);
    for (i = 0; i < LT_LANES; i++)
        assert_true(ops->ray16_t(&ra, i) == (double)ra.tmax.l[i] / 65536.0);
    /* lanes from doubles, then an any-hit trace */
    for (i = 0; i < LT_LANES; i++) {
        ops->ray16_lane(&ra, i, c->eye, d, 0.125, 1000.0 + i);
        rb.ox.l[i] = lt_q16_from_double_sat(c->eye[0]);
        rb.oy.l[i] = lt_q16_from_double_sat(c->eye[1]);
        rb.oz.l[i] = lt_q16_from_double_sat(c->eye[2]);
        rb.dx.l[i] = lt_q30_from_double_sat(d[0]);
        rb.dy.l[i] = lt_q30_from_double_sat(d[1]);
        rb.dz.l[i] = lt_q30_from_double_sat(d[2]);
        rb.tmin.l[i] = lt_q16_from_double_sat(0.125);
        rb.tmax.l[i] = lt_q16_from_double_sat(1000.0 + i);
    }
    ops->ray16_setup(&ra);
    lt_ray16_q16_setup(&rb);
    assert_memory_equal(&ra, &rb, sizeof ra);
    {
        lt_mask16_t oa = ops->bvh_occluded16(&ba, ops->tris(s), &ra, 0xFFFF), ob = 0;
        (void)lt_bvh_occluded16_q16(&bb, s->tq, &rb, 0xFFFF, &ob);
        assert_int_equal(oa, ob);
    }
    /* one ray */
    memset(&r1, 0, sizeof r1);
    for (i = 0; i < 3; i++) {
        r1.o[i] = lt_q16_from_double_sat(o[i]);
        r1.d[i] = lt_q30_from_double_sat(d[i]);
    }
    r1.tmax = LT_Q16_MAX - 1;
    lt_ray1_q16_setup(&r1);
    (void)lt_bvh_trace1_q16(&bb, s->tq, &r1, &id);
    assert_int_equal(ops->bvh_trace1(&ba, ops->tris(s), o, d, &t), id);
    assert_true(t == (double)r1.tmax / 65536.0);
    free(aa);
    free(ab);
}

/* float32: the same. */
static void check_render_f32(const lt_render_ops_t *ops, const lt_scene_t *s, const lt_camera_t *c)
{
    static lt_ray16_f32_t ra, rb;
    lt_bvh_t ba, bb;
    void *aa, *ab;
    lt_hit16_t ha, hb;
    lt_mask16_t k;
    double o[3] = {1.0, -2.5, 3.25}, d[3] = {0.6, 0.0, -0.8}, t;
    int32_t id = -1;
    lt_ray1_f32_t r1;
    int i;
    assert_ptr_equal(ops->tris(s), s->tf);
    assert_int_equal(ops->tri_bytes, sizeof(lt_tri_f32_t));
    check_bvh_build(ops, s, &ba, &aa, &bb, &ab, 0);
    k = ops->camera_packet(c, NULL, 16, 8, &ra);
    assert_int_equal(k, lt_camera_packet_f32(c, 16, 8, &rb));
    assert_memory_equal(&ra, &rb, sizeof ra);
    ops->bvh_trace16(&ba, ops->tris(s), &ra, k, &ha);
    (void)lt_bvh_trace16_f32(&bb, s->tf, &rb, k, &hb);
    assert_memory_equal(&ra, &rb, sizeof ra);
    assert_memory_equal(&ha, &hb, sizeof ha);
    for (i = 0; i < LT_LANES; i++)
        assert_true(ops->ray16_t(&ra, i) == (double)ra.tmax.l[i]);
    for (i = 0; i < LT_LANES; i++) {
        ops->ray16_lane(&ra, i, c->eye, d, 0.125, 1000.0 + i);
        rb.ox.l[i] = (float)c->eye[0];
        rb.oy.l[i] = (float)c->eye[1];
        rb.oz.l[i] = (float)c->eye[2];
        rb.dx.l[i] = (float)d[0];
        rb.dy.l[i] = (float)d[1];
        rb.dz.l[i] = (float)d[2];
        rb.tmin.l[i] = 0.125f;
        rb.tmax.l[i] = (float)(1000.0 + i);
    }
    ops->ray16_setup(&ra);
    lt_ray16_f32_setup(&rb);
    assert_memory_equal(&ra, &rb, sizeof ra);
    {
        lt_mask16_t oa = ops->bvh_occluded16(&ba, ops->tris(s), &ra, 0xFFFF), ob = 0;
        (void)lt_bvh_occluded16_f32(&bb, s->tf, &rb, 0xFFFF, &ob);
        assert_int_equal(oa, ob);
    }
    memset(&r1, 0, sizeof r1);
    for (i = 0; i < 3; i++) {
        r1.o[i] = (float)o[i];
        r1.d[i] = (float)d[i];
    }
    r1.tmax = 3.0e38f;
    lt_ray1_f32_setup(&r1);
    (void)lt_bvh_trace1_f32(&bb, s->tf, &r1, &id);
    assert_int_equal(ops->bvh_trace1(&ba, ops->tris(s), o, d, &t), id);
    assert_true(t == (double)r1.tmax);
    free(aa);
    free(ab);
}

/* Through the ops, every structure of every object-space path traces the teapot's view into the
 * frame the hand-dispatched renderer traced (lanetrace run --res 40x24 --structure S, before the
 * ops tables), with the intersector of then (Moller-Trumbore); float32 since its scene vertices
 * lie on one grid (the watertight change); bvhq is refused where the path has no quantised nodes. */
static void test_render_ops_agree(void **state)
{
    static const struct {
        const char *name;
        uint32_t hash;
    } golden[] = {{"q16", 0xcba40b40u}, {"f32", 0xb6bdb64eu}}; /* f32: vertices on the float grid */
    const lt_path_info_t *p;
    lt_mesh_t m;
    lt_scene_t s;
    lt_camera_t c;
    size_t g;
    (void)state;
    teapot(&m, &s, &c);
    check_render_q16(lt_paths_find("q16", LT_PATHS_OBJECT)->render, &s, &c);
    check_render_f32(lt_paths_find("f32", LT_PATHS_OBJECT)->render, &s, &c);
    for (g = 0; g < sizeof golden / sizeof golden[0]; g++) {
        const char *const *st;
        lt_frame_t f;
        lt_diag_t diag;
        p = lt_paths_find(golden[g].name, LT_PATHS_OBJECT);
        assert_non_null(p);
        assert_int_equal(lt_frame_alloc(&f, c.width, c.height, &diag), 0);
        for (st = lt_render_structures; *st != NULL; st++) {
            lt_accel_t *a = lt_accel_build(&s, *st, p, &diag);
            if (strcmp(*st, "bvhq") == 0 && p->render->bvhq_build == NULL) {
                assert_null(a);
                assert_non_null(strstr(diag.msg, "exists in s15.16 only"));
                continue;
            }
            assert_non_null(a);
            /* the hashes were taken with Moller-Trumbore, the intersector before watertight
               became the default */
            lt_accel_set_isect(a, LT_ISECT_MT);
            lt_render_primary(&s, a, &c, &f, NULL);
            if (lt_frame_hash(&f) != golden[g].hash)
                printf("  %s %s: hash 0x%08x\n", golden[g].name, *st, lt_frame_hash(&f));
            assert_int_equal(lt_frame_hash(&f), golden[g].hash);
            lt_accel_free(a);
        }
        lt_frame_free(&f);
    }
    lt_scene_free(&s);
    lt_mesh_free(&m);
}

/* lt_accel_set_view: the table holds lt_camera_tile_dirs's directions (and lt_camera_dir's), and
 * primary packets, single rays, shadow packets and depth peeling read from it give the frames and
 * counts they give computing them (41x23: partial tiles at both edges); a camera other than the
 * table's computes its own (a table would give the wrong rays). */
static void test_view_table(void **state)
{
    lt_mesh_t m;
    lt_scene_t s;
    lt_camera_t c, c2;
    lt_diag_t diag;
    double *tab, light[3];
    uint32_t tx, ty, nchk = 0;
    size_t np;
    int g, i;
    (void)state;
    memset(&m, 0, sizeof m);
    assert_int_equal(lt_mesh_load("scenes/teapot.obj", &m, &diag), 0);
    assert_int_equal(lt_scene_prepare(&m, &s, &diag), 0);
    lt_camera_default(&s, 41, 23, &c);
    np = (size_t)c.width * c.height;
    c2 = c;
    c2.eye[0] += 0.25 * s.radius;
    lt_scene_light(&s, NULL, light);
    tab = lt_camera_dirs_table(&c);
    assert_non_null(tab);
    for (ty = 0; ty < c.height; ty += 4)
        for (tx = 0; tx < c.width; tx += 4) {
            double ax[16], ay[16], az[16], bx[16], by[16], bz[16], d[3];
            unsigned ka = lt_camera_tile_dirs(&c, tx, ty, ax, ay, az);
            assert_int_equal(lt_camera_tile_dirs_tab(&c, tab, tx, ty, bx, by, bz), ka);
            assert_memory_equal(ax, bx, sizeof ax);
            assert_memory_equal(ay, by, sizeof ay);
            assert_memory_equal(az, bz, sizeof az);
            for (i = 0; i < 16; i++)
                if ((ka >> i) & 1u) {
                    lt_camera_dir(&c, tx + (uint32_t)(i % 4), ty + (uint32_t)(i / 4), d);
                    assert_true(d[0] == bx[i] && d[1] == by[i] && d[2] == bz[i]);
                    nchk++;
                }
        }
    assert_int_equal(nchk, np);
    free(tab);
    for (g = 0; g < 2; g++) {
        const lt_path_info_t *p = lt_paths_find(g == 0 ? "q16" : "f32", LT_PATHS_OBJECT);
        lt_accel_t *a = lt_accel_build(&s, "bvh", p, &diag);
        lt_frame_t f[4], v[4];
        uint32_t n[2], o[2], nv[2], ov[2];
        int pass;
        assert_non_null(a);
        for (i = 0; i < 4; i++) {
            assert_int_equal(lt_frame_alloc(&f[i], c.width, c.height, &diag), 0);
            assert_int_equal(lt_frame_alloc(&v[i], c.width, c.height, &diag), 0);
        }
        for (pass = 0; pass < 2; pass++) {
            lt_frame_t *x = pass == 0 ? f : v;
            uint32_t *xn = pass == 0 ? n : nv, *xo = pass == 0 ? o : ov;
            assert_int_equal(lt_accel_set_view(a, pass == 0 ? NULL : &c, &diag), 0);
            lt_render_primary(&s, a, &c, &x[0], NULL);
            assert_int_equal(lt_render_primary1(&s, a, &c, &x[1], &diag), 0);
            assert_int_equal(lt_render_peel(&s, a, &c, &x[0], &x[2], &diag), 0);
            assert_int_equal(
                lt_render_shadows(&s, a, &c, &x[0], light, &xn[0], &xo[0], NULL, &diag), 0);
            assert_int_equal(
                lt_render_shadows1(&s, a, &c, &x[0], light, &xn[1], &xo[1], NULL, &diag), 0);
            lt_render_primary(&s, a, &c2, &x[3], NULL); /* not the table's camera */
        }
        for (i = 0; i < 4; i++) {
            assert_memory_equal(f[i].id, v[i].id, np * sizeof *f[i].id);
            assert_memory_equal(f[i].t, v[i].t, np * sizeof *f[i].t);
        }
        assert_int_not_equal(lt_frame_hash(&f[3]), lt_frame_hash(&f[0]));
        assert_true(n[0] == nv[0] && o[0] == ov[0] && n[1] == nv[1] && o[1] == ov[1]);
        assert_true(n[0] > 0 && o[0] > 0);
        printf("  view table %s: %u pixels' directions equal; primary, single, peel, other camera "
               "equal; %u shadow rays, %u occluded both ways\n",
               p->name, nchk, n[0], o[0]);
        for (i = 0; i < 4; i++) {
            lt_frame_free(&f[i]);
            lt_frame_free(&v[i]);
        }
        lt_accel_free(a);
    }
    lt_scene_free(&s);
    lt_mesh_free(&m);
}

/* The soft-shadow renderer through the frusta ops gives the hashes the hand-dispatched renderer
 * gave (lanetrace shadows --mesh scenes/teapot.obj --res 32 --num P --filter F, before the ops
 * tables, Moller-Trumbore; float32 since its vertices lie on one grid): primary images of P-Packet
 * and P-Frusta, then occlusion and filtered E. */
static void test_frusta_ops_golden(void **state)
{
    static const struct {
        const char *name;
        int vis;
        uint32_t prim, result;
    } golden[] = {{"q16", 0, 0xc00a8fb6u, 0x31410b77u}, {"q16", 1, 0xc00a8fb6u, 0x4086c110u},
                  {"f32", 0, 0x11f6e078u, 0x021eebe9u}, {"f32", 1, 0x11f6e078u, 0x01d96a2fu}};
    lt_ss_view_t view;
    lt_mesh_t m;
    lt_scene_t s;
    lt_camera_t c;
    lt_ss_light_t l;
    lt_diag_t diag;
    size_t g;
    (void)state;
    memset(&m, 0, sizeof m);
    assert_int_equal(lt_ss_view_for("scenes/teapot.obj", &view), 1);
    assert_int_equal(lt_mesh_load("scenes/teapot.obj", &m, &diag), 0);
    assert_int_equal(lt_ss_add_ground(&m, 0.6, &diag), 0);
    assert_int_equal(lt_scene_prepare(&m, &s, &diag), 0);
    lt_camera_default(&s, 32, 32, &c);
    assert_int_equal(lt_ss_light_square(&s, view.light, view.size, &l, &diag), 0);
    for (g = 0; g < sizeof golden / sizeof golden[0]; g++) {
        lt_ss_opts_t o;
        lt_softshadow_t *ss;
        lt_ss_opts_default(&s, &o);
        o.path = lt_paths_find(golden[g].name, LT_PATHS_FRUSTA);
        o.filter_vis = golden[g].vis;
        o.isect = LT_ISECT_MT; /* the hashes were taken with Moller-Trumbore */
        ss = lt_ss_create(&s, &c, &l, &o, &diag);
        assert_non_null(ss);
        lt_ss_primary(ss);
        if (lt_ss_primary_hash(ss) != golden[g].prim)
            printf("  %s: primary hash 0x%08x\n", golden[g].name, lt_ss_primary_hash(ss));
        assert_int_equal(lt_ss_primary_hash(ss), golden[g].prim);
        lt_ss_shadows_packet(ss);
        lt_ss_primary_frusta(ss);
        assert_int_equal(lt_ss_primary_hash(ss), golden[g].prim);
        lt_ss_shadows_frusta(ss);
        lt_ss_shade(ss, LT_SS_FRUSTA);
        lt_ss_filter(ss);
        if (lt_ss_hash(ss) != golden[g].result)
            printf("  %s vis %d: result hash 0x%08x\n", golden[g].name, golden[g].vis,
                   lt_ss_hash(ss));
        assert_int_equal(lt_ss_hash(ss), golden[g].result);
        lt_ss_free(ss);
    }
    lt_scene_free(&s);
    lt_mesh_free(&m);
}

/* Screen space: a 24x20 two-layer depth image (a slanted plane, a box in front of it in layer 0),
 * seen from a moved and turned camera. For every screen path the w buffer, the quadtree and its
 * plane count, the mapping, one tile's segments and trace, and the lanes in double through the ops
 * equal the direct calls of the path's ray format (s1.30 or float32). */
static void test_screen_ops_agree(void **state)
{
    enum { W = 24, H = 20, L = 2, N = W * H * L };
    static float z[N], wf_a[N], wf_b[N];
    static lt_q30_t wq[N];
    const lt_path_info_t *p;
    lt_reproj_cam_t src, dst;
    const double move[3] = {0.4, -0.1, 0.2}, rot[3] = {4.0, -2.0, 1.0};
    int e, x, y;
    (void)state;
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            int box = x >= 6 && x < 14 && y >= 5 && y < 12;
            z[y * W + x] = box ? 3.0f + 0.05f * (float)x : 6.0f + 0.1f * (float)x + 0.07f * (float)y;
            z[W * H + y * W + x] = box ? 6.0f + 0.1f * (float)x + 0.07f * (float)y : NAN;
        }
    lt_rp_cam_default(W, H, 0, 0, 0, 0, 60.0, &src);
    lt_rp_cam_move(&src, move, rot, &dst);
    assert_int_equal(lt_qt_zref_exp(z, N, &e), 0);
    for (p = lt_paths; p->name != NULL; p++) {
        const lt_rp_ops_t *ops = p->screen;
        int q30 = p->ssb_enc == (int)LT_SSB_Q30, i, l;
        lt_qt_desc_t qd = {W, H, L, 0};
        lt_qt_params_t par;
        lt_qt_t qa, qb;
        lt_reproj_opts_t ro;
        lt_reproj_q30_t mq;
        lt_reproj_f32_t mf;
        static lt_qray16_q30_t rq;
        static lt_qhit16_q30_t hq;
        static lt_qray16_f32_t rf;
        static lt_qhit16_f32_t hf;
        void *w, *aa, *ab, *map, *ray, *hit;
        size_t bytes, ba, bb;
        uint64_t planes = 0;
        lt_mask16_t ka = 0xFFFF, kb = 0xFFFF;
        if (ops == NULL)
            continue;
        /* w */
        w = ops->w_bytes > 0 ? malloc(N * ops->w_bytes) : wf_a;
        ops->w_from_depth(z, N, e, w, wf_a);
        if (q30) {
            lt_qt_w_from_depth_q30(z, N, e, wq);
            assert_memory_equal(w, wq, sizeof wq);
            for (i = 0; i < N; i++)
                assert_true(wf_a[i] == (float)((double)wq[i] / 1073741824.0));
        } else {
            lt_qt_w_from_depth_f32(z, N, e, wf_b);
            assert_memory_equal(wf_a, wf_b, sizeof wf_b);
        }
        /* the quadtree and its planes */
        qd.enc = (uint32_t)p->qt_enc;
        lt_qt_params_default(&par);
        assert_int_equal(lt_qt_size(&qd, &bytes), LT_OK);
        aa = zalloc64(bytes), ab = zalloc64(bytes);
        ba = bb = bytes;
        assert_int_equal(ops->qt_build(&qa, &qd, &par, w, aa, &ba), LT_OK);
        assert_int_equal(q30 ? lt_qt_build_q30(&qb, &qd, &par, wq, ab, &bb)
                             : lt_qt_build_f32(&qb, &qd, &par, wf_b, ab, &bb),
                         LT_OK);
        assert_int_equal(ba, bb);
        assert_memory_equal(aa, ab, ba);
        for (i = 0; i < (int)(qb.layer_nodes * qb.layers); i++)
            planes += p->qt_enc == (int)LT_QT_N64  ? !LT_QT_N64_IS_AABB(((lt_qt_n64_t *)ab)[i])
                      : p->qt_enc == (int)LT_QT_N32 ? !LT_QT_N32_IS_AABB(((lt_qt_n32_t *)ab)[i])
                                                    : !LT_QT_NF32_IS_AABB(((lt_qt_nf32_t *)ab)[i]);
        assert_int_equal(ops->qt_planes(aa, (uint64_t)qb.layer_nodes * qb.layers), planes);
        assert_true(planes > 0);
        /* the mapping, one tile's segments and trace, the lanes */
        memset(&ro, 0, sizeof ro);
        ro.z_ref = ldexp(1.0, e);
        map = zalloc64(ops->map_bytes), ray = zalloc64(ops->ray_bytes);
        hit = zalloc64(ops->hit_bytes);
        assert_int_equal(ops->setup(&src, &dst, &ro, map), LT_OK);
        assert_int_equal(lt_reproj_setup(&src, &dst, &ro, &mq, &mf), LT_OK);
        assert_memory_equal(map, q30 ? (const void *)&mq : (const void *)&mf, ops->map_bytes);
        ops->rays16(map, 8, 4, ray, &ka);
        if (q30)
            (void)lt_reproj_rays16_q30(&mq, 8, 4, &rq, &kb);
        else
            (void)lt_reproj_rays16_f32(&mf, 8, 4, &rf, &kb);
        assert_int_equal(ka, kb);
        assert_true(ka != 0);
        assert_memory_equal(ray, q30 ? (const void *)&rq : (const void *)&rf, ops->ray_bytes);
        ops->qt_trace16(&qa, ray, ka, 0, hit);
        if (q30)
            (void)lt_qt_trace16_q30(&qb, &rq, kb, 0, &hq);
        else
            (void)lt_qt_trace16_f32(&qb, &rf, kb, 0, &hf);
        for (l = 0; l < LT_LANES; l++) {
            lt_rp_lane_t ln;
            if ((((unsigned)ka >> l) & 1u) == 0)
                continue;
            ops->lane(ray, hit, l, &ln);
            assert_int_equal(ln.status, q30 ? hq.status.l[l] : hf.status.l[l]);
            assert_int_equal(ln.nodes, (uint32_t)(q30 ? hq.nodes.l[l] : hf.nodes.l[l]));
            assert_true(ln.t == (q30 ? (double)hq.t.l[l] / 1073741824.0 : (double)hf.t.l[l]));
            assert_true(ln.w == (q30 ? (double)hq.w.l[l] / 1073741824.0 : (double)hf.w.l[l]));
            assert_true(ln.x == (q30 ? (double)rq.x.l[l] / 65536.0 : (double)rf.x.l[l]));
            assert_true(ln.dw == (q30 ? (double)rq.dw.l[l] / 1073741824.0 : (double)rf.dw.l[l]));
        }
        if (w != (void *)wf_a)
            free(w);
        free(aa), free(ab), free(map), free(ray), free(hit);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_names_unique_and_found), cmocka_unit_test(test_enumerations_map_back),
        cmocka_unit_test(test_lists),                  cmocka_unit_test(test_scene_file_agrees),
        cmocka_unit_test(test_conversions),            cmocka_unit_test(test_ops_complete),
        cmocka_unit_test(test_render_ops_agree),       cmocka_unit_test(test_frusta_ops_golden),
        cmocka_unit_test(test_view_table),
        cmocka_unit_test(test_screen_ops_agree),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
