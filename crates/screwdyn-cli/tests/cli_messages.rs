//! Issue 25 item 4, "say what happens": limit stops and a start outside the limits reported by
//! `simulate` (stderr and JSON), "wrote FILE" on a terminal for every command that writes a
//! file, "did you mean" for mistyped commands and flags, and `screwdyn` alone starting like
//! `--help`.

mod common;
use common::*;

/// The stderr of a run that must succeed.
fn stderr_of(args: &[&str]) -> String {
    let out = bin().args(args).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(out.status.success(), "{args:?}: {err}");
    err
}

#[test]
fn the_ur5s_passive_run_reports_the_stop_it_reaches() {
    // Issue 25: this run lost 95 % of its energy, and nothing said that a joint reached its
    // limit stop at 0.51 s. The time is checked against the run without the stops in the
    // library's tests (tests/limit_events.rs); here, that the CLI says it.
    let run = tmp("ur5_passive.json");
    let r = run.to_str().unwrap();
    let args = ["simulate", "builtin:ur5", "--duration", "1", "--output", r];
    let err = stderr_of(&args);
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 1, "{err}");
    assert!(
        lines[0].starts_with("screwdyn: warning: joint 'wrist_2_joint' hit its upper limit stop (6.28319 rad) at t = 0.51"),
        "{err}"
    );
    // The run file and the JSON summary carry the same event.
    let file: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&run).unwrap()).unwrap();
    let summary = json(&args);
    for events in [&file["events"], &summary["events"]] {
        let e = &events.as_array().unwrap()[0];
        assert_eq!(events.as_array().unwrap().len(), 1, "{events}");
        assert_eq!(
            (e["kind"].as_str(), e["joint"].as_str()),
            (Some("contact"), Some("wrist_2_joint"))
        );
        assert_eq!(e["side"], "upper");
        assert!((f(&e["t"]) - 0.51).abs() < 0.01, "{e}");
        assert_eq!(f(&e["bound"]), 2.0 * std::f64::consts::PI);
    }
    // Without the stops (all joint effects off) there is nothing to report.
    let quiet = stderr_of(&[
        "simulate",
        "builtin:ur5",
        "--duration",
        "1",
        "--no-effects",
        "--output",
        r,
    ]);
    assert_eq!(quiet, "");
}

#[test]
fn a_start_outside_the_limits_is_a_warning_saying_what_happens() {
    // The Panda's all-zero configuration has joint 4 above its upper limit −0.0698 rad.
    let err = stderr_of(&[
        "simulate",
        "builtin:panda",
        "--duration",
        "0.01",
        "--format",
        "csv",
    ]);
    assert!(
        err.starts_with("screwdyn: warning: joint 'panda_joint4' starts at 0 rad, above its upper limit -0.0698 rad: it is not moved inside before the run, the limit stop pushes it back from the first step\n"),
        "{err}"
    );
    // Started inside the limits, nothing is said.
    let inside = stderr_of(&[
        "simulate",
        "builtin:panda",
        "--duration",
        "0.01",
        "--q0",
        "0,0,0,-1.5,0,1.5,0",
        "--controller",
        "pd",
        "--format",
        "csv",
    ]);
    assert_eq!(inside, "");
}

/// Runs `args` with stderr on a pseudo-terminal (and stdout thrown away) by util-linux's
/// `script`; returns what reached the terminal, or `None` when `script` is not installed.
fn stderr_on_a_terminal(args: &[&str]) -> Option<String> {
    let quote = |s: &str| format!("'{}'", s.replace('\'', r"'\''"));
    let exe = assert_cmd::cargo::cargo_bin("screwdyn");
    let mut line = quote(exe.to_str().unwrap());
    for a in args {
        line.push(' ');
        line.push_str(&quote(a));
    }
    line.push_str(" >/dev/null");
    let out = std::process::Command::new("script")
        .args(["-qec", &line, "/dev/null"])
        .output()
        .ok()?;
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stdout)
    );
    // The progress bar clears its line (`ESC [2K`) without a new line.
    Some(
        String::from_utf8_lossy(&out.stdout)
            .replace("\r\n", "\n")
            .replace("\u{1b}[2K", "\n"),
    )
}

#[test]
fn every_command_that_writes_a_file_says_so_on_a_terminal() {
    let path = |name: &str| tmp(name).to_str().unwrap().to_string();
    let (csv, png, txt, urdf) = (
        path("said.csv"),
        path("said.png"),
        path("said.txt"),
        path("said.urdf"),
    );
    let (run, plot) = (path("said_run.json"), path("said_run.svg"));
    let cases: Vec<(Vec<&str>, Vec<&str>)> = vec![
        (
            vec![
                "torque-profile",
                "builtin:planar2",
                "--qf",
                "1,1",
                "--output",
                &csv,
                "--plot",
                &png,
            ],
            vec![&csv, &png],
        ),
        (
            vec![
                "symbolic",
                "builtin:planar2",
                "--quantity",
                "g",
                "--output",
                &txt,
            ],
            vec![&txt],
        ),
        (
            vec![
                "export",
                "builtin:planar2",
                "--to",
                "urdf",
                "--output",
                &urdf,
            ],
            vec![&urdf],
        ),
        (
            vec![
                "simulate",
                "builtin:pendulum",
                "--duration",
                "0.1",
                "--output",
                &run,
                "--plot",
                &plot,
            ],
            vec![&run, &plot],
        ),
    ];
    for (args, files) in &cases {
        let Some(text) = stderr_on_a_terminal(args) else {
            eprintln!("skipped: util-linux's `script` is not installed");
            return;
        };
        let wrote: Vec<String> = files.iter().map(|f| format!("wrote {f}")).collect();
        let said: Vec<&str> = text.lines().filter(|l| l.starts_with("wrote ")).collect();
        assert_eq!(said, wrote, "{args:?}: {text}");
        // Not a terminal (a script reading stderr): nothing is said.
        assert_eq!(stderr_of(args), "", "{args:?}");
    }
}

#[test]
fn mistyped_commands_and_flags_get_a_suggestion() {
    fails(
        &["jacobain", "builtin:ur5"],
        "unrecognized subcommand 'jacobain'; did you mean 'jacobian'?",
    );
    fails(
        &["fk", "builtin:ur5", "--qq", "0,0,0,0,0,0"],
        "unexpected argument '--qq' found; did you mean '--q'?",
    );
    fails(
        &["simulate", "builtin:ur5", "--duraton", "1"],
        "did you mean '--duration'?",
    );
    // Nothing close: no suggestion.
    let err = fails(&["xyzzy"], "unrecognized subcommand 'xyzzy'");
    assert!(!err.contains("did you mean"), "{err}");
}

#[test]
fn screwdyn_alone_starts_like_help() {
    let alone = bin().output().unwrap();
    assert_eq!(alone.status.code(), Some(2));
    let help = bin().arg("--help").output().unwrap();
    let first = |b: &[u8]| {
        String::from_utf8_lossy(b)
            .lines()
            .next()
            .unwrap_or("")
            .to_string()
    };
    let header = first(&help.stdout);
    assert_eq!(first(&alone.stderr), header);
    assert_eq!(
        header,
        "Kinematics and dynamics of robot manipulators, in the screw-theory notation."
    );
    // Both list every command.
    let text = String::from_utf8_lossy(&alone.stderr).to_string();
    for command in ["simulate", "torque-profile", "view", "identify", "symbolic"] {
        assert!(text.contains(&format!("  {command} ")), "{command}: {text}");
    }
}

#[test]
fn the_readme_lists_every_command_and_its_examples_name_real_files() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../../");
    let readme = std::fs::read_to_string(format!("{root}README.md")).unwrap();
    let help = ok(&["--help"]);
    let commands: Vec<&str> = help
        .lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .filter_map(|l| l.split_whitespace().next())
        .filter(|c| *c != "help")
        .collect();
    assert!(commands.len() > 20, "{help}");
    for c in &commands {
        assert!(
            readme.contains(&format!("| [`{c}`](docs/cli.md#")),
            "the README's command table misses '{c}'"
        );
    }
    // Installing needs the lock file's versions.
    assert!(readme.contains("cargo install --locked --path crates/screwdyn-cli"));
    // Every model file a README command line names is in the repository.
    for line in readme
        .lines()
        .filter(|l| l.starts_with("screwdyn ") || l.starts_with("$ screwdyn "))
    {
        for word in line.split_whitespace().filter(|w| w.starts_with("models/")) {
            assert!(
                std::path::Path::new(&format!("{root}{word}")).exists(),
                "{word} in: {line}"
            );
        }
    }
    // The README speaks of equations and references, not of documents the reader lacks.
    assert!(!readme.to_lowercase().contains("seed 00"));
}
