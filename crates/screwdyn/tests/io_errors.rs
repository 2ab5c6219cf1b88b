//! Every broken description is explained, never a panic: each message names the problem and
//! its place (file and line, or the element's name).

use screwdyn::io::{load_model, load_str, LoadOptions};

fn err(text: &str, file: &str) -> String {
    match load_str(text, file, &LoadOptions::default()) {
        Ok(_) => panic!("{file} loaded but should not"),
        Err(e) => e.to_string(),
    }
}

/// The one physical-consistency finding of a file that loads, as text; the same file loaded
/// strictly fails with it.
fn finding(text: &str, file: &str) -> String {
    let m = load_str(text, file, &LoadOptions::default())
        .unwrap_or_else(|e| panic!("{file} should load with a finding: {e}"));
    let f = m.physical_problems();
    assert_eq!(f.len(), 1, "{file}: {f:?}");
    let strict = load_str(text, file, &LoadOptions { strict: true }).unwrap_err();
    assert!(strict.to_string().contains(&f[0].to_string()));
    f[0].to_string()
}

fn check(msg: &str, place: &str, words: &[&str]) {
    assert!(
        msg.starts_with(place),
        "expected '{place}' at the start of: {msg}"
    );
    for w in words {
        assert!(msg.contains(w), "expected '{w}' in: {msg}");
    }
    assert!(!msg.contains('\n'), "one line, one sentence: {msg}");
}

/// A URDF with `body` on lines 2.. after `<robot>` on line 1.
fn urdf(body: &str) -> String {
    format!("<robot name=\"r\">\n{body}\n</robot>\n")
}

const MASS: &str = "<inertial><mass value=\"1\"/><inertia ixx=\"0.1\" iyy=\"0.1\" izz=\"0.1\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial>";

fn link(name: &str) -> String {
    format!("<link name=\"{name}\">{MASS}</link>")
}

fn joint(name: &str, kind: &str, parent: &str, child: &str) -> String {
    format!("<joint name=\"{name}\" type=\"{kind}\"><parent link=\"{parent}\"/><child link=\"{child}\"/></joint>")
}

#[test]
fn xml_syntax_error_names_file_and_line() {
    let e = err(
        "<robot name=\"r\">\n<link name=\"a\">\n<link name=\"b\"/>\n</robot>",
        "bad.urdf",
    );
    check(&e, "bad.urdf:", &["XML syntax error"]);
    let line: usize = e.split(':').nth(1).unwrap().parse().unwrap();
    assert!((2..=4).contains(&line), "{e}");
}

#[test]
fn a_joint_naming_a_missing_link() {
    let t = urdf(
        &[
            link("base"),
            link("a"),
            joint("j1", "revolute", "base", "a"),
            joint("j2", "revolute", "a", "ghost"),
        ]
        .join("\n"),
    );
    check(
        &err(&t, "m.urdf"),
        "m.urdf:5:",
        &["joint 'j2'", "'ghost'", "does not exist"],
    );
}

#[test]
fn two_parents_for_one_link() {
    let t = urdf(
        &[
            link("base"),
            link("a"),
            link("b"),
            joint("j1", "revolute", "base", "a"),
            joint("j2", "revolute", "base", "b"),
            joint("j3", "revolute", "b", "a"),
        ]
        .join("\n"),
    );
    check(
        &err(&t, "m.urdf"),
        "m.urdf:7:",
        &["link 'a' has two parents", "j1", "j3"],
    );
}

#[test]
fn a_cycle() {
    let t = urdf(
        &[
            link("base"),
            link("b"),
            link("c"),
            joint("j1", "revolute", "b", "c"),
            joint("j2", "revolute", "c", "b"),
        ]
        .join("\n"),
    );
    let e = err(&t, "m.urdf");
    check(&e, "m.urdf:", &["cycle", "j1", "j2"]);
}

#[test]
fn several_roots_and_no_root() {
    let t = urdf(
        &[
            link("base"),
            link("a"),
            link("island"),
            joint("j1", "revolute", "base", "a"),
        ]
        .join("\n"),
    );
    check(
        &err(&t, "m.urdf"),
        "m.urdf:4:",
        &["several root links", "base", "island"],
    );
    let t = urdf(
        &[
            link("a"),
            link("b"),
            joint("j1", "revolute", "a", "b"),
            joint("j2", "revolute", "b", "a"),
        ]
        .join("\n"),
    );
    check(&err(&t, "m.urdf"), "m.urdf:", &["cycle"]);
}

#[test]
fn duplicate_link_and_joint_names() {
    let t = urdf(&[link("base"), link("a"), link("a")].join("\n"));
    check(
        &err(&t, "m.urdf"),
        "m.urdf:4:",
        &["link 'a' is declared twice", "line 3"],
    );
    let t = urdf(
        &[
            link("base"),
            link("a"),
            link("b"),
            joint("j", "revolute", "base", "a"),
            joint("j", "revolute", "a", "b"),
        ]
        .join("\n"),
    );
    check(
        &err(&t, "m.urdf"),
        "m.urdf:6:",
        &["joint 'j' is declared twice", "line 5"],
    );
}

#[test]
fn a_non_number() {
    let t = urdf(
        &[
            link("base"),
            link("a"),
            "<joint name=\"j\" type=\"revolute\"><parent link=\"base\"/><child link=\"a\"/>".into(),
            "<origin xyz=\"0 zero 0\"/></joint>".to_string(),
        ]
        .join("\n"),
    );
    check(
        &err(&t, "m.urdf"),
        "m.urdf:5:",
        &["joint 'j'", "'zero' is not a finite number"],
    );
    let t = urdf(
        &[
            "<link name=\"base\"/>".to_string(),
            "<link name=\"a\"><inertial><mass value=\"heavy\"/></inertial></link>".into(),
            joint("j", "revolute", "base", "a"),
        ]
        .join("\n"),
    );
    check(&err(&t, "m.urdf"), "m.urdf:3:", &["link 'a'", "'heavy'"]);
    let t = urdf(&[link("base"), link("a"), "<joint name=\"j\" type=\"revolute\"><parent link=\"base\"/><child link=\"a\"/><axis xyz=\"0 1\"/></joint>".into()].join("\n"));
    check(
        &err(&t, "m.urdf"),
        "m.urdf:4:",
        &["has 2 numbers, expected 3"],
    );
}

#[test]
fn negative_or_zero_mass_on_a_moving_leaf() {
    let neg = "<link name=\"a\">\n<inertial><mass value=\"-1\"/></inertial></link>";
    let t = urdf(
        &[
            "<link name=\"base\"/>",
            neg,
            &joint("j", "revolute", "base", "a"),
        ]
        .join("\n"),
    );
    check(
        &finding(&t, "m.urdf"),
        "m.urdf:4:",
        &["link 'a'", "negative mass"],
    );
    let t = urdf(
        &[
            "<link name=\"base\"/>",
            "<link name=\"a\"/>",
            &joint("j", "revolute", "base", "a"),
        ]
        .join("\n"),
    );
    check(
        &finding(&t, "m.urdf"),
        "m.urdf:3:",
        &["link 'a'", "joint 'j'", "no mass"],
    );
    // A massless moving link is fine when a fixed child carries mass.
    let t = urdf(
        &[
            "<link name=\"base\"/>",
            "<link name=\"a\"/>",
            &link("tip"),
            &joint("j", "revolute", "base", "a"),
            &joint("f", "fixed", "a", "tip"),
        ]
        .join("\n"),
    );
    assert!(load_str(&t, "m.urdf", &LoadOptions::default()).is_ok());
}

#[test]
fn non_physical_inertias_are_findings_and_errors_when_strict() {
    let bad = |ixx: f64, iyy: f64, izz: f64, ixy: f64| {
        urdf(&[
            "<link name=\"base\"/>".to_string(),
            format!("<link name=\"a\">\n<inertial><mass value=\"1\"/><inertia ixx=\"{ixx}\" iyy=\"{iyy}\" izz=\"{izz}\" ixy=\"{ixy}\" ixz=\"0\" iyz=\"0\"/></inertial></link>"),
            joint("j", "revolute", "base", "a"),
        ].join("\n"))
    };
    // Not positive definite (a negative moment), breaking the triangle inequality (1 + 1 < 3).
    let t = bad(-0.1, 0.1, 0.1, 0.0);
    check(
        &finding(&t, "m.urdf"),
        "m.urdf:4:",
        &["link 'a': its inertia", "positive"],
    );
    let t2 = bad(1.0, 1.0, 3.0, 0.0);
    check(
        &finding(&t2, "m.urdf"),
        "m.urdf:4:",
        &["link 'a': its inertia", "triangle inequality"],
    );
    let t3 = bad(1.0, 1.0, 1.0, 2.0);
    check(
        &finding(&t3, "m.urdf"),
        "m.urdf:4:",
        &["link 'a': its inertia"],
    );
}

#[test]
fn a_zero_axis_and_unsupported_joint_types() {
    let t = urdf(
        &[
            link("base"),
            link("a"),
            "<joint name=\"j\" type=\"prismatic\"><parent link=\"base\"/><child link=\"a\"/>"
                .into(),
            "<axis xyz=\"0 0 0\"/></joint>".to_string(),
        ]
        .join("\n"),
    );
    check(&err(&t, "m.urdf"), "m.urdf:5:", &["joint 'j'", "zero axis"]);
    for kind in ["floating", "planar"] {
        let t = urdf(&[link("base"), link("a"), joint("j", kind, "base", "a")].join("\n"));
        check(
            &err(&t, "m.urdf"),
            "m.urdf:4:",
            &["joint 'j'", kind, "not support"],
        );
    }
    let t = urdf(&[link("base"), link("a"), joint("j", "hinge", "base", "a")].join("\n"));
    check(&err(&t, "m.urdf"), "m.urdf:4:", &["unknown type 'hinge'"]);
}

#[test]
fn toml_syntax_errors_and_unknown_keys_name_file_and_line() {
    check(
        &err("format = \"dh\"\n[[row]\n", "t.toml"),
        "t.toml:2:",
        &[],
    );
    let e = err(
        "format = \"dh\"\n[[row]]\ntype = \"R\"\nalfa = 0.5\nmass = 1\n",
        "t.toml",
    );
    check(&e, "t.toml:4:", &["alfa"]);
    let e = err("format = \"screwdyn\"\n[[body]]\nname = \"a\"\nparent = \"base\"\ntype = \"revolute\"\nscrew_in_child = [0, 0, 1, 0, 0, 0]\nmas = 1\n", "t.toml");
    check(&e, "t.toml:7:", &["mas"]);
    let e = err(
        "format = \"dh\"\n[[row]]\ntype = \"R\"\na = \"long\"\n",
        "t.toml",
    );
    check(&e, "t.toml:4:", &[]);
    check(
        &err("name = \"x\"\n", "t.toml"),
        "t.toml:",
        &["'format' is missing"],
    );
    check(
        &err("format = \"sdf\"\n", "t.toml"),
        "t.toml:",
        &["unknown format 'sdf'"],
    );
}

#[test]
fn toml_model_errors_name_the_element() {
    let e = err("format = \"dh\"\n[[row]]\ntype = \"X\"\n", "t.toml");
    check(&e, "t.toml:2:", &["DH row 1", "'X'"]);
    let e = finding(
        "format = \"dh\"\n[[row]]\ntype = \"R\"\nmass = 1\ninertia = [1, 0, 0, 1, 0, 3]\n",
        "t.toml",
    );
    check(&e, "t.toml:2:", &["link 'link1'", "triangle inequality"]);
    let e = finding("format = \"dh\"\n[[row]]\ntype = \"R\"\n", "t.toml");
    check(&e, "t.toml:", &["link1", "no mass"]);
    let e = err("format = \"screwdyn\"\n[[body]]\nname = \"a\"\nparent = \"base\"\ntype = \"revolute\"\nmass = 1\n", "t.toml");
    check(&e, "t.toml:2:", &["body 'a'", "no screw axis"]);
    let e = err("format = \"screwdyn\"\n[[body]]\nname = \"a\"\nparent = \"base\"\ntype = \"revolute\"\nscrew_in_child = [0, 0, 0, 0, 0, 0]\nmass = 1\n", "t.toml");
    check(&e, "t.toml:", &["joint 'a_joint'", "unit vector"]);
    let e = err("format = \"screwdyn\"\n[[body]]\nname = \"a\"\nparent = \"nowhere\"\ntype = \"revolute\"\nscrew_in_child = [0, 0, 1, 0, 0, 0]\nmass = 1\n", "t.toml");
    check(&e, "t.toml:", &["'nowhere'", "does not exist"]);
    let e = err(
        "format = \"screwdyn\"\n[[body]]\nname = \"a\"\nparent = \"base\"\ntype = \"floating\"\n",
        "t.toml",
    );
    check(&e, "t.toml:2:", &["body 'a'", "floating", "not support"]);
    let e = err("format = \"screwdyn\"\n[[body]]\nname = \"a\"\nparent = \"base\"\ntype = \"fixed\"\nhome = { quaternion = [0, 0, 0, 0] }\n", "t.toml");
    check(&e, "t.toml:2:", &["body 'a'", "zero quaternion"]);
    // The second row, and an extra frame, are placed by their own table headers.
    let e = err(
        "format = \"dh\"\n\n[[row]]\na = 1\ntype = \"R\"\nmass = 1\n\n[[row]]\ntype = \"X\"\n",
        "t.toml",
    );
    check(&e, "t.toml:8:", &["DH row 2", "'X'"]);
    let e = err(
        "format = \"dh\"\n[[row]]\ntype = \"R\"\nmass = 1\n[[frame]]\nname = \"tool\"\nlink = \"link1\"\npose = { quaternion = [0, 0, 0, 0] }\n",
        "t.toml",
    );
    check(&e, "t.toml:5:", &["frame 'tool'", "zero quaternion"]);
    let poe = "format = \"poe\"\nSlist = [[0, 0, 1, 0, 0, 0]]\nMlist = [[[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]]\nGlist = []\n";
    check(
        &err(poe, "p.toml"),
        "p.toml:",
        &["Glist has 0 entries", "Slist has 1"],
    );
    let poe = "format = \"poe\"\nSlist = [[0, 0, 1, 0, 0, 0]]\nMlist = [[[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]]\nGlist = [[[1, 0, 0, 0, 0, 0], [0, 1, 0, 0, 0, 0], [0, 0, 1, 0, 0, 0], [0, 0, 0, 1, 0, 0], [0, 0, 0, 0, 2, 0], [0, 0, 0, 0, 0, 1]]]\n";
    check(
        &err(poe, "p.toml"),
        "p.toml:",
        &["Glist entry 1", "not a spatial inertia"],
    );
}

#[test]
fn files_that_cannot_be_read_or_have_no_known_format() {
    let e = load_model("/nonexistent/robot.urdf")
        .unwrap_err()
        .to_string();
    check(&e, "/nonexistent/robot.urdf:", &["cannot be read"]);
    let e = load_model("robot.sdf").unwrap_err().to_string();
    check(&e, "robot.sdf:", &["unknown model format"]);
    let e = load_model("builtin:nope").unwrap_err().to_string();
    assert!(e.contains("nope") && e.contains("planar2"), "{e}");
}

/// Issue 12.2: every bad value is refused where it is read, with file:line.
#[test]
fn bad_joint_values_are_refused_at_their_line() {
    let with = |inner: &str| {
        urdf(&[
            "<link name=\"base\"/>".to_string(),
            link("a"),
            format!(
                "<joint name=\"j\" type=\"revolute\"><parent link=\"base\"/><child link=\"a\"/>\n{inner}\n</joint>"
            ),
        ]
        .join("\n"))
    };
    let cases: [(&str, &[&str]); 7] = [
        (
            "<limit lower=\"1\" upper=\"-1\" effort=\"1\" velocity=\"1\"/>",
            &["lower = 1 above upper = -1"],
        ),
        (
            "<limit lower=\"-1\" upper=\"1\" effort=\"-5\" velocity=\"1\"/>",
            &["effort", "negative"],
        ),
        (
            "<limit lower=\"-1\" upper=\"1\" effort=\"5\" velocity=\"-1\"/>",
            &["velocity", "negative"],
        ),
        (
            "<limit lower=\"-1\" upper=\"1\" effort=\"nan\" velocity=\"1\"/>",
            &["'nan' is not a finite number"],
        ),
        ("<dynamics damping=\"-0.1\"/>", &["damping", "negative"]),
        (
            "<dynamics friction=\"NaN\"/>",
            &["friction", "not a finite number"],
        ),
        ("<axis xyz=\"0 0 0\"/>", &["zero axis"]),
    ];
    for (inner, words) in cases {
        let e = err(&with(inner), "m.urdf");
        let line = if inner.starts_with("<mimic") {
            "m.urdf:4:"
        } else {
            "m.urdf:5:"
        };
        check(&e, line, words);
    }
    // A mimic of a missing joint: a finding at the joint's line (such published files load, as
    // in Pinocchio; mimics are information only), an error when strict.
    check(
        &finding(&with("<mimic joint=\"ghost\"/>"), "m.urdf"),
        "m.urdf:4:",
        &["joint 'j' mimics joint 'ghost'"],
    );
    // A huge axis normalises instead of overflowing to "[0,0,0]".
    let m = load_str(
        &with("<axis xyz=\"1e308 1e308 0\"/>"),
        "m.urdf",
        &LoadOptions::default(),
    )
    .unwrap();
    let s = m.joints()[0].screw;
    let h = std::f64::consts::FRAC_1_SQRT_2;
    assert!((s[0] - h).abs() < 1e-15 && (s[1] - h).abs() < 1e-15 && s[2] == 0.0);
    // Names: empty, or with a line break.
    let e = err(&urdf("<link name=\"\"/>\n<link name=\"b\"/>"), "m.urdf");
    check(&e, "m.urdf:2:", &["non-empty"]);
    let e = err(
        &urdf("<link name=\"base\"/>\n<link name=\"a&#10;b\"/>"),
        "m.urdf",
    );
    check(&e, "m.urdf:3:", &["control characters"]);
}

#[test]
fn a_huge_quaternion_is_normalised_and_a_zero_one_refused() {
    let text = |q: &str| {
        format!(
            "format = \"screwdyn\"\n[[body]]\nname = \"a\"\nparent = \"base\"\ntype = \"revolute\"\nscrew_in_child = [0, 0, 1, 0, 0, 0]\nmass = 1\nhome = {{ quaternion = {q} }}\n"
        )
    };
    // [w, x, y, z] = [1e308, 1e308, 0, 0] is (1, 1, 0, 0)/√2 once normalised: a quarter turn
    // about x (w = cos 45°, x = sin 45°).
    let m = load_str(
        &text("[1e308, 1e308, 0, 0]"),
        "q.toml",
        &LoadOptions::default(),
    )
    .unwrap();
    let r = m.joints()[0].home.rotation;
    let rx = screwdyn::spatial::Se3::from_rpy(std::f64::consts::FRAC_PI_2, 0.0, 0.0).rotation;
    assert!((r - rx).amax() < 1e-12, "{r}");
    let e = err(&text("[0, 0, 0, 0]"), "q.toml");
    check(&e, "q.toml:2:", &["quaternion"]);
}

#[cfg(unix)]
#[test]
fn a_fifo_given_as_a_model_is_refused_without_blocking() {
    let dir = std::env::temp_dir().join(format!("screwdyn-fifo-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("robot.urdf");
    let _ = std::fs::remove_file(&path);
    let status = std::process::Command::new("mkfifo").arg(&path).status();
    if !matches!(status, Ok(s) if s.success()) {
        eprintln!("mkfifo is not available here; skipped");
        return;
    }
    let e = screwdyn::io::load_model(path.to_str().unwrap()).unwrap_err();
    assert!(e.to_string().contains("not a regular file"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}
