use tumble::*;
fn main() {
    let mut world = World::new(WorldDef { solver: SolverSettings { substeps: std::env::var("SUB").map(|s| s.parse().unwrap()).unwrap_or(4), contact_hertz: std::env::var("HZ").map(|s| s.parse().unwrap()).unwrap_or(30.0), ..Default::default() }, ..Default::default() }).unwrap();
    world.add_body(BodyDef { kind: BodyKind::Static, shape: Some(Shape::Cuboid(Cuboid::new(DVec3::new(10.0, 10.0, 0.5)).unwrap())), position: DVec3::new(0.0,0.0,-0.5), ..Default::default() }).unwrap();
    let mut ids = vec![];
    let nbox: usize = std::env::var("N").map(|s| s.parse().unwrap()).unwrap_or(10); for i in 0..nbox {
        ids.push(world.add_body(BodyDef { shape: Some(Shape::Cuboid(Cuboid::new(DVec3::splat(0.5)).unwrap())), position: DVec3::new(0.0,0.0,0.5 + i as f64), material: Material { friction: std::env::var("MU").map(|s| s.parse().unwrap()).unwrap_or(0.6), ..Default::default() }, ..Default::default() }).unwrap());
    }
    for n in 0..600 {
        world.step(1.0/60.0).unwrap();
        if n % 60 == 0 {
            let top = world.body(*ids.last().unwrap()).unwrap();
            println!("t={:.1} top z={:.5} contacts={} awake={}", n as f64/60.0, top.position().z, world.contact_count(), world.awake_body_count());
        }
    }
    for (i, id) in ids.iter().enumerate() {
        let b = world.body(*id).unwrap();
        println!("{i}: {:.5} {:.5} {:.5}", b.position().x, b.position().y, b.position().z - (0.5 + i as f64));
    }
}
