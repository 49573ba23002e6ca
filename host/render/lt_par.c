/* lt_par.c - the shared task queue of lt_par.h: one atomic counter, pthreads workers, the caller
 * as worker 0 (it alone reports progress). Host only.
 */
#include "render/lt_par.h"
#include "lt_meter.h"

#include <pthread.h>
#include <unistd.h>

static unsigned par_threads = 1;

void lt_par_set_threads(unsigned n)
{
    if (n == 0) {
        long c = sysconf(_SC_NPROCESSORS_ONLN);
        n = c < 1 ? 1u : (unsigned)c;
    }
    par_threads = n > LT_PAR_MAX_THREADS ? LT_PAR_MAX_THREADS : n;
}

unsigned lt_par_threads(void) { return par_threads; }

unsigned lt_par_workers(uint32_t ntasks, int counted)
{
    unsigned w = par_threads;
    if (counted && lt_meter_available())
        return 1;
    if (w > ntasks)
        w = ntasks;
    return w < 1 ? 1u : w;
}

typedef struct par_job {
    uint32_t ntasks;
    uint32_t next; /* the next task to hand out (atomic) */
    uint32_t done; /* tasks finished (atomic) */
    lt_par_task_fn fn;
    void *ctx;
} par_job_t;

typedef struct par_worker {
    par_job_t *job;
    unsigned id;
    pthread_t th;
} par_worker_t;

/* Take tasks until none is left; worker 0 reports progress after each. */
static void par_drain(par_job_t *j, unsigned id, void (*progress)(double))
{
    for (;;) {
        uint32_t t = __atomic_fetch_add(&j->next, 1u, __ATOMIC_RELAXED);
        uint32_t d;
        if (t >= j->ntasks)
            return;
        j->fn(j->ctx, id, t);
        d = __atomic_add_fetch(&j->done, 1u, __ATOMIC_RELAXED);
        if (progress != NULL)
            progress((double)d / (double)j->ntasks);
    }
}

static void *par_main(void *arg)
{
    par_worker_t *w = arg;
    par_drain(w->job, w->id, NULL);
    return NULL;
}

unsigned lt_par_run(uint32_t ntasks, unsigned workers, lt_par_task_fn fn, void *ctx,
                    void (*progress)(double done))
{
    par_worker_t wk[LT_PAR_MAX_THREADS];
    par_job_t job;
    unsigned n = workers < 1 ? 1u : (workers > LT_PAR_MAX_THREADS ? LT_PAR_MAX_THREADS : workers);
    unsigned started = 1, i;
    job.ntasks = ntasks;
    job.next = 0;
    job.done = 0;
    job.fn = fn;
    job.ctx = ctx;
    /* workers 1.. on threads; one that cannot start leaves its tasks to the others (the queue
       hands out whatever is left), and keeps its id unused so scratch indices stay < n */
    for (i = 1; i < n; i++) {
        wk[i].job = &job;
        wk[i].id = started;
        if (pthread_create(&wk[i].th, NULL, par_main, &wk[i]) != 0)
            break;
        started++;
    }
    par_drain(&job, 0, progress);
    for (i = 1; i < started; i++)
        (void)pthread_join(wk[i].th, NULL);
    if (progress != NULL)
        progress(1.0);
    return started;
}
