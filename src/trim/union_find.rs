//! The root finder of a union-find forest, for the grouping of kept pieces (patch trimming).

/// The root of `x` in the forest `parent`, halving the path on the way.
pub fn find(parent: &mut [usize], mut x: usize) -> usize {
    while parent[x] != x {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    x
}
