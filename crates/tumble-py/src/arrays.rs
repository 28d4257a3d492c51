//! NumPy in and out: vectors, quaternions and matrices as float64 arrays, and the checked
//! conversion of any array-like (tuple, list, ndarray of any numeric dtype) into Rust values.
//!
//! Quaternions are (x, y, z, w) at every interface. Matrices are row-major `(3, 3)` arrays:
//! `m[i, j]` is row i, column j.

use numpy::{AllowTypeChange, PyArray1, PyArray2, PyArrayLikeDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;
use tumble::{DMat3, DQuat, DVec3};

use crate::errors::value_error;

/// Reads `obj` as a float64 array of the given shape (`None` = any length in that axis) and
/// returns its shape and elements in C order. The message names `what` and the shapes.
pub fn floats(
    obj: &Bound<'_, PyAny>,
    what: &str,
    shape: &[Option<usize>],
) -> PyResult<(Vec<usize>, Vec<f64>)> {
    let expected = || {
        let dims: Vec<String> = shape.iter().map(|d| d.map_or("N".to_string(), |n| n.to_string())).collect();
        format!("({}{})", dims.join(", "), if dims.len() == 1 { "," } else { "" })
    };
    let array = obj.extract::<PyArrayLikeDyn<'_, f64, AllowTypeChange>>().map_err(|e| {
        value_error(format!("{what} must be an array of numbers of shape {}: {e}", expected()))
    })?;
    let actual = array.shape().to_vec();
    let fits =
        actual.len() == shape.len() && actual.iter().zip(shape).all(|(&a, &d)| d.is_none_or(|d| a == d));
    if !fits {
        return Err(value_error(format!("{what} must have shape {}, got shape {actual:?}", expected())));
    }
    Ok((actual, array.as_array().iter().copied().collect()))
}

pub fn vec3(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<DVec3> {
    let (_, v) = floats(obj, what, &[Some(3)])?;
    Ok(DVec3::new(v[0], v[1], v[2]))
}

/// A quaternion given as (x, y, z, w).
pub fn quat(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<DQuat> {
    let (_, v) = floats(obj, what, &[Some(4)])?;
    Ok(DQuat::from_xyzw(v[0], v[1], v[2], v[3]))
}

/// An optional vector: `None` stays `None`.
pub fn opt_vec3(obj: Option<&Bound<'_, PyAny>>, what: &str) -> PyResult<Option<DVec3>> {
    obj.filter(|o| !o.is_none()).map(|o| vec3(o, what)).transpose()
}

/// A `(3, 3)` matrix, row-major.
pub fn mat3(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<DMat3> {
    let (_, v) = floats(obj, what, &[Some(3), Some(3)])?;
    // glam is column-major: transpose the rows read in C order.
    Ok(DMat3::from_cols_array(&[v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8]]).transpose())
}

/// Rows of `N` numbers, `(rows, N)`, each checked finite; the message names the first bad row.
pub fn finite_rows<const N: usize>(
    obj: &Bound<'_, PyAny>,
    what: &str,
    rows: usize,
) -> PyResult<Vec<[f64; N]>> {
    let (_, v) = floats(obj, what, &[Some(rows), Some(N)])?;
    let out: Vec<[f64; N]> = v.chunks_exact(N).map(|c| c.try_into().expect("chunks of N")).collect();
    if let Some(i) = out.iter().position(|row| !row.iter().all(|x| x.is_finite())) {
        return Err(value_error(format!("{what}[{i}] must be finite, got {:?}", out[i])));
    }
    Ok(out)
}

pub fn vec3_out(py: Python<'_>, v: DVec3) -> Bound<'_, PyArray1<f64>> {
    PyArray1::from_slice(py, &v.to_array())
}

/// (x, y, z, w).
pub fn quat_out(py: Python<'_>, q: DQuat) -> Bound<'_, PyArray1<f64>> {
    PyArray1::from_slice(py, &q.to_array())
}

/// Row-major `(3, 3)`.
pub fn mat3_out(py: Python<'_>, m: DMat3) -> PyResult<Bound<'_, PyArray2<f64>>> {
    let rows = m.transpose().to_cols_array();
    PyArray1::from_slice(py, &rows).reshape([3, 3])
}

/// `(rows, N)` float64 from rows of N numbers.
pub fn rows_out<'py, const N: usize>(
    py: Python<'py>,
    rows: &[[f64; N]],
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let flat: Vec<f64> = rows.iter().flatten().copied().collect();
    PyArray1::from_vec(py, flat).reshape([rows.len(), N])
}

// ---- the flat state arrays ------------------------------------------------------------------

/// One row per live body, in body-slot order (the order of `World.body_ids`).
pub fn state_rows<const N: usize>(
    world: &tumble::World,
    row: impl Fn(&tumble::Body) -> [f64; N],
) -> Vec<[f64; N]> {
    world.bodies().map(|(_, b)| row(b)).collect()
}

/// Writes one row per live body, atomically: the whole array is read and checked (shape, finite
/// values, `extra_check` per row) before the first body changes, so a bad array leaves the world
/// as it was. `apply` is a core setter and wakes the body.
pub fn set_state_rows<const N: usize>(
    world: &mut tumble::World,
    obj: &Bound<'_, PyAny>,
    what: &str,
    extra_check: impl Fn(&[f64; N]) -> Option<String>,
    apply: impl Fn(&mut tumble::World, tumble::BodyId, [f64; N]) -> Result<(), tumble::WorldError>,
) -> PyResult<()> {
    let rows = finite_rows::<N>(obj, what, world.body_count())?;
    if let Some((i, message)) = rows.iter().enumerate().find_map(|(i, r)| extra_check(r).map(|m| (i, m))) {
        return Err(value_error(format!("{what}[{i}] {message}")));
    }
    let ids: Vec<tumble::BodyId> = world.bodies().map(|(id, _)| id).collect();
    for (id, row) in ids.into_iter().zip(rows) {
        // Cannot fail: every id is live and every value was checked above.
        apply(world, id, row).map_err(crate::errors::world_error)?;
    }
    Ok(())
}

/// Orientation rows must be unit quaternions (as `add_body` requires); they are normalised.
pub fn unit_quat_check(q: &[f64; 4]) -> Option<String> {
    let len = DQuat::from_array(*q).length();
    ((len - 1.0).abs() > 1e-6)
        .then(|| format!("must be a unit quaternion (x, y, z, w), got {q:?} of length {len}"))
}
