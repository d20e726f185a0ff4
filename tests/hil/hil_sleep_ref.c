/* Reference for the HIL real-time jitter benchmark (tests/bench/bench_hil.sh): the
 * wake-up lateness of a bare periodic loop, clock_nanosleep(TIMER_ABSTIME)
 * on CLOCK_MONOTONIC every period, i.e. what the host's scheduler alone
 * allows before any CAN traffic or control law.
 * usage: hil_sleep_ref PERIOD_US CYCLES
 * prints: p50_us=.. p99_us=.. max_us=.. misses=.. (lateness > period) */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(int argc, char **argv)
{
    long period_ns, n, k, misses = 0;
    double *late;
    struct timespec next, now;
    if (argc != 3 || (period_ns = atol(argv[1]) * 1000L) <= 0 || (n = atol(argv[2])) < 1) {
        fprintf(stderr, "usage: hil_sleep_ref PERIOD_US CYCLES\n");
        return 2;
    }
    late = malloc((size_t)n * sizeof *late);
    if (!late)
        return 1;
    clock_gettime(CLOCK_MONOTONIC, &next);
    for (k = 0; k < n; k++) {
        next.tv_nsec += period_ns;
        while (next.tv_nsec >= 1000000000L) {
            next.tv_nsec -= 1000000000L;
            next.tv_sec++;
        }
        clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, NULL);
        clock_gettime(CLOCK_MONOTONIC, &now);
        late[k] = (double)(now.tv_sec - next.tv_sec) * 1e6 + (double)(now.tv_nsec - next.tv_nsec) * 1e-3;
        if (late[k] > period_ns * 1e-3)
            misses++;
    }
    qsort(late, (size_t)n, sizeof *late, cmp);
    printf("p50_us=%.1f p99_us=%.1f max_us=%.1f misses=%ld\n", late[n / 2], late[(size_t)((n - 1) * 0.99)],
           late[n - 1], misses);
    free(late);
    return 0;
}
