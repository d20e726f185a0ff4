/*
 * Configuration file of the task runtime (plc_rt.h), mirroring the
 * X20CP1586 configuration of Table 2.3 (seed 004 part 2, notes 8.5):
 *
 *   [timing]      interface_cycle_us, multiply_cycle_time_by (e.g. 0.25 or 4),
 *                 idle_task_class, idle_time_us, violation_reaction
 *   [resources]   cyclic_resources
 *   [cyclicN]     duration_us, tolerance_us, sim_cost_us, programs (comma list)
 *   [idle]        sim_cost_us, programs: the idle task class (no cycle time)
 *
 * idle_task_class and idle_time_us are Table 2.3's "Idle time" settings
 * (the class in whose cycle Automation Runtime reserves time for its
 * system tasks); they are validated and recorded, not modelled. The
 * [idle] section is the idle task class that runs user programs in the
 * CPU time left over; it has no entry in Table 2.3 (Fig. 2.12 puts no
 * program there).
 *
 * '#' starts a comment. Table 2.3 prints "System tick in us: 0.25"; that is
 * a table error (notes 8.5 [AMBIG]): the tick is derived here as interface
 * cycle x multiplier = 400 us x 0.25 = 100 us, as the thesis text says.
 */
#include "plc_rt.h"
#include "plc_rt_internal.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static char *trim(char *s)
{
    char *e;
    while (isspace((unsigned char)*s)) {
        s++;
    }
    e = s + strlen(s);
    while (e > s && isspace((unsigned char)e[-1])) {
        *--e = '\0';
    }
    return s;
}

static int parse_u32(const char *v, uint32_t *out)
{
    char *end;
    unsigned long x;
    if (!isdigit((unsigned char)*v)) {
        return -1;
    }
    errno = 0;
    x = strtoul(v, &end, 10);
    if (errno || *end || x > 0xFFFFFFFFul) {
        return -1;
    }
    *out = (uint32_t)x;
    return 0;
}

/* "multiply cycle time by": a positive integer or the reciprocal of one. */
static int parse_multiplier(const char *v, uint32_t *num, uint32_t *den)
{
    char *end;
    double x, r;
    errno = 0;
    x = strtod(v, &end);
    if (errno || *end || !(x > 0.0)) {
        return -1;
    }
    if (x >= 1.0) {
        r = floor(x + 0.5);
        if (fabs(x - r) > 1e-9 || r > 1e6) {
            return -1;
        }
        *num = (uint32_t)r;
        *den = 1;
    } else {
        r = floor(1.0 / x + 0.5);
        if (fabs(1.0 / x - r) > 1e-6 || r > 1e6) {
            return -1;
        }
        *num = 1;
        *den = (uint32_t)r;
    }
    return 0;
}

static int validate(plc_rt_config *cfg, const char *name, char *err, size_t errlen)
{
    unsigned c, used = 0;
    if (cfg->interface_cycle_us == 0 || cfg->interface_cycle_us % PLC_RT_INTERFACE_BASE_US) {
        plc_rt_set_err(err, errlen, "%s: interface_cycle_us = %u is not a positive multiple of %u us",
                name, (unsigned)cfg->interface_cycle_us, PLC_RT_INTERFACE_BASE_US);
        return PLC_RT_E_CONFIG;
    }
    if ((cfg->interface_cycle_us * cfg->multiplier_num) % cfg->multiplier_den) {
        plc_rt_set_err(err, errlen, "%s: system tick %u us x %u/%u is not a whole number of us", name,
                (unsigned)cfg->interface_cycle_us, (unsigned)cfg->multiplier_num,
                (unsigned)cfg->multiplier_den);
        return PLC_RT_E_CONFIG;
    }
    cfg->tick_us = cfg->interface_cycle_us * cfg->multiplier_num / cfg->multiplier_den;
    if (cfg->cyclic_resources < 1 || cfg->cyclic_resources > PLC_RT_CLASSES) {
        plc_rt_set_err(err, errlen, "%s: cyclic_resources = %u must be 1..%d", name,
                (unsigned)cfg->cyclic_resources, PLC_RT_CLASSES);
        return PLC_RT_E_CONFIG;
    }
    for (c = 0; c < PLC_RT_CLASSES; c++) {
        const plc_rt_class_config *k = &cfg->cls[c];
        if (k->duration_us == 0) {
            if (k->n_programs) {
                plc_rt_set_err(err, errlen, "%s: [cyclic%u] has programs but no duration_us", name, c + 1);
                return PLC_RT_E_CONFIG;
            }
            continue;
        }
        used = c + 1;
        if (k->duration_us % cfg->tick_us) {
            plc_rt_set_err(err, errlen, "%s: [cyclic%u] duration_us = %u is not a multiple of the system tick %u us",
                    name, c + 1, (unsigned)k->duration_us, (unsigned)cfg->tick_us);
            return PLC_RT_E_CONFIG;
        }
    }
    if (used > cfg->cyclic_resources) {
        plc_rt_set_err(err, errlen, "%s: [cyclic%u] is configured but cyclic_resources = %u", name, used,
                (unsigned)cfg->cyclic_resources);
        return PLC_RT_E_CONFIG;
    }
    if (cfg->idle_task_class > PLC_RT_CLASSES
        || (cfg->idle_task_class && cfg->cls[cfg->idle_task_class - 1].duration_us == 0)) {
        plc_rt_set_err(err, errlen, "%s: idle_task_class = %u is not a configured class", name,
                (unsigned)cfg->idle_task_class);
        return PLC_RT_E_CONFIG;
    }
    if (cfg->cls[PLC_RT_IDLE_INDEX].n_programs && cfg->cls[PLC_RT_IDLE_INDEX].sim_cost_us == 0) {
        plc_rt_set_err(err, errlen, "%s: [idle] has programs but no sim_cost_us (the simulated CPU time of one "
                "iteration, > 0)", name);
        return PLC_RT_E_CONFIG;
    }
    if (cfg->idle_time_us % cfg->tick_us) {
        plc_rt_set_err(err, errlen, "%s: idle_time_us = %u is not a multiple of the system tick", name,
                (unsigned)cfg->idle_time_us);
        return PLC_RT_E_CONFIG;
    }
    return PLC_RT_OK;
}

int plc_rt_config_parse(plc_rt_config *cfg, const char *text, const char *name, char *err, size_t errlen)
{
    char line[512];
    const char *p = text;
    int lineno = 0;
    int section = -1; /* -1 none, 0 timing, 1 resources, 2.. cyclic(section-2), 2 + PLC_RT_IDLE_INDEX idle */
    if (!cfg || !text) {
        plc_rt_set_err(err, errlen, "plc_rt_config_parse: NULL argument");
        return PLC_RT_E_ARG;
    }
    if (!name) {
        name = "config";
    }
    memset(cfg, 0, sizeof(*cfg));
    cfg->multiplier_num = 1;
    cfg->multiplier_den = 1;
    cfg->cyclic_resources = PLC_RT_CLASSES;
    while (*p) {
        size_t n = strcspn(p, "\n");
        char *s, *eq, *key, *val, *hash;
        lineno++;
        if (n >= sizeof(line)) {
            plc_rt_set_err(err, errlen, "%s:%d: line too long", name, lineno);
            return PLC_RT_E_CONFIG;
        }
        memcpy(line, p, n);
        line[n] = '\0';
        p += n + (p[n] == '\n');
        hash = strchr(line, '#');
        if (hash) {
            *hash = '\0';
        }
        s = trim(line);
        if (!*s) {
            continue;
        }
        if (*s == '[') {
            unsigned k;
            char *close = strchr(s, ']');
            if (!close || close[1]) {
                plc_rt_set_err(err, errlen, "%s:%d: malformed section header '%s'", name, lineno, s);
                return PLC_RT_E_CONFIG;
            }
            *close = '\0';
            s = trim(s + 1);
            if (!strcmp(s, "timing")) {
                section = 0;
            } else if (!strcmp(s, "resources")) {
                section = 1;
            } else if (!strcmp(s, "idle")) {
                section = 2 + PLC_RT_IDLE_INDEX;
            } else if (sscanf(s, "cyclic%u", &k) == 1 && k >= 1 && k <= PLC_RT_CLASSES
                       && strspn(s + 6, "0123456789") == strlen(s + 6)) {
                section = 2 + (int)k - 1;
            } else {
                plc_rt_set_err(err, errlen, "%s:%d: unknown section [%s] (timing, resources, cyclic1..cyclic8, idle)",
                        name, lineno, s);
                return PLC_RT_E_CONFIG;
            }
            continue;
        }
        eq = strchr(s, '=');
        if (!eq) {
            plc_rt_set_err(err, errlen, "%s:%d: expected 'key = value', found '%s'", name, lineno, s);
            return PLC_RT_E_CONFIG;
        }
        *eq = '\0';
        key = trim(s);
        val = trim(eq + 1);
        if (section < 0) {
            plc_rt_set_err(err, errlen, "%s:%d: '%s' outside a section", name, lineno, key);
            return PLC_RT_E_CONFIG;
        }
#define U32_KEY(kname, field) \
        if (!strcmp(key, kname)) { \
            if (parse_u32(val, &(field))) { \
                plc_rt_set_err(err, errlen, "%s:%d: %s = '%s' is not an unsigned integer", name, lineno, key, val); \
                return PLC_RT_E_CONFIG; \
            } \
            continue; \
        }
        if (section == 0) {
            U32_KEY("interface_cycle_us", cfg->interface_cycle_us)
            U32_KEY("idle_task_class", cfg->idle_task_class)
            U32_KEY("idle_time_us", cfg->idle_time_us)
            if (!strcmp(key, "multiply_cycle_time_by")) {
                if (parse_multiplier(val, &cfg->multiplier_num, &cfg->multiplier_den)) {
                    plc_rt_set_err(err, errlen, "%s:%d: multiply_cycle_time_by = '%s' is not a positive integer "
                            "or the reciprocal of one", name, lineno, val);
                    return PLC_RT_E_CONFIG;
                }
                continue;
            }
            if (!strcmp(key, "violation_reaction")) {
                if (!strcmp(val, "continue")) {
                    cfg->reaction = PLC_RT_REACT_CONTINUE;
                } else if (!strcmp(val, "service")) {
                    cfg->reaction = PLC_RT_REACT_SERVICE;
                } else {
                    plc_rt_set_err(err, errlen, "%s:%d: violation_reaction = '%s' (continue or service)", name,
                            lineno, val);
                    return PLC_RT_E_CONFIG;
                }
                continue;
            }
        } else if (section == 1) {
            U32_KEY("cyclic_resources", cfg->cyclic_resources)
        } else {
            plc_rt_class_config *k = &cfg->cls[section - 2];
            if (section == 2 + PLC_RT_IDLE_INDEX && (!strcmp(key, "duration_us") || !strcmp(key, "tolerance_us"))) {
                plc_rt_set_err(err, errlen, "%s:%d: %s in [idle]: the idle task class has no cycle time", name,
                        lineno, key);
                return PLC_RT_E_CONFIG;
            }
            U32_KEY("duration_us", k->duration_us)
            U32_KEY("tolerance_us", k->tolerance_us)
            U32_KEY("sim_cost_us", k->sim_cost_us)
            if (!strcmp(key, "programs")) {
                char *tok = strtok(val, ",");
                k->n_programs = 0;
                while (tok) {
                    char *t = trim(tok);
                    if (!*t || strlen(t) >= PLC_RT_NAME_LEN || k->n_programs >= PLC_RT_PROGS_PER_CLASS) {
                        plc_rt_set_err(err, errlen, "%s:%d: bad program list (names 1..%d chars, at most %d)", name,
                                lineno, PLC_RT_NAME_LEN - 1, PLC_RT_PROGS_PER_CLASS);
                        return PLC_RT_E_CONFIG;
                    }
                    strcpy(k->programs[k->n_programs++], t);
                    tok = strtok(NULL, ",");
                }
                continue;
            }
        }
#undef U32_KEY
        plc_rt_set_err(err, errlen, "%s:%d: unknown key '%s' in this section", name, lineno, key);
        return PLC_RT_E_CONFIG;
    }
    return validate(cfg, name, err, errlen);
}

int plc_rt_config_load(plc_rt_config *cfg, const char *path, char *err, size_t errlen)
{
    FILE *f;
    char buf[16384];
    size_t n;
    int rc;
    if (!cfg || !path) {
        plc_rt_set_err(err, errlen, "plc_rt_config_load: NULL argument");
        return PLC_RT_E_ARG;
    }
    f = fopen(path, "r");
    if (!f) {
        plc_rt_set_err(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        return PLC_RT_E_CONFIG;
    }
    n = fread(buf, 1, sizeof(buf) - 1, f);
    rc = !feof(f);
    fclose(f);
    if (rc) {
        plc_rt_set_err(err, errlen, "%s: larger than %u bytes", path, (unsigned)sizeof(buf) - 1);
        return PLC_RT_E_CONFIG;
    }
    buf[n] = '\0';
    return plc_rt_config_parse(cfg, buf, path, err, errlen);
}
