/* fw_model.c - lt-fwmodel: what a machine model predicts for a firmware image's whole-scene run.
 * It runs a firmware blob (a scene blob, a frusta blob or a reprojection blob: the same file the
 * image links) through the same app code the image runs (firmware/apps/lt_sblob.c,
 * reproj_app.c), in the simulator build, so every lane op and memory access is charged to the
 * machine (sim/machines/<name>.def), and splits the charged cycles at the same stage marks the
 * firmware gives the QEMU plugin (firmware/apps/lt_stage.h): the cycles between two calls of the
 * clock go to the stage the first call began. tools/fw_cycles.sh sets these predictions against
 * the plugin's modelled cycles of the images (docs/firmware.md, "Cycle models").
 * Output, two lines per stage that charged anything:
 *   stage K NAME cycles C count N UNIT
 *   ops K OP=COUNT ...
 * where N is the stage's work (rays, shadow samples, source pixels) as the image counts it and
 * the second line the ops charged per class (sim/lt_ops.def names; machine-independent).
 * Exit status: 0, 1 when the blob cannot be read or is refused, 2 usage.
 * Builds: sim only (a meter without a cycle model predicts nothing).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lt_sblob.h"
#include "lt_stage.h"
#include "reproj_app.h"
#include "lt_meter.h"
#include "lt_sim.h"

static uint64_t g_cyc[LT_STAGE__COUNT]; /* cycles charged per stage */
static uint64_t g_ops[LT_STAGE__COUNT][LT_OP__COUNT]; /* ops charged per stage and class */
static uint64_t g_last, g_last_ops[LT_OP__COUNT];
static uint32_t g_cur = LT_STAGE_UNTIMED;

/* the op counts so far, all phases */
static void ops_now(uint64_t ops[LT_OP__COUNT])
{
    static lt_sim_totals_t t;
    int ph, op;
    lt_sim_totals(&t);
    for (op = 0; op < LT_OP__COUNT; op++) {
        ops[op] = 0;
        for (ph = 0; ph < LT_PH__COUNT; ph++)
            ops[op] += t.ctr[ph][op];
    }
}

static uint64_t clock_fn(uint32_t stage)
{
    uint64_t now = lt_meter_cycles(), ops[LT_OP__COUNT];
    int op;
    ops_now(ops);
    for (op = 0; op < LT_OP__COUNT; op++) {
        g_ops[g_cur][op] += ops[op] - g_last_ops[op];
        g_last_ops[op] = ops[op];
    }
    g_cyc[g_cur] += now - g_last;
    g_last = now;
    g_cur = stage < LT_STAGE__COUNT ? stage : LT_STAGE_UNTIMED;
    return now;
}

static uint64_t port_clock(void *ctx, uint32_t stage)
{
    (void)ctx;
    return clock_fn(stage);
}

/* the reprojection app's "total:" line (the traced rays), or an error line */
static char g_rp_lines[4096];
static void port_puts(void *ctx, const char *s)
{
    (void)ctx;
    if (strncmp(s, "total: ", 7) == 0 || strncmp(s, "error ", 6) == 0)
        snprintf(g_rp_lines, sizeof g_rp_lines, "%s", s);
}

static const char *const stage_name[LT_STAGE__COUNT] = {
    "untimed", "packets-primary", "packets-shadow", "single-primary", "single-shadow",
    "frusta", "qt-build", "reproj"};

static void put_stage(uint32_t k, uint64_t n, const char *unit)
{
    int op;
    if (g_cyc[k] == 0)
        return;
    printf("stage %u %s cycles %llu count %llu %s\n", k, stage_name[k],
           (unsigned long long)g_cyc[k], (unsigned long long)n, unit);
    printf("ops %u", k);
    for (op = 0; op < LT_OP__COUNT; op++)
        if (g_ops[k][op] != 0)
            printf(" %s=%llu", lt_sim_op_name(op), (unsigned long long)g_ops[k][op]);
    printf("\n");
}

/* the value after key in the app's "total:" line, 0 if absent */
static uint64_t rp_field(const char *key)
{
    const char *t = strstr(g_rp_lines, "total: ");
    const char *p = t != NULL ? strstr(t, key) : NULL;
    return p != NULL ? strtoull(p + strlen(key), NULL, 10) : 0;
}

static int run_sblob(const char *path, const void *blob, size_t len)
{
    lt_sblob_t s;
    uint64_t rays = 0, srays[2] = {0, 0};
    uint32_t t;
    int single;
    lt_sblob_err_t e = lt_sblob_open(blob, len, &s);
    if (e != LT_SBLOB_OK) {
        fprintf(stderr, "lt-fwmodel: %s: not a usable scene blob: %s\n", path, lt_sblob_err_str(e));
        return 1;
    }
    for (single = 0; single < 2; single++)
        for (t = 0; t < s.tiles_x * s.tiles_y; t++) {
            lt_sblob_tile_t r;
            r.ids = NULL;
            if (lt_sblob_trace_tile(&s, t, single, clock_fn, &r) != LT_OK) {
                fprintf(stderr, "lt-fwmodel: %s: tile %u failed\n", path, t);
                return 1;
            }
            if (!single)
                rays += r.rays;
            srays[single] += r.srays;
        }
    (void)clock_fn(LT_STAGE_UNTIMED);
    put_stage(LT_STAGE_PRIMARY, rays, "rays");
    put_stage(LT_STAGE_SHADOW, srays[0], "rays");
    put_stage(LT_STAGE_PRIMARY1, rays, "rays");
    put_stage(LT_STAGE_SHADOW1, srays[1], "rays");
    return 0;
}

static int run_fblob(const char *path, const void *blob, size_t len)
{
    static lt_fblob_t f; /* its sample table is large */
    uint64_t lit = 0;
    uint32_t t;
    lt_sblob_err_t e = lt_fblob_open(blob, len, &f);
    if (e != LT_SBLOB_OK) {
        fprintf(stderr, "lt-fwmodel: %s: not a usable frusta blob: %s\n", path, lt_sblob_err_str(e));
        return 1;
    }
    for (t = 0; t < 16u; t++) {
        lt_fblob_tile_t r;
        if (lt_fblob_trace_tile(&f, t, clock_fn, &r) != LT_OK) {
            fprintf(stderr, "lt-fwmodel: %s: tile %u failed\n", path, t);
            return 1;
        }
        lit += r.lit;
    }
    (void)clock_fn(LT_STAGE_UNTIMED);
    put_stage(LT_STAGE_FRUSTA, lit * f.spp, "samples");
    return 0;
}

static int run_rpblob(const char *path, const void *blob, size_t len, int single)
{
    const lt_rpb_hdr_t *h = (const lt_rpb_hdr_t *)blob; /* read once lt_rpapp_mem_bytes checked it */
    lt_rpapp_port_t port;
    size_t need = 0;
    void *mem = NULL;
    int rc = lt_rpapp_mem_bytes(blob, len, &need);
    if (rc != LT_RPAPP_OK || posix_memalign(&mem, 64, need) != 0) {
        fprintf(stderr, "lt-fwmodel: %s: not a usable reprojection blob (code %d)\n", path, rc);
        return 1;
    }
    port.puts = port_puts;
    port.ticks = port_clock;
    port.ctx = NULL;
    port.name = "model";
    port.single = single;
    lt_meter_region(mem, need, 0x20000000u);
    rc = lt_rpapp_run(&port, blob, len, mem, need);
    (void)clock_fn(LT_STAGE_UNTIMED);
    free(mem);
    if (rc != LT_RPAPP_OK) {
        fprintf(stderr, "lt-fwmodel: %s: the app failed (code %d): %s", path, rc, g_rp_lines);
        return 1;
    }
    put_stage(LT_STAGE_QT_BUILD, (uint64_t)h->width * h->height * h->layers, "pixels");
    put_stage(LT_STAGE_REPROJ, rp_field(" kept "), "rays");
    return 0;
}

int main(int argc, char **argv)
{
    const char *machine = NULL, *path = NULL;
    void *blob = NULL;
    long sz;
    size_t len;
    uint32_t magic;
    FILE *f;
    lt_diag_t diag;
    int rc, single = 0;
    if ((argc == 4 || argc == 6) && strcmp(argv[1], "--machine") == 0) {
        machine = argv[2];
        path = argv[argc - 1];
        if (argc == 6) {
            if (strcmp(argv[3], "--walk") != 0 ||
                (strcmp(argv[4], "single") != 0 && strcmp(argv[4], "packets") != 0))
                machine = NULL;
            else
                single = strcmp(argv[4], "single") == 0;
        }
    }
    if (machine == NULL || path[0] == '-') {
        fprintf(stderr, "usage: lt-fwmodel --machine NAME [--walk single|packets] BLOB  (machines: "
                        "%s; the walk of a reprojection blob, as the image's ticks line says: "
                        "packets by default)\n",
                lt_meter_machine_names());
        return 2;
    }
    if (lt_meter_init(machine, NULL, NULL, &diag) != 0) {
        fprintf(stderr, "lt-fwmodel: %s\n", diag.msg);
        return 2;
    }
    f = fopen(path, "rb");
    if (f == NULL || fseek(f, 0, SEEK_END) != 0 || (sz = ftell(f)) < 4 || fseek(f, 0, SEEK_SET) != 0) {
        fprintf(stderr, "lt-fwmodel: %s: cannot read (or shorter than 4 bytes)\n", path);
        if (f != NULL)
            fclose(f);
        return 1;
    }
    len = (size_t)sz;
    if (posix_memalign(&blob, 64, len) != 0 || fread(blob, 1, len, f) != len) {
        fprintf(stderr, "lt-fwmodel: %s: cannot read %zu bytes\n", path, len);
        fclose(f);
        free(blob);
        return 1;
    }
    fclose(f);
    memcpy(&magic, blob, 4);
    lt_meter_region(blob, len, 0x10000000u);
    printf("fwmodel %s machine %s\n", path, machine);
    g_last = lt_meter_cycles();
    ops_now(g_last_ops);
    if (magic == LT_SBLOB_MAGIC)
        rc = run_sblob(path, blob, len);
    else if (magic == LT_FBLOB_MAGIC)
        rc = run_fblob(path, blob, len);
    else if (magic == LT_RPB_MAGIC)
        rc = run_rpblob(path, blob, len, single);
    else {
        fprintf(stderr, "lt-fwmodel: %s: not a scene, frusta or reprojection blob (magic 0x%08x)\n",
                path, magic);
        rc = 1;
    }
    free(blob);
    lt_meter_shutdown();
    return rc;
}
