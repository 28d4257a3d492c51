//! Scene keys beyond the basics: hull shapes, collision filters and sensors, solver settings in
//! `[world]`, and `[[joint]]` tables — each parsed into the world, and each mistake reported with
//! file, line and key.

use tumble::{BodyKind, DVec3, JointKind, Shape};
use tumble_io::Scene;

const FILE: &str = "scenes/bad.toml";

fn expect_error(text: &str, line: usize, needles: &[&str]) -> String {
    let error = Scene::from_str(text, FILE).expect_err("the scene should be rejected");
    let message = error.to_string();
    assert!(message.starts_with(&format!("{FILE}:{line}: ")), "wrong file/line in: {message}");
    for needle in needles {
        assert!(message.contains(needle), "`{needle}` missing from: {message}");
    }
    message
}

const TWO_BODIES: &str = r#"
[[body]]
name = "base"
kind = "static"
shape = { type = "box", half_extents = [1.0, 1.0, 0.1] }

[[body]]
name = "arm"
shape = { type = "box", half_extents = [0.1, 0.1, 0.5] }
position = [0.0, 0.0, 1.0]
"#;

#[test]
fn hull_from_points_and_from_a_mesh_file() {
    let text = r#"
[[body]]
name = "tetra"
shape = { type = "hull", points = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [0.1, 0.1, 0.1]] }
[[body]]
name = "handle"
shape = { type = "hull", file = "handle.obj" }
"#;
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/inline.toml");
    let scene = Scene::from_str(text, &dir).unwrap();
    match scene.bodies[0].def.shape.as_ref().unwrap() {
        Shape::ConvexHull(h) => assert_eq!(h.vertices().len(), 4, "the interior point is not a vertex"),
        other => panic!("expected a hull, got {other:?}"),
    }
    assert!(matches!(scene.bodies[1].def.shape, Some(Shape::ConvexHull(_))));
    scene.build_world().unwrap();
}

#[test]
fn hull_mistakes_name_the_key() {
    let body = |shape: &str| format!("[[body]]\nname = \"h\"\nshape = {shape}\n");
    expect_error(&body("{ type = \"hull\" }"), 3, &["body \"h\": shape", "`points`", "`file`"]);
    expect_error(
        &body("{ type = \"hull\", points = [[0, 0, 0], [1, 0, 0]], file = \"x.obj\" }"),
        3,
        &["either `points` or `file`"],
    );
    expect_error(
        &body("{ type = \"hull\", points = [[0, 0, 0], [1, 0, 0], [0, 1, 0]] }"),
        3,
        &["shape: convex hull"],
    );
    expect_error(&body("{ type = \"hull\", points = [[0, 0, 0], [1, 0]] }"), 3, &["shape.points"]);
    expect_error(
        &body("{ type = \"sphere\", radius = 1.0, points = [[0, 0, 0]] }"),
        3,
        &["takes no `points`"],
    );
}

#[test]
fn filter_and_sensor_keys_reach_the_body() {
    let text = "[[body]]\nname = \"t\"\nshape = { type = \"sphere\", radius = 1.0 }\ngroup = 2\nmask = 5\nsensor = true\n";
    let def = &Scene::from_str(text, FILE).unwrap().bodies[0].def;
    assert_eq!((def.filter.group, def.filter.mask, def.is_sensor), (2, 5, true));
    let d = &Scene::from_str("[[body]]\nname = \"t\"\nshape = { type = \"sphere\", radius = 1.0 }\n", FILE)
        .unwrap()
        .bodies[0]
        .def;
    assert_eq!((d.filter, d.is_sensor), (tumble::CollisionFilter::default(), false));
    let base = "[[body]]\nname = \"t\"\nshape = { type = \"sphere\", radius = 1.0 }\n";
    expect_error(
        &format!("{base}group = -1\n"),
        4,
        &["body \"t\": group must be between 0 and 4294967295, got -1"],
    );
    expect_error(&format!("{base}mask = 4294967296\n"), 4, &["body \"t\": mask"]);
    expect_error(&format!("{base}sensor = 1\n"), 4, &["body \"t\": sensor", "invalid type"]);
}

#[test]
fn bullet_key_reaches_the_body() {
    let base = "[[body]]\nname = \"t\"\nshape = { type = \"sphere\", radius = 1.0 }\n";
    let def = &Scene::from_str(&format!("{base}bullet = true\n"), FILE).unwrap().bodies[0].def;
    assert!(def.bullet);
    assert!(!Scene::from_str(base, FILE).unwrap().bodies[0].def.bullet);
    let world = Scene::from_str(&format!("{base}bullet = true\n"), FILE).unwrap().build_world().unwrap();
    assert!(world.world.bodies().all(|(_, b)| b.is_bullet()));
    expect_error(&format!("{base}bullet = \"yes\"\n"), 4, &["body \"t\": bullet", "invalid type"]);
    expect_error(&format!("{base}bulet = true\n"), 4, &["bulet"]);
}

#[test]
fn world_solver_keys_reach_the_world() {
    let text = format!(
        "[world]\nsubsteps = 8\nsolve_iterations = 2\nrelax_iterations = 0\ncontact_hertz = 20.0\njoint_hertz = 40.0\njoint_tree_limits = false\nsleep = false\n{TWO_BODIES}"
    );
    let scene = Scene::from_str(&text, FILE).unwrap();
    let built = scene.build_world().unwrap();
    let s = built.world.solver_settings();
    assert_eq!((s.substeps, s.solve_iterations, s.relax_iterations), (8, 2, 0));
    assert_eq!((s.contact_hertz, s.joint_hertz), (20.0, 40.0));
    assert!(s.joint_trees && !s.joint_tree_limits);
    assert!(!scene.sleep.enabled);
    expect_error("[world]\nsubsteps = 0\n", 2, &["world: substeps must be between 1 and 1000, got 0"]);
    expect_error("[world]\n\nrelax_iterations = -1\n", 3, &["world: relax_iterations"]);
    expect_error("[world]\ncontact_hertz = -5.0\n", 2, &["world: contact_hertz must be >= 0, got -5"]);
    expect_error("[world]\nsleep = \"no\"\n", 2, &["world.sleep", "invalid type"]);
    expect_error("[world]\nsubsteps = 2.5\n", 2, &["world.substeps", "invalid type"]);
}

#[test]
fn every_joint_type_builds() {
    let text = format!(
        r#"{TWO_BODIES}
[[body]]
name = "bob"
shape = {{ type = "sphere", radius = 0.1 }}
position = [2.0, 0.0, 1.0]

[[joint]]
type = "hinge"
name = "elbow"
body_a = "base"
body_b = "arm"
anchor = [0.0, 0.0, 0.5]
axis = [0.0, 1.0, 0.0]
limits = [-1.0, 1.0]
motor = {{ target_speed = 2.0, max_force = 10.0 }}
spring = {{ hertz = 2.0, damping_ratio = 0.5 }}
spring_target = 0.25
break_force = 1000.0
break_torque = 500.0
collide_connected = true

[[joint]]
type = "slider"
body_a = "arm"
body_b = "bob"
anchor = [1.0, 0.0, 1.0]
axis = [1.0, 0.0, 0.0]
limits = [-0.5, 0.5]

[[joint]]
type = "distance"
body_a = "base"
body_b = "bob"
anchor = [1.0, 0.0, 0.0]
anchor_b = [2.0, 0.0, 1.0]
min_length = 0.5
max_length = 2.0
spring = {{ hertz = 1.0 }}

[[joint]]
type = "ball"
body_a = "arm"
body_b = "bob"
anchor = [2.0, 0.0, 1.0]
swing_limit = 0.5
twist_limits = [-0.1, 0.1]

[[joint]]
type = "fixed"
body_a = "bob"
body_b = "base"
anchor = [2.0, 0.0, 1.0]
"#
    );
    let scene = Scene::from_str(&text, FILE).unwrap();
    assert_eq!(scene.joints.len(), 5);
    let built = scene.build_world().unwrap();
    assert_eq!(built.joints.len(), 5);
    let elbow = built.world.joint(built.joints[0]).unwrap();
    assert_eq!(elbow.name(), "elbow");
    assert_eq!((elbow.body_a(), elbow.body_b()), (built.bodies[0], built.bodies[1]));
    match elbow.kind() {
        JointKind::Hinge(h) => {
            assert_eq!(h.limits, Some(tumble::Limits::new(-1.0, 1.0)));
            assert_eq!(h.motor, Some(tumble::Motor::new(2.0, 10.0)));
            assert_eq!(h.spring, Some(tumble::SpringSettings::new(2.0, 0.5)));
            assert_eq!(h.spring_target_angle, 0.25);
        }
        other => panic!("expected a hinge, got {other:?}"),
    }
    assert_eq!(scene.joints[0].def.axis_world, DVec3::Y);
    assert_eq!(scene.joints[0].def.break_force, Some(1000.0));
    assert!(scene.joints[0].def.collide_connected);
    match built.world.joint(built.joints[2]).unwrap().kind() {
        JointKind::Distance(d) => {
            assert_eq!((d.min_length, d.max_length), (0.5, 2.0));
            assert!((d.length.unwrap() - 2f64.sqrt()).abs() < 1e-12, "rest length from the anchors");
        }
        other => panic!("expected a distance joint, got {other:?}"),
    }
    assert_eq!(built.world.body(built.bodies[0]).unwrap().kind(), BodyKind::Static);
}

#[test]
fn joint_mistakes_name_the_file_line_and_key() {
    let joint = |body: &str| format!("{TWO_BODIES}\n[[joint]]\ntype = \"hinge\"\nname = \"j\"\n{body}");
    // TWO_BODIES is 10 lines; `[[joint]]` is on line 12, `type` on 13, the body of the joint from 15.
    expect_error(
        &joint("body_a = \"base\"\nbody_b = \"leg\"\nanchor = [0, 0, 0]\naxis = [0, 1, 0]\n"),
        16,
        &["joint \"j\": body_b: there is no body named \"leg\""],
    );
    expect_error(
        &joint("body_a = \"base\"\nbody_b = \"arm\"\naxis = [0, 1, 0]\n"),
        13,
        &["joint \"j\": a hinge joint needs `anchor`"],
    );
    expect_error(&joint("body_a = \"base\"\nbody_b = \"arm\"\nanchor = [0, 0, 0]\n"), 13, &["needs `axis`"]);
    let ok = "body_a = \"base\"\nbody_b = \"arm\"\nanchor = [0, 0, 0]\naxis = [0, 1, 0]\n";
    expect_error(
        &joint(&format!("{ok}limits = [1.0, -1.0]\n")),
        19,
        &["joint \"j\": limits: lower (1) must be <= upper (-1)"],
    );
    expect_error(
        &joint(&format!("{ok}length = 1.0\n")),
        19,
        &["joint \"j\": length: a hinge joint takes no `length`"],
    );
    expect_error(
        &joint(&format!("{ok}motor = {{ target_speed = 1.0, max_force = -2.0 }}\n")),
        19,
        &["joint \"j\": motor.max_force must be >= 0, got -2"],
    );
    expect_error(
        &joint(&format!("{ok}motor = {{ speed = 1.0 }}\n")),
        19,
        &["joint \"j\": motor", "unknown field `speed`"],
    );
    expect_error(&joint(&format!("{ok}break_force = 0.0\n")), 19, &["break_force must be > 0"]);
    expect_error(&joint(&format!("{ok}axis2 = [0, 1, 0]\n")), 19, &["joint \"j\"", "unknown field `axis2`"]);
    expect_error(
        &joint("body_a = \"arm\"\nbody_b = \"arm\"\nanchor = [0, 0, 0]\naxis = [0, 1, 0]\n"),
        16,
        &["two different bodies"],
    );
    expect_error(
        &joint(&format!("{ok}axis = [0, 0, 0]\n").replace("axis = [0, 1, 0]\n", "")),
        18,
        &["axis must be a non-zero vector"],
    );
    // A value only the core can judge (hinge limits beyond ±π) still gets the joint's line.
    let text = joint(&format!("{ok}limits = [-4.0, 0.0]\n"));
    let error = Scene::from_str(&text, FILE).unwrap().build_world().map(drop).unwrap_err().to_string();
    assert!(error.starts_with(&format!("{FILE}:13: ")) && error.contains("hinge limits"), "{error}");
    // An unknown joint type.
    expect_error(
        &format!("{TWO_BODIES}\n[[joint]]\ntype = \"weld\"\nbody_a = \"base\"\nbody_b = \"arm\"\n"),
        13,
        &["joint #1: type", "unknown variant `weld`"],
    );
}
