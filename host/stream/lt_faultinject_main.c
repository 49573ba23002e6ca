/* lt_faultinject_main.c - build/host/lt-faultinject: read a frame stream (stdin or --in), write it
 * back (stdout or --out) with frames dropped, corrupted, duplicated, reordered and truncated at the
 * given rates and seed (host/stream/lt_faults.h), and report the ground truth: one line on stderr and,
 * with --json PATH, a JSON object. Exit: 0 ok, 1 input/output error, 2 usage. Host only.
 */
#include "stream/lt_faults.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void usage(FILE *f)
{
    fprintf(
        f, "usage: lt-faultinject [--in F] [--out F] [--drop R] [--corrupt R] [--dup R]\n"
           "                      [--reorder R] [--trunc R] [--rate R] [--flips N] [--seed S]\n"
           "                      [--json PATH] [-q]\n"
           "  --in F / --out F  input and output streams (default stdin / stdout)\n"
           "  --drop R ...      per-frame probability of each fault, 0..1, sum <= 1 (default 0);\n"
           "                    --rate R sets all five to R\n"
           "  --flips N         a corrupted frame gets 1..N distinct bit flips (default 3, max 8)\n"
           "  --seed S          PRNG seed (default 1); the same seed gives the same faults\n"
           "  --json PATH       write the ground truth as JSON\n"
           "  -q                no ground-truth line on stderr\n");
}

static int werr;

static void out_file(void *ctx, const uint8_t *b, size_t n)
{
    if (fwrite(b, 1, n, (FILE *)ctx) != n)
        werr = 1;
}

static int parse_rate(const char *opt, const char *v, double *r)
{
    char *end;
    *r = strtod(v, &end);
    if (*v == '\0' || *end != '\0' || !(*r >= 0.0 && *r <= 1.0)) {
        fprintf(stderr, "lt-faultinject: %s %s: expected a probability in [0, 1]\n", opt, v);
        return -1;
    }
    return 0;
}

int main(int argc, char **argv)
{
    lt_faults_cfg_t cfg;
    lt_faults_t *fi;
    const lt_faults_truth_t *t;
    const char *in = NULL, *out = NULL, *json = NULL;
    FILE *fin = stdin, *fout = stdout;
    lt_diag_t diag;
    uint8_t buf[65536];
    size_t n;
    int a, quiet = 0, status = 0;

    memset(&cfg, 0, sizeof cfg);
    cfg.max_flips = 3;
    cfg.seed = 1;
    for (a = 1; a < argc; a++) {
        const char *v = a + 1 < argc ? argv[a + 1] : NULL;
        double r;
        if (strcmp(argv[a], "--help") == 0 || strcmp(argv[a], "-h") == 0) {
            usage(stdout);
            return 0;
        } else if (strcmp(argv[a], "-q") == 0) {
            quiet = 1;
            continue;
        } else if (v == NULL) {
            fprintf(stderr, "lt-faultinject: %s: unknown option or missing value\n", argv[a]);
            usage(stderr);
            return 2;
        }
        a++;
        if (strcmp(argv[a - 1], "--in") == 0) {
            in = v;
        } else if (strcmp(argv[a - 1], "--out") == 0) {
            out = v;
        } else if (strcmp(argv[a - 1], "--json") == 0) {
            json = v;
        } else if (strcmp(argv[a - 1], "--seed") == 0) {
            char *end;
            cfg.seed = strtoull(v, &end, 0);
            if (*v == '\0' || *end != '\0') {
                fprintf(stderr, "lt-faultinject: --seed %s: expected an integer\n", v);
                return 2;
            }
        } else if (strcmp(argv[a - 1], "--flips") == 0) {
            char *end;
            unsigned long f = strtoul(v, &end, 10);
            if (*v == '\0' || *end != '\0' || f < 1 || f > 8) {
                fprintf(stderr, "lt-faultinject: --flips %s: expected 1..8\n", v);
                return 2;
            }
            cfg.max_flips = (uint32_t)f;
        } else if (parse_rate(argv[a - 1], v, &r) != 0) {
            return 2;
        } else if (strcmp(argv[a - 1], "--drop") == 0) {
            cfg.drop = r;
        } else if (strcmp(argv[a - 1], "--corrupt") == 0) {
            cfg.corrupt = r;
        } else if (strcmp(argv[a - 1], "--dup") == 0) {
            cfg.dup = r;
        } else if (strcmp(argv[a - 1], "--reorder") == 0) {
            cfg.reorder = r;
        } else if (strcmp(argv[a - 1], "--trunc") == 0) {
            cfg.trunc = r;
        } else if (strcmp(argv[a - 1], "--rate") == 0) {
            cfg.drop = cfg.corrupt = cfg.dup = cfg.reorder = cfg.trunc = r;
        } else {
            fprintf(stderr, "lt-faultinject: %s: unknown option\n", argv[a - 1]);
            usage(stderr);
            return 2;
        }
    }
    if (lt_faults_check(&cfg, &diag) != 0) {
        fprintf(stderr, "lt-faultinject: %s\n", diag.msg);
        return 2;
    }
    if (in != NULL && strcmp(in, "-") != 0 && (fin = fopen(in, "rb")) == NULL) {
        fprintf(stderr, "lt-faultinject: %s: cannot open: %s\n", in, strerror(errno));
        return 1;
    }
    if (out != NULL && strcmp(out, "-") != 0 && (fout = fopen(out, "wb")) == NULL) {
        fprintf(stderr, "lt-faultinject: %s: cannot write: %s\n", out, strerror(errno));
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
        fprintf(stderr, "lt-faultinject: %s: read error\n", in != NULL ? in : "stdin");
        status = 1;
    }
    lt_faults_finish(fi);
    if (fflush(fout) != 0 || werr) {
        fprintf(stderr, "lt-faultinject: %s: write error\n", out != NULL ? out : "stdout");
        status = 1;
    }
    t = lt_faults_truth(fi);
    if (!quiet)
        fprintf(stderr, "lt-faultinject: seed %llu: %llu frames in, %llu intact out; dropped %llu "
                "corrupted %llu (%llu bits) duplicated %llu reordered %llu truncated %llu; "
                "damaged bytes %llu, destroyed at the tail %llu, input garbage %llu\n",
                (unsigned long long)cfg.seed, (unsigned long long)t->frames_in,
                (unsigned long long)t->frames_out, (unsigned long long)t->dropped,
                (unsigned long long)t->corrupted, (unsigned long long)t->flipped_bits,
                (unsigned long long)t->duplicated, (unsigned long long)t->reordered,
                (unsigned long long)t->truncated, (unsigned long long)t->damaged_bytes,
                (unsigned long long)t->tail_destroyed, (unsigned long long)t->input_garbage);
    if (json != NULL) {
        FILE *j = fopen(json, "w");
        if (j == NULL) {
            fprintf(stderr, "lt-faultinject: %s: cannot write: %s\n", json, strerror(errno));
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
                fprintf(stderr, "lt-faultinject: %s: write error\n", json);
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
