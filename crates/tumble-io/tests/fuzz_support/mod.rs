//! The checks behind the parser fuzz targets (`fuzz/fuzz_targets/{scene_parse,obj_read,stl_read}`)
//! and their proptest twins (`fuzz_parsers.rs`). Each panics on a violation.
#![allow(dead_code)]

use std::path::Path;

use tumble::{Shape, TriMesh};
use tumble_io::{IoError, Scene};

/// A scene's meshes in a fuzz run: never read from the disk; `cube.obj` is a unit cube, anything
/// else is an error.
fn stub_mesh(path: &Path) -> Result<TriMesh, IoError> {
    if path.file_name().is_some_and(|n| n == "cube.obj") {
        tumble_io::obj_from_str(CUBE_OBJ, path)
    } else {
        Err(IoError::Mesh { path: path.to_owned(), message: "no meshes in fuzz runs".into() })
    }
}

pub const CUBE_OBJ: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 4 8 7\nf 4 7 3\nf 1 5 8\nf 1 8 4\nf 2 3 7\nf 2 7 6\n";

/// Parsing never panics; errors name the file; a scene that parses builds its world or says why
/// not, and a built world takes a step.
pub fn check_scene_text(text: &str) {
    match Scene::from_str_with_meshes(text, "fuzz.toml", &mut stub_mesh) {
        Ok(scene) => {
            if let Ok(mut built) = scene.build_world() {
                let dt = scene.dt;
                if dt.is_finite() && dt > 0.0 {
                    built.world.step(dt).expect("the scene's dt was checked");
                }
            }
        }
        Err(e) => assert!(e.to_string().contains("fuzz.toml"), "error without the file name: {e}"),
    }
}

fn check_mesh(mesh: Result<TriMesh, IoError>, name: &str) {
    let Ok(mesh) = mesh else { return };
    assert!(mesh.vertices().iter().all(|v| v.is_finite()), "{name}: non-finite vertex");
    let n = mesh.vertices().len() as u32;
    assert!(mesh.triangles().iter().flatten().all(|&i| i < n), "{name}: index out of range");
    // A value or an error, never a panic (open, inside-out and degenerate meshes are errors).
    if let Ok(mp) = Shape::TriMesh(mesh).mass_properties(1000.0) {
        assert!(mp.mass.is_finite() && mp.center_of_mass.is_finite(), "{name}: {mp:?}");
    }
}

pub fn check_obj(text: &str) {
    check_mesh(tumble_io::obj_from_str(text, Path::new("fuzz.obj")), "obj");
}

pub fn check_stl(bytes: &[u8]) {
    check_mesh(tumble_io::stl_from_bytes(bytes, Path::new("fuzz.stl")), "stl");
}
