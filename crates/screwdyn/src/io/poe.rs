//! Product of exponentials in the Modern Robotics style, as the MATLAB uses it: the
//! end-effector home pose `M`, the screw axes `Slist` in the space frame, `Mlist` (link `i`'s
//! frame — at its CoM — relative to link `i−1`'s, at home) and `Glist` (6×6 spatial inertias in
//! those frames, angular first).
//!
//! Mapping to the [`Model`]: link `i`'s home pose in space is `M_i = M_{01} ⋯ M_{i−1,i}`; its
//! joint's screw in the child frame is `S_i^{i,i−1} = Ad_{M_i⁻¹} S_i` (Lynch & Park, *Modern Robotics*, body vs space
//! screws); `H_i^{i−1}(0) = M_{i−1,i}`; `𝔍^{i,i} = G_i`. `M` becomes the extra frame `ee` on the
//! last link, placed at `M_n⁻¹ M`. The joint kind follows from the screw: `ω = 0` prismatic,
//! pitch `ω·v = 0` revolute, otherwise helical. `Mlist` may have `n` or `n + 1` entries (the last
//! one then is `M_{n,n+1}`, and `M`, if also given, must agree with it).
//!
//! TOML keys (`format = "poe"`):
//!
//! | key | meaning |
//! | --- | --- |
//! | `name`, `base`, `gravity` | robot name, root link name (default `base`), gravity (default `[0, 0, -9.81]`) |
//! | `M` | 4×4 home pose of the end-effector in space (4 rows) |
//! | `Slist` | list of `n` screws `[ωx, ωy, ωz, vx, vy, vz]` in the space frame (MR's columns, written as rows) |
//! | `Mlist` | list of `n` or `n + 1` 4×4 matrices |
//! | `Glist` | list of `n` 6×6 matrices |
//! | `joints`, `links` | optional names (default `joint<i>`, `link<i>`) |
//! | `lower`, `upper`, `velocity`, `effort` | optional lists of `n` joint limits |
//! | `armature` | optional list of `n` rotor inertias reflected to the joints (kg·m² or kg) |
//! | `[[frame]]` `name`, `link`, `pose = { xyz, rpy }` | extra frames, placed in the CoM frames |
//!
//! ```
//! use nalgebra::{Matrix6, Vector3, Vector6};
//! use screwdyn::io::poe::from_poe;
//! use screwdyn::spatial::Se3;
//! // One link: a 1 kg point mass 1 m along x, turning about the space z axis.
//! let m01 = Se3::from_translation(Vector3::new(1.0, 0.0, 0.0));
//! let s1 = Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0);
//! let g1 = Matrix6::from_diagonal(&Vector6::new(0.0, 0.0, 0.0, 1.0, 1.0, 1.0));
//! let model = from_poe("one", Some(&m01), &[s1], &[m01], &[g1]).unwrap();
//! // Body screw Ad_{M_1⁻¹} S_1 = (0, 0, 1, 0, 1, 0).
//! assert_eq!(model.joints()[0].screw, Vector6::new(0.0, 0.0, 1.0, 0.0, 1.0, 0.0));
//! ```

use super::common::{self, FrameSpec};
use super::options::LoadOptions;
use crate::error::{Error, Result};
use crate::model::{JointSpec, Model, ModelBuilder};
use crate::spatial::{ang, lin, Se3, SpatialInertia, Twist};
use nalgebra::{Matrix4, Matrix6};
use serde::Deserialize;

/// Everything a PoE description holds besides `M`, `Slist`, `Mlist`, `Glist`.
#[derive(Clone, Debug, Default)]
pub struct PoeExtras {
    /// Root link name (default `base`).
    pub base: Option<String>,
    /// Joint names (default `joint<i>`).
    pub joints: Option<Vec<String>>,
    /// Link names (default `link<i>`).
    pub links: Option<Vec<String>>,
    /// `(lower, upper)` position limits per joint.
    pub limits: Option<Vec<(f64, f64)>>,
    /// Speed limits per joint.
    pub velocity: Option<Vec<f64>>,
    /// Effort limits per joint.
    pub effort: Option<Vec<f64>>,
    /// Armature (rotor inertia reflected to the joint) per joint.
    pub armature: Option<Vec<f64>>,
    /// Make physical-consistency problems errors (see [`ModelBuilder::strict`]).
    pub strict: bool,
}

/// Builds a model from Modern Robotics' `M`, `Slist`, `Mlist`, `Glist` (gravity
/// `(0, 0, −9.81)`; use [`Model::with_gravity`] to change it).
///
/// # Errors
/// [`Error::InvalidModel`] when the lists disagree in length, a screw or matrix is malformed, or a name repeats.
pub fn from_poe(
    name: &str,
    m: Option<&Se3>,
    slist: &[Twist],
    mlist: &[Se3],
    glist: &[Matrix6<f64>],
) -> Result<Model> {
    let b = poe_builder(name, m, slist, mlist, glist, &PoeExtras::default(), "PoE")?;
    b.build()
}

/// [`from_poe`] returning the [`ModelBuilder`], to add frames, names and gravity; `what` prefixes
/// messages (e.g. the file name).
///
/// # Errors
/// As [`from_poe`].
pub fn poe_builder(
    name: &str,
    m: Option<&Se3>,
    slist: &[Twist],
    mlist: &[Se3],
    glist: &[Matrix6<f64>],
    extras: &PoeExtras,
    what: &str,
) -> Result<ModelBuilder> {
    let n = slist.len();
    let bad = |s: String| Err(Error::InvalidModel(format!("{what}: {s}")));
    if n == 0 {
        return bad("Slist is empty".into());
    }
    if glist.len() != n {
        return bad(format!(
            "Glist has {} entries but Slist has {n}",
            glist.len()
        ));
    }
    if mlist.len() != n && mlist.len() != n + 1 {
        return bad(format!(
            "Mlist has {} entries but Slist has {n} (expected {n} or {})",
            mlist.len(),
            n + 1
        ));
    }
    let names = |given: &Option<Vec<String>>, prefix: &str, key: &str| -> Result<Vec<String>> {
        match given {
            Some(v) if v.len() != n => Err(Error::InvalidModel(format!(
                "{what}: {key} has {} names but Slist has {n} screws",
                v.len()
            ))),
            Some(v) => Ok(v.clone()),
            None => Ok((1..=n).map(|i| format!("{prefix}{i}")).collect()),
        }
    };
    let jn = names(&extras.joints, "joint", "joints")?;
    let ln = names(&extras.links, "link", "links")?;
    let lens = [
        extras.limits.as_ref().map(|v| v.len()),
        extras.velocity.as_ref().map(|v| v.len()),
        extras.effort.as_ref().map(|v| v.len()),
        extras.armature.as_ref().map(|v| v.len()),
    ];
    if let Some(len) = lens.into_iter().flatten().find(|&l| l != n) {
        return bad(format!(
            "a list of joint limits or armatures has {len} entries but Slist has {n}"
        ));
    }
    let mut b = ModelBuilder::new(name);
    let base = extras.base.clone().unwrap_or_else(|| "base".into());
    b.base_name(&base).strict(extras.strict);
    let mut m_i = Se3::identity();
    for i in 0..n {
        m_i = m_i.compose(&mlist[i]);
        let j = poe_joint(&jn[i], i, &slist[i], &m_i, extras, what)?;
        let g = SpatialInertia::from_matrix(&glist[i]).map_err(|why| {
            Error::InvalidModel(format!(
                "{what}: Glist entry {} is not a spatial inertia: {why}",
                i + 1
            ))
        })?;
        let parent = if i == 0 {
            base.clone()
        } else {
            ln[i - 1].clone()
        };
        b.link(&ln[i], &parent, j, mlist[i], g);
    }
    if let Some(ee) = end_effector(m, &m_i, mlist, n, what)? {
        b.frame("ee", &ln[n - 1], ee);
    }
    Ok(b)
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(non_snake_case)]
struct PoeFile {
    #[allow(dead_code)]
    format: String,
    #[serde(default)]
    name: Option<String>,
    #[serde(default)]
    base: Option<String>,
    #[serde(default)]
    gravity: Option<[f64; 3]>,
    #[serde(default)]
    M: Option<[[f64; 4]; 4]>,
    Slist: Vec<[f64; 6]>,
    Mlist: Vec<[[f64; 4]; 4]>,
    Glist: Vec<[[f64; 6]; 6]>,
    #[serde(default)]
    joints: Option<Vec<String>>,
    #[serde(default)]
    links: Option<Vec<String>>,
    #[serde(default)]
    lower: Option<Vec<f64>>,
    #[serde(default)]
    upper: Option<Vec<f64>>,
    #[serde(default)]
    velocity: Option<Vec<f64>>,
    #[serde(default)]
    effort: Option<Vec<f64>>,
    #[serde(default)]
    armature: Option<Vec<f64>>,
    #[serde(default)]
    frame: Vec<toml::Spanned<FrameSpec>>,
}

fn se3_rows(rows: &[[f64; 4]; 4], what: &str, file: &str) -> Result<Se3> {
    let m = Matrix4::from_fn(|i, j| rows[i][j]);
    let h = Se3::from_matrix(&m);
    let r = h.rotation;
    let ok = (r.transpose() * r - nalgebra::Matrix3::identity()).amax() < 1e-6
        && r.determinant() > 0.0
        && (m.row(3) - nalgebra::RowVector4::new(0.0, 0.0, 0.0, 1.0)).amax() < 1e-9
        && m.iter().all(|x| x.is_finite());
    if ok {
        Ok(h)
    } else {
        Err(Error::parse(
            file,
            format!("{what} is not a homogeneous transform [R p; 0 0 0 1] with R a rotation"),
        ))
    }
}

/// Parses a PoE TOML description (see the module documentation for the keys).
///
/// # Errors
/// [`Error::Parse`] for malformed text and [`Error::InvalidModel`] for an inconsistent model,
/// each naming the file and, where known, the line (and, with `strict`, the first
/// physical-consistency problem).
pub fn parse_poe(text: &str, file: &str, options: &LoadOptions) -> Result<Model> {
    let f: PoeFile = common::from_toml(text, file)?;
    let n = f.Slist.len();
    let m = f.M.as_ref().map(|r| se3_rows(r, "M", file)).transpose()?;
    let mlist = f
        .Mlist
        .iter()
        .enumerate()
        .map(|(k, r)| se3_rows(r, &format!("Mlist entry {}", k + 1), file))
        .collect::<Result<Vec<_>>>()?;
    let glist: Vec<Matrix6<f64>> = f
        .Glist
        .iter()
        .map(|r| Matrix6::from_fn(|i, j| r[i][j]))
        .collect();
    let slist: Vec<Twist> = f.Slist.iter().map(|s| Twist::from(*s)).collect();
    for (key, v) in [
        ("lower", &f.lower),
        ("upper", &f.upper),
        ("velocity", &f.velocity),
        ("effort", &f.effort),
        ("armature", &f.armature),
    ] {
        if let Some(v) = v {
            if v.len() != n {
                return Err(Error::parse(
                    file,
                    format!("{key} has {} values but Slist has {n} screws", v.len()),
                ));
            }
        }
    }
    let inf = crate::model::JointLimits::<f64>::default().upper;
    let limits = (f.lower.is_some() || f.upper.is_some()).then(|| {
        (0..n)
            .map(|i| {
                (
                    f.lower.as_ref().map_or(-inf, |v| v[i]),
                    f.upper.as_ref().map_or(inf, |v| v[i]),
                )
            })
            .collect()
    });
    let extras = PoeExtras {
        base: f.base.clone(),
        joints: f.joints.clone(),
        links: f.links.clone(),
        limits,
        velocity: f.velocity.clone(),
        effort: f.effort.clone(),
        armature: f.armature.clone(),
        strict: options.strict,
    };
    let header = common::Header {
        name: f.name.as_deref(),
        base: f.base.as_deref(),
        gravity: f.gravity,
        frames: &f.frame,
    };
    let mut b = poe_builder(
        &header.model_name(file),
        m.as_ref(),
        &slist,
        &mlist,
        &glist,
        &extras,
        file,
    )?;
    b.gravity(common::gravity(f.gravity));
    header.finish(b, file, text)
}

/// Joint `i` of a PoE description from its space screw `S_i` (revolute, prismatic or helical by
/// its pitch), written in link frame `i` as `Ad_{M_i⁻¹} S_i` (`m_i = M_{0i}`), with its limits.
fn poe_joint(
    name: &str,
    i: usize,
    s: &Twist,
    m_i: &Se3,
    extras: &PoeExtras,
    what: &str,
) -> Result<JointSpec> {
    let bad = |s: String| Error::InvalidModel(format!("{what}: {s}"));
    let s = *s;
    if !s.iter().all(|x| x.is_finite()) {
        return Err(bad(format!(
            "screw {} of Slist has a non-finite entry",
            i + 1
        )));
    }
    let (w, v) = (ang(&s), lin(&s));
    let mut j = if w.norm() < 1e-12 {
        if v.norm() < 1e-12 {
            return Err(bad(format!("screw {} of Slist is zero", i + 1)));
        }
        JointSpec::prismatic(name)
    } else {
        let pitch = w.dot(&v) / w.norm_squared();
        if pitch.abs() < 1e-12 {
            JointSpec::revolute(name)
        } else {
            JointSpec::helical(name, pitch)
        }
    };
    // Body screw of joint i in link frame i: Ad_{M_i⁻¹} S_i.
    j = j.screw_in_child(m_i.inv_act_twist(&s));
    if let Some(l) = &extras.limits {
        j = j.limits(l[i].0, l[i].1);
    }
    if let Some(v) = &extras.velocity {
        j = j.velocity_limit(v[i]);
    }
    if let Some(e) = &extras.effort {
        j = j.effort_limit(e[i]);
    }
    if let Some(a) = &extras.armature {
        j = j.armature(a[i]);
    }
    Ok(j)
}

/// The end-effector frame `M_{n,n+1}` in the last link (`m_n = M_{0n}`), from `M` (home pose
/// of the end effector in the base) and/or an `(n+1)`-th `Mlist` entry, which must agree.
fn end_effector(
    m: Option<&Se3>,
    m_n: &Se3,
    mlist: &[Se3],
    n: usize,
    what: &str,
) -> Result<Option<Se3>> {
    let from_mlist = (mlist.len() == n + 1).then(|| mlist[n]);
    Ok(match (m, from_mlist) {
        (Some(m), Some(last)) => {
            let from_m = m_n.inverse().compose(m);
            if (from_m.to_matrix() - last.to_matrix()).amax() > 1e-9 {
                return Err(Error::InvalidModel(format!(
                    "{what}: M disagrees with the last Mlist entry M_{n}{}: M must equal M01⋯M{n}{}",
                    n + 1,
                    n + 1
                )));
            }
            Some(last)
        }
        (Some(m), None) => Some(m_n.inverse().compose(m)),
        (None, last) => last,
    })
}
