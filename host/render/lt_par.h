/* lt_par.h - the host's tile loops on every core: tasks (a row of tiles, a block, a row of
 * pixels) handed out one at a time from a shared counter to worker threads (pthreads), each task
 * writing only its own pixels, so a result is bit-identical for any thread count and any order.
 * Loops whose kernels charge the cycle model (the sim build) run on one thread: the model's
 * counters and its caches see one access stream, in order, as the accelerator would. Host only.
 */
#ifndef LT_PAR_H
#define LT_PAR_H

#include <stdint.h>

/* Largest thread count accepted (--threads). */
#define LT_PAR_MAX_THREADS 256u

/* The thread count of later loops: n >= 1, or 0 = every online core. The library's default is 1
 * (benchmarks and tests measure one core unless they ask); the CLI sets --threads (default 0). */
void lt_par_set_threads(unsigned n);

/* The thread count set (0 resolved to the online cores). */
unsigned lt_par_threads(void);

/* The workers a loop of ntasks will use: min(lt_par_threads(), ntasks), at least 1; 1 when
 * counted is non-zero and the cycle model is live (the sim build). Size per-worker scratch with
 * this before lt_par_run. */
unsigned lt_par_workers(uint32_t ntasks, int counted);

/* A task: worker is 0..workers-1 (0 is the calling thread), task 0..ntasks-1. */
typedef void (*lt_par_task_fn)(void *ctx, unsigned worker, uint32_t task);

/* Run every task once on `workers` workers (lt_par_workers, or fewer if the caller has scratch
 * for fewer; at least 1); returns when all are done. progress (may be NULL) is called on the
 * calling thread only, with the fraction of tasks done. Returns the workers used (a thread that
 * cannot be started leaves its tasks to the others). */
unsigned lt_par_run(uint32_t ntasks, unsigned workers, lt_par_task_fn fn, void *ctx,
                    void (*progress)(double done));

#endif /* LT_PAR_H */
