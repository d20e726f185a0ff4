# %% [markdown]
# # fracarm in a notebook: design, simulate with libfrac, diagnose a HIL record
#
# Run as a script (`build/pyvenv-fracarm/bin/python docs/python_example.py BUILD_DIR OUT_DIR`)
# or cell by cell in Jupyter. The tests run it (python/tests/test_example.py).

# %%
import os
import subprocess
import sys

import control
import numpy as np
import pandas as pd

import fracarm
from fracarm import design, frac, gap, models

build = sys.argv[1] if len(sys.argv) > 1 else "build"
out = sys.argv[2] if len(sys.argv) > 2 else "python_example_out"
os.makedirs(out, exist_ok=True)

# %% [markdown]
# ## 1. Tune an FO-PI for a fractional plant (seed 001), run it with libfrac

# %%
t = design.tune("fopi", K=1.0, T=0.25, lambda_=1.5, wc=2.0, phim=0.9, alpha=0.6)
print(sorted(t))
c = t["controller"]  # C(s) = Kp + Ki s^-alpha
pi = frac.FoPid(ts=1e-3, kp=c["Kp"], ki=c["Ki"], lam=c["alpha"], op={"method": "oustaloup", "wb": 0.01, "wh": 1000, "n": 5})
u = pi.run(np.ones(5000), np.zeros(5000))  # open-loop response to a unit error
print("FO-PI output after 1 s and 5 s:", u[999], u[-1])

# %% [markdown]
# ## 2. A python-control model as a project model document, and back

# %%
G = control.tf([400.0], [1.0, 4.0, 400.0])
m = models.Model.from_control(G, inputs=["tau [N m]"], outputs=["omega [rad/s]"], name="example resonance")
m.save(os.path.join(out, "resonance.json"))
back = models.load(os.path.join(out, "resonance.json")).to_control()
print("DC gain", control.dcgain(back), "poles", back.poles())

# %% [markdown]
# ## 3. Record a run on the HIL rig with a withheld torque-constant error, diagnose it

# %%
src = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
scen = [l for l in open(os.path.join(src, "hil", "scenarios", "demo.txt")) if not l.startswith(("#", "plant.fric"))]
with open(os.path.join(out, "scenario.txt"), "w") as f:
    f.write("".join(scen) + "plant.friction = 2\ndrive.gain = 0.9\n")  # no friction; a 10 % weaker torque constant
subprocess.run([os.path.join(build, "hil", "hil_bench"), "--scenario", os.path.join(out, "scenario.txt"),
                "--out", os.path.join(out, "run")], check=True, stdout=subprocess.DEVNULL)
data = pd.read_csv(os.path.join(out, "run", "signals.csv"))
r = gap.diagnose(os.path.join(src, "hil", "scenarios", "demo_nominal.json"), data, effects=["gain_error", "deadzone", "coulomb_friction"])
print(r)
for name, p in r.parameters.items():
    print("  %s = %.4g +- %.2g [%s]" % (name, p["value"], p["std"] or float("nan"), p["unit"]))
r.report(os.path.join(out, "report.html"))
gain = r.parameters["gain_error.gain" if len(r.verdict) > 1 else "gain"]["value"]
assert r.verdict[0] == "gain_error" and abs(gain - 0.9) < 0.01
