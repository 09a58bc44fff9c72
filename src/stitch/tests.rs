//! Stitching driven by the fake kernel: hand-made fused patches and probes of their free edges (as the sidecar
//! would reply), and assertions on what stitch decides (which edges grow, how, and which stay free).

use glam::DVec3;
use serde_json::{json, Value};

use super::*;
use crate::kernel::fake::FakeKernel;
use crate::kernel::protocol::Request;
use crate::synthetic;

#[test]
fn open_edges_are_said_once_with_their_patches() {
    let free = FreeEdges { rim_edges: 4, rim_length: 40.0, open_edges: 3, open_length: 2.5 };
    let w = open_edges_warning(&free, &BTreeSet::from([6, 0])).unwrap();
    assert_eq!(w.code, "open_edges");
    assert!(w.message.starts_with("3 free edge(s), 2.500 mm") && w.message.contains("(patches 1, 7)"), "{}", w.message);
    assert!(open_edges_warning(&FreeEdges { open_edges: 0, ..free }, &BTreeSet::new()).is_none());
}

#[test]
fn edges_that_met_no_patch_are_warned_only_for_patches_still_open() {
    // Patch 1's edge met no patch but another patch's strip closed it; patch 2's is still open (0-based 1); a
    // joint the kernel could not grow is warned whatever is open.
    let none = |id: usize| JointReport { patches: vec![id], kind: "none", status: "no_partner", edges: 1, length: 5.0 };
    let failed = JointReport { status: "kernel_failed", ..report(vec![3, 4], "t", 1, 7.0) };
    let warnings = joint_warnings(&[none(1), none(2), failed], &BTreeSet::from([1]));
    let messages: Vec<&str> = warnings.iter().map(|w| w.message.as_str()).collect();
    assert_eq!(messages.len(), 2, "{messages:?}");
    assert!(messages[0].starts_with("patch 2: 1 open edge(s)"), "{messages:?}");
    assert!(messages[1].starts_with("t joint of patches [3, 4]"), "{messages:?}");
}

fn v(p: DVec3) -> Value {
    json!([p.x, p.y, p.z])
}

/// A fused face of `patch` with normal `normal` (the rest does not matter to stitch).
fn face(patch: usize, normal: DVec3) -> Value {
    face_at(patch, DVec3::ZERO, normal)
}

/// A face of `patch` through `point`, with its normal there.
fn face_at(patch: usize, point: DVec3, normal: DVec3) -> Value {
    json!({"patch": patch, "area": 100.0, "centroid": v(point), "point": v(point), "normal": v(normal), "edges": []})
}

/// A straight edge from a to b on `faces`.
fn edge(a: DVec3, b: DVec3, faces: &[usize]) -> Value {
    json!({"length": a.distance(b), "faces": faces, "points": [v(a), v(b)]})
}

/// The probe of a straight free edge from a to b (`joint::SAMPLES` samples), the patch's normal, the outward
/// direction, and at every sample the same meetings (face, distance, gap).
fn probe(a: DVec3, b: DVec3, normal: DVec3, outward: DVec3, hits: &[(usize, f64, f64)]) -> Value {
    let n = joint::SAMPLES;
    let points: Vec<Value> = (0..n).map(|k| v(a.lerp(b, k as f64 / (n - 1) as f64))).collect();
    let hits: Vec<Value> =
        hits.iter().map(|&(face, distance, gap)| json!({"face": face, "distance": distance, "gap": gap})).collect();
    json!({"points": points, "normals": vec![v(normal); n], "outward": vec![v(outward); n], "hits": vec![hits; n]})
}

/// The replies of a joints pass whose fused result has no free edge left: extend_edges (`strips` and `corners`
/// made), one gather per patch, and the fuse.
fn pass_replies(strips: usize, corners: usize, patches: usize) -> Vec<Value> {
    let made = |k: usize| vec![json!({"area": 10.0, "error": null}); k];
    let mut out = vec![json!({"handle": 20, "strips": made(strips), "corners": made(corners)})];
    out.extend((0..patches).map(|p| json!({"handle": 30 + p, "faces": 1})));
    let faces: Vec<Value> = (0..patches).map(|p| face(p, DVec3::Z)).collect();
    out.push(json!({"handle": 40, "faces": faces, "edges": []}));
    out
}

fn fused(faces: Vec<Value>, edges: Vec<Value>) -> Fused {
    let wire: crate::kernel::protocol::Fused =
        serde_json::from_value(json!({"handle": 1, "faces": faces, "edges": edges})).unwrap();
    Fused::from(wire)
}

fn info(thickness: f64, wall: (usize, usize)) -> PatchInfo {
    PatchInfo {
        thickness,
        to_mid: 0.0,
        solid: 0,
        body: 0,
        reach: 4.5,
        on_rim: 0.2,
        junction: false,
        wall,
        freeform: false,
    }
}

/// Runs stitch on `fused` (every piece kept) in a solid filling `solid` (origin, size), with the probes and pass
/// replies scripted: the joints found and the kernel's requests.
fn run(fused: &Fused, patches: &[PatchInfo], solid: (DVec3, DVec3), replies: Vec<Value>) -> (Stitched, FakeKernel) {
    let mesh = SolidMesh::new(&synthetic::cuboid(solid.0, solid.1)).unwrap();
    let mut kernel = FakeKernel::new(replies);
    let keep = vec![true; fused.faces.len()];
    let stitched = stitch(&mut kernel, fused, &keep, patches, &[mesh], 1e-4).unwrap();
    assert!(kernel.replies.is_empty(), "every scripted reply was asked for");
    (stitched, kernel)
}

fn extend_request(
    kernel: &FakeKernel,
) -> (Vec<crate::kernel::protocol::StripRequest>, Vec<crate::kernel::protocol::CornerRequest>) {
    match kernel.requests.iter().find(|r| r.op() == "extend_edges") {
        Some(Request::ExtendEdges { strips, corners, .. }) => (strips.clone(), corners.clone()),
        _ => panic!("no extend_edges request"),
    }
}

/// Whether each gather request merges its faces, in order.
fn gathers_unified(kernel: &FakeKernel) -> Vec<bool> {
    let unified = |r: &Request| match r {
        Request::Gather { unify, .. } => Some(unify.is_some()),
        _ => None,
    };
    kernel.requests.iter().filter_map(unified).collect()
}

/// The number of strips of each extend_edges request, in order.
fn strips_per_extend(kernel: &FakeKernel) -> Vec<usize> {
    let strips = |r: &Request| match r {
        Request::ExtendEdges { strips, .. } => Some(strips.len()),
        _ => None,
    };
    kernel.requests.iter().filter_map(strips).collect()
}

fn report(patches: Vec<usize>, kind: &'static str, edges: usize, length: f64) -> JointReport {
    JointReport { patches, kind, status: "extended", edges, length }
}

#[test]
fn a_rib_standing_on_a_plate_grows_onto_it_as_a_t_and_the_plates_rim_stays_free() {
    // A plate 2 thick (mid-patch 0 at z = 1, out to its rim at x = 50) and a rib 2 thick standing on it (mid-patch
    // 1 at x = 0, its bottom edge on the plate's top at z = 2). The rib's edge meets the plate's patch 1 below, on
    // its face: a T, grown by the distance plus a quarter of the plate's thickness.
    let rib = (DVec3::new(0.0, 0.0, 2.0), DVec3::new(0.0, 10.0, 2.0));
    let rim = (DVec3::new(50.0, 0.0, 1.0), DVec3::new(50.0, 10.0, 1.0));
    let fused =
        fused(vec![face(0, DVec3::Z), face(1, DVec3::X)], vec![edge(rib.0, rib.1, &[1]), edge(rim.0, rim.1, &[0])]);
    let probes = json!({"edges": [
        probe(rib.0, rib.1, DVec3::X, -DVec3::Z, &[(0, 1.0, 0.0)]),
        probe(rim.0, rim.1, DVec3::Z, DVec3::X, &[]),
    ]});
    let mut replies = vec![probes];
    replies.extend(pass_replies(1, 0, 2));
    let patches = [info(2.0, (1, 0)), info(2.0, (1, 1))];
    let (stitched, kernel) =
        run(&fused, &patches, (DVec3::new(-50.0, 0.0, 0.0), DVec3::new(100.0, 10.0, 2.0)), replies);

    assert_eq!(kernel.ops(), ["probe_edges", "extend_edges", "gather", "gather", "fuse"]);
    let (strips, corners) = extend_request(&kernel);
    assert_eq!(strips.len(), 1, "the rim edge does not grow");
    assert_eq!((strips[0].edge, strips[0].face, strips[0].onto_face), (0, 1, true));
    assert!(strips[0].lengths.iter().all(|&l| (l - 1.5).abs() < 1e-12), "{:?}", strips[0].lengths);
    assert!(corners.is_empty());
    // Only the rib's patch has a strip to merge with its pieces.
    let unify = gathers_unified(&kernel);
    assert_eq!(unify, [false, true], "the rib's patch is merged with its strip");
    assert_eq!(stitched.joints, [report(vec![1, 2], "t", 1, 10.0)]);
    assert_eq!(stitched.free, FreeEdges::default(), "the fused result has no free edge left");
}

/// An L: a floor 2 thick (mid-patch 0 at z = 1, its edge at x = 2) and a wall 2 thick (mid-patch 1 at x = 1,
/// its edge at z = 2), fused, and the probes of their edges: each meets the other's support plane 1 away.
fn l_corner() -> (Fused, Value) {
    let floor = (DVec3::new(2.0, 0.0, 1.0), DVec3::new(2.0, 10.0, 1.0));
    let wall = (DVec3::new(1.0, 0.0, 2.0), DVec3::new(1.0, 10.0, 2.0));
    let fused = fused(
        vec![face(0, DVec3::Z), face(1, DVec3::X)],
        vec![edge(floor.0, floor.1, &[0]), edge(wall.0, wall.1, &[1])],
    );
    let probes = json!({"edges": [
        probe(floor.0, floor.1, DVec3::Z, -DVec3::X, &[(1, 1.0, 1.0)]),
        probe(wall.0, wall.1, DVec3::X, -DVec3::Z, &[(0, 1.0, 1.0)]),
    ]});
    (fused, probes)
}

#[test]
fn two_walls_meeting_at_a_corner_both_grow_past_each_other_as_an_l() {
    // An L: a floor 2 thick (mid-patch 0 at z = 1, its edge at x = 2) and a wall 2 thick (mid-patch 1 at x = 1,
    // its edge at z = 2). Each edge meets the other's support plane 1 away, a full unit past the other patch's
    // face: an L, both growing by 1 plus a quarter thickness of overshoot.
    let (fused, probes) = l_corner();
    let mut replies = vec![probes];
    replies.extend(pass_replies(2, 0, 2));
    let patches = [info(2.0, (1, 0)), info(2.0, (1, 1))];
    let (stitched, kernel) = run(&fused, &patches, (DVec3::ZERO, DVec3::new(50.0, 10.0, 2.0)), replies);

    let (strips, corners) = extend_request(&kernel);
    let grown: Vec<(usize, usize, bool)> = strips.iter().map(|s| (s.edge, s.face, s.onto_face)).collect();
    assert_eq!(grown, [(0, 0, false), (1, 1, false)], "both edges grow toward each other, neither onto a face");
    for s in &strips {
        assert!(s.lengths.iter().all(|&l| (l - 1.5).abs() < 1e-12), "{:?}", s.lengths);
    }
    assert!(corners.is_empty(), "strips of different faces leave no notch");
    assert_eq!(stitched.joints, [report(vec![1, 2], "l", 2, 20.0)]);
}

#[test]
fn two_levels_of_a_wall_at_a_thickness_step_are_bridged_by_a_ramp() {
    // One wall (solid 1, group 0) 2 thick for x < 20 (mid-patch 0 at z = 1) and 3 thick past it (mid-patch 1 at
    // z = 1.5). Their edges at x = 20 face each other 0.5 apart and find no partner: a step higher than a tenth of
    // the thinner wall, laid down into a ramp from the thin edge to half its thickness into the thick patch.
    let thin = (DVec3::new(20.0, 0.0, 1.0), DVec3::new(20.0, 10.0, 1.0));
    let thick = (DVec3::new(20.0, 0.0, 1.5), DVec3::new(20.0, 10.0, 1.5));
    let fused = fused(
        vec![face_at(0, DVec3::new(10.0, 5.0, 1.0), DVec3::Z), face_at(1, DVec3::new(30.0, 5.0, 1.5), DVec3::Z)],
        vec![edge(thin.0, thin.1, &[0]), edge(thick.0, thick.1, &[1])],
    );
    let probes = json!({"edges": [
        probe(thin.0, thin.1, DVec3::Z, DVec3::X, &[]),
        probe(thick.0, thick.1, DVec3::Z, -DVec3::X, &[]),
    ]});
    let mut replies = vec![probes];
    replies.extend(pass_replies(0, 1, 2));
    let patches = [info(2.0, (1, 0)), info(3.0, (1, 0))];
    let (stitched, kernel) = run(&fused, &patches, (DVec3::ZERO, DVec3::new(40.0, 10.0, 3.0)), replies);

    let (strips, corners) = extend_request(&kernel);
    assert!(strips.is_empty(), "bridged edges grow no strip");
    assert_eq!(corners.len(), 1);
    let expected = [
        DVec3::new(20.0, 0.0, 1.0),
        DVec3::new(21.0, 0.0, 1.5),
        DVec3::new(21.0, 10.0, 1.5),
        DVec3::new(20.0, 10.0, 1.0),
    ];
    for (got, want) in corners[0].points.iter().zip(expected) {
        assert!(got.distance(want) < 1e-9, "{:?}", corners[0].points);
    }
    assert_eq!(corners[0].normal, DVec3::Z, "a ramp faces its patch's way");
    // The ramp joins the thin level's patch: only its gather merges a strip.
    let unify = gathers_unified(&kernel);
    assert_eq!(unify, [true, false]);
    assert_eq!(stitched.joints, [report(vec![1, 2], "step", 2, 20.0)]);
}

#[test]
fn a_curved_edge_short_of_the_rim_grows_to_it_unless_its_patch_is_freeform() {
    // A plate 2 thick ending at x = 50 (the solid), its mid-patch at z = 1 stopping 0.7 short at x = 49.3 along an
    // edge bowed 0.3 inwards (a tube cut obliquely, seen from close). Growth to the rim: 0.7 at every sample,
    // for a patch on an analytic surface; none from a curved edge of a freeform patch.
    let (a, b) = (DVec3::new(49.3, 0.0, 1.0), DVec3::new(49.3, 10.0, 1.0));
    let bow = DVec3::new(49.0, 5.0, 1.0);
    let length = a.distance(bow) + bow.distance(b);
    let edges = vec![json!({"length": length, "faces": [0], "points": [v(a), v(bow), v(b)]})];
    let fused = fused(vec![face(0, DVec3::Z)], edges);
    let wire = probe(a, b, DVec3::Z, DVec3::X, &[]);
    let probe: EdgeProbe = serde_json::from_value::<crate::kernel::protocol::EdgeProbe>(wire).unwrap().into();
    let mesh = SolidMesh::new(&synthetic::cuboid(DVec3::ZERO, DVec3::new(50.0, 10.0, 2.0))).unwrap();
    let analytic = [info(2.0, (1, 0))];
    const CURVED: edges::RimGrowth = edges::RimGrowth { curved: true, lips: true };
    const STRAIGHT: edges::RimGrowth = edges::RimGrowth { curved: false, lips: true };
    let lengths = edges::to_rim(&fused, 0, 0, &probe, &analytic, std::slice::from_ref(&mesh), CURVED).unwrap();
    assert!(lengths.iter().all(|&d| (d - 0.7).abs() < 1e-6), "{lengths:?}");
    let freeform = [PatchInfo { freeform: true, ..info(2.0, (1, 0)) }];
    assert_eq!(edges::to_rim(&fused, 0, 0, &probe, &freeform, std::slice::from_ref(&mesh), CURVED), None);
    // The fallback of a pass the kernel failed: straight edges only.
    assert_eq!(edges::to_rim(&fused, 0, 0, &probe, &analytic, std::slice::from_ref(&mesh), STRAIGHT), None);
}

#[test]
fn a_pass_the_kernel_fails_with_a_curved_rim_strip_is_made_again_with_straight_edges_only() {
    // A plate 2 thick in x 0..50, its mid-patch at z = 1 stopping 0.7 short of both ends: at x = 49.3 along a
    // straight edge, at x = 0.7 along an edge bowed 0.3 inwards. Both grow to the rim; the fuse fails, so the
    // pass is made again growing the straight edge only: the tally counts it, and the curved one as unmade.
    let (a, b) = (DVec3::new(49.3, 0.0, 1.0), DVec3::new(49.3, 10.0, 1.0));
    let (c, d) = (DVec3::new(0.7, 10.0, 1.0), DVec3::new(0.7, 0.0, 1.0));
    let bow = DVec3::new(1.0, 5.0, 1.0);
    let curved_length = c.distance(bow) + bow.distance(d);
    let curved = json!({"length": curved_length, "faces": [0], "points": [v(c), v(bow), v(d)]});
    let fused = fused(vec![face(0, DVec3::Z)], vec![edge(a, b, &[0]), curved]);
    let probes = json!({"edges": [probe(a, b, DVec3::Z, DVec3::X, &[]), probe(c, d, DVec3::Z, -DVec3::X, &[])]});
    let made = |k: usize| vec![json!({"area": 7.0, "error": null}); k];
    let replies = vec![
        probes,
        json!({"handle": 20, "strips": made(2), "corners": []}),
        json!({"handle": 30, "faces": 1}),
        json!({"error": {"code": "kernel_failed", "message": "the fuse gave up"}}),
        json!({"handle": 21, "strips": made(1), "corners": []}),
        json!({"handle": 31, "faces": 1}),
        json!({"handle": 40, "faces": [face(0, DVec3::Z)], "edges": []}),
    ];
    let (stitched, kernel) = run(&fused, &[info(2.0, (1, 0))], (DVec3::ZERO, DVec3::new(50.0, 10.0, 2.0)), replies);

    assert_eq!(kernel.ops(), ["probe_edges", "extend_edges", "gather", "fuse", "extend_edges", "gather", "fuse"]);
    let grown: Vec<Vec<usize>> = kernel
        .requests
        .iter()
        .filter_map(|r| match r {
            Request::ExtendEdges { strips, .. } => Some(strips.iter().map(|s| s.edge).collect()),
            _ => None,
        })
        .collect();
    assert_eq!(grown, vec![vec![0, 1], vec![0]]);
    let unmade = JointReport { patches: vec![1], kind: "none", status: "no_partner", edges: 1, length: curved_length };
    assert_eq!(stitched.joints, vec![unmade, report(vec![1], "rim", 1, 10.0)]);
}

#[test]
fn a_joints_pass_the_kernel_fails_is_made_growing_nothing_and_the_later_passes_go_on() {
    // The plate of the test above with its straight edge only: the joints pass's fuse fails. Growing no curved
    // edge, it is not made again with straight edges only (that would fail the same way) but growing nothing: the
    // trimmed patches fused again. The rims pass then grows the edge to the rim, and the joints pass's failure is
    // said; the part is not written unstitched.
    let (a, b) = (DVec3::new(49.3, 0.0, 1.0), DVec3::new(49.3, 10.0, 1.0));
    let fused = fused(vec![face(0, DVec3::Z)], vec![edge(a, b, &[0])]);
    let edge_probe = json!({"edges": [probe(a, b, DVec3::Z, DVec3::X, &[])]});
    let made = json!([{"area": 7.0, "error": null}]);
    let replies = vec![
        edge_probe.clone(),
        json!({"handle": 20, "strips": made, "corners": []}),
        json!({"handle": 30, "faces": 1}),
        json!({"error": {"code": "kernel_failed", "message": "the fuse gave up"}}),
        json!({"handle": 31, "faces": 1}),
        json!({"handle": 40, "faces": [face(0, DVec3::Z)], "edges": [edge(a, b, &[0])]}),
        edge_probe,
        json!({"handle": 21, "strips": made, "corners": []}),
        json!({"handle": 32, "faces": 1}),
        json!({"handle": 41, "faces": [face(0, DVec3::Z)], "edges": []}),
    ];
    let (stitched, kernel) = run(&fused, &[info(2.0, (1, 0))], (DVec3::ZERO, DVec3::new(50.0, 10.0, 2.0)), replies);

    let ops = ["probe_edges", "extend_edges", "gather", "fuse", "gather", "fuse"];
    assert_eq!(kernel.ops(), [&ops[..], &["probe_edges", "extend_edges", "gather", "fuse"]].concat());
    assert!(matches!(kernel.requests[4], Request::Gather { unify: None, .. }), "nothing grown, nothing merged");
    assert_eq!(stitched.fused.handle, 41, "the rims pass's result stands");
    assert_eq!(
        stitched.failed_passes,
        ["the joints pass: the fuse gave up; it is made growing nothing, and the later passes make what joints they \
          can"]
    );
    assert_eq!(stitched.joints, [report(vec![1], "rim", 1, 10.0)], "the joints pass's strip is not counted");
    assert_eq!(stitched.free.open_edges, 0);
}

/// The replies for a plate whose straight edge a-b (probed as `edge_probe`) the joints pass grows but leaves
/// where it was, up to the rims pass's fuse: the probe, the strip, the patch's gather, the fuse
/// (handle 40, the edge still free), the probe of its free edges, then the rims pass's strip and gathers.
fn joints_then_rims_replies(a: DVec3, b: DVec3, edge_probe: &Value) -> Vec<Value> {
    vec![
        edge_probe.clone(),
        json!({"handle": 20, "strips": [{"area": 7.0, "error": null}], "corners": []}),
        json!({"handle": 30, "faces": 1}),
        json!({"handle": 40, "faces": [face(0, DVec3::Z)], "edges": [edge(a, b, &[0])]}),
        edge_probe.clone(),
        json!({"handle": 21, "strips": [{"area": 7.0, "error": null}], "corners": []}),
        json!({"handle": 31, "faces": 1}),
    ]
}

#[test]
fn a_later_pass_the_kernel_fails_leaves_the_earlier_stitching_and_says_so() {
    // The straight edge of the plate above, 0.7 short of the rim: the joints pass grows it, but its fused result
    // still has the edge where it was (as a kernel that merged the strip away would leave it). The rims pass
    // grows it again and its fuse fails: the joints pass's stitching stands, the failure is named, and the
    // partners pass finds no partner for the edge.
    let (a, b) = (DVec3::new(49.3, 0.0, 1.0), DVec3::new(49.3, 10.0, 1.0));
    let fused = fused(vec![face(0, DVec3::Z)], vec![edge(a, b, &[0])]);
    let edge_probe = json!({"edges": [probe(a, b, DVec3::Z, DVec3::X, &[])]});
    let mut replies = joints_then_rims_replies(a, b, &edge_probe);
    replies.extend([json!({"error": {"code": "kernel_failed", "message": "the fuse gave up"}}), edge_probe]);
    let (stitched, kernel) = run(&fused, &[info(2.0, (1, 0))], (DVec3::ZERO, DVec3::new(50.0, 10.0, 2.0)), replies);

    assert_eq!(
        kernel.ops(),
        [
            "probe_edges",
            "extend_edges",
            "gather",
            "fuse",
            "probe_edges",
            "extend_edges",
            "gather",
            "fuse",
            "probe_edges"
        ]
    );
    assert_eq!(stitched.fused.handle, 40, "the joints pass's result stands");
    assert_eq!(
        stitched.failed_passes,
        ["the rims pass: the fuse gave up; its joints are not made and the edges it grows stay as the earlier passes \
          left them"]
    );
    assert_eq!(stitched.joints, [report(vec![1], "rim", 1, 10.0)], "the rims pass's strip is not counted");
    assert_eq!(stitched.free.open_edges, 1);
}

#[test]
fn a_later_pass_that_leaves_more_open_than_it_found_is_undone() {
    // The plate above, 0.7 short of the rim: the joints pass leaves the edge where it was, the rims pass grows it
    // again and its result holds that edge and a new open one across the plate (x = 30): more open length than
    // before, so the joints pass's stitching stands and the rims pass's joint is not counted.
    let (a, b) = (DVec3::new(49.3, 0.0, 1.0), DVec3::new(49.3, 10.0, 1.0));
    let (c, d) = (DVec3::new(30.0, 0.0, 1.0), DVec3::new(30.0, 10.0, 1.0));
    let fused = fused(vec![face(0, DVec3::Z)], vec![edge(a, b, &[0])]);
    let edge_probe = json!({"edges": [probe(a, b, DVec3::Z, DVec3::X, &[])]});
    let both_probes = json!({"edges": [probe(a, b, DVec3::Z, DVec3::X, &[]), probe(c, d, DVec3::Z, DVec3::X, &[])]});
    let mut replies = joints_then_rims_replies(a, b, &edge_probe);
    replies.extend([
        json!({"handle": 41, "faces": [face(0, DVec3::Z)], "edges": [edge(a, b, &[0]), edge(c, d, &[0])]}),
        both_probes,
        edge_probe,
    ]);
    let (stitched, _) = run(&fused, &[info(2.0, (1, 0))], (DVec3::ZERO, DVec3::new(50.0, 10.0, 2.0)), replies);

    assert_eq!(stitched.fused.handle, 40, "the joints pass's result stands");
    assert!(stitched.failed_passes.is_empty());
    assert_eq!(stitched.joints, [report(vec![1], "rim", 1, 10.0)], "the rims pass's strip is not counted");
    assert_eq!((stitched.free.open_edges, stitched.free.open_length), (1, 10.0));
}

/// The plate above through the rims pass, whose result (handle 41) holds the same open edge as before, its face
/// `invalid` or not; what stands.
fn rims_result_with_face_invalid(invalid: bool) -> Stitched {
    let (a, b) = (DVec3::new(49.3, 0.0, 1.0), DVec3::new(49.3, 10.0, 1.0));
    let fused = fused(vec![face(0, DVec3::Z)], vec![edge(a, b, &[0])]);
    let edge_probe = json!({"edges": [probe(a, b, DVec3::Z, DVec3::X, &[])]});
    let broken: Vec<usize> = if invalid { vec![0] } else { vec![] };
    let mut replies = joints_then_rims_replies(a, b, &edge_probe);
    replies.extend([
        json!({"handle": 41, "faces": [face(0, DVec3::Z)], "edges": [edge(a, b, &[0])], "invalid": broken}),
        edge_probe.clone(),
        edge_probe,
    ]);
    run(&fused, &[info(2.0, (1, 0))], (DVec3::ZERO, DVec3::new(50.0, 10.0, 2.0)), replies).0
}

#[test]
fn a_later_pass_that_breaks_a_face_counts_its_edges_as_open_and_is_undone() {
    // The write leaves a face that fails the kernel's check out, which opens its edges: a pass that makes one
    // opens them, though the free edges it leaves are no longer than before. Without the broken face it stands.
    assert_eq!(rims_result_with_face_invalid(true).fused.handle, 40, "the joints pass's result stands");
    assert_eq!(rims_result_with_face_invalid(false).fused.handle, 41, "the rims pass's result stands");
}

#[test]
fn a_later_pass_that_sets_one_patch_back_is_made_again_without_that_patchs_edges() {
    // Two plates' patches in one slab (0..50 x 0..20, 2 thick), each with an edge 0.7 short of the rim that the
    // joints pass leaves where it was. The rims pass grows both: patch 1's edge closes, but patch 2's strip
    // leaves a new open edge 15 long across it (x = 30): 25 open against 20 before, so the pass is undone, and
    // made again growing patch 1's edge only, which stands (10 open).
    let (a0, b0) = (DVec3::new(49.3, 0.0, 1.0), DVec3::new(49.3, 10.0, 1.0));
    let (a1, b1) = (DVec3::new(0.7, 0.0, 1.0), DVec3::new(0.7, 10.0, 1.0));
    let (c, d) = (DVec3::new(30.0, 0.0, 1.0), DVec3::new(30.0, 15.0, 1.0));
    let faces = || vec![face(0, DVec3::Z), face(1, DVec3::Z)];
    let both = || vec![edge(a0, b0, &[0]), edge(a1, b1, &[1])];
    let fused = fused(faces(), both());
    let (p0, p1) = (probe(a0, b0, DVec3::Z, DVec3::X, &[]), probe(a1, b1, DVec3::Z, -DVec3::X, &[]));
    let pcd = probe(c, d, DVec3::Z, DVec3::X, &[]);
    let strips = |k: usize| json!(vec![json!({"area": 7.0, "error": null}); k]);
    let replies = vec![
        json!({"edges": [p0, p1]}),
        json!({"handle": 20, "strips": strips(2), "corners": []}),
        json!({"handle": 30, "faces": 1}),
        json!({"handle": 31, "faces": 1}),
        json!({"handle": 40, "faces": faces(), "edges": both()}),
        json!({"edges": [p0, p1]}),
        // The rims pass, growing both edges.
        json!({"handle": 21, "strips": strips(2), "corners": []}),
        json!({"handle": 32, "faces": 1}),
        json!({"handle": 33, "faces": 1}),
        json!({"handle": 41, "faces": faces(), "edges": [edge(a1, b1, &[1]), edge(c, d, &[1])]}),
        json!({"edges": [p1, pcd]}),
        // Made again without patch 2's edge.
        json!({"handle": 22, "strips": strips(1), "corners": []}),
        json!({"handle": 34, "faces": 1}),
        json!({"handle": 35, "faces": 1}),
        json!({"handle": 42, "faces": faces(), "edges": [edge(a1, b1, &[1])]}),
        json!({"edges": [p1]}),
        // The partners pass finds no partner.
        json!({"edges": [p1]}),
    ];
    let patches = [info(2.0, (1, 0)), info(2.0, (2, 0))];
    let (stitched, kernel) = run(&fused, &patches, (DVec3::ZERO, DVec3::new(50.0, 20.0, 2.0)), replies);

    let extends = strips_per_extend(&kernel);
    assert_eq!(extends, [2, 2, 1], "joints, rims, rims again with patch 1's edge only");
    assert_eq!(stitched.fused.handle, 42, "the rims pass made again stands");
    assert!(stitched.failed_passes.is_empty());
    assert_eq!((stitched.free.open_edges, stitched.free.open_length), (1, 10.0));
    assert_eq!(stitched.open_patches, BTreeSet::from([1]));
}

#[test]
fn a_later_pass_is_made_again_while_each_try_sets_another_patch_back() {
    // Three plates' patches in one slab (0..50 x 0..30, 2 thick), each with an edge 0.7 short of the rim, 10 long
    // (30 open). The rims pass's first try opens 15 more on patch 2 (35), its second, without patch 2's edge, 25
    // more on patch 3 (45); the third, with patch 1's edge only, closes it (20 open) and stands.
    let (a0, b0) = (DVec3::new(49.3, 0.0, 1.0), DVec3::new(49.3, 10.0, 1.0));
    let (a1, b1) = (DVec3::new(0.7, 0.0, 1.0), DVec3::new(0.7, 10.0, 1.0));
    let (a2, b2) = (DVec3::new(49.3, 20.0, 1.0), DVec3::new(49.3, 30.0, 1.0));
    let (c, d) = (DVec3::new(30.0, 0.0, 1.0), DVec3::new(30.0, 15.0, 1.0));
    let (g, h) = (DVec3::new(20.0, 5.0, 1.0), DVec3::new(20.0, 30.0, 1.0));
    let faces = || vec![face(0, DVec3::Z), face(1, DVec3::Z), face(2, DVec3::Z)];
    let (e0, e1, e2) = (edge(a0, b0, &[0]), edge(a1, b1, &[1]), edge(a2, b2, &[2]));
    let (p0, p1, p2) = (
        probe(a0, b0, DVec3::Z, DVec3::X, &[]),
        probe(a1, b1, DVec3::Z, -DVec3::X, &[]),
        probe(a2, b2, DVec3::Z, DVec3::X, &[]),
    );
    let (pcd, pgh) = (probe(c, d, DVec3::Z, DVec3::X, &[]), probe(g, h, DVec3::Z, DVec3::X, &[]));
    // One pass: the strips made, a gather per patch, the fuse leaving `edges` free, and their probes.
    let pass = |k: usize, strips: usize, edges: Vec<Value>, probes: Vec<Value>| {
        vec![
            json!({"handle": 20 + k, "strips": vec![json!({"area": 7.0, "error": null}); strips], "corners": []}),
            json!({"handle": 30 + 3 * k, "faces": 1}),
            json!({"handle": 31 + 3 * k, "faces": 1}),
            json!({"handle": 32 + 3 * k, "faces": 1}),
            json!({"handle": 40 + k, "faces": faces(), "edges": edges}),
            json!({"edges": probes}),
        ]
    };
    let all = || vec![e0.clone(), e1.clone(), e2.clone()];
    let mut replies = vec![json!({"edges": [p0, p1, p2]})];
    replies.extend(pass(0, 3, all(), vec![p0.clone(), p1.clone(), p2.clone()]));
    replies.extend(pass(1, 3, vec![e1.clone(), edge(c, d, &[1]), e2.clone()], vec![p1.clone(), pcd, p2.clone()]));
    replies.extend(pass(2, 2, vec![e1.clone(), e2.clone(), edge(g, h, &[2])], vec![p1.clone(), p2.clone(), pgh]));
    replies.extend(pass(3, 1, vec![e1.clone(), e2.clone()], vec![p1.clone(), p2.clone()]));
    replies.push(json!({"edges": [p1, p2]}));
    let patches = [info(2.0, (1, 0)), info(2.0, (2, 0)), info(2.0, (3, 0))];
    let (stitched, kernel) = run(&fused(faces(), all()), &patches, (DVec3::ZERO, DVec3::new(50.0, 30.0, 2.0)), replies);

    let extends = strips_per_extend(&kernel);
    assert_eq!(extends, [3, 3, 2, 1], "joints, then the rims pass three times");
    assert_eq!(stitched.fused.handle, 43, "the third try stands");
    assert_eq!((stitched.free.open_edges, stitched.free.open_length), (2, 20.0));
}
