//! The generator's entry point ([`generate`]): from a family and a seed, a
//! patch of that family (`grid`) and a ray aimed at one of its features
//! (`aim`), one horizontal case in five *lowered* to a height about 0; and
//! the seeded stream it draws from ([`Mix`]), the same on every machine.

use super::aim::aim_ray;
use super::case::{Case, Family};
use super::exact::pow2;
use super::grid::{bspline_grid, tensor_grid, triangle_grid};
use rootclip::ray::PatchSpec;

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
