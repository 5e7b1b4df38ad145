//! Exact numbers: the referee's rationals [`Q`], a float read as the exact
//! rational it is ([`qf`]), and the way back: the nearest float, ties to
//! even, subnormals included ([`nearest`]), and steps of a few ulps
//! ([`ulps`]).

use rootclip::num_bigint::{BigInt, Sign};
use rootclip::num_rational::BigRational;

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

pub(super) fn sgn(x: &Q) -> i32 {
    match x.numer().sign() {
        Sign::Minus => -1,
        Sign::NoSign => 0,
        Sign::Plus => 1,
    }
}

/// `2^k` for `−1022 ≤ k ≤ 1023`, exactly.
pub(super) fn pow2(k: i64) -> f64 {
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
