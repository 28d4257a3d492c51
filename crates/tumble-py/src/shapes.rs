//! Shapes: `tumble.Shape` and one Python subclass per core shape. A shape object is immutable
//! and holds the core's `tumble::Shape`, validated by the core's constructors.
//!
//! A new core shape slots in as one more subclass here and one more arm in `shape_to_py`.

use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyList, PyTuple};
use tumble::{Capsule, Compound, CompoundChild, Cone, Cuboid, Cylinder, DQuat, Sphere, Transform, TriMesh};

use crate::arrays::{floats, quat, quat_out, rows_out, vec3, vec3_out};
use crate::errors::{value_error, IntoPyResult};
use crate::mass::MassProperties;

/// A shape in its own frame (the body frame once attached). Use one of the subclasses.
#[pyclass(subclass, frozen, module = "tumble")]
pub struct Shape(pub tumble::Shape);

#[pymethods]
impl Shape {
    /// Mass properties of the shape filled with uniform `density` (kg/m³), in the shape's frame.
    #[pyo3(signature = (density = 1000.0))]
    fn mass_properties(&self, density: f64) -> PyResult<MassProperties> {
        Ok(MassProperties(self.0.mass_properties(density).py()?))
    }

    /// The shape kind: "sphere", "box", "capsule", "cylinder", "cone", "hull", "mesh",
    /// "compound", "plane" or "heightfield".
    #[getter]
    fn kind(&self) -> &'static str {
        self.0.kind_name()
    }

    fn __repr__(&self) -> String {
        match &self.0 {
            tumble::Shape::Sphere(s) => format!("Sphere(radius={})", s.radius),
            tumble::Shape::Cuboid(s) => format!("Box(half_extents={:?})", s.half_extents.to_array()),
            tumble::Shape::Capsule(s) => {
                format!("Capsule(radius={}, half_height={})", s.radius, s.half_height)
            }
            tumble::Shape::Cylinder(s) => {
                format!("Cylinder(radius={}, half_height={})", s.radius, s.half_height)
            }
            tumble::Shape::Cone(s) => format!("Cone(radius={}, half_height={})", s.radius, s.half_height),
            tumble::Shape::TriMesh(m) => {
                format!("TriMesh({} vertices, {} triangles)", m.vertices().len(), m.triangles().len())
            }
            tumble::Shape::ConvexHull(h) => {
                format!("ConvexHull({} vertices, {} faces)", h.vertices().len(), h.faces().len())
            }
            tumble::Shape::Compound(c) => format!("Compound({} parts)", c.children().len()),
            tumble::Shape::Plane(p) => {
                format!("Plane(normal={:?}, offset={})", p.normal.to_array(), p.offset)
            }
            tumble::Shape::HeightField(h) => format!(
                "HeightField({} rows x {} cols, scale={:?})",
                h.rows(),
                h.cols(),
                h.scale().to_array()
            ),
        }
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other.cast::<Shape>().is_ok_and(|o| o.get().0 == self.0)
    }
}

/// The initializer of subclass `S` around a core shape (what `#[new]` returns).
fn init<S: pyo3::PyClass<BaseType = Shape>>(shape: tumble::Shape, marker: S) -> PyClassInitializer<S> {
    PyClassInitializer::from(Shape(shape)).add_subclass(marker)
}

/// Builds the Python object of a subclass `S` around a core shape.
fn new_shape<S: pyo3::PyClass<BaseType = Shape>>(
    py: Python<'_>,
    shape: tumble::Shape,
    marker: S,
) -> PyResult<Py<PyAny>> {
    Ok(Py::new(py, init(shape, marker))?.into_any())
}

/// The Python object (of the right subclass) for a core shape.
pub fn shape_to_py(py: Python<'_>, shape: &tumble::Shape) -> PyResult<Py<PyAny>> {
    let s = shape.clone();
    match shape {
        tumble::Shape::Sphere(_) => new_shape(py, s, SphereShape),
        tumble::Shape::Cuboid(_) => new_shape(py, s, BoxShape),
        tumble::Shape::Capsule(_) => new_shape(py, s, CapsuleShape),
        tumble::Shape::Cylinder(_) => new_shape(py, s, CylinderShape),
        tumble::Shape::Cone(_) => new_shape(py, s, ConeShape),
        tumble::Shape::TriMesh(_) => new_shape(py, s, TriMeshShape),
        tumble::Shape::ConvexHull(_) => new_shape(py, s, ConvexHullShape),
        tumble::Shape::Compound(_) => new_shape(py, s, CompoundShape),
        tumble::Shape::Plane(_) => new_shape(py, s, PlaneShape),
        tumble::Shape::HeightField(_) => new_shape(py, s, HeightFieldShape),
    }
}

/// A ball of `radius` centred on the origin.
#[pyclass(name = "Sphere", extends = Shape, frozen, module = "tumble")]
pub struct SphereShape;

#[pymethods]
impl SphereShape {
    #[new]
    fn new(radius: f64) -> PyResult<PyClassInitializer<Self>> {
        Ok(init(tumble::Shape::Sphere(Sphere::new(radius).py()?), SphereShape))
    }
    /// The radius, m.
    #[getter]
    fn radius(slf: PyRef<'_, Self>) -> f64 {
        match &slf.as_super().0 {
            tumble::Shape::Sphere(s) => s.radius,
            _ => unreachable!("a Sphere object holds a sphere"),
        }
    }
}

/// A box with `half_extents` (x, y, z), centred on the origin.
#[pyclass(name = "Box", extends = Shape, frozen, module = "tumble")]
pub struct BoxShape;

#[pymethods]
impl BoxShape {
    #[new]
    fn new(half_extents: &Bound<'_, PyAny>) -> PyResult<PyClassInitializer<Self>> {
        let he = vec3(half_extents, "half_extents")?;
        Ok(init(tumble::Shape::Cuboid(Cuboid::new(he).py()?), BoxShape))
    }
    /// Half extents (x, y, z), m.
    #[getter]
    fn half_extents<'py>(slf: PyRef<'py, Self>) -> Bound<'py, PyArray1<f64>> {
        match &slf.as_super().0 {
            tumble::Shape::Cuboid(s) => vec3_out(slf.py(), s.half_extents),
            _ => unreachable!("a Box object holds a box"),
        }
    }
}

/// Radius and half height of the shapes along local Z (capsule, cylinder, cone).
fn radius_half_height(shape: &tumble::Shape) -> (f64, f64) {
    match shape {
        tumble::Shape::Capsule(s) => (s.radius, s.half_height),
        tumble::Shape::Cylinder(s) => (s.radius, s.half_height),
        tumble::Shape::Cone(s) => (s.radius, s.half_height),
        _ => unreachable!("only axial shapes have a radius and half height"),
    }
}

macro_rules! axial_shape {
    ($rust:ident, $name:literal, $core:ident, $variant:ident, $doc:literal) => {
        #[doc = $doc]
        #[pyclass(name = $name, extends = Shape, frozen, module = "tumble")]
        pub struct $rust;

        #[pymethods]
        impl $rust {
            #[new]
            fn new(radius: f64, half_height: f64) -> PyResult<PyClassInitializer<Self>> {
                Ok(init(tumble::Shape::$variant($core::new(radius, half_height).py()?), $rust))
            }
            /// The radius, m.
            #[getter]
            fn radius(slf: PyRef<'_, Self>) -> f64 {
                radius_half_height(&slf.as_super().0).0
            }
            /// Half the length of the axis along local Z, m.
            #[getter]
            fn half_height(slf: PyRef<'_, Self>) -> f64 {
                radius_half_height(&slf.as_super().0).1
            }
        }
    };
}

axial_shape!(
    CapsuleShape,
    "Capsule",
    Capsule,
    Capsule,
    "A segment from (0, 0, -half_height) to (0, 0, +half_height) swept by a ball of `radius`."
);
axial_shape!(
    CylinderShape,
    "Cylinder",
    Cylinder,
    Cylinder,
    "A solid cylinder along local Z, from z = -half_height to z = +half_height."
);
axial_shape!(
    ConeShape,
    "Cone",
    Cone,
    Cone,
    "A solid cone along local Z: base disc at z = -half_height, apex at z = +half_height."
);

/// Reads `(M, 3)` vertex indices: whole numbers in u32 range (range against the vertex count is
/// the core's check).
pub fn triangles(obj: &Bound<'_, PyAny>) -> PyResult<Vec<[u32; 3]>> {
    let (_, v) = floats(obj, "triangles", &[None, Some(3)])?;
    let mut out = Vec::with_capacity(v.len() / 3);
    for (t, tri) in v.chunks_exact(3).enumerate() {
        let mut idx = [0u32; 3];
        for (k, &x) in tri.iter().enumerate() {
            if !(x.fract() == 0.0 && (0.0..=f64::from(u32::MAX)).contains(&x)) {
                return Err(value_error(format!(
                    "triangles[{t}][{k}] must be a non-negative whole vertex index, got {x}"
                )));
            }
            idx[k] = x as u32;
        }
        out.push(idx);
    }
    Ok(out)
}

/// Reads `(N, 3)` vertices (finiteness is the core's check, with its message).
pub fn vertices(obj: &Bound<'_, PyAny>) -> PyResult<Vec<tumble::DVec3>> {
    let (_, v) = floats(obj, "vertices", &[None, Some(3)])?;
    Ok(v.chunks_exact(3).map(|c| tumble::DVec3::new(c[0], c[1], c[2])).collect())
}

/// A closed, outward-wound triangle mesh: `vertices` (N, 3), `triangles` (M, 3) vertex indices.
#[pyclass(name = "TriMesh", extends = Shape, frozen, module = "tumble")]
pub struct TriMeshShape;

impl TriMeshShape {
    fn mesh<'a>(slf: &'a PyRef<'_, Self>) -> &'a TriMesh {
        match &slf.as_super().0 {
            tumble::Shape::TriMesh(m) => m,
            _ => unreachable!("a TriMesh object holds a mesh"),
        }
    }
}

#[pymethods]
impl TriMeshShape {
    #[new]
    fn new(vertices: &Bound<'_, PyAny>, triangles: &Bound<'_, PyAny>) -> PyResult<PyClassInitializer<Self>> {
        let mesh = TriMesh::new(self::vertices(vertices)?, self::triangles(triangles)?).py()?;
        Ok(init(tumble::Shape::TriMesh(mesh), TriMeshShape))
    }
    /// The mesh vertices, (N, 3).
    #[getter]
    fn vertices<'py>(slf: PyRef<'py, Self>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let rows: Vec<[f64; 3]> = Self::mesh(&slf).vertices().iter().map(|v| v.to_array()).collect();
        rows_out(slf.py(), &rows)
    }
    /// The triangles as vertex indices, (M, 3) uint32.
    #[getter]
    fn triangles<'py>(slf: PyRef<'py, Self>) -> PyResult<Bound<'py, PyArray2<u32>>> {
        let tris = Self::mesh(&slf).triangles();
        let flat: Vec<u32> = tris.iter().flatten().copied().collect();
        PyArray1::from_vec(slf.py(), flat).reshape([tris.len(), 3])
    }
}

/// The convex hull of `points` (N, 3): a convex polyhedron whose vertices are the extreme points.
#[pyclass(name = "ConvexHull", extends = Shape, frozen, module = "tumble")]
pub struct ConvexHullShape;

#[pymethods]
impl ConvexHullShape {
    #[new]
    fn new(points: &Bound<'_, PyAny>) -> PyResult<PyClassInitializer<Self>> {
        let (_, v) = floats(points, "points", &[None, Some(3)])?;
        let points: Vec<tumble::DVec3> =
            v.chunks_exact(3).map(|c| tumble::DVec3::new(c[0], c[1], c[2])).collect();
        let hull = tumble::ConvexHull::new(&points).map_err(|e| value_error(format!("convex hull: {e}")))?;
        Ok(init(tumble::Shape::ConvexHull(hull), ConvexHullShape))
    }
    /// The hull's vertices (the extreme points), (V, 3).
    #[getter]
    fn vertices<'py>(slf: PyRef<'py, Self>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let tumble::Shape::ConvexHull(h) = &slf.as_super().0 else {
            unreachable!("a ConvexHull object holds a hull")
        };
        let rows: Vec<[f64; 3]> = h.vertices().iter().map(|v| v.to_array()).collect();
        rows_out(slf.py(), &rows)
    }
}

/// Several shapes rigidly joined: `Compound([(shape, position, orientation), ...])`, each part
/// placed in the compound's frame; the orientation (x, y, z, w) may be left out.
#[pyclass(name = "Compound", extends = Shape, frozen, module = "tumble")]
pub struct CompoundShape;

#[pymethods]
impl CompoundShape {
    #[new]
    fn new(parts: &Bound<'_, PyAny>) -> PyResult<PyClassInitializer<Self>> {
        let mut children = Vec::new();
        for (i, part) in parts.try_iter()?.enumerate() {
            let part = part?;
            let items: Vec<Bound<'_, PyAny>> = part.try_iter()?.collect::<PyResult<_>>()?;
            let bad = || {
                value_error(format!("parts[{i}] must be (shape, position) or (shape, position, orientation)"))
            };
            if !(2..=3).contains(&items.len()) {
                return Err(bad());
            }
            let shape = items[0].cast::<Shape>().map_err(|_| bad())?.get().0.clone();
            let position = vec3(&items[1], &format!("parts[{i}] position"))?;
            let rotation = match items.get(2) {
                Some(q) => quat(q, &format!("parts[{i}] orientation"))?,
                None => DQuat::IDENTITY,
            };
            let len = rotation.length();
            if !len.is_finite() || (len - 1.0).abs() > 1e-6 {
                return Err(value_error(format!(
                    "parts[{i}] orientation must be a unit quaternion (x, y, z, w), got {:?}",
                    rotation.to_array()
                )));
            }
            children.push(CompoundChild { pose: Transform::new(position, rotation.normalize()), shape });
        }
        Ok(init(tumble::Shape::Compound(Compound::new(children).py()?), CompoundShape))
    }

    /// The parts as a list of (shape, position, orientation).
    #[getter]
    fn parts<'py>(slf: PyRef<'py, Self>) -> PyResult<Bound<'py, PyList>> {
        let py = slf.py();
        let tumble::Shape::Compound(c) = &slf.as_super().0 else {
            unreachable!("a Compound object holds a compound")
        };
        let items = c
            .children()
            .iter()
            .map(|child| {
                let shape = shape_to_py(py, &child.shape)?;
                let pos = vec3_out(py, child.pose.translation).into_any();
                let rot = quat_out(py, child.pose.rotation).into_any();
                PyTuple::new(py, [shape.into_bound(py), pos, rot])
            })
            .collect::<PyResult<Vec<_>>>()?;
        PyList::new(py, items)
    }
}

/// A core shape error (`tumble::ShapeError`) as `TumbleValueError`, with the core's message.
fn shape_error(e: tumble::ShapeError) -> PyErr {
    value_error(e.to_string())
}

/// The half-space `normal · x <= offset`: the solid lies below the plane whose outward unit
/// `normal` (x, y, z; normalised here, any finite non-zero length) points out of it, `offset`
/// metres from the origin along the normal. `Plane((0, 0, 1), 0.0)` is a floor at z = 0.
/// Static bodies only (a plane has no finite mass).
#[pyclass(name = "Plane", extends = Shape, frozen, module = "tumble")]
pub struct PlaneShape;

impl PlaneShape {
    fn plane<'a>(slf: &'a PyRef<'_, Self>) -> &'a tumble::Plane {
        match &slf.as_super().0 {
            tumble::Shape::Plane(p) => p,
            _ => unreachable!("a Plane object holds a plane"),
        }
    }
}

#[pymethods]
impl PlaneShape {
    #[new]
    #[pyo3(signature = (normal = None, offset = 0.0))]
    fn new(normal: Option<&Bound<'_, PyAny>>, offset: f64) -> PyResult<PyClassInitializer<Self>> {
        let n = match normal {
            Some(n) => vec3(n, "normal")?,
            None => tumble::DVec3::Z,
        };
        let plane = tumble::Plane::new(n, offset).map_err(shape_error)?;
        Ok(init(tumble::Shape::Plane(plane), PlaneShape))
    }
    /// The outward unit normal (x, y, z).
    #[getter]
    fn normal<'py>(slf: PyRef<'py, Self>) -> Bound<'py, PyArray1<f64>> {
        vec3_out(slf.py(), Self::plane(&slf).normal)
    }
    /// Signed distance of the surface from the origin along the normal, m.
    #[getter]
    fn offset(slf: PyRef<'_, Self>) -> f64 {
        Self::plane(&slf).offset
    }
}

/// Terrain from a grid of heights: `heights` a 2-D array-like (rows, cols), row-major; columns
/// run along local +X, rows along local +Y, the grid is centred on the origin in X and Y.
/// `scale` (x, y, z): spacing between columns, spacing between rows, and the factor applied to
/// the heights. Sample (row, col) sits at
/// ((col - (cols-1)/2)·sx, (row - (rows-1)/2)·sy, heights[row, col]·sz). Collides on its upper
/// side only. Static bodies only.
#[pyclass(name = "HeightField", extends = Shape, frozen, module = "tumble")]
pub struct HeightFieldShape;

impl HeightFieldShape {
    fn field<'a>(slf: &'a PyRef<'_, Self>) -> &'a tumble::HeightField {
        match &slf.as_super().0 {
            tumble::Shape::HeightField(h) => h,
            _ => unreachable!("a HeightField object holds a height field"),
        }
    }
}

#[pymethods]
impl HeightFieldShape {
    #[new]
    #[pyo3(signature = (heights, scale = None))]
    fn new(
        heights: &Bound<'_, PyAny>,
        scale: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<PyClassInitializer<Self>> {
        let (dims, flat) = floats(heights, "heights", &[None, None])?;
        let scale = match scale {
            Some(s) => vec3(s, "scale")?,
            None => tumble::DVec3::ONE,
        };
        let field = tumble::HeightField::new(flat, dims[0], dims[1], scale).map_err(shape_error)?;
        Ok(init(tumble::Shape::HeightField(field), HeightFieldShape))
    }
    /// The raw (unscaled) heights, (rows, cols).
    #[getter]
    fn heights<'py>(slf: PyRef<'py, Self>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let h = Self::field(&slf);
        PyArray1::from_slice(slf.py(), h.heights()).reshape([h.rows(), h.cols()])
    }
    /// The scale (x spacing, y spacing, height factor).
    #[getter]
    fn scale<'py>(slf: PyRef<'py, Self>) -> Bound<'py, PyArray1<f64>> {
        vec3_out(slf.py(), Self::field(&slf).scale())
    }
    /// Number of sample rows (along local Y).
    #[getter]
    fn rows(slf: PyRef<'_, Self>) -> usize {
        Self::field(&slf).rows()
    }
    /// Number of sample columns (along local X).
    #[getter]
    fn cols(slf: PyRef<'_, Self>) -> usize {
        Self::field(&slf).cols()
    }
}
