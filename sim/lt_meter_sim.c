/* lt_meter_sim.c - sim/lt_meter.h in the simulator build: every call goes to sim/lt_sim.c.
 * Linked into build/sim programs (SIM_SRCS) in place of host/render/lt_meter_null.c. Host only.
 */
#include "lt_meter.h"
#include "lt_sim.h"

#include <string.h>

int lt_meter_available(void) { return 1; }

const char *lt_meter_machine_name(int i)
{
    int k;
    if (i < 0)
        return NULL;
    for (k = 0; k < i; k++)
        if (lt_sim_machines[k] == NULL)
            return NULL;
    return lt_sim_machines[i] != NULL ? lt_sim_machines[i]->name : NULL;
}

int lt_meter_machine_known(const char *name) { return lt_sim_machine_find(name) != NULL; }

const char *lt_meter_machine_names(void)
{
    static char list[512];
    int i;
    if (list[0] == '\0')
        for (i = 0; lt_sim_machines[i] != NULL; i++) {
            strncat(list, i > 0 ? ", " : "", sizeof list - strlen(list) - 1);
            strncat(list, lt_sim_machines[i]->name, sizeof list - strlen(list) - 1);
        }
    return list;
}

int lt_meter_machine_info(const char *name, lt_meter_machine_t *m)
{
    const lt_machine_t *s = lt_sim_machine_find(name);
    memset(m, 0, sizeof *m);
    if (s == NULL)
        return -1;
    m->name = s->name;
    m->desc = s->desc;
    m->clock_mhz = s->clock_mhz;
    m->lanes = s->lanes;
    m->l1 = s->l1;
    m->l2 = s->l2;
    m->l1_hit = s->l1_hit;
    m->l2_hit = s->l2_hit;
    m->mem = s->mem;
    m->latency = s->latency;
    m->issue = s->issue;
    return 0;
}

int lt_meter_init(const char *machine, const char *l1, const char *l2, lt_diag_t *diag)
{
    const lt_machine_t *m = lt_sim_machine_find(machine);
    if (m == NULL) {
        lt_diag_fail(diag, "machine '%s' unknown (known: %s)", machine,
                     lt_meter_machine_names());
        return -1;
    }
    return lt_sim_init(m, l1, l2, diag);
}

void lt_meter_reset(void) { lt_sim_reset(); }

void lt_meter_shutdown(void) { lt_sim_shutdown(); }

void lt_meter_region(const void *base, size_t bytes, uint64_t sim_base)
{
    (void)lt_sim_region(base, bytes, sim_base);
}

uint64_t lt_meter_cycles(void) { return lt_sim_cycles_total(); }

uint64_t lt_meter_event(int ev) { return lt_sim_event_total(ev); }

void lt_meter_totals(lt_meter_totals_t *t)
{
    static lt_sim_totals_t s; /* large (every counter of every phase): not on the stack */
    int p, e;
    memset(t, 0, sizeof *t);
    if (lt_sim_machine() == NULL)
        return; /* before lt_meter_init: nothing counted */
    lt_sim_totals(&s);
    for (p = 0; p < LT_PH__COUNT; p++) {
        t->cycles[p] = s.cycles[p];
        for (e = 0; e < LT_EV__COUNT; e++)
            t->events[e] += s.ctr[p][LT_OP__COUNT + e];
    }
    t->total_cycles = s.total_cycles;
    t->l1_acc = s.l1_acc;
    t->l1_hit = s.l1_hit;
    t->l2_acc = s.l2_acc;
    t->l2_hit = s.l2_hit;
}

void lt_meter_report_text(FILE *f, const char *title, uint64_t rays)
{
    lt_sim_report_text(f, title, rays);
}

char *lt_meter_report_json(const char *title, uint64_t rays, const char *extra_json)
{
    return lt_sim_report_json_string(title, rays, extra_json);
}
