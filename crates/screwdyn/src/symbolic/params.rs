//! The robot's parameters by name — masses, centres of mass, inertia entries, lengths and
//! gravity — and which of them are symbols.

use crate::error::{Error, Result};
use crate::model::{JointKind, Model};

/// What a parameter is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ParamKind {
    /// Mass of body `i`.
    Mass(usize),
    /// Centre-of-mass coordinate `axis` (0..3) of body `i`, in its frame.
    Com(usize, usize),
    /// Rotational-inertia entry of body `i` about its centre of mass, body axes:
    /// 0 xx, 1 xy, 2 xz, 3 yy, 4 yz, 5 zz.
    Inertia(usize, usize),
    /// Gravity magnitude `g` (its direction stays the model's).
    Gravity,
    /// Component `axis` of joint `i`'s home offset `H_i^{λ(i)}(0)` translation, in the parent.
    Length(usize, usize),
    /// Armature of joint `i`: the rotor inertia reflected to it, `I_a,i`, added to `M_ii`.
    Armature(usize),
}

impl ParamKind {
    /// The selection group (`mass`, `com`, `inertia`, `gravity`, `lengths`, `armature`).
    pub fn group(&self) -> &'static str {
        match self {
            ParamKind::Mass(_) => "mass",
            ParamKind::Com(..) => "com",
            ParamKind::Inertia(..) => "inertia",
            ParamKind::Gravity => "gravity",
            ParamKind::Length(..) => "lengths",
            ParamKind::Armature(_) => "armature",
        }
    }
}

/// One named parameter.
#[derive(Clone, Debug, PartialEq)]
pub struct Param {
    /// The name used in printed equations and as a generated-code argument.
    pub name: String,
    /// The model's value.
    pub value: f64,
    /// What it is.
    pub kind: ParamKind,
    /// Whether it is kept as a symbol.
    pub symbolic: bool,
    /// A short description ("mass of link2").
    pub meaning: String,
}

/// Every parameter of a model, in printing order (masses, inertias, centres of mass, gravity,
/// lengths, armatures).
#[derive(Clone, Debug, PartialEq)]
pub struct ParamTable {
    /// The parameters.
    pub params: Vec<Param>,
}

const AX: [&str; 3] = ["x", "y", "z"];
const IN: [&str; 6] = ["xx", "xy", "xz", "yy", "yz", "zz"];
const IN_IDX: [(usize, usize); 6] = [(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)];

/// Rounds values within `1e-12` of `0` or `±1` to them (e.g. `cos(π/2)` from a DH twist).
pub fn clean(x: f64) -> f64 {
    if x.abs() < 1e-12 {
        0.0
    } else if (x - 1.0).abs() < 1e-12 {
        1.0
    } else if (x + 1.0).abs() < 1e-12 {
        -1.0
    } else {
        x
    }
}

/// Whether joint `i` has the standard-DH shape: `H = Rx(α)` rotation, offset `(a, 0, d)`, axis
/// `z` through the parent origin — so its offsets are named `a_i`, `d_i`.
fn standard_dh_shape(model: &Model, i: usize) -> bool {
    let j = &model.joints()[i];
    let r = &j.home.rotation;
    let p = &j.home.translation;
    let rot_x = clean(r[(0, 0)]) == 1.0 && clean(r[(0, 1)]) == 0.0 && clean(r[(0, 2)]) == 0.0;
    if !rot_x || clean(p.y) != 0.0 || !matches!(j.kind, JointKind::Revolute | JointKind::Continuous)
    {
        return false;
    }
    let s_parent = j.home.act_twist(&j.screw);
    let w = [s_parent[0], s_parent[1], s_parent[2]].map(clean);
    let v = [s_parent[3], s_parent[4], s_parent[5]].map(clean);
    w == [0.0, 0.0, 1.0] && v == [0.0, 0.0, 0.0]
}

impl ParamTable {
    /// The parameters of `model`, all numeric. The built-in two-link arm (`planar2`) uses the
    /// textbook names `m1, m2, L1, L2, g`; other models `m_<link>`, `cx_<link>`,
    /// `Ixx_<link>`, …, `g`, and `a_<i>`, `d_<i>` (standard-DH joints) or `px_<i>`, `py_<i>`,
    /// `pz_<i>` (joint `i`'s home offset, 1-based), and `Ia_<i>` (joint `i`'s armature, 1-based).
    pub fn new(model: &Model) -> Self {
        let textbook = model.name() == "planar2" && model.nq() == 2;
        let mut params = Vec::new();
        let bodies = model.bodies();
        let body_tag = |i: usize| -> String {
            if textbook {
                format!("{}", i + 1)
            } else {
                // Link names become identifiers of generated code: other characters → '_'.
                let id: String = bodies[i]
                    .name
                    .chars()
                    .map(|c| {
                        if c.is_ascii_alphanumeric() || c == '_' {
                            c
                        } else {
                            '_'
                        }
                    })
                    .collect();
                format!("_{id}")
            }
        };
        for (i, b) in bodies.iter().enumerate() {
            params.push(Param {
                name: format!("m{}", body_tag(i)),
                value: b.inertia.mass,
                kind: ParamKind::Mass(i),
                symbolic: false,
                meaning: format!("mass of {}", b.name),
            });
        }
        for (i, b) in bodies.iter().enumerate() {
            for (k, (r, c)) in IN_IDX.iter().enumerate() {
                params.push(Param {
                    name: format!("I{}{}", IN[k], body_tag(i)),
                    value: b.inertia.inertia_com[(*r, *c)],
                    kind: ParamKind::Inertia(i, k),
                    symbolic: false,
                    meaning: format!("inertia I{} of {} about its CoM", IN[k], b.name),
                });
            }
        }
        for (i, b) in bodies.iter().enumerate() {
            for (a, ax) in AX.iter().enumerate() {
                params.push(Param {
                    name: format!("c{}{}", ax, body_tag(i)),
                    value: b.inertia.com[a],
                    kind: ParamKind::Com(i, a),
                    symbolic: false,
                    meaning: format!("centre of mass {} of {}", ax, b.name),
                });
            }
        }
        params.push(Param {
            name: "g".into(),
            value: model.gravity().norm(),
            kind: ParamKind::Gravity,
            symbolic: false,
            meaning: "gravity magnitude".into(),
        });
        for (i, j) in model.joints().iter().enumerate() {
            let dh = !textbook && standard_dh_shape(model, i);
            for (a, ax) in AX.iter().enumerate() {
                let name = if textbook {
                    if a == 0 {
                        format!("L{}", i + 1)
                    } else {
                        format!("L{}{}", ax, i + 1)
                    }
                } else if dh && a == 0 {
                    format!("a_{}", i + 1)
                } else if dh && a == 2 {
                    format!("d_{}", i + 1)
                } else {
                    format!("p{}_{}", ax, i + 1)
                };
                params.push(Param {
                    name,
                    value: clean(j.home.translation[a]),
                    kind: ParamKind::Length(i, a),
                    symbolic: false,
                    meaning: format!("offset {} of joint {} in its parent", ax, j.name),
                });
            }
        }
        for (i, j) in model.joints().iter().enumerate() {
            params.push(Param {
                name: format!("Ia_{}", i + 1),
                value: j.armature,
                kind: ParamKind::Armature(i),
                symbolic: false,
                meaning: format!(
                    "armature of joint {} (rotor inertia reflected to it)",
                    j.name
                ),
            });
        }
        ParamTable { params }
    }

    /// Marks parameters as symbols from a selection: a comma-separated list of `all`, groups
    /// (`mass`, `com`, `inertia`, `gravity`, `lengths`, `armature`) and names. Groups and `all` take only
    /// the parameters whose value is not zero (a zero stays a zero); a name is taken even when
    /// its value is zero. `none` or an empty string keeps everything numeric.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for an unknown name.
    pub fn select(&mut self, spec: &str) -> Result<()> {
        for item in spec.split(',').map(str::trim).filter(|s| !s.is_empty()) {
            match item {
                "none" => {}
                "all" | "mass" | "com" | "inertia" | "gravity" | "lengths" | "length"
                | "armature" => {
                    for p in &mut self.params {
                        let g = p.kind.group();
                        if (item == "all" || item == g || (item == "length" && g == "lengths"))
                            && p.value != 0.0
                        {
                            p.symbolic = true;
                        }
                    }
                }
                name => {
                    let k = self
                        .params
                        .iter()
                        .position(|p| p.name == name)
                        .ok_or_else(|| {
                            let known: Vec<&str> = self
                                .params
                                .iter()
                                .filter(|p| p.value != 0.0)
                                .map(|p| p.name.as_str())
                                .take(24)
                                .collect();
                            Error::InvalidArgument(format!(
                                "unknown symbol '{name}' (use all, mass, com, inertia, gravity, \
                             lengths, armature or parameter names such as {})",
                                known.join(", ")
                            ))
                        })?;
                    self.params[k].symbolic = true;
                }
            }
        }
        Ok(())
    }

    /// Index of the parameter of this kind.
    pub fn index(&self, kind: ParamKind) -> usize {
        self.params
            .iter()
            .position(|p| p.kind == kind)
            .expect("every kind is in the table")
    }

    /// The symbolic parameters, in table order, with their table indices.
    pub fn symbols(&self) -> Vec<(usize, &Param)> {
        self.params
            .iter()
            .enumerate()
            .filter(|(_, p)| p.symbolic)
            .collect()
    }
}
