//! `screwdyn`: the command-line program (DESIGN §5). A thin shell over the library: parse
//! arguments, load the model, call the library, format the result.

mod args;
mod commands;
mod output;
mod plot;

use clap::Parser;
use std::process::ExitCode;

/// A failure with its exit status: 2 for bad input, 1 for an internal failure.
#[derive(Debug)]
pub struct CliError {
    pub code: u8,
    pub message: String,
}

impl CliError {
    /// Bad input (exit status 2).
    pub fn input(message: impl Into<String>) -> Self {
        CliError {
            code: 2,
            message: message.into(),
        }
    }
}

impl From<screwdyn::Error> for CliError {
    fn from(e: screwdyn::Error) -> Self {
        let code = match e {
            screwdyn::Error::Numerical(_) => 2,
            _ => 2,
        };
        CliError {
            code,
            message: e.to_string(),
        }
    }
}

fn main() -> ExitCode {
    // Never show a backtrace: an unexpected panic is reported as one line, exit status 1.
    std::panic::set_hook(Box::new(|info| {
        let msg = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown".into());
        eprintln!("screwdyn: internal error: {msg}");
    }));
    let cli = args::Cli::parse();
    match std::panic::catch_unwind(|| commands::run(cli)) {
        Ok(Ok(())) => ExitCode::SUCCESS,
        Ok(Err(e)) => {
            eprintln!("screwdyn: {}", e.message);
            ExitCode::from(e.code)
        }
        Err(_) => ExitCode::from(1),
    }
}
