//! Files in and out: batch `--input` streamed row by row (same results as one call per state,
//! JSON arrays, errors naming the line, binary input refused), atomic output files that never
//! overwrite an input, and CSV/XML names escaped.

mod common;
use common::*;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command as Process;

/// `n` random UR5 states as a CSV file with q, v, a columns; returns the path and the states.
fn ur5_states(name: &str, n: usize, seed: u64) -> (PathBuf, Vec<[Vec<f64>; 3]>) {
    let joints = json(&["info", "builtin:ur5"])["joints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|j| j["name"].as_str().unwrap().to_string())
        .collect::<Vec<_>>();
    let mut text = String::new();
    let header: Vec<String> = ["q", "v", "a"]
        .iter()
        .flat_map(|k| joints.iter().map(move |j| format!("{k}.{j}")))
        .collect();
    text.push_str(&header.join(","));
    text.push('\n');
    let mut r = Lcg(seed);
    let mut states = Vec::new();
    for _ in 0..n {
        let s = [r.vec(6), r.vec(6), r.vec(6)];
        let cells: Vec<String> = s.iter().flatten().map(|x| x.to_string()).collect();
        text.push_str(&cells.join(","));
        text.push('\n');
        states.push(s);
    }
    let p = tmp(name);
    std::fs::write(&p, text).unwrap();
    (p, states)
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn batch_rows_equal_single_calls() {
    let (p, states) = ur5_states("stream_states.csv", 2000, 11);
    // JSON: one array, one object per row; each object is what the single call prints.
    let batch = json(&["rnea", "builtin:ur5", "--input", s(&p)]);
    let rows = batch.as_array().expect("a JSON array");
    assert_eq!(rows.len(), states.len());
    let csv_out = ok(&["rnea", "builtin:ur5", "--input", s(&p), "--format", "csv"]);
    let csv_rows: Vec<&str> = csv_out.lines().collect();
    assert_eq!(csv_rows.len(), states.len() + 1);
    for k in [0, 1, 777, 1999] {
        let [q, v, a] = &states[k];
        let single = json(&[
            "rnea",
            "builtin:ur5",
            "--q",
            &csv(q),
            "--v",
            &csv(v),
            "--a",
            &csv(a),
        ]);
        assert_eq!(rows[k], single, "row {k}");
        // CSV: the same numbers, shortest round-trip text (parses back to the same f64).
        let cells: Vec<f64> = csv_rows[k + 1]
            .split(',')
            .map(|c| c.parse().unwrap())
            .collect();
        assert_eq!(cells, vec(&single["tau"]), "row {k}");
        let single_csv = ok(&[
            "rnea",
            "builtin:ur5",
            "--q",
            &csv(q),
            "--v",
            &csv(v),
            "--a",
            &csv(a),
            "--format",
            "csv",
        ]);
        assert_eq!(single_csv.lines().nth(1).unwrap(), csv_rows[k + 1]);
    }
    // Maps and words stream as JSON too: fk (frame → pose) and jacobian (frame, reference).
    for cmd in [
        vec!["fk", "builtin:ur5"],
        vec!["jacobian", "builtin:ur5", "--reference", "local"],
    ] {
        let mut args = cmd.clone();
        args.extend(["--input", s(&p)]);
        let batch = json(&args);
        let rows = batch.as_array().expect("a JSON array");
        assert_eq!(rows.len(), states.len());
        let mut single = cmd.clone();
        let q = csv(&states[1234][0]);
        single.extend(["--q", &q]);
        assert_eq!(rows[1234], json(&single), "{cmd:?}");
    }
}

#[test]
fn batch_errors_name_their_line() {
    let (p, _) = ur5_states("stream_bad_row.csv", 1500, 5);
    let mut text = std::fs::read_to_string(&p).unwrap();
    text.push_str("0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,x1\n");
    std::fs::write(&p, text).unwrap();
    // 1 header line + 1500 rows: the bad row is on line 1502.
    fails(
        &["rnea", "builtin:ur5", "--input", s(&p)],
        "stream_bad_row.csv:1502: column 'a.wrist_3_joint': 'x1' is not a number",
    );
    // Binary data: a NUL byte, /dev/zero, and a line without end.
    let bin = tmp("stream_binary.csv");
    std::fs::write(&bin, b"q.shoulder_pan_joint\n0.5\n1\x00\x01\x02\n").unwrap();
    fails(
        &["rnea", "builtin:ur5", "--input", s(&bin)],
        "stream_binary.csv: line 3 contains a NUL byte",
    );
    fails(
        &["rnea", "builtin:ur5", "--input", "/dev/zero"],
        "/dev/zero: line 1 contains a NUL byte",
    );
    let long = tmp("stream_long.csv");
    std::fs::write(&long, "1".repeat(9 << 20)).unwrap();
    fails(
        &["rnea", "builtin:ur5", "--input", s(&long)],
        "line 1 is longer than 8 MiB",
    );
    let empty = tmp("stream_empty.csv");
    std::fs::write(&empty, "q.shoulder_pan_joint\n").unwrap();
    let out = bin_output(&["rnea", "builtin:ur5", "--input", s(&empty)]);
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty(), "nothing printed before the error");
}

fn bin_output(args: &[&str]) -> std::process::Output {
    bin().args(args).output().unwrap()
}

/// A two-joint robot whose names need quoting in CSV and escaping in XML.
const ODD_NAMES: &str = r#"<?xml version="1.0"?>
<robot name="odd--robot &quot;x&quot; &lt;1&gt; &amp; 'y'-">
  <link name="base"/>
  <link name="l,1">
    <inertial><mass value="1"/><origin xyz="0.1 0 0"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
  <link name="l2">
    <inertial><mass value="1"/><origin xyz="0.1 0 0"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
  <joint name="j1" type="revolute">
    <parent link="base"/><child link="l,1"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="10" velocity="2"/>
  </joint>
  <joint name="j&quot;2,x" type="continuous">
    <parent link="l,1"/><child link="l2"/><origin xyz="0.2 0 0"/><axis xyz="0 1 0"/>
  </joint>
</robot>
"#;

fn csv_header(text: &str) -> Vec<String> {
    let mut r = csv::Reader::from_reader(text.as_bytes());
    r.headers().unwrap().iter().map(String::from).collect()
}

#[test]
fn csv_and_xml_escape_names() {
    let p = tmp("odd_names.urdf");
    std::fs::write(&p, ODD_NAMES).unwrap();
    let m = s(&p);
    // rnea CSV: read back by a CSV reader, the header names the joint as it is.
    let out = ok(&["rnea", m, "--q", "0.1,0.2", "--format", "csv"]);
    assert_eq!(csv_header(&out), ["tau.j1", "tau.j\"2,x"]);
    // Batch input naming that joint in a quoted column, and fk columns with the link `l,1`.
    let input = tmp("odd_states.csv");
    std::fs::write(&input, "q.j1,\"q.j\"\"2,x\"\n0.1,0.2\n0.3,0.4\n").unwrap();
    let out = ok(&["fk", m, "--input", s(&input), "--format", "csv"]);
    let header = csv_header(&out);
    assert!(header.contains(&"poses.l,1.1.4".to_string()), "{header:?}");
    assert_eq!(out.lines().count(), 3);
    // simulate's run file: `t`, then q/v/a/tau of each joint, then the energies.
    let run = tmp("odd_run.csv");
    ok(&[
        "simulate",
        m,
        "--duration",
        "0.01",
        "--dt",
        "0.001",
        "--output",
        s(&run),
    ]);
    let text = std::fs::read_to_string(&run).unwrap();
    let header = csv_header(&text);
    assert_eq!(header.len(), 1 + 4 * 2 + 3);
    assert_eq!(header[2], "q.j\"2,x");
    assert_eq!(header[8], "tau.j\"2,x");
    let mut rows = csv::Reader::from_reader(text.as_bytes());
    assert!(rows.records().all(|r| r.unwrap().len() == header.len()));
    // export: the robot name in the comment and the attribute survives a round trip.
    let out = tmp("odd_export.urdf");
    ok(&["export", m, "--to", "urdf", "--output", s(&out)]);
    let name = json(&["info", s(&out)])["model"].clone();
    assert_eq!(name, json(&["info", m])["model"]);
    assert_eq!(name, "odd--robot \"x\" <1> & 'y'-");
    let again = json(&["info", s(&out)])["joints"][1]["name"].clone();
    assert_eq!(again, "j\"2,x");
}

/// Files in `dir` whose name starts with `.NAME.` (the temporary files of the writes to NAME).
fn leftovers(dir: &Path, name: &str) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
        .filter(|f| f.starts_with(&format!(".{name}.")))
        .collect()
}

#[test]
fn outputs_never_overwrite_inputs() {
    let dir = tmp("inputs");
    std::fs::create_dir_all(&dir).unwrap();
    let model = dir.join("m.urdf");
    std::fs::copy(ARM3, &model).unwrap();
    let before = std::fs::read(&model).unwrap();
    fails(
        &["export", s(&model), "--to", "urdf", "--output", s(&model)],
        "is an input of this command",
    );
    // The same file by another spelling and through a symbolic link.
    let other = format!("{}/../inputs/./m.urdf", dir.display());
    fails(
        &["export", s(&model), "--to", "urdf", "--output", &other],
        "is an input of this command",
    );
    let link = dir.join("link.urdf");
    let _ = std::fs::remove_file(&link);
    std::os::unix::fs::symlink(&model, &link).unwrap();
    fails(
        &["export", s(&link), "--to", "urdf", "--output", s(&model)],
        "is an input of this command",
    );
    assert_eq!(
        std::fs::read(&model).unwrap(),
        before,
        "the model is unchanged"
    );
    // simulate and torque-profile: the model and the torque series are inputs.
    let series = dir.join("tau.csv");
    std::fs::write(&series, "t,tau.joint1\n0,1\n1,1\n").unwrap();
    let series_before = std::fs::read(&series).unwrap();
    fails(
        &[
            "simulate",
            "builtin:planar2",
            "--controller",
            "series",
            "--torque-csv",
            s(&series),
            "--output",
            s(&series),
        ],
        "--output",
    );
    assert_eq!(std::fs::read(&series).unwrap(), series_before);
    let plot_in = dir.join("m.svg");
    std::fs::write(&plot_in, "<svg/>").unwrap();
    fails(&["simulate", s(&plot_in), "--plot", s(&plot_in)], "--plot");
    assert_eq!(std::fs::read(&plot_in).unwrap(), b"<svg/>");
    assert!(leftovers(&dir, "m.urdf").is_empty() && leftovers(&dir, "tau.csv").is_empty());
}

#[test]
fn failed_writes_leave_the_target_intact() {
    let dir = tmp("failing");
    std::fs::create_dir_all(&dir).unwrap();
    // Into a directory that does not exist: an error, nothing created.
    let missing = dir.join("no/such/dir/run.csv");
    fails(
        &["simulate", "builtin:planar2", "--output", s(&missing)],
        "cannot write",
    );
    assert!(!dir.join("no").exists());
    // Onto a directory: the rename fails, the directory and its content stay, no temporary file.
    let target = dir.join("taken.csv");
    std::fs::create_dir_all(&target).unwrap();
    std::fs::write(target.join("keep"), "x").unwrap();
    fails(
        &["simulate", "builtin:planar2", "--output", s(&target)],
        "cannot write",
    );
    assert_eq!(std::fs::read(target.join("keep")).unwrap(), b"x");
    assert!(leftovers(&dir, "taken.csv").is_empty());
    // A write that fails part-way (file size limit of 4 KiB, SIGXFSZ ignored so the write
    // returns EFBIG): the previous file is kept whole and the partial one removed.
    let run = dir.join("run.csv");
    std::fs::write(&run, "previous run\n").unwrap();
    let out = Process::new("sh")
        .arg("-c")
        .arg(format!(
            "trap '' XFSZ; ulimit -f 8; exec {} simulate builtin:ur5 --duration 0.2 --output {}",
            env!("CARGO_BIN_EXE_screwdyn"),
            s(&run)
        ))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("cannot write") && err.contains("run.csv"),
        "{err}"
    );
    assert_eq!(std::fs::read(&run).unwrap(), b"previous run\n");
    assert!(leftovers(&dir, "run.csv").is_empty());
    // The same for a plot and for export.
    let png = dir.join("plot.png");
    std::fs::write(&png, "previous plot").unwrap();
    let out = Process::new("sh")
        .arg("-c")
        .arg(format!(
            "trap '' XFSZ; ulimit -f 8; exec {} simulate builtin:ur5 --duration 0.05 --plot {}",
            env!("CARGO_BIN_EXE_screwdyn"),
            s(&png)
        ))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(std::fs::read(&png).unwrap(), b"previous plot");
    assert!(leftovers(&dir, "plot.png").is_empty());
}

#[test]
fn concurrent_outputs_do_not_interleave() {
    let dir = tmp("concurrent");
    std::fs::create_dir_all(&dir).unwrap();
    let target = dir.join("same.csv");
    let args = |q0: &str, out: &Path| {
        vec![
            "simulate".to_string(),
            "builtin:ur5".into(),
            "--duration".into(),
            "0.3".into(),
            "--q0".into(),
            q0.into(),
            "--output".into(),
            s(out).into(),
        ]
    };
    // What each run writes on its own.
    let q0s = ["0.1,0,0,0,0,0", "0,0.2,0,0,0,0"];
    let alone: Vec<Vec<u8>> = q0s
        .iter()
        .enumerate()
        .map(|(k, q0)| {
            let p = dir.join(format!("alone{k}.csv"));
            ok(&args(q0, &p).iter().map(String::as_str).collect::<Vec<_>>());
            std::fs::read(&p).unwrap()
        })
        .collect();
    assert_ne!(alone[0], alone[1]);
    for _ in 0..2 {
        let children: Vec<_> = q0s
            .iter()
            .map(|q0| {
                Process::new(env!("CARGO_BIN_EXE_screwdyn"))
                    .args(args(q0, &target))
                    .spawn()
                    .unwrap()
            })
            .collect();
        for mut c in children {
            assert!(c.wait().unwrap().success());
        }
        let got = std::fs::read(&target).unwrap();
        assert!(got == alone[0] || got == alone[1], "a mix of the two runs");
        assert!(leftovers(&dir, "same.csv").is_empty());
    }
}

#[test]
fn json_batch_is_one_array_when_piped_to_a_parser() {
    // Every row's object is complete and the array closes: the whole output is one document.
    let (p, states) = ur5_states("stream_json.csv", 300, 21);
    let out = ok(&["crba", "builtin:ur5", "--input", s(&p), "--format", "json"]);
    let v: Value = serde_json::from_str(&out).expect("one JSON document");
    assert_eq!(v.as_array().unwrap().len(), states.len());
    assert!(v
        .as_array()
        .unwrap()
        .iter()
        .all(|r| r["mass_matrix"].as_array().is_some_and(|m| m.len() == 6)));
}
