//! The data of the viewer page: a [`Timeline`] as one JSON document (shapes as triangle meshes in
//! body frames, then flat per-frame arrays), and the page itself ([`page`]) — the HTML template
//! with this document and the page's script put in, one self-contained file.
//!
//! The page's script and template live in `viewer/` at the top of the repository; the `tumble`
//! binary embeds them. Numbers go out as f32: millimetres at a kilometre, and half the bytes.

mod page;

pub use page::{viewer_page, PageError};

use serde::Serialize;
use tumble::{BodyKind, DQuat, DVec3, Transform};

use crate::tessellate::shape_mesh;
use crate::timeline::Timeline;

/// The version of the document's layout; the page checks it.
pub const VIEWER_FORMAT: &str = "tumble-viewer-1";

#[derive(Serialize)]
pub struct ViewerDoc {
    pub format: &'static str,
    pub title: String,
    pub gravity: [f32; 3],
    /// False when replayed from a recording: no contacts, sleep unknown.
    pub simulated: bool,
    pub bodies: Vec<ViewerBody>,
    pub joints: Vec<ViewerJoint>,
    /// Per frame, s.
    pub t: Vec<f32>,
    /// Per frame, per body: px, py, pz, qx, qy, qz, qw (body-frame origin and orientation).
    pub pose: Vec<Vec<f32>>,
    /// Per frame, per body: ωx, ωy, ωz (world, rad/s).
    pub omega: Vec<Vec<f32>>,
    /// Per frame, per body: L about the body's centre of mass (world, kg·m²/s).
    #[serde(rename = "L")]
    pub angular_momentum: Vec<Vec<f32>>,
    /// Per frame, per body: velocity of the centre of mass (m/s).
    pub v: Vec<Vec<f32>>,
    /// Per frame, per body: 1 awake, 0 asleep (or static).
    pub awake: Vec<Vec<u8>>,
    /// Per frame, per contact point: px, py, pz, nx, ny, nz.
    pub contacts: Vec<Vec<f32>>,
    /// Per frame, J.
    pub kinetic: Vec<f32>,
    pub potential: Vec<f32>,
    /// Per frame, total linear momentum (kg·m/s) and angular momentum about the system's centre
    /// of mass (kg·m²/s).
    pub momentum: Vec<[f32; 3]>,
    #[serde(rename = "angularMomentum")]
    pub total_angular_momentum: Vec<[f32; 3]>,
    #[serde(rename = "awakeCount")]
    pub awake_count: Vec<u32>,
}

#[derive(Serialize)]
pub struct ViewerBody {
    pub name: String,
    /// "dynamic", "static" or "kinematic".
    pub kind: &'static str,
    pub mass: f32,
    /// Centre of mass, body frame.
    pub com: [f32; 3],
    /// The shape's triangles in the body frame: flat xyz lists and triangle indices.
    pub positions: Vec<f32>,
    pub normals: Vec<f32>,
    pub indices: Vec<u32>,
}

#[derive(Serialize)]
pub struct ViewerJoint {
    pub name: String,
    pub kind: &'static str,
    pub a: usize,
    pub b: usize,
    /// The joint frame in each body's frame: px, py, pz, qx, qy, qz, qw (Z along the axis).
    #[serde(rename = "frameA")]
    pub frame_a: [f32; 7],
    #[serde(rename = "frameB")]
    pub frame_b: [f32; 7],
}

fn v3(v: DVec3) -> [f32; 3] {
    v.as_vec3().to_array()
}

fn q4(q: DQuat) -> [f32; 4] {
    [q.x as f32, q.y as f32, q.z as f32, q.w as f32]
}

fn pose7(t: &Transform) -> [f32; 7] {
    let [x, y, z] = v3(t.translation);
    let [qx, qy, qz, qw] = q4(t.rotation);
    [x, y, z, qx, qy, qz, qw]
}

impl ViewerDoc {
    pub fn from_timeline(timeline: &Timeline, title: &str) -> ViewerDoc {
        let bodies = timeline
            .bodies
            .iter()
            .map(|b| {
                let mesh = b.shape.as_ref().map(shape_mesh).unwrap_or_default();
                ViewerBody {
                    name: b.name.clone(),
                    kind: match b.kind {
                        BodyKind::Dynamic => "dynamic",
                        BodyKind::Static => "static",
                        BodyKind::Kinematic => "kinematic",
                    },
                    mass: b.mass as f32,
                    com: v3(b.com_local),
                    positions: mesh.positions.concat(),
                    normals: mesh.normals.concat(),
                    indices: mesh.indices,
                }
            })
            .collect();
        let joints = timeline
            .joints
            .iter()
            .map(|j| ViewerJoint {
                name: j.name.clone(),
                kind: j.kind,
                a: j.body_a,
                b: j.body_b,
                frame_a: pose7(&j.frame_a_local),
                frame_b: pose7(&j.frame_b_local),
            })
            .collect();
        let frames = &timeline.frames;
        let per_body = |f: &dyn Fn(&crate::timeline::BodyFrame) -> Vec<f32>| -> Vec<Vec<f32>> {
            frames.iter().map(|fr| fr.bodies.iter().flat_map(f).collect()).collect()
        };
        ViewerDoc {
            format: VIEWER_FORMAT,
            title: title.to_string(),
            gravity: v3(timeline.gravity),
            simulated: timeline.simulated,
            bodies,
            joints,
            t: frames.iter().map(|f| f.t as f32).collect(),
            pose: per_body(&|b| {
                let mut p = v3(b.position).to_vec();
                p.extend(q4(b.orientation));
                p
            }),
            omega: per_body(&|b| v3(b.angular_velocity).to_vec()),
            angular_momentum: per_body(&|b| v3(b.angular_momentum).to_vec()),
            v: per_body(&|b| v3(b.linear_velocity).to_vec()),
            awake: frames.iter().map(|f| f.bodies.iter().map(|b| u8::from(b.awake)).collect()).collect(),
            contacts: frames
                .iter()
                .map(|f| f.contacts.iter().flat_map(|c| [v3(c.point), v3(c.normal)].concat()).collect())
                .collect(),
            kinetic: frames.iter().map(|f| f.kinetic_energy as f32).collect(),
            potential: frames.iter().map(|f| f.potential_energy as f32).collect(),
            momentum: frames.iter().map(|f| v3(f.linear_momentum)).collect(),
            total_angular_momentum: frames.iter().map(|f| v3(f.angular_momentum)).collect(),
            awake_count: frames.iter().map(|f| f.awake as u32).collect(),
        }
    }

    /// The document as JSON, safe to put inside an HTML `<script>` element (`</` is escaped).
    pub fn to_json(&self) -> String {
        let text = serde_json::to_string(self).expect("the viewer document is plain data");
        text.replace("</", "<\\/")
    }
}
