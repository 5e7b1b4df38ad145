//! One adversarial case ([`Case`]): its patch family ([`Family`]), the patch
//! as exact `f64` data with the affine map its `x` and `y` follow, and the
//! ray; and how to replay it outside the tests (the patch as JSON and the
//! `rootclip ray` command line).

use rootclip::ray::PatchSpec;

/// A patch family; see "The families" in the adversary's docs (`mod.rs`).
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
    pub(super) fn rational(self) -> bool {
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
