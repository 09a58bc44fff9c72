//! Bodies: the solids of a file that are one piece of material. A part partitioned for meshing (a rib cut off
//! its plate, a bracket split at its bend) comes as several solids, each with its own copy of the face between
//! them: the two copies coincide and face opposite ways. Such solids form one body, and the stitching sees the
//! body's material (the union of its solids, without the faces between them), so that patches of different
//! solids meet across the faces they share as they would inside one solid. Solids that only touch (a cover
//! resting on a frame) share no whole face and stay apart.

use std::collections::{BTreeMap, BTreeSet};

use glam::DVec3;

use super::inside::SolidMesh;
use crate::model::face_graph::{Face, FaceGraph};
use crate::model::tolerance;
use crate::model::union_find::{find, union};

/// A face of one solid lying on a face of another: (solid, face) both ways round, lower solid first.
pub type SharedFace = [(usize, usize); 2];

/// Two faces whose outward area vectors (sum of triangle normals times areas) are shorter than this share of
/// their area close on themselves (a whole cylinder or sphere): their orientation is read at a vertex instead.
const OPEN_SHARE: f64 = 0.1;

/// The faces shared by two solids of `graphs`: coincident (area, centroid and box equal within `tol`) and
/// facing opposite ways. Faces are matched through a sweep along x of their centroids, so the cost is that of
/// sorting the faces, not of all pairs.
pub fn shared_faces(graphs: &[&FaceGraph], tol: f64) -> Vec<SharedFace> {
    let mut faces: Vec<(usize, &Face)> =
        graphs.iter().enumerate().flat_map(|(s, g)| g.faces.iter().map(move |f| (s, f))).collect();
    faces.sort_by(|a, b| a.1.centroid.x.total_cmp(&b.1.centroid.x).then(a.0.cmp(&b.0)).then(a.1.id.cmp(&b.1.id)));
    let mut shared = Vec::new();
    for (i, &(sa, a)) in faces.iter().enumerate() {
        for &(sb, b) in faces[i + 1..].iter().take_while(|(_, b)| b.centroid.x - a.centroid.x <= tol) {
            if sa != sb && coincide(a, b, tol) && opposite(a, b, tol) {
                shared.push(if sa < sb { [(sa, a.id), (sb, b.id)] } else { [(sb, b.id), (sa, a.id)] });
            }
        }
    }
    shared.sort_unstable();
    shared
}

fn coincide(a: &Face, b: &Face, tol: f64) -> bool {
    (a.area - b.area).abs() <= tol * (a.area.sqrt() + b.area.sqrt())
        && a.centroid.distance(b.centroid) <= tol
        && a.bbox.min.distance(b.bbox.min) <= tol
        && a.bbox.max.distance(b.bbox.max) <= tol
}

fn opposite(a: &Face, b: &Face, tol: f64) -> bool {
    let (Some(ma), Some(mb)) = (&a.mesh, &b.mesh) else { return a.normal.dot(b.normal) < 0.0 };
    let (va, vb) = (area_vector(ma), area_vector(mb));
    if va.length() >= OPEN_SHARE * a.area && vb.length() >= OPEN_SHARE * b.area {
        return va.dot(vb) < 0.0;
    }
    // A closed face: the outward normals at a vertex of one and the nearest vertex of the other.
    let Some((k, &p)) = ma.vertices.iter().enumerate().next() else { return false };
    let nearest = mb.vertices.iter().enumerate().min_by(|x, y| x.1.distance(p).total_cmp(&y.1.distance(p)));
    nearest.is_some_and(|(j, q)| q.distance(p) <= tol && ma.normals[k].dot(mb.normals[j]) < 0.0)
}

fn area_vector(mesh: &crate::model::face_graph::Mesh) -> DVec3 {
    mesh.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| mesh.vertices[i as usize]);
            (b - a).cross(c - a) * 0.5
        })
        .sum()
}

/// The body of each solid (the lowest solid index in it), from the faces the solids share.
pub fn bodies(solids: usize, shared: &[SharedFace]) -> Vec<usize> {
    let mut parent: Vec<usize> = (0..solids).collect();
    for [(a, _), (b, _)] in shared {
        union(&mut parent, *a, *b);
    }
    (0..solids).map(|s| find(&mut parent, s)).collect()
}

/// The solids of a part grouped into bodies, what joins them, and the material each solid's patches lie in.
pub struct Bodies {
    pub shared: Vec<SharedFace>,
    /// The body of each solid (`bodies`).
    pub of_solid: Vec<usize>,
    /// Per solid: its body's material (`materials`).
    pub materials: Vec<SolidMesh>,
}

impl Bodies {
    /// The bodies of the solids `graphs`, faces matched within `tolerance::shared_face` of the part's
    /// diagonal. None when a face was described without a mesh.
    pub fn of(graphs: &[&FaceGraph]) -> Option<Bodies> {
        let (lo, hi) = graphs
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), g| (lo.min(g.bbox.min), hi.max(g.bbox.max)));
        let shared = shared_faces(graphs, tolerance::shared_face((hi - lo).length()));
        let of_solid = bodies(graphs.len(), &shared);
        let materials = materials(graphs, &shared, &of_solid)?;
        Some(Bodies { shared, of_solid, materials })
    }
}

/// The material each solid's patches lie in (`body`: the body of each solid): the solid's own mesh, or for a
/// solid of a body of several, the body's (every face of its solids but the `shared` ones), one mesh shared by
/// its solids. None when a face was described without a mesh.
pub fn materials(graphs: &[&FaceGraph], shared: &[SharedFace], body: &[usize]) -> Option<Vec<SolidMesh>> {
    let inner: &BTreeSet<(usize, usize)> = &shared.iter().flatten().copied().collect();
    let mut members: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for (s, &b) in body.iter().enumerate() {
        members.entry(b).or_default().push(s);
    }
    let mut of_body: BTreeMap<usize, SolidMesh> = BTreeMap::new();
    for (b, solids) in members {
        let faces = solids.iter().flat_map(|&t| graphs[t].faces.iter().filter(move |f| !inner.contains(&(t, f.id))));
        of_body.insert(b, SolidMesh::of_faces(faces)?);
    }
    Some(body.iter().map(|b| of_body[b].clone()).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synthetic::{self, cuboid};

    fn split_plate() -> (FaceGraph, FaceGraph) {
        (
            cuboid(DVec3::ZERO, DVec3::new(50.0, 60.0, 2.0)),
            cuboid(DVec3::new(50.0, 0.0, 0.0), DVec3::new(50.0, 60.0, 2.0)),
        )
    }

    #[test]
    fn two_halves_of_a_plate_share_their_cut_face_and_are_one_body() {
        let (a, b) = split_plate();
        let shared = shared_faces(&[&a, &b], 1e-4);
        assert_eq!(shared.len(), 1, "{shared:?}");
        let [(sa, fa), (sb, fb)] = shared[0];
        assert_eq!((sa, sb), (0, 1));
        assert!((a.faces[fa].centroid.x - 50.0).abs() < 1e-9 && (b.faces[fb].centroid.x - 50.0).abs() < 1e-9);
        assert_eq!(bodies(2, &shared), vec![0, 0]);
        // The body's material runs on across the cut: a point just past it is inside, and a ray from one half
        // leaves the material at the far end of the other.
        let m = materials(&[&a, &b], &shared, &[0, 0]).unwrap();
        assert!(m[0].contains(DVec3::new(50.5, 30.0, 1.0)));
        assert!((m[0].exit(DVec3::new(40.0, 30.0, 1.0), DVec3::X, 100.0).unwrap() - 60.0).abs() < 1e-9);
        let alone = SolidMesh::new(&a).unwrap();
        assert!(!alone.contains(DVec3::new(50.5, 30.0, 1.0)));
    }

    #[test]
    fn a_whole_cylinder_shared_by_a_core_and_its_sleeve_is_read_at_a_vertex() {
        // A full turn: the area vector vanishes, the orientation is read from the vertex normals.
        let turn = (0.0, std::f64::consts::TAU);
        let core = synthetic::graph(vec![synthetic::cylinder(DVec3::ZERO, 3.0, turn, 10.0, true)], &[]);
        let sleeve = synthetic::graph(vec![synthetic::cylinder(DVec3::ZERO, 3.0, turn, 10.0, false)], &[]);
        assert!(area_vector(core.faces[0].mesh.as_ref().unwrap()).length() < 1e-6 * core.faces[0].area);
        assert_eq!(shared_faces(&[&core, &sleeve], 1e-4), vec![[(0, 0), (1, 0)]]);
        let twin = synthetic::graph(vec![synthetic::cylinder(DVec3::ZERO, 3.0, turn, 10.0, true)], &[]);
        assert!(shared_faces(&[&core, &twin], 1e-4).is_empty(), "facing the same way");
    }

    #[test]
    fn solids_that_only_touch_or_overlap_the_same_way_are_separate_bodies() {
        // A block standing on part of the plate: the contact is not a whole face of either.
        let plate = cuboid(DVec3::ZERO, DVec3::new(100.0, 60.0, 2.0));
        let block = cuboid(DVec3::new(10.0, 10.0, 2.0), DVec3::new(20.0, 20.0, 10.0));
        assert!(shared_faces(&[&plate, &block], 1e-4).is_empty());
        // The same box twice: its faces coincide but face the same way (not a partition).
        let copy = cuboid(DVec3::ZERO, DVec3::new(100.0, 60.0, 2.0));
        assert!(shared_faces(&[&plate, &copy], 1e-4).is_empty());
        assert_eq!(bodies(2, &[]), vec![0, 1]);
    }
}
