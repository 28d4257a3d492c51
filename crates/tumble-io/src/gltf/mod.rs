//! glTF 2.0 export: a [`Timeline`] as one binary glTF file (`.glb`) that plays in Blender,
//! three.js and any glTF viewer. One node per body, named after it, with its shape's mesh and a
//! material; one animation with a translation and a rotation channel per body (LINEAR, one key
//! per frame).
//!
//! glTF is Y up, Tumble Z up: every position, direction and quaternion vector part is mapped by
//! the rotation of −90° about X, `(x, y, z) → (x, z, −y)` ([`z_up_to_y_up`]); a quaternion's
//! scalar part is unchanged (the rotation `C R C⁻¹` has the same angle about the mapped axis).
//! Mesh vertices are in the body frame, mapped the same way, so a node's transform is the body
//! pose. Consecutive keys' quaternions are kept in one hemisphere (q and −q are the same rotation)
//! so interpolating players never turn the long way round.

mod buffer;
mod glb;

use std::path::Path;

use serde_json::{json, Value};
use tumble::{DQuat, DVec3};

use crate::error::IoError;
use crate::tessellate::shape_mesh;
use crate::timeline::Timeline;
use buffer::{BufferBuilder, ViewTarget};

/// Tumble's Z-up coordinates to glTF's Y-up ones.
pub fn z_up_to_y_up(v: DVec3) -> DVec3 {
    DVec3::new(v.x, v.z, -v.y)
}

/// glTF's Y-up coordinates back to Tumble's Z-up ones.
pub fn y_up_to_z_up(v: DVec3) -> DVec3 {
    DVec3::new(v.x, -v.z, v.y)
}

/// A Z-up orientation as the glTF (Y-up) one, `[x, y, z, w]`.
pub fn quat_z_up_to_y_up(q: DQuat) -> [f64; 4] {
    let v = z_up_to_y_up(DVec3::new(q.x, q.y, q.z));
    [v.x, v.y, v.z, q.w]
}

/// Colours of the dynamic bodies, in order (linear RGB); static bodies are grey.
const PALETTE: [[f32; 3]; 6] = [
    [0.80, 0.33, 0.10],
    [0.12, 0.40, 0.75],
    [0.20, 0.60, 0.25],
    [0.70, 0.55, 0.08],
    [0.50, 0.25, 0.65],
    [0.10, 0.60, 0.60],
];

/// The timeline as GLB bytes.
pub fn glb_bytes(timeline: &Timeline) -> Vec<u8> {
    let mut buf = BufferBuilder::default();
    let mut nodes = Vec::new();
    let mut meshes = Vec::new();
    let mut materials = Vec::new();
    let mut channels = Vec::new();
    let mut samplers = Vec::new();

    let times: Vec<f32> = timeline.frames.iter().map(|f| f.t as f32).collect();
    let animated = times.len() >= 2;
    let time_accessor = animated.then(|| buf.floats(&times, 1, ViewTarget::Other, true));

    let mut dynamic_count = 0;
    for (i, body) in timeline.bodies.iter().enumerate() {
        let mut node = json!({ "name": body.name });
        if let Some(shape) = &body.shape {
            let mesh = shape_mesh(shape);
            if !mesh.indices.is_empty() {
                let convert = |list: &[[f32; 3]]| -> Vec<f32> {
                    list.iter()
                        .flat_map(|p| z_up_to_y_up(DVec3::from(p.map(f64::from))).as_vec3().to_array())
                        .collect()
                };
                let position = buf.floats(&convert(&mesh.positions), 3, ViewTarget::Vertices, true);
                let normal = buf.floats(&convert(&mesh.normals), 3, ViewTarget::Vertices, false);
                let indices = buf.indices(&mesh.indices);
                let color = if body.kind == tumble::BodyKind::Static {
                    [0.45, 0.45, 0.45]
                } else {
                    dynamic_count += 1;
                    PALETTE[(dynamic_count - 1) % PALETTE.len()]
                };
                materials.push(json!({
                    "name": body.name,
                    "pbrMetallicRoughness": {
                        "baseColorFactor": [color[0], color[1], color[2], 1.0],
                        "metallicFactor": 0.0,
                        "roughnessFactor": 0.6
                    }
                }));
                meshes.push(json!({
                    "name": body.name,
                    "primitives": [{
                        "attributes": { "POSITION": position, "NORMAL": normal },
                        "indices": indices,
                        "material": materials.len() - 1
                    }]
                }));
                node["mesh"] = json!(meshes.len() - 1);
            }
        }
        if let Some(first) = timeline.frames.first().and_then(|f| f.bodies.get(i)) {
            node["translation"] = json!(z_up_to_y_up(first.position).as_vec3().to_array());
            node["rotation"] = json!(quat_z_up_to_y_up(first.orientation.normalize()).map(|x| x as f32));
        }
        if let Some(input) = time_accessor {
            let mut translations = Vec::with_capacity(times.len() * 3);
            let mut rotations = Vec::with_capacity(times.len() * 4);
            let mut previous: Option<DQuat> = None;
            for frame in &timeline.frames {
                let b = &frame.bodies[i];
                translations.extend(z_up_to_y_up(b.position).as_vec3().to_array());
                let mut q = b.orientation.normalize();
                if previous.is_some_and(|p| p.dot(q) < 0.0) {
                    q = -q;
                }
                previous = Some(q);
                rotations.extend(quat_z_up_to_y_up(q).map(|x| x as f32));
            }
            for (path, values, width) in [("translation", translations, 3), ("rotation", rotations, 4)] {
                let output = buf.floats(&values, width, ViewTarget::Other, false);
                samplers.push(json!({ "input": input, "output": output, "interpolation": "LINEAR" }));
                channels.push(
                    json!({ "sampler": samplers.len() - 1, "target": { "node": nodes.len(), "path": path } }),
                );
            }
        }
        nodes.push(node);
    }

    let name = timeline.source.file_stem().map_or("tumble".into(), |s| s.to_string_lossy().into_owned());
    let mut doc = json!({
        "asset": { "version": "2.0", "generator": concat!("Tumble ", env!("CARGO_PKG_VERSION")) },
        "scene": 0,
        "scenes": [{ "name": name, "nodes": (0..nodes.len()).collect::<Vec<_>>() }],
        "nodes": nodes,
    });
    let put = |doc: &mut Value, key: &str, list: Vec<Value>| {
        if !list.is_empty() {
            doc[key] = Value::Array(list);
        }
    };
    put(&mut doc, "meshes", meshes);
    put(&mut doc, "materials", materials);
    if !channels.is_empty() {
        doc["animations"] = json!([{ "name": name, "channels": channels, "samplers": samplers }]);
    }
    put(&mut doc, "accessors", std::mem::take(&mut buf.accessors));
    put(&mut doc, "bufferViews", std::mem::take(&mut buf.views));
    if !buf.bytes.is_empty() {
        doc["buffers"] = json!([{ "byteLength": buf.bytes.len() }]);
    }
    glb::pack(&doc.to_string(), buf.bytes)
}

/// Writes the timeline to `path` as GLB, creating its folder if needed.
pub fn write_glb(timeline: &Timeline, path: impl AsRef<Path>) -> Result<(), IoError> {
    let path = path.as_ref();
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| IoError::file(dir, e))?;
    }
    std::fs::write(path, glb_bytes(timeline)).map_err(|e| IoError::file(path, e))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axis_mapping_is_a_proper_rotation_and_inverts() {
        let v = DVec3::new(1.0, 2.0, 3.0);
        assert_eq!(z_up_to_y_up(v), DVec3::new(1.0, 3.0, -2.0));
        assert_eq!(y_up_to_z_up(z_up_to_y_up(v)), v);
        // Z up becomes Y up; X stays; handedness is kept (x × y = z maps to x' × y' = z').
        assert_eq!(z_up_to_y_up(DVec3::Z), DVec3::Y);
        let (x, y) = (z_up_to_y_up(DVec3::X), z_up_to_y_up(DVec3::Y));
        assert_eq!(x.cross(y), z_up_to_y_up(DVec3::Z));
    }

    #[test]
    fn rotations_map_by_conjugation() {
        let q = DQuat::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), 0.7);
        let [x, y, z, w] = quat_z_up_to_y_up(q);
        let q_gltf = DQuat::from_xyzw(x, y, z, w);
        let v = DVec3::new(-0.3, 0.5, 2.0);
        let a = z_up_to_y_up(q * v);
        let b = q_gltf * z_up_to_y_up(v);
        assert!((a - b).length() < 1e-12);
    }
}
