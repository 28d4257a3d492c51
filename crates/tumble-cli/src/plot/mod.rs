//! `tumble plot`: time series of a run (energy, momenta, a body's ω) as PNG or SVG, one panel
//! per `--what` item, with axes and units.

mod draw;
mod series;
mod what;

use std::path::{Path, PathBuf};

use crate::source::{create_parent, input_kind, load_timeline, read_recording, InputKind, SourceArgs};
use series::PlotData;
use what::{panels, parse_what, What};

/// Default size: this wide, and this tall per panel.
pub const DEFAULT_WIDTH: u32 = 1000;
pub const PANEL_HEIGHT: u32 = 360;

pub fn plot(args: &SourceArgs, out: &Path, what: Option<&str>, size: Option<&str>) -> Result<String, String> {
    let ext = out.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    if !matches!(ext.as_deref(), Some("png") | Some("svg")) {
        return Err(format!("{}: the plot is written as PNG or SVG; name it *.png or *.svg", out.display()));
    }
    let requested = what.map(parse_what).transpose()?;
    let size = size.map(parse_size).transpose()?;

    let data = match (input_kind(args.input)?, args.scene) {
        (InputKind::Recording, None) => {
            let recording = read_recording(args.input)?;
            if let Some(d) = args.duration.filter(|d| !(d.is_finite() && *d >= 0.0)) {
                return Err(format!("--duration must be finite and >= 0, got {d}"));
            }
            let mut data = PlotData::from_recording(&recording);
            if let Some(d) = args.duration {
                let end = data.t[0] + d;
                let keep = data.t.iter().take_while(|&&t| t <= end + 1e-9).count();
                data.t.truncate(keep);
                for track in &mut data.omega {
                    track.omega_world.truncate(keep);
                    track.orientation.truncate(keep);
                }
            }
            data
        }
        _ => PlotData::from_timeline(&load_timeline(args)?),
    };
    let what = requested.unwrap_or_else(|| {
        if data.energy.is_some() {
            vec![What::Energy, What::AngularMomentum]
        } else {
            vec![What::Omega(None)]
        }
    });
    let panels = panels(&data, &what)?;
    let size = size.unwrap_or((DEFAULT_WIDTH, PANEL_HEIGHT * panels.len() as u32));
    create_parent(out)?;
    draw::draw(out, size, &data.t, &panels)?;
    let names: Vec<&str> = panels.iter().map(|p| p.title.as_str()).collect();
    Ok(format!("wrote {} ({}x{}): {}\n", out.display(), size.0, size.1, names.join("; ")))
}

/// `WIDTHxHEIGHT` in pixels.
fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let bad =
        || format!("--size `{text}`: expected WIDTHxHEIGHT in pixels, each 100 to 10000 (e.g. 1200x800)");
    let (w, h) = text.split_once(['x', 'X']).ok_or_else(bad)?;
    let w: u32 = w.trim().parse().map_err(|_| bad())?;
    let h: u32 = h.trim().parse().map_err(|_| bad())?;
    if !(100..=10_000).contains(&w) || !(100..=10_000).contains(&h) {
        return Err(bad());
    }
    Ok((w, h))
}

/// Where the plot goes when `-o` is not given.
pub fn default_plot_output(input: &Path) -> PathBuf {
    crate::source::default_output(input, "png")
}
