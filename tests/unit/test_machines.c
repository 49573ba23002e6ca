/* test_machines.c: cmocka unit tests of the machine models (sim/machines/<name>.def, one file per
 * machine, listed by the Makefile in $(B)/gen/lt_machines.inc). An independent reading of the
 * files through sim/lt_machines.h checks every machine: name, description, clock > 0, lanes > 0,
 * an L1 spec, cache specs of the form sets:ways:line, every op of lt_ops.def priced exactly once;
 * spot values of lrb16 as it was before the machines became data files, of mcu-m4 and mcu-m55
 * (their unfitted rows; the fitted ones are checked by tests/run.d/fwcycles.sh) and of rv32imac
 * (the integer-only machine: float32 in soft float dearer than s15.16); the machine
 * names every build knows (scene-file validator, lt_meter.h); and, in the sim build, that the
 * simulator's table equals the files field by field, that its cache specs parse and that every
 * machine initialises. Builds: host, sim, asan (the sim-only part is under LT_COST_SIM).
 */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lt/lt.h"
#include "lt_meter.h"
#include "io/lt_scenefile.h"
#if LT_COST_MODE == LT_COST_SIM
#include "lt_cache.h"
#include "lt_sim.h"
#endif

/* ---- the files, read here independently of sim/lt_sim.c --------------------------------------- */

typedef struct tm_machine {
    const char *id, *name, *desc;
    long clock_mhz, lanes;
    int ncache;                       /* LT_MACHINE_CACHE lines */
    const char *l1, *l2;
    long l1_hit, l2_hit, mem;
    int nmem;                         /* LT_MACHINE_MEM lines */
    int seen[LT_OP__COUNT];           /* LT_OP_COST lines per op */
    long latency[LT_OP__COUNT], issue[LT_OP__COUNT];
} tm_machine_t;

#define TM_MAX 64
static tm_machine_t tm[TM_MAX];
static int ntm;

static void tm_begin(const char *id, const char *name, const char *desc, long mhz, long lanes)
{
    tm_machine_t *m;
    assert_true(ntm < TM_MAX);
    m = &tm[ntm++];
    memset(m, 0, sizeof *m);
    m->id = id;
    m->name = name;
    m->desc = desc;
    m->clock_mhz = mhz;
    m->lanes = lanes;
}

static void tm_cache(int level, const char *spec, long hit)
{
    tm_machine_t *m = &tm[ntm - 1];
    m->ncache++;
    if (level == 1) {
        m->l1 = spec;
        m->l1_hit = hit;
    } else {
        m->l2 = spec;
        m->l2_hit = hit;
    }
}

static void tm_mem(long cycles)
{
    tm[ntm - 1].mem = cycles;
    tm[ntm - 1].nmem++;
}

static void tm_op(int op, long lat, long iss)
{
    tm_machine_t *m = &tm[ntm - 1];
    m->seen[op]++;
    m->latency[op] = lat;
    m->issue[op] = iss;
}

static void tm_read(void)
{
    ntm = 0;
#define TM_LEVEL_L1 1
#define TM_LEVEL_L2 2
#define LT_MACHINE(id, name, desc, mhz, lanes) tm_begin(#id, name, desc, mhz, lanes);
#define LT_MACHINE_CACHE(level, spec, hit) tm_cache(TM_LEVEL_##level, spec, hit);
#define LT_MACHINE_MEM(cycles) tm_mem(cycles);
#define LT_OP_COST(op, lat, iss) tm_op(LT_OP_##op, lat, iss);
#include "lt_machines.h"
}

static const tm_machine_t *tm_find(const char *name)
{
    int i;
    for (i = 0; i < ntm; i++)
        if (strcmp(tm[i].name, name) == 0)
            return &tm[i];
    return NULL;
}

/* "sets:ways:line", each a positive number */
static int spec_ok(const char *s)
{
    unsigned a, b, c;
    char x;
    return s != NULL && sscanf(s, "%u:%u:%u%c", &a, &b, &c, &x) == 3 && a > 0 && b > 0 && c > 0;
}

/* ---- every machine ----------------------------------------------------------------------------- */

static void test_every_machine_complete(void **state)
{
    int i, j, o;
    (void)state;
    tm_read();
    assert_true(ntm >= 2);
    for (i = 0; i < ntm; i++) {
        const tm_machine_t *m = &tm[i];
        char what[160];
        snprintf(what, sizeof what, "sim/machines: %s (\"%s\")", m->id, m->name);
        if (m->name == NULL || m->name[0] == '\0' || strlen(m->name) >= 32)
            fail_msg("%s: name empty or longer than 31 characters", what);
        if (m->desc == NULL || m->desc[0] == '\0')
            fail_msg("%s: no description", what);
        if (m->clock_mhz <= 0 || m->lanes <= 0)
            fail_msg("%s: clock %ld MHz, %ld lanes", what, m->clock_mhz, m->lanes);
        if (!spec_ok(m->l1))
            fail_msg("%s: L1 spec '%s' is not sets:ways:line", what, m->l1 ? m->l1 : "(none)");
        if (m->l2 != NULL && !spec_ok(m->l2))
            fail_msg("%s: L2 spec '%s' is not sets:ways:line", what, m->l2);
        if (m->ncache < 1 || m->ncache > 2 || m->nmem != 1)
            fail_msg("%s: %d LT_MACHINE_CACHE, %d LT_MACHINE_MEM lines", what, m->ncache, m->nmem);
        if (m->l1_hit <= 0 || m->mem <= 0 || m->l2_hit < 0)
            fail_msg("%s: latencies L1 %ld, L2 %ld, memory %ld", what, m->l1_hit, m->l2_hit,
                     m->mem);
        for (o = 0; o < LT_OP__COUNT; o++) {
            if (m->seen[o] != 1)
                fail_msg("%s: op %d priced %d times", what, o, m->seen[o]);
            if (m->latency[o] < 1 || m->issue[o] < 1 || m->latency[o] > 65535 ||
                m->issue[o] > 65535)
                fail_msg("%s: op %d latency %ld issue %ld (1..65535)", what, o, m->latency[o],
                         m->issue[o]);
        }
        for (j = 0; j < i; j++)
            if (strcmp(tm[j].name, m->name) == 0)
                fail_msg("%s: name also used by %s", what, tm[j].id);
    }
    printf("machines: %d files, each with %d op prices\n", ntm, (int)LT_OP__COUNT);
}

/* The values of lrb16 before it became a data file (sim/lt_sim.c machines_fill), and the MCUs'. */
static void test_known_values(void **state)
{
    const tm_machine_t *m;
    (void)state;
    tm_read();
    m = tm_find("lrb16");
    assert_non_null(m);
    assert_string_equal(m->desc, "Larrabee-like core: 1 GHz, in-order, 16 lanes, L1 32 KiB 8-way, "
                                 "L2 256 KiB 8-way");
    assert_int_equal(m->clock_mhz, 1000);
    assert_int_equal(m->lanes, 16);
    assert_string_equal(m->l1, "64:8:64");
    assert_string_equal(m->l2, "512:8:64");
    assert_int_equal(m->l1_hit, 3);
    assert_int_equal(m->l2_hit, 14);
    assert_int_equal(m->mem, 150);
    assert_int_equal(m->latency[LT_OP_SMUL], 3);
    assert_int_equal(m->issue[LT_OP_SMUL], 1);
    assert_int_equal(m->issue[LT_OP_SDIV], 20);
    assert_int_equal(m->latency[LT_OP_VMUL], 4);
    assert_int_equal(m->issue[LT_OP_VMUL], 2);
    assert_int_equal(m->latency[LT_OP_VMULW], 1);
    assert_int_equal(m->issue[LT_OP_VMULW], 2);
    assert_int_equal(m->latency[LT_OP_VSQRT], 40);
    assert_int_equal(m->issue[LT_OP_VSQRT], 20);
    assert_int_equal(m->latency[LT_OP_FDIV], 20);
    assert_int_equal(m->issue[LT_OP_FDIV], 8);
    assert_int_equal(m->issue[LT_OP_VRED], 4);
    assert_int_equal(m->latency[LT_OP_VGATHER], 3);

    /* mcu-m4: its integer rows are fitted (tools/fw_cycles.sh --fit; tests/run.d/fwcycles.sh
     * checks that a refit gives them), its float rows and VSQRT/VSCATTER are opcal.sh's */
    m = tm_find("mcu-m4");
    assert_non_null(m);
    assert_string_equal(m->id, "mcu_m4");
    assert_string_equal(m->desc, "Cortex-M4F MCU: 168 MHz, scalar (16-lane ops cost their loops), "
                                 "no data cache");
    assert_int_equal(m->clock_mhz, 168);
    assert_int_equal(m->lanes, 1);
    assert_string_equal(m->l1, "1:1:4"); /* SRAM: a 1-line cache whose miss costs a hit */
    assert_null(m->l2);
    assert_int_equal(m->l1_hit, 1);
    assert_int_equal(m->l2_hit, 1);
    assert_int_equal(m->mem, 1);
    assert_int_equal(m->issue[LT_OP_VSQRT], 1600);
    assert_int_equal(m->issue[LT_OP_VSCATTER], 26);
    assert_int_equal(m->issue[LT_OP_FMUL], 144);
    assert_true(m->issue[LT_OP_SALU] >= 1 && m->issue[LT_OP_VMUL] > m->issue[LT_OP_SMUL]);
    assert_int_equal(m->latency[LT_OP_VMUL], m->issue[LT_OP_VMUL]);

    /* mcu-m55 (Helium): fitted as mcu-m4; four lanes; its 16-lane products cheaper than
     * mcu-m4's, which loops over them one lane at a time */
    m = tm_find("mcu-m55");
    assert_non_null(m);
    assert_string_equal(m->id, "mcu_m55");
    assert_int_equal(m->clock_mhz, 400);
    assert_int_equal(m->lanes, 4);
    assert_string_equal(m->l1, "1:1:4");
    assert_null(m->l2);
    assert_true(m->issue[LT_OP_VMUL] < tm_find("mcu-m4")->issue[LT_OP_VMUL]);

    /* rv32imac (sim/machines/rv32imac.def, tests/bench/opcal.sh rv32): scalar, SRAM, and the
     * trade's other side: every float op class dearer than the s15.16 op it replaces */
    m = tm_find("rv32imac");
    assert_non_null(m);
    assert_string_equal(m->id, "rv32imac");
    assert_non_null(strstr(m->desc, "soft float"));
    assert_int_equal(m->clock_mhz, 320);
    assert_int_equal(m->lanes, 1);
    assert_string_equal(m->l1, "1:1:4");
    assert_null(m->l2);
    assert_int_equal(m->l1_hit, 1);
    assert_int_equal(m->mem, 1);
    assert_int_equal(m->issue[LT_OP_FADD], 1062);
    assert_int_equal(m->issue[LT_OP_FMUL], 2055);
    assert_int_equal(m->issue[LT_OP_FDIV], 1233);
    assert_int_equal(m->issue[LT_OP_FCMP], 594);
    assert_true(m->issue[LT_OP_FADD] > m->issue[LT_OP_VALU]);
    assert_true(m->issue[LT_OP_FMUL] > m->issue[LT_OP_VMUL]);
    assert_true(m->issue[LT_OP_FCMP] > m->issue[LT_OP_VCMP]);
    {
        /* the Cortex-M4F's FPU against RV32's soft float: the same 16-lane float ops far cheaper
           (the fitted integer classes are effective costs, not compared with the float rows) */
        const tm_machine_t *rv = m;
        m = tm_find("mcu-m4");
        assert_true(2 * m->issue[LT_OP_FMUL] < rv->issue[LT_OP_FMUL]);
        assert_true(2 * m->issue[LT_OP_FADD] < rv->issue[LT_OP_FADD]);
    }
}

/* ---- the names every build knows ---------------------------------------------------------------- */

static void test_names_everywhere(void **state)
{
    char list[1024] = "";
    lt_diag_t diag;
    lt_scenefile_t sf;
    int i;
    (void)state;
    tm_read();
    for (i = 0; i < ntm; i++) {
        assert_non_null(lt_sf_machines[i]);
        assert_string_equal(lt_sf_machines[i], tm[i].name);
        assert_non_null(lt_meter_machine_name(i));
        assert_string_equal(lt_meter_machine_name(i), tm[i].name);
        assert_true(lt_sf_machine_known(tm[i].name));
        assert_true(lt_meter_machine_known(tm[i].name));
        if (i > 0)
            strcat(list, ", ");
        strcat(list, tm[i].name);
    }
    assert_null(lt_sf_machines[ntm]);
    assert_null(lt_meter_machine_name(ntm));
    assert_null(lt_meter_machine_name(-1));
    assert_string_equal(lt_sf_machine_list(), list);
    assert_string_equal(lt_meter_machine_names(), list);
    assert_false(lt_sf_machine_known("nosuch"));
    assert_false(lt_meter_machine_known("nosuch"));
    assert_false(lt_meter_machine_known(""));

    /* the meter refuses an unknown machine in every build, naming the known ones */
    assert_int_equal(lt_meter_init("nosuch", NULL, NULL, &diag), -1);
    assert_non_null(strstr(diag.msg, "nosuch"));
    assert_non_null(strstr(diag.msg, list));

    /* the scene-file validator: every machine accepted, an unknown one refused with the list (run
     * from the repository root, as make test does: the mesh must exist) */
    for (i = 0; i < ntm; i++) {
        char text[160];
        snprintf(text, sizeof text, "{\"mesh\": \"scenes/teapot.obj\", \"machine\": \"%s\"}",
                 tm[i].name);
        if (lt_sf_parse(text, "t.json", ".", &sf, &diag) != 0)
            fail_msg("scene file with machine %s: %s", tm[i].name, diag.msg);
        assert_string_equal(sf.machine, tm[i].name);
    }
    assert_int_equal(lt_sf_parse("{\"mesh\": \"scenes/teapot.obj\", \"machine\": \"nosuch\"}",
                                 "t.json", ".", &sf, &diag),
                     -1);
    assert_non_null(strstr(diag.msg, list));
}

/* ---- the meter without and with the cycle model -------------------------------------------------- */

#if LT_COST_MODE != LT_COST_SIM
static void test_meter_null(void **state)
{
    lt_meter_machine_t m;
    lt_meter_totals_t t;
    lt_diag_t diag;
    int i;
    (void)state;
    tm_read();
    assert_int_equal(lt_meter_available(), 0);
    for (i = 0; i < ntm; i++) {
        assert_int_equal(lt_meter_machine_info(tm[i].name, &m), -1);
        /* no cache model here, but a geometry the simulator refuses is refused the same way */
        assert_int_equal(lt_meter_init(tm[i].name, "64:8:64", "512:8:64", &diag), 0);
        assert_int_equal(lt_meter_init(tm[i].name, "63:8:64", NULL, &diag), -1);
        assert_non_null(strstr(diag.msg, "63:8:64"));
    }
    lt_meter_region(&m, sizeof m, 0x10000000u);
    lt_meter_reset();
    assert_int_equal(lt_meter_cycles(), 0);
    assert_int_equal(lt_meter_event(LT_EV_NODES), 0);
    memset(&t, 0xA5, sizeof t);
    lt_meter_totals(&t);
    assert_int_equal(t.total_cycles, 0);
    assert_int_equal(t.cycles[LT_PH_TRAVERSE], 0);
    assert_int_equal(t.events[LT_EV_RAYS], 0);
    assert_null(lt_meter_report_json("t", 1, NULL));
    lt_meter_shutdown();
}
#else
static void test_sim_table(void **state)
{
    int i, n, o;
    lt_diag_t diag;
    (void)state;
    tm_read();
    assert_int_equal(lt_meter_available(), 1);
    for (n = 0; lt_sim_machines[n] != NULL; n++)
        ;
    assert_int_equal(n, ntm);
    for (i = 0; i < ntm; i++) {
        const lt_machine_t *s = lt_sim_machines[i];
        const tm_machine_t *f = &tm[i];
        lt_meter_machine_t m;
        lt_cache_cfg_t cfg;
        lt_meter_totals_t t;
        assert_ptr_equal(lt_sim_machine_find(f->name), s);
        assert_string_equal(s->name, f->name);
        assert_string_equal(s->desc, f->desc);
        assert_int_equal(s->clock_mhz, f->clock_mhz);
        assert_int_equal(s->lanes, f->lanes);
        assert_string_equal(s->l1, f->l1);
        if (f->l2 == NULL)
            assert_null(s->l2);
        else
            assert_string_equal(s->l2, f->l2);
        assert_int_equal(s->l1_hit, f->l1_hit);
        assert_int_equal(s->l2_hit, f->l2_hit);
        assert_int_equal(s->mem, f->mem);
        for (o = 0; o < LT_OP__COUNT; o++) {
            assert_int_equal(s->latency[o], f->latency[o]);
            assert_int_equal(s->issue[o], f->issue[o]);
        }
        /* its caches parse and it initialises, directly and through the meter */
        if (lt_cache_parse(s->l1, &cfg, &diag) != 0)
            fail_msg("%s: L1 %s: %s", s->name, s->l1, diag.msg);
        if (s->l2 != NULL && lt_cache_parse(s->l2, &cfg, &diag) != 0)
            fail_msg("%s: L2 %s: %s", s->name, s->l2, diag.msg);
        if (lt_sim_init(s, NULL, NULL, &diag) != 0)
            fail_msg("%s: lt_sim_init: %s", s->name, diag.msg);
        assert_ptr_equal(lt_sim_machine(), s);
        if (lt_meter_init(s->name, NULL, NULL, &diag) != 0)
            fail_msg("%s: lt_meter_init: %s", s->name, diag.msg);
        assert_int_equal(lt_meter_machine_info(s->name, &m), 0);
        assert_string_equal(m.name, s->name);
        assert_int_equal(m.clock_mhz, s->clock_mhz);
        assert_int_equal(m.mem, s->mem);
        assert_ptr_equal(m.issue, s->issue);
        assert_ptr_equal(m.latency, s->latency);
        lt_meter_totals(&t);
        assert_int_equal(t.total_cycles, 0);
        assert_int_equal(lt_meter_cycles(), 0);
        lt_meter_shutdown();
    }
    /* a bad override is refused with the spec in the message */
    assert_int_equal(lt_meter_init(tm[0].name, "63:8:64", NULL, &diag), -1);
    assert_non_null(strstr(diag.msg, "63:8:64"));
    lt_meter_shutdown();
}
#endif

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_machine_complete),
        cmocka_unit_test(test_known_values),
        cmocka_unit_test(test_names_everywhere),
#if LT_COST_MODE != LT_COST_SIM
        cmocka_unit_test(test_meter_null),
#else
        cmocka_unit_test(test_sim_table),
#endif
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
