//! Where the coefficients of a triangular BB polynomial are stored: the
//! multi-indices `(i, j, k)`, `i + j + k = n`, of `f_ijk`, the coefficient of
//! `n!/(i! j! k!) u^i v^j w^k` (`w = 1 − u − v`), run `j = 0..=n` outer and
//! `i = 0..=n−j` inner (Liu et al. 2016, Eq. (2)).
//!
//! ```
//! use rootclip::poly::{tri_index, tri_indices, tri_len};
//! assert_eq!(tri_len(2), 6);
//! let order: Vec<_> = tri_indices(1).collect();
//! assert_eq!(order, [(0, 0, 1), (1, 0, 0), (0, 1, 0)]);
//! assert_eq!(tri_index(2, 1, 1), 4);
//! ```

/// Number of coefficients of a triangular polynomial of degree `n`.
pub const fn tri_len(n: usize) -> usize {
    (n + 1) * (n + 2) / 2
}

/// Storage index of `f_ij` (with `k = n − i − j`) in degree `n`.
#[inline]
pub const fn tri_index(n: usize, i: usize, j: usize) -> usize {
    // Rows j = 0, 1, … hold n + 1, n, … coefficients.
    j * (n + 1) - j * (j.saturating_sub(1)) / 2 + i
}

/// Barycentric coordinates `(u, v, w)` of a point with respect to a triangle.
pub type Bary<S> = [S; 3];

/// The multi-indices `(i, j, k)` of degree `n` in storage order.
pub fn tri_indices(n: usize) -> impl Iterator<Item = (usize, usize, usize)> {
    (0..=n).flat_map(move |j| (0..=n - j).map(move |i| (i, j, n - i - j)))
}
