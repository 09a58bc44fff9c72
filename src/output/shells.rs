//! The stitched patches made into shells (one per connected set of kept pieces), and the STEP written from
//! them with each face's name, colour and thickness.

use std::collections::BTreeSet;
use std::path::Path;

use super::files::Files;
use super::pending::Pending;
use super::report::{band, band_color, LegendEntry};
use crate::error::Error;
use crate::kernel::protocol::{FaceAttributes, KeptSolid, Request, Written};
use crate::kernel::{Kernel, SidecarError};
use crate::load::Part;
use crate::model::shapes::{Fused, Shells};
use crate::model::tolerance::LOOSE_EDGE_SHARE;
use crate::model::warning::{patch_list, Warning};
use crate::pairing::driver::SolidPairing;
use crate::patch::make::Made;
use crate::stitch::Outcome;
use crate::trim::{connected_sets, merge_sets};

/// The shells made and the warning when the kernel finds them invalid.
pub struct Assembled {
    pub shells: Shells,
    pub warning: Option<Warning>,
    /// The largest edge tolerance of the file read back (0 until written and checked).
    pub max_edge_tolerance: f64,
    /// How many more free edges the file read back has than the shells written (0 until written and checked):
    /// edges a reader took apart from the faces they joined.
    pub unshared_edges: usize,
}

pub fn make_shells<K: Kernel>(kernel: &mut K, stitched: &Outcome, fuzzy: f64) -> Result<Assembled, SidecarError> {
    make_shells_apart(kernel, stitched, fuzzy, &BTreeSet::new())
}

/// `make_shells`, with the merge sets that hold a piece of `apart` left unmerged.
fn make_shells_apart<K: Kernel>(
    kernel: &mut K,
    stitched: &Outcome,
    fuzzy: f64,
    apart: &BTreeSet<usize>,
) -> Result<Assembled, SidecarError> {
    let sets = canonical(&stitched.fused, connected_sets(&stitched.fused, &stitched.keep), fuzzy);
    let merge = canonical(&stitched.fused, merged(stitched, apart), fuzzy);
    let shells = kernel.make_shells(stitched.fused.handle, sets, merge, fuzzy)?;
    let warning = invalid_output_warning(&shells, &stitched.fused);
    Ok(Assembled { shells, warning, max_edge_tolerance: 0.0, unshared_edges: 0 })
}

/// `sets` of pieces in an order the geometry alone decides: each set's pieces by patch, then by centroid and
/// area on a grid of `grid` (mm), the sets by their first piece. The fuse lists its pieces in an order of its
/// own, which moves when the same faces are fused in another order or grouping; the shells are written in the
/// order given (a merge set's first piece stands for the merged face), so the same mid-surface gives the same
/// file. Pieces on the same cell of the grid keep their order.
fn canonical(fused: &Fused, mut sets: Vec<Vec<usize>>, grid: f64) -> Vec<Vec<usize>> {
    let cell = |x: f64| if grid > 0.0 { (x / grid).round() as i64 } else { 0 };
    let key = |p: usize| {
        let f = &fused.faces[p];
        (f.patch, cell(f.centroid.x), cell(f.centroid.y), cell(f.centroid.z), cell(f.area))
    };
    for set in &mut sets {
        set.sort_by_cached_key(|&p| key(p));
    }
    sets.sort_by_cached_key(|set| set.first().map(|&p| key(p)));
    sets
}

/// The solids that are not thin-walled, to be written as they are beside the mid-surface (--keep-solids).
pub fn kept_solids(part: &Part, pairings: &[SolidPairing]) -> Vec<KeptSolid> {
    part.solids
        .iter()
        .zip(pairings)
        .enumerate()
        .filter(|(_, (_, sp))| !sp.class.is_thin_walled())
        .map(|(i, (s, _))| KeptSolid { handle: s.handle, name: format!("solid {} not_thin_walled", i + 1) })
        .collect()
}

/// Writes the STEP (and the preview, when asked) to the files' temporaries, each face named after its patch,
/// then the solids kept as they are.
#[allow(clippy::too_many_arguments)]
pub fn write_step<K: Kernel>(
    kernel: &mut K,
    files: &Files,
    made: &[Made],
    fused: &Fused,
    shells: &Shells,
    legend: &[LegendEntry],
    t_band: f64,
    solids: Vec<KeptSolid>,
    input: &Path,
) -> Result<Written, Error> {
    let faces: Vec<FaceAttributes> = shells
        .faces
        .iter()
        .enumerate()
        .map(|(j, &piece)| {
            let k = fused.faces[piece].patch;
            let t = band(made[k].plan.thickness.mean, t_band);
            FaceAttributes {
                face: j,
                name: format!("patch {} t={t:.3}", k + 1),
                color: band_color(legend, t),
                thickness: t,
            }
        })
        .collect();
    let utf8 = |p: &Pending| {
        p.temp.to_str().map(str::to_string).ok_or_else(|| Error::output(&p.target, "path is not valid UTF-8"))
    };
    let preview = files.preview.as_ref().map(utf8).transpose()?;
    // Read back always: a shape valid in memory may still read back with broken faces (the reader splits and
    // heals what it reads), and the file is what users get.
    let check = true;
    let request = Request::WriteStep { path: utf8(&files.step)?, handle: shells.handle, faces, preview, solids, check };
    kernel.call::<Written>(&request).map_err(|error| Error::Sidecar { path: input.to_path_buf(), error })
}

/// Rounds of mending broken faces: each round rebuilds the shells without what the last file broke, and
/// pieces merged or sewn differently can break anew; a few rounds settle every part seen so far.
const MEND_ROUNDS: usize = 8;

/// Writes the mid-surface with `write`, reads the file back and, while faces of it fail the kernel's check,
/// mends them and writes it again (a few rounds): a broken face merged from several pieces is written as its
/// pieces, any other broken face is left out. The file kept is the one with the fewest broken faces (the
/// earliest of equals): a broken face is worse than a hole a user can see. Returns the shells written, the
/// write's reply and the warning naming the faces left out.
pub fn write_checked<K: Kernel>(
    kernel: &mut K,
    stitched: &mut Outcome,
    assembled: Assembled,
    fuzzy: f64,
    input: &Path,
    write: impl Fn(&mut K, &Outcome, &Shells) -> Result<Written, Error>,
) -> Result<(Assembled, Written, Option<Warning>), Error> {
    let failed = |error| Error::Sidecar { path: input.to_path_buf(), error };
    let kept_before = stitched.keep.clone();
    let mut written = write(kernel, stitched, &assembled.shells)?;
    let mut assembled = assembled;
    let mut apart: BTreeSet<usize> = BTreeSet::new();
    // The best file so far: (broken faces, pieces kept, merge sets kept apart).
    let mut best = (broken(&written), stitched.keep.clone(), apart.clone());
    for _ in 0..MEND_ROUNDS {
        if broken(&written) == 0 || written.invalid.is_empty() {
            break;
        }
        let sets = merged(stitched, &apart);
        for piece in pieces_of(&assembled.shells, &written.invalid) {
            match sets.iter().find(|set| set.contains(&piece)) {
                Some(set) => apart.extend(set.iter().copied()),
                None => stitched.keep[piece] = false,
            }
        }
        assembled = make_shells_apart(kernel, stitched, fuzzy, &apart).map_err(failed)?;
        written = write(kernel, stitched, &assembled.shells)?;
        if broken(&written) < best.0 {
            best = (broken(&written), stitched.keep.clone(), apart.clone());
        }
    }
    if (&stitched.keep, &apart) != (&best.1, &best.2) {
        // A later round mended no more than it broke: write the best state again.
        stitched.keep = best.1;
        apart = best.2;
        assembled = make_shells_apart(kernel, stitched, fuzzy, &apart).map_err(failed)?;
        written = write(kernel, stitched, &assembled.shells)?;
    }
    let left: Vec<usize> = (0..stitched.keep.len()).filter(|&p| stitched.keep[p] != kept_before[p]).collect();
    let warning = (!left.is_empty()).then(|| left_out_warning(&stitched.fused, &left));
    Ok((assembled, written, warning))
}

/// The merge sets of the kept pieces of `stitched`, but those holding a piece of `apart`.
fn merged(stitched: &Outcome, apart: &BTreeSet<usize>) -> Vec<Vec<usize>> {
    let mut sets = merge_sets(&stitched.fused, &stitched.keep);
    sets.retain(|set| !set.iter().any(|p| apart.contains(p)));
    sets
}

/// How many faces of the file fail the kernel's check once read back (an unreadable file counts as one).
fn broken(written: &Written) -> usize {
    match written.valid {
        Some(false) => written.invalid.len().max(1),
        _ => 0,
    }
}

/// The pieces of `stitched` that faces of `shells` (indices `invalid`) are.
fn pieces_of(shells: &Shells, invalid: &[usize]) -> Vec<usize> {
    let mut pieces: Vec<usize> = invalid.iter().map(|&j| shells.faces[j]).collect();
    pieces.sort_unstable();
    pieces.dedup();
    pieces
}

/// The warning naming the pieces left out because they failed the check once written and read back.
fn left_out_warning(fused: &Fused, pieces: &[usize]) -> Warning {
    let patches: BTreeSet<usize> = pieces.iter().map(|&p| fused.faces[p].patch).collect();
    let area: f64 = pieces.iter().map(|&p| fused.faces[p].area).sum();
    Warning {
        code: "faces_left_out",
        message: format!(
            "{} face(s) of patches {}, {area:.3} mm2 in all, fail the kernel's validity check (BRepCheck) once \
             written and read back; left out of the mid-surface",
            pieces.len(),
            patch_list(&patches)
        ),
        solid: None,
        faces: Vec::new(),
    }
}

/// The file's own check (when it was read back) stands for the shells' validity and names the faces that fail.
pub fn checked(assembled: &mut Assembled, written: &Written, fused: &Fused) {
    if let Some(valid) = written.valid {
        assembled.shells.valid = valid;
        assembled.shells.invalid = written.invalid.clone();
        assembled.warning = invalid_output_warning(&assembled.shells, fused);
    }
    assembled.max_edge_tolerance = written.max_edge_tolerance.unwrap_or(0.0);
    assembled.unshared_edges = written.free_edges.map_or(0, |n| n.saturating_sub(assembled.shells.free_edges));
}

/// Edges shared in the shells written that the file read back has apart: a reader rebuilt the faces on them
/// (the report's topology, counted on the shells, does not show these gaps).
pub fn unshared_edges_warning(unshared: usize) -> Option<Warning> {
    (unshared > 0).then(|| Warning {
        code: "edges_unshared",
        message: format!(
            "{unshared} edge(s) shared by faces of the mid-surface come apart when the file is read back (the \
             reader rebuilt faces on them): the file has gaps there that the report's topology does not count"
        ),
        solid: None,
        faces: Vec::new(),
    })
}

/// Edges of the file lying off their faces by more than `LOOSE_EDGE_SHARE` of the thinnest patch's thickness
/// (`thinnest`): the file is valid, but a mesh following those edges strays from the mid-surface as far.
pub fn loose_edges_warning(max_edge_tolerance: f64, thinnest: f64) -> Option<Warning> {
    (max_edge_tolerance > LOOSE_EDGE_SHARE * thinnest).then(|| Warning {
        code: "loose_edges",
        message: format!(
            "edges of the mid-surface lie up to {max_edge_tolerance:.3} mm off their faces (their tolerance once \
             read back), over {:.0}% of the thinnest patch's thickness {thinnest:.3}: a mesh along them strays as \
             far from the mid-surface",
            100.0 * LOOSE_EDGE_SHARE
        ),
        solid: None,
        faces: Vec::new(),
    })
}

/// Faces failing the kernel's check are written as they are (readers usually repair them), but a script must
/// know: said once, with their patches.
pub fn invalid_output_warning(shells: &Shells, fused: &Fused) -> Option<Warning> {
    let patches: BTreeSet<usize> = shells.invalid.iter().map(|&j| fused.faces[shells.faces[j]].patch).collect();
    (!shells.valid).then(|| Warning {
        code: "invalid_output",
        message: format!(
            "the mid-surface fails the kernel's validity check (BRepCheck){}: check them before meshing",
            if patches.is_empty() {
                String::new()
            } else {
                format!(" on {} face(s) of patches {}", shells.invalid.len(), patch_list(&patches))
            }
        ),
        solid: None,
        faces: Vec::new(),
    })
}

/// The area of the faces written: every kept piece is written, as a face of its own, as the two halves of a face
/// closed on itself, or inside the face its merge set makes (so not from the written faces' own pieces).
pub fn written_area(fused: &Fused, keep: &[bool]) -> f64 {
    fused.faces.iter().zip(keep).filter(|(_, &k)| k).map(|(f, _)| f.area).sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::fake::FakeKernel;
    use crate::model::shapes::{FusedEdge, FusedFace};
    use glam::DVec3;

    #[test]
    fn edges_read_back_off_their_faces_by_a_twentieth_of_the_thinnest_wall_are_warned_of() {
        // A 0.28 tolerance on walls 1.2 and ribs 0.8 thick (a drafted housing's corner seams): warned; a
        // B-spline fit's 0.002 is not.
        let warning = loose_edges_warning(0.28, 0.8).expect("0.28 > 0.05 x 0.8");
        assert_eq!(warning.code, "loose_edges");
        assert!(warning.message.contains("0.280 mm"), "{}", warning.message);
        assert!(loose_edges_warning(0.002, 0.8).is_none());
        assert!(loose_edges_warning(0.039, 0.8).is_none() && loose_edges_warning(0.041, 0.8).is_some());
    }

    #[test]
    fn edges_the_file_reads_back_apart_are_counted_and_warned_of() {
        // The shells written have 15 free edges; the file read back 16 (a reader rebuilt a face apart from the
        // rib's foot): one edge unshared, warned. As many as written: nothing.
        let mut assembled = Assembled {
            shells: Shells { free_edges: 15, ..shells(vec![0], true, vec![]) },
            warning: None,
            max_edge_tolerance: 0.0,
            unshared_edges: 0,
        };
        let fused = fused(&[(0, 1.0)]);
        let mut read = written(&assembled.shells, &[], false);
        read.free_edges = Some(16);
        checked(&mut assembled, &read, &fused);
        assert_eq!(assembled.unshared_edges, 1);
        assert_eq!(unshared_edges_warning(assembled.unshared_edges).expect("one edge apart").code, "edges_unshared");
        read.free_edges = Some(15);
        checked(&mut assembled, &read, &fused);
        assert_eq!(assembled.unshared_edges, 0);
        assert!(unshared_edges_warning(assembled.unshared_edges).is_none());
    }

    /// Fused pieces of the given (patch, area).
    fn fused(faces: &[(usize, f64)]) -> Fused {
        let face = |&(patch, area): &(usize, f64)| FusedFace {
            patch,
            area,
            centroid: DVec3::ZERO,
            point: DVec3::ZERO,
            normal: DVec3::Z,
            edges: vec![],
        };
        Fused { handle: 1, faces: faces.iter().map(face).collect(), edges: vec![], invalid: vec![] }
    }

    fn shells(faces: Vec<usize>, valid: bool, invalid: Vec<usize>) -> Shells {
        Shells {
            handle: 2,
            count: 1,
            components: 1,
            faces,
            valid,
            invalid,
            edges: 0,
            vertices: 0,
            free_edges: 0,
            nonmanifold_edges: 0,
        }
    }

    fn outcome(pieces: usize) -> Outcome {
        let fused = fused(&vec![(0, 1.0); pieces]);
        Outcome { fused, keep: vec![true; pieces], branches: vec![], joints: vec![], free: None, warnings: vec![] }
    }

    /// The sidecar's reply to make_shells with the kept pieces of `keep`, each a shell of its own, all valid.
    fn shells_reply(keep: &[bool]) -> serde_json::Value {
        let faces: Vec<usize> = (0..keep.len()).filter(|&p| keep[p]).collect();
        serde_json::json!({"handle": 3, "shells": faces.len(), "components": faces.len(), "faces": faces,
            "valid": true, "invalid": [], "edges": 0, "vertices": 0,
            "free_edges": 0, "nonmanifold_edges": 0})
    }

    /// A file whose read-back breaks the written faces that are the pieces `broken` (or, with `unnamed`, breaks
    /// without naming a face).
    fn written(shells: &Shells, broken: &[usize], unnamed: bool) -> Written {
        let invalid: Vec<usize> = (0..shells.faces.len()).filter(|&j| broken.contains(&shells.faces[j])).collect();
        let valid = invalid.is_empty() && !unnamed;
        Written {
            path: String::new(),
            bytes: 0,
            valid: Some(valid),
            invalid,
            max_edge_tolerance: None,
            free_edges: None,
        }
    }

    /// `write_checked` on `stitched`, first written as one face per piece, the kernel answering make_shells with
    /// `replies` and the file read back as `read` says; returns its result and the kernel (its requests).
    fn check_all(
        stitched: &mut Outcome,
        replies: Vec<serde_json::Value>,
        read: impl Fn(&Outcome, &Shells) -> Written,
    ) -> (Assembled, Written, Option<Warning>, FakeKernel) {
        let faces = (0..stitched.keep.len()).collect();
        check_all_from(stitched, faces, replies, read)
    }

    /// `check_all`, first written as the faces `faces` (the piece each is).
    fn check_all_from(
        stitched: &mut Outcome,
        faces: Vec<usize>,
        replies: Vec<serde_json::Value>,
        read: impl Fn(&Outcome, &Shells) -> Written,
    ) -> (Assembled, Written, Option<Warning>, FakeKernel) {
        let mut kernel = FakeKernel::new(replies);
        let first = Assembled {
            shells: shells(faces, true, vec![]),
            warning: None,
            max_edge_tolerance: 0.0,
            unshared_edges: 0,
        };
        let write = |_: &mut FakeKernel, s: &Outcome, sh: &Shells| Ok(read(s, sh));
        let (assembled, written, warning) =
            write_checked(&mut kernel, stitched, first, 0.0, Path::new("in.step"), write).unwrap();
        (assembled, written, warning, kernel)
    }

    #[test]
    fn broken_faces_are_left_out_round_after_round_until_the_file_reads_back_valid() {
        // Piece 1 breaks on reading; without it, piece 2 does (its merge or sewing changed); without both, none.
        let mut stitched = outcome(3);
        let replies = vec![shells_reply(&[true, false, true]), shells_reply(&[true, false, false])];
        let (assembled, last, warning, _) = check_all(&mut stitched, replies, |s, sh| {
            let broken: Vec<usize> = if s.keep[1] {
                vec![1]
            } else if s.keep[2] {
                vec![2]
            } else {
                vec![]
            };
            written(sh, &broken, false)
        });
        assert_eq!(stitched.keep, vec![true, false, false]);
        assert_eq!(assembled.shells.faces, vec![0]);
        assert_eq!(last.valid, Some(true));
        let warning = warning.unwrap();
        assert_eq!(warning.code, "faces_left_out");
        assert!(warning.message.starts_with("2 face(s) of patches 1,"), "{}", warning.message);
    }

    #[test]
    fn a_round_that_mends_nothing_is_undone() {
        // Without piece 1 the file still breaks (unnamed): leaving it out bought nothing, so it stays in.
        let mut stitched = outcome(3);
        let replies = vec![shells_reply(&[true, false, true]), shells_reply(&[true, true, true])];
        let (assembled, last, warning, _) = check_all(&mut stitched, replies, |s, sh| {
            if s.keep[1] {
                written(sh, &[1], false)
            } else {
                written(sh, &[], true)
            }
        });
        assert_eq!(stitched.keep, vec![true, true, true]);
        assert_eq!(assembled.shells.faces, vec![0, 1, 2]);
        assert_eq!(last.invalid, vec![1]);
        assert!(warning.is_none());
    }

    #[test]
    fn a_broken_merged_face_is_written_as_its_pieces() {
        // Pieces 0 and 1 of one patch share an edge no other piece uses: merged into one face, which breaks on
        // reading; written as two faces, it reads back valid and nothing is left out.
        let mut stitched = outcome(3);
        stitched.fused.faces[0].edges = vec![0];
        stitched.fused.faces[1].edges = vec![0];
        stitched.fused.edges =
            vec![FusedEdge { length: 1.0, faces: vec![0, 1], points: vec![], inside: vec![], stem_end: false }];
        // First written as faces 0 (pieces 0 and 1 merged) and 2.
        let (assembled, last, warning, kernel) =
            check_all_from(&mut stitched, vec![0, 2], vec![shells_reply(&[true, true, true])], |_, sh| {
                let merged_face_breaks = sh.faces.len() == 2;
                written(sh, if merged_face_breaks { &[0] } else { &[] }, false)
            });
        let Some(Request::MakeShells { merge, .. }) = kernel.requests.last() else { panic!("no make_shells") };
        assert!(merge.is_empty(), "{merge:?}");
        assert_eq!(stitched.keep, vec![true, true, true]);
        assert_eq!(assembled.shells.faces, vec![0, 1, 2]);
        assert_eq!(last.valid, Some(true));
        assert!(warning.is_none());
    }

    /// Sets of pieces, each piece given as the (patch, centroid x) it is.
    type NamedSets = Vec<Vec<(usize, f64)>>;

    /// The shells and merge sets `make_shells` asks of the kernel for `stitched`.
    fn asked_shells(stitched: &Outcome) -> (NamedSets, NamedSets) {
        let mut kernel = FakeKernel::new(vec![shells_reply(&stitched.keep)]);
        make_shells(&mut kernel, stitched, 1e-3).unwrap();
        let Some(Request::MakeShells { shells, merge, .. }) = kernel.requests.last() else { panic!("no make_shells") };
        let named = |sets: &Vec<Vec<usize>>| -> NamedSets {
            let face = |p: usize| (stitched.fused.faces[p].patch, stitched.fused.faces[p].centroid.x);
            sets.iter().map(|set| set.iter().map(|&p| face(p)).collect()).collect()
        };
        (named(shells), named(merge))
    }

    #[test]
    fn shells_are_asked_in_an_order_the_geometry_decides_not_the_fuse() {
        // Pieces (patch, centroid x): patch 1 in two pieces sharing an edge (a merge set), patch 0 in two pieces
        // sharing an edge with patch 1's first, and a lone piece of patch 2. The fuse may list them in any order.
        let pieces = [(1, 3.0), (0, 5.0), (2, 9.0), (1, 1.0), (0, 2.0)];
        let edges = [vec![0, 3], vec![3, 1], vec![1, 4]];
        let stitched_in = |order: &[usize]| {
            let mut stitched = outcome(pieces.len());
            let at = |piece: usize| order.iter().position(|&p| p == piece).unwrap();
            for (k, &piece) in order.iter().enumerate() {
                let face = &mut stitched.fused.faces[k];
                (face.patch, face.centroid) = (pieces[piece].0, DVec3::new(pieces[piece].1, 0.0, 0.0));
            }
            stitched.fused.edges = edges
                .iter()
                .map(|e| FusedEdge {
                    length: 1.0,
                    faces: e.iter().map(|&p| at(p)).collect(),
                    points: vec![],
                    inside: vec![],
                    stem_end: false,
                })
                .collect();
            for (j, edge) in stitched.fused.edges.iter().enumerate() {
                for &f in &edge.faces {
                    stitched.fused.faces[f].edges.push(j);
                }
            }
            stitched
        };
        let listed = asked_shells(&stitched_in(&[0, 1, 2, 3, 4]));
        assert_eq!(
            listed.0,
            vec![vec![(0, 2.0), (0, 5.0), (1, 1.0), (1, 3.0)], vec![(2, 9.0)]],
            "pieces by patch then position, shells by their first piece"
        );
        assert_eq!(listed.1, vec![vec![(0, 2.0), (0, 5.0)], vec![(1, 1.0), (1, 3.0)]]);
        assert_eq!(asked_shells(&stitched_in(&[4, 2, 3, 0, 1])), listed);
    }

    #[test]
    fn invalid_faces_are_named_by_the_patches_they_belong_to() {
        // Shell face j is fused piece faces[j]; pieces 0..3 belong to patches 4, 4, 0, 2 (ids 5, 5, 1, 3).
        let fused = fused(&[(4, 1.0), (4, 1.0), (0, 1.0), (2, 1.0)]);
        let w = invalid_output_warning(&shells(vec![3, 0, 1, 2], false, vec![1, 2, 0]), &fused).unwrap();
        assert_eq!(w.code, "invalid_output");
        assert!(w.message.contains("on 3 face(s) of patches 3, 5:"), "{}", w.message);
        assert!(invalid_output_warning(&shells(vec![0, 1, 2, 3], true, vec![]), &fused).is_none());
        // Invalid as a whole (say, a shell in two pieces) with every face sound: no patch to name.
        let whole = invalid_output_warning(&shells(vec![0, 1, 2, 3], false, vec![]), &fused).unwrap();
        assert!(!whole.message.contains("patches"), "{}", whole.message);
    }

    #[test]
    fn the_written_area_is_the_kept_pieces_area() {
        let fused = fused(&[(0, 2.0), (1, 3.0), (2, 5.0)]);
        assert_eq!(written_area(&fused, &[true, false, true]), 7.0);
    }
}
