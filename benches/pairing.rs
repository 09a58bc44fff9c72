//! Pairing time on synthetic face graphs of ~10,000 and ~100,000 faces (a field of 10 x 10 x 2 plates, six
//! faces each): growth should stay close to n log n. Then a perforated sheet, whose hole walls (a cylinder
//! against a plane is measured by rays) each sample two skins meshed finer as the holes grow in number: growth
//! should stay close to linear in the holes. Run with `cargo bench --bench pairing`.

use std::time::Instant;

use glam::DVec3;
use midsurf::model::face_graph::{FaceGraph, Surface};
use midsurf::model::tolerance::Tolerances;
use midsurf::pairing;
use midsurf::synthetic;

fn plate_field(k: usize) -> FaceGraph {
    let mut faces = Vec::with_capacity(6 * k * k);
    for j in 0..k {
        for i in 0..k {
            let plate =
                synthetic::cuboid(DVec3::new(12.0 * i as f64, 12.0 * j as f64, 0.0), DVec3::new(10.0, 10.0, 2.0));
            faces.extend(plate.faces);
        }
    }
    synthetic::graph(faces, &[])
}

/// A 1.5 mm sheet with `k x k` holes of 3 mm on a 6 mm pitch: two skins meshed with 4 x 4 quads per hole
/// cell, and a cylindrical wall per hole (the skins' inner loops are not modelled: pairing does not read them).
fn perforated(k: usize) -> FaceGraph {
    let (pitch, t) = (6.0, 1.5);
    let side = pitch * (k + 1) as f64;
    let n = 4 * (k + 1);
    let skin = |z: f64, normal: DVec3| {
        let origin = DVec3::new(0.0, 0.0, z);
        synthetic::face(Surface::Plane { origin, normal }, n, |u, v| {
            (origin + DVec3::new(u * side, v * side, 0.0), normal)
        })
    };
    let mut faces = vec![skin(0.0, -DVec3::Z), skin(t, DVec3::Z)];
    for j in 1..=k {
        for i in 1..=k {
            let centre = DVec3::new(pitch * i as f64, pitch * j as f64, 0.0);
            faces.push(synthetic::cylinder(centre, 1.5, (0.0, std::f64::consts::TAU), t, false));
        }
    }
    synthetic::graph(faces, &[])
}

fn perforated_rows() {
    let mut rows = Vec::new();
    for k in [20, 40] {
        let graph = perforated(k);
        let tol = Tolerances::new(graph.bbox.diagonal(), 2.25, 3.0_f64.to_radians());
        let pairable = vec![true; graph.faces.len()];
        let start = Instant::now();
        let pairing = pairing::detect(&graph, &tol, &pairable);
        assert_eq!(pairing.pairs.len(), 1, "the two skins are the only pair");
        let time = start.elapsed().as_secs_f64();
        println!("perforated {:>5} holes: {time:>8.3} s", k * k);
        rows.push((k * k, time));
    }
    let ((h0, t0), (h1, t1)) = (rows[0], rows[1]);
    let ratio = h1 as f64 / h0 as f64;
    println!(
        "growth x{:.1} for x{ratio:.1} holes (linear x{ratio:.1}; every wall against every skin triangle x{:.0})",
        t1 / t0,
        ratio * ratio
    );
}

fn main() {
    perforated_rows();
    let mut rows = Vec::new();
    for k in [41, 129] {
        let graph = plate_field(k);
        let n = graph.faces.len();
        let tol = Tolerances::new(graph.bbox.diagonal(), 3.0, 3.0_f64.to_radians());
        let pairable = vec![true; n];
        let best = (0..3)
            .map(|_| {
                let start = Instant::now();
                let pairing = pairing::detect(&graph, &tol, &pairable);
                assert_eq!(pairing.pairs.len(), k * k, "one pair per plate");
                start.elapsed().as_secs_f64()
            })
            .fold(f64::INFINITY, f64::min);
        let nlogn = n as f64 * (n as f64).log2();
        println!("pairing {n:>7} faces: {:>8.3} s  ({:.3} us per n log2 n)", best, best / nlogn * 1e6);
        rows.push((n, best));
    }
    let (n0, t0) = rows[0];
    let (n1, t1) = rows[1];
    let expected = (n1 as f64 * (n1 as f64).ln()) / (n0 as f64 * (n0 as f64).ln());
    println!(
        "growth x{:.1} for x{:.1} faces (n log n predicts x{expected:.1}, n^2 x{:.0})",
        t1 / t0,
        n1 as f64 / n0 as f64,
        (n1 as f64 / n0 as f64).powi(2)
    );
}
