/* lt_faultinject_main.c - build/host/lt-faultinject: read a frame stream (stdin or --in), write it
 * back (stdout or --out) with frames dropped, corrupted, duplicated, reordered and truncated at the
 * given rates and seed (host/stream/lt_faults.h), and report the ground truth: one line on stderr and,
 * with --json PATH, a JSON object. Exit: 0 ok, 1 input/output error, 2 usage. Host only.
 */
#include "cli/lt_opt.h"
#include "stream/lt_faults.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int werr;

static void out_file(void *ctx, const uint8_t *b, size_t n)
{
    if (fwrite(b, 1, n, (FILE *)ctx) != n)
        werr = 1;
}

/* --seed: an unsigned 64-bit integer, decimal or 0x hex */
static int parse_seed(const char *text, void *dest, const void *ctx)
{
    char *end;
    unsigned long long v;
    (void)ctx;
    if (*text == '\0' || *text == '-' || *text == '+')
        return -1;
    errno = 0;
    v = strtoull(text, &end, 0);
    if (*end != '\0' || errno == ERANGE)
        return -1;
    *(uint64_t *)dest = (uint64_t)v;
    return 0;
}

typedef struct args {
    const char *in, *out, *json;
    int quiet;
} args_t;

/* The options into cfg and a. --rate R sets the five rates given before it (and the ones never
 * given); a rate given after --rate wins. LT_OPT_OK, LT_OPT_HELP or LT_OPT_USAGE. */
static int parse_args(lt_faults_cfg_t *cfg, args_t *a, int argc, char **argv)
{
    double rates[5] = {0, 0, 0, 0, 0}, rate = 0.0;
    double *const dst[5] = {&cfg->drop, &cfg->corrupt, &cfg->dup, &cfg->reorder, &cfg->trunc};
    int seen[5] = {0, 0, 0, 0, 0}, seen_rate = 0, flips = 3, i, rc;
#define RATE(nm, k, h)                                                                             \
    {.name = (nm), .kind = LT_OPT_DOUBLE, .dest = &rates[k], .seen = &seen[k], .meta = "R",       \
     .help = (h), .lo = 0.0, .hi = 1.0}
    const lt_opt_t opts[] = {
        LT_OPT_STR("--in", "F", &a->in, "input stream (default stdin; - = stdin)"),
        LT_OPT_STR("--out", "F", &a->out, "output stream (default stdout; - = stdout)"),
        LT_OPT_SECTION_("per-frame probability of each fault, sum <= 1 (default 0):"),
        RATE("--drop", 0, "drop the frame, {range}"),
        RATE("--corrupt", 1, "flip 1..--flips bits in it, {range}"),
        RATE("--dup", 2, "send it twice, {range}"),
        RATE("--reorder", 3, "swap it with the next one, {range}"),
        RATE("--trunc", 4, "cut it short, {range}"),
        {.name = "--rate", .kind = LT_OPT_DOUBLE, .dest = &rate, .seen = &seen_rate, .meta = "R",
         .help = "all five at once, {range} (a rate given after it wins)", .lo = 0.0, .hi = 1.0},
        LT_OPT_SECTION_("options:"),
        LT_OPT_INT("--flips", "N", &flips, 1, 8,
                   "a corrupted frame gets 1..N distinct bit flips, {range} (default 3)"),
        {.name = "--seed", .kind = LT_OPT_CUSTOM, .dest = &cfg->seed, .meta = "S",
         .help = "PRNG seed (default 1); the same seed gives the same faults",
         .expect = "an unsigned 64-bit integer (decimal or 0x hex)", .parse = parse_seed},
        LT_OPT_STR("--json", "PATH", &a->json, "write the ground truth as JSON"),
        LT_OPT_FLAG_("-q", &a->quiet, "no ground-truth line on stderr"),
        LT_OPT_END_};
#undef RATE
    const lt_opt_cmd_t cmd = {"lt-faultinject", "[options]",
                              "Copy a frame stream with frames dropped, corrupted, duplicated, "
                              "reordered and\ntruncated at the given rates, and report the ground "
                              "truth.\n",
                              "exit status: 0 ok, 1 input/output error, 2 usage\n", opts, NULL, 0,
                              NULL};
    rc = lt_opt_parse(&cmd, argc, argv, 1);
    if (rc != LT_OPT_OK)
        return rc;
    for (i = 0; i < 5; i++)
        *dst[i] = seen_rate != 0 && seen[i] < seen_rate ? rate : rates[i];
    cfg->max_flips = (uint32_t)flips;
    return LT_OPT_OK;
}

int main(int argc, char **argv)
{
    lt_faults_cfg_t cfg;
    lt_faults_t *fi;
    const lt_faults_truth_t *t;
    args_t ar = {NULL, NULL, NULL, 0};
    FILE *fin = stdin, *fout = stdout;
    lt_diag_t diag;
    uint8_t buf[65536];
    size_t n;
    int status = 0, rc;

    memset(&cfg, 0, sizeof cfg);
    cfg.max_flips = 3;
    cfg.seed = 1;
    if ((rc = parse_args(&cfg, &ar, argc, argv)) != LT_OPT_OK)
        return lt_opt_exit_code(rc);
    if (lt_faults_check(&cfg, &diag) != 0) {
        fprintf(stderr, "lt-faultinject: %s\n", diag.msg);
        return 2;
    }
    if (ar.in != NULL && strcmp(ar.in, "-") != 0 && (fin = fopen(ar.in, "rb")) == NULL) {
        fprintf(stderr, "lt-faultinject: %s: cannot open: %s\n", ar.in, strerror(errno));
        return 1;
    }
    if (ar.out != NULL && strcmp(ar.out, "-") != 0 && (fout = fopen(ar.out, "wb")) == NULL) {
        fprintf(stderr, "lt-faultinject: %s: cannot write: %s\n", ar.out, strerror(errno));
        return 1;
    }
    fi = lt_faults_new(&cfg, out_file, fout, &diag);
    if (fi == NULL) {
        fprintf(stderr, "lt-faultinject: %s\n", diag.msg);
        return 1;
    }
    while ((n = fread(buf, 1, sizeof buf, fin)) > 0)
        lt_faults_feed(fi, buf, n);
    if (ferror(fin)) {
        fprintf(stderr, "lt-faultinject: %s: read error\n", ar.in != NULL ? ar.in : "stdin");
        status = 1;
    }
    lt_faults_finish(fi);
    if (fflush(fout) != 0 || werr) {
        fprintf(stderr, "lt-faultinject: %s: write error\n", ar.out != NULL ? ar.out : "stdout");
        status = 1;
    }
    t = lt_faults_truth(fi);
    if (!ar.quiet)
        fprintf(stderr, "lt-faultinject: seed %llu: %llu frames in, %llu intact out; dropped %llu "
                "corrupted %llu (%llu bits) duplicated %llu reordered %llu truncated %llu; "
                "damaged bytes %llu, destroyed at the tail %llu, input garbage %llu\n",
                (unsigned long long)cfg.seed, (unsigned long long)t->frames_in,
                (unsigned long long)t->frames_out, (unsigned long long)t->dropped,
                (unsigned long long)t->corrupted, (unsigned long long)t->flipped_bits,
                (unsigned long long)t->duplicated, (unsigned long long)t->reordered,
                (unsigned long long)t->truncated, (unsigned long long)t->damaged_bytes,
                (unsigned long long)t->tail_destroyed, (unsigned long long)t->input_garbage);
    if (ar.json != NULL) {
        FILE *j = fopen(ar.json, "w");
        if (j == NULL) {
            fprintf(stderr, "lt-faultinject: %s: cannot write: %s\n", ar.json, strerror(errno));
            status = 1;
        } else {
            fprintf(j, "{\n  \"seed\": %llu,\n  \"rates\": [%g, %g, %g, %g, %g],\n"
                    "  \"frames_in\": %llu,\n  \"frames_out\": %llu,\n  \"bytes_out\": %llu,\n"
                    "  \"dropped\": %llu,\n  \"corrupted\": %llu,\n  \"flipped_bits\": %llu,\n"
                    "  \"duplicated\": %llu,\n  \"reordered\": %llu,\n  \"truncated\": %llu,\n"
                    "  \"damaged_bytes\": %llu,\n  \"tail_destroyed\": %llu,\n"
                    "  \"input_garbage\": %llu\n}\n",
                    (unsigned long long)cfg.seed, cfg.drop, cfg.corrupt, cfg.dup, cfg.reorder,
                    cfg.trunc, (unsigned long long)t->frames_in, (unsigned long long)t->frames_out,
                    (unsigned long long)t->bytes_out, (unsigned long long)t->dropped,
                    (unsigned long long)t->corrupted, (unsigned long long)t->flipped_bits,
                    (unsigned long long)t->duplicated, (unsigned long long)t->reordered,
                    (unsigned long long)t->truncated, (unsigned long long)t->damaged_bytes,
                    (unsigned long long)t->tail_destroyed, (unsigned long long)t->input_garbage);
            if (fclose(j) != 0) {
                fprintf(stderr, "lt-faultinject: %s: write error\n", ar.json);
                status = 1;
            }
        }
    }
    lt_faults_free(fi);
    if (fin != stdin)
        fclose(fin);
    if (fout != stdout)
        fclose(fout);
    return status;
}
