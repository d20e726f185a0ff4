"""``fracarm-fleet``: fleet gap diagnosis and the sharded gap-bench on Dask.

  fracarm-fleet diagnose MANIFEST --out DIR [--scheduler ADDR | --workers N] [--effects e1,e2]
  fracarm-fleet bench [--cases N] [--seed S] [--duration D] [--noise X] [--scheduler ADDR | --workers N]
                      [--out FILE] [--json]

Exit status: 0 done; 1 some records failed (their errors are in the table,
the table is written) or a run error; 2 bad usage or manifest (nothing written).
"""
from __future__ import annotations

import argparse
import json
import os
import sys
from typing import List, Optional

from ..errors import FracarmError, UsageError


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="fracarm-fleet", description="Fleet gap diagnosis and sharded gap-bench on Dask.")
    sub = p.add_subparsers(dest="verb", required=True)
    d = sub.add_parser("diagnose", help="diagnose every record of a manifest; one Parquet table + reports")
    d.add_argument("manifest", help="CSV or Parquet: machine, data, [validate], model, [record]")
    d.add_argument("--out", required=True, help="output folder: fleet.parquet and records/<record>/")
    b = sub.add_parser("bench", help="gap-bench with one task per case")
    b.add_argument("--cases", type=int, default=28)
    b.add_argument("--seed", type=int, default=1)
    b.add_argument("--duration", type=float, default=2.4)
    b.add_argument("--noise", type=float, default=0.005)
    b.add_argument("--out", help="write the bench document (JSON) here")
    b.add_argument("--json", action="store_true", help="print the bench document")
    for q in (d, b):
        g = q.add_mutually_exclusive_group()
        g.add_argument("--scheduler", help="address of a running Dask scheduler (default: a LocalCluster)")
        g.add_argument("--workers", type=int, default=2, help="LocalCluster worker processes (default 2)")
    d.add_argument("--effects", help="candidate effects, comma-separated (default: all)")
    return p


def main(argv: Optional[List[str]] = None) -> int:
    from . import bench, diagnose

    a = _parser().parse_args(argv)
    try:
        if a.verb == "diagnose":
            eff = [e for e in a.effects.split(",") if e] if a.effects else None
            t = diagnose(a.manifest, a.out, scheduler=a.scheduler, workers=a.workers, effects=eff)
            bad = t[t["error"].notna()]
            print("fracarm-fleet: %d records, %d failed; table %s" % (len(t), len(bad), os.path.join(a.out, "fleet.parquet")))
            for _, r in bad.iterrows():
                print("  %s: %s" % (r["record"], r["error"]), file=sys.stderr)
            return 1 if len(bad) else 0
        doc = bench(a.cases, a.seed, a.duration, a.noise, scheduler=a.scheduler, workers=a.workers)
        text = json.dumps(doc, indent=2)
        if a.out:
            with open(a.out, "w") as f:
                f.write(text + "\n")
        if a.json:
            print(text)
        else:
            s = doc["score"]
            print("fracarm-fleet bench: %d cases, seed %d: top-1 %d/%d, median parameter error %s, median shrink %s"
                  % (s["cases"], a.seed, s["correct"], s["cases"], s["median_param_error"], s["median_shrink_found"]))
        return 0
    except UsageError as e:
        print("fracarm-fleet: %s" % e, file=sys.stderr)
        return 2
    except FracarmError as e:
        print("fracarm-fleet: error: %s" % e, file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
