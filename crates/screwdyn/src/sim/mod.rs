//! Simulation: integrators, trajectories, controllers,
//! joint effects, disturbances, recording and torque profiles.
//!
//! ```
//! use screwdyn::sim::{simulate, PdGravity, SimOptions};
//! // PD + gravity compensation brings the two-link arm to rest at its target.
//! let m = screwdyn::builtin::planar2();
//! let mut pd = PdGravity::new(m.clone(), vec![0.5, -0.3], vec![100.0, 100.0], vec![40.0, 40.0]).unwrap();
//! let opts = SimOptions { duration: 5.0, dt: 1e-3, record_every: 100, ..Default::default() };
//! let run = simulate(&m, &[0.0, 0.0], &[0.0, 0.0], &mut pd, &[], &opts, &mut |_| {}).unwrap();
//! let q = run.q.last().unwrap();
//! assert!((q[0] - 0.5).abs() < 1e-3 && (q[1] + 0.3).abs() < 1e-3);
//! ```

mod controller;
mod controller_spec;
mod effects;
mod integrate;
mod limit_events;
mod options;
mod profile;
mod record;
mod setting;
mod simulate;
mod trajectory;

pub use controller::{
    ComputedTorque, ConstantTorque, Controller, PdGravity, TorqueSeries, ZeroTorque,
    DEFAULT_NATURAL_FREQUENCY,
};
pub use controller_spec::ControllerSpec;
pub use effects::{EffectGains, JointEffects};
pub use integrate::{AccelFn, Integrator, Stepper};
pub use limit_events::{LimitEvent, LimitEventKind, LimitSide, LimitWatch};
pub use options::SimOptions;
pub(crate) use profile::TorqueStatistics;
pub use profile::{
    torque_profile, torque_profile_into, torque_profile_limited, ProfileSummary, TorqueProfile,
    Violation, ViolationSummary, MAX_PROFILE_SAMPLES,
};
pub use record::{
    sample_columns, CsvSampleWriter, JsonSampleWriter, Recording, Sample, SampleSink,
};
pub use simulate::{simulate, simulate_into, step_plan, Disturbance, RunSummary};
pub use trajectory::{Quintic, Trajectory, Trapezoid, Waypoints};
