//! Built-in robots, available as `builtin:<name>` wherever a model path is accepted.
//!
//! - `planar2`: the classic two-link planar arm — point masses `m1 = m2 = 1` kg at
//!   the link ends, `L1 = L2 = 1` m, both joints about `z`, gravity `(0, −9.81, 0)` (along −y of
//!   the base, as in the example). Link frames sit at the link ends (the CoMs).
//! - `pendulum`: a simple pendulum, point mass 1 kg on a 1 m massless rod, joint about `z`,
//!   gravity `(0, −9.81, 0)`; at `q = 0` the mass hangs straight down.
//! - `ur5`: Universal Robots UR5 from its published standard-DH table, masses and CoMs
//!   (rotational inertias approximated as cylinders), `models/ur5.toml`.
//! - `panda`: Franka Emika Panda from its published modified-DH table and Gaz et al. (2019)'s
//!   inertial parameters, `models/panda.toml`.
//! - `branched`: a torso turning about `z` with a fixed head and two 3-DoF arms,
//!   `models/branched.toml`.
//!
//! The last three are the files in `models/`, compiled in with `include_str!`, so a built-in
//! and its file are the same robot. The DH tables of `ur5` and `panda` are also compiled in as
//! values (`builtin_tables.rs`, written out from the files and checked against them by a test),
//! so that loading them reads no TOML at run time.

use super::builtin_tables;
use super::dh::dh_model;
use super::options::LoadOptions;
use super::toml_format::load_toml_str;
use crate::error::{Error, Result};
use crate::model::{JointSpec, Model, ModelBuilder};
use crate::spatial::{Se3, SpatialInertia};
use nalgebra::{Vector3, Vector6};

/// The names accepted by [`load`].
pub const NAMES: &[&str] = &["planar2", "pendulum", "ur5", "panda", "branched"];

/// The shipped description files: (built-in name, file name in `models/`, text).
pub const FILES: &[(&str, &str, &str)] = &[
    (
        "planar2",
        "planar2.toml",
        include_str!("../../../../models/planar2.toml"),
    ),
    (
        "ur5",
        "ur5.toml",
        include_str!("../../../../models/ur5.toml"),
    ),
    (
        "panda",
        "panda.toml",
        include_str!("../../../../models/panda.toml"),
    ),
    (
        "branched",
        "branched.toml",
        include_str!("../../../../models/branched.toml"),
    ),
];

/// The shipped description a built-in robot is parsed from: `(file name in models/, text)`;
/// `None` for the robots built in code (`planar2`, `pendulum`) and unknown names.
fn shipped(name: &str) -> Option<(&'static str, &'static str)> {
    if matches!(name, "planar2" | "pendulum") {
        return None;
    }
    FILES
        .iter()
        .find(|(n, _, _)| *n == name)
        .map(|(_, file, text)| (*file, *text))
}

/// The text of the description the built-in robot `name` is parsed from (its file in
/// `models/`); `None` for the robots built in code (`planar2`, `pendulum`) and unknown names.
///
/// ```
/// assert!(screwdyn::builtin::description("ur5").unwrap().contains("format"));
/// assert_eq!(screwdyn::builtin::description("pendulum"), None);
/// ```
pub fn description(name: &str) -> Option<&'static str> {
    shipped(name).map(|(_, text)| text)
}

/// The built-in robot called `name` (without the `builtin:` prefix).
///
/// # Errors
/// [`Error::UnknownName`] for a name that is not a built-in robot.
///
/// ```
/// assert_eq!(screwdyn::builtin::load("pendulum").unwrap().nq(), 1);
/// assert_eq!(screwdyn::builtin::load("ur5").unwrap().nq(), 6);
/// assert_eq!(screwdyn::builtin::load("panda").unwrap().nq(), 7);
/// assert!(screwdyn::builtin::load("r2d2").unwrap_err().to_string().contains("planar2"));
/// ```
pub fn load(name: &str) -> Result<Model> {
    match name {
        "planar2" => Ok(planar2()),
        "pendulum" => Ok(pendulum()),
        _ => match shipped(name) {
            Some((file, text)) => {
                let label = format!("builtin:{name} (models/{file})");
                // A DH table compiled in as a value is built as its file would be, without
                // parsing the text (kept for the lines an error names).
                match builtin_tables::table(name) {
                    Some(table) => dh_model(&table, text, &label, &LoadOptions::default()),
                    None => load_toml_str(text, &label, &LoadOptions::default()),
                }
            }
            None => Err(Error::UnknownName {
                kind: "built-in robot",
                name: name.into(),
                known: NAMES.join(", "),
            }),
        },
    }
}

/// The two-link planar arm with given lengths and point masses.
///
/// ```
/// let m = screwdyn::builtin::planar2_with(0.5, 0.3, 2.0, 1.0);
/// assert!((m.total_mass() - 3.0).abs() < 1e-15);
/// ```
pub fn planar2_with(l1: f64, l2: f64, m1: f64, m2: f64) -> Model {
    let h_0_1_home = Se3::from_translation(Vector3::new(l1, 0.0, 0.0));
    let h_1_2_home = Se3::from_translation(Vector3::new(l2, 0.0, 0.0));
    let s_0_0_1 = Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0);
    let s_1_1_2 = Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0);
    let i_1 = SpatialInertia::point_mass(m1, Vector3::zeros());
    let i_2 = SpatialInertia::point_mass(m2, Vector3::zeros());
    let mut b = ModelBuilder::new("planar2");
    b.gravity(Vector3::new(0.0, -9.81, 0.0))
        .link(
            "link1",
            "base",
            JointSpec::revolute("joint1").screw_in_parent(s_0_0_1),
            h_0_1_home,
            i_1,
        )
        .link(
            "link2",
            "link1",
            JointSpec::revolute("joint2").screw_in_parent(s_1_1_2),
            h_1_2_home,
            i_2,
        );
    b.build().expect("planar2 is a valid model")
}

/// `planar2` with `L1 = L2 = 1` m and `m1 = m2 = 1` kg.
pub fn planar2() -> Model {
    planar2_with(1.0, 1.0, 1.0, 1.0)
}

/// A simple pendulum of length `l` and point mass `m`, hanging along −y at `q = 0`.
pub fn pendulum_with(l: f64, m: f64) -> Model {
    let mut b = ModelBuilder::new("pendulum");
    b.gravity(Vector3::new(0.0, -9.81, 0.0)).link(
        "bob",
        "base",
        JointSpec::continuous("pivot").screw_in_parent(Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0)),
        Se3::from_translation(Vector3::new(0.0, -l, 0.0)),
        SpatialInertia::point_mass(m, Vector3::zeros()),
    );
    b.build().expect("pendulum is a valid model")
}

/// The 1 m, 1 kg pendulum.
pub fn pendulum() -> Model {
    pendulum_with(1.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::super::common::{from_toml, FrameSpec, LimitSpec, PoseSpec};
    use super::super::dh::{DhFile, Row};
    use super::*;
    use std::fmt::Write;

    /// The built-ins compiled in as values are the models of their files, parsed: the same
    /// `Model`, every field (the tables' numbers are the files' to the bit: the test below
    /// compares their shortest round-trip digits, which tell −0.0 from 0.0).
    #[test]
    fn builtin_tables_give_the_models_of_their_files() {
        for name in GIVEN {
            let (file, text) = shipped(name).unwrap();
            let label = format!("builtin:{name} (models/{file})");
            let parsed = load_toml_str(text, &label, &LoadOptions::default()).unwrap();
            let direct = load(name).unwrap();
            assert_eq!(direct, parsed, "{name}");
        }
    }

    /// `builtin_tables.rs` is what the files in `models/` say, spans included (the lines of
    /// errors): it is written out from them here. `SCREWDYN_WRITE_TABLES=1 cargo test -p
    /// screwdyn --lib builtin_tables_are_the_model_files` rewrites it after a file changed.
    #[test]
    fn builtin_tables_are_the_model_files() {
        let rewrite = std::env::var_os("SCREWDYN_WRITE_TABLES").is_some();
        let mut out = String::from(HEADER);
        for name in GIVEN {
            let (file, text) = shipped(name).unwrap();
            let parsed: DhFile = from_toml(text, file).unwrap();
            render(&mut out, name, file, &parsed);
            // Rewriting: the compiled-in tables are the old ones, compared on the next run.
            if rewrite {
                continue;
            }
            let Some(direct) = builtin_tables::table(name) else {
                continue; // not written out yet: the comparison of the texts below fails
            };
            assert_eq!(direct, parsed, "{name}");
            let spans = |f: &DhFile| {
                let rows = f.row.iter().map(|r| r.span());
                rows.chain(f.frame.iter().map(|r| r.span()))
                    .collect::<Vec<_>>()
            };
            assert_eq!(spans(&direct), spans(&parsed), "{name}");
        }
        render_index(&mut out);
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/src/io/builtin_tables.rs");
        if rewrite {
            std::fs::write(path, &out).unwrap();
        }
        assert!(
            out == include_str!("builtin_tables.rs"),
            "src/io/builtin_tables.rs differs from models/: rewrite it with \
             SCREWDYN_WRITE_TABLES=1 cargo test -p screwdyn --lib builtin_tables_are_the_model_files"
        );
    }

    /// The built-in robots whose DH tables are compiled in as values.
    const GIVEN: [&str; 2] = ["ur5", "panda"];

    const HEADER: &str = "\
//! The DH tables of `models/ur5.toml` and `models/panda.toml` as values, so that `builtin:ur5`
//! and `builtin:panda` are built without parsing TOML at run time (BENCHMARKS.md, \"The CLI's
//! fixed costs\"). Written out from the files by the test
//! `io::builtin::tests::builtin_tables_are_the_model_files`, which fails when a file and this
//! one differ; `SCREWDYN_WRITE_TABLES=1 cargo test -p screwdyn --lib
//! builtin_tables_are_the_model_files` rewrites it. Edit the files in `models/`, not this one.

// The files' digits as written (π/2 and 2π among them), not the named constants.
#![allow(clippy::approx_constant)]

use super::common::{FrameSpec, LimitSpec, PoseSpec};
use super::dh::{DhFile, Row};
use toml::Spanned;
";

    fn string(s: &str) -> String {
        format!("{s:?}.into()")
    }
    fn option<T>(x: &Option<T>, f: impl Fn(&T) -> String) -> String {
        x.as_ref()
            .map_or("None".into(), |v| format!("Some({})", f(v)))
    }
    fn number(x: &f64) -> String {
        format!("{x:?}")
    }
    fn numbers(xs: &[f64]) -> String {
        let items: Vec<String> = xs.iter().map(number).collect();
        format!("[{}]", items.join(", "))
    }

    fn render_row(out: &mut String, r: &Row) {
        let LimitSpec {
            lower,
            upper,
            velocity,
            effort,
        } = &r.limits;
        let o = |x: &Option<f64>| option(x, number);
        let s = |x: &Option<String>| option(x, |v| string(v));
        writeln!(out, "                kind: {},", string(&r.kind)).unwrap();
        writeln!(out, "                a: {},", number(&r.a)).unwrap();
        writeln!(out, "                alpha: {},", number(&r.alpha)).unwrap();
        writeln!(out, "                d: {},", number(&r.d)).unwrap();
        writeln!(out, "                theta: {},", number(&r.theta)).unwrap();
        writeln!(out, "                name: {},", s(&r.name)).unwrap();
        writeln!(out, "                link: {},", s(&r.link)).unwrap();
        writeln!(out, "                parent: {},", s(&r.parent)).unwrap();
        writeln!(
            out,
            "                limits: LimitSpec {{ lower: {}, upper: {}, velocity: {}, effort: {} }},",
            o(lower),
            o(upper),
            o(velocity),
            o(effort)
        )
        .unwrap();
        for (key, x) in [
            ("damping", &r.damping),
            ("friction", &r.friction),
            ("armature", &r.armature),
            ("stiffness", &r.stiffness),
            ("springref", &r.springref),
            ("mass", &r.mass),
        ] {
            writeln!(out, "                {key}: {},", o(x)).unwrap();
        }
        writeln!(
            out,
            "                com: {},",
            option(&r.com, |v| numbers(v))
        )
        .unwrap();
        writeln!(
            out,
            "                inertia: {},",
            option(&r.inertia, |v| numbers(v))
        )
        .unwrap();
    }

    fn render_frame(out: &mut String, f: &FrameSpec) {
        let PoseSpec {
            xyz,
            rpy,
            quaternion,
            rotation,
        } = &f.pose;
        let rows = |m: &[[f64; 3]; 3]| {
            let r: Vec<String> = m.iter().map(|r| numbers(r)).collect();
            format!("[{}]", r.join(", "))
        };
        writeln!(out, "                name: {},", string(&f.name)).unwrap();
        writeln!(out, "                link: {},", string(&f.link)).unwrap();
        writeln!(out, "                pose: PoseSpec {{").unwrap();
        writeln!(
            out,
            "                    xyz: {},",
            option(xyz, |v| numbers(v))
        )
        .unwrap();
        writeln!(
            out,
            "                    rpy: {},",
            option(rpy, |v| numbers(v))
        )
        .unwrap();
        writeln!(
            out,
            "                    quaternion: {},",
            option(quaternion, |v| numbers(v))
        )
        .unwrap();
        writeln!(
            out,
            "                    rotation: {},",
            option(rotation, rows)
        )
        .unwrap();
        writeln!(out, "                }},").unwrap();
    }

    fn render(out: &mut String, name: &str, file: &str, f: &DhFile) {
        let g = option(&f.gravity, |v| numbers(v));
        let s = |x: &Option<String>| option(x, |v| string(v));
        writeln!(out, "\n/// `models/{file}`.").unwrap();
        writeln!(out, "fn {name}() -> DhFile {{").unwrap();
        writeln!(out, "    DhFile {{").unwrap();
        writeln!(out, "        format: {},", string(&f.format)).unwrap();
        writeln!(out, "        name: {},", s(&f.name)).unwrap();
        writeln!(out, "        base: {},", s(&f.base)).unwrap();
        writeln!(out, "        gravity: {g},").unwrap();
        writeln!(out, "        row: vec![").unwrap();
        for r in &f.row {
            let span = r.span();
            writeln!(
                out,
                "            Spanned::new({}..{}, Row {{",
                span.start, span.end
            )
            .unwrap();
            render_row(out, r.get_ref());
            writeln!(out, "            }}),").unwrap();
        }
        writeln!(out, "        ],").unwrap();
        writeln!(out, "        frame: vec![").unwrap();
        for fr in &f.frame {
            let span = fr.span();
            let start = format!(
                "            Spanned::new({}..{}, FrameSpec {{",
                span.start, span.end
            );
            writeln!(out, "{start}").unwrap();
            render_frame(out, fr.get_ref());
            writeln!(out, "            }}),").unwrap();
        }
        writeln!(out, "        ],").unwrap();
        writeln!(out, "    }}").unwrap();
        writeln!(out, "}}").unwrap();
    }

    fn render_index(out: &mut String) {
        writeln!(
            out,
            "\n/// The DH table of the built-in robot `name`, if it is given here."
        )
        .unwrap();
        writeln!(out, "pub(super) fn table(name: &str) -> Option<DhFile> {{").unwrap();
        writeln!(out, "    match name {{").unwrap();
        for n in GIVEN {
            writeln!(out, "        {n:?} => Some({n}()),").unwrap();
        }
        writeln!(out, "        _ => None,").unwrap();
        writeln!(out, "    }}").unwrap();
        writeln!(out, "}}").unwrap();
    }
}
