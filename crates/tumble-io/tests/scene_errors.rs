//! Every class of bad scene gives an error that names the file, the line and the key.

use std::path::Path;

use tumble_io::{IoError, Scene};

const FILE: &str = "scenes/bad.toml";

/// Parses `text`, expects an error at `line` whose message contains every one of `needles`.
fn expect_error(text: &str, line: usize, needles: &[&str]) -> String {
    let error = Scene::from_str(text, FILE).expect_err("the scene should be rejected");
    let message = error.to_string();
    assert!(message.starts_with(&format!("{FILE}:{line}: ")), "wrong file/line in: {message}");
    assert_eq!(error.line(), Some(line), "{message}");
    for needle in needles {
        assert!(message.contains(needle), "`{needle}` missing from: {message}");
    }
    message
}

const GOOD_BODY: &str = r#"
[[body]]
name = "ball"
shape = { type = "sphere", radius = 0.5 }
"#;

#[test]
fn a_minimal_scene_parses_with_defaults() {
    let scene = Scene::from_str(GOOD_BODY, FILE).unwrap();
    assert_eq!(scene.dt, 1.0 / 240.0);
    assert_eq!(scene.duration, 10.0);
    assert_eq!(scene.gravity, tumble::DVec3::new(0.0, 0.0, -9.81));
    let def = &scene.bodies[0].def;
    assert_eq!(def.name, "ball");
    assert_eq!(def.density, 1000.0);
    assert_eq!(def.mass, None);
    assert_eq!(def.kind, tumble::BodyKind::Dynamic);
    assert_eq!(def.orientation, tumble::DQuat::IDENTITY);
    assert_eq!(scene.bodies[0].line, 3);
}

#[test]
fn every_key_parses() {
    let text = r#"
[world]
gravity = [0.0, 0.0, -1.0]
dt = 0.01
duration = 2
[[body]]
name = "all"
shape = { type = "compound", parts = [
    { shape = { type = "box", half_extents = [0.5, 1.0, 1.5] } },
    { shape = { type = "capsule", radius = 0.1, half_height = 0.2 }, position = [1.0, 0, 0], orientation = [0.0, 0.0, 0.6, 0.8] },
    { shape = { type = "cylinder", radius = 0.1, half_height = 0.2 } },
    { shape = { type = "cone", radius = 0.1, half_height = 0.2 } },
] }
mass = 3.0
position = [1.0, 2.0, 3.0]
orientation = [0.0, 0.0, 0.0, 1.0]
linear_velocity = [1.0, 0.0, 0.0]
angular_velocity = [0.01, 5.0, 0.01]
kind = "kinematic"
linear_damping = 0.1
angular_damping = 0.2
gravity_scale = 0.5
friction = 0.3
restitution = 0.5
rolling_friction = 0.01
torsional_friction = 0.02
allow_sleep = false
"#;
    let scene = Scene::from_str(text, FILE).unwrap();
    assert_eq!((scene.dt, scene.duration), (0.01, 2.0));
    let def = &scene.bodies[0].def;
    assert_eq!(def.mass, Some(3.0));
    assert_eq!(def.kind, tumble::BodyKind::Kinematic);
    assert_eq!(def.angular_velocity, tumble::DVec3::new(0.01, 5.0, 0.01));
    assert_eq!((def.linear_damping, def.angular_damping, def.gravity_scale), (0.1, 0.2, 0.5));
    assert_eq!(
        (
            def.material.friction,
            def.material.restitution,
            def.material.rolling_friction,
            def.material.torsional_friction
        ),
        (0.3, 0.5, 0.01, 0.02)
    );
    assert!(!def.allow_sleep);
    match def.shape.as_ref().unwrap() {
        tumble::Shape::Compound(c) => {
            assert_eq!(c.children().len(), 4);
            assert_eq!(c.children()[1].pose.translation, tumble::DVec3::X);
        }
        other => panic!("expected a compound, got {other:?}"),
    }
}

#[test]
fn unknown_key_names_the_key() {
    expect_error(
        "[[body]]\nname = \"arm\"\nshape = { type = \"sphere\", radius = 0.5 }\ndensityy = 2.0\n",
        4,
        &["body \"arm\"", "unknown field `densityy`"],
    );
    expect_error("[world]\ndt = 0.1\nsteps = 3\n", 3, &["world", "unknown field `steps`"]);
    expect_error(
        "[[body]]\nname = \"arm\"\nshape = { type = \"sphere\", radius = 0.5, colour = 1 }\n",
        3,
        &["body \"arm\": shape", "unknown field `colour`"],
    );
}

#[test]
fn wrong_type_names_the_key() {
    expect_error(
        "[[body]]\nname = \"arm\"\nshape = { type = \"sphere\", radius = 0.5 }\n\ndensity = \"heavy\"\n",
        5,
        &["body \"arm\": density", "invalid type"],
    );
    expect_error(
        "[[body]]\nname = \"arm\"\nshape = { type = \"sphere\", radius = 0.5 }\nposition = [1.0, 2.0]\n",
        4,
        &["body \"arm\": position", "length 2"],
    );
    expect_error("[world]\n\ngravity = 3\n", 3, &["world.gravity", "invalid type"]);
}

#[test]
fn missing_radius_names_the_key() {
    expect_error(
        "[[body]]\nname = \"ball\"\nshape = { type = \"sphere\" }\n",
        3,
        &["body \"ball\": shape", "needs `radius`"],
    );
    expect_error(
        "[[body]]\nname = \"can\"\nshape = { type = \"cylinder\", radius = 1.0 }\n",
        3,
        &["body \"can\": shape", "needs `half_height`"],
    );
}

#[test]
fn missing_shape_or_name_is_an_error() {
    expect_error("[[body]]\nname = \"ghost\"\n", 1, &["body \"ghost\"", "missing field `shape`"]);
    expect_error(
        "\n[[body]]\nshape = { type = \"sphere\", radius = 1.0 }\n",
        2,
        &["body #1", "missing field `name`"],
    );
}

#[test]
fn negative_radius_names_the_key_and_value() {
    expect_error(
        "[[body]]\nname = \"ball\"\nshape = { type = \"sphere\", radius = -0.5 }\n",
        3,
        &["body \"ball\": shape.radius must be > 0, got -0.5"],
    );
    expect_error(
        "[[body]]\nname = \"brick\"\nshape = { type = \"box\", half_extents = [1.0, 0.0, 1.0] }\n",
        3,
        &["body \"brick\": shape.half_extents", "y must be finite and > 0, got 0"],
    );
    expect_error(
        "[[body]]\nname = \"arm\"\nshape = { type = \"sphere\", radius = 0.5 }\ndensity = -2\n",
        4,
        &["body \"arm\": density must be > 0, got -2"],
    );
}

#[test]
fn keys_of_another_shape_type_are_errors() {
    expect_error(
        "[[body]]\nname = \"ball\"\nshape = { type = \"sphere\", radius = 1.0, half_extents = [1, 1, 1] }\n",
        3,
        &["shape.half_extents", "a sphere shape takes no `half_extents`"],
    );
    expect_error(
        "[[body]]\nname = \"ball\"\nshape = { type = \"blob\", radius = 1.0 }\n",
        3,
        &["shape.type", "unknown variant `blob`"],
    );
}

#[test]
fn non_unit_or_zero_quaternion_is_an_error() {
    let body = "[[body]]\nname = \"q\"\nshape = { type = \"sphere\", radius = 1.0 }\n";
    expect_error(
        &format!("{body}orientation = [0.0, 0.0, 0.0, 1.001]\n"),
        4,
        &["body \"q\": orientation must be a unit quaternion", "length 1.001"],
    );
    expect_error(
        &format!("{body}orientation = [0.0, 0.0, 0.0, 0.0]\n"),
        4,
        &["orientation is the zero quaternion"],
    );
    expect_error(&format!("{body}orientation = [nan, 0.0, 0.0, 1.0]\n"), 4, &["orientation must be finite"]);
    // Rounding in a hand-written file is accepted (and normalised).
    let scene = Scene::from_str(&format!("{body}orientation = [0.0, 0.0, 0.6, 0.8000001]\n"), FILE).unwrap();
    assert!((scene.bodies[0].def.orientation.length() - 1.0).abs() < 1e-15);
    // Compound parts are checked the same way.
    expect_error(
        "[[body]]\nname = \"c\"\nshape = { type = \"compound\", parts = [\n  { shape = { type = \"sphere\", radius = 1.0 }, orientation = [1.0, 1.0, 0.0, 0.0] },\n] }\n",
        4,
        &["body \"c\": shape.parts[0].orientation must be a unit quaternion"],
    );
}

#[test]
fn both_density_and_mass_is_an_error() {
    expect_error(
        "[[body]]\nname = \"arm\"\nshape = { type = \"sphere\", radius = 0.5 }\ndensity = 2.0\nmass = 3.0\n",
        5,
        &["body \"arm\"", "either density or mass, not both"],
    );
}

#[test]
fn impossible_world_values_are_errors() {
    expect_error("[world]\ndt = 0.0\n", 2, &["world: dt must be > 0, got 0"]);
    expect_error("[world]\ndt = 0.1\nduration = -1.0\n", 3, &["world: duration must be >= 0, got -1"]);
    expect_error("[world]\ngravity = [0.0, nan, 0.0]\n", 2, &["world: gravity must be finite"]);
    expect_error(
        &format!("{GOOD_BODY}linear_velocity = [inf, 0.0, 0.0]\n"),
        5,
        &["body \"ball\": linear_velocity must be finite"],
    );
}

#[test]
fn impossible_material_values_are_errors() {
    expect_error(
        &format!("{GOOD_BODY}restitution = 1.5\n"),
        5,
        &["body \"ball\": restitution must be in [0, 1], got 1.5"],
    );
    expect_error(
        &format!("{GOOD_BODY}friction = -0.1\n"),
        5,
        &["body \"ball\": friction must be >= 0, got -0.1"],
    );
}

#[test]
fn duplicate_body_names_are_errors() {
    expect_error(&format!("{GOOD_BODY}{GOOD_BODY}"), 7, &["\"ball\" is used twice (first on line 3)"]);
}

#[test]
fn toml_syntax_errors_have_a_line() {
    expect_error("[world]\ndt = 0.1\ngravity = [0.0, 0.0\n", 3, &["invalid TOML"]);
}

#[test]
fn missing_mesh_file_names_the_key_and_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("scene.toml");
    let text = "[[body]]\nname = \"h\"\nshape = { type = \"mesh\", file = \"nowhere.obj\" }\n";
    std::fs::write(&scene, text).unwrap();
    let error = Scene::from_file(&scene).unwrap_err();
    let message = error.to_string();
    assert!(message.starts_with(&format!("{}:3: ", scene.display())), "{message}");
    assert!(message.contains("body \"h\": shape.file"), "{message}");
    assert!(message.contains(&dir.path().join("nowhere.obj").display().to_string()), "{message}");
}

#[test]
fn unreadable_scene_file_names_it() {
    let error = Scene::from_file(Path::new("no/such/scene.toml")).unwrap_err();
    assert!(matches!(error, IoError::File { .. }));
    assert!(error.to_string().starts_with("no/such/scene.toml: "), "{error}");
}
