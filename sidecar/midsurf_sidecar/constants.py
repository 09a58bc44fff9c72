"""Every tolerance, step and sample count the sidecar chooses itself, each with its reason.

The part-dependent tolerances (fuzzy values, mesh deflection of `describe`, widths and reaches) come from Rust in
each request, derived from the part's diagonal and t_max (src tolerances); these are the sidecar's own: kernel
floors, numerical guards and sampling densities. Values relative to a size say which size. No OCP here: the
protocol layer, which must import without OCP, uses it too. The protocol version lives in server.py.
"""

import math

# --- kernel floors and numerical guards -------------------------------------------------------------------------

# OCCT's Precision::Confusion() (mm): the smallest distance the kernel tells apart. The tolerance of faces built
# exactly on a known surface, and the floor of a tolerance that comes in as 0 (a fuzzy value of 0 still needs the
# kernel's own least tolerance to classify a point or merge coplanar faces).
CONFUSION = 1e-7
# OCCT's Precision::Angular() (radians): directions closer than this are the same to the kernel. Offsets of a
# plane or a cylinder keep its axis exactly.
ANGULAR = 1e-12
# OCCT's Precision::PConfusion(): the least difference of two parameters (of a curve, or of a face's UV) the
# kernel tells apart; the tolerance of 2D curve intersections in a face's parameters.
PARAMETRIC_CONFUSION = 1e-9
# OCCT marks the ends of an unbounded curve (a line) with Precision::Infinite() (2e100); anything beyond this is
# such a marker, not a parameter.
INFINITE_PARAMETER = 1e100
# A direction given by a request shorter than this (in its own units) is the zero vector: no direction at all.
ZERO_VECTOR = 1e-12
# Divisor guard of a face's mean width (2 x area / perimeter, mm): a degenerate face with no perimeter has width 0.
MIN_PERIMETER = 1e-12
# Determinant of a surface's first fundamental form below which the parametrisation is singular there (a pole, an
# apex): no direction across an edge can be solved for.
SINGULAR_METRIC = 1e-300
# An edge sample at a singular point (a pole of a face narrowing to a point; an offset surface, whose normal is
# undefined there) is taken this share of the way toward the edge's middle instead, each tried in turn: the
# first is the exact sample.
SINGULAR_NUDGES = (0.0, 1e-3, 1e-2, 5e-2)

# --- describe: the face graph -------------------------------------------------------------------------------------

# Faces meeting at less than this angle (radians) are tangent, a fillet running into a wall: "smooth".
SMOOTH_ANGLE = math.radians(1.0)
# Interior parameters, as fractions of the edge's range, where an edge's dihedral angle is sampled (the median is
# kept, so one bad sample cannot flip the convexity).
CONVEXITY_SAMPLES = (0.25, 0.5, 0.75)
# Angular deflection (radians) of the meshes `describe` returns; the linear deflection comes from Rust.
MESH_ANGULAR_DEFLECTION = 0.5
# Angular deflections (rad) a face BRepMesh left without a triangulation is meshed again with, in turn.
MESH_RETRY_ANGLES = (0.2, 0.1, 0.05)
# A face with more wires than this (a sheet with many holes) is triangulated with BRepMesh's Delabella
# algorithm instead of its default (Watson). Watson's time on a face grows with its boundary nodes times its
# wires, as it classifies against every wire; Delabella's about as its nodes. Measured on one face of a
# perforated sheet (3 mm holes, 0.0375 mm chords): 100 holes Watson 0.43 s, Delabella 0.09 s; 400 holes
# 3.8 s and 0.6 s. Other faces keep Watson, the mesher every other result has been checked with (no face of
# the fixtures or of the development corpus has more than 33 wires: their outputs are unchanged).
MANY_WIRES = 64
# Finest mesh tolerance accepted, relative to the part's diagonal. Beyond it the mesh of a large curved face runs
# into millions of triangles and the sidecar can be killed for memory (a 250 m model meshed at 0.1 mm was); at this
# ratio the same model takes 7 s and 200k triangles.
MIN_RELATIVE_MESH_TOLERANCE = 1e-5

# --- geom: normals and a point inside a face ----------------------------------------------------------------------

# Below this first-derivative magnitude the surface normal is undefined (a cone's apex, a sphere's pole).
NORMAL_RESOLUTION = 1e-9
# The fallback mesh of interior_point only has to hold a few triangles well inside the face: its deflection is this
# share of the face's bounding-box diagonal, so it scales with the face (its chords may cut across concave
# boundaries, hence each candidate is classified before it is used).
FALLBACK_DEFLECTION_RATIO = 0.01
# A face's area samples number at most this many: their step doubles until they fit, evenly over the face (a
# bound on the work for one face; the clip's tongue test asks for a step of half the dead-end width).
MAX_AREA_SAMPLES = 4096
FALLBACK_ANGLE = 0.5
# Distances from an edge's middle, as fractions of the face's bounding-box diagonal, tried on both sides when
# neither the UV centre nor a mesh triangle lies in the face: a ring 0.5 mm wide on a 100 m disc needs 1e-6.
BESIDE_EDGE_STEPS = (1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7)

# --- patch: offset, projection, clip ------------------------------------------------------------------------------

# A tapered wall's patch (patch/mid_wall.py) moves the poles of its reference face's B-spline form: the form is
# raised to this degree (cubic: the mid-points of a thickness varying smoothly) and split into at least as many
# spans each way over the face as the first of these counts, so that a face whose own surface is simple (a plane
# has four poles) can follow the thickness; a finer face keeps its own knots. When the moved face misses the
# mid-points by more than MID_WALL_ACCURACY x the local thickness (a face curved tightly for the step: poles
# moved along normals that turn within a span), the next count is tried, then the face is offset at the mean.
MID_WALL_DEGREE = 3
MID_WALL_SPANS = (8, 32)
# 2% of the thickness off mid-wall: a fifth of what a mid-surface may be off (10%).
MID_WALL_ACCURACY = 0.02
# The moved face is checked at area samples about its diagonal over this many apart: a few hundred points.
MID_WALL_CHECKS = 10
# A pole's ray looks for the partner up to this many times the mean wall thickness: a taper's thickest end, not a
# wall across the next gap.
MID_WALL_REACH = 2.0
# A tapered wall's plane is made this many mean thicknesses wider than its face each way: room for its joints to
# grow into (a joint reaches 1.5 t_max), as a B-spline's own extent past its face gives.
MID_WALL_ROOM = 2.0

# An offset radius at or below this share of the original radius counts as collapsed onto the axis or centre
# (OCCT would return a degenerate face it still calls valid).
COLLAPSE_RATIO = 1e-6
# |cos| between a face's normal and the projection plane's normal below which the face is edge-on to the plane:
# its projection would be a sliver.
EDGE_ON_COSINE = 1e-3
# Relative parameter step (share of the period) below which a periodic edge's ends coincide: it goes once round.
PARAMETER_RESOLUTION = 1e-9
# A tangent shorter than this share of the curve's first derivative, once projected into the plane, runs along
# the projection direction: its sense on the plane is read further along the edge.
EDGE_ON_TANGENT = 1e-9
# A projected curve may miss its projected vertex by the vertex's tolerance or this much (mm), whichever is
# larger, before the projection is refused; ProjLib's approximations stay within 1e-5 or so.
MAX_VERTEX_MISS = 1e-3
# A vertex a projected curve misses gets its tolerance raised to the miss times this, so that MakeEdge accepts it
# where the curve ends (1% over, not exactly the miss, which round-off could still exceed).
VERTEX_MISS_MARGIN = 1.01
# The clip is kept only when it removes more than this share of the face: below it the face already lies over its
# partners, and splitting its edges would only add work for the joints.
MIN_CLIPPED_SHARE = 0.01
# An uncovered piece at a dead end of a clipped patch that reaches farther than this many times the dead-end width
# from the covered pieces is a tongue, not a corner's overshoot: an overshoot band reaches its width, up to
# sqrt(2) of it at a corner of two bands, and a tongue its length.
TONGUE_REACH = 2.0
# Material across a patch up to this many times its thickness is its own wall (Rust's stitch::peel
# OWN_WALL_FACTOR): a tapered wall measures up to its thickest end, a wall crossed lengthwise its whole extent.
OWN_WALL_FACTOR = 2.0
# Directions of a patch's tangent plane (over a half turn) along which the clip measures the wall a tongue lies
# on: a wall at any angle between two of them measures at most 1 / cos(pi / 16) = 1.02 times its thickness.
TANGENT_DIRECTIONS = 8
# Two cylinder axes within this angle (radians) are parallel: coaxial partners clip a cylindrical face.
PARALLEL_AXES = 1e-6
# A face is the whole (u, v) box of its parameter range when their areas differ by no more than this share (the
# mean cylinder's range is moved only for such a face: its boundary is four iso-lines).
RECTANGLE_SHARE = 1e-6
# A partner's sector starts at this share of the smaller radius: short of the axis, where a revolved section
# degenerates and the splitter misses the sector's sides, and still inside any wall of that cylinder.
SECTOR_INNER_SHARE = 0.5

# --- fuse and write ---------------------------------------------------------------------------------------------

# Two straight joint lines within this angle (radians) of each other are parallel: the two lines of one tube
# crossing a wall (`fuse.patch_fuse._stem_end_cuts`); both are rulings of the one surface, parallel to round-off.
PARALLEL_LINES = 1e-6

# Angular tolerance (radians) of the same-domain test that merges a patch's faces: OCCT's default (1e-12) misses
# faces that are coplanar to round-off (KERNEL_NOTES, "Extending").
SAME_DOMAIN_ANGLE = 1e-6
# Points reported along each fused edge, evenly spaced by parameter, both ends included (Rust reads an edge's
# straightness and its ends from them).
EDGE_POINTS = 5
# A face spanning its surface's period to within this share closes on itself (UV bounds carry float noise).
FULL_TURN = 1e-9
# A broken face read back from the STEP file came from the written face its edges lie on, within this share of
# the shape's extent: the reader's healing may rebuild a broken face a little differently (its wires, its
# pcurves), so not to round-off.
READBACK_MATCH = 1e-3
# A face's box coordinate beyond this (mm) is an unbounded face's, not a part's: OCCT boxes infinite surfaces at
# 1e100. Such boxes are left out of the size that scales READBACK_MATCH.
UNBOUNDED_BOX = 1e12
# The STEP header's FILE_NAME carries the time of writing: fixed, so equal requests give equal bytes.
FIXED_TIME_STAMP = "1970-01-01T00:00:00"
# Chordal deflection of the glTF preview's mesh, as a share of the part's diagonal (smooth enough to look at,
# small enough to open), with an absolute floor (mm) for a tiny part; and its angular deflection (radians).
PREVIEW_RELATIVE_DEFLECTION = 1e-3
PREVIEW_MIN_DEFLECTION = 1e-4
PREVIEW_ANGULAR_DEFLECTION = 0.3
# glTF lengths are metres, the STEP's millimetres: the writer's input unit, in metres.
GLTF_INPUT_LENGTH_UNIT = 0.001

# --- joints: probing and growing free edges -----------------------------------------------------------------------

# The side test of an edge's outward direction steps this share of the face's diagonal off the edge, or this many
# face tolerances if that is more, so the classifier sees the step whatever the face's size and tolerance.
SIDE_STEP_RATIO = 1e-4
SIDE_STEP_TOLERANCES = 20.0
# A ray meets an offset of a spline surface (a mid-patch of a freeform wall) about 30 times faster on a B-spline
# approximation of it: the approximation (this share of the probe's reach) only locates the meetings, which Newton's
# method then settles on the exact surface to RAY_MEET_RESIDUAL (mm) within RAY_MEET_ITERATIONS steps (else the
# exact surface is intersected directly).
RAY_APPROX_RATIO = 1e-3
RAY_MEET_RESIDUAL = 1e-9
RAY_MEET_ITERATIONS = 20
# A ray misses a spline when its poles all lie on one side of one of this many planes through the ray (evenly
# turned about it), by more than HULL_MARGIN (mm: round-off of the intersector; the locator's tolerance is added).
HULL_DIRECTIONS = 8
HULL_MARGIN = 1e-6
# A spline surface is sampled into at least this many points each way, span by span, to meet rays; a line's piece
# across a span's box is lengthened to at least this (mm) each way. Both are GeomAPI_IntCS's own for a line.
POLYHEDRON_MIN_SAMPLES = 20
POLYGON_MIN_LENGTH = 1e-10
# A spline's samples are kept for the whole probe only up to this many points (about 20 MB); past it (a spline of
# hundreds of spans), each ray samples it anew as IntCS does.
POLYHEDRON_MAX_POINTS = 200_000
# Polylines within this share of the probe's reach of a target face's edges (about 0.5 um for a 4.5 mm reach) find
# the edges nearest a meeting off the face; the distance is then measured to those edges exactly.
GAP_DEFLECTION_RATIO = 1e-4
# Outward directions (unit vectors) and lengths equal to this (relative) share make one straight sweep; also how far
# an edge's ends may differ in v (relative to the sweep, at least 1 mm) and still be a circle of its cylinder.
SWEEP_PARALLEL = 1e-6
# Tolerance of a strip's far curve and of its collinearity and planarity tests, relative to the strip's size.
STRIP_RELATIVE_TOLERANCE = 1e-6
# A strip on a cylindrical patch keeps to the cylinder when the samples grow along its axis: most within this
# angle (degrees) of it, none against it.
AXIAL_DEG = 45.0
# A piece of a patch face cut off by the solid's boundary is enclosed (a filled hole of the wall, which the
# patch spans on purpose) when all of its boundary but this share of it is the cut.
ENCLOSED_SHARE = 1e-6
# An uncovered piece of a clipped mid-patch face whose boundary runs along covered pieces for at least this share
# of its length is a bay cut into the partners' footprint, flanked by the wall on opposite sides
# (face_clip._flanked): more than half, so that an overshoot along one covered edge (its long side, at most
# half of it) is not one.
BAY_SHARE = 0.5
# Points inside each edge of a curved patch face at which its boundary is tested for leaving the solid
# (patch.face_clip.within_solid: a sign the fuzzy split missed an overshoot).
BOUNDARY_SAMPLES = 5
# Points along an edge's pcurve to find its extent in the cylinder's parameters.
PCURVE_SAMPLES = 64

# An edge whose pcurve's v stays within this (relative) is a parallel of a surface of revolution, and an
# outward direction within this of its meridian runs along it (joints.edge_strip._along_meridian).
MERIDIAN_ISO = 1e-6

# A patch edge within this share of its wall's thickness of the solid's boundary is on the rim (Rust's
# tolerance::RIM_SHARE): a curved patch overshooting its rim by no more is not cut to the solid.
RIM_SHARE = 0.1

# A plane, cylinder or cone face whose parametric origin lies more than this many times the face's size (its
# bounding box diagonal) from the face gets an origin at the face at load (load.reanchor): OCCT's 2D
# algorithms lose accuracy on parameters far larger than the face they describe.
ANCHOR_FAR = 100.0

# A boolean split only cuts faces: the pieces of a face cover its area, up to what merging within the fuzzy value
# moves (fuzzy x its boundary). Faces whose pieces differ by more, together by more than this share of the area
# split, are a broken result (inverted or dropped loops), not a split (geom.booleans.check_area_kept).
AREA_KEPT_SHARE = 0.01

# The faces whose areas and centroids are kept once integrated (geom.topology.face_props): more than the faces of
# the largest stitching seen (about 2,000 inputs and pieces per fuse), few enough to hold in memory.
FACE_PROPS_KEPT = 20_000
