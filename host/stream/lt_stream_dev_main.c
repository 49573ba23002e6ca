/* lt_stream_dev_main.c - build/sim/lt-stream-dev: the simulator acting as a streaming device. Runs
 * the same device code as the firmware image (firmware/apps/stream_dev.c) with the core built in
 * LT_COST_SIM, so its TILE and SUMMARY records carry the simulator's counters (modelled cycles,
 * packet/ray box and triangle tests), and its device clock is the modelled cycle count (plus idle
 * time spent waiting for link slots) at the machine's clock. Frames go to stdout or --out.
 * --direct traces the same frames without streaming and prints one summary line per frame in the
 * format of lt-stream --tiles, the reference the end-to-end test compares the stream against.
 * Exit: 0 ok, 1 device or output error, 2 usage. Host (sim build) only; it reads the cycle model
 * through lt_meter.h like the other programs.
 */
#include "lt/lt.h"
#include "lt_meter.h"
#include "stream_dev.h"
#include "cli/lt_opt.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

typedef struct simdev {
    FILE *out;
    uint64_t idle;      /* ticks spent waiting for link slots */
    int werr;           /* a write failed */
} simdev_t;

static uint64_t sd_ticks(void *ctx)
{
    simdev_t *d = ctx;
    return lt_meter_cycles() + d->idle;
}

static void sd_idle_until(void *ctx, uint64_t t)
{
    simdev_t *d = ctx;
    uint64_t now = sd_ticks(ctx);
    if (now < t)
        d->idle += t - now;
}

static void sd_counters(void *ctx, lt_sdev_ctr_t *c)
{
    lt_meter_totals_t t;
    (void)ctx;
    lt_meter_totals(&t);
    c->cycles = t.total_cycles;
    c->aabb = t.events[LT_EV_AABB];
    c->aabb_rays = t.events[LT_EV_AABB_RAYS];
    c->tris = t.events[LT_EV_TRIS];
    c->tri_rays = t.events[LT_EV_TRI_RAYS];
}

static void sd_region(void *ctx, const void *p, size_t bytes, uint64_t sim_base)
{
    (void)ctx;
    lt_meter_region(p, bytes, sim_base);
}

static void sd_sink(void *ctx, const uint8_t *b, uint32_t n)
{
    simdev_t *d = ctx;
    if (fwrite(b, 1, n, d->out) != n)
        d->werr = 1;
}

typedef struct args {
    const char *machine, *out;
    int frames, image_from, cap, link;
} args_t;

/* The options into cfg and a. LT_OPT_OK, LT_OPT_HELP or LT_OPT_USAGE. */
static int parse_args(lt_sdev_cfg_t *cfg, args_t *a, int argc, char **argv)
{
    char machine_help[512];
    size_t k;
    const char *name;
    int i, rc;
    const lt_opt_t opts[] = {
        LT_OPT_STR("--machine", "NAME", &a->machine, machine_help),
        LT_OPT_INT("--frames", "N", &a->frames, 1, LT_SDEV_MAX_FRAMES,
                   "image frames to trace, {range} (default 4)"),
        LT_OPT_INT("--image-from", "N", &a->image_from, 0, 1000000,
                   "frames >= N also stream IMAGE tiles, {range} (default 2; N >= frames: none)"),
        LT_OPT_INT("--cap", "N", &a->cap, 4, 64,
                   "batcher ring capacity in frames, {range} (default 16; limits scale)"),
        LT_OPT_INT("--link", "B", &a->link, 64, 1000000000,
                   "link budget in bytes/s, {range} (default 64000, full-speed HID)"),
        LT_OPT_STR("--out", "PATH", &a->out, "write the frames to PATH instead of stdout"),
        LT_OPT_FLAG_("--direct", &cfg->direct, "trace without streaming; print one summary line "
                                               "per frame"),
        LT_OPT_END_};
    const lt_opt_cmd_t cmd = {"lt-stream-dev", "[options]",
                              "The simulator acting as a streaming device: trace frames on a "
                              "machine model and\nstream the report frames.\n",
                              "exit status: 0 ok, 1 device or output error, 2 usage\n", opts, NULL,
                              0, NULL};
    k = (size_t)snprintf(machine_help, sizeof machine_help, "machine model (default mcu-m4):");
    for (i = 0; (name = lt_meter_machine_name(i)) != NULL && k < sizeof machine_help; i++) {
        lt_meter_machine_t m;
        (void)lt_meter_machine_info(name, &m);
        k += (size_t)snprintf(machine_help + k, sizeof machine_help - k, "%s %s (%u MHz)",
                              i > 0 ? "," : "", name, m.clock_mhz);
    }
    rc = lt_opt_parse(&cmd, argc, argv, 1);
    cfg->frames = (uint32_t)a->frames;
    cfg->image_from = (uint32_t)a->image_from;
    return rc;
}

int main(int argc, char **argv)
{
    static lt_sdev_result_t res;
    args_t ar = {"mcu-m4", NULL, 0, 0, 16, (int)LT_STREAM_HID_BYTES_PER_S};
    lt_meter_machine_t m;
    lt_sdev_cfg_t cfg;
    lt_sdev_port_t port;
    simdev_t dev;
    char name[32];
    lt_diag_t diag;
    uint32_t f;
    int rc;

    lt_sdev_cfg_default(&cfg);
    ar.frames = (int)cfg.frames;
    ar.image_from = (int)cfg.image_from;
    if ((rc = parse_args(&cfg, &ar, argc, argv)) != LT_OPT_OK)
        return lt_opt_exit_code(rc);
    if (lt_meter_machine_info(ar.machine, &m) != 0) {
        fprintf(stderr, "lt-stream-dev: --machine %s: unknown machine (known: %s)\n", ar.machine,
                lt_meter_machine_names());
        return 2;
    }
    if (lt_meter_init(ar.machine, NULL, NULL, &diag) != 0) {
        fprintf(stderr, "lt-stream-dev: %s\n", diag.msg);
        return 1;
    }
    /* the default limits (16/12/8) scaled to the ring: TILE 3/4, IMAGE 1/2 of it */
    cfg.link.link_bytes_per_s = (uint32_t)ar.link;
    cfg.link.cap = (uint32_t)ar.cap;
    cfg.link.limit[0] = (uint32_t)ar.cap;
    cfg.link.limit[1] = (uint32_t)ar.cap * 3 / 4;
    cfg.link.limit[2] = (uint32_t)ar.cap / 2;
    memset(&dev, 0, sizeof dev);
    dev.out = stdout;
    if (!cfg.direct) {
        if (ar.out != NULL) {
            dev.out = fopen(ar.out, "wb");
            if (dev.out == NULL) {
                fprintf(stderr, "lt-stream-dev: %s: cannot write: %s\n", ar.out, strerror(errno));
                return 1;
            }
        } else if (isatty(1)) {
            fprintf(stderr, "lt-stream-dev: stdout is a terminal; the stream is binary: pipe it "
                            "into lt-stream or use --out PATH\n");
            return 2;
        }
    }
    snprintf(name, sizeof name, "sim:%s", m.name);
    port.ticks = sd_ticks;
    port.idle_until = sd_idle_until;
    port.counters = sd_counters;
    port.region = sd_region;
    port.sink = sd_sink;
    port.ctx = &dev;
    port.tick_hz = m.clock_mhz * 1000000u;
    port.valid = LT_STREAM_F_TICKS | LT_STREAM_F_CYCLES | LT_STREAM_F_AABB | LT_STREAM_F_TRIS;
    port.source = LT_STREAM_SRC_SIM;
    port.name = name;
    rc = lt_sdev_run(&port, &cfg, &res);
    if (cfg.direct) {
        for (f = 0; f < res.frames; f++) {
            const lt_stream_summary_t *s = &res.sum[f];
            printf("summary %u tiles %u rays %u hits %u hash 0x%08x ticks %llu cycles %llu aabb %u "
                   "aabb_rays %u tris %u tri_rays %u\n", s->frame, s->tiles, s->rays, s->hits,
                   s->hash, (unsigned long long)s->ticks, (unsigned long long)s->cycles, s->aabb,
                   s->aabb_rays, s->tris, s->tri_rays);
        }
    } else {
        if (fflush(dev.out) != 0 || dev.werr) {
            fprintf(stderr, "lt-stream-dev: %s: write error\n", ar.out != NULL ? ar.out : "stdout");
            rc = rc != 0 ? rc : 1;
        }
        if (ar.out != NULL)
            fclose(dev.out);
        fprintf(stderr, "lt-stream-dev: %s, %u frames: %llu stream frames (%llu bytes) sent, "
                "%u dropped (tile %u, image %u) in %u DROP records, ring max %u/%u, "
                "%u waits for a slot; link done at tick %llu (%.4f s device time)\n",
                name, res.frames, (unsigned long long)res.tx.sent_frames,
                (unsigned long long)res.tx.sent_bytes,
                res.tx.dropped[0] + res.tx.dropped[1] + res.tx.dropped[2], res.tx.dropped[1],
                res.tx.dropped[2], res.tx.drop_records, res.tx.max_depth, (uint32_t)ar.cap, res.tx.full_waits,
                (unsigned long long)res.link_done, (double)res.link_done / (double)port.tick_hz);
    }
    lt_meter_shutdown();
    if (rc != 0)
        fprintf(stderr, "lt-stream-dev: device error %d\n", rc);
    return rc != 0 ? 1 : 0;
}
