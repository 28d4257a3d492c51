//! # tumble-io
//!
//! Tumble's files: scene TOML in (checked, with errors that name the file, line and key),
//! triangle meshes in (OBJ, STL), recordings out and back in (CSV), and the pictures of a run:
//! a [`Timeline`] (simulated or replayed), its viewer page ([`viewer`]) and its glTF animation
//! ([`gltf`]), with shapes as triangles from [`tessellate`].
//!
//! ```no_run
//! use tumble_io::{Scene, RecordingWriter};
//! let scene = Scene::from_file("scenes/demo.toml")?;
//! let mut built = scene.build_world()?;
//! let mut out = RecordingWriter::create("out/demo.csv", 1)?;
//! out.write_frame(&built.world)?;
//! for _ in 0..10 {
//!     built.world.step(built.dt)?;
//!     out.record_step(&built.world)?;
//! }
//! # Ok::<(), tumble_io::IoError>(())
//! ```

pub mod error;
pub mod gltf;
pub mod mesh;
pub mod recording;
pub mod scene;
pub mod tessellate;
pub mod timeline;
pub mod viewer;

pub use error::IoError;
pub use mesh::{load_mesh, load_obj, load_stl, obj_from_str, stl_from_bytes};
pub use recording::{BodySample, Frame, Recording, RecordingWriter, RECORDING_HEADER};
pub use scene::{Scene, SceneBody, SceneJoint, SceneWorld};
pub use timeline::{SimulateOptions, Timeline, TimelineRecorder};
