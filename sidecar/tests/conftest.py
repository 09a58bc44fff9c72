"""Fixtures: in-process sidecar sessions (the Client below) and the real part ender3_e_plate."""

import json
import os
import sys
from pathlib import Path
from typing import Any

import pytest

# `python -m midsurf_sidecar` runs with sidecar/ on PYTHONPATH; give the tests the same, from any cwd.
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from midsurf_sidecar.server import PROTOCOL_VERSION, Session  # noqa: E402

from shapes import write_step  # noqa: E402

def _shared() -> Path:
    """The read-only ../shared beside the repository (MIDSURF_SHARED overrides); a clone elsewhere (say /tmp)
    falls back to the workplace's /work/shared."""
    if "MIDSURF_SHARED" in os.environ:
        return Path(os.environ["MIDSURF_SHARED"])
    beside = Path(__file__).resolve().parents[3] / "shared"
    return beside if beside.is_dir() else Path("/work/shared")


# MANIFEST.tsv: 56 faces, 9859.45 mm3, 64 x 64 x 27.4 mm.
E_PLATE = _shared() / "parts" / "ender3_e_plate.step"


class Client:
    """Sends requests to a Session the way the Rust side does, one JSON line each."""

    def __init__(self) -> None:
        self.session = Session()
        self._next_id = 0

    def request(self, op: str, **args: Any) -> dict[str, Any]:
        self._next_id += 1
        line = json.dumps({"id": self._next_id, "op": op, "args": args}).encode()
        reply = self.session.respond(line)
        assert reply["id"] == self._next_id
        # What goes on the wire must survive a strict JSON round trip.
        return json.loads(json.dumps(reply, allow_nan=False))

    def ok(self, op: str, **args: Any) -> dict[str, Any]:
        reply = self.request(op, **args)
        assert "ok" in reply, reply
        return reply["ok"]

    def err(self, op: str, **args: Any) -> dict[str, Any]:
        reply = self.request(op, **args)
        assert "err" in reply, reply
        assert "\n" not in reply["err"]["message"]
        return reply["err"]

    def load(self, shape, tmp_path: Path, name: str = "part.step") -> int:
        """Writes `shape` to STEP, loads it, returns the handle of its (single) solid."""
        solids = self.ok("load_step", path=str(write_step(shape, tmp_path / name)))["solids"]
        assert len(solids) == 1
        return solids[0]["handle"]


@pytest.fixture
def fresh_client() -> Client:
    return Client()


@pytest.fixture
def client() -> Client:
    c = Client()
    c.ok("hello", protocol=PROTOCOL_VERSION)
    return c


@pytest.fixture
def e_plate_path() -> Path:
    return E_PLATE


@pytest.fixture(scope="module")
def e_plate() -> tuple[Client, int, dict[str, Any]]:
    """The real part loaded and described once (mesh 0.1 mm) per test module: (client, handle, graph)."""
    c = Client()
    c.ok("hello", protocol=PROTOCOL_VERSION)
    handle = c.ok("load_step", path=str(E_PLATE))["solids"][0]["handle"]
    return c, handle, c.ok("describe", handle=handle, mesh=True, mesh_tolerance=0.1)
