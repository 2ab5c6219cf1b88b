//! Helpers shared by the CLI integration tests: run the binary, parse its output, write files.
#![allow(dead_code)]

use assert_cmd::Command;
use serde_json::Value;
use std::path::PathBuf;

/// The URDF test robot of the library's tests (three revolute joints, fixed DH frames).
pub const ARM3: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../screwdyn/tests/data/arm3.urdf"
);

pub fn bin() -> Command {
    Command::cargo_bin("screwdyn").unwrap()
}

/// Runs a command that must succeed; returns stdout.
pub fn ok(args: &[&str]) -> String {
    let out = bin().args(args).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{args:?}: {err}");
    assert!(!err.contains("panicked"));
    String::from_utf8(out.stdout).unwrap()
}

/// Runs a command with `--format json`; returns the parsed output.
pub fn json(args: &[&str]) -> Value {
    let mut a = args.to_vec();
    a.extend(["--format", "json"]);
    serde_json::from_str(&ok(&a)).unwrap()
}

/// Runs a command that must fail with exit status 2 and one line on stderr containing `expected`
/// (after any `screwdyn: warning:` lines about the model).
pub fn fails(args: &[&str], expected: &str) -> String {
    let out = bin().args(args).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(
        err.contains(expected),
        "{args:?}: expected '{expected}' in: {err}"
    );
    assert!(!err.contains("panicked") && !err.contains("RUST_BACKTRACE"));
    let errors = err
        .trim()
        .lines()
        .filter(|l| !l.starts_with("screwdyn: warning: "));
    assert_eq!(errors.count(), 1, "one sentence: {err}");
    err
}

/// A fresh file path under the target's temporary directory.
pub fn tmp(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli-tests");
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// A number of a JSON value.
pub fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// A JSON list of numbers.
pub fn vec(v: &Value) -> Vec<f64> {
    v.as_array().unwrap().iter().map(f).collect()
}

/// A JSON list of rows.
pub fn mat(v: &Value) -> Vec<Vec<f64>> {
    v.as_array().unwrap().iter().map(vec).collect()
}

pub fn close(a: &[f64], b: &[f64], tol: f64) {
    assert_eq!(a.len(), b.len(), "{a:?} vs {b:?}");
    for (x, y) in a.iter().zip(b) {
        assert!((x - y).abs() <= tol * (1.0 + y.abs()), "{a:?} vs {b:?}");
    }
}

/// Comma-joined numbers for a flag.
pub fn csv(x: &[f64]) -> String {
    x.iter()
        .map(|v| v.to_string())
        .collect::<Vec<_>>()
        .join(",")
}

/// Deterministic pseudo-random numbers in [-1, 1).
pub struct Lcg(pub u64);
impl Lcg {
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }
    pub fn vec(&mut self, n: usize) -> Vec<f64> {
        (0..n).map(|_| self.next()).collect()
    }
}
