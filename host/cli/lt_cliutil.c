/* lt_cliutil.c - see lt_cliutil.h. */
#include "cli/lt_cliutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

double lt_now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int lt_parse_wh(const char *s, uint32_t max, uint32_t *w, uint32_t *h)
{
    unsigned long a, b;
    char *end;
    a = strtoul(s, &end, 10);
    b = a;
    if (end == s)
        return -1;
    if (*end == 'x')
        b = strtoul(end + 1, &end, 10);
    if (*end != '\0' || a == 0 || b == 0 || a > max || b > max)
        return -1;
    *w = (uint32_t)a;
    *h = (uint32_t)b;
    return 0;
}

const char *lt_shown(const char *s, char *out, size_t n)
{
    size_t i;
    if (n == 0)
        return out;
    for (i = 0; s[i] != '\0' && i + 1 < n; i++)
        out[i] = (unsigned char)s[i] < 0x20 || s[i] == 0x7F ? '?' : s[i];
    out[i] = '\0';
    return out;
}

uint8_t lt_gamma8(double v)
{
    v = v < 0.0 || v != v ? 0.0 : (v > 1.0 ? 1.0 : v);
    return (uint8_t)(255.0 * pow(v, 1.0 / 2.2) + 0.5);
}

int lt_path_tagged(char *out, size_t n, const char *path, const char *tag)
{
    const char *base = strrchr(path, '/'), *dot;
    int k;
    base = base != NULL ? base + 1 : path;
    dot = strrchr(base, '.');
    if (dot == NULL || dot == base)
        k = snprintf(out, n, "%s.%s", path, tag);
    else
        k = snprintf(out, n, "%.*s.%s%s", (int)(dot - path), path, tag, dot);
    return k >= 0 && (size_t)k < n ? 0 : -1;
}

static struct {
    const char *label;
    double t0;
    int quiet, shown;
} bar;

void lt_progress_begin(const char *label, int quiet)
{
    bar.label = label;
    bar.t0 = lt_now_s();
    bar.quiet = quiet;
    bar.shown = 0;
}

void lt_progress(double done)
{
    double el = lt_now_s() - bar.t0;
    int i, w = 30, fill;
    if (bar.quiet || !isatty(2) || el < 1.0)
        return;
    if (done > 1.0)
        done = 1.0;
    fill = (int)(done * w);
    fprintf(stderr, "\r%-10s [", bar.label != NULL ? bar.label : "");
    for (i = 0; i < w; i++)
        fputc(i < fill ? '#' : ' ', stderr);
    fprintf(stderr, "] %3.0f%% ETA %.1fs ", 100.0 * done, done > 0 ? el * (1.0 - done) / done : 0.0);
    bar.shown = 1;
}

void lt_progress_end(void)
{
    if (bar.shown)
        fprintf(stderr, "\r%60s\r", "");
    bar.shown = 0;
}
