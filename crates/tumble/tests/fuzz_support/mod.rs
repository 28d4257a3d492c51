//! The checks behind the fuzz targets (`fuzz/fuzz_targets/`) and their proptest twins
//! (`fuzz_geometry.rs`, `fuzz_world.rs`): structured inputs built with `arbitrary`, and the
//! properties every input must keep. Each check panics on a violation; the fuzzers report the
//! panic and the input, the proptests shrink it.
//!
//! Numbers reach the engine through bounded integers mapped onto ranges (sizes 0.01–100 m,
//! positions within a few metres) so that most inputs build valid shapes and poses and exercise
//! the geometry rather than the input checks; the world target also feeds raw `f64` forces and
//! velocities (NaN, infinities, 1e308) to the API.
#![allow(dead_code)]

use arbitrary::Arbitrary;
use tumble::collision::support::support_world;
use tumble::collision::{collide, Manifold, PairCache};
use tumble::{
    BallJoint, BodyDef, BodyKind, Capsule, Cone, ConvexHull, Cuboid, Cylinder, DQuat, DVec3, DistanceJoint,
    FixedJoint, HingeJoint, JointDef, JointKind, Limits, Shape, SliderJoint, Sphere, Transform, World,
};

/// A length in [0.01, 100] m, spread evenly in log scale.
fn size(x: u16) -> f64 {
    10f64.powf(-2.0 + 4.0 * f64::from(x) / f64::from(u16::MAX))
}

fn unit(x: i16) -> f64 {
    f64::from(x) / f64::from(i16::MAX)
}

fn vec3(v: [i16; 3], scale: f64) -> DVec3 {
    DVec3::new(unit(v[0]), unit(v[1]), unit(v[2])) * scale
}

fn quat(q: [i16; 4]) -> DQuat {
    let q = DQuat::from_xyzw(unit(q[0]), unit(q[1]), unit(q[2]), unit(q[3]));
    if q.length() > 1e-3 {
        q.normalize()
    } else {
        DQuat::IDENTITY
    }
}

/// A convex shape: a primitive, or the hull of up to 64 points.
#[derive(Arbitrary, Clone, Debug)]
pub struct ShapeInput {
    pub kind: u8,
    pub dims: [u16; 3],
    pub points: Vec<[i16; 3]>,
}

impl ShapeInput {
    /// The shape, or `None` when the input does not describe one (a degenerate hull).
    pub fn shape(&self) -> Option<Shape> {
        let [a, b, c] = self.dims.map(size);
        Some(match self.kind % 6 {
            0 => Shape::Sphere(Sphere::new(a).ok()?),
            1 => Shape::Cuboid(Cuboid::new(DVec3::new(a, b, c)).ok()?),
            2 => Shape::Capsule(Capsule::new(a, b).ok()?),
            3 => Shape::Cylinder(Cylinder::new(a, b).ok()?),
            4 => Shape::Cone(Cone::new(a, b).ok()?),
            _ => Shape::ConvexHull(hull_of(&self.points, a).ok()?),
        })
    }

    /// A length that bounds the shape, to scale tolerances.
    pub fn extent(&self) -> f64 {
        let [a, b, c] = self.dims.map(size);
        a + b + c
    }
}

pub fn hull_of(points: &[[i16; 3]], scale: f64) -> Result<ConvexHull, tumble::HullError> {
    let points: Vec<DVec3> = points.iter().take(64).map(|&p| vec3(p, scale)).collect();
    ConvexHull::new(&points)
}

/// A pose within 4 m of the origin.
#[derive(Arbitrary, Clone, Copy, Debug)]
pub struct PoseInput {
    pub translation: [i16; 3],
    pub rotation: [i16; 4],
}

impl PoseInput {
    pub fn pose(&self) -> Transform {
        Transform::new(vec3(self.translation, 4.0), quat(self.rotation))
    }
}

// ---- convex hull ----------------------------------------------------------------------------------

#[derive(Arbitrary, Clone, Debug)]
pub struct HullInput {
    pub points: Vec<[i16; 3]>,
    pub scale: u16,
}

/// Building a hull never panics; a hull that builds has finite vertices, outward faces that
/// every input point lies behind, and a positive finite volume.
pub fn check_hull(input: &HullInput) {
    let scale = size(input.scale);
    let Ok(hull) = hull_of(&input.points, scale) else { return };
    let points: Vec<DVec3> = input.points.iter().take(64).map(|&p| vec3(p, scale)).collect();
    let (lo, hi) = points.iter().fold((points[0], points[0]), |(lo, hi), &p| (lo.min(p), hi.max(p)));
    assert!(hull.vertices().len() >= 4);
    assert!(hull.vertices().iter().all(|v| v.is_finite()));
    let inside = hull.interior_point();
    // Faces within 1e-7 of the points' extent of one plane are merged into one (`ConvexHull::new`),
    // so an input point may stand that far in front of the merged face's fitted plane.
    let tolerance = 1e-6 * (hi - lo).length();
    for face in hull.faces() {
        let n = face.normal;
        assert!((n.length() - 1.0).abs() < 1e-9, "face normal {n}");
        assert!(n.dot(inside) < face.offset, "interior point in front of a face");
        for &p in &points {
            let out = n.dot(p) - face.offset;
            assert!(out <= tolerance, "input point {p} {out} m outside face {n} (tolerance {tolerance})");
        }
    }
    let mp = Shape::ConvexHull(hull).mass_properties(1000.0).expect("a built hull has mass properties");
    assert!(mp.volume.is_finite() && mp.volume > 0.0, "volume {}", mp.volume);
}

// ---- narrow phase ---------------------------------------------------------------------------------

#[derive(Arbitrary, Clone, Debug)]
pub struct PairInput {
    pub a: ShapeInput,
    pub pose_a: PoseInput,
    pub b: ShapeInput,
    pub pose_b: PoseInput,
}

/// The speculative margin the checks collide with, m.
pub const MARGIN: f64 = 0.02;

fn check_manifold(m: &Manifold, scale: f64) {
    let n = m.normal_world;
    assert!(n.is_finite() && (n.length() - 1.0).abs() < 1e-6, "normal {n}");
    assert!(!m.is_empty(), "an empty manifold");
    for p in m.points() {
        assert!(p.point_world.is_finite() && p.separation.is_finite(), "point {p:?}");
        assert!(p.separation <= MARGIN + 1e-6 * scale, "separation {} beyond the margin", p.separation);
    }
}

/// How far apart the shapes are along `n` (A to B): `min n·b − max n·a`; the largest value over
/// all `n` is the deepest separation.
fn separation_along(a: &Shape, pose_a: &Transform, b: &Shape, pose_b: &Transform, n: DVec3) -> f64 {
    let on_a = support_world(a, pose_a, n).expect("convex");
    let on_b = support_world(b, pose_b, -n).expect("convex");
    n.dot(on_b) - n.dot(on_a)
}

fn min_separation(m: &Manifold) -> f64 {
    m.points().iter().map(|p| p.separation).fold(f64::INFINITY, f64::min)
}

/// Colliding A with B and B with A: no panic, finite manifolds with unit normals and separations
/// within the margin; one way finding a contact and the other not only at the edge of the margin.
/// For shallow contacts (overlap below a tenth of the smaller shape, what a running world sees),
/// both ways also agree on the deepest separation (within what each normal shows) and their
/// normals are opposite, or each realises that separation (a tie: concentric spheres, a box
/// centred in a bigger one). Deeper overlaps of round shapes go through EPA, whose polytope
/// approximates the curved `A − B` to within about 1e-3 of the size when it stops (a 0.2 m
/// cylinder inside a 100 m one: normals 0.27 m off the depth,
/// `fuzz_regression_narrow_phase_small_cylinder_deep_in_large`), so only the first checks apply.
pub fn check_pair(input: &PairInput) {
    let (Some(a), Some(b)) = (input.a.shape(), input.b.shape()) else { return };
    let scale = input.a.extent() + input.b.extent();
    let shallow = 0.1 * input.a.extent().min(input.b.extent());
    check_shapes(&a, &input.pose_a.pose(), &b, &input.pose_b.pose(), scale, shallow);
}

/// How close the two answers must come to a common depth, relative to the pair's size: EPA
/// approximates a curved `A − B` by a polytope, and A–B and B–A grow different ones.
const DEPTH_ACCURACY: f64 = 1e-4;

/// `scale`: a size of the pair, for tolerances; `shallow`: the overlap below which depths and
/// normals are compared.
pub fn check_shapes(a: &Shape, pose_a: &Transform, b: &Shape, pose_b: &Transform, scale: f64, shallow: f64) {
    let ab = collide(a, pose_a, b, pose_b, MARGIN, &mut PairCache::default());
    let ba = collide(b, pose_b, a, pose_a, MARGIN, &mut PairCache::default());
    let tolerance = 1e-6 * scale.max(1.0);
    for m in ab.iter().chain(&ba) {
        check_manifold(m, scale);
    }
    match (&ab, &ba) {
        (Some(ab), Some(ba)) if min_separation(ab).min(min_separation(ba)) >= -shallow => {
            // The true deepest separation D is the largest separation along any direction, so
            // D >= separation_along(n) for either normal; each reported separation should be D
            // up to the accuracy of the method.
            let (d1, d2) = (min_separation(ab), min_separation(ba));
            let (s1, s2) = (
                separation_along(a, pose_a, b, pose_b, ab.normal_world),
                separation_along(b, pose_b, a, pose_a, ba.normal_world),
            );
            let accuracy = DEPTH_ACCURACY * scale + tolerance;
            assert!(
                s1.max(s2) <= d1.min(d2) + accuracy,
                "A-B says {d1} (normal gives {s1}), B-A says {d2} (normal gives {s2}): no common depth"
            );
            // Opposite normals; or each realising the depth (a tie, or EPA's approximation).
            let flipped = (ab.normal_world + ba.normal_world).length() < 1e-6;
            let both_realise = d1 - s1 <= accuracy && d2 - s2 <= accuracy;
            assert!(
                flipped || both_realise,
                "normals {} and {} are not opposite and miss the depth: {d1} vs {s1}, {d2} vs {s2}",
                ab.normal_world,
                ba.normal_world
            );
        }
        (Some(m), None) | (None, Some(m)) => {
            let d = min_separation(m);
            assert!(d >= MARGIN - tolerance, "a contact at separation {d} found one way only");
        }
        _ => {}
    }
}

// ---- a world ---------------------------------------------------------------------------------------

#[derive(Arbitrary, Clone, Debug)]
pub struct BodyInput {
    pub shape: ShapeInput,
    pub kind: u8,
    pub position: [i16; 3],
    pub rotation: [i16; 4],
    pub velocity: [i16; 3],
    pub spin: [i16; 3],
}

#[derive(Arbitrary, Clone, Debug)]
pub struct JointInput {
    pub a: u8,
    pub b: u8,
    pub kind: u8,
    pub anchor: [i16; 3],
    pub axis: [i16; 3],
    pub limit: i16,
}

/// Something done to a body before a step: raw `f64`s, so NaN, infinities and 1e308 arrive too.
#[derive(Arbitrary, Clone, Debug)]
pub struct PushInput {
    pub step: u8,
    pub body: u8,
    pub what: u8,
    pub value: [f64; 3],
}

#[derive(Arbitrary, Clone, Debug)]
pub struct WorldInput {
    pub ground: bool,
    pub substeps: u8,
    pub bodies: Vec<BodyInput>,
    pub joints: Vec<JointInput>,
    pub pushes: Vec<PushInput>,
}

/// Steps a world built from `input` 100 times at 1/60 s, with its pushes: no panic, and every
/// body's state finite after every step (a body that overflows is isolated, `non_finite.rs`).
pub fn check_world(input: &WorldInput) {
    let mut world = World::default();
    let mut settings = world.solver_settings().clone();
    settings.substeps = 1 + u32::from(input.substeps % 8);
    world.set_solver_settings(settings).expect("valid settings");
    if input.ground {
        let ground = BodyDef {
            kind: BodyKind::Static,
            shape: Some(Shape::Cuboid(Cuboid::new(DVec3::new(50.0, 50.0, 0.5)).unwrap())),
            position: DVec3::new(0.0, 0.0, -0.5),
            ..Default::default()
        };
        world.add_body(ground).unwrap();
    }
    let mut ids = Vec::new();
    for (i, b) in input.bodies.iter().take(12).enumerate() {
        let kind = match b.kind % 8 {
            0 => BodyKind::Static,
            1 => BodyKind::Kinematic,
            _ => BodyKind::Dynamic,
        };
        let def = BodyDef {
            name: format!("b{i}"),
            kind,
            shape: b.shape.shape(),
            position: vec3(b.position, 5.0) + DVec3::new(0.0, 0.0, 5.0),
            orientation: quat(b.rotation),
            linear_velocity: vec3(b.velocity, 20.0),
            angular_velocity: vec3(b.spin, 20.0),
            ..Default::default()
        };
        if let Ok(id) = world.add_body(def) {
            ids.push(id);
        }
    }
    if ids.is_empty() {
        return;
    }
    let pick = |k: u8| ids[usize::from(k) % ids.len()];
    for j in input.joints.iter().take(8) {
        let limit = unit(j.limit).abs() * std::f64::consts::PI;
        let kind = match j.kind % 5 {
            0 => JointKind::Ball(BallJoint {
                swing_limit: (j.limit % 2 == 0).then_some(limit),
                twist_limits: (j.limit % 3 == 0).then(|| Limits::new(-limit, limit)),
                ..Default::default()
            }),
            1 => JointKind::Hinge(HingeJoint {
                limits: (j.limit % 2 == 0).then(|| Limits::new(-limit, limit)),
                ..Default::default()
            }),
            2 => JointKind::Slider(SliderJoint {
                limits: (j.limit % 2 == 0).then(|| Limits::new(-limit, limit)),
                ..Default::default()
            }),
            3 => JointKind::Fixed(FixedJoint::default()),
            _ => JointKind::Distance(DistanceJoint::default()),
        };
        let anchor = vec3(j.anchor, 5.0) + DVec3::new(0.0, 0.0, 5.0);
        let def = JointDef::new(pick(j.a), pick(j.b), anchor, kind).with_axis(vec3(j.axis, 1.0));
        let _ = world.add_joint(def);
    }
    let mut pushes: Vec<&PushInput> = input.pushes.iter().take(16).collect();
    pushes.sort_by_key(|p| p.step % 100);
    let mut next = 0;
    for step in 0..100u8 {
        while next < pushes.len() && pushes[next].step % 100 == step {
            let p = pushes[next];
            let (id, v) = (pick(p.body), DVec3::from_array(p.value));
            // Errors (non-finite values) are the API doing its job; only panics and NaN state count.
            let _ = match p.what % 6 {
                0 => world.apply_force(id, v),
                1 => world.apply_torque(id, v),
                2 => world.apply_impulse_at_point(id, v, DVec3::ZERO),
                3 => world.set_linear_velocity(id, v),
                4 => world.set_angular_velocity(id, v),
                _ => world.apply_force_at_point(id, v, DVec3::ONE),
            };
            next += 1;
        }
        world.step(1.0 / 60.0).expect("a valid time step");
        for (id, body) in world.bodies() {
            let s = body.state();
            let finite = s.com_world.is_finite()
                && s.rotation.is_finite()
                && s.linear_velocity.is_finite()
                && s.angular_velocity.is_finite();
            assert!(finite, "step {step}: body {id} ({}) has non-finite state {s:?}", body.name());
        }
    }
}
