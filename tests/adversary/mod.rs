//! The ray adversary: families of *grazing* rays against height-field patches,
//! judged by an independent referee in exact rational arithmetic.
//!
//! Shared by `tests/ray_props.rs` (a few hundred cases under proptest) and the
//! fuzz tool `dev/src/bin/adversary.rs` (many thousands, with reproductions).
//!
//! # The families
//! Every patch is a *height field* whose `x` and `y` are affine in the
//! parameters, exactly: `x = a·u + x0`, `y = b·v + y0` with `a, x0, b, y0`
//! dyadic, heights `z` random `f64` (all 52 mantissa bits, or sometimes few
//! bits so that ties are exact):
//! * [`Family::Tensor`]: bidegree `(m, n)`, `1 ≤ m, n ≤ 4`, control points
//!   `(x0 + a·i/m, y0 + b·j/n, z_ij)` (`a` a multiple of `m`, so they are floats);
//! * [`Family::Rational`]: the same with weights `w_ij = α_i` (positive,
//!   random): `y = b·v + y0` still holds, `x(u)` is rational; rays have `dy = 0`;
//! * [`Family::Triangle`]: degree `1 ≤ n ≤ 4`, points at the domain points
//!   `(x0 + a·i/n, y0 + b·j/n)`;
//! * [`Family::Bspline`]: bidegree `(p, q)`, `2 ≤ p, q ≤ 4`, dyadic knots
//!   (clamped, or unclamped one time in four), often with a crease (an
//!   interior knot of multiplicity `p`), control points at `a·`(Greville
//!   abscissae)`+ x0` (linear precision: `x = a·u + x0` on the domain);
//! * [`Family::Nurbs`]: the same with weights `w_ij = α_i`; rays have `dy = 0`.
//!
//! Heights are full-precision, or multiples of 1/256 (exact ties), or nearly
//! flat (`c + ε·r`, `ε` down to `2^-50`); one patch in five has a *flat edge*
//! (`∂z/∂u = 0` along an edge: its last two control rows equal).
//!
//! Rays are aimed at a *feature*: a corner, an edge (`u + v = 1` on
//! triangles), an interior knot line, a crease, a knot corner, or the
//! interior, and built so that the true hit lies on the feature up to the
//! rounding of one float (and ±1..3 ulps): horizontal or slanted rays through
//! the feature point with `oz` the rounded exact height there ("cross"),
//! vertical rays with `(ox, oy)` the rounded feature point ("vertical"),
//! horizontal rays running exactly along an edge or knot line ("along"), rays
//! whose `oz` is the rounded extremum of the height along their line, across
//! or along a feature ("tangent": two hits a few 1e-8 apart, or none), rays
//! along `u` onto a flat edge ("edge-tangent": a double hit on the edge split
//! by the rounding), and rays starting on the surface at the feature ("start":
//! a hit at `t ≈ 0`). Direction scales are about 1 or `2^±100`. One
//! horizontal case in five is *lowered* (see [`generate`]): the aimed height
//! becomes about 0, so one ulp of `oz` is tiny and the hits lie within
//! 1e-300 of their feature, tangent pairs down to 1e-162 apart.
//!
//! # The referee
//! The ray's line meets the patch where a univariate polynomial vanishes:
//! with the line parameter `s = t` (polynomial patches: `u(t)`, `v(t)` are
//! affine, the hits are the zeros of `z(u(t), v(t)) − oz − dz·t`), or `s = u`
//! (rational patches, `dy = 0`: `v = v*` is fixed and the hits are the zeros of
//! `dx·(N_z − oz·D) − dz·(N_x − ox·D)`, the homogeneous numerators and the
//! weight sum, and `t` a rational function of `u`, per knot span). The polynomial is found exactly (exact evaluation of the
//! Bernstein / B-spline sums at rational points and interpolation; one piece
//! per knot cell for B-splines, a zero on a shared knot counted once) on the
//! closed interval of `s` where the line is in the domain, and its distinct
//! zeros there are isolated by Sturm sequences with exact rational ends. The
//! referee reads the patch's floats from its [`PatchSpec`] (checking the
//! affine claim exactly) and uses nothing of rootclip but its public types.
//!
//! # What is checked ([`judge`])
//! On `intersect(patch, ray, RayOptions::default())`:
//! * **no silent miss**: if the outcome is complete, every true hit with
//!   `t ≥ 0` lies in the `(u, v)` box of a reported hit ([`Fault::Miss`]), and in
//!   the `t` box of one such hit ([`Fault::MissT`]);
//! * **no phantom**: every certified box holds exactly one true hit of the line
//!   ([`Fault::Phantom`]: none, [`Fault::Multiple`]: more), a transversal one
//!   ([`Fault::Tangent`]: a multiple zero, or a touch of a crease where the two
//!   pieces' one-sided slopes differ in sign), whose `t` lies in the `t` box
//!   and in the range `t ≥ 0` ([`Fault::TBox`]); no true hit is claimed by two
//!   certified boxes ([`Fault::Duplicate`]);
//! * every reported `(u, v)` lies in the closed domain ([`Fault::Domain`]);
//! * no error ([`Fault::Error`]); a `ZeroEquation` answer on these non-planar
//!   patches is recorded as suspicious ([`Fault::ZeroEquation`]) but keeps the
//!   contract (no hit list rather than a wrong one).
//!
//! Every membership is decided exactly: a zero is compared with a float (a
//! box end) by the sign of the polynomial there, or, for a non-linear test
//! (the `t` of a rational patch), by refining its isolating interval until the
//! test polynomial has no zero in it. Undecided hits and incomplete or
//! unresolved outcomes are allowed (counted, not faults).

// Shared by a test binary and a dev tool, each using a part of it.
#![allow(dead_code)]

use rootclip::glam::DVec3;
use rootclip::num_bigint::{BigInt, Sign};
use rootclip::num_rational::BigRational;
use rootclip::ray::{intersect, Degeneracy, Hit, HitBox, Patch, PatchSpec, Ray, RayOptions, RayOutcome};
use std::fmt::Write as _;
use std::time::{Duration, Instant};

// ---------------------------------------------------------------------------
// Exact numbers
// ---------------------------------------------------------------------------

/// An exact rational.
pub type Q = BigRational;

/// The float `x` as the exact rational it is.
pub fn qf(x: f64) -> Q {
    Q::from_float(x).expect("a finite float")
}

/// The integer `i`.
pub fn qi(i: i64) -> Q {
    Q::from_integer(BigInt::from(i))
}

fn sgn(x: &Q) -> i32 {
    match x.numer().sign() {
        Sign::Minus => -1,
        Sign::NoSign => 0,
        Sign::Plus => 1,
    }
}

/// `2^k` for `−1022 ≤ k ≤ 1023`, exactly.
fn pow2(k: i64) -> f64 {
    f64::from_bits(((k + 1023) as u64) << 52)
}

/// The float nearest to `x` (ties to even), subnormals included.
pub fn nearest(x: &Q) -> f64 {
    let s = sgn(x);
    if s == 0 {
        return 0.0;
    }
    let n = if s < 0 { -x.numer() } else { x.numer().clone() };
    let d = x.denom().clone();
    // 2^e ≤ n/d < 2^(e+1).
    let at_least = |e: i64| {
        if e >= 0 {
            n >= (&d << e as usize)
        } else {
            (&n << (-e) as usize) >= d
        }
    };
    let mut e = n.bits() as i64 - d.bits() as i64;
    while !at_least(e) {
        e -= 1;
    }
    while at_least(e + 1) {
        e += 1;
    }
    if e > 1023 {
        return s as f64 * f64::INFINITY;
    }
    let shift = (52 - e).min(1074);
    let (num, den) = if shift >= 0 {
        (&n << shift as usize, d)
    } else {
        (n, &d << (-shift) as usize)
    };
    let quo = &num / &den;
    let twice_rem: BigInt = (&num - &quo * &den) << 1usize;
    let mut m = u64::try_from(&quo).expect("a 53-bit mantissa");
    if twice_rem > den || (twice_rem == den && m % 2 == 1) {
        m += 1;
    }
    // m·2^-shift is a float: each product below is exact.
    let mag = if shift <= 1022 {
        m as f64 * pow2(-shift)
    } else {
        m as f64 * pow2(-(shift - 1022)) * pow2(-1022)
    };
    s as f64 * mag
}

/// `x` moved by `k` ulps (up for `k > 0`).
pub fn ulps(x: f64, k: i32) -> f64 {
    (0..k.abs()).fold(x, |y, _| if k > 0 { y.next_up() } else { y.next_down() })
}

// ---------------------------------------------------------------------------
// Polynomials (power form): over Q to build, over Z for Sturm sequences
// ---------------------------------------------------------------------------

/// A polynomial over Q, coefficients from the constant term up, no trailing
/// zeros (the zero polynomial is empty).
#[derive(Clone, Debug, PartialEq)]
pub struct Poly(Vec<Q>);

impl Poly {
    pub fn new(mut c: Vec<Q>) -> Poly {
        while c.last().is_some_and(|x| sgn(x) == 0) {
            c.pop();
        }
        Poly(c)
    }
    pub fn constant(c: Q) -> Poly {
        Poly::new(vec![c])
    }
    /// `c0 + c1·s`.
    pub fn linear(c0: Q, c1: Q) -> Poly {
        Poly::new(vec![c0, c1])
    }
    /// `Π (s − r)` over `roots`.
    pub fn from_roots(roots: &[Q]) -> Poly {
        roots
            .iter()
            .fold(Poly::constant(qi(1)), |p, r| p.mul(&Poly::linear(-r, qi(1))))
    }
    pub fn is_zero(&self) -> bool {
        self.0.is_empty()
    }
    /// The degree (0 for constants and for zero).
    pub fn degree(&self) -> usize {
        self.0.len().saturating_sub(1)
    }
    pub fn eval(&self, x: &Q) -> Q {
        self.0.iter().rev().fold(qi(0), |acc, c| acc * x + c)
    }
    fn deriv(&self) -> Poly {
        Poly::new(
            self.0
                .iter()
                .enumerate()
                .skip(1)
                .map(|(k, c)| c * qi(k as i64))
                .collect(),
        )
    }
    fn add(&self, o: &Poly) -> Poly {
        let n = self.0.len().max(o.0.len());
        let at = |p: &Poly, k: usize| p.0.get(k).cloned().unwrap_or_else(|| qi(0));
        Poly::new((0..n).map(|k| at(self, k) + at(o, k)).collect())
    }
    fn scale(&self, c: &Q) -> Poly {
        Poly::new(self.0.iter().map(|x| x * c).collect())
    }
    fn sub(&self, o: &Poly) -> Poly {
        self.add(&o.scale(&qi(-1)))
    }
    fn mul(&self, o: &Poly) -> Poly {
        if self.is_zero() || o.is_zero() {
            return Poly(Vec::new());
        }
        let mut c = vec![qi(0); self.0.len() + o.0.len() - 1];
        for (i, a) in self.0.iter().enumerate() {
            for (j, b) in o.0.iter().enumerate() {
                c[i + j] += a * b;
            }
        }
        Poly::new(c)
    }
    /// `1 + max |c_k / c_n|`: every zero has a smaller modulus.
    fn cauchy_bound(&self) -> Q {
        let l = self.0.last().expect("a non-zero polynomial");
        let m = self.0[..self.0.len() - 1]
            .iter()
            .map(|c| {
                let r = c / l;
                if sgn(&r) < 0 {
                    -r
                } else {
                    r
                }
            })
            .max()
            .unwrap_or_else(|| qi(0));
        m + qi(1)
    }
}

fn int_sgn(x: &BigInt) -> i32 {
    match x.sign() {
        Sign::Minus => -1,
        Sign::NoSign => 0,
        Sign::Plus => 1,
    }
}

fn int_abs(x: &BigInt) -> BigInt {
    if int_sgn(x) < 0 {
        -x
    } else {
        x.clone()
    }
}

fn int_gcd(a: &BigInt, b: &BigInt) -> BigInt {
    let (mut a, mut b) = (int_abs(a), int_abs(b));
    while int_sgn(&b) != 0 {
        let r = &a % &b;
        a = b;
        b = r;
    }
    a
}

/// A primitive polynomial over Z: a positive multiple of the polynomial it
/// was made from (the same signs everywhere), so that Sturm sequences and
/// gcds run without rational arithmetic.
#[derive(Clone, Debug)]
struct IPoly(Vec<BigInt>);

impl IPoly {
    /// Trailing zeros dropped, divided by the content.
    fn primitive(mut c: Vec<BigInt>) -> IPoly {
        while c.last().is_some_and(|x| int_sgn(x) == 0) {
            c.pop();
        }
        let g = c.iter().fold(BigInt::from(0), |g, x| int_gcd(&g, x));
        if int_sgn(&g) > 0 {
            for x in &mut c {
                *x = &*x / &g;
            }
        }
        IPoly(c)
    }

    /// `p` times the (positive) lcm of its denominators, made primitive.
    fn of(p: &Poly) -> IPoly {
        let lcm = p.0.iter().fold(BigInt::from(1), |l, c| {
            let d = c.denom();
            &l / int_gcd(&l, d) * d
        });
        IPoly::primitive(p.0.iter().map(|c| c.numer() * (&lcm / c.denom())).collect())
    }

    fn is_zero(&self) -> bool {
        self.0.is_empty()
    }

    fn degree(&self) -> usize {
        self.0.len().saturating_sub(1)
    }

    /// The sign at `x = n/d` (`d > 0`): of `Σ c_k n^k d^(deg − k)`.
    fn sign_at(&self, x: &Q) -> i32 {
        let Some(lead) = self.0.last() else { return 0 };
        let (n, d) = (x.numer(), x.denom());
        let (mut acc, mut dk) = (lead.clone(), BigInt::from(1));
        for c in self.0.iter().rev().skip(1) {
            dk *= d;
            acc = acc * n + c * &dk;
        }
        int_sgn(&acc)
    }

    fn deriv(&self) -> IPoly {
        IPoly::primitive(
            self.0
                .iter()
                .enumerate()
                .skip(1)
                .map(|(k, c)| c * BigInt::from(k))
                .collect(),
        )
    }

    /// A positive multiple of the remainder of `self` by `b` (pseudo-division
    /// with the multiplier `|lead(b)|`), made primitive.
    fn rem(&self, b: &IPoly) -> IPoly {
        let mut r = self.0.clone();
        let lb = b.0.last().expect("a non-zero divisor");
        let (mul, flip) = (int_abs(lb), int_sgn(lb));
        while r.len() >= b.0.len() {
            let k = r.len() - b.0.len();
            let lr = r.last().unwrap() * BigInt::from(flip);
            for x in &mut r {
                *x *= &mul;
            }
            for (j, bj) in b.0.iter().enumerate() {
                r[k + j] -= &lr * bj;
            }
            r.pop();
            while r.last().is_some_and(|x| int_sgn(x) == 0) {
                r.pop();
            }
        }
        IPoly::primitive(r)
    }

    /// `self / g` for a primitive `g` dividing it (Gauss: the quotient is
    /// integral).
    fn div_exact(&self, g: &IPoly) -> IPoly {
        let mut r = self.0.clone();
        let dn = g.0.len();
        let mut q = vec![BigInt::from(0); r.len() + 1 - dn];
        for k in (0..q.len()).rev() {
            let c = &r[k + dn - 1] / g.0.last().unwrap();
            for (j, gj) in g.0.iter().enumerate() {
                r[k + j] -= &c * gj;
            }
            q[k] = c;
        }
        assert!(r.iter().all(|x| int_sgn(x) == 0), "an exact division");
        IPoly::primitive(q)
    }

    fn gcd(&self, o: &IPoly) -> IPoly {
        let (mut a, mut b) = (self.clone(), o.clone());
        while !b.is_zero() {
            let r = a.rem(&b);
            a = b;
            b = r;
        }
        a
    }

    /// The square-free part: the same distinct zeros, all simple.
    fn squarefree(&self) -> IPoly {
        if self.degree() == 0 {
            return self.clone();
        }
        self.div_exact(&self.gcd(&self.deriv()))
    }

    fn neg(&self) -> IPoly {
        IPoly(self.0.iter().map(|x| -x).collect())
    }
}

/// The Sturm sequence of a square-free polynomial, each member scaled by a
/// positive number.
struct Sturm(Vec<IPoly>);

impl Sturm {
    fn new(p: &IPoly) -> Sturm {
        let mut chain = vec![p.clone()];
        if p.degree() >= 1 {
            chain.push(p.deriv());
            loop {
                let n = chain.len();
                let r = chain[n - 2].rem(&chain[n - 1]);
                if r.is_zero() {
                    break;
                }
                chain.push(r.neg());
            }
        }
        Sturm(chain)
    }
    /// Sign changes at `x`, zeros skipped.
    fn changes(&self, x: &Q) -> usize {
        let (mut last, mut n) = (0, 0);
        for p in &self.0 {
            let s = p.sign_at(x);
            if s != 0 {
                if last != 0 && s != last {
                    n += 1;
                }
                last = s;
            }
        }
        n
    }
    /// Distinct zeros in `(a, b]` (Sturm's theorem, `a < b`).
    fn count(&self, a: &Q, b: &Q) -> usize {
        self.changes(a)
            .checked_sub(self.changes(b))
            .expect("Sturm counts decrease")
    }
    /// Distinct zeros in the open `(a, b)`.
    fn count_open(&self, a: &Q, b: &Q) -> usize {
        self.count(a, b) - usize::from(self.0[0].sign_at(b) == 0)
    }
}

// ---------------------------------------------------------------------------
// Zeros on pieces of the line
// ---------------------------------------------------------------------------

/// A closed piece `[lo, hi]` of the line parameter and the square-free
/// polynomial whose zeros there are hits.
struct Piece {
    lo: Q,
    hi: Q,
    /// The polynomial as found (a positive multiple), multiple zeros and all.
    raw: IPoly,
    p: IPoly,
    sturm: Sturm,
    t: TOfS,
}

/// A distinct zero: exactly known, or the only zero of piece `piece`'s
/// polynomial in the open `(lo, hi)` (a simple one).
#[derive(Clone, Debug)]
pub enum Root {
    Exact(Q),
    Iso { piece: usize, lo: Q, hi: Q },
}

impl Piece {
    fn new(lo: Q, hi: Q, raw: &Poly, t: TOfS) -> Piece {
        let raw = IPoly::of(raw);
        let p = raw.squarefree();
        let sturm = Sturm::new(&p);
        Piece {
            lo,
            hi,
            raw,
            p,
            sturm,
            t,
        }
    }

    /// The sign of `q` at the zero isolated in `(lo, hi)`, exactly.
    fn sign_at_iso(&self, lo: &Q, hi: &Q, q: &IPoly) -> i32 {
        if q.degree() == 0 {
            return q.0.first().map_or(0, int_sgn);
        }
        if q.degree() == 1 {
            // The zero against c = −q0/q1: by the sign of p at c.
            let c = Q::new(-&q.0[0], q.0[1].clone());
            let side = if &c <= lo {
                1
            } else if &c >= hi {
                -1
            } else {
                match self.p.sign_at(&c) {
                    0 => 0,
                    x if x == self.sign_right_of(lo) => 1,
                    _ => -1,
                }
            };
            return side * int_sgn(&q.0[1]);
        }
        // A common zero with p in (lo, hi) is the zero itself.
        let g = self.p.gcd(q);
        if g.degree() >= 1 && Sturm::new(&g).count_open(lo, hi) >= 1 {
            return 0;
        }
        let qs = Sturm::new(&q.squarefree());
        let (mut lo, mut hi) = (lo.clone(), hi.clone());
        loop {
            if qs.count(&lo, &hi) == 0 && q.sign_at(&lo) != 0 {
                return q.sign_at(&((&lo + &hi) / qi(2)));
            }
            if let Some(x) = self.bisect(&mut lo, &mut hi) {
                return q.sign_at(&x);
            }
        }
    }

    /// The sign of the raw polynomial's derivative at a zero in this piece:
    /// 0 for a multiple zero (a tangency).
    fn slope_at(&self, r: &Root) -> i32 {
        let d = self.raw.deriv();
        match r {
            Root::Exact(x) => d.sign_at(x),
            Root::Iso { lo, hi, .. } => self.sign_at_iso(lo, hi, &d),
        }
    }

    /// Every distinct zero in the closed piece.
    fn roots(&self, k: usize) -> Vec<Root> {
        let mut out = Vec::new();
        if self.p.sign_at(&self.lo) == 0 {
            out.push(Root::Exact(self.lo.clone()));
        }
        if self.hi == self.lo {
            return out;
        }
        if self.p.sign_at(&self.hi) == 0 {
            out.push(Root::Exact(self.hi.clone()));
        }
        let mut stack = vec![(self.lo.clone(), self.hi.clone())];
        while let Some((a, b)) = stack.pop() {
            match self.sturm.count_open(&a, &b) {
                0 => {}
                1 => out.push(Root::Iso { piece: k, lo: a, hi: b }),
                _ => {
                    let m = (&a + &b) / qi(2);
                    if self.p.sign_at(&m) == 0 {
                        out.push(Root::Exact(m.clone()));
                    }
                    stack.push((a, m.clone()));
                    stack.push((m, b));
                }
            }
        }
        out
    }

    /// The sign of `p` on `(lo, r)` for the zero `r` isolated in `(lo, hi)`.
    fn sign_right_of(&self, lo: &Q) -> i32 {
        match self.p.sign_at(lo) {
            0 => self.p.deriv().sign_at(lo),
            s => s,
        }
    }

    /// One bisection step of an isolating interval: the zero itself if the
    /// midpoint is it.
    fn bisect(&self, lo: &mut Q, hi: &mut Q) -> Option<Q> {
        let s = self.sign_right_of(lo);
        let m = (&*lo + &*hi) / qi(2);
        match self.p.sign_at(&m) {
            0 => return Some(m),
            x if x == s => *lo = m,
            _ => *hi = m,
        }
        None
    }
}

/// The line `s ↦ (u(s), v(s))` in the parameter domain.
#[derive(Clone, Debug)]
pub struct Line {
    pub u: Poly,
    pub v: Poly,
}

/// `t(s) = num(s) / den(s)` on a piece, `den > 0` there.
#[derive(Clone, Debug)]
pub struct TOfS {
    pub num: Poly,
    pub den: Poly,
}

impl TOfS {
    /// `t = s`.
    fn identity() -> TOfS {
        TOfS {
            num: Poly::linear(qi(0), qi(1)),
            den: Poly::constant(qi(1)),
        }
    }
}

/// One piece of a [`Restriction`]: `[lo, hi]`, the polynomial whose zeros
/// there are the hits, and `t` there.
#[derive(Clone, Debug)]
pub struct RPiece {
    pub lo: Q,
    pub hi: Q,
    pub p: Poly,
    pub t: TOfS,
}

/// The exact hits of the ray's line with the closed patch.
pub struct Truth {
    pub line: Line,
    pieces: Vec<Piece>,
    /// The distinct zeros, any `t`.
    pub roots: Vec<Root>,
    /// Per zero: the line crosses the surface there transversally (a simple
    /// zero; on a knot line shared by two pieces, both one-sided slopes
    /// non-zero and of one sign: not a tangency, not a touch of a crease).
    pub transversal: Vec<bool>,
    /// A piece's polynomial vanishes identically: a curve of hits.
    pub degenerate: bool,
}

impl Truth {
    /// The referee's answer for `case`.
    pub fn of(case: &Case) -> Truth {
        let r = restrict(case);
        let (mut pieces, mut roots, mut degenerate) = (Vec::new(), Vec::<Root>::new(), false);
        let (mut slopes, mut transversal) = (Vec::new(), Vec::new());
        for rp in r.pieces {
            if rp.p.is_zero() {
                degenerate = true;
                continue;
            }
            let piece = Piece::new(rp.lo, rp.hi, &rp.p, rp.t);
            for root in piece.roots(pieces.len()) {
                let slope = piece.slope_at(&root);
                // A zero on a knot line shared by two pieces is one hit,
                // a crossing if both pieces cross the same way.
                let seen = match &root {
                    Root::Exact(x) => roots.iter().position(|r| matches!(r, Root::Exact(y) if y == x)),
                    Root::Iso { .. } => None,
                };
                match seen {
                    Some(j) => transversal[j] = transversal[j] && slope != 0 && slope == slopes[j],
                    None => {
                        roots.push(root);
                        slopes.push(slope);
                        transversal.push(slope != 0);
                    }
                }
            }
            pieces.push(piece);
        }
        Truth {
            line: r.line,
            pieces,
            roots,
            transversal,
            degenerate,
        }
    }

    /// The sign of `q` at the zero `r`, exactly.
    pub fn sign_at(&self, r: &Root, q: &Poly) -> i32 {
        match r {
            Root::Exact(x) => sgn(&q.eval(x)),
            Root::Iso { piece, lo, hi } => self.pieces[*piece].sign_at_iso(lo, hi, &IPoly::of(q)),
        }
    }

    /// The zero within `2^-bits` of its piece's length, as a rational.
    pub fn approx(&self, r: &Root, bits: usize) -> Q {
        match r {
            Root::Exact(x) => x.clone(),
            Root::Iso { piece, lo, hi } => {
                let (mut lo, mut hi) = (lo.clone(), hi.clone());
                for _ in 0..bits {
                    if let Some(x) = self.pieces[*piece].bisect(&mut lo, &mut hi) {
                        return x;
                    }
                }
                (lo + hi) / qi(2)
            }
        }
    }

    /// A piece holding the zero (`t` is continuous: either piece at a
    /// shared end).
    fn piece_of(&self, r: &Root) -> &Piece {
        match r {
            Root::Iso { piece, .. } => &self.pieces[*piece],
            Root::Exact(x) => self
                .pieces
                .iter()
                .find(|p| &p.lo <= x && x <= &p.hi)
                .expect("a zero lies on a piece"),
        }
    }

    /// `(u, v, t)` of the zero, rounded (`bits`: bisections of an isolating
    /// interval first).
    pub fn uvt(&self, r: &Root, bits: usize) -> [f64; 3] {
        let s = self.approx(r, bits);
        let (l, t) = (&self.line, &self.piece_of(r).t);
        [
            nearest(&l.u.eval(&s)),
            nearest(&l.v.eval(&s)),
            nearest(&(t.num.eval(&s) / t.den.eval(&s))),
        ]
    }

    /// `lo ≤ f(r) ≤ hi` for `f = num / den` (`den > 0`); infinite ends are
    /// no constraint.
    fn within(&self, r: &Root, num: &Poly, den: &Poly, range: [f64; 2]) -> bool {
        let lo_ok = range[0] == f64::NEG_INFINITY || self.sign_at(r, &num.sub(&den.scale(&qf(range[0])))) >= 0;
        let hi_ok = range[1] == f64::INFINITY || self.sign_at(r, &den.scale(&qf(range[1])).sub(num)) >= 0;
        lo_ok && hi_ok
    }

    /// The zero's `(u, v)` lies in the closed box.
    pub fn in_uv(&self, r: &Root, bx: &HitBox) -> bool {
        let one = Poly::constant(qi(1));
        self.within(r, &self.line.u, &one, bx.u) && self.within(r, &self.line.v, &one, bx.v)
    }

    /// The zero's `t` lies in the closed range.
    pub fn in_t(&self, r: &Root, t: [f64; 2]) -> bool {
        let f = &self.piece_of(r).t;
        self.within(r, &f.num, &f.den, t)
    }
}

// ---------------------------------------------------------------------------
// The patch in exact arithmetic
// ---------------------------------------------------------------------------

enum Kind {
    Tensor(usize, usize),
    Triangle(usize),
    Bspline {
        p: usize,
        q: usize,
        ku: Vec<Q>,
        kv: Vec<Q>,
        nu: usize,
        nv: usize,
    },
}

/// A case's patch as exact rationals: `x`, `z`, weights.
struct Surface {
    kind: Kind,
    x: Vec<Q>,
    z: Vec<Q>,
    w: Option<Vec<Q>>,
    /// The parameter domain `[u0, u1] × [v0, v1]` (triangles: `u + v ≤ 1` too).
    dom: [Q; 4],
}

fn binom(n: usize, k: usize) -> i64 {
    (0..k).fold(1i64, |acc, i| acc * (n - i) as i64 / (i + 1) as i64)
}

fn powq(x: &Q, k: usize) -> Q {
    (0..k).fold(qi(1), |acc, _| acc * x)
}

fn bernstein(n: usize, x: &Q) -> Vec<Q> {
    let y = qi(1) - x;
    (0..=n)
        .map(|i| qi(binom(n, i)) * powq(x, i) * powq(&y, n - i))
        .collect()
}

/// The `p + 1` B-spline basis functions of span `span` at `x` (the span's
/// polynomials, The NURBS Book A2.2), for `N_{span−p}, …, N_span`.
fn bspline_basis(k: &[Q], p: usize, span: usize, x: &Q) -> Vec<Q> {
    let mut n = vec![qi(0); p + 1];
    n[0] = qi(1);
    let (mut left, mut right) = (vec![qi(0); p + 1], vec![qi(0); p + 1]);
    for j in 1..=p {
        left[j] = x - &k[span + 1 - j];
        right[j] = &k[span + j] - x;
        let mut saved = qi(0);
        for r in 0..j {
            let temp = &n[r] / (&right[r + 1] + &left[j - r]);
            n[r] = &saved + &right[r + 1] * &temp;
            saved = &left[j - r] * &temp;
        }
        n[j] = saved;
    }
    n
}

/// The span `[k_a, k_{a+1})` (of positive length) holding `x`, clamped to the domain.
fn span_of(k: &[Q], p: usize, ncp: usize, x: &Q) -> usize {
    (p..ncp).rfind(|&a| k[a] < k[a + 1] && &k[a] <= x).unwrap_or(p)
}

/// The Greville abscissae `(k_{i+1} + … + k_{i+p}) / p`.
fn greville(k: &[Q], p: usize, ncp: usize) -> Vec<Q> {
    (0..ncp)
        .map(|i| k[i + 1..=i + p].iter().fold(qi(0), |a, x| a + x) / qi(p as i64))
        .collect()
}

impl Surface {
    /// The patch of `case`, its affine claim checked exactly.
    fn of(case: &Case) -> Surface {
        let [a, x0, b, y0] = case.affine.map(qf);
        let check = |pt: &[f64; 3], u: &Q, v: &Q| {
            assert!(
                qf(pt[0]) == &x0 + &a * u && qf(pt[1]) == &y0 + &b * v,
                "adversary: the patch breaks its affine map at {pt:?}"
            );
        };
        let zs = |pts: &[[f64; 3]]| pts.iter().map(|p| qf(p[2])).collect::<Vec<_>>();
        let xs = |pts: &[[f64; 3]]| pts.iter().map(|p| qf(p[0])).collect::<Vec<_>>();
        let unit = [qi(0), qi(1), qi(0), qi(1)];
        match &case.spec {
            PatchSpec::Tensor {
                degree: [m, n],
                points,
                weights,
            } => {
                for i in 0..=*m {
                    for j in 0..=*n {
                        let ui = Q::new(BigInt::from(i), BigInt::from(*m));
                        let vj = Q::new(BigInt::from(j), BigInt::from(*n));
                        check(&points[i * (n + 1) + j], &ui, &vj);
                        if let Some(w) = weights {
                            assert!(w[i * (n + 1) + j] == w[i * (n + 1)], "adversary: weights must be α_i");
                        }
                    }
                }
                let w = weights.as_ref().map(|w| w.iter().map(|&x| qf(x)).collect());
                Surface {
                    kind: Kind::Tensor(*m, *n),
                    x: xs(points),
                    z: zs(points),
                    w,
                    dom: unit,
                }
            }
            PatchSpec::Triangle {
                degree,
                points,
                weights,
            } => {
                assert!(weights.is_none(), "adversary: rational triangles are not refereed");
                let n = *degree;
                let mut k = 0;
                for j in 0..=n {
                    for i in 0..=n - j {
                        let ui = Q::new(BigInt::from(i), BigInt::from(n));
                        let vj = Q::new(BigInt::from(j), BigInt::from(n));
                        check(&points[k], &ui, &vj);
                        k += 1;
                    }
                }
                Surface {
                    kind: Kind::Triangle(n),
                    x: xs(points),
                    z: zs(points),
                    w: None,
                    dom: unit,
                }
            }
            PatchSpec::Bspline {
                degree: [p, q],
                knots_u,
                knots_v,
                points,
                weights,
            } => {
                let ku: Vec<Q> = knots_u.iter().map(|&x| qf(x)).collect();
                let kv: Vec<Q> = knots_v.iter().map(|&x| qf(x)).collect();
                let (nu, nv) = (ku.len() - p - 1, kv.len() - q - 1);
                let (gu, gv) = (greville(&ku, *p, nu), greville(&kv, *q, nv));
                for i in 0..nu {
                    for j in 0..nv {
                        check(&points[i * nv + j], &gu[i], &gv[j]);
                        if let Some(w) = weights {
                            assert!(w[i * nv + j] == w[i * nv], "adversary: weights must be α_i");
                        }
                    }
                }
                let dom = [ku[*p].clone(), ku[nu].clone(), kv[*q].clone(), kv[nv].clone()];
                Surface {
                    kind: Kind::Bspline {
                        p: *p,
                        q: *q,
                        ku,
                        kv,
                        nu,
                        nv,
                    },
                    x: xs(points),
                    z: zs(points),
                    w: weights.as_ref().map(|w| w.iter().map(|&x| qf(x)).collect()),
                    dom,
                }
            }
            other => panic!("adversary: unknown patch {other:?}"),
        }
    }

    /// The degree of the height along a line, a bound.
    fn line_degree(&self) -> usize {
        match &self.kind {
            Kind::Tensor(m, n) => m + n,
            Kind::Triangle(n) => *n,
            Kind::Bspline { p, q, .. } => p + q,
        }
    }

    /// The cell (B-spline spans) holding `(u, v)`.
    fn cell_of(&self, u: &Q, v: &Q) -> (usize, usize) {
        match &self.kind {
            Kind::Bspline { p, q, ku, kv, nu, nv } => (span_of(ku, *p, *nu, u), span_of(kv, *q, *nv, v)),
            _ => (0, 0),
        }
    }

    /// `(Σ w x B, Σ w z B, Σ w B)` at `(u, v)`, with the polynomials of `cell`.
    fn hom(&self, u: &Q, v: &Q, cell: (usize, usize)) -> [Q; 3] {
        let mut acc = [qi(0), qi(0), qi(0)];
        let mut add = |idx: usize, basis: Q| {
            let wb = match &self.w {
                Some(w) => &w[idx] * basis,
                None => basis,
            };
            acc[0] += &self.x[idx] * &wb;
            acc[1] += &self.z[idx] * &wb;
            acc[2] += wb;
        };
        match &self.kind {
            Kind::Tensor(m, n) => {
                let (bu, bv) = (bernstein(*m, u), bernstein(*n, v));
                for (i, bi) in bu.iter().enumerate() {
                    for (j, bj) in bv.iter().enumerate() {
                        add(i * (n + 1) + j, bi * bj);
                    }
                }
            }
            Kind::Triangle(n) => {
                let w = qi(1) - u - v;
                let mut k = 0;
                for j in 0..=*n {
                    for i in 0..=n - j {
                        let c = qi(binom(*n, i) * binom(n - i, j));
                        add(k, c * powq(u, i) * powq(v, j) * powq(&w, n - i - j));
                        k += 1;
                    }
                }
            }
            Kind::Bspline { p, q, ku, kv, nv, .. } => {
                let (bu, bv) = (bspline_basis(ku, *p, cell.0, u), bspline_basis(kv, *q, cell.1, v));
                for (r, nu_r) in bu.iter().enumerate() {
                    for (c, nv_c) in bv.iter().enumerate() {
                        add((cell.0 - p + r) * nv + (cell.1 - q + c), nu_r * nv_c);
                    }
                }
            }
        }
        acc
    }

    /// The height `z(u, v)`, exactly.
    fn height(&self, u: &Q, v: &Q) -> Q {
        let [_, z, w] = self.hom(u, v, self.cell_of(u, v));
        z / w
    }

    /// Linear forms in `(u, v)` that are `≥ 0` exactly on the domain.
    fn constraints(&self, u: &Poly, v: &Poly) -> Vec<Poly> {
        let [u0, u1, v0, v1] = &self.dom;
        let c = |x: &Q| Poly::constant(x.clone());
        let mut out = vec![u.sub(&c(u0)), c(u1).sub(u), v.sub(&c(v0)), c(v1).sub(v)];
        if matches!(self.kind, Kind::Triangle(_)) {
            out.push(c(&qi(1)).sub(u).sub(v));
        }
        out
    }

    /// `(u, v)` lies in the closed domain.
    fn contains(&self, u: &Q, v: &Q) -> bool {
        self.constraints(&Poly::constant(u.clone()), &Poly::constant(v.clone()))
            .iter()
            .all(|c| c.0.first().map_or(0, sgn) >= 0)
    }

    /// The distance (in parameters, rounded) from `(u, v)` to the nearest
    /// edge or interior knot line.
    fn feature_distance(&self, [u, v, _]: [f64; 3]) -> f64 {
        let (mut us, mut vs): (Vec<f64>, Vec<f64>) = (vec![0.0, 1.0], vec![0.0, 1.0]);
        if let Kind::Bspline { ku, kv, .. } = &self.kind {
            us = ku.iter().map(nearest).collect();
            vs = kv.iter().map(nearest).collect();
        }
        let d = |x: f64, cs: &[f64]| cs.iter().map(|c| (x - c).abs()).fold(f64::INFINITY, f64::min);
        let hyp = if matches!(self.kind, Kind::Triangle(_)) {
            (1.0 - u - v).abs()
        } else {
            f64::INFINITY
        };
        d(u, &us).min(d(v, &vs)).min(hyp)
    }

    /// The values of `s` at which the line crosses an interior knot line.
    fn breaks(&self, u: &Poly, v: &Poly) -> Vec<Q> {
        let Kind::Bspline { ku, kv, .. } = &self.kind else {
            return Vec::new();
        };
        let mut out = Vec::new();
        for (line, knots, lo, hi) in [(u, ku, &self.dom[0], &self.dom[1]), (v, kv, &self.dom[2], &self.dom[3])] {
            if line.degree() == 1 {
                for k in knots.iter().filter(|k| *k > lo && *k < hi) {
                    out.push((k - &line.0[0]) / &line.0[1]);
                }
            }
        }
        out
    }
}

/// The closed interval of `s` on which every form is `≥ 0` (`None`: empty;
/// an end `None`: unbounded).
fn clip(forms: &[Poly]) -> Option<(Option<Q>, Option<Q>)> {
    let (mut lo, mut hi): (Option<Q>, Option<Q>) = (None, None);
    for f in forms {
        match f.degree() {
            0 => {
                if f.0.first().map_or(0, sgn) < 0 {
                    return None;
                }
            }
            _ => {
                let r = -&f.0[0] / &f.0[1];
                if sgn(&f.0[1]) > 0 {
                    lo = Some(lo.map_or(r.clone(), |l| l.max(r)));
                } else {
                    hi = Some(hi.map_or(r.clone(), |h| h.min(r)));
                }
            }
        }
    }
    match (&lo, &hi) {
        (Some(l), Some(h)) if l > h => None,
        _ => Some((lo, hi)),
    }
}

/// The polynomial through `(xs[i], ys[i])` (Newton's divided differences).
fn interpolate(xs: &[Q], ys: &[Q]) -> Poly {
    let n = xs.len();
    let mut c = ys.to_vec();
    for j in 1..n {
        for i in (j..n).rev() {
            c[i] = (&c[i] - &c[i - 1]) / (&xs[i] - &xs[i - j]);
        }
    }
    let mut p = Poly::constant(c[n - 1].clone());
    for i in (0..n - 1).rev() {
        p = p.mul(&Poly::linear(-&xs[i], qi(1))).add(&Poly::constant(c[i].clone()));
    }
    p
}

/// `deg + 1` points strictly inside `[lo, hi]` (`lo < hi`).
fn samples(lo: &Q, hi: &Q, deg: usize) -> Vec<Q> {
    (0..=deg)
        .map(|i| lo + (hi - lo) * Q::new(BigInt::from(i + 1), BigInt::from(deg + 2)))
        .collect()
}

/// The ray's line restricted to the patch: consecutive closed pieces of the
/// line parameter, on each the exact polynomial whose zeros are the hits
/// (the B-spline's cells, a single piece for Bézier patches).
pub struct Restriction {
    pub line: Line,
    pub pieces: Vec<RPiece>,
}

/// See [`Restriction`] and the module docs.
pub fn restrict(case: &Case) -> Restriction {
    let surf = Surface::of(case);
    let [ox, oy, oz] = case.origin.map(qf);
    let [dx, dy, dz] = case.dir.map(qf);
    let [a, x0, b, y0] = case.affine.map(qf);
    if surf.w.is_some() {
        return restrict_rational(&surf, case);
    }
    // s = t: u(t), v(t) affine.
    let line = Line {
        u: Poly::linear((&ox - &x0) / &a, &dx / &a),
        v: Poly::linear((&oy - &y0) / &b, &dy / &b),
    };
    let piece = |lo: Q, hi: Q, p: Poly| RPiece {
        lo,
        hi,
        p,
        t: TOfS::identity(),
    };
    let deg = surf.line_degree() + 1;
    let on_cell = |s: &Q, cell: (usize, usize)| {
        let [_, z, w] = surf.hom(&line.u.eval(s), &line.v.eval(s), cell);
        z / w - &oz - &dz * s
    };
    let cell_at = |s: &Q| surf.cell_of(&line.u.eval(s), &line.v.eval(s));
    let fit = |lo: &Q, hi: &Q| {
        let cell = cell_at(&((lo + hi) / qi(2)));
        let xs = samples(lo, hi, deg);
        let ys: Vec<Q> = xs.iter().map(|s| on_cell(s, cell)).collect();
        interpolate(&xs, &ys)
    };
    let mut pieces = Vec::new();
    match clip(&surf.constraints(&line.u, &line.v)) {
        None => {}
        Some((Some(lo), Some(hi))) => {
            let mut cuts: Vec<Q> = surf
                .breaks(&line.u, &line.v)
                .into_iter()
                .filter(|s| *s > lo && *s < hi)
                .collect();
            cuts.push(lo.clone());
            cuts.push(hi.clone());
            cuts.sort();
            cuts.dedup();
            if lo == hi {
                // The line touches the domain at one point: the piece is
                // that point, its polynomial the cell's there.
                let cell = cell_at(&lo);
                let xs = samples(&lo, &(&lo + qi(1)), deg);
                let ys: Vec<Q> = xs.iter().map(|s| on_cell(s, cell)).collect();
                pieces.push(piece(lo.clone(), lo, interpolate(&xs, &ys)));
            }
            for w in cuts.windows(2) {
                pieces.push(piece(w[0].clone(), w[1].clone(), fit(&w[0], &w[1])));
            }
        }
        Some(_) => {
            // A vertical ray: u, v constant, the line meets the patch at one
            // point for every t; its zero is bounded by Cauchy's bound.
            assert!(line.u.degree() == 0 && line.v.degree() == 0, "a bounded domain");
            let p = fit(&qi(-1), &qi(1));
            let bound = if p.is_zero() { qi(1) } else { p.cauchy_bound() };
            pieces.push(piece(-&bound, bound, p));
        }
    }
    Restriction { line, pieces }
}

/// A rational tensor or NURBS patch (`w_ij = α_i`) and a ray with `dy = 0`:
/// `s = u`, `v = v*`, hits the zeros of `dx·(N_z − oz·D) − dz·(N_x − ox·D)`
/// (per knot span in `u`), `t = (x − ox)/dx` (or `(z − oz)/dz` for `dx = 0`).
fn restrict_rational(surf: &Surface, case: &Case) -> Restriction {
    let [ox, oy, oz] = case.origin.map(qf);
    let [dx, dy, dz] = case.dir.map(qf);
    let [_, _, b, y0] = case.affine.map(qf);
    assert!(sgn(&dy) == 0, "adversary: rays on rational patches need dy = 0");
    let vstar = (&oy - &y0) / &b;
    let line = Line {
        u: Poly::linear(qi(0), qi(1)),
        v: Poly::constant(vstar.clone()),
    };
    let [u0, u1, v0, v1] = &surf.dom;
    if vstar < *v0 || vstar > *v1 {
        return Restriction {
            line,
            pieces: Vec::new(),
        };
    }
    let (deg, knots) = match &surf.kind {
        Kind::Tensor(m, _) => (*m, Vec::new()),
        Kind::Bspline { p, ku, .. } => (*p, ku.iter().filter(|k| *k > u0 && *k < u1).cloned().collect()),
        Kind::Triangle(_) => panic!("adversary: rational triangles are not refereed"),
    };
    let mut cuts = knots;
    cuts.push(u0.clone());
    cuts.push(u1.clone());
    cuts.sort();
    cuts.dedup();
    // t = num / den, den > 0 (flip both for a negative dx, or dz when dx = 0).
    let flip = if sgn(&dx) < 0 || (sgn(&dx) == 0 && sgn(&dz) < 0) {
        qi(-1)
    } else {
        qi(1)
    };
    let pieces = cuts
        .windows(2)
        .map(|w| {
            let cell = surf.cell_of(&((&w[0] + &w[1]) / qi(2)), &vstar);
            let xs = samples(&w[0], &w[1], deg);
            let rows: Vec<[Q; 3]> = xs.iter().map(|u| surf.hom(u, &vstar, cell)).collect();
            let fit = |f: &dyn Fn(&[Q; 3]) -> Q| interpolate(&xs, &rows.iter().map(f).collect::<Vec<_>>());
            let p = fit(&|[nx, nz, d]| &dx * (nz - &oz * d) - &dz * (nx - &ox * d));
            let t = if sgn(&dx) != 0 {
                TOfS {
                    num: fit(&|[nx, _, d]| &flip * (nx - &ox * d)),
                    den: fit(&|[_, _, d]| &flip * &dx * d),
                }
            } else {
                TOfS {
                    num: fit(&|[_, nz, d]| &flip * (nz - &oz * d)),
                    den: fit(&|[_, _, d]| &flip * &dz * d),
                }
            };
            RPiece {
                lo: w[0].clone(),
                hi: w[1].clone(),
                p,
                t,
            }
        })
        .collect();
    Restriction { line, pieces }
}

// ---------------------------------------------------------------------------
// The generator
// ---------------------------------------------------------------------------

/// A patch family; see the module docs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Family {
    Tensor,
    Rational,
    Triangle,
    Bspline,
    Nurbs,
}

impl Family {
    pub const ALL: [Family; 5] = [
        Family::Tensor,
        Family::Rational,
        Family::Triangle,
        Family::Bspline,
        Family::Nurbs,
    ];

    /// Rays of this family have `dy = 0` (the referee's rational path).
    fn rational(self) -> bool {
        matches!(self, Family::Rational | Family::Nurbs)
    }

    pub fn name(self) -> &'static str {
        match self {
            Family::Tensor => "tensor",
            Family::Rational => "rational",
            Family::Triangle => "triangle",
            Family::Bspline => "bspline",
            Family::Nurbs => "nurbs",
        }
    }

    pub fn parse(s: &str) -> Option<Family> {
        Family::ALL.into_iter().find(|f| f.name() == s)
    }
}

/// splitmix64 (Steele, Lea, Flood 2014): a seeded stream, the same on every machine.
#[derive(Clone, Debug)]
pub struct Mix(pub u64);

impl Mix {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    /// Uniform in `[0, 1)`, 53 random bits.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * pow2(-53)
    }
    /// Uniform in `[−1, 1)`.
    pub fn signed(&mut self) -> f64 {
        2.0 * self.unit() - 1.0
    }
    /// Uniform in `lo..=hi`.
    pub fn range(&mut self, lo: i64, hi: i64) -> i64 {
        lo + (self.next_u64() % (hi - lo + 1) as u64) as i64
    }
    pub fn chance(&mut self, p: f64) -> bool {
        self.unit() < p
    }
    pub fn pick<T: Copy>(&mut self, xs: &[T]) -> T {
        xs[self.range(0, xs.len() as i64 - 1) as usize]
    }
}

/// One adversarial case: a patch (exact `f64` data), the affine map
/// `[a, x0, b, y0]` that makes `x = a·u + x0`, `y = b·v + y0` (polynomial
/// patches), and a ray.
#[derive(Clone, Debug)]
pub struct Case {
    pub family: Family,
    pub seed: u64,
    /// How the ray was built (feature, construction, perturbation).
    pub label: String,
    pub spec: PatchSpec,
    pub affine: [f64; 4],
    pub origin: [f64; 3],
    pub dir: [f64; 3],
}

/// A line in the domain a ray can run along.
#[derive(Clone, Copy, Debug)]
enum Along {
    /// `u = c`, `v` varying.
    U(f64),
    /// `v = c`.
    V(f64),
    /// The hypotenuse `u + v = 1` of a triangle.
    Hyp,
}

/// A point on a feature of the domain.
#[derive(Clone, Debug)]
struct Target {
    name: String,
    u: f64,
    v: f64,
    along: Option<Along>,
}

fn target(name: impl Into<String>, u: f64, v: f64, along: Option<Along>) -> Target {
    Target {
        name: name.into(),
        u,
        v,
        along,
    }
}

/// A patch with its affine map, domain, and the features to aim at.
struct Grid {
    spec: PatchSpec,
    affine: [f64; 4],
    dom: [f64; 4],
    targets: Vec<Target>,
    /// On the heights, for the label.
    note: String,
    /// `Some(c)`: `∂z/∂u = 0` along the edge `u = c`.
    flat_edge: Option<f64>,
}

/// `k/64` for a random `1 ≤ k ≤ 63`.
fn dyadic01(rng: &mut Mix) -> f64 {
    rng.range(1, 63) as f64 / 64.0
}

/// Heights and a note on them: full-precision in `[−1, 1)` (most cases),
/// multiples of `1/256` (exact ties: hits exactly on edges), or nearly flat,
/// `c + ε·r` with `ε` down to `2^-50` (a ray at height `c` runs almost in the
/// surface: many hits, or a ridge of near-tangency).
fn heights(rng: &mut Mix, count: usize) -> (Vec<f64>, String) {
    match rng.range(0, 9) {
        0 | 1 => (
            (0..count).map(|_| rng.range(-256, 256) as f64 / 256.0).collect(),
            "coarse z".into(),
        ),
        2 | 3 => {
            let c = rng.signed();
            let e = rng.pick(&[-10, -20, -30, -40, -50]);
            let z = (0..count).map(|_| c + pow2(e) * rng.signed()).collect();
            (z, format!("flat z (2^{e})"))
        }
        _ => ((0..count).map(|_| rng.signed()).collect(), String::new()),
    }
}

/// `[hx, x0, hy, y0]`: grid steps and offsets, dyadic.
fn steps(rng: &mut Mix) -> [f64; 4] {
    let step = [0.25, 0.5, 0.75, 1.0, 1.5];
    let offset = [0.0, -0.5, 0.25, -3.0, 1024.5, 1048576.5, -196608.25];
    [rng.pick(&step), rng.pick(&offset), rng.pick(&step), rng.pick(&offset)]
}

/// The four corners and four edges of `[u0, u1] × [v0, v1]`, and the interior.
fn box_targets(rng: &mut Mix, [u0, u1, v0, v1]: [f64; 4]) -> Vec<Target> {
    let mut out = Vec::new();
    for (cu, cv) in [(u0, v0), (u0, v1), (u1, v0), (u1, v1)] {
        let along = if rng.chance(0.5) { Along::U(cu) } else { Along::V(cv) };
        out.push(target(format!("corner ({cu}, {cv})"), cu, cv, Some(along)));
    }
    let (su, sv) = (u0 + (u1 - u0) * dyadic01(rng), v0 + (v1 - v0) * dyadic01(rng));
    for cu in [u0, u1] {
        out.push(target(format!("edge u={cu}"), cu, sv, Some(Along::U(cu))));
    }
    for cv in [v0, v1] {
        out.push(target(format!("edge v={cv}"), su, cv, Some(Along::V(cv))));
    }
    out.push(target("interior", su, sv, None));
    out
}

/// `α_0 … α_m`: positive, random, in `[1/4, 2)` or (one time in four) over
/// `2^±6`.
fn alphas(rng: &mut Mix, m: usize) -> Vec<f64> {
    let extreme = rng.chance(0.25);
    (0..=m)
        .map(|_| {
            if extreme {
                pow2(rng.range(-6, 6)) * (1.0 + rng.unit())
            } else {
                0.25 + 1.75 * rng.unit()
            }
        })
        .collect()
}

/// Rational patches take rays with `dy = 0` only: no line `u = c` to run along.
fn only_rows(targets: &mut [Target]) {
    for t in targets {
        if matches!(t.along, Some(Along::U(_))) {
            t.along = Some(Along::V(t.v));
        }
    }
}

fn tensor_grid(rng: &mut Mix, rational: bool) -> Grid {
    let (m, n) = (rng.range(1, 4) as usize, rng.range(1, 4) as usize);
    let [hx, x0, hy, y0] = steps(rng);
    let (mut z, mut note) = heights(rng, (m + 1) * (n + 1));
    let flat_edge = (m >= 2 && rng.chance(0.2)).then(|| {
        // Rows m and m − 1 equal: ∂z/∂u = 0 along u = 1.
        z.copy_within((m - 1) * (n + 1)..m * (n + 1), m * (n + 1));
        note += " flat edge";
        1.0
    });
    let points = (0..=m)
        .flat_map(|i| (0..=n).map(move |j| (i, j)))
        .map(|(i, j)| [x0 + hx * i as f64, y0 + hy * j as f64, z[i * (n + 1) + j]])
        .collect();
    let weights = rational.then(|| alphas(rng, m).into_iter().flat_map(|a| vec![a; n + 1]).collect());
    let mut targets = box_targets(rng, [0.0, 1.0, 0.0, 1.0]);
    if rational {
        only_rows(&mut targets);
    }
    Grid {
        spec: PatchSpec::Tensor {
            degree: [m, n],
            points,
            weights,
        },
        affine: [hx * m as f64, x0, hy * n as f64, y0],
        dom: [0.0, 1.0, 0.0, 1.0],
        targets,
        note,
        flat_edge,
    }
}

fn triangle_grid(rng: &mut Mix) -> Grid {
    let n = rng.range(1, 4) as usize;
    let [hx, x0, hy, y0] = steps(rng);
    let (mut z, mut note) = heights(rng, (n + 1) * (n + 2) / 2);
    let flat_edge = (n >= 2 && rng.chance(0.2)).then(|| {
        // z(1, j) = z(0, j): ∂z/∂u = 0 along u = 0 (points (i, j) stored
        // j outer, i inner).
        let mut start = 0;
        for j in 0..n {
            z[start + 1] = z[start];
            start += n - j + 1;
        }
        note += " flat edge";
        0.0
    });
    let points = (0..=n)
        .flat_map(|j| (0..=n - j).map(move |i| (i, j)))
        .zip(&z)
        .map(|((i, j), &z)| [x0 + hx * i as f64, y0 + hy * j as f64, z])
        .collect();
    let r = dyadic01(rng);
    let targets = vec![
        target("corner (0, 0)", 0.0, 0.0, Some(Along::U(0.0))),
        target(
            "corner (1, 0)",
            1.0,
            0.0,
            Some(if rng.chance(0.5) { Along::V(0.0) } else { Along::Hyp }),
        ),
        target(
            "corner (0, 1)",
            0.0,
            1.0,
            Some(if rng.chance(0.5) { Along::U(0.0) } else { Along::Hyp }),
        ),
        target("edge u=0", 0.0, r, Some(Along::U(0.0))),
        target("edge v=0", r, 0.0, Some(Along::V(0.0))),
        target("hypotenuse", r, 1.0 - r, Some(Along::Hyp)),
        target("interior", r / 2.0, (1.0 - r) / 2.0, None),
    ];
    Grid {
        spec: PatchSpec::Triangle {
            degree: n,
            points,
            weights: None,
        },
        affine: [hx * n as f64, x0, hy * n as f64, y0],
        dom: [0.0, 1.0, 0.0, 1.0],
        targets,
        note,
        flat_edge,
    }
}

/// A knot vector of degree `p` on the domain `[0, K]` with dyadic interior
/// knots, often one of multiplicity `p` (a crease); clamped, or (one time in
/// four) unclamped (`p` knots below 0 and above `K`: the domain's edges do
/// not interpolate). And the interior values, the crease's flagged, and
/// whether the vector is clamped.
fn knot_vector(rng: &mut Mix, p: usize) -> (Vec<f64>, Vec<(f64, bool)>, bool) {
    let count = rng.range(1, 3) as usize;
    let crease = rng.chance(0.6).then(|| rng.range(0, count as i64 - 1) as usize);
    let clamped = rng.chance(0.75);
    let end_step = |rng: &mut Mix| if clamped { 0.0 } else { rng.pick(&[0.5, 1.0]) };
    let h0 = end_step(rng);
    // h0·k − h0·p, not −h0·(p − k): no −0.0 in the vector.
    let mut knots: Vec<f64> = (0..=p).map(|k| h0 * k as f64 - h0 * p as f64).collect();
    let (mut at, mut interior) = (0.0, Vec::new());
    for k in 0..count {
        at += rng.pick(&[0.5, 0.75, 1.0, 1.5, 2.0]);
        let mult = if crease == Some(k) {
            p
        } else if p >= 3 && rng.chance(0.2) {
            2
        } else {
            1
        };
        knots.extend(std::iter::repeat_n(at, mult));
        interior.push((at, crease == Some(k)));
    }
    at += rng.pick(&[0.5, 1.0, 1.5]);
    let h1 = end_step(rng);
    knots.extend((0..=p).map(|k| at + h1 * k as f64));
    (knots, interior, clamped)
}

fn bspline_grid(rng: &mut Mix, rational: bool) -> Grid {
    let (p, q) = (rng.range(2, 4) as usize, rng.range(2, 4) as usize);
    let (ku, iu, clamped_u) = knot_vector(rng, p);
    let (kv, iv, clamped_v) = knot_vector(rng, q);
    let (nu, nv) = (ku.len() - p - 1, kv.len() - q - 1);
    let [hx, x0, hy, y0] = steps(rng);
    // x = p·hx·u + x0: the points sit at p·hx·(Greville) = hx·(sum of p knots).
    let sum = |k: &[f64], i: usize, p: usize| k[i + 1..=i + p].iter().sum::<f64>();
    let (mut z, mut note) = heights(rng, nu * nv);
    if !(clamped_u && clamped_v) {
        note += " unclamped";
    }
    let flat_edge = (clamped_u && rng.chance(0.2)).then(|| {
        // The last two rows equal: ∂z/∂u = 0 along u = U1.
        z.copy_within((nu - 2) * nv..(nu - 1) * nv, (nu - 1) * nv);
        note += " flat edge";
        ku[nu]
    });
    let points = (0..nu)
        .flat_map(|i| (0..nv).map(move |j| (i, j)))
        .map(|(i, j)| [x0 + hx * sum(&ku, i, p), y0 + hy * sum(&kv, j, q), z[i * nv + j]])
        .collect();
    let weights = rational.then(|| alphas(rng, nu - 1).into_iter().flat_map(|a| vec![a; nv]).collect());
    let dom = [ku[p], ku[nu], kv[q], kv[nv]];
    let mut targets = box_targets(rng, dom);
    let crease = |c: bool| if c { " (crease)" } else { "" };
    let (su, sv) = (dom[1] * dyadic01(rng), dom[3] * dyadic01(rng));
    for &(k, c) in &iu {
        targets.push(target(format!("knot u={k}{}", crease(c)), k, sv, Some(Along::U(k))));
        targets.push(target(
            format!("knot u={k}{} at v=0", crease(c)),
            k,
            0.0,
            Some(Along::V(0.0)),
        ));
    }
    for &(k, c) in &iv {
        targets.push(target(format!("knot v={k}{}", crease(c)), su, k, Some(Along::V(k))));
    }
    for &(a, ca) in &iu {
        for &(b, cb) in &iv {
            let along = if rng.chance(0.5) { Along::U(a) } else { Along::V(b) };
            targets.push(target(
                format!("knot corner ({a}{}, {b}{})", crease(ca), crease(cb)),
                a,
                b,
                Some(along),
            ));
        }
    }
    if rational {
        only_rows(&mut targets);
    }
    Grid {
        spec: PatchSpec::Bspline {
            degree: [p, q],
            knots_u: ku,
            knots_v: kv,
            points,
            weights,
        },
        affine: [hx * p as f64, x0, hy * q as f64, y0],
        dom,
        targets,
        note,
        flat_edge,
    }
}

/// `0` (often), or `±1..3`.
fn wiggle(rng: &mut Mix) -> i32 {
    rng.pick(&[0, 0, 0, 0, 1, -1, 1, -1, 2, -2, 3, -3])
}

fn tag(k: i32) -> String {
    if k == 0 {
        String::new()
    } else {
        format!("{k:+}ulp")
    }
}

/// A horizontal direction `(dx, dy)`, exact dyadic (or, one time in eight, a
/// full-precision slope), of size about `2^e`.
fn direction(rng: &mut Mix, dy_zero: bool) -> (f64, f64) {
    let sx = rng.pick(&[1.0, -1.0]);
    let sy = rng.pick(&[1.0, -1.0]);
    let e = scale(rng);
    if dy_zero {
        return (sx * e, 0.0);
    }
    let k = rng.range(1, 16) as f64 / 16.0;
    let (dx, dy) = match rng.range(0, 7) {
        0 => (1.0, 0.0),
        1 => (0.0, 1.0),
        2 | 3 => (1.0, k),
        4 | 5 => (k, 1.0),
        _ => (1.0, rng.signed()),
    };
    (sx * dx * e, sy * dy * e)
}

/// A power of two about 1, or (one time in twenty) `2^±100`: `t` scales
/// inversely.
fn scale(rng: &mut Mix) -> f64 {
    if rng.chance(0.05) {
        pow2(rng.pick(&[-100, 100]))
    } else {
        pow2(rng.range(-2, 2))
    }
}

/// The builder of rays for one patch.
struct Aim<'a> {
    g: &'a Grid,
    surf: Surface,
    rational: bool,
}

impl Aim<'_> {
    /// `(x, y)` of the parameter point, exactly.
    fn xy(&self, u: f64, v: f64) -> (Q, Q) {
        let [a, x0, b, y0] = self.g.affine.map(qf);
        let (u, v) = (qf(u), qf(v));
        let x = if self.rational {
            let [nx, _, w] = self.surf.hom(&u, &v, self.surf.cell_of(&u, &v));
            nx / w
        } else {
            x0 + a * &u
        };
        (x, y0 + b * v)
    }

    /// A time `t0` (a power of two) after which a ray with horizontal speed
    /// `m` has crossed the whole footprint.
    fn lead_time(&self, m: f64) -> f64 {
        let [a, _, b, _] = self.g.affine;
        let span = (self.g.dom[1] - self.g.dom[0]) * a.abs() + (self.g.dom[3] - self.g.dom[2]) * b.abs() + 2.0;
        pow2((span / m).log2().ceil() as i64)
    }

    /// Horizontal (or slightly slanted) through the target, `oz` its rounded height.
    fn cross(&self, rng: &mut Mix, t: &Target) -> ([f64; 3], [f64; 3], String) {
        let (dx, dy) = direction(rng, self.rational);
        let slant = rng.chance(0.25);
        let dz = if slant {
            rng.pick(&[0.0625, -0.25, 1.0, -4.0]) * dx.abs().max(dy.abs())
        } else {
            0.0
        };
        self.cross_with(rng, t, [dx, dy, dz])
    }

    fn cross_with(&self, rng: &mut Mix, t: &Target, [dx, dy, dz]: [f64; 3]) -> ([f64; 3], [f64; 3], String) {
        let t0 = self.lead_time(dx.abs().max(dy.abs()));
        let (x, y) = self.xy(t.u, t.v);
        let z = self.surf.height(&qf(t.u), &qf(t.v));
        let k = wiggle(rng);
        let o = [
            nearest(&(x - qf(t0 * dx))),
            nearest(&(y - qf(t0 * dy))),
            ulps(nearest(&(z - qf(t0 * dz))), k),
        ];
        (o, [dx, dy, dz], format!("cross dz={dz} oz{}", tag(k)))
    }

    /// Vertical through the rounded target, `(ox, oy)` moved by a few ulps.
    fn vertical(&self, rng: &mut Mix, t: &Target) -> ([f64; 3], [f64; 3], String) {
        let (x, y) = self.xy(t.u, t.v);
        let (kx, ky) = (wiggle(rng), wiggle(rng));
        let e = scale(rng);
        let down = rng.chance(0.5);
        let o = [
            ulps(nearest(&x), kx),
            ulps(nearest(&y), ky),
            if down { 2.0 } else { -2.0 },
        ];
        let d = [0.0, 0.0, if down { -e } else { e }];
        (o, d, format!("vertical ox{} oy{}", tag(kx), tag(ky)))
    }

    /// Horizontal, in the vertical plane over the line `along` (moved by a
    /// few ulps), at the rounded height of the target.
    fn along(&self, rng: &mut Mix, t: &Target, along: Along) -> ([f64; 3], [f64; 3], String) {
        let [a, x0, b, y0] = self.g.affine;
        let e = pow2(rng.range(-2, 2));
        let sign = rng.pick(&[1.0, -1.0]);
        let k = wiggle(rng);
        let z = nearest(&self.surf.height(&qf(t.u), &qf(t.v)));
        let (o, d) = match along {
            Along::U(c) => {
                let t0 = self.lead_time(e);
                let y = y0 + b * t.v;
                ([ulps(x0 + a * c, k), y - t0 * sign * e, z], [0.0, sign * e, 0.0])
            }
            Along::V(c) => {
                let t0 = self.lead_time(e);
                let x = nearest(&self.xy(t.u, t.v).0);
                ([x - t0 * sign * e, ulps(y0 + b * c, k), z], [sign * e, 0.0, 0.0])
            }
            Along::Hyp => {
                // Points (x0 + a·u, y0 + b·(1 − u)), from u = −1 up or u = 2 down.
                let d = [sign * a * e, -sign * b * e, 0.0];
                let u = if sign > 0.0 { -1.0 } else { 2.0 };
                ([ulps(x0 + a * u, k), y0 + b * (1.0 - u), z], d)
            }
        };
        (o, d, format!("along {along:?} ({}){}", t.name, tag(k)))
    }

    /// From the rounded target point on the surface itself, leaving it
    /// slanted: a hit at `t ≈ 0`, just inside or outside the range `t ≥ 0`.
    fn start(&self, rng: &mut Mix, t: &Target) -> ([f64; 3], [f64; 3], String) {
        let (dx, dy) = direction(rng, self.rational);
        let dz = rng.pick(&[0.25, -0.25, 1.0, -1.0, 4.0]) * dx.abs().max(dy.abs());
        let (x, y) = self.xy(t.u, t.v);
        let z = self.surf.height(&qf(t.u), &qf(t.v));
        let (kx, kz) = (wiggle(rng), wiggle(rng));
        let o = [ulps(nearest(&x), kx), nearest(&y), ulps(nearest(&z), kz)];
        (o, [dx, dy, dz], format!("start dz={dz} ox{} oz{}", tag(kx), tag(kz)))
    }

    /// Horizontal through the target, across in a random direction or along
    /// its feature line, `oz` the rounded value of an extremum of the height
    /// along the line: two hits a few 1e-8 apart, or none.
    fn tangent(&self, rng: &mut Mix, t: &Target) -> Option<([f64; 3], [f64; 3], String)> {
        let along = t.along.filter(|_| rng.chance(0.5));
        let (mut o, d, _) = match along {
            Some(a) => self.along(rng, t, a),
            None => self.cross(rng, t),
        };
        let d = [d[0], d[1], 0.0];
        o[2] = 0.0;
        let probe = Case {
            family: Family::Tensor,
            seed: 0,
            label: String::new(),
            spec: self.g.spec.clone(),
            affine: self.g.affine,
            origin: o,
            dir: d,
        };
        let r = restrict(&probe);
        // (lo, hi, height along the line, its derivative's numerator).
        let mut cands = Vec::new();
        for RPiece { lo, hi, p: h, t } in r.pieces.into_iter().filter(|rp| rp.lo < rp.hi) {
            if self.rational {
                // h = dx·N_z here; the height is N_z / D with D = t.den / |dx|.
                let crit = h.deriv().mul(&t.den).sub(&h.mul(&t.den.deriv()));
                cands.push((lo, hi, h, Some(t.den), crit));
            } else {
                let crit = h.deriv();
                cands.push((lo, hi, h, None, crit));
            }
        }
        let mut zeros = Vec::new();
        for (lo, hi, h, den, crit) in &cands {
            if crit.is_zero() || crit.degree() == 0 {
                continue;
            }
            let piece = Piece::new(lo.clone(), hi.clone(), crit, TOfS::identity());
            for root in piece.roots(0) {
                let s = match root {
                    Root::Exact(x) => x,
                    Root::Iso { lo, hi, .. } => {
                        let (mut lo, mut hi) = (lo, hi);
                        let mut exact = None;
                        for _ in 0..100 {
                            exact = piece.bisect(&mut lo, &mut hi);
                            if exact.is_some() {
                                break;
                            }
                        }
                        exact.unwrap_or((lo + hi) / qi(2))
                    }
                };
                let z = match den {
                    Some(den) => h.eval(&s) / den.eval(&s) * qf(d[0].abs()) / qf(d[0]),
                    None => h.eval(&s),
                };
                zeros.push(z);
            }
        }
        if zeros.is_empty() {
            return None;
        }
        let z = &zeros[rng.range(0, zeros.len() as i64 - 1) as usize];
        let k = wiggle(rng);
        o[2] = ulps(nearest(z), k);
        let how = if along.is_some() { "tangent-along" } else { "tangent" };
        Some((o, d, format!("{how} oz{}", tag(k))))
    }
}

/// The case of `family` for `seed`.
///
/// One case in five is *lowered* when its ray is horizontal: the patch is
/// shifted down by the ray's height (each control height rounded) and the
/// same construction replayed on it, so that the aimed height is about 0 and
/// one ulp of `oz` is tiny (down to 5e-324). Then a grazing hit lies that
/// close to its edge, and a tangent ray's two hits are some
/// `sqrt(ulp(oz) / z″)` apart: 1e-16 and far below.
pub fn generate(family: Family, seed: u64) -> Case {
    let mut rng = Mix(seed);
    let mut g = match family {
        Family::Tensor => tensor_grid(&mut rng, false),
        Family::Rational => tensor_grid(&mut rng, true),
        Family::Triangle => triangle_grid(&mut rng),
        Family::Bspline => bspline_grid(&mut rng, false),
        Family::Nurbs => bspline_grid(&mut rng, true),
    };
    let lower = rng.chance(0.2);
    let replay = rng.clone();
    let (mut origin, mut dir, mut how) = aim_ray(&g, family, &mut rng);
    if lower && dir[2] == 0.0 && origin[2] != 0.0 {
        shift_heights(&mut g.spec, origin[2]);
        g.note += " lowered";
        (origin, dir, how) = aim_ray(&g, family, &mut replay.clone());
    }
    Case {
        family,
        seed,
        label: format!("{} {} {}: {how}", family.name(), shape(&g.spec), g.note),
        spec: g.spec,
        affine: g.affine,
        origin,
        dir,
    }
}

/// Every control height minus `c` (rounded).
fn shift_heights(spec: &mut PatchSpec, c: f64) {
    match spec {
        PatchSpec::Tensor { points, .. } | PatchSpec::Triangle { points, .. } | PatchSpec::Bspline { points, .. } => {
            for p in points {
                p[2] -= c;
            }
        }
        _ => unreachable!("the adversary's patches"),
    }
}

/// A ray aimed at a random feature of `g` by a random construction, and
/// how (`"… @ feature"`).
fn aim_ray(g: &Grid, family: Family, rng: &mut Mix) -> ([f64; 3], [f64; 3], String) {
    let probe = Case {
        family,
        seed: 0,
        label: String::new(),
        spec: g.spec.clone(),
        affine: g.affine,
        origin: [0.0; 3],
        dir: [0.0; 3],
    };
    let aim = Aim {
        surf: Surface::of(&probe),
        g,
        rational: family.rational(),
    };
    let mut t = g.targets[rng.range(0, g.targets.len() as i64 - 1) as usize].clone();
    let (o, d, how) = match rng.range(0, if g.flat_edge.is_some() { 6 } else { 4 }) {
        5 => {
            // Along u at the rounded height of the flat edge: a double hit
            // on the edge, split by the rounding into two hits straddling
            // it (or none).
            let c = g.flat_edge.unwrap();
            let r = dyadic01(rng);
            let v = g.dom[2] + (g.dom[3] - g.dom[2]) * rng.pick(&[0.0, r, r, 1.0]);
            t = target(format!("flat edge u={c} v={v}"), c, v, None);
            let dx = rng.pick(&[1.0, -1.0]) * scale(rng);
            let (o, d, how) = aim.cross_with(rng, &t, [dx, 0.0, 0.0]);
            (o, d, how.replace("cross", "edge-tangent"))
        }
        0 => aim.cross(rng, &t),
        1 => aim.vertical(rng, &t),
        2 => match t.along {
            Some(along) => aim.along(rng, &t, along),
            None => aim.cross(rng, &t),
        },
        3 => aim.tangent(rng, &t).unwrap_or_else(|| aim.cross(rng, &t)),
        _ => aim.start(rng, &t),
    };
    (o, d, format!("{how} @ {}", t.name))
}

fn shape(spec: &PatchSpec) -> String {
    match spec {
        PatchSpec::Tensor { degree, weights, .. } => {
            format!(
                "{}({}, {})",
                if weights.is_some() { "rational" } else { "" },
                degree[0],
                degree[1]
            )
        }
        PatchSpec::Triangle { degree, .. } => format!("({degree})"),
        PatchSpec::Bspline {
            degree,
            knots_u,
            knots_v,
            weights,
            ..
        } => format!(
            "{}({}, {}) knots {knots_u:?} × {knots_v:?}",
            if weights.is_some() { "rational" } else { "" },
            degree[0],
            degree[1]
        ),
        _ => String::new(),
    }
}

// ---------------------------------------------------------------------------
// The judge
// ---------------------------------------------------------------------------

/// A broken promise; see the module docs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Fault {
    Miss,
    MissT,
    Phantom,
    Multiple,
    Tangent,
    TBox,
    Duplicate,
    Domain,
    ZeroEquation,
    Error,
}

impl Fault {
    pub const ALL: [Fault; 10] = [
        Fault::Miss,
        Fault::MissT,
        Fault::Phantom,
        Fault::Multiple,
        Fault::Tangent,
        Fault::TBox,
        Fault::Duplicate,
        Fault::Domain,
        Fault::ZeroEquation,
        Fault::Error,
    ];

    /// A broken promise of the contract: every fault but `ZeroEquation`, an
    /// honest "no hit list" that is only suspicious on these non-planar
    /// patches (the library may call an equation zero when every coefficient
    /// enclosure holds 0, e.g. a B-spline net widened by its knot-insertion
    /// error on a nearly flat patch).
    pub fn breaks_contract(self) -> bool {
        self != Fault::ZeroEquation
    }

    pub fn name(self) -> &'static str {
        match self {
            Fault::Miss => "miss",
            Fault::MissT => "miss-t",
            Fault::Phantom => "phantom",
            Fault::Multiple => "multiple",
            Fault::Tangent => "tangent",
            Fault::TBox => "t-box",
            Fault::Duplicate => "duplicate",
            Fault::Domain => "domain",
            Fault::ZeroEquation => "zero-equation",
            Fault::Error => "error",
        }
    }
}

/// What the library answered, in kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Answer {
    Complete,
    Incomplete,
    Unresolved,
    ZeroEquation,
    Error,
}

/// The judgement of one case.
#[derive(Clone, Debug)]
pub struct Verdict {
    pub answer: Answer,
    /// True hits with `t ≥ 0`.
    pub roots: usize,
    pub certified: usize,
    pub undecided: usize,
    /// The truth is a curve of hits (not judged).
    pub degenerate: bool,
    /// True hits with `t ≥ 0` within `1e-12` of an edge or knot line (or on it).
    pub near_feature: usize,
    pub faults: Vec<(Fault, String)>,
    pub hits: Vec<Hit>,
    /// The truth, `(u, v, t)` rounded, for reports.
    pub truth: Vec<[f64; 3]>,
    /// Time in `intersect`.
    pub time: Duration,
}

impl Verdict {
    /// Some fault breaks the contract ([`Fault::breaks_contract`]).
    pub fn fails(&self) -> bool {
        self.faults.iter().any(|f| f.0.breaks_contract())
    }
}

/// The case's patch and ray, as rootclip takes them.
pub fn patch_and_ray(case: &Case) -> (Patch, Ray) {
    let patch = Patch::from_spec(&case.spec).expect("adversary: a valid patch");
    let ray = Ray::new(DVec3::from_array(case.origin), DVec3::from_array(case.dir)).expect("a valid ray");
    (patch, ray)
}

/// Runs `intersect` on the case and judges its answer against the referee.
pub fn judge(case: &Case) -> Verdict {
    let truth = Truth::of(case);
    let (patch, ray) = patch_and_ray(case);
    let start = Instant::now();
    let out = intersect(&patch, &ray, &RayOptions::default());
    let time = start.elapsed();
    judge_outcome(case, &truth, out, time)
}

fn describe(h: &Hit) -> String {
    format!(
        "{:?} u {:?} v {:?} t {:?}",
        h.status,
        h.bx.u.map(|x| format!("{x:e}")),
        h.bx.v.map(|x| format!("{x:e}")),
        h.bx.t.map(|x| format!("{x:e}"))
    )
}

fn judge_outcome(case: &Case, truth: &Truth, out: rootclip::Result<RayOutcome>, time: Duration) -> Verdict {
    let in_range: Vec<bool> = truth
        .roots
        .iter()
        .map(|r| truth.in_t(r, [0.0, f64::INFINITY]))
        .collect();
    let mut v = Verdict {
        answer: Answer::Complete,
        roots: in_range.iter().filter(|x| **x).count(),
        certified: 0,
        undecided: 0,
        degenerate: truth.degenerate,
        near_feature: 0,
        faults: Vec::new(),
        hits: Vec::new(),
        truth: Vec::new(),
        time,
    };
    let (hits, complete) = match out {
        Err(e) => {
            v.answer = Answer::Error;
            v.faults.push((Fault::Error, e.to_string()));
            return v;
        }
        Ok(RayOutcome::Hits(h)) => {
            v.answer = if h.complete {
                Answer::Complete
            } else {
                Answer::Incomplete
            };
            (h.hits, h.complete)
        }
        Ok(RayOutcome::Degenerate(Degeneracy::Unresolved(h))) => {
            v.answer = Answer::Unresolved;
            (h.hits, false)
        }
        Ok(RayOutcome::Degenerate(_)) => {
            v.answer = Answer::ZeroEquation;
            if !truth.degenerate {
                v.faults.push((Fault::ZeroEquation, "on a non-planar patch".into()));
            }
            (Vec::new(), false)
        }
    };
    if truth.degenerate {
        v.hits = hits;
        return v;
    }
    let surf = Surface::of(case);
    v.near_feature = (truth.roots.iter().zip(&in_range))
        .filter(|(r, ok)| **ok && surf.feature_distance(truth.uvt(r, 64)) < 1e-12)
        .count();
    let root_name = |k: usize| format!("true hit {k} (u, v, t) ≈ {:?}", truth.uvt(&truth.roots[k], 120));
    let mut claimed: Vec<Option<usize>> = vec![None; truth.roots.len()];
    for (k, h) in hits.iter().enumerate() {
        if !surf.contains(&qf(h.u), &qf(h.v)) {
            v.faults
                .push((Fault::Domain, format!("hit {k} at ({:e}, {:e})", h.u, h.v)));
        }
        if !h.is_certified() {
            v.undecided += 1;
            continue;
        }
        v.certified += 1;
        let inside: Vec<usize> = (0..truth.roots.len())
            .filter(|&r| truth.in_uv(&truth.roots[r], &h.bx))
            .collect();
        match inside[..] {
            [] => v.faults.push((
                Fault::Phantom,
                format!("certified hit {k}, {}, holds no true hit", describe(h)),
            )),
            [r] => {
                if !truth.transversal[r] {
                    let what = format!(
                        "certified hit {k}, {}, holds {}, a tangency or crease touch",
                        describe(h),
                        root_name(r)
                    );
                    v.faults.push((Fault::Tangent, what));
                }
                if !truth.in_t(&truth.roots[r], h.bx.t) || !in_range[r] {
                    let what = format!(
                        "certified hit {k}, {}: {} not in its t box / t ≥ 0",
                        describe(h),
                        root_name(r)
                    );
                    v.faults.push((Fault::TBox, what));
                }
                if let Some(other) = claimed[r] {
                    let what = format!("certified hits {other} and {k} both hold {}", root_name(r));
                    v.faults.push((Fault::Duplicate, what));
                }
                claimed[r] = Some(k);
            }
            _ => v
                .faults
                .push((Fault::Multiple, format!("certified hit {k} holds true hits {inside:?}"))),
        }
    }
    if complete {
        for (r, root) in truth.roots.iter().enumerate().filter(|(r, _)| in_range[*r]) {
            let uv: Vec<&Hit> = hits.iter().filter(|h| truth.in_uv(root, &h.bx)).collect();
            if uv.is_empty() {
                v.faults.push((Fault::Miss, format!("{} in no hit box", root_name(r))));
            } else if !uv.iter().any(|h| truth.in_t(root, h.bx.t)) {
                v.faults
                    .push((Fault::MissT, format!("{} in no covering hit's t box", root_name(r))));
            }
        }
    }
    v.hits = hits;
    if !v.faults.is_empty() {
        v.truth = truth.roots.iter().map(|r| truth.uvt(r, 120)).collect();
    }
    v
}

// ---------------------------------------------------------------------------
// Reproductions
// ---------------------------------------------------------------------------

impl Case {
    /// The patch as `rootclip ray --patch` reads it.
    pub fn patch_json(&self) -> String {
        serde_json::to_string(&self.spec).expect("a patch spec serializes")
    }

    /// The command line that replays the ray (numbers round-trip exactly).
    pub fn command(&self, patch_path: &str) -> String {
        let [ox, oy, oz] = self.origin;
        let [dx, dy, dz] = self.dir;
        format!("rootclip ray --patch {patch_path} --origin={ox:e},{oy:e},{oz:e} --dir={dx:e},{dy:e},{dz:e} --json")
    }

    /// A size for picking small reproductions: control points, then degree.
    pub fn size(&self) -> usize {
        match &self.spec {
            PatchSpec::Tensor { points, .. }
            | PatchSpec::Triangle { points, .. }
            | PatchSpec::Bspline { points, .. } => points.len(),
            _ => usize::MAX,
        }
    }
}

/// A human-readable account of a judged case: label, truth, answer, faults,
/// and how to replay it.
pub fn report(case: &Case, v: &Verdict, patch_path: &str) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# {} seed {:#x}: {}", case.family.name(), case.seed, case.label);
    let _ = writeln!(s, "# answer {:?}, {} true hit(s) with t ≥ 0:", v.answer, v.roots);
    for (k, r) in v.truth.iter().enumerate() {
        let _ = writeln!(s, "#   true hit {k}: (u, v, t) ≈ {r:?}");
    }
    for (k, h) in v.hits.iter().enumerate() {
        let _ = writeln!(s, "#   reported {k}: {}", describe(h));
    }
    for (f, what) in &v.faults {
        let _ = writeln!(s, "# FAULT {}: {what}", f.name());
    }
    let _ = writeln!(s, "{}", case.command(patch_path));
    s
}

// ---------------------------------------------------------------------------
// The referee's own tests
// ---------------------------------------------------------------------------

#[cfg(test)]
mod tests {
    use super::*;
    use rootclip::ray::{TensorPatch, TriPatch};

    fn q(n: i64, d: i64) -> Q {
        Q::new(BigInt::from(n), BigInt::from(d))
    }

    fn count(p: &Poly, lo: Q, hi: Q) -> usize {
        Piece::new(lo.clone(), hi, p, TOfS::identity()).roots(0).len()
    }

    #[test]
    fn sturm_counts_distinct_roots_in_closed_intervals() {
        let p = Poly::from_roots(&[qi(1), qi(2), qi(3)]);
        assert_eq!(count(&p, qi(0), qi(4)), 3);
        assert_eq!(count(&p, qi(1), qi(2)), 2);
        assert_eq!(count(&p, q(3, 2), q(5, 2)), 1);
        assert_eq!(count(&p, q(7, 2), qi(9)), 0);
        // Multiple roots count once.
        let p = Poly::from_roots(&[qi(1), qi(1), q(1, 3), q(1, 3), q(1, 3)]);
        assert_eq!(count(&p, qi(0), qi(1)), 2);
        // s² + 1 has no real root; s² − 2 two irrational ones.
        assert_eq!(count(&Poly::new(vec![qi(1), qi(0), qi(1)]), qi(-10), qi(10)), 0);
        let p = Poly::new(vec![qi(-2), qi(0), qi(1)]);
        assert_eq!(count(&p, qi(-2), qi(2)), 2);
        assert_eq!(count(&p, q(141, 100), q(142, 100)), 1);
        assert_eq!(count(&p, q(142, 100), qi(2)), 0);
        // Two roots 1e-30 apart are separated.
        let e = Q::new(BigInt::from(1), BigInt::from(10).pow(30));
        let p = Poly::from_roots(&[q(1, 2), q(1, 2) + e]);
        assert_eq!(count(&p, qi(0), qi(1)), 2);
    }

    #[test]
    fn signs_at_isolated_roots_are_exact() {
        // √2 against floats just below and above it, and t = s² at √2 is 2.
        let p = Poly::new(vec![qi(-2), qi(0), qi(1)]);
        let t = Truth {
            line: Line {
                u: Poly::linear(qi(0), qi(1)),
                v: Poly::constant(qi(0)),
            },
            pieces: vec![Piece::new(
                qi(0),
                qi(2),
                &p,
                TOfS {
                    num: Poly::new(vec![qi(0), qi(0), qi(1)]),
                    den: Poly::constant(qi(1)),
                },
            )],
            roots: vec![],
            transversal: vec![],
            degenerate: false,
        };
        let r = &t.pieces[0].roots(0)[0];
        let s2 = std::f64::consts::SQRT_2;
        assert!(qf(s2) * qf(s2) > qi(2) && qf(s2.next_down()) * qf(s2.next_down()) < qi(2));
        let bx = |lo: f64, hi: f64| HitBox {
            u: [lo, hi],
            v: [0.0, 0.0],
            t: [0.0, 0.0],
        };
        assert!(!t.in_uv(r, &bx(s2, 2.0)));
        assert!(t.in_uv(r, &bx(s2.next_down(), 2.0)));
        assert!(t.in_uv(r, &bx(0.0, s2)));
        assert!(!t.in_uv(r, &bx(0.0, s2.next_down())));
        assert!(t.in_t(r, [2.0, 2.0]));
        assert!(!t.in_t(r, [2.0f64.next_up(), 3.0]));
    }

    #[test]
    fn nearest_rounds_to_nearest_even() {
        assert_eq!(nearest(&q(1, 10)), 0.1);
        assert_eq!(nearest(&q(-1, 3)), -1.0 / 3.0);
        assert_eq!(nearest(&qf(5e-324)), 5e-324);
        assert_eq!(nearest(&(qf(5e-324) / qi(2))), 0.0);
        assert_eq!(nearest(&(qf(5e-324) * q(3, 2))), 1e-323);
        let half_ulp = qf(1.0) + qf(f64::EPSILON) / qi(2);
        assert_eq!(nearest(&half_ulp), 1.0);
        assert_eq!(
            nearest(&(qf(1.0) + qf(f64::EPSILON) * q(3, 2))),
            1.0 + 2.0 * f64::EPSILON
        );
        assert_eq!(nearest(&qf(1e300)), 1e300);
    }

    /// The hand-checked grazing case: the bilinear `z = c·u` over the unit
    /// square (`c` the float 0.1) and horizontal rays along `x` at height
    /// `oz`: a hit iff `0 ≤ oz ≤ c`, at `u = oz / c`. At `oz = c` the hit is
    /// the edge `u = 1` exactly; one ulp above, none; one below, just inside.
    #[test]
    fn hand_built_grazing_tensor() {
        let c = 0.1;
        let pts = [[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, c], [1.0, 1.0, c]];
        let mk = |oz: f64, dir: [f64; 3], origin: [f64; 3]| Case {
            family: Family::Tensor,
            seed: 0,
            label: "hand".into(),
            spec: PatchSpec::Tensor {
                degree: [1, 1],
                points: pts.to_vec(),
                weights: None,
            },
            affine: [1.0, 0.0, 1.0, 0.0],
            origin: [origin[0], origin[1], if dir[2] == 0.0 { oz } else { origin[2] }],
            dir,
        };
        let horizontal = |oz: f64| mk(oz, [1.0, 0.0, 0.0], [-1.0, 0.5, 0.0]);
        let on_edge = Truth::of(&horizontal(c));
        assert_eq!(on_edge.roots.len(), 1);
        assert!(
            matches!(&on_edge.roots[0], Root::Exact(t) if *t == qi(2)),
            "{:?}",
            on_edge.roots
        );
        assert!(Truth::of(&horizontal(c.next_up())).roots.is_empty());
        let inside = Truth::of(&horizontal(c.next_down()));
        assert_eq!(inside.roots.len(), 1);
        let [u, v, t] = inside.uvt(&inside.roots[0], 120);
        assert!(u < 1.0 && (u - 1.0).abs() < 1e-15 && v == 0.5 && (t - 2.0).abs() < 1e-15);
        assert_eq!(Truth::of(&horizontal(0.0)).roots.len(), 1);
        assert!(Truth::of(&horizontal(-5e-324)).roots.is_empty());
        // Vertical rays on and just off the edge x = 1.
        let vertical = |x: f64| mk(0.0, [0.0, 0.0, -1.0], [x, 0.5, 1.0]);
        assert_eq!(Truth::of(&vertical(1.0)).roots.len(), 1);
        assert!(Truth::of(&vertical(1.0f64.next_up())).roots.is_empty());
        // And the library on all of them.
        for case in [
            horizontal(c),
            horizontal(c.next_up()),
            horizontal(c.next_down()),
            vertical(1.0),
        ] {
            let v = judge(&case);
            assert!(!v.fails(), "{}", report(&case, &v, "PATCH.json"));
        }
        assert!(TensorPatch::new(1, 1, pts.iter().map(|p| DVec3::from_array(*p)).collect(), None).is_ok());
    }

    /// `z = (u − ½)²` (bidegree (2, 1), heights ¼, −¼, ¼) and horizontal
    /// rays along `x`: at `oz = 0` one double hit at `u = ½` (not
    /// transversal); at `oz = 5e-324` two simple hits `±2^-537` from it; at
    /// `oz = −5e-324` none. The library must certify neither side of the double
    /// hit as a simple one.
    #[test]
    fn hand_built_tangency() {
        let mut points = Vec::new();
        for (i, z) in [0.25, -0.25, 0.25].into_iter().enumerate() {
            for j in 0..2 {
                points.push([i as f64 / 2.0, j as f64, z]);
            }
        }
        let case = |oz: f64| Case {
            family: Family::Tensor,
            seed: 0,
            label: "hand tangency".into(),
            spec: PatchSpec::Tensor {
                degree: [2, 1],
                points: points.clone(),
                weights: None,
            },
            affine: [1.0, 0.0, 1.0, 0.0],
            origin: [-1.0, 0.5, oz],
            dir: [1.0, 0.0, 0.0],
        };
        let double = Truth::of(&case(0.0));
        assert_eq!(double.roots.len(), 1);
        assert_eq!(double.approx(&double.roots[0], 60), q(3, 2));
        assert!(!double.transversal[0]);
        let split = Truth::of(&case(5e-324));
        assert_eq!(split.roots.len(), 2);
        assert!(split.transversal.iter().all(|x| *x));
        let gap = split.approx(&split.roots[0], 1200) - split.approx(&split.roots[1], 1200);
        let gap = nearest(&if sgn(&gap) < 0 { -gap } else { gap });
        assert!((gap / 2f64.powi(-536) - 1.0).abs() < 1e-9, "{gap:e}");
        assert!(Truth::of(&case(-5e-324)).roots.is_empty());
        for oz in [0.0, 5e-324, -5e-324] {
            let v = judge(&case(oz));
            assert!(!v.fails(), "{}", report(&case(oz), &v, "PATCH.json"));
        }
    }

    /// A degree-1 triangle `z = c·v` and a vertical ray onto its hypotenuse,
    /// one ulp in and out; and a rational row whose hits are known.
    #[test]
    fn hand_built_triangle_and_rational() {
        let c = 0.3;
        let pts = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, c]];
        let tri = |x: f64, y: f64| Case {
            family: Family::Triangle,
            seed: 0,
            label: "hand".into(),
            spec: PatchSpec::Triangle {
                degree: 1,
                points: pts.clone(),
                weights: None,
            },
            affine: [1.0, 0.0, 1.0, 0.0],
            origin: [x, y, 1.0],
            dir: [0.0, 0.0, -1.0],
        };
        assert_eq!(Truth::of(&tri(0.25, 0.75)).roots.len(), 1);
        assert!(Truth::of(&tri(0.25f64.next_up(), 0.75)).roots.is_empty());
        assert_eq!(Truth::of(&tri(0.25f64.next_down(), 0.75)).roots.len(), 1);
        assert!(TriPatch::new(1, pts.iter().map(|p| DVec3::from_array(*p)).collect(), None).is_ok());
        // Rational (1, 1) with α = (1, 3): z = 3u / (1 + 2u) at the row
        // z = (0, 1); at oz = 1/2, u = 1/4 exactly (t from x = u: t = 1 + 1/4).
        let rat = Case {
            family: Family::Rational,
            seed: 0,
            label: "hand".into(),
            spec: PatchSpec::Tensor {
                degree: [1, 1],
                points: vec![[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, 1.0], [1.0, 1.0, 1.0]],
                weights: Some(vec![1.0, 1.0, 3.0, 3.0]),
            },
            affine: [1.0, 0.0, 1.0, 0.0],
            origin: [-1.0, 0.5, 0.5],
            dir: [1.0, 0.0, 0.0],
        };
        let truth = Truth::of(&rat);
        assert_eq!(truth.roots.len(), 1);
        let r = &truth.roots[0];
        assert_eq!(truth.approx(r, 200), q(1, 4));
        // x(u) = 3u / (1 + 2u) too: x(1/4) = 1/2, t = x − ox = 3/2.
        assert!(truth.in_t(r, [1.5, 1.5]) && !truth.in_t(r, [1.5f64.next_up(), 2.0]));
    }

    /// A biquadratic B-spline with a crease at u = 1 (knot of multiplicity 2):
    /// the exact pieces meet on the crease, a zero there counts once.
    #[test]
    fn bspline_crease_zero_counts_once() {
        let ku = vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 2.0];
        let kv = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
        let (nu, nv) = (5, 3);
        let zu = [0.0, 0.5, 0.25, 0.5, 0.0];
        let mut points = Vec::new();
        for (i, z) in zu.iter().enumerate() {
            for j in 0..nv {
                let gx = (ku[i + 1] + ku[i + 2]) / 2.0;
                let gy = (kv[j + 1] + kv[j + 2]) / 2.0;
                points.push([gx, gy, *z]);
            }
        }
        assert_eq!(points.len(), nu * nv);
        // z on the crease u = 1 is the control value 0.25 (interpolated).
        let case = Case {
            family: Family::Bspline,
            seed: 0,
            label: "hand".into(),
            spec: PatchSpec::Bspline {
                degree: [2, 2],
                knots_u: ku,
                knots_v: kv,
                points,
                weights: None,
            },
            affine: [1.0, 0.0, 1.0, 0.0],
            origin: [1.0, 0.5, 1.0],
            dir: [0.0, 0.0, -1.0],
        };
        let t = Truth::of(&case);
        assert_eq!(t.roots.len(), 1);
        assert!(t.in_t(&t.roots[0], [0.75, 0.75]));
        // Horizontal along x at the crease height: z = u − 3u²/4 on [0, 1]
        // (and its mirror image on [1, 2]), a valley at the crease (z = 1/4,
        // rising to 1/3 on both sides): the ray touches the crease (t = 2)
        // and crosses at u = 1/3 and 5/3.
        let along = Case {
            origin: [-1.0, 0.5, 0.25],
            dir: [1.0, 0.0, 0.0],
            ..case
        };
        let t = Truth::of(&along);
        let crease = t.roots.iter().position(|r| matches!(r, Root::Exact(x) if *x == qi(2)));
        assert_eq!(t.roots.len(), 3, "{:?}", t.roots);
        // The touch is not a crossing; the other two are.
        assert_eq!(t.transversal.iter().filter(|x| **x).count(), 2);
        assert!(!t.transversal[crease.expect("a zero on the crease")]);
    }

    /// The judge can fail: the library's answers, mutated, draw each fault.
    #[test]
    fn judge_catches_mutated_answers() {
        let (mut multiple, mut phantom) = (false, false);
        for seed in 0..300 {
            let case = generate(Family::Tensor, seed);
            let truth = Truth::of(&case);
            let (patch, ray) = patch_and_ray(&case);
            let out = intersect(&patch, &ray, &RayOptions::default()).unwrap();
            let RayOutcome::Hits(h) = &out else { continue };
            let in_range = truth.roots.iter().any(|r| truth.in_t(r, [0.0, f64::INFINITY]));
            let Some(c) = h.hits.iter().position(Hit::is_certified) else {
                continue;
            };
            if !h.complete || !in_range {
                continue;
            }
            let faults = |f: &dyn Fn(&mut Vec<Hit>)| -> Vec<Fault> {
                let mut o = out.clone();
                if let RayOutcome::Hits(h) = &mut o {
                    f(&mut h.hits);
                }
                let v = judge_outcome(&case, &truth, Ok(o), Duration::ZERO);
                v.faults.into_iter().map(|x| x.0).collect()
            };
            assert!(faults(&|_| {}).is_empty(), "{}", case.label);
            assert!(faults(&|h| h.clear()).contains(&Fault::Miss));
            assert!(faults(&|h| h.push(h[c].clone())).contains(&Fault::Duplicate));
            assert!(faults(&|h| h[c].bx.t = [h[c].bx.t[1] + 1.0, h[c].bx.t[1] + 2.0]).contains(&Fault::TBox));
            assert!(faults(&|h| h[c].u = -1e-300).contains(&Fault::Domain));
            let off = HitBox {
                u: [0.5, 0.5],
                v: [0.375, 0.375],
                t: h.hits[c].bx.t,
            };
            if truth.roots.iter().all(|r| !truth.in_uv(r, &off)) {
                assert!(faults(&|h| h[c].bx = off).contains(&Fault::Phantom));
                phantom = true;
            }
            if truth.roots.len() >= 2 {
                let all = HitBox {
                    u: [0.0, 1.0],
                    v: [0.0, 1.0],
                    t: [0.0, 1e300],
                };
                assert!(faults(&|h| h[c].bx = all).contains(&Fault::Multiple));
                multiple = true;
            }
        }
        assert!(multiple && phantom);
    }

    /// The smallest certified crease touch: a biquadratic B-spline whose
    /// height is `u − 3u²/4` on `[0, 1]`, mirrored on `[1, 2]` (a valley
    /// crease at `u = 1`, `z = 1/4` there), and the horizontal ray at `z = 1/4`
    /// along `x`: hits at `u = 1/3` and `5/3` cross the surface, the one at the
    /// crease only touches it and must not be certified (a transversal hit
    /// is promised). Fails on main at 87ca309, which certifies all three.
    #[test]
    #[ignore = "fails on the current library: the touch at the crease is certified"]
    fn crease_touch_is_not_certified() {
        let zs = [0.0, 0.5, 0.25, 0.5, 0.0];
        let points = (0..5)
            .flat_map(|i| (0..3).map(move |j| [i as f64 / 2.0, j as f64 / 2.0, zs[i]]))
            .collect();
        let case = Case {
            family: Family::Bspline,
            seed: 0,
            label: "hand crease touch".into(),
            spec: PatchSpec::Bspline {
                degree: [2, 2],
                knots_u: vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 2.0],
                knots_v: vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
                points,
                weights: None,
            },
            affine: [1.0, 0.0, 1.0, 0.0],
            origin: [-1.0, 0.5, 0.25],
            dir: [1.0, 0.0, 0.0],
        };
        let truth = Truth::of(&case);
        assert_eq!(truth.roots.len(), 3);
        assert_eq!(truth.transversal.iter().filter(|x| !**x).count(), 1);
        let v = judge(&case);
        assert!(!v.fails(), "{}", report(&case, &v, "PATCH.json"));
    }

    /// Every family generates valid, refereed cases.
    #[test]
    fn generated_cases_are_valid() {
        for family in Family::ALL {
            for seed in 0..20 {
                let case = generate(family, seed);
                let _ = patch_and_ray(&case);
                let t = Truth::of(&case);
                assert!(!t.degenerate, "{}", case.label);
            }
        }
    }
}
