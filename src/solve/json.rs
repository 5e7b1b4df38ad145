//! The JSON form of roots and clusters (feature `serde`): the fields plus
//! what a reader wants spelled out (`certified`, `reason_text`), derived
//! and ignored when read; empty `diameters` left out.

use super::solution::{Box2, Cluster, Root, UndecidedReason};
use serde::{Deserialize, Serialize};

#[derive(Serialize, Deserialize)]
pub(super) struct RootRepr {
    u: f64,
    v: f64,
    #[serde(rename = "box")]
    bx: Box2,
    on_boundary: bool,
    #[serde(default = "yes", skip_deserializing)]
    certified: bool,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    diameters: Vec<f64>,
}

fn yes() -> bool {
    true
}

impl From<Root> for RootRepr {
    fn from(r: Root) -> Self {
        RootRepr {
            u: r.u,
            v: r.v,
            bx: r.bx,
            on_boundary: r.on_boundary,
            certified: true,
            diameters: r.diameters,
        }
    }
}

impl From<RootRepr> for Root {
    fn from(r: RootRepr) -> Self {
        Root {
            u: r.u,
            v: r.v,
            bx: r.bx,
            on_boundary: r.on_boundary,
            diameters: r.diameters,
        }
    }
}

#[derive(Serialize, Deserialize)]
pub(super) struct ClusterRepr {
    #[serde(rename = "box")]
    bx: Box2,
    reason: UndecidedReason,
    #[serde(default, skip_deserializing)]
    reason_text: &'static str,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    diameters: Vec<f64>,
}

impl From<Cluster> for ClusterRepr {
    fn from(c: Cluster) -> Self {
        ClusterRepr {
            bx: c.bx,
            reason: c.reason,
            reason_text: c.reason.describe(),
            diameters: c.diameters,
        }
    }
}

impl From<ClusterRepr> for Cluster {
    fn from(c: ClusterRepr) -> Self {
        Cluster {
            bx: c.bx,
            reason: c.reason,
            diameters: c.diameters,
        }
    }
}
