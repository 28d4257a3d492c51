//! Test support for the mass-properties tests: mesh generators, and *independent* reference
//! values — analytic moments of boxes, and a decomposition into tetrahedra with Tonon's closed-form
//! tetrahedron inertia (F. Tonon, "Explicit exact formulas for the 3-D tetrahedron inertia tensor
//! in terms of its vertex coordinates", J. Math. Stat. 1(1), 2004). Neither shares code with the
//! library's Mirtich–Eberly integrals.
#![allow(dead_code)]

use std::f64::consts::PI;
use tumble::math::mat3_max_abs;
use tumble::{DMat3, DQuat, DVec3, MassProperties};

/// A triangle mesh as the library takes it.
#[derive(Clone, Debug)]
pub struct Mesh {
    pub vertices: Vec<DVec3>,
    pub triangles: Vec<[u32; 3]>,
}

impl Mesh {
    pub fn mass(&self, density: f64) -> MassProperties {
        MassProperties::from_mesh(&self.vertices, &self.triangles, density).expect("valid mesh")
    }

    /// Every vertex mapped by `p ↦ rotation · p + translation`.
    pub fn moved(&self, rotation: DQuat, translation: DVec3) -> Mesh {
        let vertices = self.vertices.iter().map(|&p| rotation * p + translation).collect();
        Mesh { vertices, triangles: self.triangles.clone() }
    }

    /// Every triangle's winding reversed (normals inward).
    pub fn flipped(&self) -> Mesh {
        let triangles = self.triangles.iter().map(|&[a, b, c]| [a, c, b]).collect();
        Mesh { vertices: self.vertices.clone(), triangles }
    }

    fn quad(&mut self, a: u32, b: u32, c: u32, d: u32) {
        self.triangles.push([a, b, c]);
        self.triangles.push([a, c, d]);
    }
}

/// The 12-triangle box `[lo, hi]`, outward wound. Vertex `i` has x from bit 0, y bit 1, z bit 2.
pub fn box_mesh(lo: DVec3, hi: DVec3) -> Mesh {
    let vertices = (0..8)
        .map(|i| {
            let pick = |bit: u32, l: f64, h: f64| if i & (1 << bit) != 0 { h } else { l };
            DVec3::new(pick(0, lo.x, hi.x), pick(1, lo.y, hi.y), pick(2, lo.z, hi.z))
        })
        .collect();
    let mut m = Mesh { vertices, triangles: Vec::new() };
    m.quad(0, 4, 6, 2); // −x
    m.quad(1, 3, 7, 5); // +x
    m.quad(0, 1, 5, 4); // −y
    m.quad(2, 6, 7, 3); // +y
    m.quad(0, 2, 3, 1); // −z
    m.quad(4, 5, 7, 6); // +z
    m
}

/// A prism: the plane region bounded by `loops` (region on the left of every loop, so outer loops
/// counter-clockwise, holes clockwise), with the cap triangulation `caps` (counter-clockwise),
/// extruded from `z0` to `z1`.
pub fn extrude(points: &[(f64, f64)], loops: &[Vec<u32>], caps: &[[u32; 3]], z0: f64, z1: f64) -> Mesh {
    let n = points.len() as u32;
    let mut vertices: Vec<DVec3> = points.iter().map(|&(x, y)| DVec3::new(x, y, z0)).collect();
    vertices.extend(points.iter().map(|&(x, y)| DVec3::new(x, y, z1)));
    let mut m = Mesh { vertices, triangles: Vec::new() };
    for &[a, b, c] in caps {
        m.triangles.push([a, c, b]); // bottom, facing −z
        m.triangles.push([a + n, b + n, c + n]); // top, facing +z
    }
    for lp in loops {
        for k in 0..lp.len() {
            let (a, b) = (lp[k], lp[(k + 1) % lp.len()]);
            m.quad(a, b, b + n, a + n);
        }
    }
    m
}

/// Plane points, one boundary loop, and a triangulation.
type Polygon = (Vec<(f64, f64)>, Vec<u32>, Vec<[u32; 3]>);

/// Regular `n`-gon of circumradius `r` plus its centre (last point), with a fan triangulation.
fn ngon(r: f64, n: u32) -> Polygon {
    let mut points: Vec<(f64, f64)> = (0..n)
        .map(|k| {
            let a = 2.0 * PI * k as f64 / n as f64;
            (r * a.cos(), r * a.sin())
        })
        .collect();
    points.push((0.0, 0.0));
    let fan = (0..n).map(|k| [n, k, (k + 1) % n]).collect();
    (points, (0..n).collect(), fan)
}

/// A cylinder along Z, radius `r` (circumscribed), from −h to h, with `n` sides.
pub fn cylinder_mesh(r: f64, h: f64, n: u32) -> Mesh {
    let (points, ring, fan) = ngon(r, n);
    extrude(&points, &[ring], &fan, -h, h)
}

/// A cone along Z: base `n`-gon of circumradius `r` at z = −h, apex at z = +h.
pub fn cone_mesh(r: f64, h: f64, n: u32) -> Mesh {
    let mut vertices: Vec<DVec3> = (0..n)
        .map(|k| {
            let a = 2.0 * PI * k as f64 / n as f64;
            DVec3::new(r * a.cos(), r * a.sin(), -h)
        })
        .collect();
    vertices.push(DVec3::new(0.0, 0.0, -h)); // n: base centre
    vertices.push(DVec3::new(0.0, 0.0, h)); // n + 1: apex
    let triangles = (0..n)
        .flat_map(|k| {
            let k1 = (k + 1) % n;
            [[n, k1, k], [k, k1, n + 1]]
        })
        .collect();
    Mesh { vertices, triangles }
}

/// A UV sphere: `nlat` latitude bands, `nlon` meridians, vertices on the sphere of radius `r`.
pub fn uv_sphere(r: f64, nlon: u32, nlat: u32) -> Mesh {
    let mut vertices = vec![DVec3::new(0.0, 0.0, r), DVec3::new(0.0, 0.0, -r)];
    for j in 1..nlat {
        let theta = PI * j as f64 / nlat as f64;
        for k in 0..nlon {
            let phi = 2.0 * PI * k as f64 / nlon as f64;
            vertices.push(r * DVec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos()));
        }
    }
    let idx = |j: u32, k: u32| 2 + (j - 1) * nlon + k % nlon;
    let mut m = Mesh { vertices, triangles: Vec::new() };
    for k in 0..nlon {
        m.triangles.push([0, idx(1, k), idx(1, k + 1)]);
        m.triangles.push([1, idx(nlat - 1, k + 1), idx(nlat - 1, k)]);
        for j in 1..nlat - 1 {
            m.quad(idx(j, k), idx(j + 1, k), idx(j + 1, k + 1), idx(j, k + 1));
        }
    }
    m
}

/// A torus around Z: major radius `big_r`, tube radius `r`, `nu` × `nv` quads.
pub fn torus_mesh(big_r: f64, r: f64, nu: u32, nv: u32) -> Mesh {
    let mut vertices = Vec::new();
    for i in 0..nu {
        let u = 2.0 * PI * i as f64 / nu as f64;
        for j in 0..nv {
            let v = 2.0 * PI * j as f64 / nv as f64;
            let rho = big_r + r * v.cos();
            vertices.push(DVec3::new(rho * u.cos(), rho * u.sin(), r * v.sin()));
        }
    }
    let idx = |i: u32, j: u32| (i % nu) * nv + j % nv;
    let mut m = Mesh { vertices, triangles: Vec::new() };
    for i in 0..nu {
        for j in 0..nv {
            m.quad(idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1));
        }
    }
    m
}

/// Neumaier's compensated sum: the reference should not add round-off of its own.
pub fn compensated_sum(values: impl IntoIterator<Item = f64>) -> f64 {
    let (mut sum, mut carry) = (0.0_f64, 0.0_f64);
    for v in values {
        let t = sum + v;
        carry += if sum.abs() >= v.abs() { (sum - t) + v } else { (v - t) + sum };
        sum = t;
    }
    sum + carry
}

/// Sums `[f64; N]` rows column by column with [`compensated_sum`].
fn sum_rows<const N: usize>(rows: &[[f64; N]]) -> [f64; N] {
    std::array::from_fn(|k| compensated_sum(rows.iter().map(|r| r[k])))
}

/// Reference mass properties of the polyhedron by signed tetrahedra `(apex, triangle)` and Tonon's
/// formulas, with the second pass taken directly about the centre of mass.
pub fn tetra_reference(mesh: &Mesh, apex: DVec3, density: f64) -> MassProperties {
    let tets: Vec<([DVec3; 3], f64)> = mesh
        .triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| mesh.vertices[i as usize]);
            ([a, b, c], (a - apex).dot((b - apex).cross(c - apex)) / 6.0)
        })
        .collect();
    // Volume and first moment: each tetrahedron's volume times its centroid (relative to apex).
    let first: Vec<[f64; 4]> = tets
        .iter()
        .map(|&([a, b, c], v)| {
            let m = v * ((a - apex) + (b - apex) + (c - apex)) / 4.0;
            [v, m.x, m.y, m.z]
        })
        .collect();
    let [volume, mx, my, mz] = sum_rows(&first);
    let com = apex + DVec3::new(mx, my, mz) / volume;

    // Tonon: with coordinates relative to the point of reference and J = 6V (signed here),
    // ∫y² + z² = J (Σ_{k≤l} y_k y_l + Σ_{k≤l} z_k z_l) / 60 and
    // ∫yz = J (2 Σ_k y_k z_k + Σ_{k≠l} y_k z_l) / 120, and likewise for the other axes.
    let sq = |u: [f64; 4]| {
        let mut s = 0.0;
        for k in 0..4 {
            for l in k..4 {
                s += u[k] * u[l];
            }
        }
        s
    };
    // 2 Σ_k u_k w_k + Σ_{k≠l} u_k w_l = (Σ_k u_k)(Σ_l w_l) + Σ_k u_k w_k.
    let mixed = |u: [f64; 4], w: [f64; 4]| {
        u.iter().sum::<f64>() * w.iter().sum::<f64>() + u.iter().zip(w).map(|(a, b)| a * b).sum::<f64>()
    };
    let second: Vec<[f64; 6]> = tets
        .iter()
        .map(|&([a, b, c], v)| {
            let p = [apex - com, a - com, b - com, c - com];
            let coord = |axis: usize| p.map(|q| q[axis]);
            let (x, y, z) = (coord(0), coord(1), coord(2));
            let j = 6.0 * v;
            [
                j * (sq(y) + sq(z)) / 60.0,
                j * (sq(x) + sq(z)) / 60.0,
                j * (sq(x) + sq(y)) / 60.0,
                j * mixed(y, z) / 120.0,
                j * mixed(x, z) / 120.0,
                j * mixed(x, y) / 120.0,
            ]
        })
        .collect();
    let [ia, ib, ic, a_yz, b_xz, c_xy] = sum_rows(&second);
    let inertia = DMat3::from_cols(
        DVec3::new(ia, -c_xy, -b_xz),
        DVec3::new(-c_xy, ib, -a_yz),
        DVec3::new(-b_xz, -a_yz, ic),
    );
    MassProperties { volume, mass: density * volume, center_of_mass: com, inertia: inertia * density }
}

/// `∫1, ∫r, ∫r rᵀ` over a solid, per unit density: adds and subtracts exactly for unions and
/// differences of solids, which makes analytic references for non-convex shapes.
#[derive(Clone, Copy, Debug)]
pub struct RawMoments {
    pub volume: f64,
    pub first: DVec3,
    pub second: DMat3,
}

impl RawMoments {
    /// The box `[lo, hi]`: every integral separates into 1-D ones, `∫ x^k dx = (h^{k+1} − l^{k+1})/(k+1)`.
    pub fn cuboid(lo: DVec3, hi: DVec3) -> RawMoments {
        let i0 = hi - lo;
        let i1 = (hi * hi - lo * lo) / 2.0;
        let i2 = (hi * hi * hi - lo * lo * lo) / 3.0;
        let xy = i1.x * i1.y * i0.z;
        let yz = i0.x * i1.y * i1.z;
        let zx = i1.x * i0.y * i1.z;
        RawMoments {
            volume: i0.x * i0.y * i0.z,
            first: DVec3::new(i1.x * i0.y * i0.z, i0.x * i1.y * i0.z, i0.x * i0.y * i1.z),
            second: DMat3::from_cols(
                DVec3::new(i2.x * i0.y * i0.z, xy, zx),
                DVec3::new(xy, i0.x * i2.y * i0.z, yz),
                DVec3::new(zx, yz, i0.x * i0.y * i2.z),
            ),
        }
    }

    pub fn plus(self, o: RawMoments) -> RawMoments {
        RawMoments {
            volume: self.volume + o.volume,
            first: self.first + o.first,
            second: self.second + o.second,
        }
    }

    pub fn minus(self, o: RawMoments) -> RawMoments {
        RawMoments {
            volume: self.volume - o.volume,
            first: self.first - o.first,
            second: self.second - o.second,
        }
    }

    /// Centre of mass and `I = ρ ((tr S) 1 − S)` with `S` the second moments about the centre.
    pub fn mass_properties(&self, density: f64) -> MassProperties {
        let c = self.first / self.volume;
        let s = self.second - self.volume * DMat3::from_cols(c * c.x, c * c.y, c * c.z);
        let trace = s.x_axis.x + s.y_axis.y + s.z_axis.z;
        MassProperties {
            volume: self.volume,
            mass: density * self.volume,
            center_of_mass: c,
            inertia: (DMat3::from_diagonal(DVec3::splat(trace)) - s) * density,
        }
    }
}

/// Errors of `got` against `want`: (volume, mass, centre / `length`, inertia), each relative;
/// the inertia by its largest entry, since off-diagonal entries may be zero.
pub fn errors(got: &MassProperties, want: &MassProperties, length: f64) -> [f64; 4] {
    [
        ((got.volume - want.volume) / want.volume).abs(),
        ((got.mass - want.mass) / want.mass).abs(),
        (got.center_of_mass - want.center_of_mass).length() / length,
        mat3_max_abs(got.inertia - want.inertia) / mat3_max_abs(want.inertia),
    ]
}

/// Asserts every error is below `tol`; returns the worst one (for reporting).
#[track_caller]
pub fn assert_close(what: &str, got: &MassProperties, want: &MassProperties, length: f64, tol: f64) -> f64 {
    let e = errors(got, want, length);
    let worst = e.iter().fold(0.0_f64, |a, &b| a.max(b));
    assert!(
        worst <= tol,
        "{what}: errors (volume, mass, com, inertia) = {e:?} exceed {tol:e}\n got {got:?}\nwant {want:?}"
    );
    eprintln!("{what}: worst relative error {worst:.2e}");
    worst
}

/// A rotation from four numbers in [−1, 1] (normalised; `None` if too short to normalise well).
pub fn quat_from(q: [f64; 4]) -> Option<DQuat> {
    let v = glam::DVec4::from_array(q);
    (v.length() > 0.1).then(|| DQuat::from_vec4(v.normalize()))
}
