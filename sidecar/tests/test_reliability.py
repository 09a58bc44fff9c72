"""Failure isolation and the reader's problems in the sidecar: a face the kernel cannot describe is described
as far as it can be, with its reason; a bad entity is reported by number; the sidecar dies with its parent."""

import os
import subprocess
import sys
from pathlib import Path

from shapes import box, write_step

REPO = Path(__file__).resolve().parents[2]
SIDECAR = REPO / "sidecar"


def test_a_face_with_no_point_inside_is_kept_with_its_problem(client):
    # The groove's floor, a ring 2e-6 wide: no point inside it is found (describe failed on it as a whole).
    path = REPO / "fixtures" / "plate_hairline_groove.step"
    handle = client.ok("load_step", path=str(path))["solids"][0]["handle"]
    graph = client.ok("describe", handle=handle, mesh=True, mesh_tolerance=0.1)
    troubled = [f for f in graph["faces"] if "problem" in f]
    assert [f["id"] for f in troubled] == [7]
    assert "no point inside the face" in troubled[0]["problem"]
    # Still whole: its loops name its edges, and each of those edges names it.
    for e in (e for loop in troubled[0]["loops"] for e in loop):
        assert 7 in graph["edges"][e]["faces"]
    assert all("mesh" in f and "loops" in f for f in graph["faces"])


def _with_line(text: str, line: str) -> str:
    end = text.rindex("ENDSEC;")
    return text[:end] + line + "\n" + text[end:]


def test_a_bad_entity_nothing_uses_is_reported_by_number(client, tmp_path):
    clean = write_step(box(10, 20, 30), tmp_path / "box.step")
    assert client.ok("load_step", path=str(clean))["entity_problems"] == []
    bad = tmp_path / "bad.step"
    bad.write_text(_with_line(clean.read_text(), "#9003 = CARTESIAN_POINT('',(1.,2.,3.),5.);"))
    loaded = client.ok("load_step", path=str(bad))
    assert len(loaded["solids"]) == 1
    assert loaded["entity_problems"] == [
        {"entity": 9003, "message": "Count of Parameters is not 2 for cartesian_point", "used": False}
    ]


def test_the_sidecar_leaves_at_once_when_its_parent_is_already_gone():
    env = dict(os.environ, PYTHONPATH=str(SIDECAR), MIDSURF_PARENT_PID="1")
    done = subprocess.run(
        [sys.executable, "-c", "from midsurf_sidecar.lifeline import tie_to_parent; tie_to_parent(); print('alive')"],
        env=env, capture_output=True, text=True, timeout=60,
    )
    assert done.returncode == 1 and "alive" not in done.stdout


def test_the_parent_death_signal_is_set():
    env = dict(os.environ, PYTHONPATH=str(SIDECAR), MIDSURF_PARENT_PID=str(os.getpid()))
    code = (
        "import ctypes; from midsurf_sidecar.lifeline import tie_to_parent; tie_to_parent();"
        "sig = ctypes.c_int(); ctypes.CDLL(None).prctl(2, ctypes.byref(sig), 0, 0, 0); print(sig.value)"
    )
    done = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=60)
    assert done.stdout.strip() == "9", done.stderr
