"""The real process: `python -m midsurf_sidecar` over pipes, as the Rust binary runs it."""

import json
import os
import subprocess
import sys
from pathlib import Path

from midsurf_sidecar.server import PROTOCOL_VERSION

SIDECAR_DIR = Path(__file__).resolve().parents[1]


def run_sidecar(requests: list[dict | str], timeout: float = 120) -> subprocess.CompletedProcess:
    lines = [r if isinstance(r, str) else json.dumps(r) for r in requests]
    return subprocess.run(
        [sys.executable, "-m", "midsurf_sidecar"],
        input="".join(line + "\n" for line in lines),
        capture_output=True,
        text=True,
        env={**os.environ, "PYTHONPATH": str(SIDECAR_DIR)},
        cwd="/",
        timeout=timeout,
    )


def replies(process: subprocess.CompletedProcess) -> list[dict]:
    # Every stdout line is a protocol line: OCCT's own printing must have gone to stderr.
    return [json.loads(line) for line in process.stdout.splitlines()]


def test_session_over_pipes(tmp_path, e_plate_path):
    truncated = tmp_path / "half.step"
    truncated.write_bytes(e_plate_path.read_bytes()[:50_000])
    process = run_sidecar([
        {"id": 0, "op": "ping", "args": {}},
        {"id": 1, "op": "hello", "args": {"protocol": PROTOCOL_VERSION}},
        {"id": 2, "op": "ping", "args": {}},
        {"id": 3, "op": "load_step", "args": {"path": str(truncated)}},
        {"id": 4, "op": "load_step", "args": {"path": str(e_plate_path)}},
        {"id": 5, "op": "describe", "args": {"handle": 1, "mesh": True, "mesh_tolerance": 0.1}},
        {"id": 6, "op": "describe", "args": {"handle": 99}},
        {"id": 7, "op": "free", "args": {"handles": [1]}},
        {"id": 8, "op": "shutdown", "args": {}},
        {"id": 9, "op": "ping", "args": {}},
    ])
    assert process.returncode == 0, process.stderr
    got = replies(process)
    assert [r["id"] for r in got] == list(range(9))
    assert got[0]["err"]["code"] == "no_handshake"
    assert got[1]["ok"]["protocol"] == PROTOCOL_VERSION
    assert got[2]["ok"] == {"pong": True}
    assert got[3]["err"]["code"] in ("read_failed", "no_solid")
    assert got[4]["ok"]["solids"][0] == {**got[4]["ok"]["solids"][0], "handle": 1, "faces": 56}
    assert len(got[5]["ok"]["faces"]) == 56 and "mesh" in got[5]["ok"]["faces"][0]
    assert got[6]["err"]["code"] == "bad_args"
    assert got[7]["ok"] == {"freed": 1}
    assert got[8]["ok"] == {"bye": True}
    # The reader's complaint about the truncated file is OCCT output: stderr, not stdout.
    assert "StepFile" in process.stderr


def test_end_of_input_exits_cleanly():
    process = run_sidecar([{"id": 0, "op": "hello", "args": {"protocol": PROTOCOL_VERSION}}])
    assert process.returncode == 0, process.stderr
    assert replies(process)[0]["ok"]["protocol"] == PROTOCOL_VERSION


def test_garbage_and_blank_lines_do_not_kill_the_process():
    hello = {"id": 0, "op": "hello", "args": {"protocol": PROTOCOL_VERSION}}
    process = run_sidecar(["", "{not json", hello, {"id": 1, "op": "ping"}])
    assert process.returncode == 0, process.stderr
    got = replies(process)
    assert got[0]["id"] is None and got[0]["err"]["code"] == "bad_args"
    assert got[2] == {"id": 1, "ok": {"pong": True}}
