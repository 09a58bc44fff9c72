//! The pair tests of the paper, per surface kind: parallel or draft normals, distance <= t_max, overlap;
//! and for curved faces a shared axis or centre with the material between the two faces.

use glam::DVec3;

use super::features::BEVEL_TURN_DEG;
use super::levels::one_plane;
use super::overlap::{self, Overlap};
use super::wall_class::CHUNKY_SHARE;
use super::{Pair, PairKind, Rejection, Thickness};
use crate::geom::angle_between;
use crate::model::face_graph::{Convexity, EdgeId, Face, FaceGraph, FaceId, Mesh, Surface};
use crate::model::tolerance::Tolerances;

/// The thickest a wall may be for the length of its shorter skin, as a share of that length: a square slab of
/// these proportions (thickness d, sides d / THICK_WALL_SHARE) is exactly as thin as a thin-walled solid may be
/// (`wall_class`: 2V/A = CHUNKY_SHARE x its middle extent, and 2V/A = d / (1 + 2 x THICK_WALL_SHARE) for it).
const THICK_WALL_SHARE: f64 = CHUNKY_SHARE / (1.0 - 2.0 * CHUNKY_SHARE);

/// The largest thickness a pair of skins `sizes` (each `[length, width]`, see [`FaceGraph::face_size`]) may
/// have and be a wall: t_max, or more, up to t_bound, when the wall is thin for its extent by the measure that
/// classifies solids: at most THICK_WALL_SHARE of the length of the shorter skin, and no more than the wider
/// skin is wide (a wall is at least as wide as it is thick; a narrower pair goes through the stub tests as any
/// other). A low thick rim along a tray's edge, a lug up to a third as thick as long, a short thick band round a
/// corner are walls; a block as thick as long and a pin's flats (both narrower than they stand apart) are not.
pub fn wall_limit(tol: &Tolerances, sizes: [[f64; 2]; 2]) -> f64 {
    let length = sizes[0][0].min(sizes[1][0]);
    let width = sizes[0][1].max(sizes[1][1]);
    tol.t_max.max((THICK_WALL_SHARE * length).min(width).min(tol.t_bound))
}

/// A thickness over `limit` by more than the part's length tolerance: a wall as thick as t_max (the gauge a
/// user gives as --t-max) measures it give or take the kernel's rounding, and is within it.
pub fn over(thickness: f64, limit: f64, tol: &Tolerances) -> bool {
    thickness > limit + tol.point
}

/// Tests whether faces `a` and `b` are the two skins of one wall.
pub fn test_pair(graph: &FaceGraph, a: FaceId, b: FaceId, tol: &Tolerances) -> Result<Pair, Rejection> {
    let (fa, fb) = (&graph.faces[a], &graph.faces[b]);
    // Only the thickness limit depends on the pair (its width); every other tolerance stays the solid's. With
    // no room above t_max (a user's hard limit) the widths need not be measured.
    let limit =
        if tol.t_bound > tol.t_max { wall_limit(tol, [graph.face_size(a), graph.face_size(b)]) } else { tol.t_max };
    let t_max = tol.t_max;
    let tol = &Tolerances { t_max: limit, ..*tol };
    let (kind, thickness, overlap_area) = match analytic(fa, fb, tol) {
        Err(rejection) if measurable(fa, fb, &rejection) => {
            // Faces the rays cannot see across say no more than their parameters did.
            let (kind, thickness, overlap_area) =
                match sampled_pair(fa, fb, PairKind::Freeform, Spread::NearlyConstant, tol) {
                    Err(Rejection::NotFacing) | Err(Rejection::Overlap { share: 0.0, .. }) => return Err(rejection),
                    other => other?,
                };
            let share = overlap_area / fa.area.min(fb.area);
            if share < MEASURED_SHARE {
                return Err(Rejection::Overlap { share, limit: MEASURED_SHARE });
            }
            let width = graph.face_width(a).min(graph.face_width(b));
            if width < thickness.mean {
                return Err(Rejection::Stub { width, thickness: thickness.mean, top: false });
            }
            (kind, thickness, overlap_area)
        }
        result => result?,
    };
    if over(thickness.mean, t_max, tol) {
        reject_stacked(graph, [a, b], thickness.mean)?;
    }
    reject_stub(graph, [a, b], thickness.mean, tol)?;
    Ok(Pair { faces: [a.min(b), a.max(b)], kind, thickness, overlap_area })
}

/// Share of the smaller face's samples whose ray across the wall may meet another face first before the pair
/// counts as stacked walls: a hole or a pocket in between is a few samples, a second layer most of them.
const STACKED_SHARE: f64 = 0.5;

/// Samples of the smaller face tested by `reject_stacked`: enough to tell most of it from a few holes.
const MAX_STACKED_SAMPLES: usize = 32;

/// How much nearer than the partner another face must be to lie between the two: the skins' own mesh chords
/// and a draft's spread stay well within it.
const STACKED_GAP: f64 = 0.05;

/// A pair thicker than t_max (a wall only when thin for its extent, `wall_limit`) is one wall when the material
/// runs from one face to the other: rays from points of the smaller face, along its inward normal, meet no
/// other face nearer than the partner (at least `1 - STACKED_GAP` of the thickness) at most samples. Two sheets
/// lying one on the other a gap apart (a hem, a doubled flange) have each their own pair, and their outer skins
/// would otherwise pair across both. Within t_max the pairing of every other wall stands as it was.
fn reject_stacked(graph: &FaceGraph, [a, b]: [FaceId; 2], thickness: f64) -> Result<(), Rejection> {
    let from = if graph.faces[a].area <= graph.faces[b].area { a } else { b };
    let Some(mesh) = graph.faces[from].mesh.as_ref() else { return Ok(()) };
    let reach = (1.0 - STACKED_GAP) * thickness;
    let lo = graph.faces[a].bbox.min.min(graph.faces[b].bbox.min);
    let hi = graph.faces[a].bbox.max.max(graph.faces[b].bbox.max);
    let near: Vec<&Mesh> = graph
        .faces
        .iter()
        .filter(|f| f.id != a && f.id != b && f.bbox.min.cmple(hi).all() && f.bbox.max.cmpge(lo).all())
        .filter_map(|f| f.mesh.as_ref())
        .collect();
    let step = mesh.triangles.len().div_ceil(MAX_STACKED_SAMPLES).max(1);
    let (mut samples, mut blocked, mut nearest) = (0usize, 0usize, f64::INFINITY);
    for t in mesh.triangles.iter().step_by(step) {
        let [p, q, r] = t.map(|i| mesh.vertices[i as usize]);
        let outward = (q - p).cross(r - p).normalize_or_zero();
        if outward == DVec3::ZERO {
            continue;
        }
        let centre = (p + q + r) / 3.0;
        samples += 1;
        let first =
            near.iter().filter_map(|m| m.nearest_hit(centre, -outward, reach, |_| true)).fold(f64::INFINITY, f64::min);
        if first.is_finite() {
            blocked += 1;
            nearest = nearest.min(first);
        }
    }
    if samples > 0 && blocked as f64 > STACKED_SHARE * samples as f64 {
        return Err(Rejection::Stacked { thickness, between: nearest });
    }
    Ok(())
}

/// Curved faces whose analytic test fails on their parameters alone (axes or centres apart, surface kinds
/// with no analytic pairing: a cylinder against a torus, a plane or a sphere) may still be the two skins of
/// one wall: real CAD puts an inner and an outer arc on centres a little apart, and a bend meets a flat. The
/// measurement decides then, as for freeform faces: the distance along the normals, nearly constant or
/// tapering, over nearly all of the smaller face (`MEASURED_SHARE`): a round along a wall's rim faces the
/// other skin only near its tangent edge and stays a connecting face. A face narrower than the distance
/// measured from it samples a sliver across a corner, not a wall, and stays unpaired (as `stub_sides` decides
/// for planes and coaxial cylinders). Rejections that the measurement would repeat (distance, overlap,
/// material on one side of coaxial faces) stand; two planes are always decided analytically.
fn measurable(fa: &Face, fb: &Face, rejection: &Rejection) -> bool {
    let curved = !fa.surface.is_plane() || !fb.surface.is_plane();
    curved && matches!(rejection, Rejection::NotCoaxial { .. } | Rejection::Incompatible { .. })
}

/// The analytic tests of the paper, per pair of surface kinds; freeform faces are measured by rays.
fn analytic(fa: &Face, fb: &Face, tol: &Tolerances) -> Result<(PairKind, Thickness, f64), Rejection> {
    Ok(match (&fa.surface, &fb.surface) {
        (Surface::Plane { origin: pa, normal: na }, Surface::Plane { origin: pb, normal: nb }) => {
            planes(fa, fb, (*pa, *na), (*pb, *nb), tol)?
        }
        (
            Surface::Cylinder { origin: oa, axis: aa, radius: ra, convex: ca },
            Surface::Cylinder { origin: ob, axis: ab, radius: rb, convex: cb },
        ) => {
            coaxial(*oa, *aa, *ob, *ab, tol)?;
            let t = radial_gap((*ra, *ca), (*rb, *cb), tol)?;
            let ov = overlap::cylindrical(mesh(fa)?, mesh(fb)?, *oa, *aa, 0.5 * (ra + rb));
            check_overlap(&ov, tol)?;
            (PairKind::Cylindrical, Thickness::uniform(t), ov.area)
        }
        (
            Surface::Sphere { center: ca, radius: ra, convex: xa },
            Surface::Sphere { center: cb, radius: rb, convex: xb },
        ) => {
            let offset = ca.distance(*cb);
            if offset > tol.coaxial {
                return Err(Rejection::NotCoaxial { offset });
            }
            let t = radial_gap((*ra, *xa), (*rb, *xb), tol)?;
            sampled_pair(fa, fb, PairKind::Spherical, Spread::Exact(t), tol)?
        }
        (
            Surface::Torus { center: ca, axis: aa, major_radius: ma, minor_radius: ra, convex: xa },
            Surface::Torus { center: cb, axis: ab, major_radius: mb, minor_radius: rb, convex: xb },
        ) => {
            coaxial(*ca, *aa, *cb, *ab, tol)?;
            let offset = ca.distance(*cb).max((ma - mb).abs());
            if offset > tol.coaxial {
                return Err(Rejection::NotCoaxial { offset });
            }
            let t = radial_gap((*ra, *xa), (*rb, *xb), tol)?;
            sampled_pair(fa, fb, PairKind::Toroidal, Spread::Exact(t), tol)?
        }
        (
            Surface::Cone { origin: oa, axis: aa, half_angle: ha, apex: pa, convex: xa, .. },
            Surface::Cone { origin: ob, axis: ab, half_angle: hb, apex: pb, convex: xb, .. },
        ) => {
            coaxial(*oa, *aa, *ob, *ab, tol)?;
            if xa == xb {
                return Err(Rejection::SameSense);
            }
            let spread = match parallel_cones((*aa, *ha, *pa), (*ab, *hb, *pb), tol)? {
                Some(t) => Spread::Exact(t),
                None => drafted_rulings((*aa, *ha), (*ab, *hb), tol)?,
            };
            sampled_pair(fa, fb, PairKind::Conical, spread, tol)?
        }
        (
            Surface::Cylinder { origin: oa, axis: aa, convex: xa, .. },
            Surface::Cone { origin: ob, axis: ab, half_angle: h, convex: xb, .. },
        )
        | (
            Surface::Cone { origin: ob, axis: ab, half_angle: h, convex: xb, .. },
            Surface::Cylinder { origin: oa, axis: aa, convex: xa, .. },
        ) => {
            coaxial(*oa, *aa, *ob, *ab, tol)?;
            if xa == xb {
                return Err(Rejection::SameSense);
            }
            let spread = drafted_rulings((*aa, 0.0), (*ab, *h), tol)?;
            sampled_pair(fa, fb, PairKind::Conical, spread, tol)?
        }
        (sa, sb) if sa.is_freeform() || sb.is_freeform() => {
            sampled_pair(fa, fb, PairKind::Freeform, Spread::NearlyConstant, tol)?
        }
        (sa, sb) => return Err(Rejection::Incompatible { kinds: [sa.kind_name(), sb.kind_name()] }),
    })
}

/// A narrow face stands proud when less than this share of its outline is concave: each long side of a strip is
/// nearly half its outline, so one concave long side (a strip beside a rib) is not proud, while concave ends
/// (a land running into walls, the corner blends at a lip's ends) still are.
const PROUD_CONCAVE_SHARE: f64 = 0.25;

/// A planar face narrower than the wall is thick and standing proud of its surroundings (no concave long side),
/// whichever face of the pair it is, is the top of a stub (a land between two shallow pockets, a bead, a lip
/// along a plate's edge), not a skin of a wall: the stub's material belongs to the wall it stands on, whose patch
/// runs on beneath it. Width is 2 x area / perimeter (the width of a band). A narrow strip between two ribs
/// stays paired: its edges to the ribs are concave.
fn reject_stub(graph: &FaceGraph, faces: [FaceId; 2], thickness: f64, tol: &Tolerances) -> Result<(), Rejection> {
    if !all_planar(graph, &faces) {
        return Ok(());
    }
    for face in faces {
        let skin = flat_skin(graph, face, tol);
        let (width, perimeter, concave) = skin_outline(graph, &skin);
        if width < thickness && concave < PROUD_CONCAVE_SHARE * perimeter {
            return Err(Rejection::Stub { width, thickness, top: true });
        }
    }
    Ok(())
}

/// The planar faces that continue `face` in its plane across smooth edges (a flat skin the CAD split into
/// faces along a line, a sketch's or a moulding step's), `face` first, then in id order: how the skin is split
/// must not decide whether it is the top of a stub.
fn flat_skin(graph: &FaceGraph, face: FaceId, tol: &Tolerances) -> Vec<FaceId> {
    let mut skin = vec![face];
    let mut k = 0;
    while k < skin.len() {
        for next in graph.smooth_neighbours(skin[k]) {
            let flat = one_plane(&graph.faces[face], &graph.faces[next], tol.point, tol.parallel_angle);
            if !skin.contains(&next) && flat {
                skin.push(next);
            }
        }
        k += 1;
    }
    skin[1..].sort_unstable();
    skin
}

/// The mean width (2 x area / perimeter) of the faces `skin` taken as one, its perimeter and the concave part
/// of it (edges between two of its faces lie inside it).
fn skin_outline(graph: &FaceGraph, skin: &[FaceId]) -> (f64, f64, f64) {
    let area: f64 = skin.iter().map(|&f| graph.faces[f].area).sum();
    let (mut perimeter, mut concave) = (0.0, 0.0);
    for &f in skin {
        for e in graph.faces[f].loops.iter().flatten().map(|&e| &graph.edges[e]) {
            if e.faces.iter().all(|g| skin.contains(g)) && e.faces.len() > 1 {
                continue;
            }
            perimeter += e.length;
            if e.convexity == Convexity::Concave {
                concave += e.length;
            }
        }
    }
    let width = if perimeter > 0.0 { 2.0 * area / perimeter } else { f64::INFINITY };
    (width, perimeter, concave)
}

/// Planar faces narrower than this share of the distance between them are slivers, whatever joins them: a shell
/// element there would be four times thicker than wide (ender3_x_limit: a counterbore's two annular steps,
/// 0.017 mm wide, had paired 2.9 mm apart, and the patch grew to 15.7 mm2 across the bore, measuring 33 mm).
/// A short tab (fw13_hinge: sides 0.57 wide, 1.0 apart) is no sliver. Cylinders are left out: a pipe cut into
/// short bands (salome_pipe) has faces narrower than its wall, each band still a piece of the wall.
const SLIVER: f64 = 0.25;

/// Two planar or cylindrical faces no wider than they stand apart and joined by a skin of another wall (the top
/// face a land between two pockets belongs to) are the sides of a stub, not a wall: rejected after every pair
/// is known. A land curving round (a logo's stroke) has cylindrical sides. Narrow sides joined only by
/// thickness faces (a short tab's edge faces) stay a wall, unless both are slivers (`SLIVER`).
pub fn stub_sides(graph: &FaceGraph, pair: &Pair, skins: &[bool]) -> Option<Rejection> {
    let width = pair.faces.iter().map(|&f| graph.face_width(f)).fold(0.0, f64::max);
    let flat_or_round = pair.faces.iter().all(|&f| graph.faces[f].surface.is_flat_or_round());
    if !flat_or_round || width >= pair.thickness.mean {
        return None;
    }
    let [a, b] = pair.faces.map(|f| graph.neighbours(f));
    let joined_by_skin = a.iter().any(|f| skins[*f] && b.binary_search(f).is_ok());
    let sliver = all_planar(graph, &pair.faces) && width < SLIVER * pair.thickness.mean;
    (joined_by_skin || sliver).then_some(Rejection::Stub { width, thickness: pair.thickness.mean, top: false })
}

/// A face stands on a base along its length when their concave edges make at least this share of its length.
const STANDS_ALONG: f64 = 0.5;

/// The length of the concave edges between `face` and `other`.
fn concave_length(graph: &FaceGraph, face: FaceId, other: FaceId) -> f64 {
    graph.faces[face]
        .loops
        .iter()
        .flatten()
        .map(|&e| &graph.edges[e])
        .filter(|e| e.convexity == Convexity::Concave && e.faces.contains(&other))
        .map(|e| e.length)
        .sum()
}

/// A planar face lies wholly over its partner when at least this share of its area overlaps it (the overlap is
/// measured on the faces' meshes).
const LIES_OVER: f64 = 0.9;

/// One side of a low stretch of a wall: a planar face narrower than the wall is thick (the width of the band of
/// its area and perimeter: a short face is not narrow for being short), lying wholly over a partner that is no
/// narrow face, the two standing on one plane skin of another wall (concave edges to it, along the face's
/// length, or to two faces of it that the stub splits apart), the partner running on up at least as far as the
/// wall is thick: a low rib whose other side runs on up a snap hook or tab rising from it. The low stretch is a
/// stub: its material belongs to the wall it stands on. A narrow piece of a plate's skin between ribs stands on
/// no skin that its partner, on the plate's other side, stands on too; two narrow faces (a rib low all along)
/// are left to `stub_sides`.
pub fn low_side(graph: &FaceGraph, pair: &Pair, skins: &[bool], tol: &Tolerances) -> Option<Rejection> {
    if !all_planar(graph, &pair.faces) {
        return None;
    }
    let widths = pair.faces.map(|f| graph.face_size(f)[1]);
    let narrow = if widths[0] <= widths[1] { 0 } else { 1 };
    let (face, partner) = (pair.faces[narrow], pair.faces[1 - narrow]);
    let lies_over = pair.overlap_area >= LIES_OVER * graph.faces[face].area;
    if widths[narrow] >= pair.thickness.mean || widths[1 - narrow] < pair.thickness.mean || !lies_over {
        return None;
    }
    let bases = |f: FaceId| graph.concave_neighbours(f).into_iter().filter(|&s| skins[s]).collect::<Vec<_>>();
    // The face stands on its base along its length, not at an end (where a rib runs into a wall).
    let length = graph.face_size(face)[0];
    let along = |s: FaceId| concave_length(graph, face, s) >= STANDS_ALONG * length;
    let (under_face, under_partner) = (bases(face), bases(partner));
    let stub = under_face.iter().filter(|&&s| along(s)).any(|&s| {
        under_partner.iter().any(|&r| {
            let (base, other) = (&graph.faces[s], &graph.faces[r]);
            let one_base = s == r || one_plane(base, other, tol.point, tol.parallel_angle);
            one_base && graph.reach(partner, base.point, base.normal) >= pair.thickness.mean
        })
    });
    stub.then_some(Rejection::Stub { width: widths[narrow], thickness: pair.thickness.mean, top: false })
}

/// A planar or cylindrical face narrower than its distance to its partner cannot be a shell of its own (a level
/// running round a box's rounded corner is the corner's as on the flats beside it). When that partner
/// pairs with another face wide enough to be a wall (at least as wide as that pair is thick) at a different
/// thickness, the narrow face is a minor level of the wall (a groove's floor, a rebate or a bead along it): the
/// wall's patch runs on past it. `pairs_of[f]`: the pairs of face f. Returns the narrow face and the rejection.
/// A narrow strip between two ribs keeps its pair: it lies at the wall's own level.
///
/// When neither face pairs with anything else, the partner is the wider and the narrow face runs into the skin
/// of a wall square to it (the underside of a lip along a plate's end, across from that end face), the pair
/// measures the lip along its wall: `Rejection::Lip`. A chamfered corner's two bevels meet their walls at 45
/// degrees and stay a wall; two narrow faces of a short tab are left to `stub_sides`.
pub fn minor_level(graph: &FaceGraph, pair: &Pair, pairs_of: &[Vec<&Pair>], same: f64) -> Option<(FaceId, Rejection)> {
    let t = pair.thickness.mean;
    pair.faces.iter().find_map(|&face| {
        if !graph.faces[face].surface.is_flat_or_round() {
            return None;
        }
        let plane = graph.faces[face].surface.is_plane();
        let width = graph.face_width(face);
        if width >= t {
            return None;
        }
        let partner = pair.other(face);
        let wall = pairs_of[partner].iter().find(|q| {
            let other = q.other(partner);
            other != face && (q.thickness.mean - t).abs() > same && graph.face_width(other) >= q.thickness.mean
        });
        match wall {
            Some(wall) => Some((face, Rejection::MinorLevel { width, thickness: t, wall: wall.thickness.mean })),
            None => {
                let isolated = pairs_of[face].len() == 1 && pairs_of[partner].len() == 1;
                let lip = plane && isolated && graph.face_width(partner) >= t && ledge(graph, face, pairs_of);
                lip.then_some((face, Rejection::Lip { width, thickness: t }))
            }
        }
    })
}

/// The material between the faces of `pair` belongs to a wider wall's slab, which that wall's patch spans
/// already: one face reaches from one skin of another pair to its other skin (each meets both skins, through a
/// suppressed blend at most), and the other face either does too or lies between the two (planar) skins'
/// planes. Both reaching: a web of a perforated wall (between two holes or slots narrower apart than the wall
/// is thick). One reaching: the wall's rim or a rib's top facing a pocket inside the wall (a bore's ceiling
/// under a rib's top, a slot's side near a plate's edge). Such a pair's patch would stand across the wall's,
/// joined to nothing at its ends. A lone bar whose sides pair is no web: its faces across are narrower than its
/// sides (`stub_sides`), and its sides overlap over more area.
pub fn web_of_sheet(graph: &FaceGraph, pair: &Pair, pairs_of: &[Vec<&Pair>], pairable: &[bool]) -> Option<Rejection> {
    let reached = pair.faces.map(|f| reach(graph, f, pairable));
    let spans = |k: usize, sheet: &Pair| sheet.faces.iter().all(|s| reached[k].binary_search(s).is_ok());
    (0..2).find_map(|k| {
        reached[k].iter().find_map(|&s| {
            pairs_of[s].iter().find_map(|sheet| {
                let wider =
                    sheet.overlap_area > pair.overlap_area && !sheet.faces.iter().any(|f| pair.faces.contains(f));
                let other = 1 - k;
                let inside = spans(other, sheet) || in_slab(graph, pair.faces[other], sheet);
                (wider && spans(k, sheet) && inside)
                    .then_some(Rejection::Web { thickness: pair.thickness.mean, sheet: sheet.thickness.mean })
            })
        })
    })
}

/// Every vertex of `face`'s mesh lies between the planes of the two skins of `sheet` (both planar), within a
/// hundredth of the sheet's thickness. A face without a mesh, or a sheet that is not planar, is not inside.
fn in_slab(graph: &FaceGraph, face: FaceId, sheet: &Pair) -> bool {
    let [a, b] = sheet.faces.map(|f| &graph.faces[f]);
    let (Surface::Plane { origin: pa, normal: n }, Surface::Plane { origin: pb, .. }) = (&a.surface, &b.surface) else {
        return false;
    };
    let (da, db) = (n.dot(*pa), n.dot(*pb));
    let slack = 0.01 * sheet.thickness.mean;
    let (lo, hi) = (da.min(db) - slack, da.max(db) + slack);
    graph.faces[face]
        .mesh
        .as_ref()
        .is_some_and(|m| !m.vertices.is_empty() && m.vertices.iter().all(|v| (lo..=hi).contains(&n.dot(*v))))
}

/// The faces `face` meets, directly or across one face left out of pairing (a suppressed round or chamfer),
/// sorted.
pub(super) fn reach(graph: &FaceGraph, face: FaceId, pairable: &[bool]) -> Vec<FaceId> {
    let mut out = graph.neighbours(face);
    let beyond: Vec<FaceId> =
        out.iter().filter(|&&g| !pairable[g]).flat_map(|&g| graph.neighbours(g)).filter(|&g| g != face).collect();
    out.extend(beyond);
    out.sort_unstable();
    out.dedup();
    out
}

/// A wall skin and a face square to it within this cosine (about 3 degrees) meet as a ledge on the wall.
const SQUARE_COS: f64 = 0.05;

/// Planar `face` meets, along a concave edge, a planar skin of a wall (a face with pairs) square to it, and is no
/// bevel between two walls (`bevel_between_walls`): the narrow face runs along that skin as a lip's underside
/// runs along its plate.
fn ledge(graph: &FaceGraph, face: FaceId, pairs_of: &[Vec<&Pair>]) -> bool {
    let normal = graph.faces[face].normal;
    let square_skin = |g: FaceId| {
        !pairs_of[g].is_empty()
            && graph.faces[g].surface.is_plane()
            && graph.faces[g].normal.dot(normal).abs() < SQUARE_COS
    };
    let mut concave =
        graph.faces[face].loops.iter().flatten().filter(|&&e| graph.edges[e].convexity == Convexity::Concave);
    concave.any(|&e| graph.across(e, face).any(square_skin)) && !bevel_between_walls(graph, face, pairs_of)
}

/// Whether planar `face` is the inner bevel of a corner cut on both skins: its two longest edges are concave
/// bevels (`BEVEL_TURN_DEG`) onto two planar skins of walls (faces with pairs). Standing on a floor, it meets
/// the floor square to it by its short end, as a lip's underside meets its plate along its length; the bevels
/// are the corner's wall.
fn bevel_between_walls(graph: &FaceGraph, face: FaceId, pairs_of: &[Vec<&Pair>]) -> bool {
    let mut edges: Vec<EdgeId> = graph.faces[face].loops.iter().flatten().copied().collect();
    edges.sort_by(|&a, &b| graph.edges[b].length.total_cmp(&graph.edges[a].length).then(a.cmp(&b)));
    let onto_wall = |e: EdgeId| {
        let edge = &graph.edges[e];
        let g = graph.across(e, face).next()?;
        let bevel = edge.convexity == Convexity::Concave && BEVEL_TURN_DEG.contains(&edge.angle.abs().to_degrees());
        (bevel && graph.faces[g].surface.is_plane() && !pairs_of[g].is_empty()).then_some(g)
    };
    match edges[..] {
        [a, b, ..] => matches!((onto_wall(a), onto_wall(b)), (Some(ga), Some(gb)) if ga != gb),
        _ => false,
    }
}

fn all_planar(graph: &FaceGraph, faces: &[FaceId]) -> bool {
    faces.iter().all(|&f| graph.faces[f].surface.is_plane())
}

fn mesh(face: &Face) -> Result<&crate::model::face_graph::Mesh, Rejection> {
    // Without a mesh no overlap can be measured: the faces cannot be shown to overlap.
    face.mesh.as_ref().ok_or(Rejection::Overlap { share: 0.0, limit: 0.0 })
}

fn check_overlap(ov: &Overlap, tol: &Tolerances) -> Result<(), Rejection> {
    let share = ov.share();
    if share < tol.overlap_share {
        return Err(Rejection::Overlap { share, limit: tol.overlap_share });
    }
    Ok(())
}

/// Plane pairs: parallel (opposite normals) or draft (normals within twice the draft limit of opposite).
fn planes(
    fa: &Face,
    fb: &Face,
    (pa, na): (DVec3, DVec3),
    (pb, nb): (DVec3, DVec3),
    tol: &Tolerances,
) -> Result<(PairKind, Thickness, f64), Rejection> {
    let angle = angle_between(na, -nb);
    let kind = if angle <= tol.parallel_angle {
        PairKind::Parallel
    } else if angle <= 2.0 * tol.draft_max {
        PairKind::Draft
    } else {
        return Err(Rejection::Angle {
            degrees: angle.to_degrees(),
            limit_degrees: (2.0 * tol.draft_max).to_degrees(),
        });
    };
    // Material lies behind each face (against its outward normal): the other face must be there.
    let behind_a = (fb.centroid - pa).dot(na);
    let behind_b = (fa.centroid - pb).dot(nb);
    if behind_a >= -tol.point || behind_b >= -tol.point {
        return Err(Rejection::NotFacing);
    }
    // The mid-plane: the exact bisector of the two planes (parallel planes: halfway).
    let (ca, cb) = (na.dot(pa), nb.dot(pb));
    let scale = (na - nb).length();
    let mid_normal = (na - nb) / scale;
    let thickness_at = |x: DVec3| {
        // Along the mid-plane normal from a point of the mid-plane to each plane.
        let sa = (ca - na.dot(x)) / na.dot(mid_normal);
        let sb = (cb - nb.dot(x)) / nb.dot(mid_normal);
        sa - sb
    };
    let thickness = match kind {
        PairKind::Parallel => Thickness::uniform(-behind_a),
        _ => draft_thickness(fa, fb, mid_normal, (ca - cb) / scale, thickness_at),
    };
    // Distance first: it is cheap, and most candidates from the box search fail it.
    if over(thickness.max, tol.t_max, tol) {
        return Err(Rejection::Distance { distance: thickness.max, limit: tol.t_max });
    }
    let ov = overlap::planar(mesh(fa)?, mesh(fb)?, mid_normal);
    check_overlap(&ov, tol)?;
    Ok((kind, thickness, ov.area))
}

/// A draft pair's thickness is linear across the mid-plane, so its mean over the overlap is its value at the
/// overlap's centroid; min and max are taken over the projected vertices of both faces that lie in the
/// overlap's range. The projected centroids of the two faces stand in for the overlap's centroid.
fn draft_thickness(
    fa: &Face,
    fb: &Face,
    mid_normal: DVec3,
    mid_offset: f64,
    thickness_at: impl Fn(DVec3) -> f64,
) -> Thickness {
    let onto_mid = |p: DVec3| p - mid_normal * (mid_normal.dot(p) - mid_offset);
    let smaller = if fa.area <= fb.area { fa } else { fb };
    let mean = thickness_at(onto_mid(smaller.centroid));
    let samples = smaller.mesh.as_ref().map(|m| m.vertices.as_slice()).unwrap_or(&[]);
    let (mut min, mut max) = (mean, mean);
    for &p in samples {
        let t = thickness_at(onto_mid(p));
        min = min.min(t);
        max = max.max(t);
    }
    Thickness { mean, min, max }
}

/// Axes (or an axis and a torus's axis) that are one line.
fn coaxial(oa: DVec3, aa: DVec3, ob: DVec3, ab: DVec3, tol: &Tolerances) -> Result<(), Rejection> {
    let tilt = angle_between(aa, ab).min(angle_between(aa, -ab));
    if tilt > tol.parallel_angle {
        return Err(Rejection::Angle { degrees: tilt.to_degrees(), limit_degrees: tol.parallel_angle.to_degrees() });
    }
    let d = ob - oa;
    let offset = (d - aa * d.dot(aa)).length();
    if offset > tol.coaxial {
        return Err(Rejection::NotCoaxial { offset });
    }
    Ok(())
}

/// Two concentric surfaces of opposite sense: the convex one (normal away from the centre) must be outside
/// the concave one, and the gap between them is the thickness.
fn radial_gap((ra, convex_a): (f64, bool), (rb, convex_b): (f64, bool), tol: &Tolerances) -> Result<f64, Rejection> {
    if convex_a == convex_b {
        return Err(Rejection::SameSense);
    }
    let (outer, inner) = if convex_a { (ra, rb) } else { (rb, ra) };
    let t = outer - inner;
    if t <= tol.point {
        return Err(Rejection::NotFacing);
    }
    if over(t, tol.t_max, tol) {
        return Err(Rejection::Distance { distance: t, limit: tol.t_max });
    }
    Ok(t)
}

/// The thickness of two coaxial cones opening the same way at the same half-angle (a drafted boss's or a
/// moulded corner's two skins): their rulings are parallel lines in every plane through the axis, so the wall is
/// as thick everywhere as the distance between those lines, the apexes' offset along the axis times the sine of
/// the half-angle. Exact where rays on a faceted mesh scatter by a few percent, so the mid-patch meets its drafted
/// planar neighbours, offset exactly, edge to edge. None for other cones (measured by rays).
fn parallel_cones(
    (axis_a, half_a, apex_a): (DVec3, f64, DVec3),
    (axis_b, half_b, apex_b): (DVec3, f64, DVec3),
    tol: &Tolerances,
) -> Result<Option<f64>, Rejection> {
    // OCCT's semi-angle is signed: the radius grows along the axis when it is positive.
    let (open_a, open_b) = (axis_a * half_a.signum(), axis_b * half_b.signum());
    if angle_between(open_a, open_b) > tol.parallel_angle || (half_a.abs() - half_b.abs()).abs() > tol.parallel_angle {
        return Ok(None);
    }
    let t = (apex_a - apex_b).dot(open_a).abs() * half_a.abs().sin();
    if t <= tol.point {
        return Err(Rejection::NotFacing);
    }
    if over(t, tol.t_max, tol) {
        return Err(Rejection::Distance { distance: t, limit: tol.t_max });
    }
    Ok(Some(t))
}

/// A freeform pair whose distance varies by more than `Tolerances::freeform_spread` is a tapered wall when at
/// least this share of the smaller face meets the other within the draft limit of opposite: a taper's skins
/// face each other nearly everywhere, while two differently shaped faces (a wavy skin across a flat one) do
/// only in patches.
const TAPER_SHARE: f64 = 0.5;

/// Curved faces the parameters reject pair by measurement only when this share of the smaller face meets the
/// other: the inner and outer skins of one wall drawn on centres a little apart face each other nearly
/// everywhere (all but the rays at their ends), while two faces of a block that face each other in part (a
/// boss's round beside a pocket's) do over half of it or less. The patch is the offset of the whole larger
/// face, with no footprint to clip it to, so the pair must be nearly whole.
const MEASURED_SHARE: f64 = 0.8;

/// How the distance between two faces measured by rays may vary.
enum Spread {
    /// Known exactly from the surfaces (concentric spheres, parallel cones): the rays only test the overlap.
    Exact(f64),
    /// A freeform pair: nearly constant (`Tolerances::freeform_spread`), or tapered (`TAPER_SHARE`).
    NearlyConstant,
    /// Drafted skins (rulings within twice the draft limit): the wall tapers, its range is reported.
    Tapered,
}

/// Two coaxial cones, or a cone and a cylinder (half-angle 0), whose rulings in a plane through the axis lean
/// apart by no more than twice the draft limit are the drafted skins of one wall, as two draft planes are (a
/// moulded boss: its outside narrows upwards, its core-pin hole widens upwards). OCCT's half-angles are
/// signed along the axis (the radius grows along it when positive), so the rulings lean apart by the
/// difference of the half-angles measured along one axis direction.
fn drafted_rulings(
    (axis_a, half_a): (DVec3, f64),
    (axis_b, half_b): (DVec3, f64),
    tol: &Tolerances,
) -> Result<Spread, Rejection> {
    let half_b = if axis_a.dot(axis_b) >= 0.0 { half_b } else { -half_b };
    let lean = (half_a - half_b).abs();
    if lean > 2.0 * tol.draft_max + tol.parallel_angle {
        return Err(Rejection::Angle { degrees: lean.to_degrees(), limit_degrees: (2.0 * tol.draft_max).to_degrees() });
    }
    Ok(Spread::Tapered)
}

/// Pairs measured by rays: from the smaller face along its inward normal onto the other.
fn sampled_pair(
    fa: &Face,
    fb: &Face,
    kind: PairKind,
    spread: Spread,
    tol: &Tolerances,
) -> Result<(PairKind, Thickness, f64), Rejection> {
    let (from, to) = if fa.area <= fb.area { (fa, fb) } else { (fb, fa) };
    let max_angle = 2.0 * tol.draft_max + tol.parallel_angle;
    let Some(s) = overlap::sampled(from, to, tol.t_max, max_angle) else {
        return Err(Rejection::Overlap { share: 0.0, limit: tol.overlap_share });
    };
    let share = s.share();
    let Some((mean, min, max)) = s.distance_stats().filter(|_| share >= tol.overlap_share) else {
        // A face whose partner lies in front of it, not behind, gets no hit at all.
        let facing = (to.centroid - from.point).dot(from.normal) < 0.0;
        return Err(if facing { Rejection::Overlap { share, limit: tol.overlap_share } } else { Rejection::NotFacing });
    };
    let thickness = match spread {
        Spread::Exact(t) => Thickness::uniform(t),
        // Past the spread a freeform wall tapers (a blade, a cast web): one wall still, when most of the smaller
        // face lies across it within the draft limit of opposite (the rays' own test), as drafted planes do.
        Spread::NearlyConstant if max - min > tol.freeform_spread * mean && share < TAPER_SHARE => {
            return Err(Rejection::Spread { min, max });
        }
        Spread::NearlyConstant | Spread::Tapered => Thickness { mean, min, max },
    };
    Ok((kind, thickness, s.hit_area))
}
