//! `tumble view`: one self-contained HTML page that plays a run in 3D (the viewer in `viewer/`,
//! three.js bundled at build time by `build.rs`). Nothing is fetched when the page is opened.

use std::path::{Path, PathBuf};

use tumble_io::viewer::{viewer_page, ViewerDoc};

use crate::source::{create_parent, default_output, load_timeline, SourceArgs};

const TEMPLATE: &str = include_str!("../../../viewer/template.html");
const SCRIPT: &str = include_str!(concat!(env!("OUT_DIR"), "/viewer.js"));

/// The page's script, or why this binary has none.
fn script() -> Result<&'static str, String> {
    if SCRIPT.starts_with("/* TUMBLE_VIEWER_NOT_BUILT") {
        let reason = SCRIPT.trim_start_matches("/* TUMBLE_VIEWER_NOT_BUILT: ").trim_end_matches(" */");
        return Err(format!(
            "this tumble was built without the viewer page's script ({reason}).\n\
             Install Node.js (18 or newer) with npm, then rebuild (`cargo build --release`): the build runs \
             `npm ci && node build.mjs` in viewer/"
        ));
    }
    Ok(SCRIPT)
}

pub fn view(args: &SourceArgs, out: Option<PathBuf>) -> Result<String, String> {
    let script = script()?;
    let out = out.unwrap_or_else(|| default_output(args.input, "html"));
    let timeline = load_timeline(args)?;
    let title = title_of(args.input);
    let doc = ViewerDoc::from_timeline(&timeline, &title);
    let page = viewer_page(TEMPLATE, &title, &doc.to_json(), script).map_err(|e| e.to_string())?;
    create_parent(&out)?;
    std::fs::write(&out, &page).map_err(|e| format!("{}: {e}", out.display()))?;
    Ok(format!(
        "wrote {} ({} bodies, {} frames over {:.2} s, {:.1} MB): open it in a browser\n",
        out.display(),
        timeline.bodies.len(),
        timeline.frames.len(),
        timeline.duration(),
        page.len() as f64 / 1e6
    ))
}

fn title_of(input: &Path) -> String {
    let name = input.file_name().map_or("run".into(), |s| s.to_string_lossy().into_owned());
    format!("Tumble — {name}")
}
