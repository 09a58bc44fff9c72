//! A union-find forest: pieces of patches joined in trimming, solids joined into bodies by the faces they share.

/// The root of `x` in the forest `parent`, halving the path on the way.
pub fn find(parent: &mut [usize], mut x: usize) -> usize {
    while parent[x] != x {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    x
}

/// Joins the trees of `a` and `b` under the lower root, so that roots (and the sets read from them) do not
/// depend on the order of the joins.
pub fn union(parent: &mut [usize], a: usize, b: usize) {
    let (ra, rb) = (find(parent, a), find(parent, b));
    parent[ra.max(rb)] = ra.min(rb);
}
