//! Timelines: simulated ones see contacts and sleep; replayed ones give back the recording's poses
//! with the energies recomputed; any world (joints included) can be captured; the viewer document
//! carries it all.

use std::path::Path;

use tumble::{BodyDef, Cuboid, DVec3, HingeJoint, JointDef, JointKind, Shape, World};
use tumble_io::viewer::{viewer_page, ViewerDoc};
use tumble_io::{Recording, RecordingWriter, Scene, SimulateOptions, Timeline, TimelineRecorder};

fn scene(name: &str) -> Scene {
    Scene::from_file(Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes")).join(name)).unwrap()
}

#[test]
fn simulated_drop_has_contacts_and_keeps_the_requested_rate() {
    let scene = scene("shapes.toml");
    let timeline = Timeline::simulate(&scene, &SimulateOptions { duration: Some(1.5), fps: 30.0 }).unwrap();
    assert!(timeline.simulated);
    assert_eq!(timeline.frames.len(), 46, "0 to 1.5 s at 30 frames a second");
    assert!(timeline.frames[0].contacts.is_empty(), "everything starts in the air");
    let last = timeline.frames.last().unwrap();
    assert!(!last.contacts.is_empty(), "by 1.5 s things rest on the slab");
    for c in &last.contacts {
        assert!((c.normal.length() - 1.0).abs() < 1e-9);
        assert!(c.point.z > -0.05 && c.point.z < 0.5, "contact at {}", c.point);
    }
    assert_eq!(timeline.frames[0].awake, 6, "six dynamic bodies, all awake");
}

#[test]
fn replay_gives_back_the_recording() {
    let scene = scene("projectile.toml");
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("p.csv");
    let mut built = scene.build_world().unwrap();
    let mut out = RecordingWriter::create(&path, 2).unwrap();
    out.write_frame(&built.world).unwrap();
    let energy = |w: &World| w.kinetic_energy() + w.potential_energy();
    let mut energies = vec![energy(&built.world)];
    for _ in 0..100 {
        built.world.step(scene.dt).unwrap();
        if out.record_step(&built.world).unwrap() {
            energies.push(energy(&built.world));
        }
    }
    out.finish().unwrap();
    let recording = Recording::read(&path).unwrap();
    let timeline = Timeline::replay(&scene, &recording, &path).unwrap();
    assert!(!timeline.simulated);
    assert_eq!(timeline.frames.len(), recording.frames.len());
    for ((f, r), e_sim) in timeline.frames.iter().zip(&recording.frames).zip(energies) {
        assert_eq!(f.t, r.t);
        let (b, s) = (&f.bodies[0], &r.bodies[0]);
        assert!((b.position - s.position).length() < 1e-12);
        assert!(b.orientation.dot(s.orientation).abs() > 1.0 - 1e-12);
        assert_eq!(b.angular_velocity, s.angular_velocity);
        // The energy recomputed from the recording is the one the simulation had.
        let e = f.kinetic_energy + f.potential_energy;
        assert!((e - e_sim).abs() < 1e-9 * e_sim.abs(), "{e} vs {e_sim}");
    }
}

#[test]
fn replay_names_a_body_the_scene_lacks() {
    let scene = scene("projectile.toml");
    let text = format!("{}\n0,ghost,0,0,0,0,0,0,1,0,0,0,0,0,0\n", tumble_io::RECORDING_HEADER);
    let recording = Recording::from_reader(text.as_bytes(), "ghost.csv").unwrap();
    let err = Timeline::replay(&scene, &recording, Path::new("ghost.csv")).unwrap_err().to_string();
    assert!(
        err.contains("ghost.csv") && err.contains("body \"ghost\"") && err.contains("not in the scene"),
        "{err}"
    );
}

#[test]
fn a_world_with_a_joint_becomes_a_viewer_document() {
    let mut world = World::default();
    let slab = |kind, z| BodyDef {
        name: format!("slab{z}"),
        kind,
        position: DVec3::new(0.0, 0.0, z),
        shape: Some(Shape::Cuboid(Cuboid::new(DVec3::new(0.5, 0.1, 0.05)).unwrap())),
        ..Default::default()
    };
    let a = world.add_body(slab(tumble::BodyKind::Static, 1.0)).unwrap();
    let b = world.add_body(slab(tumble::BodyKind::Dynamic, 0.5)).unwrap();
    let hinge = JointDef::new(a, b, DVec3::new(0.5, 0.0, 0.75), JointKind::Hinge(HingeJoint::default()))
        .named("door")
        .with_axis(DVec3::Y);
    world.add_joint(hinge).unwrap();
    let mut recorder = TimelineRecorder::new(&world, "door");
    recorder.record(&world);
    for _ in 0..30 {
        world.step(1.0 / 60.0).unwrap();
        recorder.record(&world);
    }
    let timeline = recorder.finish();
    assert_eq!(timeline.joints.len(), 1);
    assert_eq!((timeline.joints[0].body_a, timeline.joints[0].body_b), (0, 1));

    let doc = ViewerDoc::from_timeline(&timeline, "door");
    let json: serde_json::Value = serde_json::from_str(&doc.to_json()).unwrap();
    assert_eq!(json["format"], "tumble-viewer-1");
    assert_eq!(json["joints"][0]["name"], "door");
    assert_eq!(json["joints"][0]["kind"], "hinge");
    assert_eq!(json["bodies"].as_array().unwrap().len(), 2);
    assert_eq!(json["bodies"][0]["indices"].as_array().unwrap().len(), 36);
    assert_eq!(json["pose"].as_array().unwrap().len(), 31);
    assert_eq!(json["pose"][0].as_array().unwrap().len(), 14, "7 numbers per body");
    // The swinging slab has moved by the end.
    assert_ne!(json["pose"][30][7], json["pose"][0][7]);

    let page = viewer_page(
        "<title>{{TITLE}}</title>{{DATA}}<script>{{SCRIPT}}</script>",
        "door",
        &doc.to_json(),
        "",
    )
    .unwrap();
    assert!(page.contains("\"tumble-viewer-1\""));
}
