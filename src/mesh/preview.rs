//! A binary glTF 2.0 (`.glb`) preview of a shell mesh for any glTF viewer: one mesh of two primitives, the
//! elements (each flat-coloured: its own copy of its nodes, with its colour and normal) and their outlines
//! (dark lines). Written by hand: the container is a 12-byte header, a JSON chunk and a binary chunk.

use glam::DVec3;
use serde_json::json;

use super::shell::{element_normal, ShellMesh};

/// What the preview's colours show.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Coloring {
    /// Each element in its thickness band's colour, as in the run's STEP (the report's `thickness_legend`).
    Thickness,
    /// Elements failing any quality criterion red, the others grey.
    Quality,
}

/// Colour of an element failing a criterion in the quality preview.
pub const FAILING: [f64; 3] = [0.85, 0.15, 0.15];
/// Colour of an element passing every criterion.
pub const PASSING: [f64; 3] = [0.6, 0.6, 0.6];
const OUTLINE: [f32; 4] = [0.05, 0.05, 0.05, 1.0];

const GLB_MAGIC: u32 = 0x4654_6C67; // "glTF"
const CHUNK_JSON: u32 = 0x4E4F_534A;
const CHUNK_BIN: u32 = 0x004E_4942;
const FLOAT: u32 = 5126;
const UNSIGNED_INT: u32 = 5125;
const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
const TRIANGLES: u32 = 4;
const LINES: u32 = 1;

/// The `.glb` bytes of `mesh`, element `i` coloured `colors[i]` (sRGB, 0..1, as the STEP and the report give
/// colours; glTF stores them linear). The model is in metres (the mesh's millimetres scaled by 0.001) and
/// turned so that the mesh's +Z is glTF's up (+Y).
pub fn glb(mesh: &ShellMesh, colors: &[[f64; 3]]) -> Vec<u8> {
    assert_eq!(colors.len(), mesh.elements.len(), "one colour per element");
    let mut positions: Vec<[f32; 3]> = Vec::new();
    let mut normals: Vec<[f32; 3]> = Vec::new();
    let mut vertex_colors: Vec<[f32; 3]> = Vec::new();
    let mut triangles: Vec<u32> = Vec::new();
    let mut lines: Vec<u32> = Vec::new();
    for (e, color) in mesh.elements.iter().zip(colors) {
        let first = positions.len() as u32;
        let normal = element_normal(&mesh.nodes, &e.nodes).normalize_or(DVec3::Z).as_vec3().to_array();
        for &n in &e.nodes {
            positions.push(mesh.nodes[n].as_vec3().to_array());
            normals.push(normal);
            vertex_colors.push(color.map(|c| linear(c) as f32));
        }
        let k = e.nodes.len() as u32;
        // A fan from the first node: a quad's two triangles share its 0-2 diagonal.
        for j in 1..k - 1 {
            triangles.extend([first, first + j, first + j + 1]);
        }
        for j in 0..k {
            lines.extend([first + j, first + (j + 1) % k]);
        }
    }
    let (lo, hi) = positions.iter().fold(([f32::MAX; 3], [f32::MIN; 3]), |(mut lo, mut hi), p| {
        for a in 0..3 {
            lo[a] = lo[a].min(p[a]);
            hi[a] = hi[a].max(p[a]);
        }
        (lo, hi)
    });

    let mut bin: Vec<u8> = Vec::new();
    let mut views = Vec::new();
    let mut push_view = |bytes: Vec<u8>, target: u32| {
        views.push(json!({"buffer": 0, "byteOffset": bin.len(), "byteLength": bytes.len(), "target": target}));
        bin.extend(bytes);
        views.len() - 1
    };
    let floats = |v: &[[f32; 3]]| v.iter().flatten().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
    let ints = |v: &[u32]| v.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
    let position_view = push_view(floats(&positions), ARRAY_BUFFER);
    let normal_view = push_view(floats(&normals), ARRAY_BUFFER);
    let color_view = push_view(floats(&vertex_colors), ARRAY_BUFFER);
    let triangle_view = push_view(ints(&triangles), ELEMENT_ARRAY_BUFFER);
    let line_view = push_view(ints(&lines), ELEMENT_ARRAY_BUFFER);
    let vertices = positions.len();
    let half = std::f32::consts::FRAC_1_SQRT_2;
    let document = json!({
        "asset": {"version": "2.0", "generator": "midsurf mesh"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        // -90° about X takes +Z up to +Y; mm to m.
        "nodes": [{"mesh": 0, "rotation": [-half, 0.0, 0.0, half], "scale": [0.001, 0.001, 0.001]}],
        "meshes": [{"name": "shells", "primitives": [
            {"attributes": {"POSITION": 0, "NORMAL": 1, "COLOR_0": 2}, "indices": 3, "material": 0, "mode": TRIANGLES},
            {"attributes": {"POSITION": 0}, "indices": 4, "material": 1, "mode": LINES}
        ]}],
        "materials": [
            {"name": "elements", "doubleSided": true,
             "pbrMetallicRoughness":
                {"baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.8}},
            {"name": "outlines",
             "pbrMetallicRoughness": {"baseColorFactor": OUTLINE, "metallicFactor": 0.0, "roughnessFactor": 1.0}}
        ],
        "accessors": [
            {"bufferView": position_view, "componentType": FLOAT, "count": vertices, "type": "VEC3",
             "min": lo, "max": hi},
            {"bufferView": normal_view, "componentType": FLOAT, "count": vertices, "type": "VEC3"},
            {"bufferView": color_view, "componentType": FLOAT, "count": vertices, "type": "VEC3"},
            {"bufferView": triangle_view, "componentType": UNSIGNED_INT, "count": triangles.len(), "type": "SCALAR"},
            {"bufferView": line_view, "componentType": UNSIGNED_INT, "count": lines.len(), "type": "SCALAR"}
        ],
        "bufferViews": views,
        "buffers": [{"byteLength": bin.len()}]
    });
    container(&serde_json::to_vec(&document).expect("glTF documents always serialise"), bin)
}

/// An sRGB channel (0..1) as glTF's linear value (the sRGB transfer function, IEC 61966-2-1).
pub fn linear(c: f64) -> f64 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// The GLB container: header, JSON chunk padded with spaces, binary chunk padded with zeros (to 4 bytes).
fn container(json: &[u8], mut bin: Vec<u8>) -> Vec<u8> {
    let mut json = json.to_vec();
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    for word in [GLB_MAGIC, 2, total as u32, json.len() as u32, CHUNK_JSON] {
        out.extend(word.to_le_bytes());
    }
    out.extend(json);
    for word in [bin.len() as u32, CHUNK_BIN] {
        out.extend(word.to_le_bytes());
    }
    out.extend(bin);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shell::Element;

    #[test]
    fn a_quad_and_a_triangle_make_seven_vertices_three_triangles_and_a_well_formed_container() {
        let nodes = vec![DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y, DVec3::new(2.0, 0.0, 0.0)];
        let element = |nodes: Vec<usize>| Element { nodes, patch: 1, face: 0 };
        let mesh =
            ShellMesh { nodes, dims: vec![2; 5], elements: vec![element(vec![0, 1, 2, 3]), element(vec![1, 4, 2])] };
        let bytes = glb(&mesh, &[FAILING, PASSING]);
        assert_eq!(&bytes[0..4], b"glTF");
        assert_eq!(u32::from_le_bytes(bytes[8..12].try_into().unwrap()) as usize, bytes.len());
        let json_len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
        let doc: serde_json::Value = serde_json::from_slice(&bytes[20..20 + json_len]).unwrap();
        assert_eq!(doc["accessors"][0]["count"], 7);
        assert_eq!(doc["accessors"][3]["count"], 9, "2 + 1 triangles");
        assert_eq!(doc["accessors"][4]["count"], 14, "4 + 3 outline segments");
        assert_eq!(bytes.len() % 4, 0);
    }
}
