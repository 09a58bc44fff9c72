"""What lies under a point of a mid-patch: its own wall, another wall, or nothing. The clip asks it of a narrow
piece at a dead end that reaches far from its partners' footprint (face_clip: a tongue, lying on the end of a
taller wall whose own patch covers it), before the patch is fused; the joints' peel asks the same of fused
pieces in Rust (stitch::peel)."""

import math

from OCP.IntCurvesFace import IntCurvesFace_ShapeIntersector
from OCP.TopAbs import TopAbs_IN
from OCP.TopoDS import TopoDS_Face, TopoDS_Shape
from OCP.gp import gp_Ax2, gp_Dir, gp_Lin, gp_Pnt, gp_Vec

from ..constants import CONFUSION, OWN_WALL_FACTOR, TANGENT_DIRECTIONS
from ..geom.face_normals import OutwardNormals
from ..geom.face_point import area_samples
from ..geom.solid_boundary import SolidBoundary
from ..geom.topology import diagonal, distance_to


class WallProbe:
    """The solid a patch lies in, the patch's thickness, the step from the patch to mid-wall along the source
    face's outward normal, and the thickest wall that pairs whatever its width (t_max): what lies under a point
    of the patch."""

    def __init__(self, solid: SolidBoundary, thickness: float, to_mid: float, wall_max: float):
        self.solid = solid
        self.thickness = thickness
        self.to_mid = to_mid
        self.wall_max = wall_max
        self._rays = None

    def tongue(self, piece: TopoDS_Face, cover: TopoDS_Shape, reach: float) -> bool:
        """Whether `piece` is a tongue: most of its area farther than `reach` from `cover` (the covered pieces
        of its clip) lies on another wall (on_other_wall). Near the cover a dead-end piece is the wall's
        overshoot into its joint, whatever lies there; the part beyond is judged by what it lies on."""
        normals = OutwardNormals(piece)
        on, far = 0.0, 0.0
        for area, u, v in area_samples(piece, diagonal(piece), 0.5 * reach):
            sample = normals.at(u, v)
            if sample is None:
                continue
            distance = distance_to(gp_Pnt(*sample[0]), cover)
            if distance is None or distance <= reach:
                continue
            far += area
            if self.on_other_wall(*sample):
                on += area
        return far > 0.0 and on > 0.5 * far

    def runs_through(self, piece: TopoDS_Face, step: float) -> bool:
        """Whether the wall runs on under all of `piece`: every area sample of it (sides up to `step`), moved to
        mid-wall, lies in the solid. An uncovered band between covered pieces of a patch that does (under a thick
        land, a bead or a block standing on the wall, which get no patch of their own) is the wall going on
        through their root; one over a slot or a groove deeper than half the wall is not."""
        normals = OutwardNormals(piece)
        classifier = self.solid.classifier
        samples = 0
        for _, u, v in area_samples(piece, diagonal(piece), step):
            sample = normals.at(u, v)
            if sample is None:
                continue
            point, normal = sample
            classifier.Perform(gp_Pnt(*point).Translated(gp_Vec(*normal) * self.to_mid), CONFUSION)
            if classifier.State() != TopAbs_IN:
                return False
            samples += 1
        return samples > 0

    def on_other_wall(self, point, normal) -> bool:
        """Whether `point` (moved to mid-wall) lies outside the solid, or on another thin wall rather than in
        its own: the material across it along `normal` (the source face's outward one) is thicker than
        OWN_WALL_FACTOR x the thickness (the joints' peel test, Rust's stitch::peel), and across it in some
        direction of its tangent plane no thicker than `wall_max` (a wall standing square to the patch, whose
        own patch covers the point; over a block or a thick rib nothing else does)."""
        if self._rays is None:
            # Loaded on first use: most clips have no tongue to judge.
            self._rays = IntCurvesFace_ShapeIntersector()
            self._rays.Load(self.solid.shape, CONFUSION)
        origin = gp_Pnt(*point).Translated(gp_Vec(*normal) * self.to_mid)
        classifier = self.solid.classifier
        classifier.Perform(origin, CONFUSION)
        if classifier.State() != TopAbs_IN:
            return True
        across = self._across(origin, gp_Dir(*normal))
        if across is None or across <= OWN_WALL_FACTOR * self.thickness:
            return False
        frame = gp_Ax2(origin, gp_Dir(*normal))
        x, y = gp_Vec(frame.XDirection()), gp_Vec(frame.YDirection())
        for k in range(TANGENT_DIRECTIONS):
            angle = math.pi * k / TANGENT_DIRECTIONS
            width = self._across(origin, gp_Dir(x * math.cos(angle) + y * math.sin(angle)))
            if width is not None and width <= self.wall_max:
                return True
        return False

    def _across(self, origin: gp_Pnt, direction: gp_Dir) -> float | None:
        """The material across `origin` (inside the solid) along `direction`: the nearest boundary ahead plus the
        nearest behind; None when a side has none (the kernel missed)."""
        self._rays.Perform(gp_Lin(origin, direction), -math.inf, math.inf)
        if not self._rays.IsDone():
            return None
        hits = [self._rays.WParameter(k) for k in range(1, self._rays.NbPnt() + 1)]
        ahead = [w for w in hits if w > CONFUSION]
        behind = [-w for w in hits if w < -CONFUSION]
        if not ahead or not behind:
            return None
        return min(ahead) + min(behind)
