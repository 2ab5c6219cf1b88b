//! `screwdyn`: the command-line program (docs/cli.md). A thin shell over the library: parse
//! arguments, load the model, call the library, format the result.
//!
//! On Linux with glibc the program starts at its own C `main` (`#![no_main]`) rather than
//! through the standard library's runtime, whose start-up reads `/proc/self/maps` to place a
//! guard for the main thread's stack (≈ 0.1 ms of a 2 ms process; BENCHMARKS.md, "The CLI's
//! start and finish"). What else that start-up does is done here: `SIGPIPE` ignored (a closed
//! pipe is an `EPIPE` error), closed standard descriptors reopened onto `/dev/null` (so an
//! output file never becomes fd 1), stdout flushed at the end. A stack overflow then ends the
//! process by `SIGSEGV` without the runtime's one-line report.
#![cfg_attr(all(target_os = "linux", target_env = "gnu"), no_main)]

mod args;
mod commands;
mod output;
mod plot;
mod write;

use clap::Parser;

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

impl CliError {
    /// Not a failure: the reader of stdout went away (`| head`); the command stops quietly
    /// with status 0.
    pub fn stop() -> Self {
        CliError {
            code: 0,
            message: String::new(),
        }
    }

    /// The same error with `suffix` appended to its message.
    pub fn with_suffix(mut self, suffix: &str) -> Self {
        self.message.push_str(suffix);
        self
    }

    /// An internal failure (exit status 1).
    pub fn internal(message: impl Into<String>) -> Self {
        CliError {
            code: 1,
            message: message.into(),
        }
    }
}

/// Help and version go to stdout with status 0; a usage error becomes one line on stderr with
/// status 2 (clap's usage block and tips are dropped).
fn clap_error(e: clap::Error) -> u8 {
    use clap::error::ErrorKind;
    if matches!(
        e.kind(),
        ErrorKind::DisplayHelp
            | ErrorKind::DisplayVersion
            | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
    ) {
        let _ = e.print();
        return if e.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand {
            2
        } else {
            0
        };
    }
    let text = e.render().to_string();
    let lines: Vec<&str> = text
        .lines()
        .map(str::trim)
        .take_while(|l| !l.starts_with("Usage:") && !l.starts_with("For more information"))
        .filter(|l| !l.is_empty())
        .collect();
    let parts: Vec<&str> = lines
        .iter()
        .copied()
        .filter(|l| !l.starts_with("tip:"))
        .collect();
    let line = parts.join(" ");
    let line = line.strip_prefix("error: ").unwrap_or(&line);
    // clap's suggestion ("tip: a similar subcommand exists: 'jacobian'") becomes "did you
    // mean"; its other tips (how to pass a value that starts with '-') are dropped.
    match lines.iter().find_map(|l| similar(l)) {
        Some(names) => eprintln!("screwdyn: {line}; did you mean {names}?"),
        None => eprintln!("screwdyn: {line}"),
    }
    2
}

/// The most similar name of clap's "similar … exist(s): 'a', 'b'" tip (clap lists them from
/// the least to the most similar).
fn similar(tip: &str) -> Option<String> {
    let rest = tip.strip_prefix("tip:")?.trim();
    if !rest.contains("similar") {
        return None;
    }
    let (_, names) = rest.split_once(": ")?;
    names.rsplit(", ").next().map(|n| n.trim().to_string())
}

impl From<screwdyn::Error> for CliError {
    fn from(e: screwdyn::Error) -> Self {
        // Every library error is caused by the input (model, state, options): exit status 2.
        CliError::input(e.to_string())
    }
}

/// A write past the file-size limit (`ulimit -f`) then fails with `EFBIG` instead of killing
/// the process with `SIGXFSZ`: the temporary file is removed and the error reported (status 2).
/// The standard library has no call to set a signal's disposition, hence `libc` (already a
/// dependency of the dependencies).
#[cfg(unix)]
fn ignore_file_size_signal() {
    // SAFETY: installs the disposition SIG_IGN (no handler code runs), at the start of `main`,
    // before any other thread exists.
    unsafe {
        libc::signal(libc::SIGXFSZ, libc::SIG_IGN);
    }
}

/// `SIGTERM` or `SIGINT` (Ctrl-C) ends the program after removing the temporary files of the
/// outputs it was writing (their targets stay as they were), with one line on stderr and the
/// status 128 + the signal's number, as a shell reports a signal.
#[cfg(unix)]
fn end_cleanly_on_signals() {
    use signal_hook::consts::{SIGINT, SIGTERM};
    let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGTERM, SIGINT]) else {
        return;
    };
    std::thread::spawn(move || {
        if let Some(signal) = signals.forever().next() {
            let removed = screwdyn::io::output::remove_pending();
            let name = if signal == SIGINT {
                "SIGINT"
            } else {
                "SIGTERM"
            };
            let files: Vec<String> = removed.iter().map(|p| p.display().to_string()).collect();
            if files.is_empty() {
                eprintln!("screwdyn: stopped by {name}");
            } else {
                eprintln!(
                    "screwdyn: stopped by {name}; removed the unfinished {}",
                    files.join(", ")
                );
            }
            std::process::exit(128 + signal);
        }
    });
}

/// The program: its exit status.
fn run() -> u8 {
    #[cfg(unix)]
    ignore_file_size_signal();
    #[cfg(unix)]
    end_cleanly_on_signals();
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
    let cli = match args::Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return clap_error(e),
    };
    match std::panic::catch_unwind(|| commands::run(cli)) {
        Ok(Ok(())) => 0,
        Ok(Err(e)) if e.code == 0 => 0,
        Ok(Err(e)) => {
            eprintln!("screwdyn: {}", e.message);
            e.code
        }
        Err(_) => 1,
    }
}

#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
fn main() -> std::process::ExitCode {
    std::process::ExitCode::from(run())
}

/// The C entry point (see the module documentation): the standard library's start-up without
/// its stack-guard lookup, then [`run`], then stdout flushed as the runtime would at exit.
/// `std::env::args` does not depend on the runtime here (glibc hands the arguments to the
/// standard library before `main`).
#[cfg(all(target_os = "linux", target_env = "gnu"))]
#[no_mangle]
pub extern "C" fn main(_argc: libc::c_int, _argv: *const *const libc::c_char) -> libc::c_int {
    // SAFETY: at the start of the process, before any other thread exists: SIG_IGN for
    // SIGPIPE, and /dev/null opened onto the lowest closed descriptor among 0, 1, 2.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_IGN);
        for fd in 0..3 {
            if libc::fcntl(fd, libc::F_GETFD) == -1 {
                libc::open(c"/dev/null".as_ptr(), libc::O_RDWR);
            }
        }
    }
    let code = run();
    let _ = std::io::Write::flush(&mut std::io::stdout());
    libc::c_int::from(code)
}
