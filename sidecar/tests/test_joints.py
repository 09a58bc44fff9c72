"""probe_edges, extend_edges and gather: a T joint made by growing the rib's free edge down to the base."""

import pytest
from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox
from OCP.gp import gp_Pnt

from patch_shapes import horizontal, put_patches, rectangle
from test_fuse import fuse


def t_solid(client) -> int:
    """Base plate z 0..2 and a rib x 29..31 up to z 40, as one box each (their union is irrelevant here: only
    inside/outside of the points past the rib's free edge is asked)."""
    box = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), gp_Pnt(60, 40, 2)).Shape()
    return client.session.store.put(box)


def rib(z0: float):
    """x = 30 over y in [0, 40], z in [z0, 40]."""
    return rectangle((30, 0, z0), (30, 40, z0), (30, 40, 40), (30, 0, 40))


def free_edge_of(fused, patch, z):
    """(edge, face) of the free edge of `patch` lying at height z."""
    for i, face in enumerate(fused["faces"]):
        if face["patch"] != patch:
            continue
        for e in face["edges"]:
            edge = fused["edges"][e]
            if len(edge["faces"]) == 1 and all(p[2] == pytest.approx(z) for p in edge["points"]):
                return e, i
    raise AssertionError(f"no free edge of patch {patch} at z={z}")


def test_rib_edge_reaches_base_then_strip_shares_the_t_edge(client):
    solid = t_solid(client)
    fused = fuse(client, put_patches(client, horizontal(), rib(2.0)))
    edge, face = free_edge_of(fused, 1, 2.0)
    targets = list(range(len(fused["faces"])))
    reply = client.ok(
        "probe_edges", handle=fused["handle"], edges=[{"edge": edge, "face": face, "solid": solid}],
        targets=targets, samples=5, reach=3.0, step=0.5,
    )
    (probe,) = reply["edges"]
    assert len(probe["points"]) == 5
    for outward, inside, hits in zip(probe["outward"], probe["inside"], probe["hits"]):
        assert outward == pytest.approx([0, 0, -1], abs=1e-12)
        # z = 1.5 lies in the base plate: an open joint, not the rim.
        assert inside
        assert hits[0]["distance"] == pytest.approx(1.0)
        assert hits[0]["gap"] == pytest.approx(0.0)
        assert fused["faces"][hits[0]["face"]]["patch"] == 0

    strips = client.ok("extend_edges", handle=fused["handle"], strips=[{"edge": edge, "face": face, "lengths": [1.25] * 5}])
    assert strips["strips"] == [{"area": pytest.approx(1.25 * 40), "error": None}]
    rib_faces = [i for i, f in enumerate(fused["faces"]) if f["patch"] == 1]
    base_faces = [i for i, f in enumerate(fused["faces"]) if f["patch"] == 0]
    base = client.ok("gather", parts=[{"handle": fused["handle"], "faces": base_faces}])
    grown = client.ok("gather", parts=[{"handle": fused["handle"], "faces": rib_faces}, {"handle": strips["handle"], "faces": [0]}])
    assert grown["faces"] == 2
    again = fuse(client, [base["handle"], grown["handle"]])
    # The base is split in two along x = 30, the strip into the part above it and a 0.25 overshoot.
    areas = sorted((f["patch"], round(f["area"], 6)) for f in again["faces"])
    assert areas == [(0, 1200), (0, 1200), (1, 10), (1, 40), (1, 38 * 40)]
    t_edges = [e for e in again["edges"] if len(e["faces"]) == 4]
    assert len(t_edges) == 1 and t_edges[0]["length"] == pytest.approx(40.0)


def test_rim_edge_points_outside_the_solid(client):
    solid = t_solid(client)
    fused = fuse(client, put_patches(client, horizontal(), rib(2.0)))
    # The base patch's edge at x = 60 is the plate's rim: just past it is outside.
    for i, face in enumerate(fused["faces"]):
        for e in face["edges"]:
            if all(p[0] == pytest.approx(60) for p in fused["edges"][e]["points"]):
                edge, own = e, i
    reply = client.ok(
        "probe_edges", handle=fused["handle"], edges=[{"edge": edge, "face": own, "solid": solid}],
        targets=[], samples=3, reach=3.0, step=0.5,
    )
    (probe,) = reply["edges"]
    assert probe["inside"] == [False, False, False]
    assert probe["outward"] == [pytest.approx([1, 0, 0], abs=1e-12)] * 3
    assert probe["hits"] == [[], [], []]


def test_strip_needs_positive_lengths(client):
    fused = fuse(client, put_patches(client, horizontal(), rib(2.0)))
    edge, face = free_edge_of(fused, 1, 2.0)
    reply = client.request("extend_edges", handle=fused["handle"], strips=[{"edge": edge, "face": face, "lengths": [1.0, 0.0]}])
    assert reply["err"]["code"] == "bad_args"
