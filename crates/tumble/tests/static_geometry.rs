//! Static geometry: planes, triangle meshes and height fields against convex shapes — known
//! answers, the internal-edge rule, a world simulation over a mesh floor, and bad input.

mod static_support;

use static_support::{flat_heightfield, grid, grid_floor};
use tumble::collision::narrow_phase::{collide, PairCache};
use tumble::collision::Manifold;
use tumble::{
    BodyDef, BodyKind, Capsule, Cuboid, DQuat, DVec3, HeightField, MassError, Plane, Shape, ShapeError,
    Sphere, Transform, TriMesh, World, WorldError,
};

const MARGIN: f64 = 0.02;

fn floor_plane() -> Shape {
    Shape::Plane(Plane::new(DVec3::Z, 0.0).unwrap())
}

fn at(x: f64, y: f64, z: f64) -> Transform {
    Transform::new(DVec3::new(x, y, z), DQuat::IDENTITY)
}

fn contact(a: &Shape, pa: &Transform, b: &Shape, pb: &Transform) -> Option<Manifold> {
    collide(a, pa, b, pb, MARGIN, &mut PairCache::default())
}

/// Angle of `n` from +Z, degrees.
fn tilt_degrees(n: DVec3) -> f64 {
    n.dot(DVec3::Z).clamp(-1.0, 1.0).acos().to_degrees()
}

/// The manifold seen from both orders must agree (flipped normal, same points and separations).
fn check_symmetric(a: &Shape, pa: &Transform, b: &Shape, pb: &Transform) -> Option<Manifold> {
    let ab = contact(a, pa, b, pb);
    let ba = contact(b, pb, a, pa);
    assert_eq!(ab.is_some(), ba.is_some());
    if let (Some(ab), Some(ba)) = (&ab, &ba) {
        assert!((ab.normal_world + ba.normal_world).length() < 1e-12);
        assert_eq!(ab.len(), ba.len());
        for (p, q) in ab.points().iter().zip(ba.points()) {
            assert_eq!(p.point_world, q.point_world);
            assert_eq!(p.separation, q.separation);
            assert_eq!(p.local_point_a, q.local_point_b);
        }
    }
    ab
}

#[test]
fn box_resting_on_plane_has_four_corner_points() {
    let b = Shape::Cuboid(Cuboid::new(DVec3::new(0.5, 0.3, 0.2)).unwrap());
    let pose = Transform::new(DVec3::new(1.0, -2.0, 0.195), DQuat::from_rotation_z(0.4));
    let m = check_symmetric(&floor_plane(), &Transform::IDENTITY, &b, &pose).unwrap();
    assert_eq!(m.len(), 4);
    assert!((m.normal_world - DVec3::Z).length() < 1e-15);
    for p in m.points() {
        assert!((p.separation + 0.005).abs() < 1e-12, "separation {}", p.separation);
        // Each point is (the midpoint above) a bottom corner of the box.
        let local = pose.inverse_transform_point(p.point_world + DVec3::Z * 0.5 * p.separation);
        assert!((local.abs() - DVec3::new(0.5, 0.3, 0.2)).length() < 1e-12, "{local}");
        assert!(local.z < 0.0);
    }
    // Ids are the corners: stable when the box slides.
    let moved = Transform::new(DVec3::new(1.3, -1.7, 0.195), DQuat::from_rotation_z(0.4));
    let m2 = contact(&floor_plane(), &Transform::IDENTITY, &b, &moved).unwrap();
    let ids = |m: &Manifold| m.points().iter().map(|p| p.feature_id).collect::<Vec<_>>();
    assert_eq!(ids(&m), ids(&m2));
    // Lifted beyond the margin: nothing.
    assert!(contact(&floor_plane(), &Transform::IDENTITY, &b, &at(0.0, 0.0, 0.2 + 1.01 * MARGIN)).is_none());
}

#[test]
fn sphere_and_capsule_on_plane() {
    let s = Shape::Sphere(Sphere::new(0.5).unwrap());
    // A tilted, offset plane: normal (0, 1, 1)/√2 through (0, 0, 1).
    let n = DVec3::new(0.0, 1.0, 1.0).normalize();
    let plane = Shape::Plane(Plane::new(DVec3::new(0.0, 2.0, 2.0), n.z).unwrap());
    let centre = DVec3::new(3.0, 0.0, 1.0) + n * 0.49;
    let m =
        check_symmetric(&plane, &Transform::IDENTITY, &s, &Transform::new(centre, DQuat::IDENTITY)).unwrap();
    assert_eq!(m.len(), 1);
    assert!((m.points()[0].separation + 0.01).abs() < 1e-12);
    assert!((m.normal_world - n).length() < 1e-12);

    // A capsule lying on the floor: its two segment ends.
    let c = Shape::Capsule(Capsule::new(0.1, 0.4).unwrap());
    let lying =
        Transform::new(DVec3::new(0.0, 0.0, 0.1), DQuat::from_rotation_y(std::f64::consts::FRAC_PI_2));
    let m = check_symmetric(&floor_plane(), &Transform::IDENTITY, &c, &lying).unwrap();
    assert_eq!(m.len(), 2);
    for p in m.points() {
        assert!(p.separation.abs() < 1e-12);
        assert!((p.point_world.x.abs() - 0.4).abs() < 1e-12);
    }
    // Standing: one end.
    let m = contact(&floor_plane(), &Transform::IDENTITY, &c, &at(0.0, 0.0, 0.5)).unwrap();
    assert_eq!(m.len(), 1);
}

#[test]
fn box_resting_on_mesh_floor_and_heightfield() {
    let floor = Shape::TriMesh(grid_floor(20, 0.25, 0.0));
    let hf = Shape::HeightField(flat_heightfield(21, 0.25, 0.0));
    let b = Shape::Cuboid(Cuboid::new(DVec3::new(0.4, 0.3, 0.2)).unwrap());
    for yaw in [0.0, 0.3, 1.0] {
        let pose = Transform::new(DVec3::new(0.13, -0.31, 0.199), DQuat::from_rotation_z(yaw));
        for ground in [&floor, &hf] {
            let m = check_symmetric(ground, &Transform::IDENTITY, &b, &pose).unwrap();
            assert_eq!(m.len(), 4, "{}", ground.kind_name());
            assert!((m.normal_world - DVec3::Z).length() < 1e-12);
            for p in m.points() {
                assert!((p.separation + 0.001).abs() < 1e-9, "separation {}", p.separation);
                let local = pose.inverse_transform_point(p.point_world + DVec3::Z * 0.5 * p.separation);
                assert!((local.abs() - DVec3::new(0.4, 0.3, 0.2)).length() < 1e-9, "not a corner: {local}");
            }
        }
    }
    // A mesh floor placed by its pose (raised and turned) gives the same answer.
    let pose_floor = Transform::new(DVec3::new(0.0, 0.0, 1.0), DQuat::from_rotation_z(0.7));
    let m = contact(&floor, &pose_floor, &b, &at(0.1, 0.2, 1.195)).unwrap();
    assert_eq!(m.len(), 4);
    assert!(m.points().iter().all(|p| (p.separation + 0.005).abs() < 1e-9));
}

#[test]
fn sphere_on_heightfield_slope_has_the_slope_normal() {
    // z = 0.5 x: a plane sampled on a grid; every edge is flat, so the normal is the slope's.
    let (rows, cols, dx) = (9, 9, 0.5);
    let heights: Vec<f64> = (0..rows * cols).map(|i| 0.5 * ((i % cols) as f64 - 4.0) * dx).collect();
    let hf = Shape::HeightField(HeightField::new(heights, rows, cols, DVec3::new(dx, dx, 1.0)).unwrap());
    let n = DVec3::new(-0.5, 0.0, 1.0).normalize();
    let s = Shape::Sphere(Sphere::new(0.3).unwrap());
    for x in [-1.0, -0.26, 0.0, 0.25, 0.9] {
        let on_surface = DVec3::new(x, 0.1, 0.5 * x);
        let m =
            contact(&hf, &Transform::IDENTITY, &s, &Transform::new(on_surface + n * 0.29, DQuat::IDENTITY))
                .unwrap();
        assert_eq!(m.len(), 1);
        assert!((m.normal_world - n).length() < 1e-9, "{}", m.normal_world);
        assert!((m.points()[0].separation + 0.01).abs() < 1e-9);
    }
}

/// The test: a box sliding across a flat floor of 800 small triangles never gets a contact
/// normal more than 1° off vertical, whatever its yaw, small tilt, or depth.
#[test]
fn box_sliding_over_a_flat_mesh_floor_never_catches_on_internal_edges() {
    let floor = Shape::TriMesh(grid_floor(20, 0.25, 0.0));
    assert_eq!(floor_triangles(&floor), 800);
    let shapes = [
        Shape::Cuboid(Cuboid::new(DVec3::new(0.3, 0.2, 0.1)).unwrap()),
        Shape::Cuboid(Cuboid::new(DVec3::splat(0.05)).unwrap()),
        Shape::Sphere(Sphere::new(0.1).unwrap()),
        Shape::Capsule(Capsule::new(0.05, 0.2).unwrap()),
    ];
    let mut worst: f64 = 0.0;
    let mut contacts = 0;
    for shape in &shapes {
        let bottom = match shape {
            Shape::Cuboid(c) => c.half_extents.z,
            Shape::Sphere(s) => s.radius,
            Shape::Capsule(c) => c.radius,
            _ => unreachable!(),
        };
        for (yaw, tilt) in [(0.0, 0.0), (0.3, 0.0), (0.785, 0.0), (0.2, 0.01), (1.1, -0.02)] {
            let rotation = DQuat::from_rotation_z(yaw) * DQuat::from_rotation_x(tilt);
            let capsule_lying = if matches!(shape, Shape::Capsule(_)) {
                DQuat::from_rotation_y(std::f64::consts::FRAC_PI_2)
            } else {
                DQuat::IDENTITY
            };
            for depth in [0.0, 0.002, 0.01] {
                // Sweep along a diagonal in 1 mm steps across many cells.
                for k in 0..1500 {
                    let s = -1.5 + k as f64 * 0.002;
                    let pose = Transform::new(
                        DVec3::new(s, 0.37 * s + 0.01, bottom - depth),
                        rotation * capsule_lying,
                    );
                    if let Some(m) = contact(&floor, &Transform::IDENTITY, shape, &pose) {
                        worst = worst.max(tilt_degrees(m.normal_world));
                        contacts += 1;
                    }
                }
            }
        }
    }
    println!("internal-edge sweep: {contacts} manifolds, worst normal {worst:.3e} degrees off vertical");
    assert!(contacts > 50_000);
    assert!(worst <= 1.0, "a contact normal was {worst}° off vertical");
}

fn floor_triangles(floor: &Shape) -> usize {
    match floor {
        Shape::TriMesh(m) => m.triangles().len(),
        _ => 0,
    }
}

/// A convex ridge keeps its edge normals: a sphere resting on the ridge of a roof is pushed along
/// the bisector, not straight up.
#[test]
fn convex_ridge_keeps_edge_normals() {
    let (vertices, triangles) = grid(8, 0.5, |x, _| -0.5 * x.abs());
    let roof = Shape::TriMesh(TriMesh::new_static(vertices, triangles).unwrap());
    let s = Shape::Sphere(Sphere::new(0.2).unwrap());
    let m = contact(&roof, &Transform::IDENTITY, &s, &at(0.0, 0.1, 0.19)).unwrap();
    assert!((m.normal_world - DVec3::Z).length() < 1e-9, "on the ridge the normal is the bisector (up)");
    // Slightly to one side of the ridge, still touching the edge: the normal leans that way, and
    // no further than the slope's normal.
    let m = contact(&roof, &Transform::IDENTITY, &s, &at(0.05, 0.1, 0.18)).unwrap();
    let slope = DVec3::new(0.5, 0.0, 1.0).normalize();
    assert!(m.normal_world.x > 0.0 && m.normal_world.dot(slope) <= 1.0 + 1e-12, "{}", m.normal_world);
}

/// Boxes given a push across a static mesh floor in a world slide (one also tumbles in from a
/// drop) and stop; every contact normal along the way is vertical to within 1°.
#[test]
fn world_boxes_sliding_over_a_mesh_floor() {
    let mut world = World::default();
    world
        .add_body(BodyDef {
            name: "floor".into(),
            kind: BodyKind::Static,
            shape: Some(Shape::TriMesh(grid_floor(20, 0.25, 0.0))),
            ..Default::default()
        })
        .unwrap();
    let slider = world
        .add_body(BodyDef {
            name: "slider".into(),
            shape: Some(Shape::Cuboid(Cuboid::new(DVec3::new(0.2, 0.15, 0.1)).unwrap())),
            position: DVec3::new(-1.5, -1.0, 0.1),
            orientation: DQuat::from_rotation_z(0.3),
            linear_velocity: DVec3::new(3.0, 1.5, 0.0),
            ..Default::default()
        })
        .unwrap();
    let tumbler = world
        .add_body(BodyDef {
            name: "tumbler".into(),
            shape: Some(Shape::Cuboid(Cuboid::new(DVec3::splat(0.06)).unwrap())),
            position: DVec3::new(-1.8, 1.0, 0.3),
            orientation: DQuat::from_rotation_z(0.5) * DQuat::from_rotation_x(0.4),
            linear_velocity: DVec3::new(4.0, -0.5, -2.0),
            angular_velocity: DVec3::new(0.0, 5.0, 1.0),
            ..Default::default()
        })
        .unwrap();
    let mut worst: f64 = 0.0;
    let mut manifolds = 0;
    for _ in 0..180 {
        world.step(1.0 / 60.0).unwrap();
        for c in world.contacts() {
            worst = worst.max(tilt_degrees(c.normal.abs()));
            manifolds += 1;
        }
    }
    for id in [slider, tumbler] {
        let body = world.body(id).unwrap();
        let p = body.position();
        println!("world slide: {} ends at {p}", body.name());
        assert!(body.linear_velocity().length() < 0.05, "friction stopped {}", body.name());
    }
    println!("world slide: worst normal {worst:.3e}° over {manifolds} manifolds");
    assert!(manifolds >= 250);
    assert!(worst <= 1.0, "contact normal {worst}° off vertical");
    let p = world.body(slider).unwrap().position();
    assert!((p.z - 0.1).abs() < 0.01, "the box stays on the floor: z = {}", p.z);
    assert!(p.x > -1.0, "it slid: x = {}", p.x);
}

/// A dynamic closed mesh (a box made of triangles) collides through its hull with a plane and with
/// a static mesh floor.
#[test]
fn dynamic_mesh_rests_on_plane_and_on_mesh() {
    let (v, t) = shape_box_mesh(DVec3::new(0.3, 0.2, 0.1));
    for floor in [floor_plane(), Shape::TriMesh(grid_floor(10, 0.5, 0.0))] {
        let mut world = World::default();
        world
            .add_body(BodyDef { kind: BodyKind::Static, shape: Some(floor.clone()), ..Default::default() })
            .unwrap();
        let id = world
            .add_body(BodyDef {
                shape: Some(Shape::TriMesh(TriMesh::new(v.clone(), t.clone()).unwrap())),
                position: DVec3::new(0.1, 0.0, 0.3),
                ..Default::default()
            })
            .unwrap();
        for _ in 0..90 {
            world.step(1.0 / 60.0).unwrap();
        }
        let z = world.body(id).unwrap().position().z;
        assert!((z - 0.1).abs() < 0.01, "{}: rests at z = {z}", floor.kind_name());
    }
}

fn shape_box_mesh(h: DVec3) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let vertices: Vec<DVec3> = (0..8)
        .map(|i| {
            let s = |bit: u32| if i & (1 << bit) != 0 { 1.0 } else { -1.0 };
            DVec3::new(s(0) * h.x, s(1) * h.y, s(2) * h.z)
        })
        .collect();
    #[rustfmt::skip]
    let triangles = vec![
        [0, 2, 3], [0, 3, 1], [4, 5, 7], [4, 7, 6], [0, 1, 5], [0, 5, 4],
        [2, 6, 7], [2, 7, 3], [0, 4, 6], [0, 6, 2], [1, 3, 7], [1, 7, 5],
    ];
    (vertices, triangles)
}

#[test]
fn sphere_rolls_to_rest_on_heightfield_and_plane() {
    for ground in [Shape::HeightField(flat_heightfield(11, 0.5, 0.0)), floor_plane()] {
        let mut world = World::default();
        world
            .add_body(BodyDef { kind: BodyKind::Static, shape: Some(ground.clone()), ..Default::default() })
            .unwrap();
        let id = world
            .add_body(BodyDef {
                shape: Some(Shape::Sphere(Sphere::new(0.2).unwrap())),
                position: DVec3::new(0.0, 0.0, 0.5),
                linear_velocity: DVec3::new(0.5, 0.0, 0.0),
                ..Default::default()
            })
            .unwrap();
        for _ in 0..120 {
            world.step(1.0 / 60.0).unwrap();
        }
        let z = world.body(id).unwrap().position().z;
        assert!((z - 0.2).abs() < 0.01, "{}: z = {z}", ground.kind_name());
    }
}

#[test]
fn bounds_of_static_shapes() {
    use tumble::collision::shape_aabb;
    // An axis-aligned floor is bounded at its surface; a tilted plane fills the extent cube.
    let b = shape_aabb(&floor_plane(), &at(0.0, 0.0, 2.0));
    assert_eq!(b.max.z, 2.0);
    assert_eq!(b.min.z, -tumble::shape::PLANE_EXTENT);
    let tilted = Shape::Plane(Plane::new(DVec3::new(0.0, 1.0, 1.0), 0.0).unwrap());
    assert_eq!(shape_aabb(&tilted, &Transform::IDENTITY).max.z, tumble::shape::PLANE_EXTENT);
    // A height field: centred, its height range in z, moved by its pose.
    let h = HeightField::new(vec![0.0, 1.0, -2.0, 0.5, 0.0, 0.0], 2, 3, DVec3::new(1.0, 2.0, 0.5)).unwrap();
    let b = shape_aabb(&Shape::HeightField(h.clone()), &at(10.0, 0.0, 0.0));
    assert_eq!((b.min, b.max), (DVec3::new(9.0, -1.0, -1.0), DVec3::new(11.0, 1.0, 0.5)));
    assert_eq!(h.vertex(1, 2), DVec3::new(1.0, 1.0, 0.0));
    assert_eq!(h.vertex(0, 2), DVec3::new(1.0, -1.0, -1.0));
}

#[test]
fn bad_input_is_rejected_with_clear_errors() {
    // Meshes.
    let mut v = vec![DVec3::ZERO, DVec3::X, DVec3::Y];
    assert_eq!(TriMesh::new_static(v.clone(), vec![]), Err(MassError::EmptyMesh));
    v[1].y = f64::NAN;
    let e = TriMesh::new_static(v.clone(), vec![[0, 1, 2]]).unwrap_err();
    assert!(matches!(e, MassError::NonFiniteVertex { index: 1, .. }), "{e}");
    assert!(e.to_string().contains("vertex 1"));
    let e = TriMesh::new_static(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 3]]).unwrap_err();
    assert!(matches!(e, MassError::IndexOutOfRange { .. }));
    let e = TriMesh::new_static(vec![DVec3::ZERO, DVec3::X, DVec3::X * 2.0], vec![[0, 1, 2]]).unwrap_err();
    assert!(matches!(e, MassError::DegenerateTriangle { triangle: 0 }));
    // An open mesh is fine for new_static, not for new, and has no mass.
    let floor = grid_floor(2, 1.0, 0.0);
    let (fv, ft) = (floor.vertices().to_vec(), floor.triangles().to_vec());
    assert!(matches!(TriMesh::new(fv, ft), Err(MassError::OpenMesh { .. })));
    let e = Shape::TriMesh(floor.clone()).mass_properties(1000.0).unwrap_err();
    assert!(e.to_string().contains("static"), "{e}");

    // Height fields.
    let scale = DVec3::ONE;
    assert_eq!(
        HeightField::new(vec![0.0; 2], 1, 2, scale),
        Err(ShapeError::HeightFieldTooSmall { rows: 1, cols: 2 })
    );
    assert!(matches!(
        HeightField::new(vec![0.0; 5], 2, 3, scale),
        Err(ShapeError::HeightFieldSize { len: 5, .. })
    ));
    let mut h = vec![0.0; 6];
    h[4] = f64::NAN;
    let e = HeightField::new(h, 2, 3, scale).unwrap_err();
    assert!(matches!(e, ShapeError::NonFiniteHeight { row: 1, col: 1, .. }), "{e}");
    assert!(e.to_string().contains("row 1, column 1"), "{e}");
    assert!(matches!(
        HeightField::new(vec![0.0; 4], 2, 2, DVec3::new(1.0, 0.0, 1.0)),
        Err(ShapeError::BadScale { what: "y", .. })
    ));
    // Planes.
    assert!(matches!(Plane::new(DVec3::ZERO, 0.0), Err(ShapeError::BadPlaneNormal { .. })));
    assert!(matches!(
        Plane::new(DVec3::new(f64::NAN, 0.0, 1.0), 0.0),
        Err(ShapeError::BadPlaneNormal { .. })
    ));
    assert_eq!(Plane::new(DVec3::Z, f64::INFINITY), Err(ShapeError::BadPlaneOffset(f64::INFINITY)));
    assert_eq!(Plane::new(DVec3::new(0.0, 0.0, 2.0), 1.0).unwrap().normal, DVec3::Z);

    // Static-only shapes on moving bodies.
    let mut world = World::default();
    for (kind, shape) in [
        (BodyKind::Dynamic, floor_plane()),
        (BodyKind::Kinematic, floor_plane()),
        (BodyKind::Dynamic, Shape::HeightField(flat_heightfield(3, 1.0, 0.0))),
        (BodyKind::Dynamic, Shape::TriMesh(floor.clone())),
    ] {
        let e = world
            .add_body(BodyDef {
                name: "ground".into(),
                kind,
                shape: Some(shape.clone()),
                ..Default::default()
            })
            .unwrap_err();
        assert!(matches!(e, WorldError::InvalidBody { .. }), "{e}");
        let text = e.to_string();
        assert!(text.contains("\"ground\"") && text.contains("static"), "{text}");
    }
    // ... and they are fine on static bodies.
    for shape in [floor_plane(), Shape::HeightField(flat_heightfield(3, 1.0, 0.0)), Shape::TriMesh(floor)] {
        world.add_body(BodyDef { kind: BodyKind::Static, shape: Some(shape), ..Default::default() }).unwrap();
    }
    assert_eq!(world.body_count(), 3);
}
