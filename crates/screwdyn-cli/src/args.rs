//! Command-line arguments (clap derive).

use clap::{Args, Parser, Subcommand, ValueEnum};
use std::path::PathBuf;

mod motion;
pub use motion::{ControllerArg, SimulateArgs, TorqueProfileArgs, TrajectoryArg};

/// Kinematics and dynamics of robot manipulators, in the screw-theory notation.
///
/// MODEL is a .urdf, .xml (MuJoCo's MJCF) or .toml file, or builtin:<name> (builtin:planar2,
/// builtin:pendulum, builtin:ur5, builtin:panda, builtin:branched). Joint-space vectors are
/// comma-separated numbers in model joint order (`--q 0.1,0.2`), or for `--q` a model's named
/// configuration (`--q key:home`, an MJCF <key>); an absent vector is all zeros. Numeric commands take one
/// state from flags or many from `--input states.csv` (columns q.<joint>, v.<joint>, a.<joint>,
/// tau.<joint>; a missing column is zero). Output: `--format table|json|csv` (table on a
/// terminal, JSON otherwise). Bad input exits with status 2 and one sentence on stderr.
#[derive(Parser, Debug)]
// `about` is the first paragraph (with its full stop, which clap would drop) and `long_about`
// the whole comment, so that `screwdyn` alone (the short help, on stderr) starts with the same
// line as `--help`.
#[command(
    name = "screwdyn",
    version,
    about = "Kinematics and dynamics of robot manipulators, in the screw-theory notation."
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

// `defer`: a subcommand's arguments are built only when that subcommand is chosen, not the
// argument lists of every subcommand on each start (BENCHMARKS.md, "The CLI's fixed costs").
// The deferred arguments are added after the variant's doc comment, so the argument structs
// below carry plain comments: a doc comment there would replace the subcommand's help line.
#[derive(Subcommand, Debug)]
#[command(defer = true)]
pub enum Command {
    /// Joints (kind, screw axis, limits), bodies (mass, CoM), frames and the kinematic tree.
    Info(ModelArgs),
    /// Validates a model and lists its physical-consistency problems (exit 2 if any).
    Check(CheckArgs),
    /// Poses H_f^0 of all frames (or of --frame) at configuration --q.
    Fk(FkArgs),
    /// The 6×n Jacobian of --frame at --q (angular rows first).
    Jacobian(JacobianArgs),
    /// Inverse kinematics: joint positions that put --frame at --target (or --position), or
    /// at every target of --input; with --all every closed-form solution.
    Ik(IkArgs),
    /// Inverse dynamics τ = M(q) q̈ + C(q, q̇) q̇ + g(q) − Σ Jᵀ W_ext by RNEA.
    #[command(visible_alias = "rnea")]
    InverseDynamics(InverseDynamicsArgs),
    /// The joint-space mass matrix M(q) by CRBA.
    #[command(visible_alias = "crba")]
    MassMatrix(QArgs),
    /// The Coriolis matrix C(q, q̇) (Christoffel-consistent: Ṁ − 2C skew-symmetric).
    Coriolis(QvArgs),
    /// The gravity torques g(q).
    Gravity(QArgs),
    /// The nonlinear effects C(q, q̇) q̇ + g(q).
    NonlinearEffects(QvArgs),
    /// Kinetic, potential and total energy and the centre of mass.
    Energy(QvArgs),
    /// Forward dynamics q̈ = M⁻¹ (τ − C q̇ − g + Σ Jᵀ W_ext).
    #[command(visible_alias = "aba")]
    ForwardDynamics(ForwardDynamicsArgs),
    /// The stacked closed form: A, L, S, 𝔍, J and M, C, g (small robots).
    ClosedForm(ClosedFormArgs),
    /// The Lagrangian coefficients D_ij, D_ijk, D_i and the effective inertias.
    Lagrange(LagrangeArgs),
    /// The RNEA iterations step by step in the notation of docs/notation.md (H, V, V̇ out; W, τ back).
    Explain(ExplainArgs),
    /// Simulates the robot under a controller; writes the run (CSV/JSON) and plots it.
    Simulate(Box<SimulateArgs>),
    /// Torques needed along a trapezoid or quintic motion: peak, RMS, effort-limit violations.
    TorqueProfile(TorqueProfileArgs),
    /// Writes the model in another format (URDF).
    Export(ExportArgs),
    /// Per-call timing (median ns) of the core algorithms on random states.
    Bench(BenchArgs),
    /// Symbolic equations of motion (M, C, g, τ, FK, Jacobian, energies, regressor) as text,
    /// LaTeX, JSON or code (C, Python, Rust, MATLAB).
    Symbolic(Box<SymbolicArgs>),
    /// Inertia tensor of a shape (box, cylinder, sphere, rod, point) about a point, in turned
    /// axes (the parallel-axis theorem).
    Inertia(InertiaArgs),
    /// Analytical derivatives of inverse and forward dynamics at (q, q̇, q̈): ∂τ/∂q, ∂τ/∂q̇,
    /// ∂q̈/∂q, ∂q̈/∂q̇ and ∂q̈/∂τ = M⁻¹ (forward dynamics at τ = ID(q, q̇, q̈)).
    Derivatives(DerivativesArgs),
    /// The joint-torque regressor Y(q, q̇, q̈) with τ = Y π, or with --base the base
    /// (identifiable) parameters and their expressions.
    Regressor(RegressorArgs),
    /// Least-squares identification of the base inertial parameters from a log (t, q.*, v.*,
    /// a.*, tau.*), or with --excite the writing of an exciting trajectory log.
    Identify(IdentifyArgs),
    /// Writes one self-contained HTML page showing the robot in 3-D (and animating --run).
    View(ViewArgs),
}

#[derive(Args, Debug)]
pub struct DerivativesArgs {
    #[command(flatten)]
    pub common: Common,
    /// Joint positions q, comma-separated, or key:NAME (default: all zero).
    #[arg(long, allow_hyphen_values = true)]
    pub q: Option<String>,
    /// Joint velocities q̇ (default: all zero).
    #[arg(long, allow_hyphen_values = true)]
    pub v: Option<String>,
    /// Joint accelerations q̈ (default: all zero).
    #[arg(long, allow_hyphen_values = true)]
    pub a: Option<String>,
    #[command(flatten)]
    pub wrenches: WrenchArgs,
}

#[derive(Args, Debug)]
pub struct RegressorArgs {
    #[command(flatten)]
    pub common: Common,
    /// Joint positions q, comma-separated, or key:NAME (default: all zero).
    #[arg(long, allow_hyphen_values = true)]
    pub q: Option<String>,
    /// Joint velocities q̇ (default: all zero).
    #[arg(long, allow_hyphen_values = true)]
    pub v: Option<String>,
    /// Joint accelerations q̈ (default: all zero).
    #[arg(long, allow_hyphen_values = true)]
    pub a: Option<String>,
    /// Append viscous and Coulomb friction columns (fv_<joint>, fc_<joint>).
    #[arg(long)]
    pub friction: bool,
    /// Print the base parameters (numerical rank, expressions, model values) instead of Y.
    #[arg(long)]
    pub base: bool,
    /// Random states used to find the base parameters.
    #[arg(long, default_value_t = screwdyn::identification::DEFAULT_STATES)]
    pub states: usize,
}

#[derive(Args, Debug)]
pub struct IdentifyArgs {
    #[command(flatten)]
    pub model: ModelArgs,
    /// Gravity x,y,z in the base frame (m/s²), overriding the model's.
    #[arg(long, allow_hyphen_values = true, value_name = "X,Y,Z")]
    pub gravity: Option<String>,
    /// The log: CSV with columns t, q.<joint>, v.<joint>, tau.<joint> and optionally
    /// a.<joint> (without them, q̈ is the slope of a Savitzky–Golay quadratic fit of q̇).
    #[arg(long, value_name = "LOG.CSV")]
    pub input: Option<std::path::PathBuf>,
    /// Also estimate viscous and Coulomb friction per joint.
    #[arg(long)]
    pub friction: bool,
    /// Constrain the estimate to physically consistent bodies (log-Cholesky parametrisation).
    #[arg(long)]
    pub physical: bool,
    /// Half width (samples) of the Savitzky–Golay window used when a.* columns are absent.
    #[arg(long, default_value_t = 5)]
    pub window: usize,
    /// Plot the torque residual per joint over time (.png or .svg).
    #[arg(long, value_name = "FILE")]
    pub plot: Option<std::path::PathBuf>,
    /// Write an exciting Fourier-series trajectory log to --output instead of identifying.
    #[arg(long)]
    pub excite: bool,
    /// With --excite: the log to write (.csv).
    #[arg(long, value_name = "LOG.CSV")]
    pub output: Option<std::path::PathBuf>,
    /// With --excite: duration (s).
    #[arg(long, default_value_t = 20.0)]
    pub duration: f64,
    /// With --excite: samples per second.
    #[arg(long, default_value_t = 100.0)]
    pub rate: f64,
    /// With --excite: base frequency of the Fourier series (Hz).
    #[arg(long, default_value_t = 0.1)]
    pub frequency: f64,
    /// With --excite: harmonics per joint.
    #[arg(long, default_value_t = 5)]
    pub harmonics: usize,
    /// With --excite: standard deviation of the Gaussian noise added to the torques (N·m, N).
    #[arg(long, default_value_t = 0.0)]
    pub noise: f64,
    /// With --excite: random seed of the coefficients and the noise.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
}

#[derive(Args, Debug)]
pub struct ModelArgs {
    /// A .urdf or .toml file, or builtin:<name>.
    pub model: String,
    /// Output format (default: table on a terminal, JSON otherwise).
    #[arg(long, value_enum)]
    pub format: Option<Format>,
    /// Treat physical-consistency problems of the model (listed as warnings on stderr
    /// otherwise) as errors.
    #[arg(long)]
    pub strict: bool,
    /// Accepted for compatibility: inconsistent inertias are warnings now, not errors.
    #[arg(long, hide = true)]
    pub allow_nonphysical: bool,
}

#[derive(Args, Debug)]
pub struct CheckArgs {
    /// A .urdf, .xml (MJCF) or .toml file, or builtin:<name>.
    pub model: String,
    /// Output format (default: table on a terminal, JSON otherwise).
    #[arg(long, value_enum)]
    pub format: Option<Format>,
}

// Model, gravity override and batch input shared by the numeric commands.
#[derive(Args, Debug)]
pub struct Common {
    #[command(flatten)]
    pub model: ModelArgs,
    /// Gravity x,y,z in the base frame (m/s²), overriding the model's.
    #[arg(long, allow_hyphen_values = true, value_name = "X,Y,Z")]
    pub gravity: Option<String>,
    /// Many states from a CSV file: columns q.<joint>, v.<joint>, a.<joint>, tau.<joint>
    /// (a missing column is zero); one output row / JSON object per input row. `-` reads
    /// standard input.
    #[arg(long, value_name = "STATES.CSV")]
    pub input: Option<PathBuf>,
}

#[derive(Args, Debug)]
pub struct QArgs {
    #[command(flatten)]
    pub common: Common,
    /// Joint positions q, comma-separated, or key:NAME (default: all zero).
    #[arg(long, allow_hyphen_values = true)]
    pub q: Option<String>,
}

#[derive(Args, Debug)]
pub struct QvArgs {
    #[command(flatten)]
    pub common: Common,
    /// Joint positions q, comma-separated, or key:NAME (default: all zero).
    #[arg(long, allow_hyphen_values = true)]
    pub q: Option<String>,
    /// Joint velocities q̇, comma-separated (default: all zero).
    #[arg(long, allow_hyphen_values = true)]
    pub v: Option<String>,
}

#[derive(Args, Debug)]
pub struct FkArgs {
    #[command(flatten)]
    pub common: Common,
    /// Joint positions q, comma-separated, or key:NAME (default: all zero).
    #[arg(long, allow_hyphen_values = true)]
    pub q: Option<String>,
    /// Only this frame.
    #[arg(long)]
    pub frame: Option<String>,
}

#[derive(Args, Debug)]
pub struct JacobianArgs {
    #[command(flatten)]
    pub common: Common,
    /// Joint positions q, comma-separated, or key:NAME (default: all zero).
    #[arg(long, allow_hyphen_values = true)]
    pub q: Option<String>,
    /// The frame whose Jacobian to compute (default: the last frame of the model).
    #[arg(long)]
    pub frame: Option<String>,
    /// Frame the twist is written in.
    #[arg(long, value_enum, default_value = "world")]
    pub reference: ReferenceArg,
}

// `screwdyn ik MODEL --frame NAME --target x,y,z,qw,qx,qy,qz` (docs/cli.md, docs/ik.md).
#[derive(Args, Debug)]
pub struct IkArgs {
    #[command(flatten)]
    pub model: ModelArgs,
    /// The frame to place.
    #[arg(long)]
    pub frame: String,
    /// The target pose in the world frame: position (m) and unit quaternion, scalar first.
    #[arg(long, allow_hyphen_values = true, value_name = "X,Y,Z,QW,QX,QY,QZ")]
    pub target: Option<String>,
    /// A target position only (m, world frame); the orientation is free.
    #[arg(long, allow_hyphen_values = true, value_name = "X,Y,Z")]
    pub position: Option<String>,
    /// Every closed-form solution within the joint limits (6R arms with a spherical wrist or
    /// three parallel axes).
    #[arg(long)]
    pub all: bool,
    /// The start (default: each joint at 0, or at the nearer limit when 0 is outside them);
    /// with --input, the start of rows without q0.<joint> columns.
    #[arg(long, allow_hyphen_values = true)]
    pub q0: Option<String>,
    /// Seed of the random restarts (the same seed gives the same answer).
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Largest accepted position error (m; default 1e-6).
    #[arg(long, value_name = "M")]
    pub position_tolerance: Option<f64>,
    /// Largest accepted orientation error (rad; default 1e-6).
    #[arg(long, value_name = "RAD")]
    pub orientation_tolerance: Option<f64>,
    /// Random restarts after the first attempt (default 50).
    #[arg(long, value_name = "N")]
    pub max_restarts: Option<usize>,
    /// Many targets from a CSV file: columns x, y, z, qw, qx, qy, qz (world frame, quaternion
    /// scalar first; without the quaternion columns the targets are positions) and optional
    /// q0.<joint>; one output row per target, streamed. `-` reads standard input.
    #[arg(long, value_name = "TARGETS.CSV")]
    pub input: Option<PathBuf>,
    /// With --input: write the rows to this .csv or .json file instead of stdout.
    #[arg(long, value_name = "FILE")]
    pub output: Option<PathBuf>,
    /// With --input: threads solving the rows (default: one per core). The answers do not
    /// depend on it.
    #[arg(long)]
    pub threads: Option<usize>,
}

// External wrenches on bodies and at frames.
#[derive(Args, Debug)]
pub struct WrenchArgs {
    /// A wrench of the environment on a link (one attached by a fixed joint too), moment first,
    /// in the link's frame unless @world: LINK:mx,my,mz,fx,fy,fz[@world]. Repeatable.
    #[arg(long, allow_hyphen_values = true, value_name = "LINK:W[@world]")]
    pub wrench: Vec<String>,
    /// A wrench that a frame applies to the environment, in that frame (adds J_eᵀ W):
    /// FRAME:mx,my,mz,fx,fy,fz. Repeatable.
    #[arg(long, allow_hyphen_values = true, value_name = "FRAME:W")]
    pub tip_wrench: Vec<String>,
}

#[derive(Args, Debug)]
pub struct InverseDynamicsArgs {
    #[command(flatten)]
    pub common: Common,
    /// Joint positions q, comma-separated, or key:NAME (default: all zero).
    #[arg(long, allow_hyphen_values = true)]
    pub q: Option<String>,
    /// Joint velocities q̇ (default: all zero).
    #[arg(long, allow_hyphen_values = true)]
    pub v: Option<String>,
    /// Joint accelerations q̈ (default: all zero).
    #[arg(long, allow_hyphen_values = true)]
    pub a: Option<String>,
    #[command(flatten)]
    pub wrenches: WrenchArgs,
}

#[derive(Args, Debug)]
pub struct ForwardDynamicsArgs {
    #[command(flatten)]
    pub common: Common,
    /// Joint positions q, comma-separated, or key:NAME (default: all zero).
    #[arg(long, allow_hyphen_values = true)]
    pub q: Option<String>,
    /// Joint velocities q̇ (default: all zero).
    #[arg(long, allow_hyphen_values = true)]
    pub v: Option<String>,
    /// Joint torques τ (default: all zero).
    #[arg(long, allow_hyphen_values = true)]
    pub tau: Option<String>,
    /// Algorithm: aba, crba or walker-orin.
    #[arg(long, default_value = "aba")]
    pub method: String,
    #[command(flatten)]
    pub wrenches: WrenchArgs,
}

#[derive(Args, Debug)]
pub struct ExplainArgs {
    #[command(flatten)]
    pub common: Common,
    /// Joint positions θ, comma-separated (default: all zero).
    #[arg(long, allow_hyphen_values = true)]
    pub q: Option<String>,
    /// Joint velocities θ̇ (default: all zero).
    #[arg(long, allow_hyphen_values = true)]
    pub v: Option<String>,
    /// Joint accelerations θ̈ (default: all zero).
    #[arg(long, allow_hyphen_values = true)]
    pub a: Option<String>,
    #[command(flatten)]
    pub wrenches: WrenchArgs,
    /// lie-group (the twist/wrench trace), or the classic vector Newton–Euler table per
    /// link: craig (Craig, *Introduction to Robotics*) or luh-walker-paul.
    #[arg(long, value_enum, default_value = "lie-group")]
    pub style: ExplainStyle,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExplainStyle {
    /// The Lie-group RNEA: H, V, V̇ out; W, τ back.
    LieGroup,
    /// Craig's iterative Newton–Euler (*Introduction to Robotics*): ω, ω̇, v̇, v̇_C, F, N out; f, n, τ in.
    Craig,
    /// Luh, Walker & Paul's recursive algorithm, same quantities.
    LuhWalkerPaul,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExportFormat {
    Urdf,
    /// MuJoCo's XML format.
    Mjcf,
}

#[derive(Args, Debug)]
pub struct ExportArgs {
    /// A .urdf or .toml file, or builtin:<name>.
    pub model: String,
    /// The format to write: urdf or mjcf (MuJoCo).
    #[arg(long, value_enum, alias = "format")]
    pub to: ExportFormat,
    /// Write to this file instead of stdout.
    #[arg(long)]
    pub output: Option<PathBuf>,
    /// Treat physical-consistency problems of the model (listed as warnings on stderr
    /// otherwise) as errors.
    #[arg(long)]
    pub strict: bool,
    /// Accepted for compatibility: inconsistent inertias are warnings now, not errors.
    #[arg(long, hide = true)]
    pub allow_nonphysical: bool,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Table,
    Json,
    Csv,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReferenceArg {
    /// Spatial twist in the base frame (the J^{0,0}).
    World,
    /// Body twist in the frame itself (J^{f,0}).
    Local,
    /// Frame-origin velocity with base-frame axes.
    WorldAligned,
}

// `screwdyn bench MODEL`: per-call medians over batches of random states.
#[derive(Args, Debug)]
pub struct BenchArgs {
    /// A .urdf or .toml file, or builtin:<name>.
    pub model: String,
    /// Algorithms to time, comma-separated: fk, jacobians, rnea, crba, aba, gravity, nle,
    /// coriolis, minv, forward_crba, rnea_derivatives, aba_derivatives.
    #[arg(
        long,
        default_value = "fk,jacobians,rnea,crba,aba,rnea_derivatives,aba_derivatives"
    )]
    pub algorithms: String,
    /// Number of timed batches (the median is reported).
    #[arg(long, default_value_t = 21)]
    pub batches: usize,
    /// Calls per batch (cycling through 1000 random states).
    #[arg(long, default_value_t = 20000)]
    pub calls: usize,
    /// Output format.
    #[arg(long, value_enum)]
    pub format: Option<Format>,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum SymbolicFormat {
    /// Unicode text as written by hand (θ, θ̇, c₁₂ with a legend).
    Text,
    /// LaTeX (an aligned block).
    Latex,
    /// A Python function (keyword arguments for the symbols; returns nested lists).
    Python,
    /// A C function writing a row-major `double *out`.
    C,
    /// A Rust function returning a nested array.
    Rust,
    /// A MATLAB/Octave function.
    Matlab,
    /// JSON: SymPy-parsable expressions (q1, qd1, qdd1) and the symbols' values.
    Json,
}

// `screwdyn symbolic MODEL --quantity …` (issue 14).
#[derive(Args, Debug)]
pub struct SymbolicArgs {
    /// A .urdf or .toml file, or builtin:<name>.
    pub model: String,
    /// mass-matrix, coriolis, gravity, torque, fk, jacobian, energy or regressor.
    #[arg(long, default_value = "mass-matrix")]
    pub quantity: String,
    /// Parameters kept as symbols: all, groups (mass, com, inertia, gravity, lengths, armature)
    /// or names (m_link2, a_2, Ixx_link1, g, … — planar2: m1, m2, L1, L2, g), comma-separated.
    /// Groups take the non-zero parameters only. Default: none (all numeric).
    #[arg(long, default_value = "")]
    pub symbols: String,
    /// The frame of fk and jacobian (default: the last body's frame).
    #[arg(long)]
    pub frame: Option<String>,
    /// The Jacobian's reference.
    #[arg(long, value_enum, default_value = "local")]
    pub reference: ReferenceArg,
    /// Which C: closed-form (the stacked closed form's own factorisation) or christoffel.
    #[arg(long, default_value = "closed-form")]
    pub coriolis_form: String,
    /// Text/LaTeX grouping: inertial (m2 (L1² + …)), config ((m1 + m2) L1² + …) or none.
    #[arg(long, default_value = "inertial")]
    pub collect: String,
    /// Output format.
    #[arg(long, value_enum, default_value = "text")]
    pub format: SymbolicFormat,
    /// Write cos(θ1 + θ2) instead of c₁₂.
    #[arg(long)]
    pub no_abbrev: bool,
    /// The largest number of terms one expanded expression may have (text, LaTeX, JSON).
    #[arg(long, default_value_t = screwdyn::symbolic::DEFAULT_MAX_TERMS)]
    pub max_terms: usize,
    /// The largest number of operations generated code may have (c, rust, python, matlab).
    #[arg(long, default_value_t = screwdyn::symbolic::DEFAULT_MAX_OPS)]
    pub max_ops: usize,
    /// Write to this file instead of stdout.
    #[arg(long)]
    pub output: Option<PathBuf>,
    /// Accept inertias that are not physically consistent and massless leaf bodies.
    #[arg(long)]
    pub allow_nonphysical: bool,
}

// `screwdyn inertia SHAPE --mass M --size … [--about x,y,z] [--rotate r,p,y]`.
#[derive(Args, Debug)]
pub struct InertiaArgs {
    /// box, cylinder, sphere, rod or point.
    pub shape: String,
    /// Mass (kg).
    #[arg(long, allow_hyphen_values = true)]
    pub mass: f64,
    /// Sizes: box w,l,h (along x, y, z); cylinder r,h (axis z); sphere r; rod length (along z);
    /// point none.
    #[arg(long, allow_hyphen_values = true)]
    pub size: Option<String>,
    /// The point to take the inertia about, in the shape's frame (origin at the centre of mass),
    /// e.g. a box's corner -w/2,-l/2,-h/2 (default: the centre of mass).
    #[arg(long, allow_hyphen_values = true, value_name = "X,Y,Z")]
    pub about: Option<String>,
    /// Turns the output axes by roll,pitch,yaw (rad, URDF rpy) relative to the shape's:
    /// I = Rᵀ I_shape R.
    #[arg(long, allow_hyphen_values = true, value_name = "R,P,Y")]
    pub rotate: Option<String>,
    /// Output format (default: table on a terminal, JSON otherwise).
    #[arg(long, value_enum)]
    pub format: Option<Format>,
}

// `closed-form`: `--q`, `--v` and the acceleration `--a` for the stacked V̇, W and τ.
#[derive(Args, Debug)]
pub struct ClosedFormArgs {
    #[command(flatten)]
    pub qv: QvArgs,
    /// Joint accelerations θ̈ for V̇, W and τ = Sᵀ W (default: all zero).
    #[arg(long, allow_hyphen_values = true)]
    pub a: Option<String>,
}

// `lagrange`: numeric `D_ij`, `D_ijk`, `D_i` at `--q`, or with `--steps` the symbolic
// steps.
#[derive(Args, Debug)]
pub struct LagrangeArgs {
    #[command(flatten)]
    pub qa: QArgs,
    /// Print the symbolic steps ∂L/∂θ̇, d/dt(∂L/∂θ̇), ∂L/∂θ and τ instead of numbers.
    #[arg(long)]
    pub steps: bool,
    /// With --steps: the parameters kept as symbols (as in `symbolic --symbols`).
    #[arg(long, default_value = "all")]
    pub symbols: String,
    /// With --steps: cos(θ1 + θ2) instead of c₁₂.
    #[arg(long)]
    pub no_abbrev: bool,
    /// With --steps: the largest number of terms of one expression.
    #[arg(long, default_value_t = screwdyn::symbolic::DEFAULT_MAX_TERMS)]
    pub max_terms: usize,
}
// `screwdyn view MODEL`: the robot in 3-D in one self-contained HTML page (docs/view.md).
#[derive(Args, Debug)]
pub struct ViewArgs {
    /// A .urdf, .xml (MJCF) or .toml file, or builtin:<name>.
    pub model: String,
    /// The configuration shown when there is no --run (default: all zero).
    #[arg(long, allow_hyphen_values = true)]
    pub q: Option<String>,
    /// A run to animate: the .csv or .json written by `simulate --output` or
    /// `torque-profile --output`.
    #[arg(long, value_name = "FILE")]
    pub run: Option<PathBuf>,
    /// The page to write (default: the model's file name with .html, in the current folder;
    /// `planar2.html` for builtin:planar2).
    #[arg(long, value_name = "FILE")]
    pub output: Option<PathBuf>,
    /// A folder searched for `package://` mesh paths (repeatable; before ROS_PACKAGE_PATH).
    #[arg(long = "package-path", value_name = "DIR")]
    pub package_path: Vec<PathBuf>,
    /// Cap on the triangles embedded (larger meshes are simplified to fit).
    #[arg(long, default_value_t = screwdyn_view::DEFAULT_MAX_TRIANGLES)]
    pub max_triangles: usize,
    /// Cap on the run samples embedded (longer runs are strided to fit).
    #[arg(long, default_value_t = screwdyn_view::DEFAULT_MAX_SAMPLES)]
    pub max_samples: usize,
    /// Treat physical-consistency problems of the model (listed as warnings on stderr
    /// otherwise) as errors.
    #[arg(long)]
    pub strict: bool,
    /// Accepted for compatibility: inconsistent inertias are warnings now, not errors.
    #[arg(long, hide = true)]
    pub allow_nonphysical: bool,
}
