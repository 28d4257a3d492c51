//! OBJ and STL (ASCII and binary) load to the same solid; broken meshes are errors naming the file.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use tumble::{MassProperties, TriMesh};
use tumble_io::{load_mesh, IoError};

fn scenes() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes")
}

/// The demo handle scaled by 20, so every coordinate is a small integer: exact in f32, which STL
/// stores, so all three formats describe bit-identical solids.
fn integer_handle_obj() -> String {
    let text = std::fs::read_to_string(scenes().join("handle.obj")).unwrap();
    text.lines()
        .map(|line| match line.strip_prefix("v ") {
            Some(coords) => {
                let scaled: Vec<String> = coords
                    .split_whitespace()
                    .map(|c| format!("{}", (c.parse::<f64>().unwrap() * 20.0).round()))
                    .collect();
                format!("v {}\n", scaled.join(" "))
            }
            None => format!("{line}\n"),
        })
        .collect()
}

fn stl_ascii(mesh: &TriMesh) -> String {
    let mut s = String::from("solid handle\n");
    for t in mesh.triangles() {
        s.push_str("  facet normal 0 0 0\n    outer loop\n");
        for &i in t {
            let v = mesh.vertices()[i as usize];
            writeln!(s, "      vertex {} {} {}", v.x as f32, v.y as f32, v.z as f32).unwrap();
        }
        s.push_str("    endloop\n  endfacet\n");
    }
    s.push_str("endsolid handle\n");
    s
}

/// Binary STL: 80-byte header, triangle count, then per triangle a normal, three vertices (all
/// little-endian f32) and a 2-byte attribute.
fn stl_binary(mesh: &TriMesh) -> Vec<u8> {
    let mut bytes = vec![0u8; 80];
    bytes[..19].copy_from_slice(b"tumble-io test mesh");
    bytes.extend((mesh.triangles().len() as u32).to_le_bytes());
    for t in mesh.triangles() {
        bytes.extend([0f32; 3].iter().flat_map(|x| x.to_le_bytes()));
        for &i in t {
            let v = mesh.vertices()[i as usize];
            for c in [v.x, v.y, v.z] {
                bytes.extend((c as f32).to_le_bytes());
            }
        }
        bytes.extend([0u8, 0u8]);
    }
    bytes
}

fn mass(mesh: &TriMesh) -> MassProperties {
    MassProperties::from_mesh(mesh.vertices(), mesh.triangles(), 1000.0).unwrap()
}

fn assert_same_solid(a: &MassProperties, b: &MassProperties, tolerance: f64, what: &str) {
    let scale = a.inertia.to_cols_array().iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    assert!(
        (a.volume - b.volume).abs() <= tolerance * a.volume,
        "{what}: volume {} vs {}",
        a.volume,
        b.volume
    );
    assert!((a.mass - b.mass).abs() <= tolerance * a.mass, "{what}: mass");
    assert!((a.center_of_mass - b.center_of_mass).length() <= tolerance * a.volume.cbrt(), "{what}: com");
    let worst = (a.inertia - b.inertia).to_cols_array().iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    assert!(worst <= tolerance * scale, "{what}: inertia differs by {worst}");
}

fn write(dir: &Path, name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

#[test]
fn obj_and_stl_ascii_and_binary_give_the_same_mass_properties() {
    let dir = tempfile::tempdir().unwrap();
    let obj_path = write(dir.path(), "handle.obj", integer_handle_obj());
    let obj = load_mesh(&obj_path).unwrap();
    let ascii = load_mesh(&write(dir.path(), "handle.stl", stl_ascii(&obj))).unwrap();
    let binary = load_mesh(&write(dir.path(), "handle_bin.STL", stl_binary(&obj))).unwrap();
    // Welding restores the shared vertices STL does not store.
    assert_eq!(ascii.vertices().len(), obj.vertices().len());
    assert_eq!(binary.vertices().len(), obj.vertices().len());
    let reference = mass(&obj);
    assert_same_solid(&reference, &mass(&ascii), 1e-12, "ascii STL");
    assert_same_solid(&reference, &mass(&binary), 1e-12, "binary STL");
}

#[test]
fn stl_of_the_real_handle_matches_the_obj_to_f32_precision() {
    let obj = load_mesh(&scenes().join("handle.obj")).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let binary = load_mesh(&write(dir.path(), "handle.stl", stl_binary(&obj))).unwrap();
    assert_same_solid(&mass(&obj), &mass(&binary), 1e-6, "binary STL of the f64 handle");
}

#[test]
fn obj_split_into_groups_is_welded_back_together() {
    // A unit cube in two groups; tobj gives each group its own copy of the shared vertices.
    let cube = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
                g bottom_and_sides\nf 1 4 3 2\nf 1 2 6 5\nf 2 3 7 6\n\
                g top_and_rest\nf 5 6 7 8\nf 3 4 8 7\nf 4 1 5 8\n";
    let mesh = tumble_io::obj_from_str(cube, Path::new("cube.obj")).unwrap();
    assert_eq!(mesh.vertices().len(), 8);
    assert_eq!(mesh.triangles().len(), 12);
    let mp = mass(&mesh);
    assert!((mp.volume - 1.0).abs() < 1e-14, "volume {}", mp.volume);
}

#[test]
fn open_mesh_is_an_error_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    // A tetrahedron with one face missing.
    let path =
        write(dir.path(), "open.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\n");
    let error = load_mesh(&path).unwrap_err();
    let message = error.to_string();
    assert!(matches!(error, IoError::Mesh { .. }), "{message}");
    assert!(message.starts_with(&path.display().to_string()), "{message}");
    assert!(message.contains("open"), "{message}");
}

#[test]
fn inside_out_mesh_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(
        dir.path(),
        "inverted.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 4 2\nf 2 4 3\nf 1 3 4\n",
    );
    let message = load_mesh(&path).unwrap_err().to_string();
    assert!(message.contains("inverted.obj") && message.contains("inside out"), "{message}");
}

#[test]
fn unreadable_and_unknown_files_are_errors() {
    let message = load_mesh(Path::new("no/such/mesh.obj")).unwrap_err().to_string();
    assert!(message.starts_with("no/such/mesh.obj: "), "{message}");
    let message = load_mesh(Path::new("mesh.ply")).unwrap_err().to_string();
    assert!(message.contains("mesh.ply") && message.contains("unsupported"), "{message}");
    let message =
        tumble_io::obj_from_str("v 0 0 0\nf 1 x 3\n", Path::new("bad.obj")).unwrap_err().to_string();
    assert!(message.starts_with("bad.obj: "), "{message}");
    let message =
        tumble_io::stl_from_bytes(b"solid x\nfacet oops\n", Path::new("bad.stl")).unwrap_err().to_string();
    assert!(message.starts_with("bad.stl: "), "{message}");
}
