//! Certified projection (`rootclip::project::project_batch`) of 2000 points
//! on Pei, Wang & Zhang's (2019) Table 4 Bézier surface (bidegree (4, 3)), parameters from a
//! fixed stream, `P = S(u, v)` (inversion) and `P = S(u, v) + 0.2 N`
//! (projection from off the surface): `project/table4-on`,
//! `project/table4-off`, on rayon's default pool; and one thread,
//! `project/table4-on-1thread`. Divide by 2000 for the time per point; the
//! whole-process timing of `rootclip project` and the heuristics of the same
//! paper are in `papers/multipoint-inversion-2019/inversion.md`.
//!
//! `cargo bench --bench project` takes about half a minute.

use criterion::{criterion_group, criterion_main, Criterion};
use rootclip::glam::DVec3;
use rootclip::project::{project_batch, ProjectOptions};
use rootclip::ray::{Patch, TensorPatch};
use std::hint::black_box;
use std::time::Duration;

const POINTS: usize = 2000;

fn table4() -> Patch {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/papers/multipoint-inversion-2019/paper_data_inversion.json"
    ))
    .expect("paper data");
    let data: serde_json::Value = serde_json::from_str(&text).expect("json");
    let pts: Vec<DVec3> = data["table4_bezier"]["points"]
        .as_array()
        .expect("rows")
        .iter()
        .flat_map(|row| row.as_array().expect("row").clone())
        .map(|p| {
            let c: Vec<f64> = p
                .as_array()
                .expect("point")
                .iter()
                .map(|x| x.as_f64().expect("number"))
                .collect();
            DVec3::new(c[0], c[1], c[2])
        })
        .collect();
    TensorPatch::new(4, 3, pts, None).expect("patch").into()
}

fn params() -> Vec<[f64; 2]> {
    let mut x: u64 = 0x5eed_0001_2019;
    let mut next = move || {
        x = x.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (x >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..POINTS).map(|_| [next(), next()]).collect()
}

fn bench(c: &mut Criterion) {
    let patch = table4();
    let Patch::Tensor(t) = &patch else { unreachable!() };
    let on: Vec<DVec3> = params().iter().map(|&[u, v]| patch.eval(u, v)).collect();
    let off: Vec<DVec3> = params()
        .iter()
        .map(|&[u, v]| patch.eval(u, v) + 0.2 * t.normal(u, v))
        .collect();
    let opts = ProjectOptions::default();
    let mut g = c.benchmark_group("project");
    g.sample_size(10);
    g.bench_function("table4-on", |b| b.iter(|| black_box(project_batch(&patch, &on, &opts))));
    g.bench_function("table4-off", |b| {
        b.iter(|| black_box(project_batch(&patch, &off, &opts)))
    });
    let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().expect("pool");
    g.bench_function("table4-on-1thread", |b| {
        b.iter(|| one.install(|| black_box(project_batch(&patch, &on, &opts))))
    });
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().measurement_time(Duration::from_secs(5)).warm_up_time(Duration::from_secs(1));
    targets = bench
}
criterion_main!(benches);
