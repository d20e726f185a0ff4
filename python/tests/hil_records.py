"""Records of the HIL rig with known withheld effects, for the fleet tests.

Each record is the demo scenario (hil/scenarios/demo.txt: ArmCtrl Exp. A on
the two-mass plant) with one effect the nominal model
(hil/scenarios/demo_nominal.json) leaves out, its size drawn by a seeded
generator here (not a value any document prints): a torque-constant error
(drive.gain), a power-stage dead zone (drive.deadzone), viscous or Coulomb
motor friction (plant.friction = 0 with fric_b1 / fric_b0), or nothing.
truth: the effect and the diagnosis parameter it maps to (docs/hil.md,
docs/gap.md): gain_error.gain = drive.gain, deadzone.upper = -deadzone.lower =
drive.deadzone, viscous_friction.Fv = fric_b1, coulomb_friction.Fc = fric_b0.
"""
import json
import os
import subprocess

import numpy as np

FAMILIES = ["gain_error", "deadzone", "viscous_friction", "coulomb_friction", "none"]


def _base(src):
    keep = []
    for line in open(os.path.join(src, "hil", "scenarios", "demo.txt")):
        s = line.strip()
        if not s or s.startswith("#") or s.startswith("plant.fric") or s.startswith("plant.friction"):
            continue
        keep.append(s)
    return keep


def draw(rng, family):
    """(scenario lines, truth) for one record of `family`."""
    no_friction = ["plant.friction = 2"]  # Stribeck with b1s = b2s = b3s = 0: zero friction
    if family == "gain_error":
        g = float(rng.choice([rng.uniform(0.7, 0.9), rng.uniform(1.15, 1.35)]))
        return no_friction + ["drive.gain = %r" % g], {"effect": family, "params": {"gain": g}}
    if family == "deadzone":
        a = float(rng.uniform(2.0, 6.0))
        return no_friction + ["drive.deadzone = %r" % a], {"effect": family, "params": {"lower": -a, "upper": a}}
    if family == "viscous_friction":
        b = float(rng.uniform(1.5, 4.0))
        return ["plant.friction = 0", "plant.fric_b1 = %r" % b, "plant.fric_b0 = 0"], {"effect": family, "params": {"Fv": b}}
    if family == "coulomb_friction":
        c = float(rng.uniform(3.0, 7.0))
        return ["plant.friction = 0", "plant.fric_b1 = 0", "plant.fric_b0 = %r" % c], {"effect": family, "params": {"Fc": c}}
    return no_friction, {"effect": "none", "params": {}}


def make(src, hil_bench, nominal, out, n, seed):
    """Writes n records under out/ and out/manifest.csv; returns {record: truth}."""
    rng = np.random.default_rng(seed)
    base = _base(src)
    truths, rows = {}, ["machine,record,data,model"]
    for i in range(n):
        fam = FAMILIES[i % len(FAMILIES)]
        lines, truth = draw(rng, fam)
        rec = "arm%02d-shift%d" % (i % 7, i)
        d = os.path.join(out, rec)
        os.makedirs(d, exist_ok=True)
        scen = os.path.join(d, "scenario.txt")
        with open(scen, "w") as f:
            f.write("\n".join(base + lines) + "\n")
        subprocess.run([hil_bench, "--scenario", scen, "--out", os.path.join(d, "run")], check=True,
                       stdout=subprocess.DEVNULL)
        with open(os.path.join(d, "truth.json"), "w") as f:
            json.dump(truth, f)
        truths[rec] = truth
        rows.append("arm%02d,%s,%s/run/signals.csv,%s" % (i % 7, rec, rec, nominal))
    with open(os.path.join(out, "manifest.csv"), "w") as f:
        f.write("\n".join(rows) + "\n")
    return truths
