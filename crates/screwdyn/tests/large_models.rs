//! Issue 12.6: loading and the O(n) algorithms are linear in the size of the robot, in time and
//! memory. A generated chain of 10,000 joints loads from URDF and runs forward kinematics, RNEA
//! and ABA; the peak heap is measured by a counting global allocator and compared with a chain
//! half as long, and the results are checked against the closed form of a horizontal chain of
//! point masses.

use screwdyn::dynamics::{aba, crba, gravity_torque, lagrange_coefficients, rnea};
use screwdyn::io::{load_str, LoadOptions};
use screwdyn::kinematics::{forward_kinematics, frame_pose};
use screwdyn::Workspace;
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Peak;

static NOW: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Peak {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let now = NOW.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
        PEAK.fetch_max(now, Ordering::Relaxed);
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        NOW.fetch_sub(layout.size(), Ordering::Relaxed);
        System.dealloc(ptr, layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if new_size > layout.size() {
            let now = NOW.fetch_add(new_size - layout.size(), Ordering::Relaxed) + new_size
                - layout.size();
            PEAK.fetch_max(now, Ordering::Relaxed);
        } else {
            NOW.fetch_sub(layout.size() - new_size, Ordering::Relaxed);
        }
        System.realloc(ptr, layout, new_size)
    }
}

#[global_allocator]
static GLOBAL: Peak = Peak;

const L: f64 = 0.001; // link length (m)
const M: f64 = 0.001; // point mass at each link origin (kg)
const G: f64 = 9.81;

/// A straight chain along x of `n` joints about y, link `i`'s frame at `x = i L` and its point
/// mass one link length further out.
fn chain_urdf(n: usize) -> String {
    let mut s = String::from("<robot name=\"chain\">\n<link name=\"l0\"/>\n");
    for i in 1..=n {
        s.push_str(&format!(
            "<link name=\"l{i}\"><inertial><origin xyz=\"{L} 0 0\"/><mass value=\"{M}\"/><inertia ixx=\"0\" iyy=\"0\" izz=\"0\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link>\n\
             <joint name=\"j{i}\" type=\"continuous\"><parent link=\"l{}\"/><child link=\"l{i}\"/><origin xyz=\"{L} 0 0\"/><axis xyz=\"0 1 0\"/></joint>\n",
            i - 1
        ));
    }
    s.push_str("</robot>\n");
    s
}

/// Peak heap bytes above the level at the start while loading the chain and running FK, the
/// gravity torques (RNEA) and ABA once; checks the physics on the way.
fn run(n: usize) -> usize {
    let text = chain_urdf(n);
    let base = NOW.load(Ordering::Relaxed);
    PEAK.store(base, Ordering::Relaxed);
    let m = load_str(&text, "chain.urdf", &LoadOptions::default()).unwrap();
    assert_eq!(m.nq(), n);
    let mut ws = Workspace::new(&m);
    let q = vec![0.0; n];
    forward_kinematics(&m, &mut ws, &q).unwrap();
    let tip = frame_pose(&m, &ws, m.frame_id(&format!("l{n}")).unwrap()).unwrap();
    assert!((tip.translation.x - n as f64 * L).abs() < 1e-9);
    // Joint j (0-based) carries the c = n − j masses at 1, 2, …, c link lengths beyond it; the
    // weight pulls them down (−z), so holding them takes τ_j = −m g L c(c + 1)/2 about y.
    let g = gravity_torque(&m, &mut ws, &q).unwrap().clone();
    for i in [0, n / 2, n - 1] {
        let c = (n - i) as f64;
        let expected = -M * G * L * c * (c + 1.0) / 2.0;
        assert!(
            (g[i] - expected).abs() <= 1e-9 * (1.0 + expected.abs()),
            "τ_{i} = {} vs {expected}",
            g[i]
        );
    }
    // Holding torques keep the chain still: ABA gives q̈ ≈ 0, which RNEA maps back to the same
    // torques (the tip's inertia is m L² = 1e-9, so q̈ itself is only as good as the conditioning).
    let v = vec![0.0; n];
    let qdd = aba(&m, &mut ws, &q, &v, g.as_slice()).unwrap().clone();
    let back = rnea(&m, &mut ws, &q, &v, qdd.as_slice()).unwrap();
    assert!(
        (back - &g).amax() <= 1e-9 * g.amax(),
        "{}",
        (back - &g).amax()
    );
    PEAK.load(Ordering::Relaxed) - base
}

#[test]
fn a_ten_thousand_joint_chain_loads_and_runs_in_linear_memory() {
    let small = run(5_000);
    let large = run(10_000);
    let ratio = large as f64 / small as f64;
    // Linear: twice the joints, about twice the memory (a quadratic term would give 4).
    assert!(
        ratio < 2.6,
        "peak {small} B at 5k joints, {large} B at 10k ({ratio:.2}×)"
    );
    // And small in absolute terms: a few kB per joint, not n² doubles (800 MB at 10k).
    assert!(large < 10_000 * 8_000, "{large} B for 10k joints");
}

#[test]
fn algorithms_that_need_n_by_n_storage_get_it_on_first_use_and_quadratic_ones_are_refused() {
    let n = 300;
    let m = load_str(&chain_urdf(n), "chain.urdf", &LoadOptions::default()).unwrap();
    let mut ws = Workspace::new(&m);
    assert_eq!(
        ws.mass_matrix.nrows(),
        0,
        "no n×n buffer above the eager size"
    );
    let mm = crba(&m, &mut ws, &vec![0.0; n]).unwrap();
    // The last joint moves one point mass one link length away: M_nn = m L².
    assert!((mm[(n - 1, n - 1)] - M * L * L).abs() < 1e-18);
    let e = lagrange_coefficients(&m, &vec![0.0; n])
        .unwrap_err()
        .to_string();
    assert!(e.contains("300 joints") && e.contains("limit of 60"), "{e}");
}
