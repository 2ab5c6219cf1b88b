//! Command-line arguments (clap derive).

use clap::{Args, Parser, Subcommand, ValueEnum};

/// Kinematics and dynamics of robot manipulators, in the screw-theory notation.
///
/// MODEL is a .urdf or .toml file, or builtin:<name> (builtin:planar2, builtin:pendulum, ...).
/// Joint-space vectors are comma-separated numbers in model joint order.
#[derive(Parser, Debug)]
#[command(name = "screwdyn", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Joints, bodies, frames and the kinematic tree of a model.
    Info(ModelArgs),
    /// Poses of all frames (or of --frame) at configuration --q.
    Fk(FkArgs),
    /// The 6×n Jacobian of --frame at --q (angular rows first).
    Jacobian(JacobianArgs),
    /// Per-call timing (median ns) of the core algorithms on random states.
    Bench(BenchArgs),
}

#[derive(Args, Debug)]
pub struct ModelArgs {
    /// A .urdf or .toml file, or builtin:<name>.
    pub model: String,
    /// Output format.
    #[arg(long, value_enum)]
    pub format: Option<Format>,
}

#[derive(Args, Debug)]
pub struct FkArgs {
    #[command(flatten)]
    pub model: ModelArgs,
    /// Joint positions, comma-separated (default: all zero).
    #[arg(long, allow_hyphen_values = true)]
    pub q: Option<String>,
    /// Only this frame.
    #[arg(long)]
    pub frame: Option<String>,
}

#[derive(Args, Debug)]
pub struct JacobianArgs {
    #[command(flatten)]
    pub model: ModelArgs,
    /// Joint positions, comma-separated (default: all zero).
    #[arg(long, allow_hyphen_values = true)]
    pub q: Option<String>,
    /// The frame whose Jacobian to compute (default: the last frame of the model).
    #[arg(long)]
    pub frame: Option<String>,
    /// Frame the twist is written in.
    #[arg(long, value_enum, default_value = "world")]
    pub reference: ReferenceArg,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Table,
    Json,
    Csv,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReferenceArg {
    /// Spatial twist in the base frame (the seeds' J^{0,0}).
    World,
    /// Body twist in the frame itself (J^{f,0}).
    Local,
    /// Frame-origin velocity with base-frame axes.
    WorldAligned,
}

/// `screwdyn bench MODEL`: per-call medians over batches of random states (DESIGN §5).
#[derive(Args, Debug)]
pub struct BenchArgs {
    /// A .urdf or .toml file, or builtin:<name>.
    pub model: String,
    /// Algorithms to time, comma-separated: fk, jacobians, rnea, crba, aba, gravity, nle,
    /// coriolis, minv, forward_crba.
    #[arg(long, default_value = "fk,jacobians,rnea,crba,aba")]
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
