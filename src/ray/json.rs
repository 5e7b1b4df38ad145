//! The JSON form of hits and ray outcomes (feature `serde`): the fields,
//! plus what a reader wants spelled out (the status as flags, the reasons
//! in English); the spelled-out keys are derived, and ignored when read.

use super::hit::{Degeneracy, Hit, HitBox, HitStatus, RayHits, RayOutcome};
use crate::solve::UndecidedReason;
use glam::DVec3;
use serde::{Deserialize, Serialize, Serializer};

/// A hit as written.
#[derive(Serialize)]
struct HitOut<'a> {
    t: f64,
    u: f64,
    v: f64,
    point: DVec3,
    normal: DVec3,
    #[serde(flatten)]
    status: HitStatus,
    #[serde(skip_serializing_if = "Option::is_none")]
    reason_text: Option<&'static str>,
    certified: bool,
    on_edge: bool,
    t_straddles_zero: bool,
    #[serde(rename = "box")]
    bx: &'a HitBox,
}

impl Serialize for Hit {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let reason = self.undecided_reason();
        HitOut {
            t: self.t,
            u: self.u,
            v: self.v,
            point: self.point,
            normal: self.normal,
            status: self.status,
            reason_text: reason.map(UndecidedReason::describe),
            certified: self.is_certified(),
            on_edge: reason == Some(UndecidedReason::Boundary),
            t_straddles_zero: reason == Some(UndecidedReason::RangeEnd),
            bx: &self.bx,
        }
        .serialize(s)
    }
}

/// A hit as read: the fields; the derived keys are ignored.
#[derive(Deserialize)]
pub(super) struct HitIn {
    t: f64,
    u: f64,
    v: f64,
    point: DVec3,
    normal: DVec3,
    #[serde(flatten)]
    status: HitStatus,
    #[serde(rename = "box")]
    bx: HitBox,
}

impl From<HitIn> for Hit {
    fn from(h: HitIn) -> Self {
        Hit {
            t: h.t,
            u: h.u,
            v: h.v,
            point: h.point,
            normal: h.normal,
            status: h.status,
            bx: h.bx,
        }
    }
}

/// A ray's outcome as written and read ([`RayOutcome`]'s docs).
#[derive(Serialize, Deserialize)]
pub(super) struct OutcomeRepr {
    complete: bool,
    hits: Vec<Hit>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    degenerate: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    degenerate_code: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    hits_complete: Option<bool>,
}

impl From<RayOutcome> for OutcomeRepr {
    fn from(o: RayOutcome) -> Self {
        let complete = o.is_complete();
        let (d, hits) = match o {
            RayOutcome::Hits(h) => (None, h),
            RayOutcome::Degenerate(d) => {
                let hits = match &d {
                    Degeneracy::ZeroEquation => RayHits {
                        complete: false,
                        hits: Vec::new(),
                    },
                    Degeneracy::Unresolved(h) | Degeneracy::AlongSurface(h) => h.clone(),
                };
                (Some(d), hits)
            }
        };
        OutcomeRepr {
            complete,
            degenerate: d.as_ref().map(|d| d.describe().to_string()),
            degenerate_code: d.as_ref().map(|d| d.code().to_string()),
            hits_complete: d
                .as_ref()
                .filter(|d| !matches!(d, Degeneracy::ZeroEquation))
                .map(|_| hits.complete),
            hits: hits.hits,
        }
    }
}

impl TryFrom<OutcomeRepr> for RayOutcome {
    type Error = String;

    fn try_from(r: OutcomeRepr) -> Result<Self, String> {
        let inner = RayHits {
            complete: r.hits_complete.unwrap_or(false),
            hits: r.hits,
        };
        Ok(match r.degenerate_code.as_deref() {
            None => RayOutcome::Hits(RayHits {
                complete: r.complete,
                hits: inner.hits,
            }),
            Some("zero_equation") => RayOutcome::Degenerate(Degeneracy::ZeroEquation),
            Some("unresolved") => RayOutcome::Degenerate(Degeneracy::Unresolved(inner)),
            Some("along_surface") => RayOutcome::Degenerate(Degeneracy::AlongSurface(inner)),
            Some(other) => return Err(format!("unknown degenerate_code {other:?}")),
        })
    }
}
