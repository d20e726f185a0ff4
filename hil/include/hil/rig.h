/* The whole bench in one process, in lockstep (simulated time, deterministic,
 * as fast as the host runs): drive, IMU, plant and controller nodes on an
 * in-memory bus that behaves like CAN (every frame reaches every node except
 * its sender, in transmission order). The nodes are the same objects the
 * node executables run over SocketCAN or UDP.
 *
 * Cycle k: the controller's tick (NMT at k = 0, SYNC), then frames are
 * delivered until the bus is idle, then the controller's deadline (law on
 * stale inputs if the drive's TPDOs were lost) and delivery until idle again.
 * Every delivered frame is written to the candump log with time
 * t_k + i * 1 us (i: position in the cycle) so the log keeps the bus order.
 *
 * Effects on the bus: frame_loss drops each PDO (not NMT/SYNC/EMCY/heartbeat,
 * not the rig-internal physics frames) with that probability, seeded by
 * bus_seed; dropped frames are neither delivered nor logged (counted).
 * inject_every > 0 puts two malformed frames on the bus every inject_every
 * cycles (the drive RPDO with DLC 5 and the unknown identifier 0x555), which
 * every node must count and ignore. imu_dropout_start/end: every IMU PDO
 * sent in that window of simulated time is lost (the "IMU frames stop" fault);
 * drive_dropout_start/end the same for the drive's TPDOs. drive_busoff_start/
 * end: the drive's CAN controller is bus-off: nothing it sends reaches the bus
 * and it hears nothing but SYNC (its own cycle stays locked to the bus clock)
 * and the RIG_* wiring; on recovery it sends EMCY 0x8140. */
#ifndef HIL_RIG_H
#define HIL_RIG_H
#include <stdio.h>
#include "hil/ctrl.h"
#include "hil/drive.h"
#include "hil/imu.h"
#include "hil/plant.h"
#include "hil/rng.h"

#define HIL_RIG_QUEUE 256
/* Bounds of one run (docs/hil.md, "Bounds of a run"): simulated seconds, and
 * bytes of the candump log (a run that reaches it stops with HIL_E_FULL and
 * r->err saying so). ~0.45 MB of log per simulated second at T = 1.2 ms on
 * the default traffic: 600 s give ~270 MB. */
#define HIL_RIG_DURATION_MAX 600.0
#define HIL_RIG_LOG_MAX (512ul << 20)

struct hil_rig_config {
    char scenario[128];        /* scenario name or file, for the metadata */
    char plant[16];            /* "rigid", "twomass" or "arm" */
    char law[16];              /* controller law: "pd" (test law), "armctrl_a" or "armctrl" (plc_blocks) */
    char ctrl_table[HIL_PLANT_PATH_MAX]; /* armctrl: the ArmCtrl parameter table file (FRPT) */
    double duration;           /* simulated seconds > 0 */
    double frame_loss;         /* [0, 1) */
    uint64_t bus_seed;
    unsigned inject_every;     /* 0: off */
    double imu_dropout_start, imu_dropout_end; /* IMU PDOs lost in [start, end) [s] */
    double drive_dropout_start, drive_dropout_end; /* drive TPDOs lost in [start, end) [s] */
    double drive_busoff_start, drive_busoff_end;   /* drive bus-off in [start, end) [s] */
    struct hil_drive_params drive;
    struct hil_imu_params imu;
    struct hil_plant_params plant_p;
    struct hil_ctrl_params ctrl;
    char err[320];             /* why the last hil_rig_config_set/load failed ("" after success) */
};

struct hil_rig_stats {
    uint64_t cycles, frames_sent, frames_lost, frames_delivered, frames_logged;
    uint64_t injected, bus_off_episodes;
    uint64_t boot_frames;      /* frames of the SDO boot before cycle 0 */
};

struct hil_rig {
    struct hil_rig_config cfg;
    struct hil_drive drive;
    struct hil_imu imu;
    struct hil_plant plant;
    struct hil_ctrl ctrl;
    struct hil_rng bus_rng;
    struct hil_can_frame q[HIL_RIG_QUEUE];
    int q_from[HIL_RIG_QUEUE];
    int q_head, q_len;
    unsigned slot;             /* frames in the current cycle */
    unsigned booted_slots;     /* frames of the boot (logged before cycle 0's) */
    FILE *log, *csv;
    unsigned long log_bytes;   /* bytes written to log so far */
    unsigned long log_max;     /* bound of log_bytes: HIL_RIG_LOG_MAX after init, the caller may lower it */
    struct hil_rig_stats st;
    char err[320];             /* why init or the run failed ("" when it did not) */
};

/* Defaults: the thesis delays (hil_*_params_default), plant "rigid",
 * 1 s, no loss, no injection, bus seed 1. */
void hil_rig_config_default(struct hil_rig_config *c);

/* Reads "key = value" lines ('#' comments, at most 254 bytes) into c, on top of what it holds.
 * Keys: T (sets the cycle of every node), duration, plant, frame_loss,
 * bus_seed, inject_every, imu_dropout_start, imu_dropout_end, drive_dropout_start,
 * drive_dropout_end, drive_busoff_start, drive_busoff_end, ctrl.law, the file paths
 * plant.table and ctrl.table (no '#'), and the fields
 * of the node parameter structs as drive.*, imu.*, plant.*, ctrl.*. Returns HIL_OK, HIL_E_IO, or HIL_E_FORMAT with *line_no set to
 * the first bad line (unknown key, bad number, value out of range, line too
 * long); c->err names the key, the value and what is allowed. */
int hil_rig_config_load(struct hil_rig_config *c, const char *path, int *line_no);
/* Sets one key from text; HIL_OK, HIL_E_UNKNOWN_ID (c->err lists the keys of
 * the key's group), HIL_E_FORMAT (not a value of the key's type) or
 * HIL_E_RANGE (duration outside (0, HIL_RIG_DURATION_MAX], frame_loss outside
 * [0, 1)); c->err says "KEY = 'VALUE': what is allowed". */
int hil_rig_config_set(struct hil_rig_config *c, const char *key, const char *value);

/* Initialises every node and boots the devices by SDO (hil_ctrl_boot; its
 * frames go to the log); log and csv may be NULL. The CSV header is written
 * here. Returns HIL_OK, HIL_E_ARG (a parameter failed validation; r->err says
 * which) or HIL_E_STATE (the boot failed: r->err says why, from
 * r->ctrl.boot_error). */
int hil_rig_init(struct hil_rig *r, const struct hil_rig_config *c, FILE *log, FILE *csv);
/* Runs one controller cycle. HIL_OK, or HIL_E_FULL if the bus queue
 * overflowed or the log reached HIL_RIG_LOG_MAX (r->err says which). */
int hil_rig_cycle(struct hil_rig *r);
/* Runs round(duration / T) cycles, then NMT stop. */
int hil_rig_run(struct hil_rig *r);
/* Writes c as a scenario file (every key, %.17g: loads back bit for bit). */
int hil_rig_config_write(const struct hil_rig_config *c, FILE *f);
/* Opens the metadata JSON object and writes schema, version, mode, scenario,
 * seeds, every parameter and the effects, each line ending with ",". The
 * caller adds its own members and closes the object. */
int hil_rig_meta_begin(const struct hil_rig_config *c, const char *mode, FILE *f);
/* Writes the run metadata JSON (scenario, every parameter and effect, seeds,
 * version, frame counts, node receive counters). */
int hil_rig_write_meta(const struct hil_rig *r, FILE *f, double wall_s);

#endif
