//! The stitched patches made into shells (one per connected set of kept pieces), and the STEP written from
//! them with each face's name, colour and thickness.

use std::collections::BTreeSet;
use std::path::Path;

use super::files::Files;
use super::pending::Pending;
use super::report::{band_color, LegendEntry};
use crate::error::Error;
use crate::kernel::protocol::{FaceAttributes, KeptSolid, Request, Written};
use crate::kernel::{Kernel, SidecarError};
use crate::load::Part;
use crate::model::shapes::{Fused, Shells};
use crate::model::warning::{patch_list, Warning};
use crate::pairing::driver::SolidPairing;
use crate::patch::make::Made;
use crate::stitch::Outcome;
use crate::trim::{connected_sets, merge_sets};

/// The shells made and the warning when the kernel finds them invalid.
pub struct Assembled {
    pub shells: Shells,
    pub warning: Option<Warning>,
}

pub fn make_shells<K: Kernel>(kernel: &mut K, stitched: &Outcome, fuzzy: f64) -> Result<Assembled, SidecarError> {
    let sets = connected_sets(&stitched.fused, &stitched.keep);
    let merge = merge_sets(&stitched.fused, &stitched.keep);
    let shells = kernel.make_shells(stitched.fused.handle, sets, merge, fuzzy)?;
    let warning = invalid_output_warning(&shells, &stitched.fused);
    Ok(Assembled { shells, warning })
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
    solids: Vec<KeptSolid>,
    input: &Path,
) -> Result<Written, Error> {
    let faces: Vec<FaceAttributes> = shells
        .faces
        .iter()
        .enumerate()
        .map(|(j, &piece)| {
            let k = fused.faces[piece].patch;
            let t = made[k].plan.thickness.mean;
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
    // Read back only what the kernel doubts: a shape valid in memory reads back valid.
    let check = !shells.valid;
    let request = Request::WriteStep { path: utf8(&files.step)?, handle: shells.handle, faces, preview, solids, check };
    kernel.call::<Written>(&request).map_err(|error| Error::Sidecar { path: input.to_path_buf(), error })
}

/// Writes the mid-surface with `write`; when the file read back has broken faces, leaves them out and writes it
/// again without them (once). When the file is still broken without them (a shell the reader cannot take),
/// leaving them out only costs coverage: it is written as it was, and the report names the faces that fail.
/// Returns the shells written, the write's reply and the warning naming the faces left out.
pub fn write_checked<K: Kernel>(
    kernel: &mut K,
    stitched: &mut Outcome,
    assembled: Assembled,
    fuzzy: f64,
    input: &Path,
    write: impl Fn(&mut K, &Outcome, &Shells) -> Result<Written, Error>,
) -> Result<(Assembled, Written, Option<Warning>), Error> {
    let failed = |error| Error::Sidecar { path: input.to_path_buf(), error };
    let written = write(kernel, stitched, &assembled.shells)?;
    if written.invalid.is_empty() {
        return Ok((assembled, written, None));
    }
    let kept_before = stitched.keep.clone();
    let left_out = leave_out(stitched, &assembled.shells, &written.invalid);
    let again = make_shells(kernel, stitched, fuzzy).map_err(failed)?;
    let rewritten = write(kernel, stitched, &again.shells)?;
    if rewritten.valid != Some(false) {
        return Ok((again, rewritten, Some(left_out)));
    }
    stitched.keep = kept_before;
    let assembled = make_shells(kernel, stitched, fuzzy).map_err(failed)?;
    let written = write(kernel, stitched, &assembled.shells)?;
    Ok((assembled, written, None))
}

/// Leaves out of `stitched` the pieces whose faces of `shells` (indices `invalid`) failed the check once written
/// and read back: a broken face is worse than a hole a user can see. Returns the warning naming them.
fn leave_out(stitched: &mut Outcome, shells: &Shells, invalid: &[usize]) -> Warning {
    let mut pieces: Vec<usize> = invalid.iter().map(|&j| shells.faces[j]).collect();
    pieces.sort_unstable();
    pieces.dedup();
    for &p in &pieces {
        stitched.keep[p] = false;
    }
    let fused = &stitched.fused;
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
    use crate::model::shapes::FusedFace;
    use glam::DVec3;

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
        Fused { handle: 1, faces: faces.iter().map(face).collect(), edges: vec![] }
    }

    fn shells(faces: Vec<usize>, valid: bool, invalid: Vec<usize>) -> Shells {
        Shells { handle: 2, count: 1, components: 1, faces, valid, invalid, edges: 0, vertices: 0 }
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
