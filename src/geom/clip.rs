//! Exact area of the intersection of 2D triangles (Sutherland-Hodgman against a convex clip polygon).

use glam::DVec2;
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::{RTree, AABB};

/// Signed area of a polygon (counter-clockwise positive).
pub fn signed_area(poly: &[DVec2]) -> f64 {
    let n = poly.len();
    (0..n).map(|i| poly[i].perp_dot(poly[(i + 1) % n])).sum::<f64>() * 0.5
}

/// The part of `subject` inside the convex, counter-clockwise polygon `clip`.
pub fn clip_convex(subject: &[DVec2], clip: &[DVec2]) -> Vec<DVec2> {
    let mut output = subject.to_vec();
    for i in 0..clip.len() {
        if output.is_empty() {
            break;
        }
        let (a, b) = (clip[i], clip[(i + 1) % clip.len()]);
        let inside = |p: DVec2| (b - a).perp_dot(p - a) >= 0.0;
        let input = std::mem::take(&mut output);
        for j in 0..input.len() {
            let (p, q) = (input[j], input[(j + 1) % input.len()]);
            let (p_in, q_in) = (inside(p), inside(q));
            if p_in {
                output.push(p);
            }
            if p_in != q_in {
                let d1 = (b - a).perp_dot(p - a);
                let d2 = (b - a).perp_dot(q - a);
                output.push(p + (q - p) * (d1 / (d1 - d2)));
            }
        }
    }
    output
}

/// Area of the intersection of two triangles, in any orientation.
pub fn triangle_overlap(a: [DVec2; 3], b: [DVec2; 3]) -> f64 {
    let ccw = |t: [DVec2; 3]| {
        if signed_area(&t) < 0.0 {
            [t[0], t[2], t[1]]
        } else {
            t
        }
    };
    let piece = clip_convex(&ccw(a), &ccw(b));
    if piece.len() < 3 {
        0.0
    } else {
        signed_area(&piece).abs()
    }
}

/// Axis-aligned 2D box of a triangle, for cheap rejection before clipping.
pub fn bounds(t: &[DVec2; 3]) -> (DVec2, DVec2) {
    (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2]))
}

/// Area of the intersection of two triangle soups, each a partition of a region without self-overlap
/// (a face's mesh projected to 2D). Triangles of `b` are found by box in an R-tree (a sweep over x alone
/// tested every triangle to the left of each one: n^2 on a large face, 4 s of a 2,500-hole plate's
/// pairing) and summed in the order of their lower x bound, so the sum is the same to the last bit.
pub fn soup_overlap(a: &[[DVec2; 3]], b: &[[DVec2; 3]]) -> f64 {
    let b_bounds: Vec<(DVec2, DVec2)> = b.iter().map(bounds).collect();
    let mut order: Vec<usize> = (0..b.len()).collect();
    order.sort_by(|&x, &y| b_bounds[x].0.x.total_cmp(&b_bounds[y].0.x));
    let mut rank = vec![0; b.len()];
    for (r, &i) in order.iter().enumerate() {
        rank[i] = r;
    }
    let boxes = b_bounds
        .iter()
        .enumerate()
        .map(|(i, (lo, hi))| GeomWithData::new(Rectangle::from_corners(lo.to_array(), hi.to_array()), i))
        .collect();
    let tree: RTree<GeomWithData<Rectangle<[f64; 2]>, usize>> = RTree::bulk_load(boxes);
    let mut total = 0.0;
    let mut near = Vec::new();
    for ta in a {
        let (lo, hi) = bounds(ta);
        near.clear();
        near.extend(
            tree.locate_in_envelope_intersecting(&AABB::from_corners(lo.to_array(), hi.to_array())).map(|g| g.data),
        );
        near.sort_unstable_by_key(|&i| rank[i]);
        for &i in &near {
            total += triangle_overlap(*ta, b[i]);
        }
    }
    total
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64) -> DVec2 {
        DVec2::new(x, y)
    }

    #[test]
    fn overlap_of_shifted_squares() {
        let sq = |x0: f64, y0: f64| {
            vec![
                [v(x0, y0), v(x0 + 2.0, y0), v(x0 + 2.0, y0 + 2.0)],
                [v(x0, y0), v(x0 + 2.0, y0 + 2.0), v(x0, y0 + 2.0)],
            ]
        };
        assert!((soup_overlap(&sq(0.0, 0.0), &sq(0.0, 0.0)) - 4.0).abs() < 1e-12);
        assert!((soup_overlap(&sq(0.0, 0.0), &sq(1.0, 1.0)) - 1.0).abs() < 1e-12);
        assert!((soup_overlap(&sq(0.0, 0.0), &sq(1.0, 0.0)) - 2.0).abs() < 1e-12);
        assert_eq!(soup_overlap(&sq(0.0, 0.0), &sq(2.0, 0.0)), 0.0);
        assert_eq!(soup_overlap(&sq(0.0, 0.0), &sq(5.0, 5.0)), 0.0);
    }

    #[test]
    fn clockwise_triangles_are_handled() {
        let a = [v(0.0, 0.0), v(0.0, 1.0), v(1.0, 0.0)];
        assert!((triangle_overlap(a, a) - 0.5).abs() < 1e-12);
    }

    #[test]
    fn soups_overlap_as_every_pair_of_their_triangles_does() {
        // Two triangulated grids (one rotated and shifted): the tree finds every pair a scan of all pairs does.
        let grid = |n: usize, angle: f64, shift: DVec2| {
            let r = DVec2::from_angle(angle);
            let mut t = Vec::new();
            for i in 0..n {
                for j in 0..n {
                    let p = |a: usize, b: usize| r.rotate(v(a as f64, b as f64 * 0.7)) + shift;
                    t.push([p(i, j), p(i + 1, j), p(i + 1, j + 1)]);
                    t.push([p(i, j), p(i + 1, j + 1), p(i, j + 1)]);
                }
            }
            t
        };
        let (a, b) = (grid(12, 0.0, DVec2::ZERO), grid(10, 0.3, v(2.5, -1.0)));
        let scan: f64 = a.iter().flat_map(|&ta| b.iter().map(move |&tb| triangle_overlap(ta, tb))).sum();
        assert!(scan > 10.0);
        assert!((soup_overlap(&a, &b) - scan).abs() < 1e-9 * scan, "{} vs {scan}", soup_overlap(&a, &b));
    }
}
