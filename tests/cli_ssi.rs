//! `rootclip ssi` as a user runs it: two patch files in, the issue's JSON
//! out; bad input exits 2 with one line.

use serde_json::Value;
use std::process::Command;

fn write(name: &str, text: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("rootclip-cli-ssi-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

const PLANE: &str = r#"{"type": "tensor", "degree": [1, 1],
  "points": [[-1, -1, 0.5], [-1, 1, 0.5], [1, -1, 0.5], [1, 1, 0.5]]}"#;

/// z = x² + y² over [−1, 1]².
const BOWL: &str = r#"{"type": "tensor", "degree": [2, 2], "points": [
  [-1, -1, 2], [-1, 0, 0], [-1, 1, 2],
  [0, -1, 0], [0, 0, -2], [0, 1, 0],
  [1, -1, 2], [1, 0, 0], [1, 1, 2]]}"#;

#[test]
fn a_loop_in_json() {
    let (a, b) = (write("plane.json", PLANE), write("bowl.json", BOWL));
    let out = Command::new(env!("CARGO_BIN_EXE_rootclip"))
        .args(["ssi", "--a", a.to_str().unwrap(), "--b", b.to_str().unwrap(), "--json"])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["schema_version"], 1);
    assert_eq!(v["complete"], true);
    let br = v["branches"].as_array().unwrap();
    assert_eq!(br.len(), 1);
    assert_eq!(br[0]["closed"], true);
    for p in br[0]["points"].as_array().unwrap() {
        assert_eq!(p["certified"], true);
        let xyz: Vec<f64> = p["xyz"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        assert!((xyz[0] * xyz[0] + xyz[1] * xyz[1] - 0.5).abs() < 1e-9 && (xyz[2] - 0.5).abs() < 1e-12);
        assert_eq!(p["a"].as_array().unwrap().len(), 2);
        assert_eq!(p["b"].as_array().unwrap().len(), 2);
    }
    assert!(v["singular"].as_array().unwrap().is_empty());
}

#[test]
fn bad_input_is_one_line_and_exit_2() {
    let a = write("plane2.json", PLANE);
    let bad = write(
        "bad.json",
        r#"{"type": "tensor", "degree": [1, 1], "points": [[0, 0, 0]]}"#,
    );
    for args in [
        vec!["ssi", "--a", a.to_str().unwrap(), "--b", bad.to_str().unwrap()],
        vec![
            "ssi",
            "--a",
            a.to_str().unwrap(),
            "--b",
            a.to_str().unwrap(),
            "--tol",
            "0",
        ],
        vec!["ssi", "--a", "/nonexistent/a.json", "--b", a.to_str().unwrap()],
    ] {
        let out = Command::new(env!("CARGO_BIN_EXE_rootclip"))
            .args(&args)
            .output()
            .unwrap();
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(out.stdout.is_empty());
        assert!(err.starts_with("rootclip: ") && err.lines().count() == 1, "{err:?}");
    }
}
