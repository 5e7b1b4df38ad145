//! The `rootclip` binary's input and output as a user sees them: `ray` and
//! `solve` run as processes, files and standard input, the JSON schema
//! (version, status and reason codes), and one clean error line for bad input.

use serde_json::Value;
use std::io::Write;
use std::path::PathBuf;
use std::process::{Command, Output, Stdio};

fn run_with_stdin(args: &[&str], stdin: &str) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_rootclip"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    // A process that rejects its arguments may exit before reading its
    // standard input; the pipe then breaks, which is not a test failure.
    match child.stdin.take().expect("stdin").write_all(stdin.as_bytes()) {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => {}
        r => r.expect("write stdin"),
    }
    child.wait_with_output().expect("the binary ends")
}

fn run(args: &[&str]) -> Output {
    run_with_stdin(args, "")
}

fn ok_json(args: &[&str], stdin: &str) -> Value {
    let out = run_with_stdin(args, stdin);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{args:?}: {stderr}");
    let v: Value = serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("{args:?}: not JSON ({e})"));
    assert_eq!(v["schema_version"], 1, "{args:?}: {v}");
    v
}

/// Exit code 2, nothing on stdout, one line on stderr starting `rootclip: `.
fn fails_cleanly(args: &[&str], stdin: &str) -> String {
    let out = run_with_stdin(args, stdin);
    let stderr = String::from_utf8(out.stderr).expect("UTF-8 stderr");
    assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
    assert!(
        out.stdout.is_empty(),
        "{args:?}: stdout {:?}",
        String::from_utf8_lossy(&out.stdout)
    );
    assert!(
        stderr.starts_with("rootclip: ") && stderr.ends_with('\n'),
        "{args:?}: {stderr:?}"
    );
    assert_eq!(stderr.lines().count(), 1, "{args:?}: {stderr:?}");
    stderr
}

struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("rootclip_{name}_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        Self(dir)
    }
    fn file(&self, name: &str, text: &str) -> String {
        let p = self.0.join(name);
        std::fs::write(&p, text).unwrap();
        p.display().to_string()
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        std::fs::remove_dir_all(&self.0).ok();
    }
}

const FLAT: &str = r#"{"type":"triangle","degree":1,"points":[[0,0,0],[1,0,0],[0,1,0]]}"#;

#[test]
fn ray_json_and_errors() {
    let dir = TempDir::new("ray_cli");
    let patch = dir.file("patch.json", FLAT);
    let rays = dir.file("rays.txt", "# two rays\n0.25 0.5 1  0 0 -1\n5 5 1 0 0 -1\n");
    let out = ok_json(&["ray", "--patch", &patch, "--rays", &rays, "--json"], "");
    let list = out["rays"].as_array().unwrap();
    assert_eq!(list.len(), 2);
    assert_eq!(list[0]["hits"].as_array().unwrap().len(), 1);
    let hit = &list[0]["hits"][0];
    assert_eq!(hit["certified"], true);
    assert_eq!(hit["status"], "certified");
    assert!(hit.get("reason").is_none(), "{hit}");
    assert_eq!(hit["normal"].as_array().unwrap().len(), 3);
    assert_eq!(hit["box"]["t"].as_array().unwrap().len(), 2);
    assert_eq!(list[1]["complete"], true);
    assert!(list[1]["hits"].as_array().unwrap().is_empty());
    // A single ray, text: the hit line shows the normal.
    let out = run(&[
        "ray",
        "--patch",
        &patch,
        "--origin",
        "0.25,0.5,1",
        "--dir",
        "0,0,-1",
        "--nearest",
    ]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.starts_with("ray 0: 1 hit(s), complete"), "{text}");
    assert!(text.contains("normal [0.000000, 0.000000, 1.000000]"), "{text}");
    // Both a single ray and a file: invalid option.
    let err = fails_cleanly(
        &[
            "ray", "--patch", &patch, "--rays", &rays, "--origin", "0,0,0", "--dir", "0,0,1",
        ],
        "",
    );
    assert!(err.contains("invalid option"), "{err}");
    // A wrong number of points, a negative weight, a misspelled key.
    let bad = dir.file("bad.json", r#"{"type":"tensor","degree":[1,1],"points":[[0,0,0]]}"#);
    assert!(fails_cleanly(&["ray", "--patch", &bad, "--rays", &rays], "").contains("shape"));
    let neg = dir.file(
        "neg.json",
        r#"{"type":"triangle","degree":1,"points":[[0,0,0],[1,0,0],[0,1,0]],"weights":[1,-1,1]}"#,
    );
    assert!(fails_cleanly(&["ray", "--patch", &neg, "--rays", &rays], "").contains("degenerate"));
    let typo = dir.file(
        "typo.json",
        r#"{"type":"triangle","degree":1,"points":[[0,0,0],[1,0,0],[0,1,0]],"weight":[1,1,1]}"#,
    );
    let err = fails_cleanly(&["ray", "--patch", &typo, "--rays", &rays], "");
    assert!(err.contains("weight"), "{err}");
    // A missing file is an I/O error, not a shape error.
    let err = fails_cleanly(&["ray", "--patch", "/nonexistent/patch.json", "--rays", &rays], "");
    assert!(err.contains("cannot read /nonexistent/patch.json"), "{err}");
    // A batch never aborts: a malformed line, a zero direction and a NaN
    // each get their error (with the line) in their place, the good rays
    // their answers, and the exit code is 1.
    let badrays = dir.file(
        "badrays.txt",
        "0.25 0.5 1 0 0 -1\n0 0 1 0 0\n# comment\n0.25 0.5 1 0 0 0\n0.25 nan 1 0 0 -1\n0.1 0.1 1 0 0 -1\n",
    );
    let out = run(&["ray", "--patch", &patch, "--rays", &badrays, "--json"]);
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("3 of 5 items failed"), "{stderr}");
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    let list = v["rays"].as_array().unwrap();
    assert_eq!(list.len(), 5);
    assert_eq!(list[0]["hits"][0]["status"], "certified");
    assert_eq!(list[4]["hits"][0]["status"], "certified");
    for (k, line, code) in [(1, 2, "format"), (2, 4, "degenerate"), (3, 5, "non_finite")] {
        assert_eq!(list[k]["error"]["line"], line, "{}", list[k]);
        assert_eq!(list[k]["error"]["code"], code, "{}", list[k]);
    }
    // Each ray's JSON is the library's serialization of its outcome.
    let lib = rootclip::ray::intersect(
        &rootclip::ray::Patch::from_spec(&serde_json::from_str(FLAT).unwrap()).unwrap(),
        &rootclip::ray::Ray::new(
            rootclip::glam::DVec3::new(0.25, 0.5, 1.0),
            rootclip::glam::DVec3::new(0.0, 0.0, -1.0),
        )
        .unwrap(),
        &rootclip::ray::RayOptions::default(),
    )
    .unwrap();
    assert_eq!(list[0], serde_json::to_value(&lib).unwrap());
    let back: rootclip::ray::RayOutcome = serde_json::from_value(list[0].clone()).unwrap();
    assert_eq!(back, lib);
    let text = String::from_utf8(run(&["ray", "--patch", &patch, "--rays", &badrays]).stdout).unwrap();
    assert!(text.contains("ray 1 (line 2): error: malformed input"), "{text}");
}

/// A reader that closes the pipe early (`rootclip ray … | head`) ends the
/// output quietly: exit 0, nothing on stderr (the output, streamed, is far
/// larger than the pipe's buffer, so the writes do meet the closed pipe).
#[test]
fn ray_output_into_a_closed_pipe() {
    use std::io::Read;
    let dir = TempDir::new("ray_pipe");
    let patch = dir.file("patch.json", FLAT);
    let line = "0.25 0.5 1 0 0 -1\n";
    let rays = dir.file("rays.txt", &line.repeat(5000));
    for json in [false, true] {
        let mut args = vec!["ray", "--patch", &patch, "--rays", &rays];
        if json {
            args.push("--json");
        }
        let mut child = Command::new(env!("CARGO_BIN_EXE_rootclip"))
            .args(&args)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("the binary runs");
        let mut head = [0u8; 100];
        child
            .stdout
            .take()
            .expect("stdout")
            .read_exact(&mut head)
            .expect("some output");
        // The pipe's read end is dropped here: the rest of the output meets a closed pipe.
        let out = child.wait_with_output().expect("the binary ends");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{args:?}: {:?} {stderr}", out.status);
        assert!(stderr.is_empty(), "{args:?}: {stderr}");
        let expected: &[u8] = if json {
            b"{\"schema_version\":1,\"rays\":["
        } else {
            b"ray 0: 1 hit(s)"
        };
        assert!(head.starts_with(expected), "{}", String::from_utf8_lossy(&head));
    }
}

#[test]
fn ray_reads_standard_input() {
    let dir = TempDir::new("ray_stdin");
    let patch = dir.file("patch.json", FLAT);
    let rays = dir.file("rays.txt", "0.25 0.5 1 0 0 -1\n");
    let a = ok_json(&["ray", "--patch", "-", "--rays", &rays, "--json"], FLAT);
    let b = ok_json(
        &["ray", "--patch", &patch, "--rays", "-", "--json"],
        "0.25 0.5 1 0 0 -1\n",
    );
    assert_eq!(a, b);
    assert_eq!(a["rays"][0]["hits"][0]["certified"], true);
    fails_cleanly(&["ray", "--patch", "-", "--rays", "-"], FLAT);
}

/// The `t` range: a hit at t = 1 is dropped by `--t-max 0.5`, kept by
/// `--t-min 1`; the origin exactly on the surface (t = 0) is a certified hit
/// of the default range `[0, ∞]` and of `--t-min 0`, and none of `--t-min
/// 1e-300` (settled exactly).
#[test]
fn ray_t_range() {
    let dir = TempDir::new("ray_range");
    let patch = dir.file("patch.json", FLAT);
    let hits = |extra: &[&str], origin: &str| -> Vec<Value> {
        let mut args = vec![
            "ray", "--patch", &patch, "--origin", origin, "--dir", "0,0,-1", "--json",
        ];
        args.extend_from_slice(extra);
        ok_json(&args, "")["rays"][0]["hits"].as_array().unwrap().clone()
    };
    assert_eq!(hits(&[], "0.25,0.25,1").len(), 1);
    assert!(hits(&["--t-max", "0.5"], "0.25,0.25,1").is_empty());
    assert_eq!(hits(&["--t-min", "1"], "0.25,0.25,1")[0]["status"], "certified");
    assert!(hits(&["--t-min", "1.0000001"], "0.25,0.25,1").is_empty());
    let on = hits(&[], "0.25,0.25,0");
    assert_eq!(on.len(), 1, "{on:?}");
    assert_eq!(on[0]["status"], "certified", "{on:?}");
    assert!(hits(&["--t-min", "1e-300"], "0.25,0.25,0").is_empty());
    // The whole line: a hit behind the origin.
    let behind = hits(&["--t-min", "-10"], "0.25,0.25,-1");
    assert_eq!(behind.len(), 1, "{behind:?}");
    assert!((behind[0]["t"].as_f64().unwrap() + 1.0).abs() < 1e-12);
    fails_cleanly(
        &[
            "ray", "--patch", &patch, "--origin", "0,0,1", "--dir", "0,0,-1", "--t-min", "2", "--t-max", "1",
        ],
        "",
    );
    fails_cleanly(
        &[
            "ray", "--patch", &patch, "--origin", "0,0,1", "--dir", "0,0,-1", "--t-min", "nan",
        ],
        "",
    );
}

/// A patch file's numbers are read as the exact binary numbers they name
/// (correctly rounded, as `str::parse` reads `--origin`): the corner
/// `x = 0.23394803155649946` (which a fast, not correctly rounded parser
/// reads one ulp low) meets a vertical ray at that `x` exactly on the edge
/// `u = 1`, a certified hit; one ulp beyond the edge, no hit.
#[test]
fn patch_numbers_are_read_exactly() {
    let dir = TempDir::new("ray_exact_numbers");
    let x = "0.23394803155649946";
    let patch = dir.file(
        "edge.json",
        &format!(r#"{{"type":"tensor","degree":[1,1],"points":[[0,0,0],[0,1,0],[{x},0,0],[{x},1,0]]}}"#),
    );
    let hits = |x0: f64| -> Vec<Value> {
        let origin = format!("{x0:e},0.5,1");
        let v = ok_json(
            &[
                "ray", "--patch", &patch, "--origin", &origin, "--dir", "0,0,-1", "--json",
            ],
            "",
        );
        assert_eq!(v["rays"][0]["complete"], true, "{v}");
        v["rays"][0]["hits"].as_array().unwrap().clone()
    };
    let x0: f64 = x.parse().unwrap();
    let on = hits(x0);
    assert_eq!(on.len(), 1, "{on:?}");
    assert_eq!(on[0]["status"], "certified", "{on:?}");
    assert_eq!(on[0]["u"], 1.0, "{on:?}");
    assert!(hits(f64::from_bits(x0.to_bits() + 1)).is_empty());
}

/// `bernstein --json` output is what `solve --f-bb` reads: the same system
/// from expressions and from BB files gives the same roots.
#[test]
fn solve_from_bb_files() {
    let dir = TempDir::new("solve_bb");
    for (domain, f, g) in [
        ("triangle", "u^3 - v", "u^3 + v - 1/4"),
        ("square", "u*v - 1/8", "u - v"),
    ] {
        let bb = |e: &str| {
            let out = run(&["bernstein", "--f", e, "--domain", domain, "--json"]);
            assert!(out.status.success());
            String::from_utf8(out.stdout).unwrap()
        };
        let (fp, gp) = (dir.file("f.json", &bb(f)), dir.file("g.json", &bb(g)));
        let from_bb = ok_json(&["solve", "--f-bb", &fp, "--g-bb", &gp, "--json"], "");
        let from_expr = ok_json(&["solve", "--f", f, "--g", g, "--domain", domain, "--json"], "");
        assert_eq!(from_bb["roots"], from_expr["roots"], "{domain}");
        assert_eq!(from_bb["roots"].as_array().unwrap().len(), 1, "{domain}");
        assert_eq!(from_bb["complete"], true);
        // Standard input for one of them.
        let stdin = ok_json(&["solve", "--f-bb", "-", "--g-bb", &gp, "--json"], &bb(f));
        assert_eq!(stdin["roots"], from_expr["roots"]);
    }
    // Hand-written: JSON numbers are exact floats, strings exact rationals.
    let f = dir.file(
        "hf.json",
        r#"{"domain":"triangle","degree":1,"coefficients":[
            {"i":0,"j":0,"k":1,"value":-0.25},{"i":1,"j":0,"k":0,"value":"3/4"},{"i":0,"j":1,"k":0,"value":-0.25}]}"#,
    );
    let g = dir.file(
        "hg.json",
        r#"{"domain":"triangle","degree":1,"coefficients":[
            {"i":0,"j":0,"k":1,"value":"-1/2"},{"i":1,"j":0,"k":0,"value":"-0.5"},{"i":0,"j":1,"k":0,"value":0.5}]}"#,
    );
    let sol = ok_json(&["solve", "--f-bb", &f, "--g-bb", &g, "--json"], "");
    let r = &sol["roots"][0]["box"];
    assert!(
        r["u"][0].as_f64().unwrap() <= 0.25 && 0.25 <= r["u"][1].as_f64().unwrap(),
        "{sol}"
    );
    assert!(
        r["v"][0].as_f64().unwrap() <= 0.5 && 0.5 <= r["v"][1].as_f64().unwrap(),
        "{sol}"
    );
    // A missing coefficient, an unknown key, mixed domains, a common factor.
    let missing = dir.file(
        "missing.json",
        r#"{"domain":"triangle","degree":1,"coefficients":[{"i":0,"j":0,"k":1,"value":"1"}]}"#,
    );
    assert!(fails_cleanly(&["solve", "--f-bb", &missing, "--g-bb", &g], "").contains("missing"));
    let unknown = dir.file(
        "unknown.json",
        r#"{"domain":"triangle","degree":0,"coefficients":[],"extra":1}"#,
    );
    assert!(fails_cleanly(&["solve", "--f-bb", &unknown, "--g-bb", &g], "").contains("extra"));
    let square = dir.file(
        "sq.json",
        r#"{"domain":"square","degree":[0,0],"coefficients":[{"i":0,"j":0,"value":"1"}]}"#,
    );
    fails_cleanly(&["solve", "--f-bb", &square, "--g-bb", &g], "");
    // A common factor: the factor, and the roots off its curve (f/f = 1: none).
    let v = ok_json(&["solve", "--f-bb", &f, "--g-bb", &f, "--json"], "");
    assert!(v["common_factor"].as_str().is_some_and(|h| h != "1"), "{v}");
    assert_eq!(v["roots"].as_array().unwrap().len(), 0);
    let v = ok_json(
        &["solve", "--f", "(u-v)*(u+v-1)", "--g", "(u-v)*(2*u-1/3)", "--json"],
        "",
    );
    assert_eq!(v["common_factor"], "-u + v");
    assert_eq!(v["roots"].as_array().unwrap().len(), 1);
    assert_eq!(v["roots"][0]["certified"], true);
    fails_cleanly(&["solve", "--f-bb", &f], "");
    fails_cleanly(&["solve", "--f", "u", "--f-bb", &f, "--g", "v"], "");
}

/// Clusters carry a machine-readable reason beside the English text, and a
/// NaN or non-positive `eps` is an invalid option.
#[test]
fn solve_json_reasons_and_options() {
    let v = ok_json(&["solve", "--f", "u^2 + v^2 - 1/4", "--g", "u*v - 1/8", "--json"], "");
    let c = &v["clusters"][0];
    assert_eq!(c["reason"], "multiple_or_close", "{v}");
    assert!(c["reason_text"].as_str().unwrap().contains("Krawczyk"), "{v}");
    assert_eq!(v["roots"].as_array().unwrap().len(), 0);
    for eps in ["nan", "0", "-1", "inf"] {
        let err = fails_cleanly(&["solve", "--f", "u - v", "--g", "u + v - 1/2", "--eps", eps], "");
        assert!(err.contains("invalid option"), "{eps}: {err}");
    }
}

#[test]
fn help_has_no_escaped_brackets() {
    for cmd in ["ray", "solve", "bernstein", "tables"] {
        let out = run(&[cmd, "--help"]);
        assert_eq!(out.status.code(), Some(0));
        let text = String::from_utf8(out.stdout).unwrap();
        assert!(!text.contains("\\["), "{cmd}: {text}");
        assert!(!text.contains('`'), "{cmd}: {text}");
    }
}

/// `crosscheck`: verdicts per claim in file order, missed hits, the nearest
/// hit, the summary; malformed claims name their line and exit 2.
#[test]
fn crosscheck_claims() {
    let dir = TempDir::new("crosscheck");
    let patch = dir.file("patch.json", FLAT);
    // Ray 0 hits (0.25, 0.5) at t = 1; ray 1 misses; ray 2 hits (0.1, 0.1) at t = 2.
    // Ray 0's last three claims have the right (u, v) and a wrong t.
    let rays = dir.file("rays.txt", "0.25 0.5 1 0 0 -1\n5 5 1 0 0 -1\n0.1 0.1 2 0 0 -1\n");
    let claims = dir.file(
        "claims.txt",
        "# ray u v t\n0 0.25 0.5 1\n0 0.25 0.500000000001 1\n0 0.6 0.2 1\n1 0.5 0.5 3\n\
         0 0.25 0.5 1.001\n0 0.25 0.5 2\n0 0.25 0.5 -1\n",
    );
    let v = ok_json(
        &[
            "crosscheck",
            "--patch",
            &patch,
            "--rays",
            &rays,
            "--claims",
            &claims,
            "--json",
        ],
        "",
    );
    let r = v["rays"].as_array().unwrap();
    assert_eq!(r.len(), 3);
    let verdicts = |k: usize| -> Vec<String> {
        r[k]["claims"]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| c["verdict"].as_str().unwrap().to_string())
            .collect()
    };
    assert_eq!(
        verdicts(0),
        ["confirmed", "duplicate", "spurious", "spurious", "spurious", "spurious"]
    );
    assert_eq!(verdicts(1), ["spurious"]);
    assert!(verdicts(2).is_empty());
    assert_eq!(r[0]["nearest_claimed"], true);
    assert_eq!(r[1]["nearest_claimed"], Value::Null);
    assert_eq!(r[2]["nearest_claimed"], false);
    assert_eq!(r[2]["missed"].as_array().unwrap().len(), 1);
    let k = r[2]["missed"][0].as_u64().unwrap() as usize;
    assert!((r[2]["hits"][k]["t"].as_f64().unwrap() - 2.0).abs() < 1e-12);
    // The confirmed claim names its hit; each ray is the library's Classification.
    assert_eq!(r[0]["claims"][0]["hit"], 0);
    let c: rootclip::ray::Classification = serde_json::from_value(r[0].clone()).unwrap();
    assert_eq!(serde_json::to_value(&c).unwrap(), r[0]);
    let s = &v["summary"];
    assert_eq!(
        [
            s["claims"].clone(),
            s["confirmed"].clone(),
            s["duplicate"].clone(),
            s["spurious"].clone(),
            s["undecided"].clone(),
            s["missed"].clone(),
            s["true_hits"].clone()
        ],
        [7, 1, 1, 5, 0, 1, 2].map(Value::from)
    );
    // A looser tol turns the third claim of ray 0 into... still spurious (0.35 away).
    let v = ok_json(
        &[
            "crosscheck",
            "--patch",
            &patch,
            "--rays",
            &rays,
            "--claims",
            &claims,
            "--tol",
            "0.1",
            "--json",
        ],
        "",
    );
    assert_eq!(v["rays"][0]["claims"][2]["verdict"], "spurious");
    // A malformed claim is listed with its line; the others are judged;
    // exit 1.
    for (bad, line) in [
        ("0 0.25 0.5\n", 1),
        ("0 0.25 0.5 1\n0 x 0.5 1\n", 2),
        ("0 0.25 NaN 1\n", 1),
        ("3 0.25 0.5 1\n", 1),
        ("-1 0.25 0.5 1\n", 1),
    ] {
        let c = dir.file("bad.txt", bad);
        let out = run(&[
            "crosscheck",
            "--patch",
            &patch,
            "--rays",
            &rays,
            "--claims",
            &c,
            "--json",
        ]);
        assert_eq!(out.status.code(), Some(1), "{bad:?}");
        let v: Value = serde_json::from_slice(&out.stdout).unwrap();
        let errs = v["claim_errors"].as_array().unwrap();
        assert_eq!(errs.len(), 1, "{bad:?}: {v}");
        assert_eq!(errs[0]["line"], line, "{bad:?}: {v}");
        assert_eq!(v["rays"].as_array().unwrap().len(), 3);
    }
    fails_cleanly(
        &[
            "crosscheck",
            "--patch",
            &patch,
            "--rays",
            &rays,
            "--claims",
            &claims,
            "--tol",
            "-1",
        ],
        "",
    );
}

#[test]
fn heuristics_example_json_and_errors() {
    let v = ok_json(&["heuristics", "--example", "2", "--json"], "");
    assert_eq!(v["example"], "2");
    let runs = v["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 4 * 121);
    let methods = ["newton", "halley", "first-order", "second-order"];
    for (k, r) in runs.iter().enumerate() {
        assert_eq!(r["method"], methods[k / 121], "{r}");
        let start = r["start"].as_array().unwrap();
        assert_eq!(start.len(), 2);
        assert!(r["iterations"].as_u64().is_some(), "{r}");
        let verdict = r["verdict"].as_str().unwrap();
        assert!(
            ["correct", "wrong_hit", "not_a_hit", "undecided", "failed"].contains(&verdict),
            "{r}"
        );
        if verdict == "failed" {
            assert!(r["end"].is_null() && r["reason"].is_string(), "{r}");
        } else {
            for key in ["u", "v", "t"] {
                assert!(r["end"][key].is_f64(), "{r}");
            }
        }
    }
    // Starts run u0 outer, v0 inner over 0, 0.1, …, 1.
    assert_eq!(runs[1]["start"][1].as_f64(), Some(0.1));
    assert_eq!(runs[11]["start"][0].as_f64(), Some(0.1));
    // Example 2 has two hits: some starts end at the farther one.
    assert!(runs.iter().any(|r| r["verdict"] == "correct"));
    assert!(runs.iter().any(|r| r["verdict"] == "wrong_hit"));
    let summary = v["summary"].as_array().unwrap();
    assert_eq!(summary.len(), 4);
    let correct: u64 = summary.iter().map(|s| s["correct"].as_u64().unwrap()).sum();
    assert_eq!(
        correct as usize,
        runs.iter().filter(|r| r["verdict"] == "correct").count()
    );
    // Options reach the iterations.
    let v = ok_json(&["heuristics", "--example", "1", "--max-iterations", "1", "--json"], "");
    assert!(v["runs"]
        .as_array()
        .unwrap()
        .iter()
        .all(|r| r["iterations"].as_u64().unwrap() <= 1));
    assert_eq!(v["options"]["max_iterations"], 1);
    // Text: one summary row per method.
    let out = run(&["heuristics", "--example", "3"]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        out.status.success() && text.contains("second-order") && text.starts_with("Example 3"),
        "{text}"
    );
    // Bad input: one line, exit 2.
    for bad in [
        &["heuristics", "--example", "4"][..],
        &["heuristics", "--example", "0"],
        &["heuristics", "--example", "two"],
        &["heuristics"],
        &["heuristics", "--example", "1", "--tol", "-1"],
        &["heuristics", "--example", "1", "--max-iterations", "0"],
        &["heuristics", "--example", "1", "--domain-rule", "bounce"],
    ] {
        fails_cleanly(bad, "");
    }
}

/// The JSON shapes docs/cli.md shows are what the commands print: every key
/// in a section's example block appears in the command's real output, and
/// every key of the real output (outside `stats`, whose counters the
/// example elides) appears in the block.
#[test]
fn documented_json_matches_the_output() {
    let doc = std::fs::read_to_string(format!("{}/docs/cli.md", env!("CARGO_MANIFEST_DIR"))).unwrap();
    // The first ```json block after "JSON:" in a section.
    let block = |heading: &str| -> String {
        let at = doc.find(heading).unwrap_or_else(|| panic!("no section {heading}"));
        let at = at + doc[at..].find("\nJSON:").expect("a JSON paragraph");
        let rest = &doc[at..];
        let start = rest.find("```json").expect("a JSON block") + 7;
        let end = rest[start..].find("```").unwrap();
        rest[start..start + end].to_string()
    };
    let doc_keys = |text: &str| -> std::collections::BTreeSet<String> {
        text.split('"')
            .collect::<Vec<_>>()
            .windows(2)
            .filter(|w| w[1].trim_start().starts_with(':'))
            .map(|w| w[0].to_string())
            .filter(|k| k != "...")
            .collect()
    };
    // Every key, and the keys outside `elided` objects (`stats`, whose
    // counters the examples elide; crosscheck's `hits`, documented by
    // reference to `rootclip ray`).
    type Keys = std::collections::BTreeSet<String>;
    fn real_keys(v: &Value, elided: &[&str], under: bool, all: &mut Keys, main: &mut Keys) {
        match v {
            Value::Object(m) => {
                for (k, x) in m {
                    all.insert(k.clone());
                    if !under {
                        main.insert(k.clone());
                    }
                    real_keys(x, elided, under || elided.contains(&k.as_str()), all, main);
                }
            }
            Value::Array(a) => a.iter().for_each(|x| real_keys(x, elided, under, all, main)),
            _ => {}
        }
    }
    let dir = TempDir::new("doc_json");
    let patch = dir.file("patch.json", FLAT);
    let rays = dir.file(
        "rays.txt",
        "0.25 0.5 1 0 0 -1\n0.25 0.5 0 1 0 0\n0 0 1 0 0 0\n0.1 0.1 2 0 0 -1\n",
    );
    let claims = dir.file("claims.txt", "0 0.25 0.5 1\n3 0.2 0.2 2\n9 0 0 0\n");
    let saddle = dir.file(
        "saddle.json",
        r#"{"type":"tensor","degree":[1,1],"points":[[0,0,1],[0,1,-1],[1,0,-1],[1,1,1]]}"#,
    );
    let cases: [(&str, Vec<&str>); 3] = [
        (
            "## `rootclip solve`",
            vec![
                "solve",
                "--f",
                "u^2 + v^2 - 1/4",
                "--g",
                "16*u*v - 1",
                "--triangle-route",
                "triangle",
                "--json",
            ],
        ),
        (
            "## `rootclip ray`",
            vec!["ray", "--patch", &patch, "--rays", &rays, "--json"],
        ),
        (
            "## `rootclip crosscheck`",
            vec![
                "crosscheck",
                "--patch",
                &patch,
                "--rays",
                &rays,
                "--claims",
                &claims,
                "--json",
            ],
        ),
    ];
    for (heading, args) in cases {
        let out = run(&args);
        let mut v: Value = serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("{args:?}: {e}"));
        if heading.contains("ray`") {
            // Add a ray along the surface for `degenerate`, `hits_complete`.
            let along = ok_json(
                &[
                    "ray", "--patch", &saddle, "--origin", "-1,0.5,0", "--dir", "1,0,0", "--json",
                ],
                "",
            );
            v["rays"].as_array_mut().unwrap().push(along["rays"][0].clone());
        }
        if heading.contains("solve`") {
            // A cluster (a double root) and a leftover tri-box (a budget of 1).
            let double = ok_json(&["solve", "--f", "(u-1/3)^2 + (v-1/3)^2", "--g", "u - v", "--json"], "");
            let left = ok_json(
                &[
                    "solve",
                    "--f",
                    "u^2 + v^2 - 1/4",
                    "--g",
                    "16*u*v - 1",
                    "--triangle-route",
                    "triangle",
                    "--max-boxes",
                    "1",
                    "--json",
                ],
                "",
            );
            v["clusters"] = double["clusters"].clone();
            v["leftovers"] = left["leftovers"].clone();
        }
        let (mut all, mut main) = (Keys::new(), Keys::new());
        let elided: &[&str] = if heading.contains("crosscheck") {
            &["stats", "hits"]
        } else {
            &["stats"]
        };
        real_keys(&v, elided, false, &mut all, &mut main);
        let documented = doc_keys(&block(heading));
        let missing: Vec<_> = documented.difference(&all).collect();
        let undocumented: Vec<_> = main.difference(&documented).collect();
        assert!(missing.is_empty(), "{heading}: documented but not printed: {missing:?}");
        assert!(
            undocumented.is_empty(),
            "{heading}: printed but not documented: {undocumented:?}"
        );
    }
}
