"""Checks of arm_document_chain.sh's outputs with bounds derived from the design (issue 16).

Prints the figures (first three modes full vs reduced, spectral radius, tracking error RMS/peak with
both feedforwards, torque range, gap verdict) and writes them to figures.json; exits 1 on a failure."""
import csv, json, math, sys

arm_path, move, fc, d = sys.argv[1], sys.argv[2], float(sys.argv[3]), sys.argv[4]
arm = json.load(open(arm_path))
model = json.load(open(d + "/model.json"))
lqg = json.load(open(d + "/lqg.json"))
inv = json.load(open(d + "/armctrl_inverse.json"))
fails = []

def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        fails.append(what)

T = arm["sample_time"]; di = arm["delays"]["input"]; do = arm["delays"]["output"]
modes = model["retained"][:3]
for m in modes:
    print("mode: full %.5f Hz, reduced %.5f Hz, error %.2e" % (m["full_hz"], m["reduced_hz"], m["rel_error"]))
below = [m for m in model["retained"] if m["full_hz"] <= model["bandwidth_hz"] * (1 + 1e-9)]
check(len(below) >= 1 and all(m["rel_error"] <= arm.get("design", {}).get("mode_error_max", 0.01) for m in below),
      "retained modes at or below the bandwidth within design.mode_error_max")
cu = lqg["check_unreduced"]
check(cu["plant_di"] == di and cu["plant_do"] == do, "loop checked with the document's delays")
check(cu["spectral_radius"] < 1.0, "LQG stable on the unreduced arm: spectral radius %.9f" % cu["spectral_radius"])

def run(name):
    rows = list(csv.DictReader(open("%s/%s/signals.csv" % (d, name))))
    e = [float(r["tip_angle"]) - float(r["ref"]) for r in rows]
    tq = [float(r["torque_cmd"]) for r in rows]
    return math.sqrt(sum(x * x for x in e) / len(e)), max(abs(x) for x in e), min(tq), max(tq), float(rows[-1]["tip_angle"])

# move amplitude and peak speed from the sin^2 segments "Q0:Q1@T0+DUR,..." (qd_m = 1.5 s_e / DUR)
q0, rest = move.split(":", 1)
q, qd_max, q_end = float(q0), 0.0, float(q0)
for seg in rest.split(","):
    qe, tt = seg.split("@"); t0, dur = tt.split("+")
    qd_max = max(qd_max, 1.5 * abs(float(qe) - q) / float(dur)); q = q_end = float(qe)
rms_i, peak_i, tmin_i, tmax_i, end_i = run("run_inverse")
rms_r, peak_r, tmin_r, tmax_r, end_r = run("run_rigid")
print("tip tracking inverse-model ff: rms %.3e rad, peak %.3e rad; rigid-body ff: rms %.3e rad, peak %.3e rad" % (rms_i, peak_i, rms_r, peak_r))
print("torque inverse-model ff %.3f .. %.3f N m; rigid-body ff %.3f .. %.3f N m" % (tmin_i, tmax_i, tmin_r, tmax_r))
# bound: the distance the tip covers at its peak speed during the loop's dead time (d_i + d_o) T
lag = (di + do) * T * qd_max
check(peak_i < lag, "inverse-model ff peak error %.3e < (d_i + d_o) T qd_max = %.3e rad" % (peak_i, lag))
check(rms_i < rms_r, "the inverse-model feedforward tracks better than the rigid-body one (rms %.3e < %.3e)" % (rms_i, rms_r))
check(abs(end_i - q_end) < 0.01 * abs(q_end - float(q0)) + 1e-9, "final tip within 1 %% of the move (%.5f rad)" % end_i)
peak = arm["drive"]["torque_peak"]
check(max(abs(tmin_i), abs(tmax_i)) <= peak, "torque within drive.torque_peak")
check(max(abs(tmin_i), abs(tmax_i)) <= 2.0 * inv["tau_M_max"] + 0.1 * arm["drive"]["torque_rated"],
      "torque within twice the feedforward's peak + 10 % rated")
g = json.load(open(d + "/gap/result.json"))
v = g["verdict"]
print("gap verdict: %s %s, shrink %.3f" % ("+".join(v["effects"]), v["params"], v["shrink"]))
check(v["effects"][:1] == ["coulomb_friction"], "the gap verdict names the withheld Coulomb friction first")
fcv = v["params"].get("Fc", v["params"].get("coulomb_friction.Fc", float("nan")))
check(abs(fcv - fc) < 0.1 * fc, "fitted Fc %.4g within 10 %% of the withheld %.4g N m" % (fcv, fc))
check(not v.get("unidentified"), "the fitted parameters are identified (the record pins Fc), flagged: %s" % v.get("unidentified"))
json.dump({"modes": modes, "spectral_radius_unreduced": cu["spectral_radius"], "gain_margin_db": cu["gain_margin_db"],
           "phase_margin_deg": cu["phase_margin_deg"],
           "tracking": {"inverse": {"rms": rms_i, "peak": peak_i}, "rigid": {"rms": rms_r, "peak": peak_r}},
           "torque": {"inverse": [tmin_i, tmax_i], "rigid": [tmin_r, tmax_r]},
           "gap": {"withheld_Fc": fc, "verdict": v["effects"], "params": v["params"], "shrink": v["shrink"]}},
          open(d + "/figures.json", "w"), indent=1)
sys.exit(1 if fails else 0)
