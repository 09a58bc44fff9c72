use super::*;

#[test]
fn requests_encode_as_exact_json() {
    let cases = [
        (Request::Hello { protocol: 1 }, r#"{"id":0,"op":"hello","args":{"protocol":1}}"#),
        (Request::Ping {}, r#"{"id":0,"op":"ping","args":{}}"#),
        (
            Request::LoadStep { path: "/tmp/a b/ü.step".into() },
            r#"{"id":0,"op":"load_step","args":{"path":"/tmp/a b/ü.step"}}"#,
        ),
        (
            Request::Describe { handle: 3, mesh: true, mesh_tolerance: 0.1 },
            r#"{"id":0,"op":"describe","args":{"handle":3,"mesh":true,"mesh_tolerance":0.1}}"#,
        ),
        (
            Request::Mesh { handle: 3, mesh_tolerance: 0.1 },
            r#"{"id":0,"op":"mesh","args":{"handle":3,"mesh_tolerance":0.1}}"#,
        ),
        (
            Request::WriteStep {
                path: "o.step".into(),
                handle: 7,
                faces: vec![FaceAttributes {
                    face: 0,
                    name: "patch 1 t=2.000".into(),
                    color: [1.0, 0.5, 0.0],
                    thickness: 2.0,
                }],
                preview: None,
                solids: vec![],
                check: false,
            },
            r#"{"id":0,"op":"write_step","args":{"path":"o.step","handle":7,"faces":[{"face":0,"name":"patch 1 t=2.000","color":[1.0,0.5,0.0],"thickness":2.0}]}}"#,
        ),
        (
            Request::WriteStep {
                path: "o.step".into(),
                handle: 7,
                faces: vec![],
                preview: Some("o.glb".into()),
                solids: vec![],
                check: true,
            },
            r#"{"id":0,"op":"write_step","args":{"path":"o.step","handle":7,"faces":[],"preview":"o.glb","check":true}}"#,
        ),
        (
            Request::WriteStep {
                path: "o.step".into(),
                handle: 7,
                faces: vec![],
                preview: None,
                solids: vec![KeptSolid { handle: 3, name: "solid 2 not_thin_walled".into() }],
                check: false,
            },
            r#"{"id":0,"op":"write_step","args":{"path":"o.step","handle":7,"faces":[],"solids":[{"handle":3,"name":"solid 2 not_thin_walled"}]}}"#,
        ),
        (
            Request::MakePatch {
                handle: 2,
                faces: vec![4, 5],
                placement: Placement::Offset(-1.0),
                clip: None,
                reverse: false,
                mid_wall: false,
                fill: vec![],
            },
            r#"{"id":0,"op":"make_patch","args":{"handle":2,"faces":[4,5],"offset":-1.0}}"#,
        ),
        (
            Request::MakePatch {
                handle: 2,
                faces: vec![7],
                placement: Placement::Plane { origin: [50.0, 0.0, 0.0], normal: [1.0, 0.0, 0.0] },
                clip: Some(Clip {
                    partners: vec![vec![8, 9]],
                    fuzzy: 0.001,
                    narrow: 3.0,
                    narrow_end: 2.0,
                    exclude: vec![vec![]],
                    thickness: 2.0,
                    to_mid: -1.0,
                    wall_max: 3.0,
                }),
                reverse: true,
                mid_wall: false,
                fill: vec![12, 13],
            },
            r#"{"id":0,"op":"make_patch","args":{"handle":2,"faces":[7],"plane":{"origin":[50.0,0.0,0.0],"normal":[1.0,0.0,0.0]},"clip":{"partners":[[8,9]],"fuzzy":0.001,"narrow":3.0,"narrow_end":2.0,"thickness":2.0,"to_mid":-1.0,"wall_max":3.0},"reverse":true,"fill":[12,13]}}"#,
        ),
        (
            Request::Fuse {
                patches: vec![3, 4],
                fuzzy: 0.001,
                split_internal: false,
                patches_fused: false,
                bodies: vec![],
                settled: vec![],
            },
            r#"{"id":0,"op":"fuse","args":{"patches":[3,4],"fuzzy":0.001}}"#,
        ),
        (
            Request::Fuse {
                patches: vec![3, 4, 5],
                fuzzy: 0.001,
                split_internal: true,
                patches_fused: true,
                bodies: vec![0, 2, 0],
                settled: vec![0, 2],
            },
            r#"{"id":0,"op":"fuse","args":{"patches":[3,4,5],"fuzzy":0.001,"split_internal":true,"patches_fused":true,"bodies":[0,2,0],"settled":[0,2]}}"#,
        ),
        (
            Request::MakeShells { handle: 9, shells: vec![vec![0, 1], vec![2]], merge: vec![vec![0, 1]], fuzzy: 0.5 },
            r#"{"id":0,"op":"make_shells","args":{"handle":9,"shells":[[0,1],[2]],"merge":[[0,1]],"fuzzy":0.5}}"#,
        ),
        (
            Request::ProbeEdges {
                handle: 9,
                edges: vec![EdgeRef { edge: 4, face: 1 }],
                targets: vec![0, 3],
                samples: 5,
                reach: 3.0,
            },
            r#"{"id":0,"op":"probe_edges","args":{"handle":9,"edges":[{"edge":4,"face":1}],"targets":[0,3],"samples":5,"reach":3.0}}"#,
        ),
        (
            Request::ExtendEdges {
                handle: 9,
                strips: vec![StripRequest { edge: 4, face: 1, lengths: vec![1.0, 1.5], onto_face: true, along: None }],
                corners: vec![
                    CornerRequest {
                        points: [glam::DVec3::ZERO, glam::DVec3::X, glam::DVec3::ONE, glam::DVec3::Y],
                        normal: glam::DVec3::Z,
                        axis: None,
                    },
                    CornerRequest {
                        points: [glam::DVec3::X, glam::DVec3::X, glam::DVec3::Y, glam::DVec3::Y],
                        normal: glam::DVec3::X,
                        axis: Some([glam::DVec3::ZERO, glam::DVec3::Z]),
                    },
                ],
            },
            r#"{"id":0,"op":"extend_edges","args":{"handle":9,"strips":[{"edge":4,"face":1,"lengths":[1.0,1.5],"onto_face":true}],"corners":[{"points":[[0.0,0.0,0.0],[1.0,0.0,0.0],[1.0,1.0,1.0],[0.0,1.0,0.0]],"normal":[0.0,0.0,1.0]},{"points":[[1.0,0.0,0.0],[1.0,0.0,0.0],[0.0,1.0,0.0],[0.0,1.0,0.0]],"normal":[1.0,0.0,0.0],"axis":[[0.0,0.0,0.0],[0.0,0.0,1.0]]}]}}"#,
        ),
        (
            Request::Gather { parts: vec![GatherPart { handle: 9, faces: vec![0, 2] }], unify: Some(0.001) },
            r#"{"id":0,"op":"gather","args":{"parts":[{"handle":9,"faces":[0,2]}],"unify":0.001}}"#,
        ),
        (Request::Free { handles: vec![1, 2] }, r#"{"id":0,"op":"free","args":{"handles":[1,2]}}"#),
        (Request::Shutdown {}, r#"{"id":0,"op":"shutdown","args":{}}"#),
    ];
    for (request, json) in cases {
        assert_eq!(encode(0, &request), json, "{}", request.op());
    }
}

#[test]
fn decode_ok_err_and_garbage() {
    assert_eq!(decode(4, "ping", r#"{"id":4,"ok":{"pong":true}}"#).unwrap(), serde_json::json!({"pong":true}));
    let err =
        decode(4, "load_step", r#"{"id":4,"err":{"code":"no_solid","message":"2 faces, no solid"}}"#).unwrap_err();
    assert_eq!(
        err,
        SidecarError::Op { op: "load_step".into(), code: "no_solid".into(), message: "2 faces, no solid".into() }
    );
    assert!(matches!(decode(4, "ping", "hello world"), Err(SidecarError::BadReply { .. })));
    assert!(matches!(decode(4, "ping", r#"{"id":5,"ok":{}}"#), Err(SidecarError::BadReply { .. })));
    assert!(matches!(decode(4, "ping", r#"{"id":4}"#), Err(SidecarError::BadReply { .. })));
}
