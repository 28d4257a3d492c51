//! Broad phase under load: 10,000 boxes drifting in a closed volume, as a world step would see
//! them. One iteration = advance the boxes by one 60 Hz step, `update` the broad phase with every
//! box's new tight AABB and predicted displacement, then search pairs.

use criterion::{criterion_group, criterion_main, Criterion};
use tumble::collision::{Aabb, BroadPhase, ProxyKey, ProxyKind, ProxyUpdate};
use tumble::DVec3;

const COUNT: usize = 10_000;
/// Half the side of the cube the boxes live in: about one box per 22 m³, a busy but not packed
/// scene (a few candidate pairs per box).
const HALF_SIDE: f64 = 14.0;
const DT: f64 = 1.0 / 60.0;

/// A small deterministic generator, so every run measures the same scene.
struct Lcg(u64);
impl Lcg {
    fn unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
    fn vec(&mut self, r: f64) -> DVec3 {
        DVec3::new(self.range(-r, r), self.range(-r, r), self.range(-r, r))
    }
}

struct Scene {
    bp: BroadPhase,
    keys: Vec<ProxyKey>,
    centers: Vec<DVec3>,
    velocities: Vec<DVec3>,
    half_extents: Vec<DVec3>,
    moves: Vec<ProxyUpdate>,
}

impl Scene {
    fn new() -> Self {
        let mut rng = Lcg(7);
        let mut bp = BroadPhase::default();
        let (mut keys, mut centers, mut velocities, mut half_extents) = (vec![], vec![], vec![], vec![]);
        for i in 0..COUNT {
            let c = rng.vec(HALF_SIDE);
            let h = DVec3::new(rng.range(0.2, 0.6), rng.range(0.2, 0.6), rng.range(0.2, 0.6));
            keys.push(bp.create_proxy(Aabb::from_center_half_extents(c, h), ProxyKind::Dynamic, i as u64));
            centers.push(c);
            velocities.push(rng.vec(3.0));
            half_extents.push(h);
        }
        // A static floor of 20 × 20 tiles under the volume.
        for i in 0..400 {
            let c =
                DVec3::new((i % 20) as f64 * 1.5 - 14.25, (i / 20) as f64 * 1.5 - 14.25, -HALF_SIDE - 0.5);
            bp.create_proxy(
                Aabb::from_center_half_extents(c, DVec3::new(0.75, 0.75, 0.5)),
                ProxyKind::Static,
                u64::MAX,
            );
        }
        bp.find_new_pairs();
        Self { bp, keys, centers, velocities, half_extents, moves: Vec::with_capacity(COUNT) }
    }

    /// Moves every box one step, bouncing off the walls, and updates the broad phase.
    fn step(&mut self) -> usize {
        self.moves.clear();
        for i in 0..COUNT {
            let mut c = self.centers[i] + self.velocities[i] * DT;
            for k in 0..3 {
                if c[k].abs() > HALF_SIDE {
                    self.velocities[i][k] = -self.velocities[i][k];
                    c[k] = c[k].clamp(-HALF_SIDE, HALF_SIDE);
                }
            }
            self.centers[i] = c;
            let aabb = Aabb::from_center_half_extents(c, self.half_extents[i]);
            self.moves.push(ProxyUpdate { key: self.keys[i], aabb, displacement: self.velocities[i] * DT });
        }
        self.bp.update(&self.moves)
    }
}

fn broad_phase(c: &mut Criterion) {
    let mut scene = Scene::new();
    let pairs = scene.bp.find_pairs().len();
    let tree = scene.bp.tree(ProxyKind::Dynamic);
    eprintln!(
        "{COUNT} boxes, {pairs} candidate pairs at start; tree height {}, area ratio {:.1}",
        tree.height(),
        tree.area_ratio()
    );
    let mut warm = Scene::new();
    for _ in 0..120 {
        warm.step();
    }
    let tree = warm.bp.tree(ProxyKind::Dynamic);
    eprintln!(
        "after 120 steps: {} pairs; tree height {}, area ratio {:.1}",
        warm.bp.find_pairs().len(),
        tree.height(),
        tree.area_ratio()
    );
    c.bench_function("broad_phase/10k_boxes/update+find_pairs", |b| {
        b.iter(|| {
            scene.step();
            scene.bp.find_pairs().len()
        })
    });
    let mut scene = Scene::new();
    c.bench_function("broad_phase/10k_boxes/update_only", |b| b.iter(|| scene.step()));
    c.bench_function("broad_phase/10k_boxes/find_pairs_only", |b| b.iter(|| scene.bp.find_pairs().len()));
    let mut scene = Scene::new();
    c.bench_function("broad_phase/10k_boxes/update+find_new_pairs", |b| {
        b.iter(|| {
            scene.step();
            scene.bp.find_new_pairs().len()
        })
    });
}

criterion_group!(benches, broad_phase);
criterion_main!(benches);
