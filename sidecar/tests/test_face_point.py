"""Points of a face: area samples that stand for small regions, as the clip's tongue test needs them."""

import pytest
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
from OCP.gp import gp_Pln

from midsurf_sidecar.geom.face_point import area_samples


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
