//! Serde adapters for the crate's option types.

/// A `[lo, hi]` range whose ends may be infinite: JSON has no infinity, so an
/// infinite end is written `null` and `null` is read as `−∞` (first) or `+∞`
/// (second).
pub(crate) mod range {
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    pub(crate) fn serialize<S: Serializer>(r: &[f64; 2], s: S) -> Result<S::Ok, S::Error> {
        let end = |x: f64| if x.is_finite() { Some(x) } else { None };
        [end(r[0]), end(r[1])].serialize(s)
    }

    pub(crate) fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<[f64; 2], D::Error> {
        let [lo, hi] = <[Option<f64>; 2]>::deserialize(d)?;
        Ok([lo.unwrap_or(f64::NEG_INFINITY), hi.unwrap_or(f64::INFINITY)])
    }
}
