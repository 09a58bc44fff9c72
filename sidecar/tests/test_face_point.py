"""Points of a face: area samples that stand for small regions, as the clip's tongue test needs them; the point a
fuse's reply gives a sliver with no point found inside it."""

import pytest
from OCP.BRep import BRep_Builder
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
from OCP.gp import gp_Pln
from OCP.TopAbs import TopAbs_FACE
from OCP.TopoDS import TopoDS_Compound

from midsurf_sidecar.fuse.fused_graph import describe
from midsurf_sidecar.geom.face_measure import measure
from midsurf_sidecar.geom.face_point import area_samples
from midsurf_sidecar.geom.topology import indexed_map
from midsurf_sidecar.protocol.errors import KernelError


def rectangle(dx: float, dy: float):
    return BRepBuilderAPI_MakeFace(gp_Pln(), 0.0, dx, 0.0, dy).Face()


def test_area_samples_cover_the_face():
    # A plane's mesh joins its corners only: two triangles, each half of the face.
    samples = area_samples(rectangle(20.0, 2.0), 20.0)
    assert len(samples) == 2
    assert sum(a for a, _, _ in samples) == pytest.approx(40.0)


def test_area_samples_split_until_small():
    # Split in four while a side is longer than the step: a 20 x 2 strip's triangles (sides up to 20.1) split
    # four times, into 2 x 4^5 = 2048 triangles of sides up to 0.63, their centroids spread along the strip.
    samples = area_samples(rectangle(20.0, 2.0), 20.0, step=1.0)
    assert len(samples) == 2 * 4**5
    assert sum(a for a, _, _ in samples) == pytest.approx(40.0)
    us = sorted(u for _, u, _ in samples)
    assert us[0] < 0.5 and us[-1] > 19.5
    assert all(0.0 < v < 2.0 for _, _, v in samples)


def test_area_samples_are_bounded_and_even():
    # A 2000 long strip at step 1 would need 2 x 4^11 triangles: the step doubles until they fit in
    # MAX_AREA_SAMPLES, the same for every triangle.
    from midsurf_sidecar.constants import MAX_AREA_SAMPLES

    samples = area_samples(rectangle(2000.0, 2.0), 2000.0, step=1.0)
    assert len(samples) <= MAX_AREA_SAMPLES
    assert len({round(a, 9) for a, _, _ in samples}) == 1
    assert sum(a for a, _, _ in samples) == pytest.approx(4000.0)


def test_a_sliver_with_no_point_found_inside_is_measured_on_its_longest_edge():
    # A 10 x 1e-5 strip: the classifier finds no point inside it (its UV centre lies within the face's
    # tolerance of its edges, every step beside an edge is wider than it). A fuse's reply measures it at the
    # middle of its longest edge rather than failing; patch making still refuses it.
    sliver = rectangle(10.0, 1e-5)
    with pytest.raises(KernelError, match="no point inside the face"):
        measure(sliver)
    measured = measure(sliver, sliver_ok=True)
    assert measured["point"][0] == pytest.approx(5.0)
    assert measured["point"][1] in (pytest.approx(0.0), pytest.approx(1e-5))
    assert measured["normal"] == pytest.approx([0.0, 0.0, 1.0])
    assert measured["area"] == pytest.approx(1e-4)


def test_a_fuse_reply_describes_a_sliver_face():
    builder, compound = BRep_Builder(), TopoDS_Compound()
    builder.MakeCompound(compound)
    builder.Add(compound, rectangle(10.0, 2.0))
    builder.Add(compound, rectangle(10.0, 1e-5))
    faces = indexed_map(compound, TopAbs_FACE)
    reply = describe(compound, faces, [0, 1])
    assert [f["patch"] for f in reply["faces"]] == [0, 1]
    assert reply["faces"][1]["point"][0] == pytest.approx(5.0)
