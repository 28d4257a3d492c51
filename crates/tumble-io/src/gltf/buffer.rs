//! The binary buffer and the accessors into it. Every accessor gets its own buffer view (simple,
//! and what the validator likes best); all data is 4-byte floats or integers, so every view
//! starts 4-byte aligned.

use serde_json::{json, Value};

/// What a buffer view holds, for its `target`.
#[derive(Clone, Copy)]
pub enum ViewTarget {
    Vertices,
    Indices,
    /// Animation data: no target.
    Other,
}

#[derive(Default)]
pub struct BufferBuilder {
    pub bytes: Vec<u8>,
    pub views: Vec<Value>,
    pub accessors: Vec<Value>,
}

impl BufferBuilder {
    fn view(&mut self, data: &[u8], target: ViewTarget) -> usize {
        let offset = self.bytes.len();
        self.bytes.extend_from_slice(data);
        let mut view = json!({ "buffer": 0, "byteOffset": offset, "byteLength": data.len() });
        match target {
            ViewTarget::Vertices => view["target"] = json!(34962),
            ViewTarget::Indices => view["target"] = json!(34963),
            ViewTarget::Other => {}
        }
        self.views.push(view);
        self.views.len() - 1
    }

    /// Floats grouped `width` at a time (1 SCALAR, 3 VEC3, 4 VEC4); returns the accessor index.
    /// `with_bounds` adds `min`/`max` (required for positions and animation inputs).
    pub fn floats(&mut self, values: &[f32], width: usize, target: ViewTarget, with_bounds: bool) -> usize {
        let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        let view = self.view(&bytes, target);
        let kind = match width {
            1 => "SCALAR",
            2 => "VEC2",
            3 => "VEC3",
            _ => "VEC4",
        };
        let mut accessor =
            json!({ "bufferView": view, "componentType": 5126, "count": values.len() / width, "type": kind });
        if with_bounds {
            let mut lo = vec![f32::INFINITY; width];
            let mut hi = vec![f32::NEG_INFINITY; width];
            for item in values.chunks(width) {
                for k in 0..width {
                    lo[k] = lo[k].min(item[k]);
                    hi[k] = hi[k].max(item[k]);
                }
            }
            accessor["min"] = json!(lo);
            accessor["max"] = json!(hi);
        }
        self.accessors.push(accessor);
        self.accessors.len() - 1
    }

    /// Triangle indices (u32 SCALAR).
    pub fn indices(&mut self, values: &[u32]) -> usize {
        let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        let view = self.view(&bytes, ViewTarget::Indices);
        self.accessors.push(json!({
            "bufferView": view, "componentType": 5125, "count": values.len(), "type": "SCALAR"
        }));
        self.accessors.len() - 1
    }
}
