//! Pairing time on synthetic face graphs of ~10,000 and ~100,000 faces (a field of 10 x 10 x 2 plates, six
//! faces each): growth should stay close to n log n. Run with `cargo bench --bench pairing`.

use std::time::Instant;

use glam::DVec3;
use midsurf::model::face_graph::FaceGraph;
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

fn main() {
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
