"""One patch's faces (its kept pieces, the strips grown from its edges and the corners between them) joined
where they touch and merged where they lie on one surface, so a strip is not left as a sliver face of its own."""

from OCP.ShapeUpgrade import ShapeUpgrade_UnifySameDomain
from OCP.TopoDS import TopoDS_Shape

from .patch_fuse import general_fuse

# Angular tolerance of the same-domain test: OCCT's default (1e-12) misses faces that are coplanar to
# round-off (KERNEL_NOTES, "Extending").
SAME_DOMAIN_ANGLE = 1e-6


def unify(faces: list[TopoDS_Shape], fuzzy: float) -> TopoDS_Shape:
    merger = ShapeUpgrade_UnifySameDomain(general_fuse(faces, fuzzy).Shape(), True, True, False)
    merger.SetLinearTolerance(max(fuzzy, 1e-7))
    merger.SetAngularTolerance(SAME_DOMAIN_ANGLE)
    merger.Build()
    return merger.Shape()
