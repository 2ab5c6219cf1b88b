//! `screwdyn view`: parse, call `screwdyn_view::render_html`, write the page atomically
//! (`Page::save`).

use crate::args::ViewArgs;
use crate::CliError;
use screwdyn_view::{read_run, render_html, ViewOptions};
use std::path::{Path, PathBuf};

/// The default page name: the model file's stem (or the built-in's name) with `.html`.
fn default_output(model: &str) -> PathBuf {
    let stem = match model.strip_prefix("builtin:") {
        Some(name) => name.to_string(),
        None => Path::new(model)
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "robot".into()),
    };
    PathBuf::from(format!("{stem}.html"))
}

/// Whether two paths name the same file (after resolving both, when they exist).
fn same_file(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(x), Ok(y)) => x == y,
        _ => a == b,
    }
}

/// `screwdyn view MODEL [--q …] [--run FILE] [--output FILE] [--package-path DIR]…`.
pub fn view(a: &ViewArgs) -> Result<(), CliError> {
    let output = a.output.clone().unwrap_or_else(|| default_output(&a.model));
    let inputs = std::iter::once(Path::new(&a.model)).chain(a.run.as_deref());
    if let Some(p) = inputs.into_iter().find(|p| same_file(p, &output)) {
        return Err(CliError::input(format!(
            "--output {} is one of the inputs ({}); choose another file name",
            output.display(),
            p.display()
        )));
    }
    if a.q.is_some() && a.run.is_some() {
        return Err(CliError::input(
            "--q cannot be combined with --run (the run gives the configurations)",
        ));
    }
    let loaded = super::inputs::load_source(&a.model, a.strict)?;
    let model = &loaded.model;
    let q =
        a.q.as_deref()
            .map(|text| super::inputs::parse_vector(Some(text), "q", model))
            .transpose()?;
    let run = a
        .run
        .as_deref()
        .map(|p| read_run(p, model, a.max_samples))
        .transpose()?;
    let (description, description_text) = loaded
        .description()
        .map(|(path, text)| (path.to_path_buf(), text.to_string()))
        .unzip();
    let page = render_html(
        model,
        &ViewOptions {
            q,
            run,
            description,
            description_text,
            package_paths: a.package_path.clone(),
            max_triangles: a.max_triangles,
            title: None,
        },
    )?;
    for w in &page.warnings {
        eprintln!("warning: {w}");
    }
    page.save(&output)?;
    crate::output::write_stdout(&format!(
        "wrote {} ({:.1} MB: {} triangles{})\n",
        output.display(),
        page.html.len() as f64 / 1e6,
        page.triangles,
        if page.samples > 0 {
            format!(", {} run samples", page.samples)
        } else {
            String::new()
        }
    ))
}
