#!/usr/bin/python3
"""A series mode in a clipped servo loop that cycles: the closed-loop fit
alone lands in another basin of the mode's frequency; `auto` starts it again
where the pass on the measured outputs found the mode (docs/gap.md "Loop
feedback", the second pass as a source of starts).

The case is drawn by outside_cases.py (its own simulator and nominal, seed
41 case 25 of its sample: a mode in series at the actuator); the truth is
what that generator drew, not a number copied here.

CLI: test_seeded_refit.py --fracdesign PATH --out DIR
"""
import argparse
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import outside_cases as oc  # noqa: E402

CASE_SEED = 41 * 100003 + 25 * 7 + 1   # outside_cases.py's plan: seed 41, case 25


def diagnose(fd, case_dir, feedback):
    out = os.path.join(case_dir, "gap_" + feedback)
    cmd = [fd, "gap", "--model", os.path.join(case_dir, "nominal.json"),
           "--data", os.path.join(case_dir, "record.csv"), "--out", out,
           "--outputs", "q", "--loop-feedback", feedback]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit("%s failed (exit %d): %s" % (" ".join(cmd), r.returncode, r.stderr[-2000:]))
    with open(os.path.join(out, "result.json")) as f:
        return json.load(f)


def mode_param(v, name):
    """A parameter of the verdict's mode (keys are prefixed with the effect
    when the verdict holds more than one)."""
    p = v["params"]
    return p.get("unmodelled_mode." + name, p.get(name))


def mode_error(res, f_true):
    v = res["verdict"]
    if not v["effects"] or v["effects"][0] != "unmodelled_mode" or v["sites"][0] != "force_input":
        return None
    return abs(mode_param(v, "f_hz") / f_true - 1)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--fracdesign", required=True)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    case_dir = os.path.join(a.out, "servo_series_mode")
    truth = oc.make_case("servo", "unmodelled_mode", CASE_SEED, case_dir)
    e = truth["effect"]
    assert e["name"] == "unmodelled_mode" and e["site"] == "actuator", e
    f_true = e["f"]
    fails = []
    # The premise: the closed loop alone names the mode at another frequency.
    model = diagnose(a.fracdesign, case_dir, "model")
    err_model = mode_error(model, f_true)
    print("model:  %s, f error %s, shrink %.3f" % (model["verdict"]["effects"], err_model,
                                                   model["verdict"]["shrink"]))
    if err_model is not None and err_model < 0.1:
        fails.append("premise: the closed loop alone found the mode within 10 %% (%.3f): the case no longer "
                     "tests the seeded refit" % err_model)
    auto = diagnose(a.fracdesign, case_dir, "auto")
    err_auto = mode_error(auto, f_true)
    v = auto["verdict"]
    note = auto["data"].get("loop_feedback_note", "")
    print("auto:   %s, f error %s, zeta %.4f (drawn %.4f), shrink %.3f\n  note: %s" % (
        v["effects"], err_auto, mode_param(v, "zeta") or float("nan"), e["zeta"], v["shrink"], note))
    if err_auto is None or err_auto > 0.01:
        fails.append("auto: the series mode is not named within 1 %% of the drawn %.3f Hz" % f_true)
    elif abs(mode_param(v, "zeta") / e["zeta"] - 1) > 0.05:
        fails.append("auto: zeta not within 5 % of the drawn one")
    if v["shrink"] < 0.95 or v["shrink"] <= model["verdict"]["shrink"]:
        fails.append("auto: shrink %.3f, not >= 0.95 and above the closed loop alone's" % v["shrink"])
    if auto["data"].get("loop_feedback") != "model outputs" or "also started" not in note:
        fails.append("auto: the result is not the closed-loop refit started from the measured pass")
    for f in fails:
        print("FAIL " + f)
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
