//! Plots a person looks at: stacked panels of time series (PNG or SVG, by file extension),
//! labelled axes with units, legends with joint names, optional horizontal limit lines.
//!
//! Text is drawn with the DejaVu Sans font embedded in the binary (its licence is in
//! `assets/`), so plots look the same on machines without system fonts.

use crate::CliError;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;
use std::sync::Once;

static FONT: Once = Once::new();

/// Width of the legend column right of each chart (pixels).
const LEGEND_WIDTH: i32 = 300;

/// Draws `(label, colour, dashed)` entries top-down in the legend column.
fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[(String, RGBColor, bool)],
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let font = ("sans-serif", 14).into_font().color(&BLACK);
    for (k, (label, color, dashed)) in entries.iter().enumerate() {
        let y = 40 + 22 * k as i32;
        let style = color.stroke_width(3);
        if *dashed {
            area.draw(&PathElement::new(vec![(8, y), (16, y)], style))?;
            area.draw(&PathElement::new(vec![(22, y), (30, y)], style))?;
        } else {
            area.draw(&PathElement::new(vec![(8, y), (30, y)], style))?;
        }
        area.draw(&Text::new(label.clone(), (38, y - 8), font.clone()))?;
    }
    Ok(())
}

/// Colours of the dashed reference lines (dark, distinct from the series palette's first hues).
const LIMIT_COLORS: [RGBColor; 4] = [
    RGBColor(200, 0, 0),
    RGBColor(90, 90, 90),
    RGBColor(150, 0, 150),
    RGBColor(0, 110, 110),
];

fn register_font() {
    FONT.call_once(|| {
        let bytes: &'static [u8] = include_bytes!("../assets/DejaVuSans.ttf");
        // The font is embedded and known good; a failure would only lose the text.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, bytes);
    });
}

/// One curve.
pub struct Series {
    /// Legend entry (a joint name, "kinetic", ...).
    pub name: String,
    /// `(x, y)` samples.
    pub points: Vec<(f64, f64)>,
}

/// One panel: a y axis with its label and units, its curves, and dashed horizontal lines.
pub struct Panel {
    /// Panel title.
    pub title: String,
    /// Y-axis label with units, e.g. "q (rad)".
    pub y_label: String,
    /// The curves.
    pub series: Vec<Series>,
    /// Horizontal reference lines `(label, y)`, e.g. effort limits.
    pub lines: Vec<(String, f64)>,
}

/// Draws `panels` stacked vertically into `path` (`.png` or `.svg`); returns the image size.
pub fn plot_panels(
    path: &Path,
    title: &str,
    x_label: &str,
    panels: &[Panel],
) -> Result<(u32, u32), CliError> {
    register_font();
    let size = (1300u32, 60 + 300 * panels.len() as u32);
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    if ext != "png" && ext != "svg" {
        return Err(CliError::input(format!(
            "--plot {}: the file name must end in .png or .svg",
            path.display()
        )));
    }
    // Drawn into a temporary file beside the target (same extension, which selects the
    // encoder), renamed over it when complete.
    crate::write::atomic_path(path, |tmp| {
        let result = if ext == "png" {
            draw(
                BitMapBackend::new(tmp, size).into_drawing_area(),
                title,
                x_label,
                panels,
            )
        } else {
            draw(
                SVGBackend::new(tmp, size).into_drawing_area(),
                title,
                x_label,
                panels,
            )
        };
        result.map_err(|e| CliError::input(format!("cannot write plot {}: {e}", path.display())))
    })?;
    crate::write::announce(path);
    Ok(size)
}

fn draw<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    title: &str,
    x_label: &str,
    panels: &[Panel],
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    root.fill(&WHITE).map_err(e)?;
    let root = root.titled(title, ("sans-serif", 26)).map_err(e)?;
    let areas = root.split_evenly((panels.len().max(1), 1));
    for (panel, whole) in panels.iter().zip(areas.iter()) {
        // The chart on the left, its legend in a column on the right (never over the curves).
        let (area, legend) = whole.split_horizontally(whole.dim_in_pixel().0 as i32 - LEGEND_WIDTH);
        let (mut x0, mut x1, mut y0, mut y1) = (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        );
        for s in &panel.series {
            for &(x, y) in &s.points {
                if x.is_finite() && y.is_finite() {
                    x0 = x0.min(x);
                    x1 = x1.max(x);
                    y0 = y0.min(y);
                    y1 = y1.max(y);
                }
            }
        }
        for (_, y) in &panel.lines {
            y0 = y0.min(*y);
            y1 = y1.max(*y);
        }
        if !x0.is_finite() {
            (x0, x1, y0, y1) = (0.0, 1.0, -1.0, 1.0);
        }
        if x1 <= x0 {
            x1 = x0 + 1.0;
        }
        if y1 - y0 < 1e-9 * y0.abs().max(y1.abs()).max(1.0) {
            // A constant signal: centre it in a range of ±1 (or ±10 % of its value).
            let half = (0.1 * y0.abs()).max(1.0);
            (y0, y1) = (y0 - half, y1 + half);
        }
        let pad = (y1 - y0) * 0.08;
        let (y0, y1) = (y0 - pad, y1 + pad);
        let mut chart = ChartBuilder::on(&area)
            .caption(&panel.title, ("sans-serif", 20))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(80)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(e)?;
        chart
            .configure_mesh()
            .x_desc(x_label)
            .y_desc(&panel.y_label)
            .label_style(("sans-serif", 14))
            .axis_desc_style(("sans-serif", 16))
            .draw()
            .map_err(e)?;
        for (k, s) in panel.series.iter().enumerate() {
            let color = Palette99::pick(k).to_rgba();
            chart
                .draw_series(LineSeries::new(
                    s.points.iter().copied(),
                    color.stroke_width(2),
                ))
                .map_err(e)?;
        }
        let mut entries: Vec<(String, RGBColor, bool)> = panel
            .series
            .iter()
            .enumerate()
            .map(|(k, s)| {
                let c = Palette99::pick(k).to_rgba();
                (s.name.clone(), RGBColor(c.0, c.1, c.2), false)
            })
            .collect();
        // Reference lines: dashed, one colour and one legend entry per distinct label.
        let mut labels: Vec<&str> = Vec::new();
        for (label, y) in &panel.lines {
            let (k, first) = match labels.iter().position(|l| l == label) {
                Some(k) => (k, false),
                None => {
                    labels.push(label);
                    (labels.len() - 1, true)
                }
            };
            let color = LIMIT_COLORS[k % LIMIT_COLORS.len()];
            let dashes = (0..40).map(|i| {
                let a = x0 + (x1 - x0) * (2 * i) as f64 / 80.0;
                let b = x0 + (x1 - x0) * (2 * i + 1) as f64 / 80.0;
                PathElement::new(vec![(a, *y), (b, *y)], color.stroke_width(2))
            });
            chart.draw_series(dashes).map_err(e)?;
            if first {
                entries.push((label.clone(), color, true));
            }
        }
        draw_legend(&legend, &entries).map_err(e)?;
    }
    root.present().map_err(e)?;
    Ok(())
}
