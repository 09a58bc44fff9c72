"""scripts/dask_batch.py on a dask.distributed LocalCluster: the same outputs as `midsurf batch`, one summary,
and a second pass that runs nothing."""

import importlib.util
import json
import shutil
import subprocess
from pathlib import Path

from dask.distributed import Client, LocalCluster

ROOT = Path(__file__).resolve().parents[2]
MIDSURF = ROOT / "target/release/midsurf"  # built by scripts/setup, as scripts/test runs it first


def load_driver():
    spec = importlib.util.spec_from_file_location("dask_batch", ROOT / "scripts/dask_batch.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_dask_batch_matches_midsurf_batch(tmp_path):
    inputs = tmp_path / "in"
    inputs.mkdir()
    for name in ["flat_plate", "l_bracket", "t_rib"]:
        shutil.copy(ROOT / "fixtures" / f"{name}.step", inputs)
    reference = tmp_path / "ref"
    subprocess.run([MIDSURF, "batch", inputs, "-o", reference, "--t-max", "5"], check=True, capture_output=True)

    driver = load_driver()
    out = tmp_path / "dask"
    argv = [str(inputs), "-o", str(out), "--midsurf", str(MIDSURF), "--", "--t-max", "5"]
    # Worker processes, as on a real cluster: tasks and results cross process boundaries pickled.
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with Client(cluster) as client:
            assert driver.main(argv, client=client) == 0

    for name in ["flat_plate", "l_bracket", "t_rib"]:
        assert (out / f"{name}.step").read_bytes() == (reference / f"{name}.step").read_bytes(), name
    summary = json.loads((out / "batch-summary.json").read_text())
    rows = summary["parts"]
    assert [r["part"] for r in rows] == ["flat_plate", "l_bracket", "t_rib"]
    assert [r["status"] for r in rows] == ["reused"] * 3, "the closing pass reuses what the tasks made"
    ref_rows = json.loads((reference / "batch-summary.json").read_text())["parts"]
    strip = lambda r: {k: v for k, v in r.items() if k not in ("time_s", "status", "input")}
    assert [strip(r) for r in rows] == [strip(r) for r in ref_rows]
    assert sorted(p.name for p in out.glob("batch-summary*")) == ["batch-summary.csv", "batch-summary.json"]
