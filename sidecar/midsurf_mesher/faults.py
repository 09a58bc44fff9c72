"""Test hook: MIDSURF_TEST_MESHER=fail:TAG or hang:TAG makes gmsh surface TAG fail (the whole model raises, every
retry of the surface leaves it empty) or hang (every attempt holding it sleeps until killed, with 1 s time
limits), so that the tests can drive the fallback on any fixture. Unset, nothing happens."""

import os
import time
from dataclasses import dataclass

HUNG_TIME_LIMIT_S = 1.0


@dataclass
class Fault:
    kind: str = ""
    surface: int = 0

    @staticmethod
    def from_env() -> "Fault":
        spec = os.environ.get("MIDSURF_TEST_MESHER", "")
        kind, _, tag = spec.partition(":")
        if kind in ("fail", "hang") and tag.isdigit():
            return Fault(kind, int(tag))
        return Fault()

    @property
    def hangs(self) -> bool:
        return self.kind == "hang"

    @property
    def time_limit_s(self) -> float:
        return HUNG_TIME_LIMIT_S

    def strike_whole(self) -> None:
        """In the whole-model attempt."""
        if self.kind == "fail":
            raise RuntimeError(f"injected failure on surface {self.surface}")
        if self.kind == "hang":
            time.sleep(3600)

    def strikes(self, surface: int) -> bool:
        """In an attempt on `surface` alone: True when it must come out empty (after sleeping, for a hang)."""
        if self.surface != surface or not self.kind:
            return False
        if self.kind == "hang":
            time.sleep(3600)
        return True
