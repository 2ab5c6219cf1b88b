//! The neutral configuration and random configurations: within the limits, the same for a seed,
//! covering each joint's range (statistical bounds).

use nalgebra::{Vector3, Vector6};
use screwdyn::model::{JointSpec, ModelBuilder, SplitMix64};
use screwdyn::spatial::{Se3, SpatialInertia};
use screwdyn::Model;
use std::f64::consts::PI;

/// A chain of every kind of range: finite limits away from zero, none, one-sided ones.
fn chain() -> Model {
    let rz = Vector6::new(0.0, 0.0, 1.0, 0.0, 0.0, 0.0);
    let tz = Vector6::new(0.0, 0.0, 0.0, 0.0, 0.0, 1.0);
    let joints = [
        JointSpec::revolute("limited").limits(0.5, 2.0),
        JointSpec::continuous("free"),
        JointSpec::prismatic("slide"),
        JointSpec::prismatic("short_slide").limits(-0.2, 0.3),
        JointSpec::revolute("from_five").limits(5.0, f64::INFINITY),
        JointSpec::revolute("below_one").limits(f64::NEG_INFINITY, 1.0),
        JointSpec::helical("screw", 0.01).limits(-7.0, -6.0),
    ];
    let mut b = ModelBuilder::new("ranges");
    let mut parent = "base".to_string();
    for (k, j) in joints.into_iter().enumerate() {
        let axis = match j.name() {
            "slide" | "short_slide" => tz,
            "screw" => rz + 0.01 * tz, // pitch 0.01 m/rad: S = (ẑ, h ẑ)
            _ => rz,
        };
        let name = format!("l{k}");
        b.link(
            &name,
            &parent,
            j.screw_in_child(axis),
            Se3::from_translation(Vector3::new(0.1, 0.0, 0.0)),
            SpatialInertia::point_mass(1.0, Vector3::new(0.05, 0.0, 0.0)),
        );
        parent = name;
    }
    b.build().unwrap()
}

#[test]
fn neutral_is_zero_or_the_nearest_point_of_the_range() {
    let m = chain();
    assert_eq!(m.neutral(), vec![0.5, 0.0, 0.0, 0.0, 5.0, 0.0, -6.0]);
    assert_eq!(
        screwdyn::builtin::load("ur5").unwrap().neutral(),
        vec![0.0; 6]
    );
}

#[test]
fn ranges_are_the_limits_or_the_documented_defaults() {
    let expected = vec![
        (0.5, 2.0),
        (-PI, PI),
        (-1.0, 1.0),
        (-0.2, 0.3),
        (5.0, 5.0 + 2.0 * PI),
        (-PI, 1.0),
        (-7.0, -6.0),
    ];
    assert_eq!(chain().configuration_ranges(), expected);
}

#[test]
fn random_configurations_stay_within_the_limits_and_cover_them() {
    let m = chain();
    let ranges = m.configuration_ranges();
    let mut rng = SplitMix64::new(2024);
    let n = 4000;
    let draws: Vec<Vec<f64>> = (0..n).map(|_| m.random_configuration(&mut rng)).collect();
    for (i, &(lo, hi)) in ranges.iter().enumerate() {
        let x: Vec<f64> = draws.iter().map(|q| q[i]).collect();
        let w = hi - lo;
        assert!(
            x.iter().all(|&v| lo <= v && v <= hi),
            "joint {i} left [{lo}, {hi}]"
        );
        // Uniform on [lo, hi]: the mean is within 5 σ/√n of the middle (σ = w/√12), and the
        // extremes come within 0.5 % of the width of each end (a miss has probability
        // (1 − 0.005)^4000 ≈ 2·10⁻⁹).
        let mean = x.iter().sum::<f64>() / n as f64;
        let sigma = w / 12f64.sqrt() / (n as f64).sqrt();
        assert!(
            (mean - (lo + hi) / 2.0).abs() < 5.0 * sigma,
            "joint {i}: mean {mean}"
        );
        let (min, max) = x
            .iter()
            .fold((f64::MAX, f64::MIN), |(a, b), &v| (a.min(v), b.max(v)));
        assert!(
            min - lo < 0.005 * w && hi - max < 0.005 * w,
            "joint {i}: [{min}, {max}]"
        );
        // A quarter of the draws in each quarter of the range, within 5 binomial σ.
        let quarter = x.iter().filter(|&&v| v < lo + w / 4.0).count() as f64;
        let sd = (n as f64 * 0.25 * 0.75).sqrt();
        assert!(
            (quarter - n as f64 / 4.0).abs() < 5.0 * sd,
            "joint {i}: {quarter}"
        );
    }
}

#[test]
fn random_configurations_are_the_same_for_a_seed() {
    let m = chain();
    let (mut a, mut b) = (SplitMix64::new(7), SplitMix64::new(7));
    let first = m.random_configuration(&mut a);
    assert_eq!(first, m.random_configuration(&mut b));
    // The next draw differs, and another seed gives another configuration.
    assert_ne!(first, m.random_configuration(&mut a));
    assert_ne!(first, m.random_configuration(&mut SplitMix64::new(8)));
}

#[test]
fn splitmix64_gives_the_published_sequence() {
    // The first outputs of SplitMix64 from seed 0 (Vigna's reference splitmix64.c).
    let mut rng = SplitMix64::new(0);
    assert_eq!(rng.next_u64(), 0xE220_A839_7B1D_CDAF);
    assert_eq!(rng.next_u64(), 0x6E78_9E6A_A1B9_65F4);
    assert_eq!(rng.next_u64(), 0x06C4_5D18_8009_454F);
}

#[test]
fn unit_coordinates_map_onto_the_ranges() {
    let m = chain();
    let q = m
        .configuration_at(&[0.0, 0.5, 1.0, 0.5, 0.0, 1.0, 0.25])
        .unwrap();
    let expected = [0.5, 0.0, 1.0, 0.05, 5.0, 1.0, -6.75];
    assert!(
        q.iter().zip(expected).all(|(a, b)| (a - b).abs() < 1e-15),
        "{q:?}"
    );
    let e = m.configuration_at(&[0.0; 3]).unwrap_err().to_string();
    assert!(
        e.starts_with("u has 3 values, the model has 7 joints"),
        "{e}"
    );
    let e = m
        .configuration_at(&[0.0, 0.5, 1.0, 0.5, 0.0, 1.2, 0.25])
        .unwrap_err()
        .to_string();
    assert_eq!(
        e,
        "the unit coordinate of joint 5 ('below_one') in row 0 is 1.2, outside [0, 1]"
    );
}

#[test]
fn stacked_rows_are_the_single_rows() {
    let m = chain();
    let rows = m.random_configurations(&mut SplitMix64::new(9), 3);
    let mut rng = SplitMix64::new(9);
    for r in rows.chunks(m.nq()) {
        assert_eq!(r, &m.random_configuration(&mut rng)[..]);
    }
    let u = [0.0, 0.5, 1.0, 0.5, 0.0, 1.0, 0.25];
    let two: Vec<f64> = u.iter().chain(u.iter()).copied().collect();
    let q = m.configurations_at(&two).unwrap();
    let one = m.configuration_at(&u).unwrap();
    assert_eq!(q[..7], one[..]);
    assert_eq!(q[7..], one[..]);
    let e = m.configurations_at(&two[..9]).unwrap_err().to_string();
    assert_eq!(
        e,
        "9 unit coordinates do not make rows of 7 (one per joint)"
    );
    let mut bad = two.clone();
    bad[12] = -0.5;
    let e = m.configurations_at(&bad).unwrap_err().to_string();
    assert_eq!(
        e,
        "the unit coordinate of joint 5 ('below_one') in row 1 is -0.5, outside [0, 1]"
    );
}
