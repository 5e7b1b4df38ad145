//! The referee's answer ([`Truth`]): the distinct zeros of a restriction's
//! pieces, isolated by Sturm sequences with exact rational ends ([`Root`]),
//! whether each is a transversal crossing (a simple zero, and on a shared
//! knot line both one-sided slopes of one sign), and exact tests of where a
//! zero lies against floats: a hit box's `(u, v)` and its `t` range.

use super::case::Case;
use super::exact::{nearest, qf, qi, sgn, Q};
use super::poly::{int_sgn, IPoly, Poly, Sturm};
use super::restrict::{restrict, Line, TOfS};
use rootclip::ray::HitBox;

/// A closed piece `[lo, hi]` of the line parameter and the square-free
/// polynomial whose zeros there are hits.
pub(super) struct Piece {
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
    pub(super) fn new(lo: Q, hi: Q, raw: &Poly, t: TOfS) -> Piece {
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
    pub(super) fn roots(&self, k: usize) -> Vec<Root> {
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
    pub(super) fn bisect(&self, lo: &mut Q, hi: &mut Q) -> Option<Q> {
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

/// The exact hits of the ray's line with the closed patch.
pub struct Truth {
    pub line: Line,
    pub(super) pieces: Vec<Piece>,
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
