/*
 * plc_rt.h - host emulation of the B&R Automation Runtime task model.
 *
 * What it mirrors (seed 004 part 2, notes 8.5, Table 2.3, Sec. 2.3.3):
 *  - task classes Cyclic #1..#8; each class has a duration (cycle time)
 *    that is a multiple of the system tick; system tick = interface cycle
 *    (POWERLINK, a multiple of 400 us) x "multiply cycle time by"
 *    (400 us x 0.25 = 100 us on the X20CP1586);
 *  - a lower class number means a higher priority; a released higher class
 *    preempts a lower one;
 *  - programs with _INIT (once, before any cyclic call), _CYCLIC (every
 *    cycle of their class, programs of a class in configuration order) and
 *    _EXIT (once, at shutdown, reverse order);
 *  - the I/O image: a class latches its programs' inputs from the process
 *    image when it starts a cycle and publishes their outputs when the cycle
 *    ends, so a program never sees a value change during its cycle;
 *  - cycle-time violations: a cycle not finished by its deadline (the next
 *    release plus the class tolerance) is detected, counted and reported;
 *    the reaction is either to continue (the overrunning cycle completes,
 *    the missed releases are skipped) or service mode (every task stops,
 *    as Automation Runtime does by default);
 *  - the idle task class: programs that run in the CPU time the cyclic
 *    classes leave over, with no cycle time and below Cyclic #8; every
 *    cyclic class preempts an idle iteration, an iteration is never
 *    late and never reported as a cycle-time violation; the runtime counts
 *    the iterations. (Not Table 2.3's "Idle time" entries, which are
 *    recorded only, see plc_rt_config.)
 *
 * Two clocks:
 *  - simulated (lockstep): time advances tick by tick; each class consumes
 *    a configured simulated CPU time per cycle (sim_cost_us) and is
 *    scheduled preemptively by priority at nanosecond resolution. A tick
 *    hook runs at every tick before the releases, so a plant model can
 *    advance exactly one tick and exchange the process image: deterministic.
 *  - wall clock: one host thread sleeps to every tick with
 *    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME), runs the released
 *    classes in priority order (a host thread cannot be preempted by a
 *    class released meanwhile, so classes run to completion), measures the
 *    CPU time of each class cycle (CLOCK_THREAD_CPUTIME_ID) and detects
 *    violations against the wall clock.
 *
 * Host emulation only (POSIX, C99): not part of the portable block bodies.
 */
#ifndef PLC_RT_H
#define PLC_RT_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

#define PLC_RT_CLASSES 8          /* Cyclic #1..#8 */
#define PLC_RT_PROGS_PER_CLASS 8
#define PLC_RT_NAME_LEN 32
#define PLC_RT_INTERFACE_BASE_US 400u /* interface cycle granularity (Table 2.3 rules) */
#define PLC_RT_IDLE 9             /* class number of the idle task class in events */
#define PLC_RT_IDLE_INDEX PLC_RT_CLASSES /* its index in cls[] and stats[] */

/* Return codes of the runtime functions. */
enum {
    PLC_RT_OK = 0,
    PLC_RT_SERVICE = 1,       /* stopped in service mode after a cycle-time violation */
    PLC_RT_E_ARG = -1,        /* NULL or invalid argument */
    PLC_RT_E_CONFIG = -2,     /* configuration invalid (message in the error buffer) */
    PLC_RT_E_PROGRAM = -3,    /* a configured program is not in the registry */
    PLC_RT_E_STATE = -4,      /* call out of order (run before start, start twice) */
    PLC_RT_E_CLOCK = -5       /* the host clock failed */
};

/* One variable of the I/O image: `size` bytes copied between the process
 * image (`image`, shared by the tasks and the plant/hardware side) and the
 * program's own copy (`local`). */
typedef struct plc_io {
    void *image;
    void *local;
    size_t size;
} plc_io;

/* A program: the three entry points of an Automation Studio program and its
 * I/O mapping. Any entry point may be NULL. */
typedef struct plc_program {
    const char *name;
    void (*init)(void *ctx);
    void (*cyclic)(void *ctx);
    void (*exit)(void *ctx);
    void *ctx;
    const plc_io *inputs;
    size_t n_inputs;
    const plc_io *outputs;
    size_t n_outputs;
} plc_program;

typedef enum plc_violation_reaction {
    PLC_RT_REACT_CONTINUE = 0, /* report, let the cycle finish, skip missed releases */
    PLC_RT_REACT_SERVICE = 1   /* report and stop every task (service mode) */
} plc_violation_reaction;

typedef struct plc_rt_class_config {
    uint32_t duration_us;   /* cycle time; 0 = class unused (always 0 for the idle class) */
    uint32_t tolerance_us;  /* extra time after the next release before a violation */
    uint32_t sim_cost_us;   /* simulated CPU time of one cycle (idle class: of one iteration) */
    char programs[PLC_RT_PROGS_PER_CLASS][PLC_RT_NAME_LEN];
    size_t n_programs;
} plc_rt_class_config;

/* The X20CP1586 configuration (Table 2.3) as read from a configuration file. */
typedef struct plc_rt_config {
    uint32_t interface_cycle_us;   /* POWERLINK interface cycle, multiple of 400 us */
    uint32_t multiplier_num;       /* "multiply cycle time by" = num/den, num or den = 1 */
    uint32_t multiplier_den;
    uint32_t tick_us;              /* system tick = interface cycle x multiplier */
    uint32_t cyclic_resources;     /* number of cyclic task classes configured (<= 8) */
    uint32_t idle_task_class;      /* Table 2.3 "Idle task class" (0 = none), recorded, not modelled */
    uint32_t idle_time_us;         /* Table 2.3 "Task class idle time", recorded, not modelled */
    plc_violation_reaction reaction;
    /* [0..7] Cyclic #1..#8, [PLC_RT_IDLE_INDEX] the idle task class ([idle]) */
    plc_rt_class_config cls[PLC_RT_CLASSES + 1];
} plc_rt_config;

/*
 * Reads a configuration file (INI-like, see plc_blocks/runtime/x20cp1586.cfg)
 * and validates it: interface cycle a multiple of 400 us, the multiplier a
 * positive integer or the reciprocal of one, the tick a whole number of us,
 * every duration a multiple of the tick, at most `cyclic_resources` classes
 * used; an [idle] section (the idle task class) takes only programs and
 * sim_cost_us, which must be > 0 when it has programs. Returns PLC_RT_OK or PLC_RT_E_CONFIG/PLC_RT_E_ARG with a message
 * "file:line: ..." in err (errlen bytes).
 */
int plc_rt_config_load(plc_rt_config *cfg, const char *path, char *err, size_t errlen);

/* Same, from a string (name used in messages). */
int plc_rt_config_parse(plc_rt_config *cfg, const char *text, const char *name, char *err, size_t errlen);

/* Events reported to the trace hook (tests, logs). */
typedef enum plc_rt_event_kind {
    PLC_RT_EV_RELEASE = 0,   /* a class cycle becomes ready (never for the idle class) */
    PLC_RT_EV_START = 1,     /* inputs latched, programs run (idle class: an iteration starts) */
    PLC_RT_EV_PREEMPT = 2,   /* a running class (or idle iteration) is preempted by a higher one */
    PLC_RT_EV_END = 3,       /* outputs published */
    PLC_RT_EV_VIOLATION = 4, /* cycle-time violation detected */
    PLC_RT_EV_SKIP = 5       /* a release skipped because the class still runs */
} plc_rt_event_kind;

typedef struct plc_rt_event {
    plc_rt_event_kind kind;
    unsigned cls;            /* 1..8, PLC_RT_IDLE for the idle class */
    uint64_t cycle;          /* cycle (idle class: iteration) index of the class (0 = first) */
    uint64_t t_ns;           /* time of the event since start */
} plc_rt_event;

typedef struct plc_rt_class_stats {
    uint64_t cycles;         /* completed cycles (idle class: iterations) */
    uint64_t violations;     /* cycle-time violations (always 0 for the idle class) */
    uint64_t skipped;        /* releases skipped while the class still ran */
    uint64_t preempted;      /* simulated clock: cycles interrupted by a higher class */
    uint64_t late;           /* wall clock, idle class: iterations that ended after the next tick was due */
    uint64_t cpu_ns_total;   /* CPU time of all cycles (simulated or measured) */
    uint64_t cpu_ns_max;
    uint64_t response_ns_max; /* release (idle: iteration start) to end, worst case */
} plc_rt_class_stats;

typedef enum plc_rt_clock {
    PLC_RT_CLOCK_SIMULATED = 0,
    PLC_RT_CLOCK_WALL = 1
} plc_rt_clock;

/* Per-class scheduler state (internal). */
typedef struct plc_rt_class_state {
    const plc_program *progs[PLC_RT_PROGS_PER_CLASS];
    size_t n_progs;
    uint64_t period_ns;
    uint64_t deadline_extra_ns; /* tolerance */
    uint64_t cost_ns;
    int active;               /* a cycle is released and not finished (idle class: it has programs) */
    int started;              /* inputs latched and programs run */
    int violated;             /* the current cycle was already reported */
    uint64_t release_ns;
    uint64_t remaining_ns;    /* simulated CPU time still to consume */
    uint64_t cycle;           /* index of the current/next cycle */
} plc_rt_class_state;

typedef struct plc_rt {
    plc_rt_config cfg;
    plc_rt_class_state cls[PLC_RT_CLASSES + 1];  /* [PLC_RT_IDLE_INDEX]: the idle class */
    plc_rt_class_stats stats[PLC_RT_CLASSES + 1];
    uint64_t tick_ns;
    uint64_t now_ns;          /* time of the next tick to process */
    uint64_t ticks;           /* ticks processed */
    int started;
    int service;              /* service mode entered */
    int running;              /* simulated clock: index of the unfinished class that had the CPU last, -1 none */
    /* hooks, all optional */
    void (*tick_hook)(void *ctx, uint64_t t_ns);   /* before the releases of every tick */
    void *tick_ctx;
    void (*trace_hook)(void *ctx, const plc_rt_event *ev);
    void *trace_ctx;
    void (*violation_hook)(void *ctx, const plc_rt_event *ev);
    void *violation_ctx;
} plc_rt;

/*
 * Builds the runtime from a validated configuration, resolving every
 * configured program name in `registry` (n entries). Hooks are NULL.
 * Returns PLC_RT_OK, PLC_RT_E_ARG, PLC_RT_E_PROGRAM (message in err).
 */
int plc_rt_init(plc_rt *rt, const plc_rt_config *cfg, const plc_program *const *registry, size_t n,
                char *err, size_t errlen);

/* Runs every _INIT, class 1 first, the idle class last, programs in configuration order.
 * Returns PLC_RT_OK or PLC_RT_E_STATE if already started. */
int plc_rt_start(plc_rt *rt);

/* Advances the simulated clock by n ticks: in every tick the released
 * classes by priority, then idle iterations (sim_cost_us each) in the CPU
 * time left; a class released at a later tick preempts an unfinished
 * iteration, which resumes when no class is ready. Returns PLC_RT_OK, PLC_RT_SERVICE
 * (stopped after a violation), PLC_RT_E_STATE (not started). */
int plc_rt_run_sim(plc_rt *rt, uint64_t n_ticks);

/* Runs n ticks against the wall clock (clock_nanosleep). After the
 * classes of a tick, idle iterations run while the next tick is farther
 * away than the longest iteration so far (one host thread cannot preempt
 * a running iteration, so the runtime budgets it instead; an iteration
 * that still ends after the next tick is counted in stats[].late; one
 * longer than the gap between ticks therefore runs once and no more).
 * Returns as plc_rt_run_sim, or PLC_RT_E_CLOCK. */
int plc_rt_run_wall(plc_rt *rt, uint64_t n_ticks);

/* Runs every _EXIT, reverse order (the idle class first). */
void plc_rt_stop(plc_rt *rt);

/* Prints one line per used class: cycles, violations, skipped releases,
 * CPU time mean/max, worst response time; and one for the idle class
 * (iterations, preemptions or late iterations, CPU time mean/max). */
void plc_rt_report(const plc_rt *rt, FILE *out);

/* Name of a return code. */
const char *plc_rt_strerror(int code);

#ifdef __cplusplus
}
#endif

#endif /* PLC_RT_H */
