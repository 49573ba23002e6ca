/* lt_icount.c: QEMU TCG plugin that counts executed guest instructions, in total, per symbol, per
 * instruction class and per program stage, and prices the classes with a per-target cost file.
 * Every translated instruction gets inline 64-bit adds (no helper call) into the total, into its
 * class's counter and, when qemu_plugin_insn_symbol() names one of the requested symbols, into
 * that symbol's counter; an instruction at a requested address (at=: a function's entry, so its
 * calls) gets its own counter. A callback at the start of every block settles whether the
 * conditional branch that ended the previous block was taken; a store callback in lt_fw_stage
 * (stage=) splits the run into stages. Targets QEMU plugin API v1 (QEMU 6.x-7.2); Debian ships
 * no qemu-plugin.h, so the calls used are declared below with the 7.2 signatures. Arguments,
 * output, classes and cost files: docs/qemu-plugin.md.
 */
#include <errno.h>
#include <stdbool.h>
#include <stdint.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- QEMU plugin API v1, the subset used (as in QEMU 7.2 include/qemu/qemu-plugin.h) ---- */

#define LT_PLUGIN_EXPORT __attribute__((visibility("default")))

typedef uint64_t qemu_plugin_id_t;
typedef uint32_t qemu_plugin_meminfo_t;
struct qemu_plugin_tb;    /* opaque, valid only during the translation callback */
struct qemu_plugin_insn;  /* opaque, valid only during the translation callback */

/* 7.2's qemu_info_t; only target_name ("arm", "riscv32", ...) is read. */
typedef struct qemu_info_t {
    const char *target_name;
    struct {
        int min;
        int cur;
    } version;
    bool system_emulation;
    union {              /* anonymous in the header; named here for C99, same layout */
        struct {
            int smp_vcpus;
            int max_vcpus;
        } system;
    } u;
} qemu_info_t;

enum qemu_plugin_op {
    QEMU_PLUGIN_INLINE_ADD_U64 = 0  /* the only inline op in v1: *ptr += imm, not atomic */
};
enum qemu_plugin_cb_flags {
    QEMU_PLUGIN_CB_NO_REGS,
    QEMU_PLUGIN_CB_R_REGS,
    QEMU_PLUGIN_CB_RW_REGS
};
enum qemu_plugin_mem_rw {
    QEMU_PLUGIN_MEM_R = 1,
    QEMU_PLUGIN_MEM_W,
    QEMU_PLUGIN_MEM_RW
};

typedef void (*qemu_plugin_udata_cb_t)(qemu_plugin_id_t id, void *userdata);
typedef void (*qemu_plugin_vcpu_udata_cb_t)(unsigned int vcpu_index, void *userdata);
typedef void (*qemu_plugin_vcpu_tb_trans_cb_t)(qemu_plugin_id_t id, struct qemu_plugin_tb *tb);
typedef void (*qemu_plugin_vcpu_mem_cb_t)(unsigned int vcpu_index, qemu_plugin_meminfo_t info,
                                          uint64_t vaddr, void *userdata);

void qemu_plugin_register_vcpu_tb_trans_cb(qemu_plugin_id_t id, qemu_plugin_vcpu_tb_trans_cb_t cb);
void qemu_plugin_register_vcpu_tb_exec_cb(struct qemu_plugin_tb *tb, qemu_plugin_vcpu_udata_cb_t cb,
                                          enum qemu_plugin_cb_flags flags, void *userdata);
void qemu_plugin_register_vcpu_insn_exec_inline(struct qemu_plugin_insn *insn,
                                                enum qemu_plugin_op op, void *ptr, uint64_t imm);
void qemu_plugin_register_vcpu_mem_cb(struct qemu_plugin_insn *insn, qemu_plugin_vcpu_mem_cb_t cb,
                                      enum qemu_plugin_cb_flags flags, enum qemu_plugin_mem_rw rw,
                                      void *userdata);
void qemu_plugin_register_atexit_cb(qemu_plugin_id_t id, qemu_plugin_udata_cb_t cb,
                                    void *userdata);
size_t qemu_plugin_tb_n_insns(const struct qemu_plugin_tb *tb);
uint64_t qemu_plugin_tb_vaddr(const struct qemu_plugin_tb *tb);
struct qemu_plugin_insn *qemu_plugin_tb_get_insn(const struct qemu_plugin_tb *tb, size_t idx);
const void *qemu_plugin_insn_data(const struct qemu_plugin_insn *insn); /* insn_size bytes */
size_t qemu_plugin_insn_size(const struct qemu_plugin_insn *insn);
uint64_t qemu_plugin_insn_vaddr(const struct qemu_plugin_insn *insn);
/* A g_malloc'd string ("mnemonic operands"); glib >= 2.46 allocates with malloc, so free() it. */
char *qemu_plugin_insn_disas(const struct qemu_plugin_insn *insn);
const char *qemu_plugin_insn_symbol(const struct qemu_plugin_insn *insn); /* NULL if none */
void qemu_plugin_outs(const char *string);

/* QEMU refuses a plugin whose version is outside its [min, cur]; 7.2 has min 0, cur 1. */
LT_PLUGIN_EXPORT int qemu_plugin_version = 1;

LT_PLUGIN_EXPORT int qemu_plugin_install(qemu_plugin_id_t id, const qemu_info_t *info,
                                         int argc, char **argv);

/* ---- classes ---- */

/* Counters: one per instruction class (K_COND counts conditional-branch executions, split into
 * taken and not taken at output), then the registers moved by LDM/STM-like instructions, then two
 * counted by the block callback, not inline: the taken conditional branches, and the loads that
 * follow a load across a block boundary (moved from load to load_after_load at output). The
 * instruction-class counters K_ALU..K_OTHER sum to the total. */
enum {
    K_ALU, K_MUL, K_MLA, K_MULL, K_DIV, K_LOAD, K_LOAD2, K_STORE, K_LDM, K_STM, K_COND, K_JUMP,
    K_IT, K_FPU, K_FPU_MAC, K_FPU_DIV, K_FPU_LOAD, K_FPU_STORE, K_MVE_ALU, K_MVE_MUL, K_MVE_LOAD,
    K_MVE_STORE, K_MVE_CTL, K_LOB, K_SYSTEM, K_OTHER,
    K_NCLASS,                         /* instruction classes end here */
    K_LDM_REG = K_NCLASS, K_STM_REG, K_TAKEN, K_LOAD2_X,
    K_NCTR
};

/* Priced names, in output order; a cost file prices any subset of them. */
enum {
    P_ALU, P_MUL, P_MLA, P_MULL, P_DIV, P_LOAD, P_LOAD2, P_STORE, P_LDM, P_LDM_REG, P_STM,
    P_STM_REG, P_TAKEN, P_NOT_TAKEN, P_JUMP, P_IT, P_FPU, P_FPU_MAC, P_FPU_DIV, P_FPU_LOAD,
    P_FPU_STORE, P_MVE_ALU, P_MVE_MUL, P_MVE_LOAD, P_MVE_STORE, P_MVE_CTL, P_LOB, P_SYSTEM, P_OTHER,
    P_N
};
static const char *const price_name[P_N] = {
    "alu", "mul", "mla", "mull", "div", "load", "load_after_load", "store", "ldm", "ldm_reg",
    "stm", "stm_reg", "branch_taken", "branch_not_taken", "jump", "it", "fpu", "fpu_mac",
    "fpu_div", "fpu_load", "fpu_store", "mve_alu", "mve_mul", "mve_load", "mve_store", "mve_ctl",
    "lob", "system", "other"
};

/* price_count: the executions (or registers) that price p is charged for, from counters c. */
static uint64_t price_count(const uint64_t *c, int p)
{
    static const signed char ctr[P_N] = {
        K_ALU, K_MUL, K_MLA, K_MULL, K_DIV, K_LOAD, K_LOAD2, K_STORE, K_LDM, K_LDM_REG, K_STM,
        K_STM_REG, -1, -1, K_JUMP, K_IT, K_FPU, K_FPU_MAC, K_FPU_DIV, K_FPU_LOAD, K_FPU_STORE,
        K_MVE_ALU, K_MVE_MUL, K_MVE_LOAD, K_MVE_STORE, K_MVE_CTL, K_LOB, K_SYSTEM, K_OTHER
    };
    if (p == P_TAKEN)
        return c[K_TAKEN];
    if (p == P_LOAD)
        return c[K_LOAD] - c[K_LOAD2_X];
    if (p == P_LOAD2)
        return c[K_LOAD2] + c[K_LOAD2_X];
    if (p == P_NOT_TAKEN)
        return c[K_COND] - c[K_TAKEN];
    return c[ctr[p]];
}

static bool is_reg_price(int p) { return p == P_LDM_REG || p == P_STM_REG; }

/* ---- plugin state ---- */

#define LT_ICOUNT_MAX_SYMS 16
#define LT_NSTAGES 16
#define LT_MAX_OTHER 64

static uint64_t total;                           /* instructions, all code */
static const char *sym_name[LT_ICOUNT_MAX_SYMS]; /* points into argv, which outlives the plugin */
static uint64_t sym_count[LT_ICOUNT_MAX_SYMS];   /* instructions whose symbol is sym_name[i] */
static unsigned n_syms;
static uint64_t at_addr[LT_ICOUNT_MAX_SYMS];     /* at=: guest virtual addresses */
static uint64_t at_count[LT_ICOUNT_MAX_SYMS];    /* executions of the instruction at at_addr[i] */
static unsigned n_ats;
static const char *out_path;                     /* NULL: write through qemu_plugin_outs */

static uint64_t ctr[K_NCTR];                     /* class, register and taken counters */
static bool riscv;                               /* guest is RISC-V (else Arm Thumb rules) */

/* cyc=: costs in tenths of a cycle (exact sums); priced[p] once the file names p */
static const char *cyc_path;
static uint64_t cost10[P_N];
static bool priced[P_N];

/* stage=: lt_fw_stage_slots; per-stage counters are the global ones accumulated between marks */
static bool stage_on;
static uint64_t stage_addr;
static unsigned stage_cur;                       /* the stage running now; 0 at the start */
static uint64_t stage_snap[K_NCTR];              /* ctr[] when stage_cur began */
static uint64_t stage_ctr[LT_NSTAGES][K_NCTR];

/* others=N: the N most executed mnemonics of class other */
static unsigned others_n;
static char other_name[LT_MAX_OTHER][24];
static uint64_t other_count[LT_MAX_OTHER + 1];   /* [LT_MAX_OTHER]: names past the table */
static unsigned n_other;

/* One per translated block (blocks are retranslated rarely): where it starts; whether its last
 * instruction is a conditional branch; if its first is a single load, the registers of its
 * address; and for each instruction, where it ends and, for a single load, the register it
 * loads. Kept in a list, freed at exit. */
struct lt_tb_insn {
    uint64_t end;                                /* address after the instruction */
    bool load1;
    char dest[8];
};
struct lt_tb {
    struct lt_tb *next;
    uint64_t start;
    bool ends_cond;
    bool starts_load;
    char first_addr[48];
    size_t n;
    struct lt_tb_insn insn[];                    /* n */
};
static struct lt_tb *tb_list;
static const struct lt_tb *last_tb;              /* the block that ran before this one */
static uint64_t last_total;                      /* total when it started */

/* ---- classification ---- */

struct insn_class {
    int k;              /* K_ALU .. K_OTHER */
    unsigned size;      /* bytes: 2 or 4 */
    unsigned regs;      /* words moved by LDM/STM-like instructions (a D register counts 2) */
    bool load1;         /* a single-register integer load (candidate for load_after_load) */
    char dest[8];       /* its destination register */
    char addr[48];      /* the registers of its address, comma separated */
    char mnem[24];      /* the mnemonic, for others= */
};

static bool in_list(const char *s, const char *const *list)
{
    for (; *list != NULL; list++)
        if (strcmp(s, *list) == 0)
            return true;
    return false;
}

static bool is_cc(const char *s)
{
    static const char *const cc[] = {"eq", "ne", "cs", "hs", "cc", "lo", "mi", "pl", "vs", "vc",
                                     "hi", "ls", "ge", "lt", "gt", "le", "al", NULL};
    return strlen(s) == 2 && in_list(s, cc);
}

/* Thumb mnemonics by class (base forms: no condition, no S, no .w/.n). */
static const char *const t_alu[] = {
    "mov", "mvn", "add", "adc", "sub", "sbc", "rsb", "and", "orr", "orn", "eor", "bic", "cmp",
    "cmn", "tst", "teq", "lsl", "lsr", "asr", "ror", "rrx", "neg", "adr", "addw", "subw", "movw",
    "movt", "ubfx", "sbfx", "bfi", "bfc", "clz", "rbit", "rev", "rev16", "revsh", "sxtb", "sxth",
    "uxtb", "uxth", "sxtab", "sxtah", "uxtab", "uxtah", "sxtb16", "uxtb16", "sxtab16", "uxtab16",
    "ssat", "usat", "ssat16", "usat16", "qadd", "qsub", "qdadd", "qdsub", "qadd8", "qadd16",
    "qsub8", "qsub16", "qasx", "qsax", "sadd8", "sadd16", "ssub8", "ssub16", "sasx", "ssax",
    "uadd8", "uadd16", "usub8", "usub16", "uasx", "usax", "uqadd8", "uqadd16", "uqsub8",
    "uqsub16", "uqasx", "uqsax", "shadd8", "shadd16", "shsub8", "shsub16", "shasx", "shsax",
    "uhadd8", "uhadd16", "uhsub8", "uhsub16", "uhasx", "uhsax", "sel", "pkhbt", "pkhtb", "usad8",
    "nop", "yield", "cpy", "csel", "csinc", "csinv", "csneg", "cset", "csetm", "cinc", "cinv",
    "cneg", "lsll", "lsrl", "asrl", "sqshl", "sqshll", "sqrshr", "sqrshrl", "srshr", "srshrl",
    "uqshl", "uqshll", "uqrshl", "uqrshll", "urshr", "urshrl", NULL};
static const char *const t_mul[] = {
    "mul", "smulbb", "smulbt", "smultb", "smultt", "smulwb", "smulwt", "smmul", "smmulr", "smuad",
    "smuadx", "smusd", "smusdx", NULL};
static const char *const t_mla[] = {
    "mla", "mls", "smlabb", "smlabt", "smlatb", "smlatt", "smlawb", "smlawt", "smlad", "smladx",
    "smlsd", "smlsdx", "smmla", "smmlar", "smmls", "smmlsr", "usada8", NULL};
static const char *const t_mull[] = {
    "smull", "umull", "smlal", "umlal", "umaal", "smlalbb", "smlalbt", "smlaltb", "smlaltt",
    "smlald", "smlaldx", "smlsld", "smlsldx", NULL};
static const char *const t_div[] = {"sdiv", "udiv", NULL};
static const char *const t_load[] = {
    "ldr", "ldrb", "ldrh", "ldrsb", "ldrsh", "ldrt", "ldrbt", "ldrht", "ldrsbt", "ldrsht", "ldrex",
    "ldrexb", "ldrexh", "lda", "ldab", "ldah", "ldaex", "ldaexb", "ldaexh", "pld", "pldw", "pli",
    NULL};
static const char *const t_store[] = {
    "str", "strb", "strh", "strt", "strbt", "strht", "strex", "strexb", "strexh", "stl", "stlb",
    "stlh", "stlex", "stlexb", "stlexh", NULL};
static const char *const t_ldm[] = {
    "ldm", "ldmia", "ldmfd", "ldmdb", "ldmea", "pop", "vldm", "vldmia", "vldmdb", "vpop", NULL};
static const char *const t_stm[] = {
    "stm", "stmia", "stmea", "stmdb", "stmfd", "push", "vstm", "vstmia", "vstmdb", "vpush", NULL};
static const char *const t_jump[] = {"b", "bl", "bx", "blx", "bxns", "blxns", "tbb", "tbh", NULL};
static const char *const t_system[] = {
    "dsb", "dmb", "isb", "wfi", "wfe", "sev", "svc", "bkpt", "mrs", "msr", "cpsid", "cpsie", "udf",
    "sg", "tt", "ttt", "tta", "ttat", "clrex", "clrm", "vscclrm", "dbg", "hlt", "vlldm", "vlstm",
    "vmrs", "vmsr", NULL};
static const char *const t_lob[] = {
    "le", "letp", "dls", "dlstp", "wls", "wlstp", "lctp", "bf", "bfx", "bfl", "bflx", "bfcsel",
    NULL};
static const char *const t_coproc[] = {
    "ldc", "ldc2", "ldcl", "ldc2l", "stc", "stc2", "stcl", "stc2l", "cdp", "cdp2", "mcr", "mcr2",
    "mrc", "mrc2", "mcrr", "mcrr2", "mrrc", "mrrc2", NULL};

/* The Thumb tables and their classes, in lookup order. */
static const struct {
    const char *const *list;
    int k;
} t_tables[] = {{t_alu, K_ALU},   {t_mul, K_MUL},   {t_mla, K_MLA},       {t_mull, K_MULL},
                {t_div, K_DIV},   {t_load, K_LOAD}, {t_store, K_STORE},   {t_ldm, K_LDM},
                {t_stm, K_STM},   {t_jump, K_JUMP}, {t_system, K_SYSTEM}, {t_lob, K_LOB}};

/* Base-form lookup over the Thumb tables; K_OTHER if none. */
static int thumb_base_class(const char *b)
{
    size_t i;
    for (i = 0; i < sizeof t_tables / sizeof t_tables[0]; i++)
        if (in_list(b, t_tables[i].list))
            return t_tables[i].k;
    if (strcmp(b, "ldrd") == 0 || strcmp(b, "ldrexd") == 0 || strcmp(b, "ldaexd") == 0)
        return K_LDM;
    if (strcmp(b, "strd") == 0 || strcmp(b, "strexd") == 0 || strcmp(b, "stlexd") == 0)
        return K_STM;
    if (strcmp(b, "cbz") == 0 || strcmp(b, "cbnz") == 0)
        return K_COND;
    return K_OTHER;
}

/* Words moved by a register list "{r4, r5, lr}", "{r4-r7}", "{d8-d15}": S and core registers
 * count 1, D registers 2. */
static unsigned list_words(const char *ops, bool *has_pc)
{
    const char *p = strchr(ops, '{');
    unsigned words = 0;

    *has_pc = false;
    if (p == NULL)
        return 0;
    for (p++; *p != '\0' && *p != '}';) {
        char a[8], b[8];
        int na = 0, nb = 0;
        unsigned w;
        long ia, ib;

        while (*p == ' ' || *p == ',')
            p++;
        if (*p == '}' || *p == '\0')
            break;
        while (*p != '\0' && *p != ',' && *p != '}' && *p != '-' && *p != ' ' && na < 7)
            a[na++] = *p++;
        a[na] = '\0';
        while (*p == ' ')
            p++;
        b[0] = '\0';
        if (*p == '-') {
            p++;
            while (*p == ' ')
                p++;
            while (*p != '\0' && *p != ',' && *p != '}' && *p != ' ' && nb < 7)
                b[nb++] = *p++;
            b[nb] = '\0';
        }
        while (*p != '\0' && *p != ',' && *p != '}')
            p++;
        if (strcmp(a, "pc") == 0 || strcmp(b, "pc") == 0)
            *has_pc = true;
        w = (a[0] == 'd') ? 2u : 1u;
        if (nb == 0) {
            words += w;
            continue;
        }
        /* a range: r4-r7, s16-s31, d8-d15 (named core registers only at an end: r8-fp) */
        {
            static const char *const named[] = {"sb", "sl", "fp", "ip", "sp", "lr", "pc", NULL};
            const char *const *n;
            ia = (a[0] == 'r' || a[0] == 's' || a[0] == 'd') && a[1] >= '0' && a[1] <= '9'
                     ? strtol(a + 1, NULL, 10) : -1;
            ib = (b[0] == 'r' || b[0] == 's' || b[0] == 'd') && b[1] >= '0' && b[1] <= '9'
                     ? strtol(b + 1, NULL, 10) : -1;
            for (n = named; *n != NULL; n++) {
                if (strcmp(a, *n) == 0) ia = 9 + (n - named);
                if (strcmp(b, *n) == 0) ib = 9 + (n - named);
            }
            if (ia < 0 || ib < ia)
                words += w;                       /* not understood: count one */
            else
                words += w * (unsigned)(ib - ia + 1);
        }
    }
    return words;
}

/* The first operand (destination) and the registers inside [...] (Arm) or (...) (RISC-V). */
static void load_operands(const char *ops, struct insn_class *c)
{
    size_t i = 0;
    const char *p = ops, *q;
    size_t n = 0;
    char open = riscv ? '(' : '[', close = riscv ? ')' : ']';

    while (*p != '\0' && *p != ',' && *p != ' ' && i + 1 < sizeof c->dest)
        c->dest[i++] = *p++;
    c->dest[i] = '\0';
    q = strchr(ops, open);
    if (q == NULL)
        return;
    for (q++; *q != '\0' && *q != close && n + 1 < sizeof c->addr; q++)
        if (*q != ' ' && *q != '#')
            c->addr[n++] = *q;
    c->addr[n] = '\0';
}

/* true if register name r is one of the comma-separated tokens of list */
static bool reg_in(const char *r, const char *list)
{
    size_t n = strlen(r);
    const char *p = list;

    if (n == 0)
        return false;
    while ((p = strstr(p, r)) != NULL) {
        bool start = (p == list || p[-1] == ',');
        bool end = (p[n] == '\0' || p[n] == ',');
        if (start && end)
            return true;
        p += n;
    }
    return false;
}

/* MVE and low-overhead-loop instructions from their encoding, for what capstone 4 prints as
 * ".byte" (or as a coprocessor instruction). hw1, hw2: the two halfwords of a 32-bit Thumb
 * instruction. Patterns from the Armv8.1-M encodings as QEMU decodes them (target/arm/mve.decode,
 * t32.decode). */
static int mve_class(unsigned hw1, unsigned hw2)
{
    if ((hw1 & 0xFF80u) == 0xF000u && (hw2 & 0xD001u) == 0xC001u)
        return hw2 == 0xE801u ? K_MVE_CTL : K_LOB;       /* VCTP; DLS/WLS/LE (+TP) */
    if ((hw1 & 0xFE00u) == 0xEA00u)
        return K_ALU;                                    /* scalar long shifts LSLL, ASRL, ... */
    if ((hw1 & 0xFFE0u) == 0xF380u || (hw1 & 0xFFE0u) == 0xF3E0u)
        return K_SYSTEM;                                 /* MSR/MRS of v8-M registers (MSPLIM) */
    if ((hw1 & 0xEE00u) == 0xEC00u) {                    /* EC ED FC FD: coprocessor ld/st space */
        unsigned coproc = (hw2 >> 8) & 0xFu;
        bool l = (hw1 & 0x0010u) != 0;
        if ((hw1 & 0x01A0u) == 0)
            return K_MVE_ALU;                            /* P=U=W=0: VMOV two lanes <-> GPRs */
        if (coproc == 10u || coproc == 11u)
            return l ? K_FPU_LOAD : K_FPU_STORE;
        return l ? K_MVE_LOAD : K_MVE_STORE;             /* VLDR/VSTR B/H/W, gather, VLD2/4 */
    }
    if ((hw1 & 0xEE00u) == 0xEE00u) {                    /* EE EF FE FF: vector data processing */
        if ((hw1 & 0xFFBFu) == 0xFE31u && (hw2 & 0x1FFFu) == 0x0F4Du)
            return K_MVE_CTL;                            /* VPST, VPNOT */
        if ((hw1 & 0xFFE0u) == 0xEEE0u && (hw2 & 0x0FFFu) == 0x0A10u)
            return (hw1 & 0xFu) == 0xDu ? K_MVE_CTL : K_FPU; /* VMSR/VMRS: P0, or FP registers */
        if ((hw1 & 0xEF81u) == 0xEE01u && (hw2 & 0x0F50u) == 0x0E00u)
            return K_MVE_MUL;                            /* VMULH, VRMULH, VMULL */
        if ((hw1 & 0xEF81u) == 0xEE01u && (hw2 & 0x0F70u) == 0x0E60u)
            return K_MVE_MUL;                            /* VMUL, VQ(R)DMULH by scalar */
        if ((hw1 & 0xEF80u) == 0xEE80u && (hw2 & 0x0E00u) == 0x0E00u)
            return K_MVE_MUL;                            /* VMLADAV / VMLALDAV families */
        return K_MVE_ALU;
    }
    return K_OTHER;
}

static bool has_qreg(const char *ops)
{
    const char *p;
    for (p = ops; *p != '\0'; p++)
        if (*p == 'q' && p[1] >= '0' && p[1] <= '7' && (p == ops || p[-1] == ' ' || p[-1] == ','
                                                        || p[-1] == '{'))
            return true;
    return false;
}

/* Scalar FPU instructions by base mnemonic (vadd.f32 -> vadd); K_FPU for the rest. */
static int fpu_class(const char *v)
{
    static const char *const mac[] = {"vmla", "vmls", "vnmla", "vnmls", "vfma", "vfms", "vfnma",
                                      "vfnms", NULL};
    if (strncmp(v, "vldr", 4) == 0)
        return K_FPU_LOAD;
    if (strncmp(v, "vstr", 4) == 0)
        return K_FPU_STORE;
    if (strcmp(v, "vdiv") == 0 || strcmp(v, "vsqrt") == 0)
        return K_FPU_DIV;
    if (in_list(v, mac))
        return K_FPU_MAC;
    return K_FPU;
}

/* A Thumb instruction (capstone text m ops; raw bytes for what capstone does not know). */
static void classify_thumb(const char *m, const char *ops, const uint8_t *d, size_t size,
                           struct insn_class *c)
{
    char b[24];
    size_t n;
    bool cond = false, pc = false, has_pc = false;
    char *dot;

    snprintf(b, sizeof b, "%s", m);
    n = strlen(b);
    if (n > 2 && b[n - 2] == '.' && (b[n - 1] == 'w' || b[n - 1] == 'n'))
        b[n -= 2] = '\0';                                /* .w / .n width qualifier */

    if (b[0] == '\0' || b[0] == '.' || in_list(b, t_coproc)) {
        c->k = K_OTHER;
        if (size == 4) {
            unsigned hw1 = d[0] | (unsigned)d[1] << 8, hw2 = d[2] | (unsigned)d[3] << 8;
            c->k = mve_class(hw1, hw2);
            if (c->k == K_OTHER)
                snprintf(c->mnem, sizeof c->mnem, ".byte:%04x", hw1);
        }
        return;
    }
    if (size == 4) {                                     /* LOB first: capstone may print BLX */
        unsigned hw1 = d[0] | (unsigned)d[1] << 8, hw2 = d[2] | (unsigned)d[3] << 8;
        if ((hw1 & 0xFF80u) == 0xF000u && (hw2 & 0xD001u) == 0xC001u) {
            c->k = mve_class(hw1, hw2);
            return;
        }
    }
    if (b[0] == 'i' && b[1] == 't' && strspn(b + 2, "te") == strlen(b + 2)) {
        c->k = K_IT;
        return;
    }

    if (b[0] == 'v') {                                   /* FPU and MVE */
        char v[24];
        snprintf(v, sizeof v, "%s", b);
        dot = strchr(v, '.');
        if (dot != NULL)
            *dot = '\0';                                 /* vadd.f32 -> vadd */
        if (strcmp(v, "vpst") == 0 || strcmp(v, "vpnot") == 0 || strcmp(v, "vctp") == 0) {
            c->k = K_MVE_CTL;
            return;
        }
        if (in_list(v, t_ldm) || in_list(v, t_stm)) {
            c->k = in_list(v, t_ldm) ? K_LDM : K_STM;
            c->regs = list_words(ops, &has_pc);
            return;
        }
        if (in_list(v, t_system)) {                      /* vmrs/vmsr: FPU status moves */
            c->k = (strcmp(v, "vmrs") == 0 || strcmp(v, "vmsr") == 0) ? K_FPU : K_SYSTEM;
            return;
        }
        if (has_qreg(ops)) {
            if (strncmp(v, "vld", 3) == 0)
                c->k = K_MVE_LOAD;
            else if (strncmp(v, "vst", 3) == 0)
                c->k = K_MVE_STORE;
            else if (strstr(v, "mul") != NULL || strstr(v, "ml") != NULL ||
                     strstr(v, "fma") != NULL || strstr(v, "fms") != NULL)
                c->k = K_MVE_MUL;
            else
                c->k = K_MVE_ALU;
            return;
        }
        c->k = fpu_class(v);
        n = strlen(v);
        if (c->k == K_FPU && n > 3 && is_cc(v + n - 2)) {
            v[n - 2] = '\0';                             /* vmlaeq -> vmla; vmls stays */
            c->k = fpu_class(v);
        }
        return;
    }

    /* integer: exact base, b<cc>, then base with a condition and/or an S suffix */
    c->k = thumb_base_class(b);
    if (c->k == K_OTHER && b[0] == 'b' && is_cc(b + 1)) {
        c->k = K_COND;                                   /* b<cc> (b + ls, not bl + s) */
        return;
    }
    if (c->k == K_OTHER) {
        n = strlen(b);
        if (n > 2 && is_cc(b + n - 2)) {
            char t[24];
            snprintf(t, sizeof t, "%.*s", (int)(n - 2), b);
            c->k = thumb_base_class(t);
            if (c->k == K_OTHER && n > 3 && t[n - 3] == 's') {
                t[n - 3] = '\0';
                c->k = thumb_base_class(t);
            }
            if (c->k != K_OTHER) {
                cond = true;
                snprintf(b, sizeof b, "%s", t);
            }
        }
        if (c->k == K_OTHER && n > 1 && b[n - 1] == 's') {
            b[n - 1] = '\0';
            c->k = thumb_base_class(b);
        }
    }
    if (c->k == K_OTHER)
        return;

    /* registers moved, PC writes */
    if (c->k == K_LDM || c->k == K_STM) {
        if (strchr(ops, '{') != NULL)
            c->regs = list_words(ops, &has_pc);
        else
            c->regs = 2;                                 /* ldrd/strd: two words */
        pc = has_pc && c->k == K_LDM;
    } else if (c->k == K_LOAD) {
        load_operands(ops, c);
        pc = strcmp(c->dest, "pc") == 0;
        c->load1 = !pc && strcmp(b, "pld") != 0 && strcmp(b, "pldw") != 0 && strcmp(b, "pli") != 0;
    } else if (c->k == K_ALU) {
        pc = strncmp(ops, "pc,", 3) == 0;                /* mov pc, rX / add pc, ... */
    } else if (c->k == K_JUMP) {
        pc = true;
    }
    if (pc)
        c->k = cond ? K_COND : K_JUMP;                   /* IT-predicated: popne {.., pc}, bxeq */
}

/* RISC-V (QEMU's own disassembler: pseudo-instructions, compressed shown expanded). */
static void classify_riscv(const char *m, const char *ops, struct insn_class *c)
{
    static const char *const alu[] = {
        "add", "addi", "sub", "lui", "auipc", "and", "andi", "or", "ori", "xor", "xori", "sll",
        "slli", "srl", "srli", "sra", "srai", "slt", "slti", "sltu", "sltiu", "mv", "li", "not",
        "neg", "seqz", "snez", "sltz", "sgtz", "nop", "addw", "addiw", "subw", NULL};
    static const char *const cond[] = {
        "beq", "bne", "blt", "bge", "bltu", "bgeu", "beqz", "bnez", "blez", "bgez", "bltz", "bgtz",
        "bgt", "ble", "bgtu", "bleu", NULL};
    static const char *const jump[] = {"jal", "jalr", "j", "jr", "ret", "call", "tail", NULL};
    static const char *const sys[] = {
        "csrrw", "csrrs", "csrrc", "csrrwi", "csrrsi", "csrrci", "csrr", "csrw", "csrs", "csrc",
        "csrwi", "csrsi", "csrci", "ecall", "ebreak", "fence", "fence.i", "wfi", "mret", "sret",
        "unimp", NULL};
    const char *b = strncmp(m, "c.", 2) == 0 ? m + 2 : m;

    if (in_list(b, alu)) c->k = K_ALU;
    else if (strcmp(b, "mul") == 0) c->k = K_MUL;
    else if (strncmp(b, "mulh", 4) == 0) c->k = K_MULL;
    else if (in_list(b, (const char *const[]){"div", "divu", "rem", "remu", NULL})) c->k = K_DIV;
    else if (in_list(b, (const char *const[]){"lb", "lh", "lw", "lbu", "lhu", "lwsp", NULL})) {
        c->k = K_LOAD;
        load_operands(ops, c);
        c->load1 = true;
    } else if (in_list(b, (const char *const[]){"sb", "sh", "sw", "swsp", NULL})) c->k = K_STORE;
    else if (in_list(b, cond)) c->k = K_COND;
    else if (in_list(b, jump)) c->k = K_JUMP;
    else if (in_list(b, sys)) c->k = K_SYSTEM;
    else if (strncmp(b, "lr.", 3) == 0) c->k = K_LOAD;
    else if (strncmp(b, "sc.", 3) == 0 || strncmp(b, "amo", 3) == 0) c->k = K_STORE;
    else c->k = K_OTHER;
}

/* The instruction's own length from its first bytes. qemu_plugin_insn_size() can be 2 more: QEMU
 * 7.2's Thumb translator reads the next halfword near the end of a page (to see whether the next
 * instruction crosses it) and the read is appended to the current instruction's bytes. */
static unsigned insn_length(const uint8_t *d, size_t size)
{
    unsigned n;

    if (size < 4)
        return (unsigned)size;
    if (riscv)
        n = (d[0] & 3u) == 3u ? 4u : 2u;                /* RVC: low bits not 11 */
    else
        n = (d[1] >> 3) >= 0x1Du ? 4u : 2u;             /* Thumb: 0b11101/11110/11111 = 32-bit */
    return n;
}

/* Classifies one instruction; *prev is the previous instruction of the same block (or NULL). */
static void classify(struct qemu_plugin_insn *insn, const struct insn_class *prev,
                     struct insn_class *c)
{
    char *text = qemu_plugin_insn_disas(insn);
    const uint8_t *d = qemu_plugin_insn_data(insn);
    size_t size = insn_length(d, qemu_plugin_insn_size(insn));
    char m[24];
    const char *p = text != NULL ? text : "", *ops;
    size_t i = 0;

    memset(c, 0, sizeof *c);
    c->size = (unsigned)size;
    while (*p == ' ')
        p++;
    /* QEMU's RISC-V disassembler starts with the instruction's hex ("0791  addi ...") */
    if (riscv && strspn(p, "0123456789abcdef") == 2 * size &&
        (p[2 * size] == ' ' || p[2 * size] == '\t'))
        p += 2 * size;
    while (*p == ' ' || *p == '\t')
        p++;
    while (*p != '\0' && *p != ' ' && *p != '\t' && i + 1 < sizeof m)
        m[i++] = *p++;
    m[i] = '\0';
    ops = p;
    while (*ops == ' ' || *ops == '\t')
        ops++;
    snprintf(c->mnem, sizeof c->mnem, "%s", m[0] != '\0' ? m : "(none)");
    if (riscv)
        classify_riscv(m, ops, c);
    else
        classify_thumb(m, ops, d, size, c);
    free(text);

    /* a load right after a load whose result it does not need for its address pipelines on
     * Cortex-M4 (TRM 3.3.2: N loads in N + 1 cycles) */
    if (c->k == K_LOAD && c->load1 && prev != NULL && prev->load1 &&
        (prev->k == K_LOAD || prev->k == K_LOAD2) && !reg_in(prev->dest, c->addr))
        c->k = K_LOAD2;
}

/* ---- callbacks ---- */

static void close_stage(void)
{
    unsigned i;
    for (i = 0; i < K_NCTR; i++) {
        stage_ctr[stage_cur][i] += ctr[i] - stage_snap[i];
        stage_snap[i] = ctr[i];
    }
}

/* The store in lt_fw_stage (lt_fw_stage_slots[k] = k): stage k begins after it. The store's own
 * inline adds ran before it, so it belongs to the stage it ends. */
static void on_stage_store(unsigned int vcpu, qemu_plugin_meminfo_t info, uint64_t vaddr,
                           void *udata)
{
    (void)vcpu;
    (void)info;
    (void)udata;
    if (vaddr < stage_addr || vaddr - stage_addr >= 4u * LT_NSTAGES)
        return;
    close_stage();
    stage_cur = (unsigned)((vaddr - stage_addr) / 4u);
}

/* Start of every block. The previous block ran up to the instruction whose inline add was the
 * last to run (the total's step since it began): all of it, or less when an exception or an
 * -icount I/O restart cut it short. (1) If it ran to its final conditional branch, the branch was
 * taken if this block does not start right after it. (2) A load that begins this block right
 * after a load that the previous block ended with, reached by falling through, is a
 * load_after_load like a pair inside one block: so the count does not depend on where QEMU
 * splits blocks (-icount I/O restarts, -singlestep). */
static void on_tb_exec(unsigned int vcpu, void *udata)
{
    const struct lt_tb *tb = udata, *prev = last_tb;
    uint64_t ran = total - last_total;           /* instructions of prev that began */

    (void)vcpu;
    if (prev != NULL && ran >= 1 && ran <= prev->n) {
        const struct lt_tb_insn *last = &prev->insn[ran - 1];
        if (ran == prev->n && prev->ends_cond && tb->start != last->end)
            ctr[K_TAKEN]++;
        if (last->load1 && tb->starts_load && last->end == tb->start &&
            !reg_in(last->dest, tb->first_addr))
            ctr[K_LOAD2_X]++;
    }
    last_tb = tb;
    last_total = total;
}

static uint64_t *other_counter(const char *name)
{
    unsigned i;
    for (i = 0; i < n_other; i++)
        if (strcmp(other_name[i], name) == 0)
            return &other_count[i];
    if (n_other == LT_MAX_OTHER)
        return &other_count[LT_MAX_OTHER];
    snprintf(other_name[n_other], sizeof other_name[0], "%s", name);
    return &other_count[n_other++];
}

/* Counting per instruction rather than adding n_insns once per block keeps the total exact when a
 * block stops early: under -icount an MMIO access mid-block restarts from that instruction in a
 * new block that QEMU does not instrument for execution (CF_MEMI_ONLY), so nothing is counted
 * twice. A block-level add would count the block's tail twice. */
static void on_tb_trans(qemu_plugin_id_t id, struct qemu_plugin_tb *tb)
{
    size_t n = qemu_plugin_tb_n_insns(tb);
    size_t i;
    unsigned k;
    struct lt_tb *t = calloc(1, sizeof *t + n * sizeof t->insn[0]);
    struct insn_class cls[2];

    (void)id;
    if (t == NULL) {
        fprintf(stderr, "lt_icount: out of memory\n");
        abort();
    }
    t->start = qemu_plugin_tb_vaddr(tb);
    t->n = n;
    t->next = tb_list;
    tb_list = t;
    for (i = 0; i < n; i++) {
        struct qemu_plugin_insn *insn = qemu_plugin_tb_get_insn(tb, i);
        struct insn_class *c = &cls[i & 1];
        const char *sym;

        qemu_plugin_register_vcpu_insn_exec_inline(insn, QEMU_PLUGIN_INLINE_ADD_U64, &total, 1);
        classify(insn, i > 0 ? &cls[(i - 1) & 1] : NULL, c);
        qemu_plugin_register_vcpu_insn_exec_inline(insn, QEMU_PLUGIN_INLINE_ADD_U64, &ctr[c->k], 1);
        if (c->regs != 0 && (c->k == K_LDM || c->k == K_STM || c->k == K_JUMP || c->k == K_COND))
            qemu_plugin_register_vcpu_insn_exec_inline(
                insn, QEMU_PLUGIN_INLINE_ADD_U64,
                &ctr[c->k == K_STM ? K_STM_REG : K_LDM_REG], c->regs);
        if (c->k == K_OTHER && others_n != 0)
            qemu_plugin_register_vcpu_insn_exec_inline(insn, QEMU_PLUGIN_INLINE_ADD_U64,
                                                       other_counter(c->mnem), 1);
        if (i == 0 && c->k == K_LOAD && c->load1) {
            t->starts_load = true;
            memcpy(t->first_addr, c->addr, sizeof t->first_addr);
        }
        t->insn[i].end = qemu_plugin_insn_vaddr(insn) + c->size;
        t->insn[i].load1 = (c->k == K_LOAD || c->k == K_LOAD2) && c->load1;
        memcpy(t->insn[i].dest, c->dest, sizeof t->insn[i].dest);
        if (i == n - 1)
            t->ends_cond = c->k == K_COND;
        if (n_ats != 0) {
            uint64_t va = qemu_plugin_insn_vaddr(insn);
            for (k = 0; k < n_ats; k++)
                if (va == at_addr[k])
                    qemu_plugin_register_vcpu_insn_exec_inline(insn, QEMU_PLUGIN_INLINE_ADD_U64,
                                                               &at_count[k], 1);
        }
        if (n_syms == 0 && !stage_on)
            continue;
        sym = qemu_plugin_insn_symbol(insn);
        if (sym == NULL)
            continue;
        if (stage_on && (c->k == K_STORE || c->k == K_STM) && strcmp(sym, "lt_fw_stage") == 0)
            qemu_plugin_register_vcpu_mem_cb(insn, on_stage_store, QEMU_PLUGIN_CB_NO_REGS,
                                             QEMU_PLUGIN_MEM_W, NULL);
        /* No break: a name given twice gets both counters. */
        for (k = 0; k < n_syms; k++)
            if (strcmp(sym, sym_name[k]) == 0)
                qemu_plugin_register_vcpu_insn_exec_inline(insn, QEMU_PLUGIN_INLINE_ADD_U64,
                                                           &sym_count[k], 1);
    }
    qemu_plugin_register_vcpu_tb_exec_cb(tb, on_tb_exec, QEMU_PLUGIN_CB_NO_REGS, t);
}

/* ---- cost file ---- */

/* "12", "1.5": tenths of a cycle; false if not a decimal with at most one digit after the point
 * or above 100000 cycles */
static bool parse_tenths(const char *s, uint64_t *t)
{
    uint64_t v = 0;
    size_t digits = 0;

    for (; *s >= '0' && *s <= '9'; s++, digits++) {
        v = v * 10u + (uint64_t)(*s - '0');
        if (v > 100000u)
            return false;
    }
    v *= 10u;
    if (*s == '.') {
        s++;
        if (*s < '0' || *s > '9')
            return false;
        v += (uint64_t)(*s++ - '0');
        digits++;
    }
    if (*s != '\0' || digits == 0)
        return false;
    *t = v;
    return true;
}

/* The next blank-separated token of s (terminated in place), *rest after it; NULL if none. */
static char *next_token(char *s, char **rest)
{
    char *t;

    while (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\n')
        s++;
    if (*s == '\0') {
        *rest = s;
        return NULL;
    }
    t = s;
    while (*s != '\0' && *s != ' ' && *s != '\t' && *s != '\r' && *s != '\n')
        s++;
    if (*s != '\0')
        *s++ = '\0';
    *rest = s;
    return t;
}

static int load_costs(const char *path)
{
    FILE *f = fopen(path, "r");
    char line[512];
    unsigned lineno = 0;
    int p, err = 0;

    if (f == NULL) {
        fprintf(stderr, "lt_icount: cyc=%s: cannot open: %s\n", path, strerror(errno));
        return 1;
    }
    while (err == 0 && fgets(line, sizeof line, f) != NULL) {
        char *hash, *name, *val, *extra, *rest;

        lineno++;
        if (strchr(line, '\n') == NULL && !feof(f)) {
            fprintf(stderr, "lt_icount: %s:%u: line too long\n", path, lineno);
            err = 1;
            break;
        }
        hash = strchr(line, '#');
        if (hash != NULL)
            *hash = '\0';
        name = next_token(line, &rest);
        if (name == NULL)
            continue;
        val = next_token(rest, &rest);
        extra = next_token(rest, &rest);
        if (val == NULL || extra != NULL) {
            fprintf(stderr, "lt_icount: %s:%u: want 'CLASS CYCLES'\n", path, lineno);
            err = 1;
            break;
        }
        for (p = 0; p < P_N && strcmp(name, price_name[p]) != 0; p++)
            ;
        if (p == P_N) {
            fprintf(stderr, "lt_icount: %s:%u: unknown class '%s' (known:", path, lineno, name);
            for (p = 0; p < P_N; p++)
                fprintf(stderr, " %s", price_name[p]);
            fprintf(stderr, ")\n");
            err = 1;
        } else if (priced[p]) {
            fprintf(stderr, "lt_icount: %s:%u: class '%s' priced twice\n", path, lineno, name);
            err = 1;
        } else if (!parse_tenths(val, &cost10[p])) {
            fprintf(stderr,
                    "lt_icount: %s:%u: '%s' is not a number of cycles (decimal, at most one "
                    "digit after the point, at most 100000)\n", path, lineno, val);
            err = 1;
        } else {
            priced[p] = true;
        }
    }
    if (err == 0 && ferror(f)) {
        fprintf(stderr, "lt_icount: cyc=%s: read error\n", path);
        err = 1;
    }
    fclose(f);
    return err;
}

/* ---- output ---- */

static void fmt_tenths(char *buf, size_t n, uint64_t t)
{
    if (t % 10u == 0)
        snprintf(buf, n, "%llu", (unsigned long long)(t / 10u));
    else
        snprintf(buf, n, "%llu.%u", (unsigned long long)(t / 10u), (unsigned)(t % 10u));
}

/* cycles of counters c in tenths; false if an executed price is missing */
static bool cycles_of(const uint64_t *c, uint64_t *t)
{
    int p;
    bool ok = true;

    *t = 0;
    for (p = 0; p < P_N; p++) {
        uint64_t cnt = price_count(c, p);
        if (cnt == 0)
            continue;
        if (!priced[p])
            ok = false;
        else
            *t += cnt * cost10[p];
    }
    return ok;
}

static void emit(FILE *f, const char *line)
{
    if (f != NULL)
        fputs(line, f);
    else
        qemu_plugin_outs(line);
}

static void on_atexit(qemu_plugin_id_t id, void *userdata)
{
    char line[256], num[32];
    FILE *f = NULL;
    unsigned k;
    int p;
    uint64_t cyc10;
    bool model, complete = false;
    struct lt_tb *t;

    (void)id;
    (void)userdata;
    close_stage();
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
        emit(f, line);
    }

    model = cyc_path != NULL;
    if (model) {
        complete = cycles_of(ctr, &cyc10);
        if (complete) {
            fmt_tenths(num, sizeof num, cyc10);
            snprintf(line, sizeof line, "icount cycles %s\n", num);
            emit(f, line);
        } else {
            for (p = 0; p < P_N; p++)
                if (price_count(ctr, p) != 0 && !priced[p]) {
                    snprintf(line, sizeof line, "icount error unpriced class %s\n",
                             price_name[p]);
                    emit(f, line);
                    fprintf(stderr, "lt_icount: %s: executed class %s has no price\n", cyc_path,
                            price_name[p]);
                }
        }
    }
    for (p = 0; p < P_N; p++) {
        uint64_t cnt = price_count(ctr, p);
        if (cnt == 0)
            continue;
        if (complete) {
            fmt_tenths(num, sizeof num, cnt * cost10[p]);
            snprintf(line, sizeof line, "icount %s %s %llu %s\n",
                     is_reg_price(p) ? "regs" : "class", price_name[p], (unsigned long long)cnt,
                     num);
        } else {
            snprintf(line, sizeof line, "icount %s %s %llu\n", is_reg_price(p) ? "regs" : "class",
                     price_name[p], (unsigned long long)cnt);
        }
        emit(f, line);
    }
    for (k = 0; k < LT_NSTAGES; k++) {
        uint64_t insns = 0;
        unsigned j;
        for (j = 0; j < K_NCLASS; j++)
            insns += stage_ctr[k][j];
        if (insns == 0)
            continue;
        if (complete) {
            cycles_of(stage_ctr[k], &cyc10);
            fmt_tenths(num, sizeof num, cyc10);
            snprintf(line, sizeof line, "icount stage %u insns %llu cycles %s\n", k,
                     (unsigned long long)insns, num);
        } else {
            snprintf(line, sizeof line, "icount stage %u insns %llu\n", k,
                     (unsigned long long)insns);
        }
        emit(f, line);
    }
    for (k = 0; k < others_n; k++) {                 /* the others= most executed, by count */
        unsigned j, best = LT_MAX_OTHER + 1;
        for (j = 0; j < n_other; j++)
            if (other_count[j] != 0 && (best > LT_MAX_OTHER || other_count[j] > other_count[best]))
                best = j;
        if (best > LT_MAX_OTHER)
            break;
        snprintf(line, sizeof line, "icount other %s %llu\n", other_name[best],
                 (unsigned long long)other_count[best]);
        emit(f, line);
        other_count[best] = 0;
    }
    if (others_n != 0 && other_count[LT_MAX_OTHER] != 0) {
        snprintf(line, sizeof line, "icount other (more) %llu\n",
                 (unsigned long long)other_count[LT_MAX_OTHER]);
        emit(f, line);
    }
    if (f != NULL && fclose(f) != 0)
        fprintf(stderr, "lt_icount: error writing out=%s\n", out_path);
    while (tb_list != NULL) {
        t = tb_list->next;
        free(tb_list);
        tb_list = t;
    }
    last_tb = NULL;
}

/* hexadecimal, 0x optional, as objdump and nm print addresses */
static bool parse_hex(const char *s, uint64_t *v)
{
    char *end;
    if (*s == '\0')
        return false;
    *v = strtoull(s, &end, 16);
    return *end == '\0';
}

/* QEMU 7.2 passes each "-plugin FILE,name=value" option as the string "name=value"; the deprecated
 * "arg=name=value" form arrives as "name=value" too. */
int qemu_plugin_install(qemu_plugin_id_t id, const qemu_info_t *info, int argc, char **argv)
{
    int i;

    riscv = info != NULL && info->target_name != NULL &&
            strncmp(info->target_name, "riscv", 5) == 0;
    for (i = 0; i < argc; i++) {
        const char *a = argv[i];

        if (strncmp(a, "sym=", 4) == 0 && a[4] != '\0') {
            if (n_syms == LT_ICOUNT_MAX_SYMS) {
                fprintf(stderr, "lt_icount: more than %d sym= arguments\n", LT_ICOUNT_MAX_SYMS);
                return 1;
            }
            sym_name[n_syms++] = a + 4;
        } else if (strncmp(a, "at=", 3) == 0 && a[3] != '\0') {
            if (n_ats == LT_ICOUNT_MAX_SYMS) {
                fprintf(stderr, "lt_icount: more than %d at= arguments\n", LT_ICOUNT_MAX_SYMS);
                return 1;
            }
            if (!parse_hex(a + 3, &at_addr[n_ats])) {
                fprintf(stderr, "lt_icount: at=%s is not a hexadecimal address\n", a + 3);
                return 1;
            }
            n_ats++;
        } else if (strncmp(a, "out=", 4) == 0 && a[4] != '\0') {
            out_path = a + 4;
        } else if (strncmp(a, "cyc=", 4) == 0 && a[4] != '\0') {
            cyc_path = a + 4;
        } else if (strncmp(a, "stage=", 6) == 0 && a[6] != '\0') {
            if (!parse_hex(a + 6, &stage_addr)) {
                fprintf(stderr, "lt_icount: stage=%s is not a hexadecimal address\n", a + 6);
                return 1;
            }
            stage_on = true;
        } else if (strncmp(a, "others=", 7) == 0 && a[7] != '\0') {
            char *end;
            unsigned long v = strtoul(a + 7, &end, 10);
            if (*end != '\0' || v > LT_MAX_OTHER) {
                fprintf(stderr, "lt_icount: others=%s is not a count 0..%d\n", a + 7,
                        LT_MAX_OTHER);
                return 1;
            }
            others_n = (unsigned)v;
        } else {
            fprintf(stderr,
                    "lt_icount: unknown argument '%s' (want sym=NAME, at=ADDR, out=PATH, "
                    "cyc=PATH, stage=ADDR or others=N)\n", a);
            return 1;
        }
    }
    if (cyc_path != NULL && load_costs(cyc_path) != 0)
        return 1;
    qemu_plugin_register_vcpu_tb_trans_cb(id, on_tb_trans);
    qemu_plugin_register_atexit_cb(id, on_atexit, NULL);
    return 0;
}
