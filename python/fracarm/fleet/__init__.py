"""Fleet-scale gap diagnosis and a sharded gap-bench on Dask distributed (issue 20).

:func:`diagnose` takes a manifest of records (CSV or Parquet; one row per
record: ``machine``, ``data``, optional ``validate``, ``model``, optional
``record`` id) and runs one Dask task per record on a
``dask.distributed.Client``: a LocalCluster by default, or the scheduler at
``scheduler`` for a real cluster. Each task runs :func:`fracarm.gap.diagnose`
and writes ``<out>/records/<record>/result.json`` and ``report.html``
atomically; a record whose files are bad gets its error in its row and the
others complete. The result is one Parquet table ``<out>/fleet.parquet``
(written atomically) with a row per manifest row, in manifest order.

Tasks are pure functions of their row (they write only their own record's
files, through a rename), so the scheduler may rerun any of them: a worker
that dies mid-run has its tasks rescheduled on the others (Dask's
``distributed.scheduler.allowed-failures`` bounds how often one task may
take a worker down) and the table is still complete.

:func:`bench` shards ``gap-bench`` across the cluster, one task
per case (``gap-bench --replay ID``, the bench's one-case entry: a case
depends only on the seed, its id, the duration and the noise), and scores
the gathered cases with the bench's own scoring, so its cases and scores are
the single-machine bench's for the same seed.
"""
from __future__ import annotations

import json
import os
import re
import subprocess
import tempfile
import time
from typing import Any, Dict, List, Optional, Sequence

from .. import _fracarm
from ..errors import FracarmError, UsageError

COLUMNS = ["machine", "record", "data", "validate", "model", "verdict", "effects", "sites", "gap_before",
           "gap_after", "shrink", "params", "params_std", "wall_s", "worker", "report", "error"]
_ID = re.compile(r"[^A-Za-z0-9_.-]+")


def _fracdesign() -> str:
    """The fracdesign executable: $FRACARM_FRACDESIGN, else this build's."""
    from .. import _build_paths

    return os.environ.get("FRACARM_FRACDESIGN") or _build_paths.FRACDESIGN


def _gap_bench() -> str:
    """The gap-bench executable (bench/): $FRACARM_GAP_BENCH, else this build's."""
    from .. import _build_paths

    return os.environ.get("FRACARM_GAP_BENCH") or _build_paths.GAP_BENCH


def read_manifest(path: str | os.PathLike):
    """The manifest as a DataFrame with columns machine, record, data, validate, model.

    CSV (``.csv``) or Parquet (``.parquet``/``.pq``). Relative file paths are
    taken relative to the manifest's folder. ``record`` defaults to
    ``<machine>-<row number>``; record ids must be unique. Raises UsageError
    naming the missing column, the duplicated id or the unknown format.
    """
    import pandas as pd

    path = os.fspath(path)
    ext = os.path.splitext(path)[1].lower()
    try:
        if ext == ".csv":
            df = pd.read_csv(path, dtype=str, keep_default_na=False)
        elif ext in (".parquet", ".pq"):
            df = pd.read_parquet(path).astype(str)
        else:
            raise UsageError("manifest %s: format '%s' is not one of .csv, .parquet, .pq" % (path, ext))
    except (OSError, ValueError) as e:
        if isinstance(e, UsageError):
            raise
        raise FracarmError("manifest %s: %s" % (path, e)) from None
    for col in ("machine", "data", "model"):
        if col not in df.columns:
            raise UsageError("manifest %s: column '%s' is missing (columns: machine, data, model, optional validate, record)"
                             % (path, col))
    if "validate" not in df.columns:
        df["validate"] = ""
    if "record" not in df.columns:
        df["record"] = ["%s-%d" % (m, i) for i, m in enumerate(df["machine"])]
    df["record"] = [_ID.sub("_", r) for r in df["record"]]
    dup = df["record"][df["record"].duplicated()]
    if len(dup):
        raise UsageError("manifest %s: record id '%s' appears more than once" % (path, dup.iloc[0]))
    base = os.path.dirname(os.path.abspath(path))
    for col in ("data", "validate", "model"):
        df[col] = [os.path.join(base, p) if p and not os.path.isabs(p) else p for p in df[col]]
    return df[["machine", "record", "data", "validate", "model"]].reset_index(drop=True)


def diagnose_record(row: Dict[str, str], out_dir: str, effects: Optional[Sequence[str]] = None) -> Dict[str, Any]:
    """One record's task: the diagnosis, its files, its table row. Never raises for a bad record."""
    from .. import gap

    t0 = time.perf_counter()
    rec_dir = os.path.join(out_dir, "records", row["record"])
    res: Dict[str, Any] = {k: row.get(k, "") for k in ("machine", "record", "data", "validate", "model")}
    res.update(verdict=None, effects=None, sites=None, gap_before=None, gap_after=None, shrink=None, params=None,
               params_std=None, report=None, error=None, worker=_worker_name())
    try:
        r = gap.diagnose(row["model"], row["data"], validate=row.get("validate") or None, effects=effects, threads=1)
        _write_dir(rec_dir, {"result.json": r.to_json(), "report.html": r._html})
        v = r.doc["verdict"]
        res.update(verdict=" + ".join(r.verdict) or "none", effects=json.dumps(r.verdict), sites=json.dumps(r.sites),
                   gap_before=r.gap_before, gap_after=r.gap_after, shrink=r.shrink,
                   params=json.dumps(v["params"]), params_std=json.dumps(v["params_std"]),
                   report=os.path.join(rec_dir, "report.html"))
    except (FracarmError, OSError) as e:
        res["error"] = str(e)
    res["wall_s"] = time.perf_counter() - t0
    return res


def _worker_name() -> str:
    try:
        from distributed import get_worker

        return get_worker().address
    except (ImportError, ValueError):
        return "local"


def _write_dir(d: str, files: Dict[str, str]) -> None:
    """Writes the files into d through a temporary sibling renamed into place."""
    parent = os.path.dirname(d)
    os.makedirs(parent, exist_ok=True)
    tmp = tempfile.mkdtemp(dir=parent, prefix=".tmp-")
    try:
        for name, text in files.items():
            with open(os.path.join(tmp, name), "w") as f:
                f.write(text)
        os.makedirs(d, exist_ok=True)
        for name in files:
            os.replace(os.path.join(tmp, name), os.path.join(d, name))
    finally:
        for name in os.listdir(tmp):
            os.unlink(os.path.join(tmp, name))
        os.rmdir(tmp)


def _client(client=None, scheduler: Optional[str] = None, workers: int = 2):
    """(client, owned): the given client, one connected to `scheduler`, or a new LocalCluster's."""
    from distributed import Client, LocalCluster

    if client is not None:
        return client, None
    if scheduler:
        return Client(scheduler), None
    cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=":0")
    return Client(cluster), cluster


def diagnose(manifest, out_dir: str | os.PathLike, client=None, scheduler: Optional[str] = None, workers: int = 2,
             effects: Optional[Sequence[str]] = None, on_result=None):
    """Diagnoses every record of ``manifest`` (a path or a DataFrame from :func:`read_manifest`).

    Returns the table (a DataFrame, manifest order) and writes it to
    ``<out_dir>/fleet.parquet``. ``on_result(row)`` is called as each record
    completes (the tests use it to kill a worker mid-run).
    """
    import pandas as pd
    from distributed import as_completed

    out_dir = os.path.abspath(os.fspath(out_dir))
    df = read_manifest(manifest) if not isinstance(manifest, pd.DataFrame) else manifest
    os.makedirs(out_dir, exist_ok=True)
    c, cluster = _client(client, scheduler, workers)
    try:
        rows = df.to_dict("records")
        futs = [c.submit(diagnose_record, row, out_dir, effects, key="gap-%s" % row["record"], pure=False)
                for row in rows]
        done: Dict[str, Dict[str, Any]] = {}
        for fut in as_completed(futs):
            r = fut.result()
            done[r["record"]] = r
            if on_result is not None:
                on_result(r)
    finally:
        if cluster is not None:
            c.close()
            cluster.close()
    table = pd.DataFrame([done[r["record"]] for r in rows], columns=COLUMNS)
    write_table(table, os.path.join(out_dir, "fleet.parquet"))
    return table


def write_table(table, path: str) -> None:
    """Parquet through a temporary file renamed into place."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    schema = pa.schema([(c, pa.float64() if c in ("gap_before", "gap_after", "shrink", "wall_s") else pa.string())
                        for c in COLUMNS])
    tab = pa.Table.from_pandas(table[COLUMNS], schema=schema, preserve_index=False)
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(path), prefix=".fleet-", suffix=".parquet")
    os.close(fd)
    try:
        pq.write_table(tab, tmp)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def bench_case(case_id: int, cases: int, seed: int, duration: float, noise: float) -> Dict[str, Any]:
    """One gap-bench case: ``gap-bench --replay case_id --json``'s case entry."""
    cmd = [_gap_bench(), "--cases", str(cases), "--seed", str(seed), "--duration", repr(float(duration)),
           "--noise", repr(float(noise)), "--replay", str(case_id), "--json"]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode not in (0, 1):
        raise FracarmError(p.stderr.strip() or "%s: exit status %d" % (" ".join(cmd), p.returncode))
    j = json.loads(p.stdout)
    (case,) = j["cases"]
    case["_bench"] = {k: v for k, v in j.items()
                      if k not in ("cases", "replay", "score", "confusion", "per_effect", "goals")}
    return case


def bench(cases: int = 28, seed: int = 1, duration: float = 2.4, noise: float = 0.005, client=None,
          scheduler: Optional[str] = None, workers: int = 2) -> Dict[str, Any]:
    """gap-bench sharded over the cluster, one task per case.

    Returns the bench document as ``gap-bench --json`` has it
    (schema, seed, cases, score, confusion, goals; "replay" -1).
    """
    if not 1 <= int(cases) <= 100000:
        raise UsageError("--cases must be in 1..100000")
    if int(seed) < 0:
        raise UsageError("--seed must be >= 0")
    c, cluster = _client(client, scheduler, workers)
    try:
        futs = [c.submit(bench_case, i, int(cases), int(seed), duration, noise, key="gap-bench-%d-%d-%d" % (seed, cases, i),
                         pure=False) for i in range(int(cases))]
        got = c.gather(futs)
    finally:
        if cluster is not None:
            c.close()
            cluster.close()
    got.sort(key=lambda x: x["id"])
    head = got[0]["_bench"]
    for g in got:
        del g["_bench"]
    scored = json.loads(_fracarm.bench_score(json.dumps(got)))
    doc = dict(head)
    doc.update(replay=-1, cases=got, **scored)
    return doc
