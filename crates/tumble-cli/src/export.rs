//! `tumble export`: a run as binary glTF 2.0 (`.glb`), one node per body with its mesh and a
//! translation/rotation animation, converted to glTF's Y up.

use std::path::PathBuf;

use crate::source::{create_parent, default_output, load_timeline, SourceArgs};

pub fn export(args: &SourceArgs, out: Option<PathBuf>) -> Result<String, String> {
    let out = out.unwrap_or_else(|| default_output(args.input, "glb"));
    let ext = out.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    if ext.as_deref() != Some("glb") {
        return Err(format!("{}: tumble export writes binary glTF; name the output *.glb", out.display()));
    }
    let timeline = load_timeline(args)?;
    create_parent(&out)?;
    tumble_io::gltf::write_glb(&timeline, &out).map_err(|e| e.to_string())?;
    Ok(format!(
        "wrote {} ({} bodies, {} keyframes over {:.2} s)\n",
        out.display(),
        timeline.bodies.len(),
        timeline.frames.len(),
        timeline.duration()
    ))
}
