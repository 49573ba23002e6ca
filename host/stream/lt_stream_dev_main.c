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

static void usage(FILE *f)
{
    const char *name;
    int i;
    fprintf(f, "usage: lt-stream-dev [--machine NAME] [--frames N] [--image-from N] [--cap N]\n"
               "                     [--link BYTES_PER_S] [--out PATH] [--direct]\n"
               "  --machine NAME   machine model (default mcu-m4):");
    for (i = 0; (name = lt_meter_machine_name(i)) != NULL; i++) {
        lt_meter_machine_t m;
        (void)lt_meter_machine_info(name, &m);
        fprintf(f, "%s %s (%u MHz)", i > 0 ? "," : "", name, m.clock_mhz);
    }
    fprintf(
        f,
        "\n"
        "  --frames N       image frames to trace, 1..%d (default 4)\n"
        "  --image-from N   frames >= N also stream IMAGE tiles (default 2; N >= frames: none)\n"
        "  --cap N          batcher ring capacity in frames, 4..64 (default 16; limits scale)\n"
        "  --link B         link budget in bytes/s (default 64000, full-speed HID)\n"
        "  --out PATH       write the frames to PATH instead of stdout\n"
        "  --direct         trace without streaming; print one summary line per frame\n",
        LT_SDEV_MAX_FRAMES);
}

static int parse_u32(const char *opt, const char *v, uint32_t lo, uint32_t hi, uint32_t *out)
{
    char *end;
    unsigned long x = strtoul(v, &end, 10);
    if (*v == '\0' || *end != '\0' || x < lo || x > hi) {
        fprintf(stderr, "lt-stream-dev: %s %s: expected %u..%u\n", opt, v, lo, hi);
        return -1;
    }
    *out = (uint32_t)x;
    return 0;
}

int main(int argc, char **argv)
{
    static lt_sdev_result_t res;
    const char *machine = "mcu-m4", *out = NULL;
    lt_meter_machine_t m;
    lt_sdev_cfg_t cfg;
    lt_sdev_port_t port;
    simdev_t dev;
    char name[32];
    lt_diag_t diag;
    uint32_t cap = 16, link = LT_STREAM_HID_BYTES_PER_S, f;
    int a, rc;

    lt_sdev_cfg_default(&cfg);
    for (a = 1; a < argc; a++) {
        const char *v = a + 1 < argc ? argv[a + 1] : NULL;
        if (strcmp(argv[a], "--help") == 0 || strcmp(argv[a], "-h") == 0) {
            usage(stdout);
            return 0;
        } else if (strcmp(argv[a], "--direct") == 0) {
            cfg.direct = 1;
        } else if (v == NULL) {
            fprintf(stderr, "lt-stream-dev: %s: unknown option or missing value\n", argv[a]);
            usage(stderr);
            return 2;
        } else if (strcmp(argv[a], "--machine") == 0) {
            machine = v, a++;
        } else if (strcmp(argv[a], "--out") == 0) {
            out = v, a++;
        } else if (strcmp(argv[a], "--frames") == 0) {
            if (parse_u32(argv[a], v, 1, LT_SDEV_MAX_FRAMES, &cfg.frames) != 0)
                return 2;
            a++;
        } else if (strcmp(argv[a], "--image-from") == 0) {
            if (parse_u32(argv[a], v, 0, 1000000, &cfg.image_from) != 0)
                return 2;
            a++;
        } else if (strcmp(argv[a], "--cap") == 0) {
            if (parse_u32(argv[a], v, 4, 64, &cap) != 0)
                return 2;
            a++;
        } else if (strcmp(argv[a], "--link") == 0) {
            if (parse_u32(argv[a], v, 64, 1000000000u, &link) != 0)
                return 2;
            a++;
        } else {
            fprintf(stderr, "lt-stream-dev: %s: unknown option\n", argv[a]);
            usage(stderr);
            return 2;
        }
    }
    if (lt_meter_machine_info(machine, &m) != 0) {
        fprintf(stderr, "lt-stream-dev: --machine %s: unknown machine (known: %s)\n", machine,
                lt_meter_machine_names());
        return 2;
    }
    if (lt_meter_init(machine, NULL, NULL, &diag) != 0) {
        fprintf(stderr, "lt-stream-dev: %s\n", diag.msg);
        return 1;
    }
    /* the default limits (16/12/8) scaled to the ring: TILE 3/4, IMAGE 1/2 of it */
    cfg.link.link_bytes_per_s = link;
    cfg.link.cap = cap;
    cfg.link.limit[0] = cap;
    cfg.link.limit[1] = cap * 3 / 4;
    cfg.link.limit[2] = cap / 2;
    memset(&dev, 0, sizeof dev);
    dev.out = stdout;
    if (!cfg.direct) {
        if (out != NULL) {
            dev.out = fopen(out, "wb");
            if (dev.out == NULL) {
                fprintf(stderr, "lt-stream-dev: %s: cannot write: %s\n", out, strerror(errno));
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
            fprintf(stderr, "lt-stream-dev: %s: write error\n", out != NULL ? out : "stdout");
            rc = rc != 0 ? rc : 1;
        }
        if (out != NULL)
            fclose(dev.out);
        fprintf(stderr, "lt-stream-dev: %s, %u frames: %llu stream frames (%llu bytes) sent, "
                "%u dropped (tile %u, image %u) in %u DROP records, ring max %u/%u, "
                "%u waits for a slot; link done at tick %llu (%.4f s device time)\n",
                name, res.frames, (unsigned long long)res.tx.sent_frames,
                (unsigned long long)res.tx.sent_bytes,
                res.tx.dropped[0] + res.tx.dropped[1] + res.tx.dropped[2], res.tx.dropped[1],
                res.tx.dropped[2], res.tx.drop_records, res.tx.max_depth, cap, res.tx.full_waits,
                (unsigned long long)res.link_done, (double)res.link_done / (double)port.tick_hz);
    }
    lt_meter_shutdown();
    if (rc != 0)
        fprintf(stderr, "lt-stream-dev: device error %d\n", rc);
    return rc != 0 ? 1 : 0;
}
