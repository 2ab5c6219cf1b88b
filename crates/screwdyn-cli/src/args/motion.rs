//! The arguments of `simulate` and `torque-profile`: runs over time.

use super::ModelArgs;
use clap::{Args, ValueEnum};
use std::path::PathBuf;

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ControllerArg {
    /// No torque: the robot moves passively.
    Zero,
    /// Constant torque --tau.
    Constant,
    /// PD to --target with gravity compensation.
    Pd,
    /// Computed torque tracking a quintic from --q0 to --target over the duration.
    ComputedTorque,
    /// Torques from --torque-csv (columns t, tau.<joint>), linearly interpolated.
    Series,
}

#[derive(Args, Debug)]
pub struct SimulateArgs {
    #[command(flatten)]
    pub model: ModelArgs,
    /// Gravity x,y,z in the base frame (m/s²), overriding the model's.
    #[arg(long, allow_hyphen_values = true, value_name = "X,Y,Z")]
    pub gravity: Option<String>,
    /// Simulated time (s).
    #[arg(long, default_value_t = 2.0)]
    pub duration: f64,
    /// Time step (s); the output interval for dopri5.
    #[arg(long, default_value_t = 1e-3)]
    pub dt: f64,
    /// Integrator: euler (symplectic), rk4 or dopri5 (adaptive).
    #[arg(long, default_value = "rk4")]
    pub integrator: String,
    /// Forward-dynamics algorithm: aba, crba or walker-orin.
    #[arg(long, default_value = "aba")]
    pub method: String,
    /// Controller.
    #[arg(long, value_enum, default_value = "zero")]
    pub controller: ControllerArg,
    /// Constant torque for --controller constant.
    #[arg(long, allow_hyphen_values = true)]
    pub tau: Option<String>,
    /// Target position for pd and computed-torque (default: --q0).
    #[arg(long, allow_hyphen_values = true)]
    pub target: Option<String>,
    /// Proportional gains. Default: pd 100·M_ii(target) (N·m/rad), computed-torque 100 (1/s²).
    #[arg(long, allow_hyphen_values = true)]
    pub kp: Option<String>,
    /// Derivative gains. Default: pd 20·M_ii(target), computed-torque 20 (1/s); critically
    /// damped at 10 rad/s.
    #[arg(long, allow_hyphen_values = true)]
    pub kd: Option<String>,
    /// Torque time series for --controller series: CSV with columns t, tau.<joint>.
    #[arg(long, value_name = "FILE")]
    pub torque_csv: Option<PathBuf>,
    /// Viscous joint damping b per joint (N·m·s/rad), replacing the model's.
    #[arg(long, allow_hyphen_values = true)]
    pub damping: Option<String>,
    /// No joint effects (no effort saturation, damping, friction or position-limit stops).
    #[arg(long)]
    pub no_effects: bool,
    /// Record this frame's position (columns pose.<frame>.x|y|z in --output). Repeatable.
    #[arg(long = "frame", value_name = "FRAME")]
    pub frames: Vec<String>,
    /// Time constant T of the position-limit stops (s): a joint with inertia I meets a
    /// spring k = I/T² and damper d = 2ζI/T past its limit (never below 4 dt).
    #[arg(
        long,
        default_value_t = 0.01,
        value_name = "T",
        allow_hyphen_values = true
    )]
    pub limit_time_constant: f64,
    /// Damping ratio ζ of the position-limit stops (1: no bounce; 0: elastic).
    #[arg(
        long,
        default_value_t = 1.0,
        value_name = "ZETA",
        allow_hyphen_values = true
    )]
    pub limit_damping_ratio: f64,
    /// A wrench on a body for a time window, moment first, body frame unless @world:
    /// BODY:mx,my,mz,fx,fy,fz[@world]@T0-T1. Repeatable.
    #[arg(long, allow_hyphen_values = true, value_name = "BODY:W[@world]@T0-T1")]
    pub disturbance: Vec<String>,
    /// Initial positions (default: all zero, or the start of --target-trajectory).
    #[arg(long, allow_hyphen_values = true)]
    pub q0: Option<String>,
    /// Initial velocities (default: all zero, or the start of --target-trajectory).
    #[arg(long, allow_hyphen_values = true)]
    pub v0: Option<String>,
    /// With --controller computed-torque: track the motion of this run file (columns t,
    /// q.<joint>, v.<joint>, a.<joint>; other columns ignored), e.g. one written by
    /// `torque-profile --output` for a time-optimal, jerk-limited, linear or circular motion,
    /// instead of a quintic to --target.
    #[arg(long, value_name = "RUN.CSV")]
    pub target_trajectory: Option<PathBuf>,
    /// Record every k-th step.
    #[arg(long, default_value_t = 1)]
    pub record_every: usize,
    /// Write the run to run.csv or run.json (columns t, q.<joint>, v.., a.., tau..,
    /// kinetic_energy, potential_energy, total_energy). Without it the run goes to stdout
    /// (CSV or JSON) or a summary is printed (table).
    #[arg(long, value_name = "RUN.CSV|RUN.JSON")]
    pub output: Option<PathBuf>,
    /// Plot positions, velocities, torques and energy to a .png or .svg file.
    #[arg(long, value_name = "RUN.PNG|RUN.SVG")]
    pub plot: Option<PathBuf>,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum TrajectoryArg {
    /// Trapezoidal velocity: accelerate at --amax, cruise at up to --vmax, decelerate.
    Trapezoid,
    /// Rest-to-rest quintic polynomial over --duration.
    Quintic,
    /// The fastest timing of the cubic spline through --waypoints within the velocity
    /// (--vmax, default the model's), acceleration (--amax, default none) and effort limits.
    TimeOptimal,
    /// The fastest jerk-limited motion from --q0 to --qf within --vmax, --amax and --jmax, all
    /// joints finishing together.
    JerkLimited,
    /// --frame in a straight line from its pose at --q0 to --target (orientation by slerp), as
    /// fast as the velocity (--vmax), acceleration (--amax), effort and tool speed (--speed)
    /// limits allow.
    Linear,
    /// As linear, on the circular arc through --via.
    Circular,
}

impl TrajectoryArg {
    /// The value as written on the command line.
    pub fn name(self) -> &'static str {
        match self {
            TrajectoryArg::Trapezoid => "trapezoid",
            TrajectoryArg::Quintic => "quintic",
            TrajectoryArg::TimeOptimal => "time-optimal",
            TrajectoryArg::JerkLimited => "jerk-limited",
            TrajectoryArg::Linear => "linear",
            TrajectoryArg::Circular => "circular",
        }
    }
}

#[derive(Args, Debug)]
pub struct TorqueProfileArgs {
    #[command(flatten)]
    pub model: ModelArgs,
    /// Gravity x,y,z in the base frame (m/s²), overriding the model's.
    #[arg(long, allow_hyphen_values = true, value_name = "X,Y,Z")]
    pub gravity: Option<String>,
    /// The motion.
    #[arg(long, value_enum, default_value = "trapezoid")]
    pub trajectory: TrajectoryArg,
    /// Start position (default: all zero; required for linear and circular).
    #[arg(long, allow_hyphen_values = true)]
    pub q0: Option<String>,
    /// End position (trapezoid, quintic, jerk-limited).
    #[arg(long, allow_hyphen_values = true)]
    pub qf: Option<String>,
    /// Speed limit (rad/s): one value for all joints or one per joint. Default: 1 for the
    /// trapezoid, the model's velocity limits for the others.
    #[arg(long, allow_hyphen_values = true)]
    pub vmax: Option<String>,
    /// Acceleration limit (rad/s²): one value for all joints or one per joint. Default: 2 for
    /// the trapezoid, none for time-optimal, linear and circular; required for jerk-limited.
    #[arg(long, allow_hyphen_values = true)]
    pub amax: Option<String>,
    /// Jerk limit (rad/s³) of jerk-limited: one value for all joints or one per joint.
    #[arg(long, allow_hyphen_values = true)]
    pub jmax: Option<String>,
    /// Time-optimal: the waypoints, a CSV file with columns q.<joint> for every joint and an
    /// optional s (the path parameter, increasing; default: the chord length).
    #[arg(long, value_name = "PATH.CSV")]
    pub waypoints: Option<PathBuf>,
    /// Time-optimal, linear and circular: a fixed grid of this many intervals in s (default: refined until the
    /// duration converges).
    #[arg(long)]
    pub grid: Option<usize>,
    /// Linear and circular: the frame to move.
    #[arg(long)]
    pub frame: Option<String>,
    /// Linear and circular: the target pose in the world frame, position (m) and unit
    /// quaternion, scalar first.
    #[arg(long, allow_hyphen_values = true, value_name = "X,Y,Z,QW,QX,QY,QZ")]
    pub target: Option<String>,
    /// Circular: a point (m, world frame) the arc passes through.
    #[arg(long, allow_hyphen_values = true, value_name = "X,Y,Z")]
    pub via: Option<String>,
    /// Linear and circular: the tool speed limit (m/s) on the frame's origin (default: none).
    #[arg(long)]
    pub speed: Option<f64>,
    /// Let each trapezoid joint finish on its own (default: all joints end together).
    #[arg(long)]
    pub unsynchronised: bool,
    /// Quintic duration (s).
    #[arg(long, default_value_t = 2.0)]
    pub duration: f64,
    /// Sampling step (s).
    #[arg(long, default_value_t = 1e-3)]
    pub dt: f64,
    /// Refuse profiles with more samples than this. Without --plot, samples are streamed to
    /// --output (or to stdout with --format csv) as they are computed, in constant memory;
    /// with --plot (or for a report alone) they are held, and a profile the machine cannot hold
    /// is refused up front with the memory it would need.
    #[arg(long, default_value_t = screwdyn::sim::MAX_PROFILE_SAMPLES)]
    pub max_samples: usize,
    /// Write the samples (t, q, v, a, tau, energies) to a .csv or .json file.
    #[arg(long, value_name = "FILE")]
    pub output: Option<PathBuf>,
    /// Plot the required torques with the effort limits to a .png or .svg file.
    #[arg(long, value_name = "FILE")]
    pub plot: Option<PathBuf>,
}
