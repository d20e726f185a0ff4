"""fracarm.gap.diagnose equals `fracdesign gap` on the same inputs (result.json
byte for byte but the wall time), from a path and from a DataFrame, and its
errors carry the CLI's messages."""
import json
import os
import subprocess

import pandas as pd
import pytest

from conftest import HIL_BENCH, SRC, cli
from fracarm import gap, models
from fracarm.errors import FracarmError, UsageError


@pytest.fixture(scope="module")
def record(tmp_path_factory):
    """The demo scenario with a torque-constant error of 0.83 (drawn for this test) withheld."""
    d = tmp_path_factory.mktemp("rec")
    lines = [l for l in open(os.path.join(SRC, "hil", "scenarios", "demo.txt"))
             if not l.startswith("plant.fric") and not l.startswith("#")]
    (d / "s.txt").write_text("".join(lines) + "plant.friction = 2\ndrive.gain = 0.83\n")
    subprocess.run([HIL_BENCH, "--scenario", str(d / "s.txt"), "--out", str(d / "run")], check=True, stdout=subprocess.DEVNULL)
    return str(d / "run" / "signals.csv")


def without_seconds(text):
    j = json.loads(text)
    j.pop("seconds")
    return j


def test_result_json_equals_the_cli(record, demo_nominal, tmp_path):
    args = ["--model", demo_nominal, "--data", record, "--out", str(tmp_path / "cli"), "--effects",
            "gain_error,deadzone,coulomb_friction,input_delay"]
    st, _, err = cli("gap", *args)
    assert st == 0, err
    cli_text = (tmp_path / "cli" / "result.json").read_text()
    r = gap.diagnose(demo_nominal, record, effects=["gain_error", "deadzone", "coulomb_friction", "input_delay"],
                     command="fracdesign gap " + " ".join(args))
    assert without_seconds(r.to_json()) == without_seconds(cli_text)
    # Byte for byte once the wall time agrees.
    j = json.loads(cli_text)
    assert r.to_json().replace('"seconds": %s' % json.dumps(r.doc["seconds"]), '"seconds": %s' % json.dumps(j["seconds"])) == cli_text
    assert r.verdict == ["gain_error"] and abs(r.parameters["gain"]["value"] - 0.83) < 0.01
    assert r.parameters["gain"]["unit"] == "1" and r.parameters["gain"]["std"] > 0
    assert r.gap_after < r.gap_before and r.candidates[0]["effect"] == "gain_error"
    r.report(tmp_path / "r.html")
    assert (tmp_path / "r.html").read_text().startswith("<!DOCTYPE html>") or "<html" in (tmp_path / "r.html").read_text()


def test_dataframe_and_model_object_give_the_cli_result(record, demo_nominal, tmp_path):
    st, _, err = cli("gap", "--model", demo_nominal, "--data", record, "--out", str(tmp_path / "cli"), "--effects",
                     "gain_error,deadzone")
    assert st == 0, err
    ref = without_seconds((tmp_path / "cli" / "result.json").read_text())
    r = gap.diagnose(models.load(demo_nominal), pd.read_csv(record), effects=["gain_error", "deadzone"])
    got = without_seconds(r.to_json())
    for j in (ref, got):
        j.pop("command"), j.pop("data")
    assert got == ref


def test_validation_record(record, demo_nominal, tmp_path):
    st, _, err = cli("gap", "--model", demo_nominal, "--data", record, "--validate", record, "--out", str(tmp_path / "c"),
                     "--effects", "gain_error")
    assert st == 0, err
    r = gap.diagnose(demo_nominal, record, validate=pd.read_csv(record), effects=["gain_error"])
    assert r.doc["verdict"]["params"] == json.loads((tmp_path / "c" / "result.json").read_text())["verdict"]["params"]


def test_errors_carry_the_cli_messages(record, demo_nominal, tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("t,torque_actual,motor_velocity\n0,0,0\n0.0012,nan,0\n0.0024,0,0\n0.0036,0,0\n")
    cases = [
        (dict(model=demo_nominal, data=str(bad)), ["--model", demo_nominal, "--data", str(bad)], FracarmError, 1),
        (dict(model=str(tmp_path / "none.json"), data=record), ["--model", str(tmp_path / "none.json"), "--data", record],
         FracarmError, 1),
        (dict(model=demo_nominal, data=record, holdout=1.5), ["--model", demo_nominal, "--data", record, "--holdout", "1.5"],
         UsageError, 2),
        (dict(model=demo_nominal, data=record, loop_feedback="simulated"),
         ["--model", demo_nominal, "--data", record, "--loop-feedback", "simulated"], UsageError, 2),
    ]
    for kw, args, exc, status in cases:
        with pytest.raises(exc) as e:
            gap.diagnose(**kw)
        st, _, err = cli("gap", *args, "--out", str(tmp_path / "never"))
        assert st == status and str(e.value) in err, (str(e.value), err)
        assert not (tmp_path / "never").exists()
    with pytest.raises(UsageError, match="unknown effect 'warp_drive'"):
        gap.diagnose(demo_nominal, record, effects=["warp_drive"])
    df = pd.read_csv(record)
    df.loc[5, "t"] = df.loc[4, "t"]
    with pytest.raises(FracarmError, match="<DataFrame data>"):
        gap.diagnose(demo_nominal, df)


def test_armctrl_documents_are_replayed_with_the_plc_program(record, demo_nominal, tmp_path):
    """The package registers the kind "armctrl" (gap-plc's): a document naming a missing ArmCtrl table is
    refused by that kind (its table field), not as a kind this program cannot replay."""
    doc = json.loads(open(demo_nominal).read())
    y = doc["outputs"][0]
    doc.setdefault("gap", {})["closed_loop"] = {"references": [], "measured": [y], "controller": {
        "kind": "armctrl", "table": "no_such_table.bin", "inputs": {"MotorAngle": y, "MotorVelocity": y, "TipRate": y}}}
    (tmp_path / "n.json").write_text(json.dumps(doc))
    with pytest.raises(FracarmError, match=r"gap.closed_loop.controller.table: cannot open the ArmCtrl table"):
        gap.diagnose(str(tmp_path / "n.json"), record)
