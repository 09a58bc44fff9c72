"""The mesher runs gmsh without address space randomisation (gmsh orders some entities by address, so that
with it one real part meshed one of two ways from run to run): the reply says so, and two runs give the same
mesh."""

import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def mesh(step: Path) -> dict:
    request = {"path": str(step), "size": 5.0, "all_quads": False, "time_floor_s": 60, "time_per_element_s": 0.002,
               "expected_elements": 1000}
    env = {**os.environ, "PYTHONPATH": str(ROOT / "sidecar")}
    env.pop("MIDSURF_MESHER_FIXED_LAYOUT", None)
    done = subprocess.run([sys.executable, "-m", "midsurf_mesher", "mesh"], input=json.dumps(request), env=env,
                          capture_output=True, text=True, check=True)
    return json.loads(done.stdout)


def test_gmsh_runs_with_a_fixed_address_layout_and_meshes_the_same_twice():
    first, second = (mesh(ROOT / "fixtures" / "pipe_tee.step") for _ in range(2))
    assert first["address_layout"] == "fixed", "personality(ADDR_NO_RANDOMIZE) refused: reruns may differ"
    assert first["whole_model"] == "meshed"
    assert (first["nodes"], first["elements"]) == (second["nodes"], second["elements"])
