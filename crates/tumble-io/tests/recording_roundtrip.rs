//! Recordings read back bit for bit, frames are whole, and bad files are errors with a line.

use tumble::{BodyDef, Cuboid, DQuat, DVec3, Shape, Sphere, World, WorldDef};
use tumble_io::{Recording, RecordingWriter, RECORDING_HEADER};

fn world() -> World {
    let mut world = World::new(WorldDef::default()).unwrap();
    world
        .add_body(BodyDef {
            name: "ball, \"quoted\"".into(),
            shape: Some(Shape::Sphere(Sphere::new(0.3).unwrap())),
            position: DVec3::new(0.1, -2.0, 3.0),
            linear_velocity: DVec3::new(1.0 / 3.0, 0.0, 2.0),
            angular_velocity: DVec3::new(0.7, -1e-9, 4.0),
            ..Default::default()
        })
        .unwrap();
    world
        .add_body(BodyDef {
            name: "brick".into(),
            shape: Some(Shape::Cuboid(Cuboid::new(DVec3::new(0.1, 0.2, 0.3)).unwrap())),
            orientation: DQuat::from_rotation_x(0.3),
            angular_velocity: DVec3::new(1.0, 6.0, 2.0),
            ..Default::default()
        })
        .unwrap();
    world
}

#[test]
fn write_then_read_back_is_bit_for_bit() {
    let mut world = world();
    let mut writer = RecordingWriter::new(Vec::new(), 3, "memory.csv").unwrap();
    let mut expected = Vec::new();
    let snapshot = |w: &World| -> Vec<(f64, String, DVec3, DQuat, DVec3, DVec3)> {
        w.bodies()
            .map(|(_, b)| {
                (
                    w.time(),
                    b.name().to_string(),
                    b.position(),
                    b.orientation(),
                    b.linear_velocity(),
                    b.angular_velocity(),
                )
            })
            .collect()
    };
    writer.write_frame(&world).unwrap();
    expected.push(snapshot(&world));
    for _ in 0..10 {
        world.step(1.0 / 240.0).unwrap();
        if writer.record_step(&world).unwrap() {
            expected.push(snapshot(&world));
        }
    }
    assert_eq!(writer.frames_written(), 4, "initial frame plus steps 3, 6, 9");
    let bytes = writer.finish().unwrap();
    let text = String::from_utf8(bytes).unwrap();
    assert_eq!(text.lines().next().unwrap(), RECORDING_HEADER);
    assert_eq!(text.lines().count(), 1 + 4 * 2);

    let recording = Recording::from_reader(text.as_bytes(), "memory.csv").unwrap();
    assert_eq!(recording.frames.len(), expected.len());
    for (frame, bodies) in recording.frames.iter().zip(&expected) {
        assert_eq!(frame.bodies.len(), bodies.len());
        for (sample, (t, name, p, q, v, w)) in frame.bodies.iter().zip(bodies) {
            assert_eq!(frame.t.to_bits(), t.to_bits());
            assert_eq!(&sample.name, name);
            for (a, b) in [(sample.position, *p), (sample.linear_velocity, *v), (sample.angular_velocity, *w)]
            {
                assert_eq!(a.to_array().map(f64::to_bits), b.to_array().map(f64::to_bits));
            }
            assert_eq!(sample.orientation.to_array().map(f64::to_bits), q.to_array().map(f64::to_bits));
        }
    }
    assert_eq!(recording.body_track("brick").count(), 4);
}

#[test]
fn file_recording_has_the_exact_header_and_whole_frames() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("nested/folder/run.csv");
    let mut world = world();
    let mut writer = RecordingWriter::create(&path, 1).unwrap();
    writer.write_frame(&world).unwrap();
    world.step(0.01).unwrap();
    writer.record_step(&world).unwrap();
    // Not finished: what is on disk already must be whole frames (flushed per frame).
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.starts_with(&format!("{RECORDING_HEADER}\n")));
    assert_eq!(text.lines().count(), 1 + 2 * 2);
    assert!(text.ends_with('\n'));
    drop(writer);
    assert_eq!(Recording::read(&path).unwrap().frames.len(), 2);
}

#[test]
fn resume_cuts_back_to_the_checkpoint_and_continues_byte_for_byte() {
    let dir = tempfile::tempdir().unwrap();
    let (straight, resumed) = (dir.path().join("straight.csv"), dir.path().join("resumed.csv"));
    let mut world = world();
    let mut writer = RecordingWriter::create(&straight, 1).unwrap();
    writer.write_frame(&world).unwrap();
    let mut at_checkpoint = None;
    for step in 0..4 {
        world.step(0.01).unwrap();
        writer.record_step(&world).unwrap();
        if step == 1 {
            at_checkpoint = Some((world.clone(), writer.frames_written(), writer.bytes_written()));
        }
    }
    drop(writer);
    let (mut world, frames, bytes) = at_checkpoint.unwrap();
    assert_eq!(bytes, std::fs::read(&straight).unwrap()[..bytes as usize].len() as u64);
    // What a killed run left: the frames after the checkpoint and part of one more line.
    let mut left = std::fs::read(&straight).unwrap();
    left.extend_from_slice(b"0.05,brick,1.0");
    std::fs::write(&resumed, left).unwrap();
    let mut writer = RecordingWriter::resume(&resumed, 1, frames, bytes).unwrap();
    for _ in 2..4 {
        world.step(0.01).unwrap();
        writer.record_step(&world).unwrap();
    }
    assert_eq!(writer.frames_written(), 5);
    drop(writer);
    assert_eq!(std::fs::read(&resumed).unwrap(), std::fs::read(&straight).unwrap());
    let short = RecordingWriter::resume(dir.path().join("straight.csv"), 1, 99, 1 << 30).err().unwrap();
    assert!(short.to_string().contains("straight.csv"), "{short}");
}

#[test]
fn bad_recordings_are_errors_with_a_line() {
    let bad_header = Recording::from_reader("t,body,x\n".as_bytes(), "r.csv").unwrap_err().to_string();
    assert!(bad_header.starts_with("r.csv:1: not a recording"), "{bad_header}");
    let text =
        format!("{RECORDING_HEADER}\n0.0,a,1,2,3,0,0,0,1,0,0,0,0,0,0\n0.0,b,1,2,oops,0,0,0,1,0,0,0,0,0,0\n");
    let bad_number = Recording::from_reader(text.as_bytes(), "r.csv").unwrap_err().to_string();
    assert!(bad_number.starts_with("r.csv:3: column pz"), "{bad_number}");
    let text = format!("{RECORDING_HEADER}\n0.0,a,1,2,3\n");
    let short = Recording::from_reader(text.as_bytes(), "r.csv").unwrap_err().to_string();
    assert!(short.starts_with("r.csv:2: expected 15 columns"), "{short}");
    let empty = Recording::from_reader("".as_bytes(), "r.csv").unwrap_err().to_string();
    assert!(empty.starts_with("r.csv:1: empty file"), "{empty}");
}

#[test]
fn every_zero_is_refused() {
    assert!(RecordingWriter::new(Vec::new(), 0, "x.csv").is_err());
}
