/* lt_meter_null.c - sim/lt_meter.h without a cycle model (native and ASan builds): nothing is
 * counted, totals are zeros, reports print nothing; machine names come from the scene-file
 * validator's list (the same generated list the simulator builds its table from). The simulator
 * build links sim/lt_meter_sim.c instead (the Makefile leaves this file out of build/sim).
 * Host only.
 */
#include "lt_meter.h"
#include "lt_cache.h"
#include "io/lt_scenefile.h"

#include <string.h>

int lt_meter_available(void) { return 0; }

const char *lt_meter_machine_name(int i)
{
    int k;
    if (i < 0)
        return NULL;
    for (k = 0; k < i; k++)
        if (lt_sf_machines[k] == NULL)
            return NULL;
    return lt_sf_machines[i];
}

int lt_meter_machine_known(const char *name) { return lt_sf_machine_known(name); }

const char *lt_meter_machine_names(void) { return lt_sf_machine_list(); }

int lt_meter_machine_info(const char *name, lt_meter_machine_t *m)
{
    (void)name;
    memset(m, 0, sizeof *m);
    return -1;
}

int lt_meter_init(const char *machine, const char *l1, const char *l2, lt_diag_t *diag)
{
    lt_cache_cfg_t cfg;
    if (!lt_sf_machine_known(machine)) {
        lt_diag_fail(diag, "machine '%s' unknown (known: %s)", machine, lt_sf_machine_list());
        return -1;
    }
    /* no cache model here, but a geometry the simulator would refuse is refused here too */
    if ((l1 != NULL && lt_cache_parse(l1, &cfg, diag) != 0) ||
        (l2 != NULL && lt_cache_parse(l2, &cfg, diag) != 0))
        return -1;
    return 0;
}

void lt_meter_reset(void) {}

void lt_meter_shutdown(void) {}

void lt_meter_region(const void *base, size_t bytes, uint64_t sim_base)
{
    (void)base;
    (void)bytes;
    (void)sim_base;
}

uint64_t lt_meter_cycles(void) { return 0; }

uint64_t lt_meter_event(int ev)
{
    (void)ev;
    return 0;
}

void lt_meter_totals(lt_meter_totals_t *t) { memset(t, 0, sizeof *t); }

void lt_meter_report_text(FILE *f, const char *title, uint64_t rays)
{
    (void)f;
    (void)title;
    (void)rays;
}

char *lt_meter_report_json(const char *title, uint64_t rays, const char *extra_json)
{
    (void)title;
    (void)rays;
    (void)extra_json;
    return NULL;
}
