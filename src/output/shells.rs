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
use crate::trim::connected_sets;

/// The shells made and the warning when the kernel finds them invalid.
pub struct Assembled {
    pub shells: Shells,
    pub warning: Option<Warning>,
}

pub fn make_shells<K: Kernel>(kernel: &mut K, stitched: &Outcome, fuzzy: f64) -> Result<Assembled, SidecarError> {
    let sets = connected_sets(&stitched.fused, &stitched.keep);
    let shells = kernel.make_shells(stitched.fused.handle, sets, fuzzy)?;
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
) -> Result<(), Error> {
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
    let request = Request::WriteStep { path: utf8(&files.step)?, handle: shells.handle, faces, preview, solids };
    kernel.call::<Written>(&request).map_err(|error| Error::Sidecar { path: input.to_path_buf(), error })?;
    Ok(())
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

/// The area of the faces written. A face closed on itself is written as two pieces that both name it: count
/// each fused face once (its pieces make it up exactly).
pub fn written_area(shells: &Shells, fused: &Fused) -> f64 {
    let written: BTreeSet<usize> = shells.faces.iter().copied().collect();
    written.iter().map(|&p| fused.faces[p].area).sum()
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
        Shells { handle: 2, count: 1, faces, valid, invalid, edges: 0, vertices: 0 }
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
    fn a_face_split_at_its_seam_counts_once_in_the_written_area() {
        let fused = fused(&[(0, 2.0), (1, 3.0), (2, 5.0)]);
        // Fused face 1 (a tube) is written as two pieces, both naming it.
        assert_eq!(written_area(&shells(vec![0, 1, 1, 2], true, vec![]), &fused), 10.0);
    }
}
