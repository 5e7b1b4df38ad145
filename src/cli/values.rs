//! The command line's names for the library's enums: each a `clap`
//! value enum with its help text, turned into the library's type (the
//! library itself carries no `clap` attribute).

use crate::heuristics::DomainRule;
use crate::solve::{Domain, Method, SplitRule, SquareRoute, TriangleRoute};

/// Declares a value enum and its conversion into the library's enum.
macro_rules! cli_enum {
    ($(#[$meta:meta])* $name:ident => $lib:ty { $($(#[$vmeta:meta])* $variant:ident => $target:expr),+ $(,)? }) => {
        $(#[$meta])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
        pub(super) enum $name {
            $($(#[$vmeta])* $variant),+
        }

        impl From<$name> for $lib {
            fn from(v: $name) -> $lib {
                match v {
                    $($name::$variant => $target),+
                }
            }
        }
    };
}

cli_enum! {
    /// `--domain`.
    DomainArg => Domain {
        #[value(name = "triangle", help = "the unit triangle {u, v >= 0, u + v <= 1}; degree = total degree")]
        Triangle => Domain::Triangle,
        #[value(name = "square", help = "the unit square [0, 1]^2; bidegree = (degree in u, degree in v)")]
        Square => Domain::Square,
    }
}

cli_enum! {
    /// `--method`.
    MethodArg => Method {
        #[value(name = "bezier", help = "triangular Bezier clipping")]
        Bezier => Method::Bezier,
        #[value(name = "linear", help = "linear fat curves for both equations")]
        Linear => Method::Linear,
        #[value(name = "hc-nopre", help = "hybrid clipping without preprocessing")]
        HcNoPre => Method::HcNoPre,
        #[value(name = "hc", help = "hybrid clipping with preprocessing (default)")]
        Hc => Method::Hc,
    }
}

cli_enum! {
    /// `--square-route`, `--route`.
    SquareRouteArg => SquareRoute {
        #[value(name = "triangles", help = "two triangles of degree m + n, clipped with --method")]
        Triangles => SquareRoute::Triangles,
        #[value(name = "rect", help = "Bezier clipping on boxes (default)")]
        Rect => SquareRoute::Rect,
        #[value(name = "rect-fat-line", help = "fat-line clipping on boxes")]
        RectFatLine => SquareRoute::RectFatLine,
        #[value(name = "rect-hybrid", help = "hybrid clipping (fat line and fat conic) on boxes")]
        RectHybrid => SquareRoute::RectHybrid,
    }
}

cli_enum! {
    /// `--triangle-route`.
    TriangleRouteArg => TriangleRoute {
        #[value(name = "triangle", help = "tri-boxes clipped with --method (Liu et al. 2016)")]
        Triangle => TriangleRoute::Triangle,
        #[value(name = "rect", help = "Bezier clipping on boxes of the unit square (default)")]
        Rect => TriangleRoute::Rect,
    }
}

cli_enum! {
    /// `--split`.
    SplitArg => SplitRule {
        #[value(name = "halving", help = "split when a clip does not halve the diameter (default)")]
        Halving => SplitRule::Halving,
        #[value(name = "paper", help = "split when u_min + v_min + w_min <= 0.5 diam(D), as printed")]
        PaperLiteral => SplitRule::PaperLiteral,
    }
}

cli_enum! {
    /// `--domain-rule`.
    DomainRuleArg => DomainRule {
        #[value(name = "clip", help = "cut the step where it leaves the domain (the paper's rule)")]
        Clip => DomainRule::Clip,
        #[value(name = "clamp", help = "the nearest point of the domain")]
        Clamp => DomainRule::Clamp,
        #[value(name = "stop", help = "fail at the first step out of the domain")]
        Stop => DomainRule::Stop,
    }
}
