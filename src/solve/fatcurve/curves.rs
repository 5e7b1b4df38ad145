//! The fat curves: a line or conic approximant of one equation with a
//! rigorous width, and the bounds a clip keeps.

use crate::scalar::geo::Geo;

/// `a0 + a1 s + a2 t`.
#[derive(Clone, Copy, Debug)]
pub struct Linear<S> {
    /// `[a0, a1, a2]`.
    pub c: [S; 3],
}

/// `c0 + c1 s + c2 t + c3 s² + c4 s t + c5 t²`.
#[derive(Clone, Copy, Debug)]
pub struct Quadratic<S> {
    /// `[c0, c1, c2, c3, c4, c5]`.
    pub c: [S; 6],
}

impl<G: Geo> Linear<G> {
    /// The monomial form of the degree-1 BB polynomial with float coefficients
    /// `c` (storage order: `f_001, f_100, f_010`) on the tri-box, enclosed in
    /// the geometry kernel.
    pub fn from_bb(c: &[f64]) -> Self {
        debug_assert_eq!(c.len(), 3);
        let [c0, c1, c2] = [c[0], c[1], c[2]].map(G::pt);
        Self {
            c: [c0, c1 - c0, c2 - c0],
        }
    }
}

impl<S: Geo> Linear<S> {
    /// Value at `(s, t)`.
    pub fn eval(&self, s: S, t: S) -> S {
        self.c[0] + self.c[1] * s + self.c[2] * t
    }

    pub(super) fn shifted(&self, d: f64) -> Self {
        Self {
            c: [self.c[0] - S::pt(d), self.c[1], self.c[2]],
        }
    }
}

impl<G: Geo> Quadratic<G> {
    /// The monomial form of the degree-2 BB polynomial with float coefficients
    /// `c` on the tri-box, enclosed in the geometry kernel: with
    /// `r = 1 − s − t`, `f = f200 s² + f020 t² + f002 r² + 2 f110 st + 2 f101 sr + 2 f011 tr`.
    pub fn from_bb(c: &[f64]) -> Self {
        debug_assert_eq!(c.len(), 6);
        // Storage order: f002, f101, f200, f011, f110, f020.
        let [f002, f101, f200, f011, f110, f020] = [c[0], c[1], c[2], c[3], c[4], c[5]].map(G::pt);
        let two = G::pt(2.0);
        Self {
            c: [
                f002,
                two * (f101 - f002),
                two * (f011 - f002),
                f200 + f002 - two * f101,
                two * (f110 + f002 - f101 - f011),
                f020 + f002 - two * f011,
            ],
        }
    }
}

impl<S: Geo> Quadratic<S> {
    /// Value at `(s, t)`.
    pub fn eval(&self, s: S, t: S) -> S {
        let c = &self.c;
        c[0] + s * (c[1] + c[3] * s + c[4] * t) + t * (c[2] + c[5] * t)
    }

    pub(super) fn shifted(&self, d: f64) -> Self {
        let mut c = self.c;
        c[0] = c[0] - S::pt(d);
        Self { c }
    }

    /// The lines where the level curves of `Q` are tangent to `s = const`
    /// (`∂Q/∂t = 0`), `t = const` (`∂Q/∂s = 0`) and `w = const`
    /// (`∂Q/∂s = ∂Q/∂t`).
    pub(super) fn tangency_lines(&self) -> [Linear<S>; 3] {
        let c = &self.c;
        let two = S::pt(2.0);
        [
            Linear {
                c: [c[2], c[4], two * c[5]],
            },
            Linear {
                c: [c[1], two * c[3], c[4]],
            },
            Linear {
                c: [c[1] - c[2], two * c[3] - c[4], c[4] - two * c[5]],
            },
        ]
    }
}

/// `|p| ≤ δ` for a linear or quadratic `p`.
#[derive(Clone, Copy, Debug)]
pub enum Fat<S> {
    /// A fat line: two parallel lines.
    Line(Linear<S>, f64),
    /// A fat conic: two level curves of a quadratic.
    Conic(Quadratic<S>, f64),
}

impl<S: Geo> Fat<S> {
    /// The same fat curve with its coefficients' midpoints (the input of
    /// the float proposal); `None` if one is not finite.
    pub(super) fn midpoints(&self) -> Option<Fat<f64>> {
        fn mids<S: Geo, const N: usize>(c: [S; N]) -> Option<[f64; N]> {
            let mut out = [0.0; N];
            for (m, x) in out.iter_mut().zip(c) {
                *m = 0.5 * (x.lower() + x.upper());
                if !m.is_finite() {
                    return None;
                }
            }
            Some(out)
        }
        Some(match self {
            Fat::Line(l, d) => Fat::Line(Linear { c: mids(l.c)? }, *d),
            Fat::Conic(q, d) => Fat::Conic(Quadratic { c: mids(q.c)? }, *d),
        })
    }

    pub(super) fn possibly_contains(&self, s: S, t: S) -> bool {
        let (val, d) = match self {
            Fat::Line(l, d) => (l.eval(s, t), *d),
            Fat::Conic(q, d) => (q.eval(s, t), *d),
        };
        // The float kernel's candidates lie on the boundary curves only up to
        // the rounding of their computation (root solving loses digits near
        // tangency): allow that much on the scale of the curve's terms
        // (`s, t ∈ [0, 1]`), or boundary points are lost. Rigorous kernels
        // carry it in their enclosures.
        let d = if S::RIGOROUS {
            d
        } else {
            let scale = match self {
                Fat::Line(l, _) => l.c.iter().map(|c| c.mag()).sum::<f64>(),
                Fat::Conic(q, _) => q.c.iter().map(|c| c.mag()).sum::<f64>(),
            };
            d + 1e-9 * scale
        };
        val.possibly_le(d) && val.possibly_ge(-d)
    }
}

/// The outcome of a clipping computation in local barycentric coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ClipBounds {
    /// Proven: no root in the tri-box.
    Empty,
    /// Every root has `u ≥ mins[0]`, `v ≥ mins[1]`, `w ≥ mins[2]` (each in `[0, 1]`).
    Keep([f64; 3]),
}

/// `Keep(m)`, or `Empty` when the bounds are inconsistent (`Σ m > 1`: no point
/// satisfies all three). Rigorous minima are lower bounds, so `Σ m > 1` is a
/// proof; float minima of a converged region can exceed 1 by rounding, so the
/// float kernel needs a margin before it calls the region empty.
pub(super) fn keep_or_empty(m: [f64; 3], rigorous: bool) -> ClipBounds {
    let margin = if rigorous { 0.0 } else { 1e-9 };
    // Float minima are estimates, not lower bounds: back them off a little so
    // the float iteration does not cut an ulp past the root it converges to.
    let m = m.map(|x| (x - margin).max(0.0));
    let sum = m[0] + m[1] + m[2];
    if sum > 1.0 + margin {
        ClipBounds::Empty
    } else if sum > 1.0 {
        let scale = 1.0 / sum;
        ClipBounds::Keep(m.map(|x| x * scale))
    } else {
        ClipBounds::Keep(m)
    }
}
