//! glTF export read back by an independent reader (the `gltf` crate): one node per body with its
//! mesh, and animation keyframes equal to the recording, converted to Y up (to f32 precision).

use std::path::Path;

use gltf::animation::util::ReadOutputs;
use tumble::{DQuat, DVec3};
use tumble_io::gltf::{glb_bytes, y_up_to_z_up};
use tumble_io::{Recording, RecordingWriter, Scene, Timeline};

fn scenes() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes"))
}

/// Runs `scene` and records every `every`-th step to a temporary CSV; returns it read back.
fn record(scene: &Scene, steps: u64, every: u64, dir: &Path) -> (Recording, std::path::PathBuf) {
    let path = dir.join("run.csv");
    let mut built = scene.build_world().unwrap();
    let mut out = RecordingWriter::create(&path, every).unwrap();
    out.write_frame(&built.world).unwrap();
    for _ in 0..steps {
        built.world.step(scene.dt).unwrap();
        out.record_step(&built.world).unwrap();
    }
    out.finish().unwrap();
    (Recording::read(&path).unwrap(), path)
}

#[test]
fn keyframes_equal_the_recording() {
    let dir = tempfile::tempdir().unwrap();
    let scene = Scene::from_file(scenes().join("projectile.toml")).unwrap();
    let (recording, path) = record(&scene, 240, 4, dir.path());
    let timeline = Timeline::replay(&scene, &recording, &path).unwrap();
    let bytes = glb_bytes(&timeline);

    let gltf = gltf::Gltf::from_slice(&bytes).expect("a valid GLB");
    let blob = gltf.blob.as_deref().expect("a BIN chunk");
    let nodes: Vec<_> = gltf.nodes().collect();
    assert_eq!(nodes.len(), 1);
    assert_eq!(nodes[0].name(), Some("brick"));
    let mesh = nodes[0].mesh().expect("the brick has a mesh");
    let primitive = mesh.primitives().next().unwrap();
    let reader = primitive.reader(|_| Some(blob));
    // A box: 24 vertices, 12 triangles; half extents (0.1, 0.05, 0.025) become (0.1, 0.025, 0.05).
    let positions: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
    assert_eq!(positions.len(), 24);
    assert_eq!(reader.read_indices().unwrap().into_u32().count(), 36);
    let max = positions.iter().fold([f32::MIN; 3], |m, p| [m[0].max(p[0]), m[1].max(p[1]), m[2].max(p[2])]);
    assert_eq!(max, [0.1, 0.025, 0.05]);

    let animation = gltf.animations().next().expect("an animation");
    let mut seen = 0;
    for channel in animation.channels() {
        assert_eq!(channel.target().node().index(), 0);
        let reader = channel.reader(|_| Some(blob));
        let times: Vec<f32> = reader.read_inputs().unwrap().collect();
        assert_eq!(times.len(), recording.frames.len(), "one key per recorded frame");
        for (t, frame) in times.iter().zip(&recording.frames) {
            assert_eq!(*t, frame.t as f32);
        }
        match reader.read_outputs().unwrap() {
            ReadOutputs::Translations(values) => {
                for (v, frame) in values.zip(&recording.frames) {
                    let p = y_up_to_z_up(DVec3::from(v.map(f64::from)));
                    let want = frame.bodies[0].position;
                    assert!(
                        (p - want).length() <= 1e-6 * want.length().max(1.0),
                        "{p} vs {want} at {}",
                        frame.t
                    );
                }
                seen += 1;
            }
            ReadOutputs::Rotations(values) => {
                for (q, frame) in values.into_f32().zip(&recording.frames) {
                    let v = y_up_to_z_up(DVec3::new(q[0].into(), q[1].into(), q[2].into()));
                    let got = DQuat::from_xyzw(v.x, v.y, v.z, q[3].into());
                    let want = frame.bodies[0].orientation;
                    // q and −q are one rotation; the export keeps neighbours in one hemisphere.
                    assert!(got.dot(want).abs() > 1.0 - 1e-6, "{got} vs {want} at {}", frame.t);
                }
                seen += 1;
            }
            _ => panic!("only translation and rotation channels"),
        }
    }
    assert_eq!(seen, 2);
}

#[test]
fn every_body_of_a_scene_becomes_a_node_with_a_mesh() {
    let scene = Scene::from_file(scenes().join("shapes.toml")).unwrap();
    let options = tumble_io::SimulateOptions { duration: Some(0.25), fps: 20.0 };
    let timeline = Timeline::simulate(&scene, &options).unwrap();
    let bytes = glb_bytes(&timeline);
    let gltf = gltf::Gltf::from_slice(&bytes).unwrap();
    let names: Vec<_> = gltf.nodes().map(|n| n.name().unwrap().to_string()).collect();
    let expected: Vec<_> = timeline.bodies.iter().map(|b| b.name.clone()).collect();
    assert_eq!(names, expected);
    assert!(gltf.nodes().all(|n| n.mesh().is_some()));
    // 0.25 s at 20 frames a second: frames at 0, 0.05, …, 0.25.
    let animation = gltf.animations().next().unwrap();
    assert_eq!(animation.channels().count(), 2 * names.len());
    assert_eq!(timeline.frames.len(), 6);
}
