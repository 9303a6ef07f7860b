/* core_parallel: core_parallel_for, contiguous bands of a loop on POSIX
 * threads (start-up work: the layout maps). */
#include "core/core.h"

#include <pthread.h>
#include <unistd.h>

typedef struct band_t {
    void (*fn)(void *user, int begin, int end);
    void *user;
    int begin, end;
} band_t;

static void *run_band(void *arg)
{
    band_t *b = arg;
    b->fn(b->user, b->begin, b->end);
    return NULL;
}

void core_parallel_for(int n, void (*fn)(void *user, int begin, int end), void *user)
{
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    int k = cores < 1 ? 1 : cores > CORE_PARALLEL_MAX ? CORE_PARALLEL_MAX : (int)cores;
    if (k > n) k = n > 0 ? n : 1;
    band_t bands[CORE_PARALLEL_MAX];
    pthread_t threads[CORE_PARALLEL_MAX];
    bool started[CORE_PARALLEL_MAX] = {false};
    for (int i = 0; i < k; i++)
        bands[i] = (band_t){.fn = fn, .user = user, .begin = (int)((long)n * i / k), .end = (int)((long)n * (i + 1) / k)};
    for (int i = 1; i < k; i++) started[i] = pthread_create(&threads[i], NULL, run_band, &bands[i]) == 0;
    run_band(&bands[0]);
    for (int i = 1; i < k; i++) {
        if (started[i]) pthread_join(threads[i], NULL);
        else run_band(&bands[i]);
    }
}
