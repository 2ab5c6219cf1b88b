//! Joint springs (`stiffness` k, `springref` q_spring): the passive torque `τ = −k (q − q_spring)`
//! in simulation (the analytic oscillation of a spring–mass slide and a damped one), read from
//! MJCF (defaults, degrees), TOML, written to MJCF, and a warning where URDF cannot hold them.
//! Agreement with MuJoCo's `qfrc_passive` and `mj_step` is checked in the Python suite
//! (crates/screwdyn-py/tests/test_mjcf_springs.py).

use screwdyn::io::mjcf_export::to_mjcf_string;
use screwdyn::io::urdf::urdf_export_warnings;
use screwdyn::io::{load_str, LoadOptions};
use screwdyn::sim::{simulate, EffectGains, Integrator, JointEffects, SimOptions, ZeroTorque};
use screwdyn::Model;
use std::f64::consts::PI;

fn load(text: &str, file: &str) -> Model {
    load_str(text, file, &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

/// A slide of mass `m` along x, no gravity, with spring `k` about `q_s` and damping `b`.
fn slide(m: f64, k: f64, q_s: f64, b: f64) -> Model {
    load(
        &format!(
            r#"<mujoco><option gravity="0 0 0"/><worldbody><body name="cart">
  <joint name="x" type="slide" axis="1 0 0" stiffness="{k}" springref="{q_s}" damping="{b}"/>
  <geom type="sphere" size="0.1" mass="{m}"/></body></worldbody></mujoco>"#
        ),
        "slide.xml",
    )
}

fn passive(effects: JointEffects) -> SimOptions {
    SimOptions {
        dt: 1e-3,
        effects,
        integrator: Integrator::Rk4,
        ..Default::default()
    }
}

#[test]
fn the_spring_torque_is_minus_k_times_the_stretch() {
    let m = slide(2.0, 50.0, 0.3, 4.0);
    let springs = JointEffects {
        damping: true,
        springs: true,
        ..JointEffects::none()
    };
    let gains = EffectGains::new(&springs, &m, &[0.0], 1e-3).unwrap();
    let mut tau = [0.0];
    springs
        .apply(&m, &gains, &[0.5], &[-0.25], &[1.5], &mut tau)
        .unwrap();
    // 1.5 − 50 (0.5 − 0.3) − 4 (−0.25) = 1.5 − 10 + 1
    assert!((tau[0] - (1.5 - 10.0 + 1.0)).abs() < 1e-12, "{}", tau[0]);
    let off = JointEffects {
        springs: false,
        ..springs
    };
    off.apply(&m, &gains, &[0.5], &[-0.25], &[1.5], &mut tau)
        .unwrap();
    assert!((tau[0] - 2.5).abs() < 1e-12);
}

#[test]
fn an_undamped_spring_mass_oscillates_about_springref_at_sqrt_k_over_m() {
    // q(t) = q_s + (q0 − q_s) cos ωt, ω = √(k/m); the armature adds to the moving mass.
    let (mass, armature, k, q_s, q0) = (2.0, 0.5, 50.0, 0.3, 0.8);
    let m = slide(mass, k, q_s, 0.0).with_armature(&[armature]).unwrap();
    let w = (k / (mass + armature)).sqrt();
    let opts = SimOptions {
        duration: 2.0 * PI / w,
        ..passive(JointEffects {
            springs: true,
            ..JointEffects::none()
        })
    };
    let run = simulate(&m, &[q0], &[0.0], &mut ZeroTorque, &[], &opts, &mut |_| {}).unwrap();
    for (t, q) in run.t.iter().zip(&run.q) {
        let want = q_s + (q0 - q_s) * (w * t).cos();
        assert!((q[0] - want).abs() < 1e-9, "t = {t}: {} vs {want}", q[0]);
    }
    // The recorded potential energy holds the spring's ½ k (q − q_s)², so the total energy
    // is the initial stretch's, ½ k (q0 − q_s)², throughout (RK4 at 1 ms: ~1e-9 relative).
    let e0 = 0.5 * k * (q0 - q_s).powi(2);
    assert!((run.potential_energy[0] - e0).abs() < 1e-12);
    for (t, e) in run.t.iter().zip(&run.total_energy) {
        assert!((e - e0).abs() < 1e-8 * e0, "t = {t}: E = {e} vs {e0}");
    }
    // Without the spring effect the cart stays where it is.
    let still = simulate(
        &m,
        &[q0],
        &[0.0],
        &mut ZeroTorque,
        &[],
        &passive(JointEffects::none()),
        &mut |_| {},
    )
    .unwrap();
    assert_eq!(still.q.last().unwrap()[0], q0);
}

#[test]
fn a_damped_spring_mass_decays_as_the_analytic_underdamped_oscillator() {
    // m q̈ + b q̇ + k (q − q_s) = 0 from rest at q0: with ζ = b / (2√(km)) < 1,
    // x(t) = (q0 − q_s) e^{−ζω t} (cos ω_d t + ζω/ω_d sin ω_d t), ω_d = ω√(1 − ζ²).
    let (mass, k, q_s, b, q0) = (1.5, 40.0, -0.2, 1.2, 0.4);
    let m = slide(mass, k, q_s, b);
    let w = (k / mass).sqrt();
    let zeta = b / (2.0 * (k * mass).sqrt());
    let wd = w * (1.0 - zeta * zeta).sqrt();
    let opts = SimOptions {
        duration: 1.5,
        ..passive(JointEffects {
            springs: true,
            damping: true,
            ..JointEffects::none()
        })
    };
    let run = simulate(&m, &[q0], &[0.0], &mut ZeroTorque, &[], &opts, &mut |_| {}).unwrap();
    for (t, q) in run.t.iter().zip(&run.q) {
        let x =
            (q0 - q_s) * (-zeta * w * t).exp() * ((wd * t).cos() + zeta * w / wd * (wd * t).sin());
        assert!((q[0] - (q_s + x)).abs() < 1e-9, "t = {t}");
    }
}

#[test]
fn mjcf_springs_follow_defaults_and_the_angle_unit() {
    // Degrees (MuJoCo's default): a hinge's springref is an angle, a slide's a length.
    let m = load(
        r#"<mujoco>
  <default><joint stiffness="2"/><default class="stiff"><joint stiffness="9" springref="30"/></default></default>
  <worldbody><body name="a"><geom size="0.1"/>
    <joint name="by_default"/>
    <joint name="by_class" class="stiff"/>
    <joint name="own" stiffness="4" springref="-90"/>
    <body name="b"><geom size="0.1"/><joint name="s" type="slide" stiffness="5" springref="30"/></body>
  </body></worldbody></mujoco>"#,
        "springs.xml",
    );
    let got: Vec<(f64, f64)> = m
        .joints()
        .iter()
        .map(|j| (j.stiffness, j.springref))
        .collect();
    let want = [(2.0, 0.0), (9.0, PI / 6.0), (4.0, -PI / 2.0), (5.0, 30.0)];
    for (g, w) in got.iter().zip(&want) {
        assert!(
            (g.0 - w.0).abs() < 1e-15 && (g.1 - w.1).abs() < 1e-15,
            "{got:?}"
        );
    }
    // A negative stiffness is refused where it is written.
    let e = load_str(
        "<mujoco><worldbody><body><geom size=\"1\"/><joint name=\"j\" stiffness=\"-1\"/></body></worldbody></mujoco>",
        "bad.xml",
        &LoadOptions::default(),
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.starts_with("bad.xml:1:") && e.contains("stiffness"),
        "{e}"
    );
}

#[test]
fn springs_survive_export_to_mjcf_and_toml_reads_them() {
    let toml = r#"
format = "screwdyn"
gravity = [0, 0, 0]
[[body]]
name = "link1"
parent = "base"
joint = "joint1"
type = "revolute"
screw_in_child = [0, 0, 1, 0, 0, 0]
mass = 1.0
com = [1, 0, 0]
stiffness = 3.5
springref = 0.25
damping = 0.5
"#;
    let m = load(toml, "spring.toml");
    let j = &m.joints()[0];
    assert_eq!((j.stiffness, j.springref, j.damping), (3.5, 0.25, 0.5));
    let xml = to_mjcf_string(&m).unwrap();
    assert!(
        xml.contains("stiffness=\"3.5\"") && xml.contains("springref=\"0.25\""),
        "{xml}"
    );
    let back = load(&xml, "back.xml");
    let b = &back.joints()[0];
    assert_eq!((b.stiffness, b.springref), (3.5, 0.25));
    // URDF cannot hold a spring: one warning names the joint.
    let w = urdf_export_warnings(&m);
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(w[0].contains("joint1") && w[0].contains("spring"));
    // A DH row takes the same keys.
    let dh = load(
        "format = \"dh\"\n[[row]]\ntype = \"P\"\nmass = 1.0\nstiffness = 7.0\nspringref = 0.1\n",
        "dh.toml",
    );
    assert_eq!(
        (dh.joints()[0].stiffness, dh.joints()[0].springref),
        (7.0, 0.1)
    );
}
