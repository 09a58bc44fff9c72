//! `midsurf mesh --preview P.glb`: the binary glTF read back by hand (header, chunks, accessors, the colours
//! in the binary chunk) against the quality report and the run's thickness legend.

mod common;

use std::path::Path;

use common::{midsurf, outcome, read_json, scratch};

/// The JSON chunk and the binary chunk of a .glb, after checking its header.
fn read_glb(path: &Path) -> (serde_json::Value, Vec<u8>) {
    let bytes = std::fs::read(path).unwrap();
    let word = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap()) as usize;
    assert_eq!(&bytes[0..4], b"glTF");
    assert_eq!((word(4), word(8)), (2, bytes.len()), "version 2, the file's length");
    let json_len = word(12);
    assert_eq!(&bytes[16..20], b"JSON");
    let json = serde_json::from_slice(&bytes[20..20 + json_len]).unwrap();
    let bin_at = 20 + json_len;
    assert_eq!(&bytes[bin_at + 4..bin_at + 8], b"BIN\0");
    let bin = bytes[bin_at + 8..bin_at + 8 + word(bin_at)].to_vec();
    (json, bin)
}

/// The per-vertex colours (COLOR_0, float RGB) of the mesh's first primitive.
fn vertex_colours(json: &serde_json::Value, bin: &[u8]) -> Vec<[f32; 3]> {
    let accessor =
        &json["accessors"][json["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"].as_u64().unwrap() as usize];
    assert_eq!((accessor["componentType"].as_u64(), accessor["type"].as_str()), (Some(5126), Some("VEC3")));
    let view = &json["bufferViews"][accessor["bufferView"].as_u64().unwrap() as usize];
    let start = view["byteOffset"].as_u64().unwrap() as usize;
    let floats: Vec<f32> = bin[start..start + view["byteLength"].as_u64().unwrap() as usize]
        .chunks(4)
        .map(|c| f32::from_le_bytes(c.try_into().unwrap()))
        .collect();
    assert_eq!(floats.len(), 3 * accessor["count"].as_u64().unwrap() as usize);
    floats.chunks(3).map(|c| [c[0], c[1], c[2]]).collect()
}

fn srgb_to_linear(c: f64) -> f32 {
    (if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }) as f32
}

fn run_fixture(dir: &Path, name: &str) -> (String, String) {
    let (mid, rep) = (dir.join("mid.step"), dir.join("mid.json"));
    let fixture = format!("fixtures/{name}.step");
    let o = outcome(midsurf().args([
        "run",
        &fixture,
        "-o",
        mid.to_str().unwrap(),
        "--report",
        rep.to_str().unwrap(),
        "--no-timings",
    ]));
    assert_eq!(o.code, 0, "{}", o.stderr);
    (mid.to_str().unwrap().to_owned(), rep.to_str().unwrap().to_owned())
}

#[test]
fn the_thickness_preview_has_a_vertex_per_element_corner_in_its_bands_colours() {
    let dir = scratch("mesh-preview-thickness");
    // plate_step: one plate of two thicknesses, so two bands.
    let (mid, rep) = run_fixture(&dir, "plate_step");
    let glb = dir.join("p.glb");
    let o = outcome(midsurf().args([
        "mesh",
        &mid,
        "--report",
        &rep,
        "-o",
        dir.join("m").to_str().unwrap(),
        "--size",
        "5",
        "--preview",
        glb.to_str().unwrap(),
    ]));
    assert_eq!(o.code, 0, "{}", o.stderr);
    let q = read_json(&dir.join("m.quality.json"));
    let (json, bin) = read_glb(&glb);
    let vertices = 4 * q["total"]["quads"].as_u64().unwrap() + 3 * q["total"]["trias"].as_u64().unwrap();
    assert_eq!(json["accessors"][0]["count"].as_u64(), Some(vertices));
    let legend: Vec<[f32; 3]> = read_json(Path::new(&rep))["thickness_legend"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| {
            let c: Vec<f64> = serde_json::from_value(e["color"].clone()).unwrap();
            [srgb_to_linear(c[0]), srgb_to_linear(c[1]), srgb_to_linear(c[2])]
        })
        .collect();
    assert_eq!(legend.len(), 2);
    let colours = vertex_colours(&json, &bin);
    for band in &legend {
        assert!(colours.contains(band), "band colour {band:?} in the preview");
    }
    assert!(colours.iter().all(|c| legend.contains(c)), "every vertex in a band's colour");
}

#[test]
fn the_quality_preview_paints_the_failing_elements_red() {
    let dir = scratch("mesh-preview-quality");
    let (mid, rep) = run_fixture(&dir, "t_rib");
    let criteria = dir.join("c.json");
    std::fs::write(&criteria, r#"{"max_aspect": 1.3}"#).unwrap();
    let glb = dir.join("q.glb");
    // Quads only, no clean-up: every element has 4 vertices.
    let o = outcome(midsurf().args([
        "mesh",
        &mid,
        "--report",
        &rep,
        "-o",
        dir.join("m").to_str().unwrap(),
        "--size",
        "5",
        "--all-quads",
        "--clean-tol",
        "0",
        "--criteria",
        criteria.to_str().unwrap(),
        "--preview",
        glb.to_str().unwrap(),
        "--color",
        "quality",
    ]));
    assert_eq!(o.code, 1, "{}", o.stderr);
    let q = read_json(&dir.join("m.quality.json"));
    assert_eq!(q["total"]["trias"], 0);
    let failing = q["criteria"].as_array().unwrap().iter().find(|c| c["criterion"] == "max_aspect").unwrap()
        ["failing_elements"]
        .as_u64()
        .unwrap() as usize;
    let elements = q["total"]["elements"].as_u64().unwrap() as usize;
    assert!(0 < failing && failing < elements, "{failing} of {elements} fail: both colours show");
    let (json, bin) = read_glb(&glb);
    let colours = vertex_colours(&json, &bin);
    assert_eq!(colours.len(), 4 * elements);
    let red = [srgb_to_linear(0.85), srgb_to_linear(0.15), srgb_to_linear(0.15)];
    let grey = [srgb_to_linear(0.6); 3];
    assert_eq!(colours.iter().filter(|c| **c == red).count(), 4 * failing);
    assert_eq!(colours.iter().filter(|c| **c == grey).count(), 4 * (elements - failing));
}
