//! Every scene shipped in `scenes/` parses and builds; scene values reach the world; errors found
//! when building (mesh problems, mass) still name the file and line.

use std::path::PathBuf;

use tumble_io::Scene;

fn scenes_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes")
}

#[test]
fn every_shipped_scene_parses_and_builds() {
    let mut count = 0;
    for entry in std::fs::read_dir(scenes_dir()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            let scene = Scene::from_file(&path).unwrap_or_else(|e| panic!("{e}"));
            let built = scene.build_world().unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(built.bodies.len(), scene.bodies.len(), "{}", path.display());
            assert!(built.world.body_count() > 0, "{}", path.display());
            count += 1;
        }
    }
    assert!(count >= 3, "expected demo, symmetric_top and projectile, found {count} scenes");
}

#[test]
fn demo_spins_about_the_handle_intermediate_axis() {
    let scene = Scene::from_file(scenes_dir().join("demo.toml")).unwrap();
    let built = scene.build_world().unwrap();
    let body = built.world.body(built.bodies[0]).unwrap();
    let moments = body.inertia_principal();
    assert!(moments.x < moments.y && moments.y < moments.z, "distinct moments: {moments}");
    // The middle principal axis, in the world, is nearly parallel to the spin.
    let axis = body.principal_rotation_world() * tumble::DVec3::Y;
    let w = body.angular_velocity();
    assert!(axis.dot(w).abs() / w.length() > 0.99, "spin {w} vs intermediate axis {axis}");
    assert_eq!(built.world.gravity(), tumble::DVec3::ZERO);
}

#[test]
fn body_values_reach_the_world_in_file_order() {
    let text = r#"
[world]
gravity = [0.0, 0.0, -1.0]
[[body]]
name = "a"
shape = { type = "sphere", radius = 0.5 }
mass = 2.0
position = [1.0, 2.0, 3.0]
linear_velocity = [0.0, 1.0, 0.0]
[[body]]
name = "b"
shape = { type = "box", half_extents = [0.5, 0.5, 0.5] }
density = 10.0
angular_velocity = [0.0, 0.0, 3.0]
"#;
    let built = Scene::from_str(text, "inline.toml").unwrap().build_world().unwrap();
    let a = built.world.body(built.bodies[0]).unwrap();
    let b = built.world.body(built.bodies[1]).unwrap();
    assert_eq!((a.name(), b.name()), ("a", "b"));
    assert!((a.mass() - 2.0).abs() < 1e-12);
    assert!((b.mass() - 10.0).abs() < 1e-12);
    assert_eq!(a.position(), tumble::DVec3::new(1.0, 2.0, 3.0));
    assert_eq!(b.angular_velocity(), tumble::DVec3::new(0.0, 0.0, 3.0));
    assert_eq!(built.world.gravity(), tumble::DVec3::new(0.0, 0.0, -1.0));
}

#[test]
fn open_mesh_file_in_a_scene_names_scene_line_key_and_mesh() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("open.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\n")
        .unwrap();
    let scene = dir.path().join("scene.toml");
    std::fs::write(&scene, "[[body]]\nname = \"lid\"\n\nshape = { type = \"mesh\", file = \"open.obj\" }\n")
        .unwrap();
    let message = Scene::from_file(&scene).unwrap_err().to_string();
    assert!(message.starts_with(&format!("{}:4: body \"lid\": shape.file: ", scene.display())), "{message}");
    assert!(message.contains("open.obj") && message.contains("open"), "{message}");
}
