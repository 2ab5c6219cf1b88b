//! `symbolic`: the equations of motion as text, LaTeX, JSON or code (issue 14). Parses, calls
//! `screwdyn::symbolic` and prints.

use super::inputs::load;
use crate::args::{ModelArgs, ReferenceArg, SymbolicArgs, SymbolicFormat};
use crate::output::write_stdout;
use crate::CliError;
use screwdyn::kinematics::Reference;
use screwdyn::symbolic::{derive, generate, Collect, CoriolisForm, Language, Options, Quantity};
use std::io::Write;
use std::path::Path;

/// Writes `text` to `path` atomically (see [`crate::write`]); refuses the model file.
pub fn write_output(path: &Path, text: &str, model: &str) -> Result<(), CliError> {
    crate::write::refuse_inputs("--output", path, &[Path::new(model)])?;
    crate::write::atomic(path, |w| {
        w.write_all(text.as_bytes())
            .map_err(|e| CliError::input(format!("cannot write --output {} ({e})", path.display())))
    })?;
    crate::write::announce(path);
    Ok(())
}

/// `screwdyn symbolic MODEL --quantity Q [...]`.
pub fn symbolic(a: &SymbolicArgs) -> Result<(), CliError> {
    let model = load(
        &ModelArgs {
            model: a.model.clone(),
            format: None,
            allow_nonphysical: a.allow_nonphysical,
            strict: false,
        },
        None,
    )?;
    let quantity: Quantity = a.quantity.parse()?;
    let coriolis: CoriolisForm = a
        .coriolis_form
        .parse()
        .map_err(|e: screwdyn::Error| CliError::input(format!("--coriolis-form: {e}")))?;
    let collect: Collect = a
        .collect
        .parse()
        .map_err(|e: screwdyn::Error| CliError::input(format!("--collect: {e}")))?;
    if a.max_terms == 0 || a.max_ops == 0 {
        return Err(CliError::input(
            "--max-terms and --max-ops must be at least 1",
        ));
    }
    let options = Options {
        symbols: a.symbols.clone(),
        frame: a.frame.clone(),
        reference: match a.reference {
            ReferenceArg::World => Reference::World,
            ReferenceArg::Local => Reference::Local,
            ReferenceArg::WorldAligned => Reference::LocalWorldAligned,
        },
        coriolis,
        max_terms: a.max_terms,
        max_ops: a.max_ops,
    };
    let language = match a.format {
        SymbolicFormat::C => Some(Language::C),
        SymbolicFormat::Python => Some(Language::Python),
        SymbolicFormat::Rust => Some(Language::Rust),
        SymbolicFormat::Matlab => Some(Language::Matlab),
        _ => None,
    };
    let text = match language {
        Some(lang) => generate(&model, quantity, &options)?.emit(lang),
        None => {
            let d = derive(&model, quantity, &options)?;
            match a.format {
                SymbolicFormat::Latex => d.render_latex(!a.no_abbrev, collect),
                SymbolicFormat::Json => {
                    let mut s = serde_json::to_string_pretty(&d.render_json())
                        .map_err(|e| CliError::internal(e.to_string()))?;
                    s.push('\n');
                    s
                }
                _ => d.render_text(!a.no_abbrev, collect),
            }
        }
    };
    match &a.output {
        Some(path) => write_output(path, &text, &a.model),
        None => write_stdout(&text),
    }
}
