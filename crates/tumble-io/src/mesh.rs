//! Triangle meshes from files: Wavefront OBJ and STL (ASCII or binary) into a validated
//! [`TriMesh`].
//!
//! Both formats are read into one vertex list and one triangle list, then vertices at exactly the
//! same position are welded. STL needs this because it stores every triangle with its own three
//! corners (no shared vertices at all); OBJ needs it because an OBJ split into groups or objects
//! comes out of the parser as separate meshes that repeat their shared vertices. Welding is exact
//! (bit-equal coordinates, with −0 = +0): a tolerance would silently change the shape, while a
//! file that only *almost* closes is better reported as open. `TriMesh::new` then checks that the
//! result is closed, consistently wound and outward.

use std::collections::HashMap;
use std::io::{BufReader, Cursor};
use std::path::Path;

use tumble::{DVec3, TriMesh};

use crate::error::IoError;

/// Loads an `.obj` or `.stl` file (by extension, case-insensitive).
pub fn load_mesh(path: &Path) -> Result<TriMesh, IoError> {
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("obj") => load_obj(path),
        Some("stl") => load_stl(path),
        _ => Err(IoError::UnsupportedFormat { path: path.to_owned(), expected: ".obj or .stl" }),
    }
}

/// Loads a Wavefront OBJ file. Faces with more than three corners are split into triangle fans;
/// points, lines, normals, texture coordinates and materials are ignored.
pub fn load_obj(path: &Path) -> Result<TriMesh, IoError> {
    let text = std::fs::read_to_string(path).map_err(|e| IoError::file(path, e))?;
    obj_from_str(&text, path)
}

/// Parses OBJ text; `path` is only used in messages.
pub fn obj_from_str(text: &str, path: &Path) -> Result<TriMesh, IoError> {
    // `..Default::default()` covers the fields that tobj's optional features add, in case another
    // crate in the build turns them on.
    #[allow(clippy::needless_update)]
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
        ..Default::default()
    };
    // Materials cannot change the solid, so the material loader refuses every .mtl file rather
    // than touching the disk; tobj then still returns the geometry.
    let (models, _materials) = tobj::load_obj_buf(&mut BufReader::new(text.as_bytes()), &options, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .map_err(|e| mesh_error(path, format!("could not parse OBJ: {e}")))?;

    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    for model in &models {
        let mesh = &model.mesh;
        let base = vertices.len();
        vertices.extend(mesh.positions.chunks_exact(3).map(|p| DVec3::new(p[0], p[1], p[2])));
        for t in mesh.indices.chunks_exact(3) {
            triangles.push([0, 1, 2].map(|k| (base + t[k] as usize) as u32));
        }
    }
    finish(path, vertices, triangles)
}

/// Loads an STL file, ASCII or binary (detected from the content).
pub fn load_stl(path: &Path) -> Result<TriMesh, IoError> {
    let bytes = std::fs::read(path).map_err(|e| IoError::file(path, e))?;
    stl_from_bytes(&bytes, path)
}

/// Parses STL bytes (ASCII or binary); `path` is only used in messages.
pub fn stl_from_bytes(bytes: &[u8], path: &Path) -> Result<TriMesh, IoError> {
    let mut reader = Cursor::new(bytes);
    let triangles_in = stl_io::create_stl_reader(&mut reader)
        .map_err(|e| mesh_error(path, format!("could not read STL: {e}")))?;
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    for (i, triangle) in triangles_in.enumerate() {
        let triangle =
            triangle.map_err(|e| mesh_error(path, format!("could not read STL triangle {i}: {e}")))?;
        let base = vertices.len() as u32;
        // STL stores f32; widening to f64 is exact, so welding below sees the file's values.
        vertices.extend(triangle.vertices.iter().map(|v| DVec3::new(v[0].into(), v[1].into(), v[2].into())));
        triangles.push([base, base + 1, base + 2]);
    }
    finish(path, vertices, triangles)
}

/// Welds and validates.
fn finish(path: &Path, vertices: Vec<DVec3>, triangles: Vec<[u32; 3]>) -> Result<TriMesh, IoError> {
    if vertices.len() > u32::MAX as usize {
        return Err(mesh_error(path, format!("too many vertices ({})", vertices.len())));
    }
    let (vertices, triangles) = weld_exact(&vertices, &triangles);
    TriMesh::new(vertices, triangles).map_err(|e| mesh_error(path, e.to_string()))
}

/// Merges vertices with bit-identical coordinates (treating −0 as +0), keeping first-seen order so
/// the result is deterministic.
pub fn weld_exact(vertices: &[DVec3], triangles: &[[u32; 3]]) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    // `+ 0.0` turns −0.0 into +0.0, so the two zeros hash alike.
    let key = |v: DVec3| [(v.x + 0.0).to_bits(), (v.y + 0.0).to_bits(), (v.z + 0.0).to_bits()];
    let mut index_of: HashMap<[u64; 3], u32> = HashMap::with_capacity(vertices.len());
    let mut welded = Vec::with_capacity(vertices.len());
    let remap: Vec<u32> = vertices
        .iter()
        .map(|&v| {
            *index_of.entry(key(v)).or_insert_with(|| {
                welded.push(v);
                (welded.len() - 1) as u32
            })
        })
        .collect();
    // An index past the end is left out of range on purpose: TriMesh::new reports it.
    let triangles =
        triangles.iter().map(|t| t.map(|i| remap.get(i as usize).copied().unwrap_or(u32::MAX))).collect();
    (welded, triangles)
}

fn mesh_error(path: &Path, message: String) -> IoError {
    IoError::Mesh { path: path.to_owned(), message }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weld_merges_equal_positions_and_signed_zeros() {
        let v = [DVec3::new(0.0, 1.0, 2.0), DVec3::new(-0.0, 1.0, 2.0), DVec3::new(1.0, 1.0, 2.0)];
        let (w, t) = weld_exact(&v, &[[0, 1, 2]]);
        assert_eq!(w.len(), 2);
        assert_eq!(t, vec![[0, 0, 1]]);
    }
}
