"""The mesher's fallback machinery without gmsh: an attempt in a forked child (value, exception, crash, time
limit) and the merge of pieces meshed apart (nodes on curves by position, a surface's inside nodes apart)."""

import os
import signal
import time

from midsurf_mesher.child import in_child
from midsurf_mesher.per_surface import merge


def test_a_child_gives_its_value_or_why_not():
    assert in_child(lambda: {"a": [1, 2]}, 10).value == {"a": [1, 2]}
    failed = in_child(lambda: 1 / 0, 10)
    assert failed.value is None and "division by zero" in failed.failure
    crashed = in_child(lambda: os.kill(os.getpid(), signal.SIGKILL), 10)
    assert crashed.failure == "crashed (signal 9)"


def test_a_child_past_its_time_limit_is_killed():
    started = time.monotonic()
    outcome = in_child(lambda: time.sleep(60), 0.5)
    assert outcome.failure == "timed out after 0.5 s"
    assert time.monotonic() - started < 5


def test_pieces_meshed_apart_share_their_curve_nodes_and_keep_their_inside_nodes():
    # Two unit squares meshed in two children: the shared curve x = 1 gives the same two nodes (dim 1) in both;
    # each piece has an inside node (dim 2) at the same index 2, which must stay two nodes. Node 3 of the first
    # piece is unused and dropped.
    left = {"nodes": [[1, 0, 0], [1, 1, 0], [0.5, 0.5, 0], [9, 9, 9]], "node_dims": [1, 1, 2, 0],
            "elements": [{"surface": 1, "quads": [], "trias": [[0, 1, 2]]}]}
    right = {"nodes": [[1, 1, 0], [1, 0, 0], [1.5, 0.5, 0]], "node_dims": [1, 1, 2],
             "elements": [{"surface": 2, "quads": [], "trias": [[1, 2, 0]]}, {"surface": 3, "quads": [], "trias": []}]}
    merged = merge([left, right])
    assert merged["nodes"] == [[1, 0, 0], [1, 1, 0], [0.5, 0.5, 0], [1.5, 0.5, 0]]
    assert merged["node_dims"] == [1, 1, 2, 2]
    assert merged["elements"] == [
        {"surface": 1, "quads": [], "trias": [[0, 1, 2]]},
        {"surface": 2, "quads": [], "trias": [[0, 3, 1]]},
    ]
