//! A height field: terrain given as a grid of heights. Static bodies only.
//!
//! Layout: `rows × cols` samples, row-major (`heights[row * cols + col]`). Columns run along local
//! +X, rows along local +Y, and the grid is **centred** on the local origin in X and Y: sample
//! `(row, col)` sits at
//!
//! ```text
//! x = (col − (cols − 1) / 2) · scale.x,   y = (row − (rows − 1) / 2) · scale.y,
//! z = heights[row · cols + col] · scale.z
//! ```
//!
//! Each cell `(row, col)` (row < rows − 1, col < cols − 1) is split along the diagonal from
//! `(row, col)` to `(row + 1, col + 1)` into two triangles, numbered `2·cell` and `2·cell + 1`
//! with `cell = row · (cols − 1) + col`; both face +Z (wind counter-clockwise seen from above).
//! Collision is with the upper side only: a body whose centre is below a triangle's plane does not
//! collide with it.

use super::ShapeError;
use crate::collision::aabb::Aabb;
use crate::collision::triangle::ray_triangle;
use crate::math::DVec3;

#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct HeightField {
    heights: Vec<f64>,
    rows: usize,
    cols: usize,
    scale: DVec3,
    /// Lowest and highest scaled height.
    z_range: (f64, f64),
}

impl HeightField {
    /// A height field of `rows × cols` samples (row-major `heights`) with sample spacing
    /// `scale.x` (between columns), `scale.y` (between rows) and heights multiplied by `scale.z`.
    pub fn new(heights: Vec<f64>, rows: usize, cols: usize, scale: DVec3) -> Result<Self, ShapeError> {
        if rows < 2 || cols < 2 {
            return Err(ShapeError::HeightFieldTooSmall { rows, cols });
        }
        if heights.len() != rows * cols {
            return Err(ShapeError::HeightFieldSize { rows, cols, len: heights.len() });
        }
        if let Some(i) = heights.iter().position(|h| !h.is_finite()) {
            return Err(ShapeError::NonFiniteHeight { row: i / cols, col: i % cols, value: heights[i] });
        }
        for (what, value) in [("x", scale.x), ("y", scale.y), ("z", scale.z)] {
            if !(value.is_finite() && value > 0.0) {
                return Err(ShapeError::BadScale { what, value });
            }
        }
        let (lo, hi) =
            heights.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &v| (l.min(v), h.max(v)));
        Ok(Self { heights, rows, cols, scale, z_range: (lo * scale.z, hi * scale.z) })
    }

    pub fn rows(&self) -> usize {
        self.rows
    }

    pub fn cols(&self) -> usize {
        self.cols
    }

    pub fn scale(&self) -> DVec3 {
        self.scale
    }

    /// The raw (unscaled) samples, row-major.
    pub fn heights(&self) -> &[f64] {
        &self.heights
    }

    /// Local x of column 0 and y of row 0 (the grid's lower corner).
    #[inline]
    pub fn origin_xy(&self) -> (f64, f64) {
        (-0.5 * (self.cols - 1) as f64 * self.scale.x, -0.5 * (self.rows - 1) as f64 * self.scale.y)
    }

    /// Sample `(row, col)` as a local point.
    #[inline]
    pub fn vertex(&self, row: usize, col: usize) -> DVec3 {
        let (x0, y0) = self.origin_xy();
        DVec3::new(
            x0 + col as f64 * self.scale.x,
            y0 + row as f64 * self.scale.y,
            self.heights[row * self.cols + col] * self.scale.z,
        )
    }

    /// Local bounds: the grid's extent in X and Y, the lowest and highest height in Z.
    pub fn local_bounds(&self) -> (DVec3, DVec3) {
        let (x0, y0) = self.origin_xy();
        (DVec3::new(x0, y0, self.z_range.0), DVec3::new(-x0, -y0, self.z_range.1))
    }

    /// Number of triangles: two per cell.
    pub fn triangle_count(&self) -> usize {
        2 * (self.rows - 1) * (self.cols - 1)
    }

    /// The corners of triangle `t` (see the module docs for the numbering), counter-clockwise
    /// seen from above.
    pub fn triangle_points(&self, t: u32) -> [DVec3; 3] {
        let cell = t as usize / 2;
        let (r, c) = (cell / (self.cols - 1), cell % (self.cols - 1));
        if t.is_multiple_of(2) {
            [self.vertex(r, c), self.vertex(r, c + 1), self.vertex(r + 1, c + 1)]
        } else {
            [self.vertex(r, c), self.vertex(r + 1, c + 1), self.vertex(r + 1, c)]
        }
    }

    /// The triangle across edge `k` (vertex `k` to vertex `k + 1`) of triangle `t`, if any.
    pub fn neighbor(&self, t: u32, k: usize) -> Option<u32> {
        let cell = t as usize / 2;
        let (r, c) = (cell / (self.cols - 1), cell % (self.cols - 1));
        let (last_r, last_c) = (self.rows - 2, self.cols - 2);
        let tri = |r: usize, c: usize, half: u32| Some((2 * (r * (self.cols - 1) + c)) as u32 + half);
        match (t % 2, k) {
            // Lower-right triangle: bottom edge, right edge, diagonal.
            (0, 0) if r > 0 => tri(r - 1, c, 1),
            (0, 1) if c < last_c => tri(r, c + 1, 1),
            (0, 2) => tri(r, c, 1),
            // Upper-left triangle: diagonal, top edge, left edge.
            (1, 0) => tri(r, c, 0),
            (1, 1) if r < last_r => tri(r + 1, c, 0),
            (1, 2) if c > 0 => tri(r, c - 1, 0),
            _ => None,
        }
    }

    /// Calls `visit` with every triangle whose cell overlaps the local box `[lo, hi]` in X and Y
    /// and whose cell's height range overlaps it in Z.
    pub fn query(&self, lo: DVec3, hi: DVec3, mut visit: impl FnMut(u32)) {
        let (x0, y0) = self.origin_xy();
        let range = |lo: f64, hi: f64, origin: f64, step: f64, cells: usize| -> Option<(usize, usize)> {
            let a = ((lo - origin) / step).floor();
            let b = ((hi - origin) / step).floor();
            if b < 0.0 || a > (cells - 1) as f64 || a.is_nan() || b.is_nan() {
                return None;
            }
            Some((a.max(0.0) as usize, (b as usize).min(cells - 1)))
        };
        let Some((c0, c1)) = range(lo.x, hi.x, x0, self.scale.x, self.cols - 1) else { return };
        let Some((r0, r1)) = range(lo.y, hi.y, y0, self.scale.y, self.rows - 1) else { return };
        for r in r0..=r1 {
            for c in c0..=c1 {
                let z = [(r, c), (r, c + 1), (r + 1, c), (r + 1, c + 1)]
                    .map(|(i, j)| self.heights[i * self.cols + j]);
                let zmin = z.iter().fold(f64::INFINITY, |m, &v| m.min(v)) * self.scale.z;
                let zmax = z.iter().fold(f64::NEG_INFINITY, |m, &v| m.max(v)) * self.scale.z;
                if zmax < lo.z || zmin > hi.z {
                    continue;
                }
                let cell = (r * (self.cols - 1) + c) as u32;
                visit(2 * cell);
                visit(2 * cell + 1);
            }
        }
    }

    /// First crossing of a ray (local frame, unit direction) with the surface, from either side:
    /// distance, the triangle's (upward) normal and its index. Walks the cells under the ray in
    /// order (a 2D digital differential analyser), so the cost grows with the cells crossed, and
    /// the first cell with a hit holds the closest one.
    pub fn ray_cast_local(&self, o: DVec3, d: DVec3, max_t: f64) -> Option<(f64, DVec3, u32)> {
        let (lo, hi) = self.local_bounds();
        let (t_enter, t_exit) = Aabb::new(lo, hi).ray_interval(o, d, max_t)?;
        let (x0, y0) = self.origin_xy();
        let (sx, sy) = (self.scale.x, self.scale.y);
        let p = o + d * t_enter;
        let clamp_cell = |v: f64, cells: usize| (v.floor().max(0.0) as usize).min(cells - 1);
        let (mut c, mut r) =
            (clamp_cell((p.x - x0) / sx, self.cols - 1), clamp_cell((p.y - y0) / sy, self.rows - 1));
        // Parameter of the next cell boundary crossed along each axis, and the step between them.
        let axis = |dir: f64, pos: f64, origin: f64, step: f64, cell: usize| -> (f64, f64) {
            if dir > 0.0 {
                ((origin + (cell + 1) as f64 * step - pos) / dir, step / dir)
            } else if dir < 0.0 {
                ((origin + cell as f64 * step - pos) / dir, -step / dir)
            } else {
                (f64::INFINITY, f64::INFINITY)
            }
        };
        let (mut next_x, dx) = axis(d.x, o.x, x0, sx, c);
        let (mut next_y, dy) = axis(d.y, o.y, y0, sy, r);
        loop {
            let cell = (r * (self.cols - 1) + c) as u32;
            let mut best: Option<(f64, u32)> = None;
            for t in [2 * cell, 2 * cell + 1] {
                let limit = best.map_or(max_t, |b| b.0);
                if let Some(hit) = ray_triangle(o, d, self.triangle_points(t), limit) {
                    best = Some((hit, t));
                }
            }
            if let Some((hit, t)) = best {
                let [a, b, cc] = self.triangle_points(t);
                return Some((hit, (b - a).cross(cc - a).normalize(), t));
            }
            if next_x.min(next_y) > t_exit {
                return None;
            }
            if next_x <= next_y {
                if (d.x > 0.0 && c + 2 >= self.cols) || (d.x < 0.0 && c == 0) {
                    return None;
                }
                c = if d.x > 0.0 { c + 1 } else { c - 1 };
                next_x += dx;
            } else {
                if (d.y > 0.0 && r + 2 >= self.rows) || (d.y < 0.0 && r == 0) {
                    return None;
                }
                r = if d.y > 0.0 { r + 1 } else { r - 1 };
                next_y += dy;
            }
        }
    }
}
