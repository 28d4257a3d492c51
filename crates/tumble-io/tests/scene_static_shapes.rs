//! Plane and height-field shapes in scene files, and their errors.

use tumble_io::Scene;

const SCENE: &str = r#"
[world]
dt = 0.016666666666666666
duration = 2.0

[[body]]
name = "floor"
kind = "static"
shape = { type = "plane", normal = [0.0, 0.0, 1.0], offset = 0.0 }

[[body]]
name = "hills"
kind = "static"
position = [10.0, 0.0, 0.0]
shape = { type = "heightfield", heights = [[0.0, 0.1, 0.0], [0.1, 0.3, 0.1], [0.0, 0.1, 0.0]], scale = [1.0, 1.0, 1.0] }

[[body]]
name = "ball"
shape = { type = "sphere", radius = 0.25 }
position = [0.0, 0.0, 1.0]
"#;

#[test]
fn a_ball_comes_to_rest_on_a_plane_from_a_scene_file() {
    let scene = Scene::from_str(SCENE, "static.toml").unwrap();
    let mut built = scene.build_world().unwrap();
    let ball = built.bodies[2];
    for _ in 0..120 {
        built.world.step(built.dt).unwrap();
    }
    let z = built.world.body(ball).unwrap().position().z;
    assert!((z - 0.25).abs() < 2e-3, "the ball rests on the plane: centre at {z}");
}

#[test]
fn bad_static_shapes_name_the_file_line_and_key() {
    let cases = [
        (
            SCENE.replace("normal = [0.0, 0.0, 1.0]", "normal = [0.0, 0.0, 0.0]"),
            "static.toml:9: body \"floor\": shape: plane normal",
        ),
        (
            SCENE.replace("[0.0, 0.1, 0.0], [0.1, 0.3, 0.1]", "[0.0, 0.1], [0.1, 0.3, 0.1]"),
            "row 1 has 3 values",
        ),
        (
            SCENE.replace("kind = \"static\"\nshape = { type = \"plane\"", "shape = { type = \"plane\""),
            "floor",
        ),
    ];
    for (text, expected) in cases {
        let err =
            Scene::from_str(&text, "static.toml").and_then(|s| s.build_world().map(|_| ())).unwrap_err();
        let message = err.to_string();
        assert!(message.contains(expected), "expected `{expected}` in: {message}");
    }
}
