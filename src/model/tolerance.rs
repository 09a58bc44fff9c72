//! Every tolerance of the pipeline, derived in one place from the part's size and the wall-thickness limit.

use serde::Serialize;

/// Tolerances for one solid. Build with [`Tolerances::new`]; each field says why it has its value.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Tolerances {
    /// Largest wall thickness that pairs whatever its width (user value or estimate: the part's gauges).
    pub t_max: f64,
    /// Safety bound: a wall thicker than t_max still pairs, up to this, when it is thin for its width
    /// (`pairing::criteria::wall_limit`). Equal to t_max when the user gives t_max (then a hard limit).
    pub t_bound: f64,
    /// Largest draft angle of a wall's side (radians): a draft pair's normals differ by up to twice this.
    pub draft_max: f64,
    /// Two lengths closer than this are equal: 1e-6 of the part's diagonal, far above STEP's float noise and
    /// far below any feature.
    pub point: f64,
    /// Two directions closer than this (radians) are parallel: exported CAD is exact to ~1e-9, so 0.5 degree
    /// only absorbs faceted or sloppily modelled parts and stays well below any intentional draft.
    pub parallel_angle: f64,
    /// Axes closer than this are the same axis (coaxial cylinders, cones, tori): 1% of the thickness limit.
    pub coaxial: f64,
    /// Smallest share of the smaller face that must overlap its partner for a pair (paper's overlap test).
    /// 10%: a real partner overlaps almost fully; faces beside each other (Fig. 9c) overlap by 0 or a sliver.
    pub overlap_share: f64,
    /// Fuzzy value for splitting patches where they cross: geometry closer than 1e-4 of the thickness limit is
    /// one, which absorbs offsetting round-off without merging anything a shell mesh could see.
    pub fuse: f64,
    /// A freeform pair's distance may vary by this share of its mean thickness ("nearly constant"); past it the
    /// wall tapers (`FREEFORM_SPREAD`).
    pub freeform_spread: f64,
    /// Farthest a free edge of a patch grows to meet another patch: 1.5 t_max covers a T-joint's half wall
    /// plus a root fillet of up to a wall's thickness, and an L-joint's half wall plus overshoot.
    pub joint_reach: f64,
    /// A mid-patch is clipped to its partners' footprint, but uncovered pieces up to this wide stay: t_max
    /// is the widest band a crossing wall or a corner overshoot leaves, which trimming and the joints handle;
    /// wider uncovered regions lie over other material (a boss, a thicker wall) and are cut away.
    pub clip_narrow: f64,
}

impl Tolerances {
    pub fn new(diagonal: f64, t_max: f64, draft_max: f64) -> Tolerances {
        Tolerances {
            t_max,
            t_bound: t_max,
            draft_max,
            point: diagonal * 1e-6,
            parallel_angle: 0.5_f64.to_radians(),
            coaxial: t_max * 0.01,
            overlap_share: 0.10,
            freeform_spread: FREEFORM_SPREAD,
            fuse: t_max * 1e-4,
            joint_reach: t_max * 1.5,
            clip_narrow: t_max,
        }
    }
}

/// A freeform pair's distance may vary by this share of its mean and still count as one thickness ("nearly
/// constant"). Past it the wall tapers, and pairs only when its skins face each other nearly everywhere.
pub const FREEFORM_SPREAD: f64 = 0.15;

/// A tapered freeform wall is offset at its mean thickness while its thickness varies by at most this share of
/// the mean: the patch is then off mid-wall by at most a quarter of it, 7.5% of the wall, within the 10% a
/// mid-surface may be off. Past it the patch follows the local mid-points (a moved B-spline, heavier for the
/// joints than an offset of the face).
pub const TAPER_SPREAD: f64 = 0.3;

/// Two cylinder axes within this angle (radians) are parallel, as two skins of one bend drawn on axes apart
/// (`patch::plan`, mean cylinder): exported CAD is exact to ~1e-9; the sidecar checks the same
/// (`PARALLEL_AXES` in its constants).
pub const PARALLEL_AXES: f64 = 1e-6;

/// Two partners' axes (or centres) closer than this share of their offset from the face's own are one: skins
/// drawn on one sketch.
pub const SAME_AXIS: f64 = 1e-9;

/// Two thicknesses closer than this share are one (the reference faces of a wall offset together, pairs that run
/// on into each other grouped as one wall): gauges of one sheet differ by more.
pub const SAME_THICKNESS: f64 = 0.01;

/// Default largest draft angle (degrees) when the user gives none: moulded parts rarely exceed 3 degrees.
pub const DEFAULT_DRAFT_MAX_DEG: f64 = 3.0;

/// Chordal tolerance of the face meshes asked from the sidecar, before any thickness is known: a twentieth of
/// the 2V/A wall estimate keeps sampled distances within ~5% of the wall (meshes are only used for overlap and
/// for distances between freeform faces).
pub fn mesh_tolerance(volume: f64, area: f64) -> f64 {
    let wall = if area > 0.0 { 2.0 * volume / area } else { 1.0 };
    (wall * 0.05).max(1e-3)
}

/// A patch's free edge this close to the part's boundary (mm, measured at mid-wall) is on the rim and does not
/// grow to it: a tenth of the patch's thickness, and never under two chords of the solid's mesh (a curved rim
/// is met on its mesh, up to a chord's sagitta off the true surface).
pub fn on_rim(thickness: f64, mesh_tolerance: f64) -> f64 {
    (RIM_SHARE * thickness).max(2.0 * mesh_tolerance)
}

/// An edge of the file written may lie off its faces by at most this share of the thinnest patch's thickness
/// (its tolerance once read back) before the report warns (`loose_edges`): a mesher's nodes along it stray as
/// far from the mid-surface.
pub const LOOSE_EDGE_SHARE: f64 = 0.05;

/// The share of a wall's thickness within which a free edge is on the rim (`on_rim`); a thickness step no
/// higher than this share of the thinner wall is not laid down into a ramp (`stitch::bridge::step_bridges`).
pub const RIM_SHARE: f64 = 0.1;

/// The fuzzy value of the fuses of a whole part (the patches of all its solids at once): the smallest of its
/// solids' `fuse`, so that no solid's geometry is merged past its own tolerance; 0 for a part with no solid.
pub fn part_fuse<'a>(solids: impl IntoIterator<Item = &'a Tolerances>) -> f64 {
    let fuzzy = solids.into_iter().map(|t| t.fuse).fold(f64::INFINITY, f64::min);
    if fuzzy.is_finite() {
        fuzzy
    } else {
        0.0
    }
}

/// Two faces of different solids whose areas, centroids and boxes agree within this are copies of one face
/// (`geom::bodies`): 1e-5 of the part's diagonal, ten times `Tolerances::point`, since the copies are
/// described separately (their properties integrated apart), and still far below any feature.
pub fn shared_face(diagonal: f64) -> f64 {
    diagonal * 1e-5
}
