//! `simulate`, `torque-profile` (with plots), `export`, `check` and `info`.

mod common;
use common::*;
use screwdyn::io::load_model;
use screwdyn::sim::{self, PdGravity, SimOptions, Trajectory, Trapezoid};

/// Decodes a PNG; returns (width, height, RGB pixels row-major).
fn decode_png(path: &std::path::Path) -> (u32, u32, Vec<[u8; 3]>) {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    let step = info.color_type.samples();
    let px = buf[..info.buffer_size()]
        .chunks(step)
        .map(|c| [c[0], c[1], c[2]])
        .collect();
    (info.width, info.height, px)
}

/// The plot is the expected size and every stacked panel has drawn, coloured content.
fn check_plot(path: &std::path::Path, panels: u32) {
    let (w, h, px) = decode_png(path);
    assert_eq!((w, h), (1300, 60 + 300 * panels));
    for p in 0..panels {
        let rows = (60 + 300 * p + 20)..(60 + 300 * (p + 1) - 20);
        let mut colours = std::collections::HashSet::new();
        let mut non_white = 0;
        for y in rows {
            for x in 0..w {
                let c = px[(y * w + x) as usize];
                if c != [255, 255, 255] {
                    non_white += 1;
                }
                colours.insert(c);
            }
        }
        assert!(colours.len() > 20, "panel {p}: {} colours", colours.len());
        assert!(non_white > 5000, "panel {p}: {non_white} drawn pixels");
    }
}

#[test]
fn simulate_writes_design_columns_and_matches_the_library() {
    let csv_path = tmp("pd.csv");
    let png = tmp("pd.png");
    let out = json(&[
        "simulate",
        "builtin:planar2",
        "--controller",
        "pd",
        "--target",
        "0.5,-0.3",
        "--kp",
        "50",
        "--kd",
        "15",
        "--duration",
        "1",
        "--dt",
        "0.001",
        "--record-every",
        "100",
        "--output",
        csv_path.to_str().unwrap(),
        "--plot",
        png.to_str().unwrap(),
    ]);
    let text = std::fs::read_to_string(&csv_path).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(
        lines[0],
        "t,q.joint1,q.joint2,v.joint1,v.joint2,a.joint1,a.joint2,tau.joint1,tau.joint2,kinetic_energy,potential_energy,total_energy"
    );
    assert_eq!(lines.len(), 1 + 11);
    // The library's own simulation with the same options is the reference.
    let m = load_model("builtin:planar2").unwrap();
    let mut pd = PdGravity::new(m.clone(), vec![0.5, -0.3], vec![50.0; 2], vec![15.0; 2]).unwrap();
    let opts = SimOptions {
        duration: 1.0,
        dt: 1e-3,
        record_every: 100,
        ..Default::default()
    };
    let rec = sim::simulate(
        &m,
        &[0.0, 0.0],
        &[0.0, 0.0],
        &mut pd,
        &[],
        &opts,
        &mut |_| {},
    )
    .unwrap();
    let last: Vec<f64> = lines[11].split(',').map(|c| c.parse().unwrap()).collect();
    close(&last[1..3], rec.q.last().unwrap(), 1e-12);
    close(&vec(&out["q"]), rec.q.last().unwrap(), 1e-12);
    check_plot(&png, 4);

    // JSON run file: the same names as arrays.
    let json_path = tmp("zero.json");
    ok(&[
        "simulate",
        "builtin:pendulum",
        "--q0",
        "0.1",
        "--duration",
        "0.6",
        "--no-effects",
        "--output",
        json_path.to_str().unwrap(),
        "--format",
        "json",
    ]);
    let run: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json_path).unwrap()).unwrap();
    for key in [
        "t",
        "q.pivot",
        "v.pivot",
        "a.pivot",
        "tau.pivot",
        "kinetic_energy",
        "potential_energy",
        "total_energy",
    ] {
        assert_eq!(run[key].as_array().unwrap().len(), 601, "{key}");
    }
    // Passive swing with RK4: energy conserved; past a quarter period (0.50 s) q < 0.
    let e = vec(&run["total_energy"]);
    assert!((e[0] - e[600]).abs() < 1e-8);
    assert!(vec(&run["q.pivot"])[600] < 0.0);
}

#[test]
fn simulate_to_stdout_and_other_controllers() {
    // Without --output the run itself goes to stdout.
    let out = ok(&[
        "simulate",
        "builtin:pendulum",
        "--duration",
        "0.01",
        "--format",
        "csv",
    ]);
    assert_eq!(out.lines().count(), 1 + 11);
    // Constant torque m g l on a horizontal pendulum holds it: τ = g sin(π/2) = 9.81.
    let out = json(&[
        "simulate",
        "builtin:pendulum",
        "--q0",
        "1.5707963267948966",
        "--controller",
        "constant",
        "--tau",
        "9.81",
        "--duration",
        "0.2",
        "--output",
        tmp("c.csv").to_str().unwrap(),
    ]);
    close(&vec(&out["q"]), &[std::f64::consts::FRAC_PI_2], 1e-9);
    // Computed torque tracks the quintic to the target.
    let out = json(&[
        "simulate",
        "builtin:planar2",
        "--controller",
        "computed-torque",
        "--target",
        "0.4,0.2",
        "--duration",
        "1",
        "--integrator",
        "dopri5",
        "--method",
        "crba",
        "--output",
        tmp("ct.json").to_str().unwrap(),
    ]);
    close(&vec(&out["q"]), &[0.4, 0.2], 1e-6);
    // A torque series from a file: columns t, tau.<joint>.
    let series = tmp("series.csv");
    std::fs::write(&series, "t,tau.pivot\n0,9.81\n1,9.81\n").unwrap();
    let out = json(&[
        "simulate",
        "builtin:pendulum",
        "--q0",
        "1.5707963267948966",
        "--controller",
        "series",
        "--torque-csv",
        series.to_str().unwrap(),
        "--duration",
        "0.2",
        "--integrator",
        "euler",
        "--output",
        tmp("s.csv").to_str().unwrap(),
    ]);
    close(&vec(&out["q"]), &[std::f64::consts::FRAC_PI_2], 1e-9);
    // A disturbance pushes the resting pendulum; damping removes energy.
    let out = json(&[
        "simulate",
        "builtin:pendulum",
        "--disturbance",
        "bob:0,0,1,1,0,0@world@0-0.1",
        "--damping",
        "0.5",
        "--duration",
        "0.5",
        "--output",
        tmp("d.csv").to_str().unwrap(),
    ]);
    assert!(vec(&out["q"])[0] > 0.001);
}

#[test]
fn torque_profile_answers_seed_003_for_the_ur5() {
    let png = tmp("tp.png");
    let qf = "1,-1,1.5,0.5,0.5,0.5";
    let out = json(&[
        "torque-profile",
        "builtin:ur5",
        "--trajectory",
        "trapezoid",
        "--qf",
        qf,
        "--vmax",
        "1",
        "--amax",
        "2",
        "--dt",
        "0.01",
        "--plot",
        png.to_str().unwrap(),
    ]);
    let m = load_model("builtin:ur5").unwrap();
    let traj = Trapezoid::new(
        &[0.0; 6],
        &[1.0, -1.0, 1.5, 0.5, 0.5, 0.5],
        &[1.0; 6],
        &[2.0; 6],
        true,
    )
    .unwrap();
    let p = sim::torque_profile(&m, &traj, 0.01).unwrap();
    close(&vec(&out["peak"]), &p.peak, 1e-12);
    close(&vec(&out["rms"]), &p.rms, 1e-12);
    close(
        &vec(&out["effort_limit"]),
        &[150.0, 150.0, 150.0, 28.0, 28.0, 28.0],
        0.0,
    );
    close(&[f(&out["duration"])], &[traj.duration()], 1e-12);
    assert_eq!(out["violations"]["elbow_joint"]["count"].as_u64(), Some(0));
    assert!(out["violations"]["elbow_joint"]["first_time"].is_null());
    check_plot(&png, 3);

    // A fast quintic on the planar arm with a low gravity-free limit: violations are reported.
    let out = json(&[
        "torque-profile",
        "builtin:ur5",
        "--trajectory",
        "quintic",
        "--qf",
        "3,-3,3,3,3,3",
        "--duration",
        "0.3",
        "--dt",
        "0.01",
    ]);
    let v = &out["violations"]["shoulder_lift_joint"];
    assert!(f(&v["count"]) > 0.0);
    assert!(f(&v["worst"]) > 150.0);
    assert!(f(&v["first_time"]) >= 0.0);
    let table = ok(&[
        "torque-profile",
        "builtin:ur5",
        "--trajectory",
        "quintic",
        "--qf",
        "3,-3,3,3,3,3",
        "--duration",
        "0.3",
        "--dt",
        "0.01",
        "--format",
        "table",
    ]);
    assert!(table.contains("over the effort limit: ") && table.contains("shoulder_lift_joint"));
}

#[test]
fn svg_plots_and_help() {
    let svg = tmp("run.svg");
    ok(&[
        "simulate",
        "builtin:pendulum",
        "--q0",
        "0.5",
        "--duration",
        "0.2",
        "--plot",
        svg.to_str().unwrap(),
        "--format",
        "table",
    ]);
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.contains("<svg") && text.contains("pivot") && text.contains("Energy"));
    let help = ok(&["inverse-dynamics", "--help"]);
    assert!(help.contains("default: all zero") && help.contains("--input"));
    let help = ok(&["--help"]);
    for cmd in [
        "torque-profile",
        "closed-form",
        "explain",
        "rnea",
        "crba",
        "aba",
    ] {
        assert!(help.contains(cmd), "{cmd}");
    }
}

#[test]
fn export_round_trips_through_urdf() {
    let path = tmp("planar2_export.urdf");
    ok(&[
        "export",
        "builtin:planar2",
        "--to",
        "urdf",
        "--output",
        path.to_str().unwrap(),
    ]);
    let text = ok(&["export", "builtin:planar2", "--to", "urdf"]);
    assert!(text.contains("<robot"));
    // The exported robot has the same dynamics (URDF has no gravity element: give it back).
    let a = json(&[
        "rnea",
        "builtin:planar2",
        "--q",
        "0.2,0.4",
        "--v",
        "1,2",
        "--a",
        "3,4",
    ]);
    let b = json(&[
        "rnea",
        path.to_str().unwrap(),
        "--q",
        "0.2,0.4",
        "--v",
        "1,2",
        "--a",
        "3,4",
        "--gravity",
        "0,-9.81,0",
    ]);
    close(&vec(&a["tau"]), &vec(&b["tau"]), 1e-12);
}

/// A two-joint DH arm with armatures, damping, friction, limits and an effort limit.
const ARMATURE_DH: &str = r#"
format = "dh"
gravity = [0, 0, -9.81]
[[row]]
type = "R"
a = 0.4
alpha = 1.5707963267948966
d = 0.3
limits = { lower = -2.5, upper = 2.5, effort = 40 }
damping = 0.5
friction = 0.2
armature = 0.25
mass = 2.0
com = [-0.2, 0, 0]
inertia = [0.02, 0, 0, 0.03, 0, 0.04]
[[row]]
type = "P"
theta = 0.3
armature = 0.125
limits = { lower = 0, upper = 0.5 }
mass = 1.0
inertia = [0.01, 0, 0, 0.01, 0, 0.01]
"#;

#[test]
fn export_to_mjcf_keeps_armature_limits_and_effort() {
    let model = tmp("armature_dh.toml");
    std::fs::write(&model, ARMATURE_DH).unwrap();
    let m = s_(&model);
    // info shows the armature the TOML gave.
    let v = json(&["info", m]);
    assert_eq!(v["joints"][0]["armature"], 0.25);
    assert_eq!(v["joints"][1]["armature"], 0.125);
    assert!(ok(&["info", m, "--format", "table"]).contains("armature"));
    // --format is the same flag as --to.
    let out = tmp("armature_dh.xml");
    ok(&["export", m, "--format", "mjcf", "--output", s_(&out)]);
    let xml = std::fs::read_to_string(&out).unwrap();
    assert_eq!(xml, ok(&["export", m, "--to", "mjcf"]));
    assert!(xml.contains("<compiler angle=\"radian\" autolimits=\"true\"/>"));
    assert!(xml.contains("<option gravity=\"0 0 -9.81\"/>"));
    for attr in [
        "type=\"hinge\"",
        "type=\"slide\"",
        "range=\"-2.5 2.5\"",
        "range=\"0 0.5\"",
        "damping=\"0.5\"",
        "frictionloss=\"0.2\"",
        "armature=\"0.25\"",
        "armature=\"0.125\"",
        "mass=\"2\"",
        "forcerange=\"-40 40\"",
    ] {
        assert!(xml.contains(attr), "{attr} missing from\n{xml}");
    }
    // One motor (only joint 1 has an effort limit); the second body is nested in the first.
    assert_eq!(xml.matches("<motor ").count(), 1);
    let (first, second) = (
        xml.find("<body name=\"link1\"").unwrap(),
        xml.find("<body name=\"link2\"").unwrap(),
    );
    assert!(first < second && xml[second..].matches("</body>").count() == 2);
    // URDF cannot hold the armature: a warning on stderr names each joint that loses it.
    let o = bin().args(["export", m, "--to", "urdf"]).output().unwrap();
    assert!(o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("warning: joint 'joint1' has an armature of 0.25, which URDF cannot hold")
            && err.contains("joint 'joint2'"),
        "{err}"
    );
    // A helical joint has no MJCF counterpart: exit status 2, one sentence naming it.
    let helical = tmp("helical.toml");
    std::fs::write(
        &helical,
        "format = \"screwdyn\"\n[[body]]\nname = \"nut\"\nparent = \"base\"\njoint = \"screw\"\ntype = \"helical\"\npitch = 0.01\nscrew_in_parent = [0, 0, 1, 0, 0, 0.01]\nmass = 1.0\n",
    )
    .unwrap();
    let e = fails(
        &["export", s_(&helical), "--to", "mjcf"],
        "joint 'screw' is helical",
    );
    assert!(e.contains("MJCF cannot describe"), "{e}");
}

fn s_(p: &std::path::Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn check_and_info() {
    let v = json(&["check", "builtin:ur5"]);
    assert_eq!(v["ok"], true);
    let v = json(&["check", ARM3]);
    assert_eq!(v["ok"], true);
    let v = json(&["info", ARM3]);
    assert_eq!(v["nq"], 3);
    assert_eq!(v["joints"][0]["name"], "joint1");
    assert_eq!(v["joints"][0]["effort"], 100.0);
    close(&[f(&v["total_mass"])], &[4.3], 1e-12);
    let text = ok(&["info", "builtin:branched", "--format", "table"]);
    assert!(text.contains("tree:") && text.contains("└─"));
    // fk on a URDF: every frame.
    let v = json(&["fk", ARM3, "--q", "0.1,0.2,0.3"]);
    assert!(v["poses"].as_object().unwrap().len() >= 4);
}

#[test]
fn limit_stop_flags_reach_the_simulation() {
    // The UR5's last wrist spun into its +2π limit at 5 rad/s, without gravity: an elastic stop
    // (ζ = 0) sends it back at the same speed; a critically damped one (ζ = 1) holds it at the
    // limit with no bounce.
    let run = |zeta: &str| {
        json(&[
            "simulate",
            "builtin:ur5",
            "--gravity",
            "0,0,0",
            "--q0",
            "0,0,0,0,0,6.2",
            "--v0",
            "0,0,0,0,0,5",
            "--duration",
            "0.3",
            "--limit-damping-ratio",
            zeta,
        ])
    };
    let last = |out: &serde_json::Value, key: &str| {
        let column = out[format!("{key}.wrist_3_joint")].as_array().unwrap();
        column.last().unwrap().as_f64().unwrap()
    };
    let elastic = run("0");
    assert!(
        (last(&elastic, "v") + 5.0).abs() < 0.05,
        "{}",
        last(&elastic, "v")
    );
    let held = run("1");
    assert!(last(&held, "v").abs() < 1e-3);
    assert!((last(&held, "q") - 2.0 * std::f64::consts::PI).abs() < 1e-3);
}

#[test]
fn recorded_frame_positions_follow_the_planar_closed_form() {
    // --frame link2 adds pose.link2.x|y|z; on the planar arm with unit links the tip is at
    // (cos q₁ + cos(q₁ + q₂), sin q₁ + sin(q₁ + q₂), 0) at every recorded sample.
    let path = tmp("frame_run.csv");
    let p = path.to_str().unwrap();
    ok(&[
        "simulate",
        "builtin:planar2",
        "--q0",
        "0.3,-0.4",
        "--duration",
        "0.5",
        "--record-every",
        "50",
        "--frame",
        "link2",
        "--output",
        p,
    ]);
    let text = std::fs::read_to_string(&path).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (q1, q2, x, y, z) = (
        col("q.joint1"),
        col("q.joint2"),
        col("pose.link2.x"),
        col("pose.link2.y"),
        col("pose.link2.z"),
    );
    let mut rows = 0;
    for line in lines {
        let r: Vec<f64> = line.split(',').map(|s| s.parse().unwrap()).collect();
        let (a, b) = (r[q1], r[q1] + r[q2]);
        close(
            &[r[x], r[y], r[z]],
            &[a.cos() + b.cos(), a.sin() + b.sin(), 0.0],
            1e-12,
        );
        rows += 1;
    }
    assert_eq!(rows, 11);
    fails(
        &["simulate", "builtin:planar2", "--frame", "nope"],
        "no frame named 'nope'",
    );
}

/// Issue 12.3: a run ends exactly at --duration (a last, shorter step), and run files quote
/// joint names that CSV needs quoted.
#[test]
fn runs_end_at_the_duration_and_csv_headers_quote_joint_names() {
    for (dt, steps) in [("0.3", 4), ("5", 1)] {
        let v = json(&[
            "simulate",
            "builtin:pendulum",
            "--q0",
            "0.2",
            "--dt",
            dt,
            "--duration",
            "1",
        ]);
        // Without --output, JSON is the run itself: one entry per sample.
        let t = v["t"].as_array().unwrap();
        assert_eq!(t.len(), steps + 1, "--dt {dt}");
        assert_eq!(f(&t[steps]), 1.0, "--dt {dt}");
    }
    let urdf = tmp("quoted.urdf");
    std::fs::write(
        &urdf,
        r#"<robot name="q"><link name="base"/>
<link name="a"><inertial><origin xyz="1 0 0"/><mass value="1"/><inertia ixx="0" iyy="0" izz="0" ixy="0" ixz="0" iyz="0"/></inertial></link>
<joint name="j&quot;2,x" type="continuous"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/></joint></robot>"#,
    )
    .unwrap();
    let run = tmp("quoted_run.csv");
    ok(&[
        "simulate",
        urdf.to_str().unwrap(),
        "--duration",
        "0.01",
        "--output",
        run.to_str().unwrap(),
    ]);
    let mut r = csv::Reader::from_path(&run).unwrap();
    let headers: Vec<String> = r.headers().unwrap().iter().map(String::from).collect();
    assert_eq!(headers[1], "q.j\"2,x");
    assert_eq!(headers.len(), 8);
    assert_eq!(r.records().count(), 11);
    // A profile that would need more samples than --max-samples is refused before it starts.
    fails(
        &[
            "torque-profile",
            "builtin:planar2",
            "--trajectory",
            "quintic",
            "--qf",
            "1,1",
            "--duration",
            "1",
            "--dt",
            "1e-3",
            "--max-samples",
            "100",
        ],
        "more than the limit of 100",
    );
    // A raised cap does not end in an allocation abort: what the profile must hold is refused
    // up front, with the memory it would need (10^11 samples of the UR5: tens of TB).
    let e = fails(
        &[
            "torque-profile",
            "builtin:ur5",
            "--qf",
            "1,-1,1,0,0,0",
            "--dt",
            "1e-9",
            "--max-samples",
            "100000000000",
        ],
        "GB of memory",
    );
    assert!(!e.contains("panicked") && !e.contains("backtrace"), "{e}");
}

/// Runs `screwdyn ARGS` under `ulimit -v KB` (virtual memory) in a shell; returns stdout's
/// line count, stderr and the exit status. Stdout is counted as it arrives, never held.
fn under_memory_limit(kb: u64, args: &[&str]) -> (usize, String, Option<i32>) {
    use std::io::BufRead;
    let exe = env!("CARGO_BIN_EXE_screwdyn");
    let mut child = std::process::Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v {kb} && exec \"$0\" \"$@\""))
        .arg(exe)
        .args(args)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let lines = std::io::BufReader::new(child.stdout.take().unwrap())
        .lines()
        .count();
    let out = child.wait_with_output().unwrap();
    (
        lines,
        String::from_utf8_lossy(&out.stderr).into_owned(),
        out.status.code(),
    )
}

#[test]
fn a_profile_without_a_plot_is_streamed_in_constant_memory() {
    // Issue 28 item 5: a million samples of the two-link arm take about 0.3 GB held in memory,
    // and their CSV about as much; under a 100 MB address-space limit they still stream out,
    // row by row, while what must hold them (a plot) is refused up front with the memory it
    // would need.
    let motion = [
        "torque-profile",
        "builtin:planar2",
        "--trajectory",
        "quintic",
        "--qf",
        "1,1",
        "--duration",
        "1",
        "--dt",
        "1e-6",
    ];
    fn with<'a>(motion: &[&'a str], extra: &[&'a str]) -> Vec<&'a str> {
        [motion, extra].concat()
    }
    let (lines, err, status) = under_memory_limit(100_000, &with(&motion, &["--format", "csv"]));
    assert_eq!((status, err.as_str()), (Some(0), ""));
    assert_eq!(lines, 1 + 1_000_001, "header and every sample");
    let plot = tmp("held.png");
    let (_, err, status) = under_memory_limit(
        100_000,
        &with(
            &motion,
            &["--plot", plot.to_str().unwrap(), "--format", "json"],
        ),
    );
    assert_eq!(status, Some(2), "{err}");
    assert!(
        err.contains("holding 1000001 samples needs about 0.3 GB of memory"),
        "{err}"
    );
    // To a file: the same rows, and the report's statistics equal the held profile's.
    let file = tmp("streamed_profile.csv");
    let (_, err, status) = under_memory_limit(
        100_000,
        &with(
            &motion,
            &["--output", file.to_str().unwrap(), "--format", "json"],
        ),
    );
    assert_eq!((status, err.as_str()), (Some(0), ""));
    let rows = std::fs::read_to_string(&file).unwrap().lines().count();
    assert_eq!(rows, 1 + 1_000_001);
}

#[test]
fn a_streamed_profile_reports_what_the_held_one_does() {
    // The statistics of a streamed profile (--output without --plot) equal those of the held
    // profile (with --plot), and its file the held one's, byte for byte.
    let args = |out: &str| {
        vec![
            "torque-profile".to_string(),
            "builtin:ur5".into(),
            "--qf".into(),
            "1,-1,1,0,0,0".into(),
            "--dt".into(),
            "0.01".into(),
            "--output".into(),
            out.into(),
        ]
    };
    let (streamed, held) = (tmp("profile_streamed.csv"), tmp("profile_held.csv"));
    let plot = tmp("profile_held.svg");
    let a: Vec<String> = args(streamed.to_str().unwrap());
    let mut b: Vec<String> = args(held.to_str().unwrap());
    b.extend(["--plot".into(), plot.to_str().unwrap().into()]);
    let a: Vec<&str> = a.iter().map(String::as_str).collect();
    let b: Vec<&str> = b.iter().map(String::as_str).collect();
    assert_eq!(json(&a), json(&b));
    assert_eq!(
        std::fs::read(&streamed).unwrap(),
        std::fs::read(&held).unwrap()
    );
    // And stdout with --format csv is that file.
    let mut c: Vec<&str> = a[..6].to_vec();
    c.extend(["--format", "csv"]);
    assert_eq!(ok(&c).into_bytes(), std::fs::read(&streamed).unwrap());
}

#[test]
fn the_summary_of_a_run_recorded_every_step_is_its_last_sample() {
    // 1000 recorded samples: the summary keeps only the latest (its buffers reused).
    let run = tmp("summary_last.csv");
    let v = json(&[
        "simulate",
        "builtin:pendulum",
        "--q0",
        "0.2",
        "--dt",
        "0.001",
        "--duration",
        "1",
        "--output",
        run.to_str().unwrap(),
    ]);
    assert_eq!(f(&v["samples"]), 1001.0);
    assert_eq!(f(&v["t"]), 1.0);
    // The small-angle pendulum (l = 1 m): q(t) ≈ q0 cos(√(g/l) t), half a period ≈ 1.003 s.
    let q = vec(&v["q"])[0];
    assert!((q - 0.2 * 9.81_f64.sqrt().cos()).abs() < 2e-3, "q(1) = {q}");
    // Energy is conserved by the passive swing (RK4, 1 ms).
    let (e0, e1) = (f(&v["total_energy_start"]), f(&v["total_energy_end"]));
    assert!((e1 - e0).abs() < 1e-9 * e0.abs(), "{e0} → {e1}");
    // The same numbers as the file's last row.
    let mut r = csv::Reader::from_path(&run).unwrap();
    let last = r.records().last().unwrap().unwrap();
    let cell = |k: usize| last[k].parse::<f64>().unwrap();
    assert_eq!((cell(0), cell(1), cell(2)), (1.0, q, vec(&v["v"])[0]));
}

#[test]
fn info_shows_joint_springs_and_urdf_export_warns_about_them() {
    // An MJCF spring in degrees: info gives springref in radians; MJCF export keeps it.
    let model = tmp("spring.xml");
    std::fs::write(
        &model,
        r#"<mujoco><worldbody><body name="b"><geom size="0.1"/>
  <joint name="j" stiffness="3" springref="90"/></body></worldbody></mujoco>"#,
    )
    .unwrap();
    let m = s_(&model);
    let v = json(&["info", m]);
    assert_eq!(v["joints"][0]["stiffness"], 3.0);
    let springref = v["joints"][0]["springref"].as_f64().unwrap();
    assert!((springref - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
    let table = ok(&["info", m, "--format", "table"]);
    assert!(
        table.contains("stiffness") && table.contains("springref"),
        "{table}"
    );
    assert!(ok(&["export", m, "--to", "mjcf"]).contains("stiffness=\"3\""));
    let o = bin().args(["export", m, "--to", "urdf"]).output().unwrap();
    assert!(o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("warning: joint 'j' has a spring (stiffness 3"),
        "{err}"
    );
}
