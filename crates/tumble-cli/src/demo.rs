//! The built-in demo: `scenes/demo.toml` and its mesh, compiled into the binary so `tumble` works
//! from any folder with nothing else installed.

use std::path::Path;

use tumble_io::{IoError, Scene};

use crate::run::{run_scene, RunOptions};

const DEMO_SCENE: &str = include_str!("../../../scenes/demo.toml");
const HANDLE_OBJ: &str = include_str!("../../../scenes/handle.obj");
/// The name the embedded scene goes by in messages; its mesh resolves next to it.
const DEMO_PATH: &str = "scenes/demo.toml";
pub const DEFAULT_OUT: &str = "out/demo.csv";

pub fn run_demo(out: &Path) -> Result<String, String> {
    let mut embedded = |path: &Path| -> Result<tumble::TriMesh, IoError> {
        if path.file_name().is_some_and(|n| n == "handle.obj") {
            tumble_io::obj_from_str(HANDLE_OBJ, path)
        } else {
            Err(IoError::Mesh { path: path.to_owned(), message: "not built into the binary".into() })
        }
    };
    let scene =
        Scene::from_str_with_meshes(DEMO_SCENE, DEMO_PATH, &mut embedded).map_err(|e| e.to_string())?;
    let options = RunOptions {
        out: out.to_owned(),
        every: 1,
        duration: scene.duration,
        dt: scene.dt,
        threads: 1,
        checkpoint: None,
    };
    let summary = run_scene(&scene, &options)?;
    Ok(format!(
        "Tumble demo: a T-handle spinning about its intermediate axis in zero gravity flips over\n\
         and back every few seconds (the Dzhanibekov effect). Plot qx..qw from the recording to see it.\n\n{}",
        summary.render(&format!("{DEMO_PATH} (built in)"))
    ))
}
