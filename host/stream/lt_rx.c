/* lt_rx.c - byte sources (file/pipe/stdin, serial tty in raw mode, TCP client, custom) and the
 * stream receiver of lt_rx.h: the core decoder (lt_stream_dec_push) finds frames, a 4096-frame
 * window over 16-bit sequence numbers extended to 64 bits classifies each copy (new, reordered,
 * duplicate), and garbage between frames is charged to the sequence gap it fills.
 * Host only (POSIX.1-2008: poll, termios, getaddrinfo).
 */
#include "stream/lt_rx.h"

#include <errno.h>
#include <stdarg.h>
#include <fcntl.h>
#include <netdb.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/types.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

/* ---- byte sources ---------------------------------------------------------------------------- */

struct lt_rx_src {
    lt_rx_src_ops_t ops;
    void *ctx;
    int live;
    char name[256];
};

lt_rx_src_t *lt_rx_src_custom(const lt_rx_src_ops_t *ops, void *ctx, const char *name, int live)
{
    lt_rx_src_t *s = calloc(1, sizeof *s);
    if (s == NULL)
        return NULL;
    s->ops = *ops;
    s->ctx = ctx;
    s->live = live;
    snprintf(s->name, sizeof s->name, "%s", name != NULL ? name : "?");
    return s;
}

long lt_rx_src_read(lt_rx_src_t *s, uint8_t *buf, size_t n, int timeout_ms, lt_diag_t *diag)
{
    return s->ops.read(s->ctx, buf, n, timeout_ms, diag);
}

const char *lt_rx_src_name(const lt_rx_src_t *s) { return s->name; }
int lt_rx_src_live(const lt_rx_src_t *s) { return s->live; }

void lt_rx_src_close(lt_rx_src_t *s)
{
    if (s == NULL)
        return;
    if (s->ops.close != NULL)
        s->ops.close(s->ctx);
    free(s);
}

/* File descriptors: files, pipes, ttys and sockets read the same way. */
typedef struct fd_src {
    int fd;
    int own;            /* close on lt_rx_src_close */
    char name[240];
} fd_src_t;

static long fd_read(void *ctx, uint8_t *buf, size_t n, int timeout_ms, lt_diag_t *diag)
{
    fd_src_t *f = ctx;
    for (;;) {
        struct pollfd p;
        ssize_t r;
        int pr;
        p.fd = f->fd;
        p.events = POLLIN;
        p.revents = 0;
        pr = poll(&p, 1, timeout_ms);
        if (pr < 0 && errno == EINTR)
            continue;
        if (pr < 0) {
            lt_diag_fail(diag, "%s: poll: %s", f->name, strerror(errno));
            return LT_RX_ERROR;
        }
        if (pr == 0)
            return LT_RX_TIMEOUT;
        r = read(f->fd, buf, n);
        if (r < 0 && (errno == EINTR || errno == EAGAIN))
            continue;
        if (r < 0) {
            lt_diag_fail(diag, "%s: read: %s", f->name, strerror(errno));
            return LT_RX_ERROR;
        }
        return (long)r;
    }
}

static void fd_close(void *ctx)
{
    fd_src_t *f = ctx;
    if (f->own)
        close(f->fd);
    free(f);
}

static const lt_rx_src_ops_t fd_ops = {fd_read, fd_close};

static lt_rx_src_t *fd_wrap(int fd, int own, const char *name, int live, lt_diag_t *diag)
{
    fd_src_t *f = calloc(1, sizeof *f);
    lt_rx_src_t *s;
    if (f == NULL) {
        lt_diag_fail(diag, "%s: out of memory", name);
        if (own)
            close(fd);
        return NULL;
    }
    f->fd = fd;
    f->own = own;
    snprintf(f->name, sizeof f->name, "%s", name);
    s = lt_rx_src_custom(&fd_ops, f, name, live);
    if (s == NULL) {
        fd_close(f);
        lt_diag_fail(diag, "%s: out of memory", name);
    }
    return s;
}

lt_rx_src_t *lt_rx_src_file(const char *path, lt_diag_t *diag)
{
    int fd;
    if (strcmp(path, "-") == 0)
        return fd_wrap(0, 0, "stdin", 0, diag);
    fd = open(path, O_RDONLY);
    if (fd < 0) {
        lt_diag_fail(diag, "%s: cannot open: %s", path, strerror(errno));
        return NULL;
    }
    return fd_wrap(fd, 1, path, 0, diag);
}

/* termios speed constant for a baud rate; B0 when unsupported. */
static speed_t baud_const(uint32_t baud)
{
    switch (baud) {
    case 9600: return B9600;
    case 19200: return B19200;
    case 38400: return B38400;
    case 57600: return B57600;
    case 115200: return B115200;
    case 230400: return B230400;
#ifdef B460800
    case 460800: return B460800;
#endif
#ifdef B921600
    case 921600: return B921600;
#endif
#ifdef B1000000
    case 1000000: return B1000000;
#endif
#ifdef B2000000
    case 2000000: return B2000000;
#endif
#ifdef B3000000
    case 3000000: return B3000000;
#endif
#ifdef B4000000
    case 4000000: return B4000000;
#endif
    default: return B0;
    }
}

lt_rx_src_t *lt_rx_src_serial(const char *dev, uint32_t baud, lt_diag_t *diag)
{
    struct termios t;
    int fd;
    speed_t sp = B0;
    if (baud != 0) {
        sp = baud_const(baud);
        if (sp == B0) {
            lt_diag_fail(diag, "%s: unsupported speed %u (9600..230400, or 460800..4000000 "
                         "where termios has them)", dev, baud);
            return NULL;
        }
    }
    fd = open(dev, O_RDONLY | O_NOCTTY | O_NONBLOCK);
    if (fd < 0) {
        lt_diag_fail(diag, "%s: cannot open: %s", dev, strerror(errno));
        return NULL;
    }
    if (tcgetattr(fd, &t) != 0) {
        lt_diag_fail(diag, "%s: not a serial device (tcgetattr: %s)", dev, strerror(errno));
        close(fd);
        return NULL;
    }
    /* raw 8N1: no line editing, no CR/LF or flow-control translation, no parity stripping
     * (cfmakeraw's settings, spelled out because cfmakeraw is not POSIX) */
    t.c_iflag &= (tcflag_t)~(IGNBRK | BRKINT | PARMRK | ISTRIP | INLCR | IGNCR | ICRNL | IXON |
                             IXOFF | IXANY | INPCK);
    t.c_oflag &= (tcflag_t)~OPOST;
    t.c_lflag &= (tcflag_t)~(ECHO | ECHONL | ICANON | ISIG | IEXTEN);
    t.c_cflag &= (tcflag_t)~(CSIZE | PARENB | CSTOPB);
    t.c_cflag |= CS8 | CREAD | CLOCAL;
    t.c_cc[VMIN] = 1;
    t.c_cc[VTIME] = 0;
    if (sp != B0 && (cfsetispeed(&t, sp) != 0 || cfsetospeed(&t, sp) != 0)) {
        lt_diag_fail(diag, "%s: cannot set speed %u: %s", dev, baud, strerror(errno));
        close(fd);
        return NULL;
    }
    if (tcsetattr(fd, TCSANOW, &t) != 0) {
        lt_diag_fail(diag, "%s: cannot set raw mode: %s", dev, strerror(errno));
        close(fd);
        return NULL;
    }
    return fd_wrap(fd, 1, dev, 1, diag);
}

static void sleep_ms(int ms)
{
    struct timespec ts;
    ts.tv_sec = ms / 1000;
    ts.tv_nsec = (long)(ms % 1000) * 1000000L;
    while (nanosleep(&ts, &ts) != 0 && errno == EINTR) {
    }
}

lt_rx_src_t *lt_rx_src_tcp(const char *hostport, int connect_ms, lt_diag_t *diag)
{
    char host[256];
    const char *colon = strrchr(hostport, ':');
    struct addrinfo hints, *res = NULL, *a;
    int fd = -1, rc, waited = 0, last_errno = 0;
    size_t hl;
    if (colon == NULL || colon == hostport || colon[1] == '\0') {
        lt_diag_fail(diag, "--tcp %s: expected HOST:PORT", hostport);
        return NULL;
    }
    hl = (size_t)(colon - hostport);
    if (hl >= sizeof host) {
        lt_diag_fail(diag, "--tcp %s: host name longer than %zu bytes", hostport,
                     sizeof host - 1);
        return NULL;
    }
    memcpy(host, hostport, hl);
    host[hl] = '\0';
    {
        /* a numeric port must be a TCP port: getaddrinfo takes 70000 as 70000 mod 65536 */
        const char *d = colon + 1;
        unsigned long port = 0;
        while (*d >= '0' && *d <= '9' && port <= 65535ul)
            port = port * 10ul + (unsigned long)(*d++ - '0');
        if (colon[1] >= '0' && colon[1] <= '9' && (*d != '\0' || port < 1 || port > 65535ul)) {
            lt_diag_fail(diag, "--tcp %s: port '%s' is not a TCP port (1..65535)", hostport,
                         colon + 1);
            return NULL;
        }
    }
    memset(&hints, 0, sizeof hints);
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    rc = getaddrinfo(host, colon + 1, &hints, &res);
    if (rc != 0) {
        lt_diag_fail(diag, "%s: cannot resolve: %s", hostport, gai_strerror(rc));
        return NULL;
    }
    for (;;) {
        for (a = res; a != NULL; a = a->ai_next) {
            fd = socket(a->ai_family, a->ai_socktype, a->ai_protocol);
            if (fd < 0) {
                last_errno = errno;
                continue;
            }
            if (connect(fd, a->ai_addr, a->ai_addrlen) == 0)
                break;
            last_errno = errno;
            close(fd);
            fd = -1;
        }
        if (fd >= 0 || waited >= connect_ms || last_errno != ECONNREFUSED)
            break;
        sleep_ms(50);
        waited += 50;
    }
    freeaddrinfo(res);
    if (fd < 0) {
        lt_diag_fail(diag, "%s: cannot connect: %s%s", hostport, strerror(last_errno),
                     waited > 0 ? " (retried for the connect timeout)" : "");
        return NULL;
    }
    return fd_wrap(fd, 1, hostport, 0, diag);
}

/* ---- receiver -------------------------------------------------------------------------------- */

#define WIN 4096u /* sequence numbers remembered behind the highest one */

struct lt_rx {
    lt_stream_dec_t dec;
    lt_rx_stats_t st;
    lt_rx_frame_fn cb;
    void *cb_ctx;
    /* current session */
    int active;             /* a frame of this session was seen */
    int64_t hi;             /* highest extended sequence number */
    uint64_t uniq;          /* distinct sequence numbers received */
    uint8_t seen[WIN / 8];  /* bit (ext % WIN) for ext in (hi - WIN, hi] */
    int sess_hello;         /* session id known */
    uint32_t sess_id;
    int sess_end;           /* END received */
    uint32_t end_sent;      /* its frames_sent */
    /* totals of finished sessions */
    uint64_t done_sent, done_recv;
    /* garbage and candidates since the last NEW frame (gap attribution) */
    uint64_t g_mark, c_mark;
    uint64_t damaged;       /* gap estimates summed; reported as at most lost (a frame of a gap
                               may still arrive late) */
    int finished;
    /* record checks (check_record): the session's HELLO taken, and the (frame, tile) pairs of
     * its TILE reports, an open-addressing set of frame << 16 | tile, stored + 1 (0 = empty) */
    int hello_taken;
    uint64_t *ft;
    size_t ft_cap, ft_n;
};

lt_rx_t *lt_rx_new(lt_rx_frame_fn cb, void *ctx)
{
    lt_rx_t *rx = calloc(1, sizeof *rx);
    if (rx == NULL)
        return NULL;
    lt_stream_dec_init(&rx->dec);
    rx->cb = cb;
    rx->cb_ctx = ctx;
    rx->hi = -1;
    return rx;
}

void lt_rx_free(lt_rx_t *rx)
{
    if (rx != NULL)
        free(rx->ft);
    free(rx);
}

const lt_rx_stats_t *lt_rx_stats(const lt_rx_t *rx) { return &rx->st; }

int lt_rx_done(const lt_rx_t *rx) { return rx->sess_end; }

const char *lt_rx_type_name(uint32_t type)
{
    static const char *const n[] = {"?", "HELLO", "TILE", "SUMMARY", "DROP", "IMAGE", "END"};
    return type <= LT_STREAM_TYPE_MAX ? n[type] : "?";
}

static int bit_get(const lt_rx_t *rx, uint64_t e)
{
    return (rx->seen[(e % WIN) / 8] >> (e % 8)) & 1;
}

static void bit_set(lt_rx_t *rx, uint64_t e, int v)
{
    uint8_t m = (uint8_t)(1u << (e % 8));
    if (v)
        rx->seen[(e % WIN) / 8] |= m;
    else
        rx->seen[(e % WIN) / 8] &= (uint8_t)~m;
}

/* Session totals into the stats: sent from END when known, else from the highest sequence. */
static void sess_totals(const lt_rx_t *rx, uint64_t *sent, uint64_t *recv)
{
    uint64_t s = 0;
    if (rx->active) {
        s = (uint64_t)(rx->hi + 1);
        if (rx->sess_end)
            s = rx->end_sent >= rx->uniq ? rx->end_sent : rx->uniq;
    }
    *sent = s;
    *recv = rx->uniq;
}

static void update_link(lt_rx_t *rx)
{
    uint64_t s, r;
    sess_totals(rx, &s, &r);
    rx->st.sent = rx->done_sent + s;
    rx->st.received = rx->done_recv + r;
    rx->st.lost = rx->st.sent - rx->st.received;
    rx->st.damaged = rx->damaged < rx->st.lost ? rx->damaged : rx->st.lost;
    rx->st.garbage_bytes = rx->dec.garbage_bytes;
    rx->st.garbage_runs = rx->dec.garbage_runs;
    rx->st.bad_header = rx->dec.bad_header;
    rx->st.bad_crc = rx->dec.bad_crc;
}

static void sess_close(lt_rx_t *rx)
{
    uint64_t s, r;
    sess_totals(rx, &s, &r);
    rx->done_sent += s;
    rx->done_recv += r;
    rx->active = 0;
    rx->hi = -1;
    rx->uniq = 0;
    memset(rx->seen, 0, sizeof rx->seen);
    rx->sess_hello = 0;
    rx->sess_end = 0;
    rx->end_sent = 0;
    rx->hello_taken = 0;
    rx->ft_n = 0;
    if (rx->ft != NULL)
        memset(rx->ft, 0, rx->ft_cap * sizeof *rx->ft);
}

/* Add key to the session's (frame, tile) set: 1 new, 0 already there, -1 out of memory (the
 * duplicate check is then skipped, never a crash). */
static int ft_add(lt_rx_t *rx, uint64_t key)
{
    size_t i, mask;
    if (2 * (rx->ft_n + 1) > rx->ft_cap) {
        size_t cap = rx->ft_cap ? 2 * rx->ft_cap : 1024, j;
        uint64_t *t = calloc(cap, sizeof *t);
        if (t == NULL)
            return -1;
        for (j = 0; j < rx->ft_cap; j++)
            if (rx->ft[j] != 0) {
                for (i = (size_t)(rx->ft[j] * 0x9E3779B97F4A7C15ull >> 17) & (cap - 1); t[i] != 0;
                     i = (i + 1) & (cap - 1))
                    ;
                t[i] = rx->ft[j];
            }
        free(rx->ft);
        rx->ft = t;
        rx->ft_cap = cap;
    }
    key += 1;
    mask = rx->ft_cap - 1;
    for (i = (size_t)(key * 0x9E3779B97F4A7C15ull >> 17) & mask; rx->ft[i] != 0; i = (i + 1) & mask)
        if (rx->ft[i] == key)
            return 0;
    rx->ft[i] = key;
    rx->ft_n++;
    return 1;
}

/* A record the session's HELLO or its own fields make impossible: counted, the first one kept. */
static void bad_record(lt_rx_t *rx, const lt_stream_frame_t *f, const char *fmt, ...)
    LT_DIAG_PRINTF(3, 4);
static void bad_record(lt_rx_t *rx, const lt_stream_frame_t *f, const char *fmt, ...)
{
    lt_rx_stats_t *st = &rx->st;
    if (st->bad_record++ == 0) {
        va_list ap;
        int n = snprintf(st->bad_first, sizeof st->bad_first, "frame seq %u (%s): ",
                         (unsigned)f->seq, lt_rx_type_name(f->type));
        if (n > 0 && (size_t)n < sizeof st->bad_first) {
            va_start(ap, fmt);
            (void)vsnprintf(st->bad_first + n, sizeof st->bad_first - (size_t)n, fmt, ap);
            va_end(ap);
        }
    }
}

/* Tiles of the session's image (0 without a usable HELLO). */
static uint64_t hello_tiles(const lt_rx_t *rx)
{
    const lt_stream_hello_t *h = &rx->st.hello;
    if (!rx->hello_taken || h->tile_w == 0 || h->tile_h == 0 || h->width == 0 || h->height == 0)
        return 0;
    return (uint64_t)((h->width + h->tile_w - 1) / h->tile_w) *
           (uint64_t)((h->height + h->tile_h - 1) / h->tile_h);
}

/* The device's data from a first copy of a frame. */
static void take(lt_rx_t *rx, const lt_stream_frame_t *f)
{
    lt_rx_stats_t *st = &rx->st;
    lt_stream_tile_t t;
    lt_stream_summary_t s;
    lt_stream_drop_t d;
    lt_stream_image_t im;
    lt_stream_end_t e;
    lt_status_t ok = LT_OK;
    st->by_type[f->type]++;
    switch (f->type) {
    case LT_STREAM_HELLO:
        if (rx->hello_taken)
            bad_record(rx, f, "a second HELLO in session 0x%08x without an END before it",
                       rx->sess_id);
        ok = lt_stream_unpack_hello(f, &st->hello);
        if (ok == LT_OK) {
            const lt_stream_hello_t *h = &st->hello;
            st->have_hello = 1;
            rx->hello_taken = 1;
            if (h->width == 0 || h->height == 0 || h->tile_w == 0 || h->tile_h == 0)
                bad_record(rx, f, "image %ux%u in %ux%u tiles: sizes must be at least 1",
                           h->width, h->height, h->tile_w, h->tile_h);
            else if (hello_tiles(rx) > 65536u)
                bad_record(rx, f, "image %ux%u in %ux%u tiles is %llu tiles, over the 65536 a "
                           "16-bit tile index can name", h->width, h->height, h->tile_w,
                           h->tile_h, (unsigned long long)hello_tiles(rx));
        }
        break;
    case LT_STREAM_TILE:
        ok = lt_stream_unpack_tile(f, &t);
        if (ok == LT_OK) {
            uint64_t nt = hello_tiles(rx);
            const lt_stream_hello_t *h = &st->hello;
            if (t.hits > t.rays)
                bad_record(rx, f, "tile %u of frame %u: %u hits of %u rays", t.tile, t.frame,
                           t.hits, t.rays);
            if (nt != 0 && t.tile >= nt)
                bad_record(rx, f, "tile index %u outside the image: %llu tiles (%ux%u in %ux%u "
                           "tiles)", t.tile, (unsigned long long)nt, h->width, h->height,
                           h->tile_w, h->tile_h);
            else if (nt != 0 && t.rays > (uint32_t)h->tile_w * h->tile_h)
                bad_record(rx, f, "tile %u of frame %u: %u rays, over the %u pixels of a %ux%u "
                           "tile", t.tile, t.frame, t.rays, (unsigned)(h->tile_w * h->tile_h),
                           h->tile_w, h->tile_h);
            if (rx->hello_taken && h->frames != 0 && t.frame >= h->frames)
                bad_record(rx, f, "tile %u of frame %u: the session traces frames 0..%u", t.tile,
                           t.frame, h->frames - 1u);
            if (ft_add(rx, (uint64_t)t.frame << 16 | t.tile) == 0)
                bad_record(rx, f, "tile %u of frame %u reported a second time (another sequence "
                           "number)", t.tile, t.frame);
            st->tiles++;
            st->rays += t.rays;
            st->hits += t.hits;
            st->tile_ticks += t.ticks;
            st->tile_cycles += t.cycles;
        }
        break;
    case LT_STREAM_SUMMARY:
        ok = lt_stream_unpack_summary(f, &s);
        if (ok == LT_OK) {
            uint64_t nt = hello_tiles(rx);
            const lt_stream_hello_t *h = &st->hello;
            if (s.hits > s.rays)
                bad_record(rx, f, "frame %u: %u hits of %u rays", s.frame, s.hits, s.rays);
            if (nt != 0 && s.tiles > nt)
                bad_record(rx, f, "frame %u: %u tiles traced, over the image's %llu (%ux%u in "
                           "%ux%u tiles)", s.frame, s.tiles, (unsigned long long)nt, h->width,
                           h->height, h->tile_w, h->tile_h);
            else if (nt != 0 && s.rays > (uint64_t)h->width * h->height)
                bad_record(rx, f, "frame %u: %u rays, over the image's %llu pixels", s.frame,
                           s.rays, (unsigned long long)h->width * h->height);
            if (rx->hello_taken && h->frames != 0 && s.frame >= h->frames)
                bad_record(rx, f, "frame %u: the session traces frames 0..%u", s.frame,
                           h->frames - 1u);
            st->summaries++;
            st->sum_tiles += s.tiles;
            st->sum_rays += s.rays;
            st->sum_hits += s.hits;
            st->sum_ticks += s.ticks;
            st->sum_cycles += s.cycles;
        }
        break;
    case LT_STREAM_DROP:
        ok = lt_stream_unpack_drop(f, &d);
        if (ok == LT_OK) {
            st->drop_records++;
            st->dev_dropped += d.dropped;
            st->dev_dropped_tile += d.tile;
            st->dev_dropped_image += d.image;
        }
        break;
    case LT_STREAM_IMAGE:
        ok = lt_stream_unpack_image(f, &im);
        if (ok == LT_OK) {
            uint64_t nt = hello_tiles(rx);
            const lt_stream_hello_t *h = &st->hello;
            st->images++;
            if (nt != 0 && im.tile >= nt)
                bad_record(rx, f, "tile index %u outside the image: %llu tiles (%ux%u in %ux%u "
                           "tiles)", im.tile, (unsigned long long)nt, h->width, h->height,
                           h->tile_w, h->tile_h);
            else if (nt != 0 && (uint32_t)im.offset + im.count > (uint32_t)h->tile_w * h->tile_h)
                bad_record(rx, f, "tile %u of frame %u: pixels %u..%u, past the %u of a %ux%u "
                           "tile", im.tile, im.frame, im.offset, im.offset + im.count - 1u,
                           (unsigned)(h->tile_w * h->tile_h), h->tile_w, h->tile_h);
            if (rx->hello_taken && h->frames != 0 && im.frame >= h->frames)
                bad_record(rx, f, "tile %u of frame %u: the session traces frames 0..%u", im.tile,
                           im.frame, h->frames - 1u);
        }
        break;
    case LT_STREAM_END:
        ok = lt_stream_unpack_end(f, &e);
        if (ok == LT_OK) {
            st->end = e;
            st->have_end = 1;
            rx->sess_end = 1;
            rx->end_sent = e.frames_sent;
        }
        break;
    default:
        break;
    }
    if (ok != LT_OK && st->bad_payload++ == 0)
        (void)snprintf(st->bad_payload_first, sizeof st->bad_payload_first,
                       "frame seq %u (%s): a payload of %u bytes that does not fit the type",
                       (unsigned)f->seq, lt_rx_type_name(f->type), (unsigned)f->len);
}

static void on_frame(lt_rx_t *rx, const lt_stream_frame_t *f)
{
    lt_rx_kind_t kind;
    int64_t ext;
    uint64_t g, c;
    rx->st.valid++;
    rx->st.last_seq = f->seq;
    /* A HELLO after END, or with another session id, starts a new session. */
    if (f->type == LT_STREAM_HELLO && rx->active) {
        lt_stream_hello_t h;
        if (lt_stream_unpack_hello(f, &h) == LT_OK &&
            (rx->sess_end || (rx->sess_hello && h.session != rx->sess_id)))
            sess_close(rx);
    }
    if (f->type == LT_STREAM_HELLO && !rx->sess_hello) {
        lt_stream_hello_t h;
        if (lt_stream_unpack_hello(f, &h) == LT_OK) {
            rx->sess_hello = 1;
            rx->sess_id = h.session;
            rx->st.sessions++;
        }
    }
    if (!rx->active) {
        ext = f->seq; /* sessions start at 0: a first frame above 0 means earlier ones were lost */
    } else {
        uint32_t d = ((uint32_t)f->seq - (uint32_t)(rx->hi & 0xFFFF)) & 0xFFFFu;
        ext = rx->hi + (d >= 0x8000u ? (int64_t)d - 0x10000 : (int64_t)d);
    }
    g = rx->dec.garbage_bytes;
    c = rx->dec.bad_header + rx->dec.bad_crc;
    if (ext < 0 || (rx->active && ext <= rx->hi && (uint64_t)(rx->hi - ext) >= WIN)) {
        kind = LT_RX_STALE;
        rx->st.stale++;
    } else if (!rx->active || ext > rx->hi) {
        int64_t from = rx->active ? rx->hi + 1 : 0, e;
        uint64_t gap = (uint64_t)(ext - from);
        /* garbage since the previous new frame fills part of this gap: damaged frames, at least
         * one per 64 garbage bytes and one per rejected candidate header, at most the gap */
        if (gap > 0 && g > rx->g_mark) {
            uint64_t by_bytes =
                (g - rx->g_mark + LT_STREAM_FRAME_BYTES - 1) / LT_STREAM_FRAME_BYTES;
            uint64_t by_cand = c - rx->c_mark, dmg = by_bytes > by_cand ? by_bytes : by_cand;
            rx->damaged += dmg < gap ? dmg : gap;
        }
        rx->g_mark = g;
        rx->c_mark = c;
        if (!rx->active || ext - rx->hi >= (int64_t)WIN) {
            memset(rx->seen, 0, sizeof rx->seen);
        } else {
            for (e = rx->hi + 1; e < ext; e++)
                bit_set(rx, (uint64_t)e, 0);
        }
        bit_set(rx, (uint64_t)ext, 1);
        rx->hi = ext;
        rx->active = 1;
        rx->uniq++;
        kind = LT_RX_NEW;
    } else if (bit_get(rx, (uint64_t)ext)) {
        kind = LT_RX_DUPLICATE;
        rx->st.duplicates++;
    } else {
        bit_set(rx, (uint64_t)ext, 1);
        rx->uniq++;
        kind = LT_RX_REORDERED;
        rx->st.reordered++;
    }
    if (kind == LT_RX_NEW || kind == LT_RX_REORDERED)
        take(rx, f);
    update_link(rx);
    if (rx->cb != NULL)
        rx->cb(rx->cb_ctx, f, kind);
}

void lt_rx_feed(lt_rx_t *rx, const uint8_t *b, size_t n)
{
    rx->st.bytes += n;
    rx->finished = 0;
    while (n > 0) {
        lt_stream_frame_t f;
        uint32_t used = 0, chunk = n > 0x10000000u ? 0x10000000u : (uint32_t)n;
        lt_status_t s = lt_stream_dec_push(&rx->dec, b, chunk, &used, &f);
        b += used;
        n -= used;
        if (s == LT_OK)
            on_frame(rx, &f);
        else if (s != LT_E_SPACE)
            break;
    }
    update_link(rx);
}

void lt_rx_finish(lt_rx_t *rx)
{
    uint32_t tail;
    if (rx->finished)
        return;
    rx->finished = 1;
    tail = lt_stream_dec_finish(&rx->dec);
    rx->st.tail_bytes += tail;
    update_link(rx);
}
