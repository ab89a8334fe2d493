//! Elements that overlap in a user-given mesh (2D and 3D).
//!
//! In a conforming mesh every side (a triangle's edge, a tetrahedron's face)
//! belongs to one element, on the boundary, or to two that lie on its two
//! sides and so list it in opposite orientations. A side that three elements
//! use, or two in the same orientation, means elements stacked on one region:
//! an element listed twice, or two meshes of one region joined. Their
//! stiffnesses would add there and the answer would be stiffer with nothing
//! to show it, so such a mesh is refused (`quality`, `mesh3d::quality`).
//! Overlaps that share no side (two meshes of one region with different
//! nodes) are not found here: that needs a geometric search.
//!
//! The sides are sorted as packed integers, `corners << 1 | orientation`, 8
//! bytes a side where the node numbers fit (16 past 2^31 nodes in 2D, 2^21
//! in 3D), instead of a map of every side (about 190 bytes an element in 2D:
//! the edge sets' look-up keeps only their own edges for that reason).

/// A side's corners, sorted, and whether its element lists them in an odd
/// permutation of that order (the orientation, which two elements on
/// opposite sides of the side give opposite values).
pub fn side_key<const N: usize>(mut corners: [usize; N]) -> ([usize; N], bool) {
    let mut odd = false;
    // Insertion sort: N ≤ 3, each swap flips the permutation's parity.
    for i in 1..N {
        let mut j = i;
        while j > 0 && corners[j - 1] > corners[j] {
            corners.swap(j - 1, j);
            odd = !odd;
            j -= 1;
        }
    }
    (corners, odd)
}

/// The first side (sorted corners) used by two elements in the same
/// orientation or by three or more, or None. `sides(e)` gives element `e`'s
/// sides as `side_key` returns them.
pub fn overlapped_side<const N: usize, const S: usize>(
    n_elems: usize,
    n_nodes: usize,
    sides: impl Fn(usize) -> [([usize; N], bool); S],
) -> Option<[usize; N]> {
    let bits = usize::BITS - n_nodes.max(1).leading_zeros();
    if bits as usize * N < 64 {
        first_fault::<u64, N, S>(n_elems, bits, &sides)
    } else {
        first_fault::<u128, N, S>(n_elems, bits, &sides)
    }
}

fn first_fault<K, const N: usize, const S: usize>(
    n_elems: usize,
    bits: u32,
    sides: &impl Fn(usize) -> [([usize; N], bool); S],
) -> Option<[usize; N]>
where
    K: Copy + Ord + From<u64> + std::ops::Shl<u32, Output = K> + std::ops::Shr<u32, Output = K>,
    K: std::ops::BitOr<Output = K> + std::ops::BitAnd<Output = K> + std::ops::Sub<Output = K> + TryInto<u64>,
{
    let mut packed: Vec<K> = Vec::with_capacity(n_elems * S);
    for e in 0..n_elems {
        for (corners, odd) in sides(e) {
            let key = corners.iter().fold(K::from(0), |k, &c| (k << bits) | K::from(c as u64));
            packed.push((key << 1) | K::from(odd as u64));
        }
    }
    packed.sort_unstable();
    // The same side in the same orientation twice is one value twice; three
    // uses of a side are three neighbours in the sorted list.
    let twice = packed.windows(2).find(|w| w[0] == w[1]).map(|w| w[0] >> 1);
    let thrice = || packed.windows(3).find(|w| w[0] >> 1 == w[2] >> 1).map(|w| w[0] >> 1);
    let key = twice.or_else(thrice)?;
    let mask = (K::from(1) << bits) - K::from(1);
    Some(std::array::from_fn(|i| {
        let c = (key >> (bits * (N - 1 - i) as u32)) & mask;
        c.try_into().ok().unwrap_or(u64::MAX) as usize
    }))
}

/// The elements (at most three, in order) that have the side `key` among
/// theirs: to name them where the side is refused.
pub fn users<const N: usize, const S: usize>(
    n_elems: usize,
    key: [usize; N],
    sides: impl Fn(usize) -> [([usize; N], bool); S],
) -> Vec<usize> {
    (0..n_elems)
        .filter(|&e| sides(e).iter().any(|s| s.0 == key))
        .take(3)
        .collect()
}

/// The refusal's text: which elements and why.
pub fn why<const N: usize>(side: &str, key: [usize; N], users: &[usize]) -> String {
    let listed = users.iter().map(|e| e.to_string()).collect::<Vec<_>>().join(", ");
    let what = if users.len() > 2 {
        format!("{side} {key:?} is shared by elements {listed} (at most two may share a {side})")
    } else {
        format!("elements {listed} lie on the same side of their common {side} {key:?}")
    };
    format!("{what}: elements overlap (an element listed twice, or two meshes of one region joined)")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two triangles of a square, counter-clockwise.
    fn square() -> Vec<[usize; 3]> {
        vec![[0, 1, 2], [0, 2, 3]]
    }

    fn edges(t: &[[usize; 3]]) -> impl Fn(usize) -> [([usize; 2], bool); 3] + '_ {
        move |e| {
            let c = t[e];
            [side_key([c[0], c[1]]), side_key([c[1], c[2]]), side_key([c[2], c[0]])]
        }
    }

    #[test]
    fn the_parity_of_a_sort_is_the_orientation() {
        assert_eq!(side_key([3, 1, 2]), ([1, 2, 3], false));
        assert_eq!(side_key([1, 3, 2]), ([1, 2, 3], true));
        assert_eq!(side_key([2, 1]), ([1, 2], true));
    }

    #[test]
    fn a_conforming_mesh_has_no_overlap() {
        let t = square();
        assert_eq!(overlapped_side(t.len(), 4, edges(&t)), None);
    }

    #[test]
    fn an_element_listed_twice_is_found_and_named() {
        let mut t = square();
        t.push([1, 2, 0]); // the first triangle again, rotated
        let key = overlapped_side(t.len(), 4, edges(&t)).expect("the repeated triangle overlaps");
        let who = users(t.len(), key, edges(&t));
        assert!(who.contains(&0) && who.contains(&2), "{who:?}");
    }

    #[test]
    fn a_side_of_three_elements_is_found() {
        // A third triangle hinged on the diagonal 0-2, on the second's side.
        let t = vec![[0, 1, 2], [0, 2, 3], [0, 2, 4]];
        let key = overlapped_side(t.len(), 5, edges(&t)).expect("three elements share 0-2");
        assert_eq!(key, [0, 2]);
        assert_eq!(users(t.len(), key, edges(&t)), vec![0, 1, 2]);
    }

    #[test]
    fn wide_node_numbers_take_the_wide_keys() {
        // 3 × 23 bits (n = 2^22 needs 23) pass 64: the u128 path, with the same answer.
        let n = 1 << 22;
        let f = |e: usize| [side_key([n - 3, n - 2, n - 1 - (e % 2)])];
        assert_eq!(overlapped_side(2, n, f), None);
        let g = |_: usize| [side_key([n - 3, n - 2, n - 1])];
        assert_eq!(overlapped_side(2, n, g), Some([n - 3, n - 2, n - 1]));
    }
}
