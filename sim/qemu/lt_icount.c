/* lt_icount.c: QEMU TCG plugin that counts executed guest instructions, in total and per symbol.
 * Every translated instruction gets an inline 64-bit add (no helper call) into the total and, when
 * qemu_plugin_insn_symbol() names one of the requested symbols, into that symbol's counter; an
 * instruction at a requested address (at=: a function's entry, so its calls) gets its own counter.
 * Targets QEMU plugin API v1 (QEMU 6.x-7.2); Debian ships no qemu-plugin.h, so the few calls
 * used are declared below with the 7.2 signatures. Arguments and output: docs/qemu-plugin.md.
 */
#include <stdint.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- QEMU plugin API v1, the subset used (as in QEMU 7.2 include/qemu/qemu-plugin.h) ---- */

#define LT_PLUGIN_EXPORT __attribute__((visibility("default")))

typedef uint64_t qemu_plugin_id_t;
struct qemu_info_t;       /* only passed through: no field is read, so the layout is not needed */
struct qemu_plugin_tb;    /* opaque, valid only during the translation callback */
struct qemu_plugin_insn;  /* opaque, valid only during the translation callback */

enum qemu_plugin_op {
    QEMU_PLUGIN_INLINE_ADD_U64 = 0  /* the only inline op in v1: *ptr += imm, not atomic */
};

typedef void (*qemu_plugin_udata_cb_t)(qemu_plugin_id_t id, void *userdata);
typedef void (*qemu_plugin_vcpu_tb_trans_cb_t)(qemu_plugin_id_t id, struct qemu_plugin_tb *tb);

void qemu_plugin_register_vcpu_tb_trans_cb(qemu_plugin_id_t id, qemu_plugin_vcpu_tb_trans_cb_t cb);
void qemu_plugin_register_vcpu_insn_exec_inline(struct qemu_plugin_insn *insn,
                                                enum qemu_plugin_op op, void *ptr, uint64_t imm);
void qemu_plugin_register_atexit_cb(qemu_plugin_id_t id, qemu_plugin_udata_cb_t cb,
                                    void *userdata);
size_t qemu_plugin_tb_n_insns(const struct qemu_plugin_tb *tb);
struct qemu_plugin_insn *qemu_plugin_tb_get_insn(const struct qemu_plugin_tb *tb, size_t idx);
const char *qemu_plugin_insn_symbol(const struct qemu_plugin_insn *insn); /* NULL if none */
uint64_t qemu_plugin_insn_vaddr(const struct qemu_plugin_insn *insn);
void qemu_plugin_outs(const char *string);

/* QEMU refuses a plugin whose version is outside its [min, cur]; 7.2 has min 0, cur 1. */
LT_PLUGIN_EXPORT int qemu_plugin_version = 1;

LT_PLUGIN_EXPORT int qemu_plugin_install(qemu_plugin_id_t id, const struct qemu_info_t *info,
                                         int argc, char **argv);

/* ---- plugin state ---- */

#define LT_ICOUNT_MAX_SYMS 16

static uint64_t total;                           /* instructions, all code */
static const char *sym_name[LT_ICOUNT_MAX_SYMS]; /* points into argv, which outlives the plugin */
static uint64_t sym_count[LT_ICOUNT_MAX_SYMS];   /* instructions whose symbol is sym_name[i] */
static unsigned n_syms;
static uint64_t at_addr[LT_ICOUNT_MAX_SYMS];     /* at=: guest virtual addresses */
static uint64_t at_count[LT_ICOUNT_MAX_SYMS];    /* executions of the instruction at at_addr[i] */
static unsigned n_ats;
static const char *out_path;                     /* NULL: write through qemu_plugin_outs */

/* Counting per instruction rather than adding n_insns once per block keeps the total exact when a
 * block stops early: under -icount an MMIO access mid-block restarts from that instruction in a
 * new block that QEMU does not instrument for execution (CF_MEMI_ONLY), so nothing is counted
 * twice. A block-level add would count the block's tail twice. */
static void on_tb_trans(qemu_plugin_id_t id, struct qemu_plugin_tb *tb)
{
    size_t n = qemu_plugin_tb_n_insns(tb);
    size_t i;
    unsigned k;

    (void)id;
    for (i = 0; i < n; i++) {
        struct qemu_plugin_insn *insn = qemu_plugin_tb_get_insn(tb, i);
        const char *sym;

        qemu_plugin_register_vcpu_insn_exec_inline(insn, QEMU_PLUGIN_INLINE_ADD_U64, &total, 1);
        if (n_ats != 0) {
            uint64_t va = qemu_plugin_insn_vaddr(insn);
            for (k = 0; k < n_ats; k++)
                if (va == at_addr[k])
                    qemu_plugin_register_vcpu_insn_exec_inline(insn, QEMU_PLUGIN_INLINE_ADD_U64,
                                                               &at_count[k], 1);
        }
        if (n_syms == 0)
            continue;
        sym = qemu_plugin_insn_symbol(insn);
        if (sym == NULL)
            continue;
        /* No break: a name given twice gets both counters. */
        for (k = 0; k < n_syms; k++)
            if (strcmp(sym, sym_name[k]) == 0)
                qemu_plugin_register_vcpu_insn_exec_inline(insn, QEMU_PLUGIN_INLINE_ADD_U64,
                                                           &sym_count[k], 1);
    }
}

static void on_atexit(qemu_plugin_id_t id, void *userdata)
{
    char line[256];
    FILE *f = NULL;
    unsigned k;

    (void)id;
    (void)userdata;
    if (out_path != NULL) {
        f = fopen(out_path, "w");
        if (f == NULL)
            fprintf(stderr, "lt_icount: cannot open out=%s, writing to the QEMU log\n", out_path);
    }
    for (k = 0; k <= n_syms + n_ats; k++) {
        if (k == 0)
            snprintf(line, sizeof line, "icount total %llu\n", (unsigned long long)total);
        else if (k <= n_syms)
            snprintf(line, sizeof line, "icount sym %s %llu\n", sym_name[k - 1],
                     (unsigned long long)sym_count[k - 1]);
        else
            snprintf(line, sizeof line, "icount at 0x%llx %llu\n",
                     (unsigned long long)at_addr[k - 1 - n_syms],
                     (unsigned long long)at_count[k - 1 - n_syms]);
        if (f != NULL)
            fputs(line, f);
        else
            qemu_plugin_outs(line);
    }
    if (f != NULL && fclose(f) != 0)
        fprintf(stderr, "lt_icount: error writing out=%s\n", out_path);
}

/* QEMU 7.2 passes each "-plugin FILE,name=value" option as the string "name=value"; the deprecated
 * "arg=name=value" form arrives as "name=value" too. */
int qemu_plugin_install(qemu_plugin_id_t id, const struct qemu_info_t *info, int argc, char **argv)
{
    int i;

    (void)info;
    for (i = 0; i < argc; i++) {
        const char *a = argv[i];

        if (strncmp(a, "sym=", 4) == 0 && a[4] != '\0') {
            if (n_syms == LT_ICOUNT_MAX_SYMS) {
                fprintf(stderr, "lt_icount: more than %d sym= arguments\n", LT_ICOUNT_MAX_SYMS);
                return 1;
            }
            sym_name[n_syms++] = a + 4;
        } else if (strncmp(a, "at=", 3) == 0 && a[3] != '\0') {
            char *end;
            if (n_ats == LT_ICOUNT_MAX_SYMS) {
                fprintf(stderr, "lt_icount: more than %d at= arguments\n", LT_ICOUNT_MAX_SYMS);
                return 1;
            }
            /* hexadecimal, 0x optional, as objdump and nm print addresses */
            at_addr[n_ats] = strtoull(a + 3, &end, 16);
            if (*end != '\0') {
                fprintf(stderr, "lt_icount: at=%s is not a hexadecimal address\n", a + 3);
                return 1;
            }
            n_ats++;
        } else if (strncmp(a, "out=", 4) == 0 && a[4] != '\0') {
            out_path = a + 4;
        } else {
            fprintf(stderr,
                    "lt_icount: unknown argument '%s' (want sym=NAME, at=ADDR or out=PATH)\n", a);
            return 1;
        }
    }
    qemu_plugin_register_vcpu_tb_trans_cb(id, on_tb_trans);
    qemu_plugin_register_atexit_cb(id, on_atexit, NULL);
    return 0;
}
