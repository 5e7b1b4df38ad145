//! Fat-line clipping on boxes: linear clipping (Liu et al. 2016, §2.3.2–
//! 2.3.3, with lines for both equations) carried over from tri-boxes to
//! boxes.
//!
//! # The clip
//! In a box's local coordinates, centred as `σ = s − ½`, `τ = t − ½`, each
//! equation `p` gets a plane `l(σ, τ) = a + b σ + c τ` (the least-squares
//! plane through its control points `(i/m − ½, j/n − ½, p_ij)`, in `f64`: any
//! plane is rigorous, a good one is narrow) and the bound
//! `δ = max |p_ij − l(i/m − ½, j/n − ½)|`, computed in [`Iv`] arithmetic. A
//! linear polynomial's tensor Bernstein coefficients are its values on the
//! grid, and the Bernstein basis is a positive partition of unity, so
//! `|p − l| ≤ δ` on the box: every root lies in the parallelogram
//! `P = {|l_f| ≤ δ_f} ∩ {|l_g| ≤ δ_g} ∩ [−½, ½]²`.
//!
//! `P` is convex and bounded, so its extreme `σ` and `τ` are attained at
//! vertices, each the meeting point of two of its eight boundary lines
//! (four strip edges, four box edges). Every such pair is solved in [`Iv`]
//! arithmetic, candidates that provably violate a constraint are dropped, and
//! the kept span in each direction is the hull of the rest. If no candidate
//! survives, `P` is empty and the box holds no root. The two strips' edges
//! are intersected only when their determinant is provably non-zero; nearly
//! parallel strips (a tangency) give [`FatLineClip::Parallel`] and the caller
//! falls back to Bézier hulls.
//!
//! # Convergence
//! `δ = O(h²)` on a box of size `h` (the plane is within the second-order
//! Taylor remainder), so near a simple root the kept box shrinks
//! quadratically, whatever the angle of the curves to the axes — where
//! Bézier clipping of one equation at a time needs the curves roughly
//! aligned with the axes.

use super::net::{at, Shape, STACK};
use crate::scalar::iv::Iv;

/// The result of [`fat_line_spans`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum FatLineClip {
    /// The two strips do not meet inside the box: no root.
    Empty,
    /// Spans `[(s_lo, s_hi), (t_lo, t_hi)]` in local coordinates holding
    /// every root.
    Spans([(f64, f64); 2]),
    /// The strips are parallel within rounding (or an equation's plane is
    /// constant): no clip computed.
    Parallel,
}

/// A strip `|a + b σ + c τ| ≤ δ` (centred local coordinates).
#[derive(Clone, Copy, Debug)]
pub(super) struct Strip {
    a: Iv,
    b: Iv,
    c: Iv,
    delta: f64,
}

impl Strip {
    /// The strip in uncentred local coordinates `(s, t) ∈ [0, 1]²`:
    /// `|a' + b s + c t| ≤ δ` with `a' = a − b/2 − c/2`, as `(a', b, c, δ)`.
    pub(super) fn uncentred(&self) -> (Iv, Iv, Iv, f64) {
        (
            self.a.sub(self.b.scale(0.5)).sub(self.c.scale(0.5)),
            self.b,
            self.c,
            self.delta,
        )
    }

    /// The least-squares plane through the control points and its rigorous
    /// distance bound (module docs). `None` for non-finite coefficients.
    pub(super) fn of(p: &[Iv], sh: Shape) -> Option<Self> {
        let (m, n) = (sh.m, sh.n);
        // Centred abscissae are symmetric about 0 on the grid, so the normal
        // equations decouple: a = mean, b = Σ x p / Σ x², c = Σ y p / Σ y².
        let x = |i: usize| i as f64 / m as f64 - 0.5;
        let y = |j: usize| j as f64 / n as f64 - 0.5;
        let (mut sum, mut sx, mut sy) = (0.0, 0.0, 0.0);
        for i in 0..=m {
            for j in 0..=n {
                let v = p[at(sh, i, j)].mid();
                sum += v;
                sx += x(i) * v;
                sy += y(j) * v;
            }
        }
        let xx: f64 = (0..=m).map(|i| x(i) * x(i)).sum::<f64>() * (n + 1) as f64;
        let yy: f64 = (0..=n).map(|j| y(j) * y(j)).sum::<f64>() * (m + 1) as f64;
        let (a, b, c) = (sum / ((m + 1) * (n + 1)) as f64, sx / xx, sy / yy);
        if !(a.is_finite() && b.is_finite() && c.is_finite()) {
            return None;
        }
        // The grid abscissae enclosed: (2i − m) / (2m).
        let (ia, ib, ic) = (Iv::point(a), Iv::point(b), Iv::point(c));
        let mut cy = [Iv::point(0.0); STACK];
        for (j, y) in cy.iter_mut().enumerate().take(n + 1) {
            *y = ic.mul(Iv::point(2.0 * j as f64 - n as f64).div(Iv::point(2.0 * n as f64)));
        }
        let mut delta = 0.0f64;
        for i in 0..=m {
            let x = Iv::point(2.0 * i as f64 - m as f64).div(Iv::point(2.0 * m as f64));
            let bx = ia.add(ib.mul(x));
            for (j, y) in cy.iter().enumerate().take(n + 1) {
                let r = p[at(sh, i, j)].sub(bx.add(*y));
                if !r.is_finite() {
                    return None;
                }
                delta = delta.max(r.lo.abs()).max(r.hi.abs());
            }
        }
        Some(Self {
            a: ia,
            b: ib,
            c: ic,
            delta,
        })
    }

    /// Provably outside the strip at the candidate point.
    fn excludes(&self, p: [Iv; 2]) -> bool {
        let v = self.a.add(self.b.mul(p[0])).add(self.c.mul(p[1]));
        v.lo > self.delta || v.hi < -self.delta
    }

    /// The right-hand sides `−a ± δ` of its two edges `b σ + c τ = e`.
    fn edges(&self) -> [Iv; 2] {
        let d = Iv::point(self.delta);
        let minus_a = Iv::point(0.0).sub(self.a);
        [minus_a.sub(d), minus_a.add(d)]
    }
}

/// The fat-line clip of the box whose polynomials (`f` then `g`, row-major,
/// shape `sh`) are the first two blocks of `c`; see the module docs.
pub(super) fn fat_line_spans(c: &[Iv], sh: Shape) -> FatLineClip {
    if sh.m >= STACK || sh.n >= STACK {
        // Beyond the stack scratch: Bézier hulls only.
        return FatLineClip::Parallel;
    }
    let (Some(sf), Some(sg)) = (Strip::of(&c[..sh.len], sh), Strip::of(&c[sh.len..2 * sh.len], sh)) else {
        return FatLineClip::Parallel;
    };
    let strips = [sf, sg];
    let half = Iv::point(0.5);
    let neg_half = Iv::point(-0.5);
    // At most 4 corners, 2 strips × 2 edges × 4 box edges, 2 × 2 crossings.
    let mut cands = [[Iv::point(0.0); 2]; 24];
    let mut len = 0;
    let mut push = |p: [Iv; 2]| {
        cands[len] = p;
        len += 1;
    };
    // Box corners.
    for s in [neg_half, half] {
        for t in [neg_half, half] {
            push([s, t]);
        }
    }
    for st in &strips {
        if st.b.lo == 0.0 && st.c.lo == 0.0 {
            // A constant plane: the strip is everything or nothing, and the
            // box corners and edges decide; nothing to intersect.
            continue;
        }
        for e in st.edges() {
            // With the box edges σ = ±½ (unless the edge is parallel: c = 0)
            // and τ = ±½ (unless b = 0). b and c are floats, so "= 0" is exact.
            for side in [neg_half, half] {
                if st.c.lo != 0.0 {
                    push([side, e.sub(st.b.mul(side)).div(st.c)]);
                }
                if st.b.lo != 0.0 {
                    push([e.sub(st.c.mul(side)).div(st.b), side]);
                }
            }
        }
    }
    // Edges of one strip with edges of the other.
    let det = sf.b.mul(sg.c).sub(sg.b.mul(sf.c));
    if !(det.lo > 0.0 || det.hi < 0.0) {
        return FatLineClip::Parallel;
    }
    for e1 in sf.edges() {
        for e2 in sg.edges() {
            let s = e1.mul(sg.c).sub(e2.mul(sf.c)).div(det);
            let t = sf.b.mul(e2).sub(sg.b.mul(e1)).div(det);
            push([s, t]);
        }
    }
    let mut span = [(f64::INFINITY, f64::NEG_INFINITY); 2];
    for &p in &cands[..len] {
        if !(p[0].is_finite() && p[1].is_finite()) {
            return FatLineClip::Parallel;
        }
        let outside_box = p.iter().any(|x| x.lo > 0.5 || x.hi < -0.5);
        if outside_box || strips.iter().any(|st| st.excludes(p)) {
            continue;
        }
        for d in 0..2 {
            let x = p[d].add(half);
            span[d] = (span[d].0.min(x.lo), span[d].1.max(x.hi));
        }
    }
    if span[0].0 > span[0].1 {
        return FatLineClip::Empty;
    }
    FatLineClip::Spans(span.map(|(lo, hi)| (lo.max(0.0), hi.min(1.0))))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Bilinear coefficients of `a + b s + c t` (its values at the corners).
    fn linear(a: f64, b: f64, c: f64) -> Vec<Iv> {
        let mut out = Vec::new();
        for i in 0..=1 {
            for j in 0..=1 {
                out.push(Iv::point(a + b * i as f64 + c * j as f64));
            }
        }
        out
    }

    #[test]
    fn two_lines_clip_to_their_crossing() {
        // s + t = 0.7 and s − t = 0.1 meet at (0.4, 0.3).
        let mut c = linear(-0.7, 1.0, 1.0);
        c.extend(linear(-0.1, 1.0, -1.0));
        let FatLineClip::Spans(sp) = fat_line_spans(&c, Shape::pair(1, 1)) else {
            panic!()
        };
        assert!(sp[0].0 <= 0.4 && 0.4 <= sp[0].1 && sp[0].1 - sp[0].0 < 1e-14, "{sp:?}");
        assert!(sp[1].0 <= 0.3 && 0.3 <= sp[1].1 && sp[1].1 - sp[1].0 < 1e-14, "{sp:?}");
    }

    #[test]
    fn lines_meeting_outside_the_box_are_empty() {
        // s + t = 1.9 and s − t = 0.5 meet at (1.2, 0.7), right of the box.
        let mut c = linear(-1.9, 1.0, 1.0);
        c.extend(linear(-0.5, 1.0, -1.0));
        assert_eq!(fat_line_spans(&c, Shape::pair(1, 1)), FatLineClip::Empty);
    }

    #[test]
    fn parallel_lines_fall_back() {
        let mut c = linear(-0.5, 1.0, 1.0);
        c.extend(linear(-0.6, 2.0, 2.0));
        assert_eq!(fat_line_spans(&c, Shape::pair(1, 1)), FatLineClip::Parallel);
    }

    #[test]
    fn curved_zero_sets_stay_inside_the_spans() {
        // f = (s − ½)² + t − 0.6 (bidegree (2, 1)), g = s − t: root at
        // s = t = r with (r − ½)² + r − 0.6 = 0, r = √0.35 (≈ 0.5916).
        let f: Vec<Iv> = [[-0.35, 0.65], [-0.85, 0.15], [-0.35, 0.65]]
            .iter()
            .flatten()
            .map(|&x| Iv::point(x))
            .collect();
        // s − t at bidegree (2, 1): coefficients i/2 − j.
        let g: Vec<Iv> = (0..=2)
            .flat_map(|i| (0..=1).map(move |j| Iv::point(i as f64 / 2.0 - j as f64)))
            .collect();
        let mut c = f;
        c.extend(g);
        let r = 0.35f64.sqrt();
        let FatLineClip::Spans(sp) = fat_line_spans(&c, Shape::pair(2, 1)) else {
            panic!()
        };
        for d in 0..2 {
            assert!(sp[d].0 <= r && r <= sp[d].1, "{sp:?}");
        }
        assert!(sp[0].1 - sp[0].0 < 0.7 && sp[1].1 - sp[1].0 < 0.7, "{sp:?}");
    }
}
