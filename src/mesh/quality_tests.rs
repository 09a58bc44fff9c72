use super::*;

#[test]
fn a_unit_square_is_perfect_and_steel_has_its_wave_speed() {
    let nodes = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
    let q = element_quality(&nodes, &[0, 1, 2, 3]);
    assert!((q.aspect - 1.0).abs() < 1e-12 && q.warpage_deg.abs() < 1e-9 && q.skew_deg.abs() < 1e-9);
    assert!((q.jacobian - 1.0).abs() < 1e-12 && (q.area - 1.0).abs() < 1e-12 && (q.char_length - 1.0).abs() < 1e-12);
    let steel = Material { young_mpa: 210_000.0, density_t_mm3: 7.85e-9, poisson: 0.3 };
    // sqrt(210000 / (7.85e-9 * 0.91)) = 5.422e6 mm/s: a 1 mm element steps 0.18 microseconds.
    assert!((steel.wave_speed() / 5.4219e6 - 1.0).abs() < 1e-4);
}

#[test]
fn a_lifted_corner_warps_and_a_rhombus_skews() {
    let warped = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.2), DVec3::Y];
    assert!(element_quality(&warped, &[0, 1, 2, 3]).warpage_deg > 10.0);
    let s = 45f64.to_radians();
    let rhombus = [DVec3::ZERO, DVec3::X, DVec3::new(1.0 + s.cos(), s.sin(), 0.0), DVec3::new(s.cos(), s.sin(), 0.0)];
    let q = element_quality(&rhombus, &[0, 1, 2, 3]);
    assert!((q.skew_deg - 45.0).abs() < 1e-9, "{}", q.skew_deg);
    assert!((q.jacobian - s.sin()).abs() < 1e-12);
}
