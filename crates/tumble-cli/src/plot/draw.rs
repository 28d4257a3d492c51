//! Drawing the panels with plotters: stacked charts over a shared time axis, to PNG (text with
//! a font built into the binary) or SVG.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};

use super::series::Panel;

const COLORS: [RGBColor; 4] =
    [RGBColor(214, 69, 65), RGBColor(46, 139, 87), RGBColor(52, 101, 164), RGBColor(40, 40, 40)];

/// Makes the font that the bitmap backend draws text with available (once).
fn register_fonts() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        // Ubuntu Light, shipped by the `epaint_default_fonts` crate (egui's default fonts).
        let _ = register_font("sans-serif", FontStyle::Normal, epaint_default_fonts::UBUNTU_LIGHT);
    });
}

pub fn draw(path: &Path, size: (u32, u32), t: &[f64], panels: &[Panel]) -> Result<(), String> {
    let is_svg = path.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("svg"));
    // Both backends measure text with it.
    register_fonts();
    let result = if is_svg {
        let root = SVGBackend::new(path, size).into_drawing_area();
        draw_on(&root, t, panels).and_then(|_| root.present().map_err(|e| e.to_string()))
    } else {
        let root = BitMapBackend::new(path, size).into_drawing_area();
        draw_on(&root, t, panels).and_then(|_| root.present().map_err(|e| e.to_string()))
    };
    result.map_err(|e| format!("{}: cannot draw the plot: {e}", path.display()))
}

fn draw_on<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    t: &[f64],
    panels: &[Panel],
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let areas = root.split_evenly((panels.len(), 1));
    let (t0, t1) = match (t.first(), t.last()) {
        (Some(&a), Some(&b)) if b > a => (a, b),
        (Some(&a), _) => (a, a + 1.0),
        _ => (0.0, 1.0),
    };
    for (area, panel) in areas.iter().zip(panels) {
        let finite = panel.lines.iter().flat_map(|l| l.values.iter().copied()).filter(|v| v.is_finite());
        let (lo, hi) = finite.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)));
        let (lo, hi) = if lo.is_finite() { (lo, hi) } else { (0.0, 1.0) };
        // A flat line gets a band around it, and every chart a margin above and below.
        let pad = ((hi - lo) * 0.06).max(1e-9 * lo.abs().max(hi.abs())).max(1e-12);
        let mut chart = ChartBuilder::on(area)
            .caption(&panel.title, ("sans-serif", 20))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(t0..t1, (lo - pad)..(hi + pad))
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc("time (s)")
            .y_desc(panel.y_label.as_str())
            .label_style(("sans-serif", 14))
            .axis_desc_style(("sans-serif", 15))
            .light_line_style(RGBColor(235, 235, 235))
            .draw()
            .map_err(|e| e.to_string())?;
        for (i, line) in panel.lines.iter().enumerate() {
            let color = COLORS[i % COLORS.len()];
            let points = t.iter().zip(&line.values).filter(|(_, v)| v.is_finite()).map(|(&t, &v)| (t, v));
            chart
                .draw_series(LineSeries::new(points, color.stroke_width(2)))
                .map_err(|e| e.to_string())?
                .label(line.label.as_str())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2)));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(200, 200, 200))
            .label_font(("sans-serif", 14))
            .draw()
            .map_err(|e| e.to_string())?;
    }
    Ok(())
}
