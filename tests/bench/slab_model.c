/* slab_model.c - the mcu-m4 (or any) machine model's prediction for the slab-test loop that
 * tests/fw/fw_slab.c runs under QEMU: prints predicted cycles for the lt_slab16_q16 calls.
 * The float32 twin (lt_slab_loop_f32, tests/fw/fw_slab_f32.c) with the path argument f32.
 * Sim build only. Usage: slab-model [machine] [calls] [q16|f32]
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "lt_sim.h"
#include "lt_slab_loop.h"

int main(int argc, char **argv)
{
    const char *mname = argc > 1 ? argv[1] : "mcu-m4";
    int calls = argc > 2 ? atoi(argv[2]) : 256;
    const char *path = argc > 3 ? argv[3] : "q16";
    const lt_machine_t *m = lt_sim_machine_find(mname);
    lt_sim_totals_t t;
    lt_diag_t diag;
    uint32_t hits;
    if (m == NULL || calls < 1 || (strcmp(path, "q16") != 0 && strcmp(path, "f32") != 0)) {
        fprintf(stderr, "usage: slab-model [machine] [calls >= 1] [q16|f32]\n");
        return 2;
    }
    if (lt_sim_init(m, NULL, NULL, &diag) != 0) {
        fprintf(stderr, "%s\n", diag.msg);
        return 1;
    }
    hits = strcmp(path, "f32") == 0 ? lt_slab_loop_f32(calls) : lt_slab_loop(calls);
    lt_sim_totals(&t);
    printf("model %s slab %s calls %d lane hits %u predicted %llu\n", mname, path, calls, hits,
           (unsigned long long)t.total_cycles);
    lt_sim_shutdown();
    return 0;
}
