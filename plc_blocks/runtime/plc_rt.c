/* Host emulation of the B&R task model (plc_rt.h). */
#include "plc_rt.h"
#include "plc_rt_internal.h"

#include <errno.h>
#include <stdarg.h>
#include <string.h>
#include <time.h>

#define NS_PER_US 1000u

void plc_rt_set_err(char *err, size_t errlen, const char *fmt, ...)
{
    va_list ap;
    if (!err || errlen == 0) {
        return;
    }
    va_start(ap, fmt);
    vsnprintf(err, errlen, fmt, ap);
    va_end(ap);
}

static void emit(plc_rt *rt, plc_rt_event_kind kind, unsigned c, uint64_t t_ns)
{
    plc_rt_event ev;
    ev.kind = kind;
    ev.cls = c + 1;
    ev.cycle = rt->cls[c].cycle;
    ev.t_ns = t_ns;
    if (rt->trace_hook) {
        rt->trace_hook(rt->trace_ctx, &ev);
    }
    if (kind == PLC_RT_EV_VIOLATION && rt->violation_hook) {
        rt->violation_hook(rt->violation_ctx, &ev);
    }
}

int plc_rt_init(plc_rt *rt, const plc_rt_config *cfg, const plc_program *const *registry, size_t n,
                char *err, size_t errlen)
{
    unsigned c;
    size_t i, j;
    if (!rt || !cfg || (n && !registry) || cfg->tick_us == 0) {
        plc_rt_set_err(err, errlen, "plc_rt_init: NULL argument or unvalidated configuration");
        return PLC_RT_E_ARG;
    }
    if (cfg->cls[PLC_RT_IDLE_INDEX].n_programs && cfg->cls[PLC_RT_IDLE_INDEX].sim_cost_us == 0) {
        plc_rt_set_err(err, errlen, "plc_rt_init: [idle] programs need sim_cost_us > 0");
        return PLC_RT_E_ARG;
    }
    memset(rt, 0, sizeof(*rt));
    rt->running = -1;
    rt->cfg = *cfg;
    rt->tick_ns = (uint64_t)cfg->tick_us * NS_PER_US;
    for (c = 0; c <= PLC_RT_IDLE_INDEX; c++) {
        const plc_rt_class_config *k = &cfg->cls[c];
        plc_rt_class_state *s = &rt->cls[c];
        s->period_ns = (uint64_t)k->duration_us * NS_PER_US;
        s->deadline_extra_ns = (uint64_t)k->tolerance_us * NS_PER_US;
        s->cost_ns = (uint64_t)k->sim_cost_us * NS_PER_US;
        for (i = 0; i < k->n_programs; i++) {
            const plc_program *found = NULL;
            for (j = 0; j < n; j++) {
                if (registry[j] && registry[j]->name && !strcmp(registry[j]->name, k->programs[i])) {
                    found = registry[j];
                    break;
                }
            }
            if (!found) {
                if (c == PLC_RT_IDLE_INDEX) {
                    plc_rt_set_err(err, errlen, "[idle]: program '%s' is not in the registry", k->programs[i]);
                } else {
                    plc_rt_set_err(err, errlen, "[cyclic%u]: program '%s' is not in the registry", c + 1,
                            k->programs[i]);
                }
                return PLC_RT_E_PROGRAM;
            }
            s->progs[s->n_progs++] = found;
        }
    }
    /* the idle class is always ready when it has programs */
    rt->cls[PLC_RT_IDLE_INDEX].active = rt->cls[PLC_RT_IDLE_INDEX].n_progs > 0;
    return PLC_RT_OK;
}

int plc_rt_start(plc_rt *rt)
{
    unsigned c;
    size_t i;
    if (!rt) {
        return PLC_RT_E_ARG;
    }
    if (rt->started) {
        return PLC_RT_E_STATE;
    }
    for (c = 0; c <= PLC_RT_IDLE_INDEX; c++) {
        for (i = 0; i < rt->cls[c].n_progs; i++) {
            const plc_program *p = rt->cls[c].progs[i];
            if (p->init) {
                p->init(p->ctx);
            }
        }
    }
    rt->started = 1;
    return PLC_RT_OK;
}

void plc_rt_stop(plc_rt *rt)
{
    int c;
    size_t i;
    if (!rt || !rt->started) {
        return;
    }
    for (c = PLC_RT_IDLE_INDEX; c >= 0; c--) {
        for (i = rt->cls[c].n_progs; i-- > 0;) {
            const plc_program *p = rt->cls[c].progs[i];
            if (p->exit) {
                p->exit(p->ctx);
            }
        }
    }
    rt->started = 0;
}

/* Task start: latch every input of the class's programs, then run their
 * _CYCLIC in configuration order. */
static void class_run_programs(plc_rt *rt, unsigned c)
{
    size_t i, k;
    for (i = 0; i < rt->cls[c].n_progs; i++) {
        const plc_program *p = rt->cls[c].progs[i];
        for (k = 0; k < p->n_inputs; k++) {
            memcpy(p->inputs[k].local, p->inputs[k].image, p->inputs[k].size);
        }
    }
    for (i = 0; i < rt->cls[c].n_progs; i++) {
        const plc_program *p = rt->cls[c].progs[i];
        if (p->cyclic) {
            p->cyclic(p->ctx);
        }
    }
}

/* Task end: publish every output of the class's programs. */
static void class_publish(plc_rt *rt, unsigned c)
{
    size_t i, k;
    for (i = 0; i < rt->cls[c].n_progs; i++) {
        const plc_program *p = rt->cls[c].progs[i];
        for (k = 0; k < p->n_outputs; k++) {
            memcpy(p->outputs[k].image, p->outputs[k].local, p->outputs[k].size);
        }
    }
}

static int class_used(const plc_rt *rt, unsigned c)
{
    return rt->cls[c].period_ns != 0;
}

static uint64_t class_deadline(const plc_rt_class_state *s)
{
    return s->release_ns + s->period_ns + s->deadline_extra_ns;
}

/* Reports a violation of class c at time t; returns 1 if the runtime must
 * enter service mode. */
static int violation(plc_rt *rt, unsigned c, uint64_t t)
{
    rt->cls[c].violated = 1;
    rt->stats[c].violations++;
    emit(rt, PLC_RT_EV_VIOLATION, c, t);
    if (rt->cfg.reaction == PLC_RT_REACT_SERVICE) {
        rt->service = 1;
        return 1;
    }
    return 0;
}

static void class_end(plc_rt *rt, unsigned c, uint64_t t, uint64_t cpu_ns)
{
    plc_rt_class_state *s = &rt->cls[c];
    plc_rt_class_stats *st = &rt->stats[c];
    uint64_t resp = t - s->release_ns;
    class_publish(rt, c);
    st->cycles++;
    st->cpu_ns_total += cpu_ns;
    if (cpu_ns > st->cpu_ns_max) {
        st->cpu_ns_max = cpu_ns;
    }
    if (resp > st->response_ns_max) {
        st->response_ns_max = resp;
    }
    emit(rt, PLC_RT_EV_END, c, t);
    s->active = c == PLC_RT_IDLE_INDEX; /* the idle class stays ready */
    s->started = 0;
    s->cycle++;
}

/* Releases of tick time t. A class still active at its release is
 * overrunning: the release is skipped (the running cycle completes). */
static void releases(plc_rt *rt, uint64_t t)
{
    unsigned c;
    for (c = 0; c < PLC_RT_CLASSES; c++) {
        plc_rt_class_state *s = &rt->cls[c];
        if (!class_used(rt, c) || t % s->period_ns) {
            continue;
        }
        if (s->active) {
            rt->stats[c].skipped++;
            emit(rt, PLC_RT_EV_SKIP, c, t);
            continue;
        }
        s->active = 1;
        s->started = 0;
        s->violated = 0;
        s->release_ns = t;
        s->remaining_ns = s->cost_ns;
        emit(rt, PLC_RT_EV_RELEASE, c, t);
    }
}

/* Deadline check at time t for every unfinished cycle. Returns 1 on service mode. */
static int check_deadlines(plc_rt *rt, uint64_t t)
{
    unsigned c;
    for (c = 0; c < PLC_RT_CLASSES; c++) {
        plc_rt_class_state *s = &rt->cls[c];
        if (s->active && !s->violated && t >= class_deadline(s) && violation(rt, c, t)) {
            return 1;
        }
    }
    return 0;
}

int plc_rt_run_sim(plc_rt *rt, uint64_t n_ticks)
{
    uint64_t k;
    if (!rt) {
        return PLC_RT_E_ARG;
    }
    if (!rt->started) {
        return PLC_RT_E_STATE;
    }
    if (rt->service) {
        return PLC_RT_SERVICE;
    }
    for (k = 0; k < n_ticks; k++) {
        uint64_t t = rt->now_ns, end = t + rt->tick_ns, cpu_t = t;
        if (rt->tick_hook) {
            rt->tick_hook(rt->tick_ctx, t);
        }
        if (check_deadlines(rt, t)) {
            return PLC_RT_SERVICE;
        }
        releases(rt, t);
        /* Fixed-priority preemptive dispatch of the CPU time [t, end): the
         * released cyclic classes, then the idle class (index after #8) in
         * what is left. Releases happen only at ticks, so an idle iteration
         * never delays a cyclic class. */
        for (;;) {
            unsigned c;
            uint64_t run;
            plc_rt_class_state *s;
            for (c = 0; c <= PLC_RT_IDLE_INDEX && !rt->cls[c].active; c++) {
            }
            if (c > PLC_RT_IDLE_INDEX) {
                break;
            }
            if (cpu_t >= end) {
                break;
            }
            s = &rt->cls[c];
            if (!s->started) {
                /* the class that had the CPU and has not finished is preempted */
                if (rt->running >= 0) {
                    rt->stats[rt->running].preempted++;
                    emit(rt, PLC_RT_EV_PREEMPT, (unsigned)rt->running, cpu_t);
                }
                if (c == PLC_RT_IDLE_INDEX) {
                    s->release_ns = cpu_t;
                    s->remaining_ns = s->cost_ns;
                }
                s->started = 1;
                emit(rt, PLC_RT_EV_START, c, cpu_t);
                class_run_programs(rt, c);
            }
            run = s->remaining_ns < end - cpu_t ? s->remaining_ns : end - cpu_t;
            s->remaining_ns -= run;
            cpu_t += run;
            rt->running = (int)c;
            if (s->remaining_ns == 0) {
                rt->running = -1;
                if (c < PLC_RT_IDLE_INDEX && !s->violated && cpu_t > class_deadline(s)
                    && violation(rt, c, class_deadline(s))) {
                    return PLC_RT_SERVICE;
                }
                class_end(rt, c, cpu_t, s->cost_ns);
            }
        }
        rt->now_ns = end;
        rt->ticks++;
    }
    return PLC_RT_OK;
}

static uint64_t ts_ns(const struct timespec *ts)
{
    return (uint64_t)ts->tv_sec * 1000000000u + (uint64_t)ts->tv_nsec;
}

/* Wall clock: idle iterations until the next tick at wall time `next`.
 * An iteration starts only while the next tick is farther away than the
 * longest iteration so far (one host thread cannot preempt it); one that
 * ends after `next` all the same is counted as late. */
static int idle_wall(plc_rt *rt, uint64_t base, uint64_t next)
{
    plc_rt_class_state *s = &rt->cls[PLC_RT_IDLE_INDEX];
    plc_rt_class_stats *st = &rt->stats[PLC_RT_IDLE_INDEX];
    for (;;) {
        struct timespec c0, c1, w0, w1;
        if (clock_gettime(CLOCK_MONOTONIC, &w0)) {
            return 1;
        }
        if (ts_ns(&w0) + st->response_ns_max >= next) {
            return 0;
        }
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &c0);
        s->release_ns = ts_ns(&w0) - base;
        s->started = 1;
        emit(rt, PLC_RT_EV_START, PLC_RT_IDLE_INDEX, s->release_ns);
        class_run_programs(rt, PLC_RT_IDLE_INDEX);
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &c1);
        clock_gettime(CLOCK_MONOTONIC, &w1);
        if (ts_ns(&w1) > next) {
            st->late++;
        }
        class_end(rt, PLC_RT_IDLE_INDEX, ts_ns(&w1) - base, ts_ns(&c1) - ts_ns(&c0));
    }
}

int plc_rt_run_wall(plc_rt *rt, uint64_t n_ticks)
{
    struct timespec now;
    uint64_t base, k;
    if (!rt) {
        return PLC_RT_E_ARG;
    }
    if (!rt->started) {
        return PLC_RT_E_STATE;
    }
    if (rt->service) {
        return PLC_RT_SERVICE;
    }
    if (clock_gettime(CLOCK_MONOTONIC, &now)) {
        return PLC_RT_E_CLOCK;
    }
    /* wall time of the runtime's time 0, so that repeated calls continue
     * the same time line */
    base = ts_ns(&now) - rt->now_ns;
    for (k = 0; k < n_ticks; k++) {
        uint64_t t = rt->now_ns, target = base + t;
        struct timespec ts;
        unsigned c;
        int rc;
        ts.tv_sec = (time_t)(target / 1000000000u);
        ts.tv_nsec = (long)(target % 1000000000u);
        do {
            rc = clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, NULL);
        } while (rc == EINTR);
        if (rc) {
            return PLC_RT_E_CLOCK;
        }
        if (rt->tick_hook) {
            rt->tick_hook(rt->tick_ctx, t);
        }
        releases(rt, t);
        /* A host thread cannot be preempted by a class released meanwhile:
         * every released class runs to completion, highest priority first. */
        for (c = 0; c < PLC_RT_CLASSES; c++) {
            plc_rt_class_state *s = &rt->cls[c];
            struct timespec c0, c1, w0, w1;
            uint64_t end;
            if (!s->active) {
                continue;
            }
            clock_gettime(CLOCK_MONOTONIC, &w0);
            clock_gettime(CLOCK_THREAD_CPUTIME_ID, &c0);
            s->started = 1;
            emit(rt, PLC_RT_EV_START, c, ts_ns(&w0) - base);
            class_run_programs(rt, c);
            clock_gettime(CLOCK_THREAD_CPUTIME_ID, &c1);
            clock_gettime(CLOCK_MONOTONIC, &w1);
            end = ts_ns(&w1) - base;
            if (end > class_deadline(s) && violation(rt, c, end)) {
                return PLC_RT_SERVICE;
            }
            class_end(rt, c, end, ts_ns(&c1) - ts_ns(&c0));
        }
        rt->now_ns = t + rt->tick_ns;
        rt->ticks++;
        if (rt->cls[PLC_RT_IDLE_INDEX].active && idle_wall(rt, base, base + rt->now_ns)) {
            return PLC_RT_E_CLOCK;
        }
    }
    return PLC_RT_OK;
}

void plc_rt_report(const plc_rt *rt, FILE *out)
{
    unsigned c;
    if (!rt || !out) {
        return;
    }
    fprintf(out, "task class   cycle[us]  cycles  violations  skipped  cpu mean[us]  cpu max[us]  response max[us]\n");
    for (c = 0; c < PLC_RT_CLASSES; c++) {
        const plc_rt_class_stats *s = &rt->stats[c];
        if (!class_used(rt, c)) {
            continue;
        }
        fprintf(out, "Cyclic #%u   %9u  %6llu  %10llu  %7llu  %12.2f  %11.2f  %16.2f\n", c + 1,
                (unsigned)rt->cfg.cls[c].duration_us, (unsigned long long)s->cycles,
                (unsigned long long)s->violations, (unsigned long long)s->skipped,
                s->cycles ? (double)s->cpu_ns_total / (double)s->cycles / 1e3 : 0.0,
                (double)s->cpu_ns_max / 1e3, (double)s->response_ns_max / 1e3);
    }
    if (rt->cls[PLC_RT_IDLE_INDEX].active) {
        const plc_rt_class_stats *s = &rt->stats[PLC_RT_IDLE_INDEX];
        fprintf(out, "Idle         iterations %llu  preempted %llu  late %llu  cpu mean[us] %.2f  cpu max[us] %.2f\n",
                (unsigned long long)s->cycles, (unsigned long long)s->preempted, (unsigned long long)s->late,
                s->cycles ? (double)s->cpu_ns_total / (double)s->cycles / 1e3 : 0.0, (double)s->cpu_ns_max / 1e3);
    }
}

const char *plc_rt_strerror(int code)
{
    switch (code) {
    case PLC_RT_OK: return "ok";
    case PLC_RT_SERVICE: return "service mode after a cycle-time violation";
    case PLC_RT_E_ARG: return "invalid argument";
    case PLC_RT_E_CONFIG: return "configuration invalid";
    case PLC_RT_E_PROGRAM: return "program not in the registry";
    case PLC_RT_E_STATE: return "call out of order";
    case PLC_RT_E_CLOCK: return "host clock failed";
    default: return "unknown";
    }
}
