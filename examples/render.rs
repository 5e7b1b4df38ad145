//! Ray traces the Utah teapot (32 bicubic patches) and three triangular Bézier
//! patches into a PNG, every visible point a certified ray–patch hit.
//!
//! `cargo run --release --example render -- [--width W] [--height H] [--out PATH] [--no-shadows]`
//!
//! * Scene: the teapot from `examples/data/teapot.txt` (Newell's 306 vertices
//!   and 32 patches, z up), standing on a floor of two flat quadratic
//!   triangles (checkered), beside a rational quadratic triangle whose edges
//!   are exact quarter circles (a sphere octant, nearly) and a cubic
//!   triangular dome.
//! * Per pixel: one primary ray; each patch is first tested against its
//!   control net's bounding box (the patch lies in the net's convex hull, so
//!   a missed box proves a missed patch), boxes are visited nearest first and
//!   the search stops once a certified hit is nearer than the next box. The
//!   pixel shows the nearest certified hit with `t > 0`, Lambert-shaded with
//!   a little ambient light; one shadow ray per lit pixel towards the
//!   (directional) light.
//! * Pixels whose answer is not proven are painted magenta and counted: a
//!   `Degenerate` outcome or an undecided region that may lie in front of the
//!   nearest certified hit (primary rays), or a shadow ray that finds an
//!   undecided region or a degenerate patch and no certified hit.
//! * Rows run in parallel (rayon); a progress bar shows on stderr when it is
//!   a terminal. The end prints rays, ray–patch calls, time, µs per ray and
//!   the failure counts; with the default `--out` it also rewrites
//!   `papers/render/README.md` with them.

use glam::DVec3;
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;
use rootclip::ray::{intersect, Patch, Query, Ray, RayOptions, RayOutcome, TensorPatch, TriPatch};
use std::error::Error;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

type Res<T> = Result<T, Box<dyn Error>>;

const ROOT: &str = env!("CARGO_MANIFEST_DIR");
const DEFAULT_OUT: &str = "papers/render/teapot.png";
/// Pixels whose answer is not proven.
const DEBUG: DVec3 = DVec3::new(1.0, 0.0, 1.0);
const AMBIENT: f64 = 0.15;

fn main() -> Res<()> {
    let args = Args::parse()?;
    let scene = Scene::build()?;
    let opts = RayOptions::default();
    let camera = Camera::new(args.width, args.height);
    let bar = ProgressBar::new(args.height as u64);
    bar.set_style(ProgressStyle::with_template(
        "rendering {bar:40} {pos}/{len} rows, {elapsed}, eta {eta}",
    )?);
    let start = Instant::now();
    let rows: Vec<(Vec<[u8; 3]>, Stats)> = (0..args.height)
        .into_par_iter()
        .map(|y| {
            let row = render_row(&scene, &camera, y, args.shadows, &opts);
            bar.inc(1);
            row
        })
        .collect();
    let time = start.elapsed();
    bar.finish_and_clear();
    let stats = rows.iter().fold(Stats::default(), |a, (_, s)| a.add(s));
    let pixels: Vec<u8> = rows.iter().flat_map(|(r, _)| r.iter().flatten().copied()).collect();
    let default_out = Path::new(ROOT).join(DEFAULT_OUT);
    let out = args.out.clone().unwrap_or_else(|| default_out.clone());
    if let Some(dir) = out.parent() {
        std::fs::create_dir_all(dir)?;
    }
    write_png(&out, args.width, args.height, &pixels)?;
    let report = Report {
        args: &args,
        scene: &scene,
        stats,
        time,
        threads: rayon::current_num_threads(),
    };
    println!("{}", report.summary());
    eprintln!("wrote {}", out.display());
    if args.out.is_none() {
        let readme = Path::new(ROOT).join("papers/render/README.md");
        std::fs::write(&readme, report.readme())?;
        eprintln!("wrote {}", readme.display());
    }
    Ok(())
}

struct Args {
    width: usize,
    height: usize,
    /// `None`: the default, `papers/render/teapot.png` in the crate, which
    /// also rewrites `papers/render/README.md`.
    out: Option<PathBuf>,
    shadows: bool,
}

impl Args {
    fn parse() -> Res<Self> {
        let mut a = Args {
            width: 320,
            height: 240,
            out: None,
            shadows: true,
        };
        let mut it = std::env::args().skip(1);
        while let Some(x) = it.next() {
            let mut value = || it.next().ok_or_else(|| format!("{x} needs a value"));
            match x.as_str() {
                "--width" => a.width = value()?.parse()?,
                "--height" => a.height = value()?.parse()?,
                "--out" => a.out = Some(PathBuf::from(value()?)),
                "--no-shadows" => a.shadows = false,
                _ => {
                    return Err(format!("unknown argument '{x}' (--width W --height H --out PATH --no-shadows)").into())
                }
            }
        }
        if a.width == 0 || a.height == 0 {
            return Err("width and height must be positive".into());
        }
        Ok(a)
    }
}

// ---------------------------------------------------------------- scene

#[derive(Clone, Copy, Debug, PartialEq)]
enum Material {
    Teapot,
    Floor,
    Octant,
    Dome,
}

impl Material {
    fn albedo(self, p: DVec3) -> DVec3 {
        match self {
            Material::Teapot => DVec3::new(0.92, 0.86, 0.74),
            Material::Floor => {
                let odd = (p.x.floor() + p.y.floor()).rem_euclid(2.0) == 1.0;
                if odd {
                    DVec3::new(0.55, 0.55, 0.6)
                } else {
                    DVec3::new(0.85, 0.85, 0.88)
                }
            }
            Material::Octant => DVec3::new(0.3, 0.5, 0.9),
            Material::Dome => DVec3::new(0.35, 0.75, 0.4),
        }
    }
}

/// A patch with its control net's bounding box, padded by 1e-9 of the scene
/// size (far more than the rounding of the slab test, so a missed box is a
/// proof).
struct Object {
    patch: Patch,
    lo: DVec3,
    hi: DVec3,
    material: Material,
}

impl Object {
    fn new(patch: Patch, material: Material) -> Self {
        let (lo, hi) = patch.points().iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(l, h), p| (l.min(*p), h.max(*p)),
        );
        let pad = DVec3::splat(1e-9 * (1.0 + lo.abs().max(hi.abs()).max_element()));
        Self {
            patch,
            lo: lo - pad,
            hi: hi + pad,
            material,
        }
    }

    /// The parameter where the ray enters the box, if it meets it at `t ≥ 0`.
    fn entry(&self, ray: &Ray) -> Option<f64> {
        let (o, d) = (ray.origin(), ray.dir());
        let (mut t0, mut t1) = (0.0_f64, f64::INFINITY);
        for k in 0..3 {
            if d[k] == 0.0 {
                if o[k] < self.lo[k] || o[k] > self.hi[k] {
                    return None;
                }
                continue;
            }
            let (a, b) = ((self.lo[k] - o[k]) / d[k], (self.hi[k] - o[k]) / d[k]);
            t0 = t0.max(a.min(b));
            t1 = t1.min(a.max(b));
        }
        (t0 <= t1).then_some(t0)
    }
}

struct Scene {
    objects: Vec<Object>,
    /// Unit vector towards the (directional) light.
    to_light: DVec3,
    teapot_patches: usize,
}

impl Scene {
    fn build() -> Res<Self> {
        let teapot = read_teapot(&Path::new(ROOT).join("examples/data/teapot.txt"))?;
        let teapot_patches = teapot.len();
        let mut objects: Vec<Object> = teapot.into_iter().map(|p| Object::new(p, Material::Teapot)).collect();
        for p in floor()? {
            objects.push(Object::new(p, Material::Floor));
        }
        objects.push(Object::new(octant(DVec3::new(2.8, -2.1, 0.0), 1.3)?, Material::Octant));
        objects.push(Object::new(dome()?, Material::Dome));
        Ok(Self {
            objects,
            to_light: DVec3::new(-0.55, -0.9, 1.4).normalize(),
            teapot_patches,
        })
    }
}

/// The teapot file: `patches N`, N lines of 16 zero-based vertex indices
/// (row-major 4 × 4), `vertices M`, M lines `x y z`; `#` comments.
fn read_teapot(path: &Path) -> Res<Vec<Patch>> {
    let text = std::fs::read_to_string(path)?;
    let lines: Vec<&str> = text
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .collect();
    let count = |at: usize, key: &str| -> Res<usize> {
        let l = lines.get(at).ok_or("teapot file ends early")?;
        let n = l
            .strip_prefix(key)
            .ok_or_else(|| format!("expected '{key} N', found '{l}'"))?;
        Ok(n.trim().parse()?)
    };
    let numbers = |at: usize| -> Res<Vec<f64>> {
        let l = lines.get(at).ok_or("teapot file ends early")?;
        Ok(l.split_whitespace().map(str::parse).collect::<Result<_, _>>()?)
    };
    let n_patches = count(0, "patches")?;
    let n_vertices = count(n_patches + 1, "vertices")?;
    let vertices = (0..n_vertices)
        .map(|k| match numbers(n_patches + 2 + k)?.as_slice() {
            &[x, y, z] => Ok(DVec3::new(x, y, z)),
            _ => Err("a vertex needs 3 coordinates".into()),
        })
        .collect::<Res<Vec<DVec3>>>()?;
    (0..n_patches)
        .map(|k| {
            let ix = numbers(1 + k)?;
            if ix.len() != 16 {
                return Err("a patch needs 16 vertex indices".into());
            }
            let pts = ix
                .iter()
                .map(|&i| vertices.get(i as usize).copied().ok_or("vertex index out of range"))
                .collect::<Result<Vec<_>, _>>()?;
            Ok(TensorPatch::new(3, 3, pts, None)?.into())
        })
        .collect()
}

/// Control point order of a triangular patch of degree `n`: `j` outer, `i`
/// inner, `B_ij = u^i v^j w^(n−i−j)` (see [`TriPatch`]).
fn tri_points(n: usize, at: impl Fn(usize, usize) -> DVec3) -> Vec<DVec3> {
    (0..=n)
        .flat_map(|j| (0..=n - j).map(move |i| (i, j)))
        .map(|(i, j)| at(i, j))
        .collect()
}

/// The floor `z = 0`, `[-12, 12] × [-10, 14]`, as two flat quadratic triangles.
fn floor() -> Res<[Patch; 2]> {
    let (a, b, c, d) = (
        DVec3::new(-12.0, -10.0, 0.0),
        DVec3::new(12.0, -10.0, 0.0),
        DVec3::new(12.0, 14.0, 0.0),
        DVec3::new(-12.0, 14.0, 0.0),
    );
    let flat = |w: DVec3, u: DVec3, v: DVec3| -> Res<Patch> {
        let pts = tri_points(2, |i, j| w + (u - w) * (i as f64 / 2.0) + (v - w) * (j as f64 / 2.0));
        Ok(TriPatch::new(2, pts, None)?.into())
    };
    Ok([flat(a, b, c)?, flat(a, c, d)?])
}

/// A rational quadratic triangle with corners `c + r·e_k` and edge control
/// points `c + r(e_k + e_l)` of weight `1/√2`: every edge is an exact quarter
/// circle around `c`, the interior close to the sphere (a quadratic cannot
/// be exactly spherical). `e_1, e_2` horizontal, turned so the patch bulges
/// towards the camera (−y); `e_3 = z`.
fn octant(c: DVec3, r: f64) -> Res<Patch> {
    let s = std::f64::consts::FRAC_1_SQRT_2;
    let e = [DVec3::new(s, -s, 0.0), DVec3::new(-s, -s, 0.0), DVec3::Z];
    // B_ij = u^i v^j w^(2−i−j); the corners u, v, w = 1 sit at e[1], e[2], e[0]
    // and an edge's middle control point at the sum of its corners' vectors.
    let dir = |i: usize, j: usize| e[1] * i.min(1) as f64 + e[2] * j.min(1) as f64 + e[0] * (2 - i - j).min(1) as f64;
    let pts = tri_points(2, |i, j| c + r * dir(i, j));
    let weights = tri_points(2, |i, j| {
        let corner = i == 2 || j == 2 || i + j == 0;
        DVec3::splat(if corner { 1.0 } else { s })
    });
    Ok(TriPatch::new(2, pts, Some(weights.iter().map(|w| w.x).collect()))?.into())
}

/// A cubic triangle on the floor, its inner control point raised: a dome.
fn dome() -> Res<Patch> {
    let (w, u, v) = (
        DVec3::new(-4.4, -2.6, 0.0),
        DVec3::new(-2.6, -3.3, 0.0),
        DVec3::new(-3.4, -1.1, 0.0),
    );
    let pts = tri_points(3, |i, j| {
        let k = 3 - i - j;
        let base = (w * k as f64 + u * i as f64 + v * j as f64) / 3.0;
        let inner = i > 0 && j > 0 && k > 0;
        let edge = !inner && (i, j, k) != (3, 0, 0) && (i, j, k) != (0, 3, 0) && (i, j, k) != (0, 0, 3);
        base + DVec3::Z
            * if inner {
                4.5
            } else if edge {
                0.8
            } else {
                0.0
            }
    });
    Ok(TriPatch::new(3, pts, None)?.into())
}

// ---------------------------------------------------------------- camera

struct Camera {
    width: usize,
    eye: DVec3,
    /// Pixel (0, 0)'s direction, and the steps to the next column and row.
    corner: DVec3,
    dx: DVec3,
    dy: DVec3,
}

impl Camera {
    fn new(width: usize, height: usize) -> Self {
        let eye = DVec3::new(3.2, -11.5, 6.2);
        let target = DVec3::new(0.0, -0.6, 1.2);
        let fwd = (target - eye).normalize();
        let right = fwd.cross(DVec3::Z).normalize();
        let up = right.cross(fwd);
        let half_h = (32f64.to_radians() / 2.0).tan();
        let half_w = half_h * width as f64 / height as f64;
        let dx = right * (2.0 * half_w / width as f64);
        let dy = -up * (2.0 * half_h / height as f64);
        Self {
            width,
            eye,
            corner: fwd - right * half_w + up * half_h + (dx + dy) / 2.0,
            dx,
            dy,
        }
    }

    fn ray(&self, x: usize, y: usize) -> Ray {
        Ray::new(self.eye, self.corner + self.dx * x as f64 + self.dy * y as f64).expect("finite, non-zero")
    }
}

// ---------------------------------------------------------------- tracing

/// Counts over a set of pixels.
#[derive(Clone, Copy, Debug, Default)]
struct Stats {
    primary: usize,
    shadow: usize,
    /// `intersect` calls (ray–patch pairs that passed the box test).
    calls: usize,
    hit_pixels: usize,
    /// Primary rays with a `Degenerate` outcome or an undecided region that
    /// may be in front of the nearest certified hit.
    primary_doubtful: usize,
    /// Shadow rays that found no certified blocker but an undecided region or
    /// a degenerate patch.
    shadow_doubtful: usize,
    degenerate_outcomes: usize,
    undecided_regions: usize,
}

impl Stats {
    fn add(self, o: &Stats) -> Stats {
        Stats {
            primary: self.primary + o.primary,
            shadow: self.shadow + o.shadow,
            calls: self.calls + o.calls,
            hit_pixels: self.hit_pixels + o.hit_pixels,
            primary_doubtful: self.primary_doubtful + o.primary_doubtful,
            shadow_doubtful: self.shadow_doubtful + o.shadow_doubtful,
            degenerate_outcomes: self.degenerate_outcomes + o.degenerate_outcomes,
            undecided_regions: self.undecided_regions + o.undecided_regions,
        }
    }
}

fn render_row(scene: &Scene, cam: &Camera, y: usize, shadows: bool, opts: &RayOptions) -> (Vec<[u8; 3]>, Stats) {
    let mut st = Stats::default();
    let px = (0..cam.width)
        .map(|x| {
            let c = shade(scene, &cam.ray(x, y), shadows, opts, &mut st);
            c.map(|v| (v.clamp(0.0, 1.0).powf(1.0 / 2.2) * 255.0).round() as u8)
        })
        .collect();
    (px, st)
}

/// The colour of one primary ray.
fn shade(scene: &Scene, ray: &Ray, shadows: bool, opts: &RayOptions, st: &mut Stats) -> [f64; 3] {
    st.primary += 1;
    let near = nearest(scene, ray, opts, st);
    if near.doubtful {
        st.primary_doubtful += 1;
        return DEBUG.to_array();
    }
    let Some((k, p, n)) = near.hit else {
        return sky(ray.dir()).to_array();
    };
    st.hit_pixels += 1;
    let mut n = if n == DVec3::ZERO { -ray.dir().normalize() } else { n };
    if n.dot(ray.dir()) > 0.0 {
        n = -n;
    }
    let albedo = scene.objects[k].material.albedo(p);
    let lambert = n.dot(scene.to_light).max(0.0);
    let lit = if lambert > 0.0 && shadows {
        match blocked(scene, p + 1e-6 * n, opts, st) {
            Some(b) => !b,
            None => {
                st.shadow_doubtful += 1;
                return DEBUG.to_array();
            }
        }
    } else {
        lambert > 0.0
    };
    let light = AMBIENT + (1.0 - AMBIENT) * if lit { lambert } else { 0.0 };
    (albedo * light).to_array()
}

fn sky(d: DVec3) -> DVec3 {
    let s = (d.normalize().z * 2.0).clamp(0.0, 1.0);
    DVec3::new(0.8, 0.87, 0.95).lerp(DVec3::new(0.45, 0.6, 0.85), s)
}

/// The nearest hit of a primary ray: object index, point and normal.
struct Nearest {
    hit: Option<(usize, DVec3, DVec3)>,
    doubtful: bool,
}

fn nearest(scene: &Scene, ray: &Ray, opts: &RayOptions, st: &mut Stats) -> Nearest {
    let mut order: Vec<(f64, usize)> = scene
        .objects
        .iter()
        .enumerate()
        .filter_map(|(k, o)| o.entry(ray).map(|t| (t, k)))
        .collect();
    order.sort_by(|a, b| a.0.total_cmp(&b.0));
    // Best certified hit so far: (t upper bound, object, point, normal).
    let mut best: Option<(f64, usize, DVec3, DVec3)> = None;
    // Lower `t` bounds of whatever might be in front: undecided regions, and
    // the box entry of a patch whose answer was degenerate.
    let mut doubts: Vec<f64> = Vec::new();
    for (entry, k) in order {
        if best.is_some_and(|b| entry > b.0) {
            break;
        }
        st.calls += 1;
        let near = opts.clone().with_query(Query::Nearest);
        match intersect(&scene.objects[k].patch, ray, &near) {
            Ok(RayOutcome::Hits(h)) => {
                for hit in &h.hits {
                    if hit.is_certified() && hit.bx.t[0] > 0.0 {
                        if best.is_none_or(|b| hit.bx.t[1] < b.0) {
                            best = Some((hit.bx.t[1], k, hit.point, hit.normal));
                        }
                    } else {
                        st.undecided_regions += 1;
                        doubts.push(hit.bx.t[0]);
                    }
                }
            }
            Ok(RayOutcome::Degenerate(_)) | Err(_) => {
                st.degenerate_outcomes += 1;
                doubts.push(entry);
            }
        }
    }
    let limit = best.map_or(f64::INFINITY, |b| b.0);
    Nearest {
        hit: best.map(|b| (b.1, b.2, b.3)),
        doubtful: doubts.iter().any(|&t| t <= limit),
    }
}

/// Whether anything lies between `p` and the light: `Some(true)` proven
/// blocked (a certified hit with `t > 0`), `Some(false)` proven free,
/// `None` undecided.
fn blocked(scene: &Scene, p: DVec3, opts: &RayOptions, st: &mut Stats) -> Option<bool> {
    st.shadow += 1;
    let ray = Ray::new(p, scene.to_light).expect("finite, non-zero");
    let mut doubt = false;
    for o in &scene.objects {
        if o.entry(&ray).is_none() {
            continue;
        }
        st.calls += 1;
        let any = opts.clone().with_query(Query::Any);
        match intersect(&o.patch, &ray, &any) {
            Ok(RayOutcome::Hits(h)) => {
                for hit in &h.hits {
                    if hit.is_certified() && hit.bx.t[0] > 0.0 {
                        return Some(true);
                    }
                    // A region straddling t = 0 is the surface the ray leaves.
                    if hit.bx.t[0] > 0.0 {
                        st.undecided_regions += 1;
                        doubt = true;
                    }
                }
            }
            Ok(RayOutcome::Degenerate(_)) | Err(_) => {
                st.degenerate_outcomes += 1;
                doubt = true;
            }
        }
    }
    (!doubt).then_some(false)
}

fn write_png(path: &Path, w: usize, h: usize, rgb: &[u8]) -> Res<()> {
    let file = std::io::BufWriter::new(std::fs::File::create(path)?);
    let mut enc = png::Encoder::new(file, w as u32, h as u32);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    enc.write_header()?.write_image_data(rgb)?;
    Ok(())
}

// ---------------------------------------------------------------- report

struct Report<'a> {
    args: &'a Args,
    scene: &'a Scene,
    stats: Stats,
    time: Duration,
    threads: usize,
}

impl Report<'_> {
    fn summary(&self) -> String {
        let (s, secs) = (&self.stats, self.time.as_secs_f64());
        let rays = s.primary + s.shadow;
        format!(
            "{}×{}: {} primary + {} shadow rays = {rays} rays, {} ray–patch intersect calls; {secs:.2} s wall on {} threads = {:.1} µs/ray, {:.1} µs/call per thread; {} pixels hit; {} doubtful primary + {} doubtful shadow rays (painted magenta), {} degenerate outcomes, {} undecided regions",
            self.args.width,
            self.args.height,
            s.primary,
            s.shadow,
            s.calls,
            self.threads,
            secs * 1e6 / rays.max(1) as f64,
            secs * 1e6 * self.threads as f64 / s.calls.max(1) as f64,
            s.hit_pixels,
            s.primary_doubtful,
            s.shadow_doubtful,
            s.degenerate_outcomes,
            s.undecided_regions
        )
    }

    fn readme(&self) -> String {
        let mut r = String::new();
        let s = &self.stats;
        let n_obj = self.scene.objects.len();
        r.push_str("# Certified ray tracing: the Utah teapot\n\n");
        r.push_str("<!-- Generated by `cargo run --release --example render`; do not edit by hand. -->\n\n");
        r.push_str("![teapot](teapot.png)\n\n");
        let _ = writeln!(
            r,
            "{} patches: the Utah teapot's {} bicubic patches (Newell's data, `examples/data/teapot.txt`), a floor \
             of two flat quadratic triangles, a rational quadratic triangle with quarter-circle edges (blue) and a \
             cubic triangular dome (green). Every shaded pixel is the nearest **certified** hit of its primary ray \
             (`rootclip::ray::intersect`, nearest-hit query for primary rays, any-hit for shadow rays: a `(u, v)` box proven to hold exactly one intersection); each patch is \
             first culled by its control net's bounding box. Lambert shading with {AMBIENT} ambient and one shadow \
             ray per lit pixel{}. Magenta marks pixels whose answer is not proven (a degenerate outcome or an \
             undecided region that may be nearer than the certified hit, or an undecided shadow ray).\n",
            n_obj,
            self.scene.teapot_patches,
            if self.args.shadows { "" } else { " (off in this run)" }
        );
        r.push_str("| | |\n|---|---:|\n");
        let secs = self.time.as_secs_f64();
        let rays = s.primary + s.shadow;
        let rows = [
            ("image", format!("{} × {}", self.args.width, self.args.height)),
            ("primary rays", thousands(s.primary)),
            ("shadow rays", thousands(s.shadow)),
            ("pixels showing a patch", thousands(s.hit_pixels)),
            ("ray–patch `intersect` calls (after box culling)", thousands(s.calls)),
            ("wall time", format!("{secs:.2} s on {} threads", self.threads)),
            ("per ray (wall)", format!("{:.1} µs", secs * 1e6 / rays.max(1) as f64)),
            (
                "per `intersect` call (per thread)",
                format!("{:.1} µs", secs * 1e6 * self.threads as f64 / s.calls.max(1) as f64),
            ),
            ("doubtful primary rays (magenta)", thousands(s.primary_doubtful)),
            ("doubtful shadow rays (magenta)", thousands(s.shadow_doubtful)),
            ("`Degenerate` outcomes", thousands(s.degenerate_outcomes)),
            ("undecided regions met", thousands(s.undecided_regions)),
        ];
        for (k, v) in rows {
            let _ = writeln!(r, "| {k} | {v} |");
        }
        let _ = writeln!(
            r,
            "\nMeasured on {}, {}. Rerun:\n\n```sh\ncargo run --release --example render -- [--width W --height H] \
             [--out PATH] [--no-shadows]\n```\n\nWith the default `--out` ({DEFAULT_OUT}) this README is rewritten \
             with the new numbers.",
            machine(),
            provenance()
        );
        r
    }
}

fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|x| x.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let threads = std::thread::available_parallelism().map_or(0, |n| n.get());
    format!("{cpu}, {threads} hardware threads shared with other jobs")
}

/// The commit the numbers come from, and whether `src/` had local changes.
fn provenance() -> String {
    let git = |args: &[&str]| {
        let o = std::process::Command::new("git")
            .args(args)
            .current_dir(ROOT)
            .output()
            .ok()?;
        o.status
            .success()
            .then(|| String::from_utf8_lossy(&o.stdout).trim().to_string())
    };
    let Some(h) = git(&["rev-parse", "--short", "HEAD"]) else {
        return "rootclip (commit unknown)".into();
    };
    let dirty = git(&["status", "--porcelain", "--", "src"]).is_some_and(|s| !s.is_empty());
    format!(
        "rootclip at commit `{h}`{}",
        if dirty {
            " with uncommitted changes in `src/`"
        } else {
            ""
        }
    )
}

/// `76800` → `76,800`.
fn thousands(n: usize) -> String {
    let d = n.to_string();
    let mut out = String::new();
    for (k, ch) in d.chars().enumerate() {
        if k > 0 && (d.len() - k) % 3 == 0 {
            out.push(',');
        }
        out.push(ch);
    }
    out
}
