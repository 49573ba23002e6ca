/* lt_stream_main.c - build/host/lt-stream: receive a device's frame stream (lt_stream.h) from a
 * file, pipe or stdin, a serial device, a TCP socket or a USB HID device, verify CRC and sequence,
 * report lost, damaged, duplicated and reordered frames and the device's own drops, show a live
 * line on stderr when it is a terminal, and print a final summary (text or --json).
 * Exit: 0 clean stream (END received, nothing lost, damaged, duplicated or reordered, no garbage,
 * device status 0), 1 any fault or input error, 2 usage. Host only.
 */
#include "cli/lt_opt.h"
#include "stream/lt_rx.h"
#include "cli/lt_cliutil.h"
#include "stream/usb/lt_rx_hid.h"

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

typedef struct opts {
    const char *file, *serial, *tcp, *hid, *hid_path, *tiles;
    uint32_t baud;
    double timeout_s;
    int json, quiet;
} opts_t;

/* --tiles output: the device's records, one line each, in arrival order (first copies only). */
static void on_frame(void *ctx, const lt_stream_frame_t *f, lt_rx_kind_t kind)
{
    FILE *o = ctx;
    lt_stream_tile_t t;
    lt_stream_summary_t s;
    lt_stream_drop_t d;
    lt_stream_end_t e;
    if (o == NULL || (kind != LT_RX_NEW && kind != LT_RX_REORDERED))
        return;
    if (lt_stream_unpack_tile(f, &t) == LT_OK)
        fprintf(o, "tile %u %u rays %u hits %u hash 0x%08x ticks %u cycles %u aabb %u aabb_rays %u "
                "tris %u tri_rays %u\n", t.frame, t.tile, t.rays, t.hits, t.hash, t.ticks,
                t.cycles, t.aabb, t.aabb_rays, t.tris, t.tri_rays);
    else if (lt_stream_unpack_summary(f, &s) == LT_OK)
        fprintf(o, "summary %u tiles %u rays %u hits %u hash 0x%08x ticks %llu cycles %llu aabb %u "
                "aabb_rays %u tris %u tri_rays %u dropped %u\n", s.frame, s.tiles, s.rays, s.hits,
                s.hash, (unsigned long long)s.ticks, (unsigned long long)s.cycles, s.aabb,
                s.aabb_rays, s.tris, s.tri_rays, s.dropped);
    else if (lt_stream_unpack_drop(f, &d) == LT_OK)
        fprintf(o, "drop %u tile %u image %u total %u t %llu\n", d.dropped, d.tile, d.image,
                d.total, (unsigned long long)d.t);
    else if (lt_stream_unpack_end(f, &e) == LT_OK)
        fprintf(o, "end frames_sent %u dropped %u ticks %llu link_done %llu status %u frames %u\n",
                e.frames_sent, e.dropped, (unsigned long long)e.ticks,
                (unsigned long long)e.link_done, e.status, e.frames);
}

static void live_line(const lt_rx_stats_t *s, double dt)
{
    if (dt <= 0.0)
        dt = 1e-9;
    fprintf(stderr,
            "\r%llu frames %.0f fr/s %.1f kB/s | %.3g rays/s %.3g cycles/s | lost %llu (corrupt "
            "%llu) dup %llu reord %llu garbage %llu B | dev dropped %llu\033[K",
            (unsigned long long)s->valid, (double)s->valid / dt, (double)s->bytes / dt / 1e3,
            (double)s->rays / dt, (double)(s->tile_cycles ? s->tile_cycles : s->tile_ticks) / dt,
            (unsigned long long)s->lost, (unsigned long long)s->damaged,
            (unsigned long long)s->duplicates, (unsigned long long)s->reordered,
            (unsigned long long)s->garbage_bytes, (unsigned long long)s->dev_dropped);
    fflush(stderr);
}

/* 1 when the stream had no link fault and the device reported success. */
/* --sessions: how many device sessions (HELLO .. END) one run accepts; a HELLO after END beyond
 * that is a restarted or replayed device, a fault */
static int g_max_sessions = 1;

/* Bytes after the last CRC-valid frame with no valid frame among them at which the receiver stops:
 * a source that sends only noise (the wrong port, a wrong baud rate, /dev/zero) would otherwise
 * keep it busy forever, since noise is not silence and --timeout never fires. */
#define LT_RX_MAX_NOISE (64ull << 20)

/* SIGINT / SIGTERM: stop reading and print the summary of what arrived (a second signal kills). */
static volatile sig_atomic_t g_stop;
static void on_stop(int sig)
{
    g_stop = 1;
    (void)signal(sig, SIG_DFL);
}

static int clean(const lt_rx_stats_t *s)
{
    return s->have_end && s->lost == 0 && s->duplicates == 0 && s->reordered == 0 &&
           s->stale == 0 && s->garbage_bytes == 0 && s->bad_payload == 0 && s->bad_record == 0 &&
           s->end.status == 0 &&
           s->sessions <= (uint32_t)g_max_sessions;
}

static void name16(const lt_stream_hello_t *h, char out[17])
{
    memcpy(out, h->name, 16);
    out[16] = '\0';
}

static const char *source_name(uint32_t s)
{
    return s == LT_STREAM_SRC_FIRMWARE ? "firmware" : s == LT_STREAM_SRC_SIM ? "sim"
         : s == LT_STREAM_SRC_HOST ? "host" : "unknown";
}

static void print_text(const char *src, const lt_rx_stats_t *s, double dt)
{
    const lt_stream_hello_t *h = &s->hello;
    char nm[17];
    double hz = s->have_hello && h->tick_hz ? (double)h->tick_hz : 0.0;
    if (dt <= 0.0)
        dt = 1e-9;
    printf("input     %s: %llu bytes in %.3f s: %.1f frames/s, %.0f B/s (host wall clock)\n", src,
           (unsigned long long)s->bytes, dt, (double)s->valid / dt, (double)s->bytes / dt);
    if (s->have_hello) {
        name16(h, nm);
        printf("device    %s (%s), session 0x%08x, %ux%u pixels in %ux%u tiles, %u triangles "
               "(scene 0x%08x), %u frames, clock %u ticks/s, link %u B/s = 1 report per %u "
               "ticks\n", nm, source_name(h->source), h->session, h->width, h->height, h->tile_w,
               h->tile_h, h->ntris, h->scene_hash, h->frames, h->tick_hz, h->link_bytes_per_s,
               h->ticks_per_report);
    } else {
        printf("device    no HELLO record received\n");
    }
    printf("frames    sent %llu received %llu lost %llu (corrupt or truncated: %llu) duplicates "
           "%llu reordered %llu stale %llu%s\n", (unsigned long long)s->sent, (unsigned long long)s->received,
           (unsigned long long)s->lost, (unsigned long long)s->damaged,
           (unsigned long long)s->duplicates, (unsigned long long)s->reordered,
           (unsigned long long)s->stale,
           s->have_end ? "" : " (no END record: frames after the last one received are unknown)");
    printf("bytes     garbage %llu in %llu runs (bad headers %llu, bad CRC %llu, cut-off tail "
           "%llu), bad payloads %llu\n", (unsigned long long)s->garbage_bytes,
           (unsigned long long)s->garbage_runs, (unsigned long long)s->bad_header,
           (unsigned long long)s->bad_crc, (unsigned long long)s->tail_bytes,
           (unsigned long long)s->bad_payload);
    if (s->bad_record != 0)
        printf("records   %llu inconsistent with the HELLO or themselves; first: %s\n",
               (unsigned long long)s->bad_record, s->bad_first);
    printf("types     HELLO %llu TILE %llu SUMMARY %llu DROP %llu IMAGE %llu END %llu\n",
           (unsigned long long)s->by_type[1], (unsigned long long)s->by_type[2],
           (unsigned long long)s->by_type[3], (unsigned long long)s->by_type[4],
           (unsigned long long)s->by_type[5], (unsigned long long)s->by_type[6]);
    printf("reports   %llu of %llu tile reports received; the device dropped %llu reports (%llu "
           "tile, %llu image) in %llu DROP records\n", (unsigned long long)s->tiles,
           (unsigned long long)s->sum_tiles, (unsigned long long)s->dev_dropped,
           (unsigned long long)s->dev_dropped_tile, (unsigned long long)s->dev_dropped_image,
           (unsigned long long)s->drop_records);
    printf("work      rays %llu hits %llu (summaries: rays %llu hits %llu) ticks %llu cycles %llu",
           (unsigned long long)s->rays, (unsigned long long)s->hits,
           (unsigned long long)s->sum_rays, (unsigned long long)s->sum_hits,
           (unsigned long long)s->sum_ticks, (unsigned long long)s->sum_cycles);
    if (hz > 0.0 && s->sum_ticks > 0)
        printf(": %.3f Mrays/s at the device clock",
               (double)s->sum_rays / ((double)s->sum_ticks / hz) / 1e6);
    printf("\n");
    if (s->have_end && hz > 0.0 && s->end.link_done > 0) {
        /* the last frame occupies the slot that starts at link_done */
        double lt = (double)(s->end.link_done + h->ticks_per_report) / hz;
        printf("link      device time %.4f s until the last frame was through: %.1f frames/s, "
               "%.0f B/s (budget %u B/s)\n", lt, (double)s->end.frames_sent / lt,
               (double)s->end.frames_sent * LT_STREAM_FRAME_BYTES / lt, h->link_bytes_per_s);
    }
    if (s->have_end)
        printf("end       device status %u, %u frames traced, %u frames sent, %u reports dropped\n",
               s->end.status, s->end.frames, s->end.frames_sent, s->end.dropped);
    if (s->sessions > (uint32_t)g_max_sessions)
        printf("sessions  %u, more than the %d expected: a HELLO after END (a restarted or replayed "
               "device; --sessions N accepts N)\n", s->sessions, g_max_sessions);
    printf("result    %s\n", clean(s) ? "ok: every frame the device sent arrived once, intact, in "
                                         "order" : "FAULTS (see above)");
}

/* A JSON string body: quotes, backslashes and control bytes escaped. */
static void json_str(const char *p)
{
    for (; *p != '\0'; p++) {
        unsigned char c = (unsigned char)*p;
        if (c == '"' || c == '\\')
            printf("\\%c", c);
        else if (c < 0x20)
            printf("\\u%04x", c);
        else
            putchar(c);
    }
}

static void print_json(const char *src, const lt_rx_stats_t *s, double dt)
{
    char nm[17];
    const lt_stream_hello_t *h = &s->hello;
    name16(h, nm);
    /* names are printed only when they are plain printable ASCII */
    {
        int i;
        for (i = 0; nm[i] != '\0'; i++)
            if (nm[i] < 0x20 || nm[i] > 0x7E || nm[i] == '"' || nm[i] == '\\')
                nm[i] = '?';
    }
    printf("{\n");
    printf("  \"input\": \"");
    json_str(src);
    printf("\",\n");
    printf("  \"clean\": %d,\n", clean(s));
    printf("  \"wall_s\": %.6f,\n", dt);
    printf("  \"bytes\": %llu,\n", (unsigned long long)s->bytes);
    printf("  \"frames_per_s\": %.3f,\n", dt > 0 ? (double)s->valid / dt : 0.0);
    printf("  \"bytes_per_s\": %.3f,\n", dt > 0 ? (double)s->bytes / dt : 0.0);
    printf("  \"valid\": %llu,\n", (unsigned long long)s->valid);
    printf("  \"sent\": %llu,\n", (unsigned long long)s->sent);
    printf("  \"received\": %llu,\n", (unsigned long long)s->received);
    printf("  \"lost\": %llu,\n", (unsigned long long)s->lost);
    printf("  \"damaged\": %llu,\n", (unsigned long long)s->damaged);
    printf("  \"duplicates\": %llu,\n", (unsigned long long)s->duplicates);
    printf("  \"reordered\": %llu,\n", (unsigned long long)s->reordered);
    printf("  \"stale\": %llu,\n", (unsigned long long)s->stale);
    printf("  \"garbage_bytes\": %llu,\n", (unsigned long long)s->garbage_bytes);
    printf("  \"garbage_runs\": %llu,\n", (unsigned long long)s->garbage_runs);
    printf("  \"bad_header\": %llu,\n", (unsigned long long)s->bad_header);
    printf("  \"bad_crc\": %llu,\n", (unsigned long long)s->bad_crc);
    printf("  \"tail_bytes\": %llu,\n", (unsigned long long)s->tail_bytes);
    printf("  \"bad_payload\": %llu,\n", (unsigned long long)s->bad_payload);
    printf("  \"bad_records\": %llu,\n", (unsigned long long)s->bad_record);
    printf("  \"sessions\": %u,\n", s->sessions);
    printf("  \"have_hello\": %d,\n", s->have_hello);
    printf("  \"have_end\": %d,\n", s->have_end);
    printf("  \"device\": \"%s\",\n", s->have_hello ? nm : "");
    printf("  \"source\": \"%s\",\n", s->have_hello ? source_name(h->source) : "");
    printf("  \"tick_hz\": %u,\n", h->tick_hz);
    printf("  \"link_bytes_per_s\": %u,\n", h->link_bytes_per_s);
    printf("  \"ticks_per_report\": %u,\n", h->ticks_per_report);
    printf("  \"scene_hash\": %u,\n", h->scene_hash);
    printf("  \"n_hello\": %llu,\n", (unsigned long long)s->by_type[1]);
    printf("  \"n_tile\": %llu,\n", (unsigned long long)s->by_type[2]);
    printf("  \"n_summary\": %llu,\n", (unsigned long long)s->by_type[3]);
    printf("  \"n_drop\": %llu,\n", (unsigned long long)s->by_type[4]);
    printf("  \"n_image\": %llu,\n", (unsigned long long)s->by_type[5]);
    printf("  \"n_end\": %llu,\n", (unsigned long long)s->by_type[6]);
    printf("  \"tiles\": %llu,\n", (unsigned long long)s->tiles);
    printf("  \"tiles_traced\": %llu,\n", (unsigned long long)s->sum_tiles);
    printf("  \"dev_dropped\": %llu,\n", (unsigned long long)s->dev_dropped);
    printf("  \"dev_dropped_tile\": %llu,\n", (unsigned long long)s->dev_dropped_tile);
    printf("  \"dev_dropped_image\": %llu,\n", (unsigned long long)s->dev_dropped_image);
    printf("  \"rays\": %llu,\n", (unsigned long long)s->rays);
    printf("  \"hits\": %llu,\n", (unsigned long long)s->hits);
    printf("  \"sum_rays\": %llu,\n", (unsigned long long)s->sum_rays);
    printf("  \"sum_hits\": %llu,\n", (unsigned long long)s->sum_hits);
    printf("  \"sum_ticks\": %llu,\n", (unsigned long long)s->sum_ticks);
    printf("  \"sum_cycles\": %llu,\n", (unsigned long long)s->sum_cycles);
    printf("  \"end_status\": %u,\n", s->end.status);
    printf("  \"end_frames_sent\": %u,\n", s->end.frames_sent);
    printf("  \"end_dropped\": %u,\n", s->end.dropped);
    printf("  \"end_ticks\": %llu,\n", (unsigned long long)s->end.ticks);
    printf("  \"end_link_done\": %llu\n", (unsigned long long)s->end.link_done);
    printf("}\n");
}

/* The options into o and how many sources were named. LT_OPT_OK, LT_OPT_HELP or LT_OPT_USAGE. */
static int parse_args(opts_t *o, int argc, char **argv, int *nsrc)
{
    int seen[5] = {0, 0, 0, 0, 0}, i, rc;
    int baud = 0;
    const lt_opt_t opts[] = {
        LT_OPT_SECTION_("sources (at most one; default --file -):"),
        {.name = "--file", .kind = LT_OPT_STRING, .dest = &o->file, .seen = &seen[0],
         .meta = "F", .help = "read a recorded stream (- = stdin, e.g. a pipe from QEMU)"},
        {.name = "--serial", .kind = LT_OPT_STRING, .dest = &o->serial, .seen = &seen[1],
         .meta = "DEV", .help = "a tty in raw 8N1 mode (e.g. /dev/ttyACM0); --baud sets its speed"},
        {.name = "--tcp", .kind = LT_OPT_STRING, .dest = &o->tcp, .seen = &seen[2],
         .meta = "HOST:PORT", .help = "connect (retrying 5 s while refused), e.g. QEMU -serial tcp:..."},
        {.name = "--hid", .kind = LT_OPT_STRING, .dest = &o->hid, .seen = &seen[3],
         .meta = "VID:PID", .help = "a USB HID device by hex ids (hidapi), e.g. 1209:0001"},
        {.name = "--hid-path", .kind = LT_OPT_STRING, .dest = &o->hid_path, .seen = &seen[4],
         .meta = "P", .help = "a USB HID device by hidapi path (hidraw: /dev/hidrawN)"},
        LT_OPT_SECTION_("options:"),
        LT_OPT_INT("--baud", "N", &baud, 1, 4000000, "serial speed in baud, {range} (--serial only)"),
        {.name = "--timeout", .kind = LT_OPT_DOUBLE, .dest = &o->timeout_s, .meta = "S",
         .help = "stop after S seconds without a byte, {range} (default: none; serial and\n"
                 "HID stop at the END record)",
         .lo = 0.0, .hi = 86400.0, .flags = LT_OPT_LO_OPEN},
        LT_OPT_INT("--sessions", "N", &g_max_sessions, 1, 1000000,
                   "device sessions (HELLO .. END) accepted, {range} (default 1: a HELLO\n"
                   "after END - a restarted or replayed device - is a fault)"),
        LT_OPT_STR("--tiles", "PATH", &o->tiles,
                   "write one line per TILE, SUMMARY, DROP and END record received"),
        LT_OPT_FLAG_("--json", &o->json, "print the summary as JSON on stdout"),
        LT_OPT_FLAG_("-q", &o->quiet, "no live line on stderr"),
        LT_OPT_END_};
    const lt_opt_cmd_t cmd = {"lt-stream", "[SOURCE] [options]",
                              "Receive the device's 64-byte report frames and check the stream "
                              "(lost, damaged,\nduplicated, reordered frames, the device's own "
                              "status).\n",
                              "exit status: 0 clean stream, 1 faults found or input error, 2 usage\n",
                              opts, NULL, 0, NULL};
    rc = lt_opt_parse(&cmd, argc, argv, 1);
    if (rc != LT_OPT_OK)
        return rc;
    for (i = 0, *nsrc = 0; i < 5; i++)
        *nsrc += seen[i] != 0;
    o->baud = (uint32_t)baud;
    return LT_OPT_OK;
}

int main(int argc, char **argv)
{
    opts_t o;
    lt_rx_src_t *src = NULL;
    lt_rx_t *rx;
    FILE *tiles = NULL;
    lt_diag_t diag;
    uint8_t buf[4096];
    double t0, last_live = 0.0, last_byte;
    int nsrc = 0, status = 0, tty, rc;
    const lt_rx_stats_t *s;
    uint64_t valid_seen = 0, bytes_at_valid = 0;

    memset(&o, 0, sizeof o);
    if ((rc = parse_args(&o, argc, argv, &nsrc)) != LT_OPT_OK)
        return lt_opt_exit_code(rc);
    if (nsrc > 1) {
        fprintf(stderr, "lt-stream: give at most one of --file, --serial, --tcp, --hid, "
                        "--hid-path\n");
        return 2;
    }
    if (o.baud != 0 && o.serial == NULL) {
        fprintf(stderr, "lt-stream: --baud applies to --serial only\n");
        return 2;
    }
    if (o.serial != NULL)
        src = lt_rx_src_serial(o.serial, o.baud, &diag);
    else if (o.tcp != NULL)
        src = lt_rx_src_tcp(o.tcp, 5000, &diag);
    else if (o.hid != NULL || o.hid_path != NULL)
        src = lt_rx_src_hid(o.hid, o.hid_path, &diag);
    else
        src = lt_rx_src_file(o.file != NULL ? o.file : "-", &diag);
    if (src == NULL) {
        fprintf(stderr, "lt-stream: %s\n", diag.msg);
        return 1;
    }
    if (o.tiles != NULL) {
        tiles = fopen(o.tiles, "w");
        if (tiles == NULL) {
            fprintf(stderr, "lt-stream: %s: cannot write: %s\n", o.tiles, strerror(errno));
            lt_rx_src_close(src);
            return 1;
        }
    }
    rx = lt_rx_new(on_frame, tiles);
    if (rx == NULL) {
        fprintf(stderr, "lt-stream: out of memory\n");
        return 1;
    }
    tty = !o.quiet && isatty(2);
    t0 = last_byte = lt_now_s();
    (void)signal(SIGINT, on_stop);
    (void)signal(SIGTERM, on_stop);
    for (;;) {
        long n = g_stop ? 0 : lt_rx_src_read(src, buf, sizeof buf, tty ? 250 : 1000, &diag);
        double t = lt_now_s();
        if (n > 0) {
            const lt_rx_stats_t *st;
            lt_rx_feed(rx, buf, (size_t)n);
            last_byte = t;
            st = lt_rx_stats(rx);
            if (st->valid != valid_seen) {
                valid_seen = st->valid;
                bytes_at_valid = st->bytes;
            } else if (st->bytes - bytes_at_valid > LT_RX_MAX_NOISE) {
                fprintf(stderr, "%slt-stream: %s: no valid frame in the last %llu bytes "
                        "(LT_RX_MAX_NOISE, 64 MiB): not a lanetrace stream, stopping\n",
                        tty ? "\n" : "", lt_rx_src_name(src),
                        (unsigned long long)(st->bytes - bytes_at_valid));
                status = 1;
                break;
            }
        }
        if (g_stop) { /* after feeding what the read brought */
            fprintf(stderr, "%slt-stream: %s: interrupted, stopping\n", tty ? "\n" : "",
                    lt_rx_src_name(src));
            status = 1;
            break;
        }
        if (n == LT_RX_EOF) {
            break;
        } else if (n == LT_RX_ERROR) {
            fprintf(stderr, "%slt-stream: %s\n", tty ? "\n" : "", diag.msg);
            status = 1;
            break;
        }
        if (tty && t - last_live >= 0.25) {
            live_line(lt_rx_stats(rx), t - t0);
            last_live = t;
        }
        if (lt_rx_src_live(src) && lt_rx_done(rx))
            break;
        if (o.timeout_s > 0.0 && t - last_byte >= o.timeout_s) {
            fprintf(stderr, "%slt-stream: %s: no data for %.3g s (--timeout), stopping\n",
                    tty ? "\n" : "", lt_rx_src_name(src), o.timeout_s);
            break;
        }
    }
    lt_rx_finish(rx);
    s = lt_rx_stats(rx);
    if (s->bad_record != 0)
        fprintf(stderr, "%slt-stream: %s: %s%s\n", tty ? "\n" : "", lt_rx_src_name(src),
                s->bad_first, s->bad_record > 1 ? " (and more: see the records line)" : "");
    if (s->bad_payload != 0)
        fprintf(stderr, "%slt-stream: %s: %s%s\n", tty ? "\n" : "", lt_rx_src_name(src),
                s->bad_payload_first, s->bad_payload > 1 ? " (and more: see bad payloads)" : "");
    if (s->tail_bytes != 0) {
        char after[48] = "before any valid frame";
        if (s->valid != 0)
            (void)snprintf(after, sizeof after, "after frame seq %u", (unsigned)s->last_seq);
        fprintf(stderr, "%slt-stream: %s: the input ends %llu bytes into a %u-byte frame, %s\n",
                tty ? "\n" : "", lt_rx_src_name(src), (unsigned long long)s->tail_bytes,
                LT_STREAM_FRAME_BYTES, after);
    }
    if (tty) {
        live_line(s, lt_now_s() - t0);
        fputc('\n', stderr);
    }
    if (o.json)
        print_json(lt_rx_src_name(src), s, lt_now_s() - t0);
    else
        print_text(lt_rx_src_name(src), s, lt_now_s() - t0);
    if (!clean(s))
        status = 1;
    if (tiles != NULL && fclose(tiles) != 0) {
        fprintf(stderr, "lt-stream: %s: write error\n", o.tiles);
        status = 1;
    }
    lt_rx_free(rx);
    lt_rx_src_close(src);
    return status;
}
