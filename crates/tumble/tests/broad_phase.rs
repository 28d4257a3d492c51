//! Dynamic tree and broad phase: invariants under random edits, pairs against brute force,
//! independence from insertion order, determinism.

use proptest::prelude::*;
use tumble::collision::{Aabb, BroadPhase, DynamicTree, ProxyId, ProxyKey, ProxyKind, ProxyUpdate, Ray};
use tumble::DVec3;

fn vec3(range: f64) -> impl Strategy<Value = DVec3> {
    (-range..range, -range..range, -range..range).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

fn small_box() -> impl Strategy<Value = Aabb> {
    (vec3(20.0), (0.05..2.0f64, 0.05..2.0f64, 0.05..2.0f64))
        .prop_map(|(c, (x, y, z))| Aabb::from_center_half_extents(c, DVec3::new(x, y, z)))
}

#[derive(Clone, Debug)]
enum Op {
    Insert(Aabb),
    /// Move the proxy picked by the index (modulo the live count) by a delta, with a displacement.
    Move(usize, DVec3, DVec3),
    Remove(usize),
}

fn op() -> impl Strategy<Value = Op> {
    prop_oneof![
        3 => small_box().prop_map(Op::Insert),
        4 => (any::<usize>(), vec3(1.5), vec3(0.5)).prop_map(|(i, d, v)| Op::Move(i, d, v)),
        1 => any::<usize>().prop_map(Op::Remove),
    ]
}

/// Applies `ops` to a tree, checking it against a plain list model as it goes. Returns the tree.
fn run_ops(ops: &[Op], check_every: usize) -> DynamicTree {
    let mut tree = DynamicTree::new(0.1);
    // Model: (id, tight box, user data) in creation order.
    let mut live: Vec<(ProxyId, Aabb, u64)> = Vec::new();
    for (step, op) in ops.iter().enumerate() {
        match *op {
            Op::Insert(aabb) => {
                let user = step as u64;
                live.push((tree.create_proxy(aabb, user), aabb, user));
            }
            Op::Move(i, delta, displacement) if !live.is_empty() => {
                let k = i % live.len();
                let (id, old, _) = live[k];
                let aabb = Aabb::new(old.min + delta, old.max + delta);
                let before = tree.fat_aabb(id);
                let moved = tree.move_proxy(id, aabb, displacement);
                if !before.contains(&aabb) {
                    assert!(moved, "a box that left its fat box must be re-inserted");
                }
                if !moved {
                    assert_eq!(tree.fat_aabb(id), before, "an unmoved proxy keeps its fat box");
                }
                live[k].1 = aabb;
            }
            Op::Remove(i) if !live.is_empty() => {
                let (id, _, _) = live.remove(i % live.len());
                tree.destroy_proxy(id);
            }
            _ => {}
        }
        if step % check_every == 0 || step + 1 == ops.len() {
            tree.validate().unwrap_or_else(|e| panic!("after op {step} ({op:?}): {e}"));
            assert_eq!(tree.proxy_count(), live.len());
            for &(id, tight, user) in &live {
                assert!(tree.fat_aabb(id).contains(&tight), "fat box lost its proxy");
                assert_eq!(tree.user_data(id), user);
            }
        }
    }
    // Queries agree with a linear scan of the model.
    let probe = Aabb::from_center_half_extents(DVec3::ZERO, DVec3::splat(6.0));
    let mut found = Vec::new();
    tree.query(&probe, |id| {
        found.push(id);
        true
    });
    found.sort();
    let mut expected: Vec<ProxyId> =
        live.iter().filter(|(id, _, _)| tree.fat_aabb(*id).overlaps(&probe)).map(|(id, _, _)| *id).collect();
    expected.sort();
    assert_eq!(found, expected);
    tree
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn tree_invariants_hold_under_random_edits(ops in prop::collection::vec(op(), 1000..3000)) {
        let tree = run_ops(&ops, 50);
        // A balanced tree of n leaves is far shallower than n.
        let n = tree.proxy_count().max(2) as f64;
        prop_assert!((tree.height() as f64) <= 3.0 * n.log2() + 2.0, "height {} for {n} leaves", tree.height());
    }

    #[test]
    fn same_operations_build_the_same_tree(ops in prop::collection::vec(op(), 200..600)) {
        let a = run_ops(&ops, 1000);
        let b = run_ops(&ops, 1000);
        prop_assert_eq!(format!("{a:?}"), format!("{b:?}"));
    }
}

/// A random scene: boxes with a kind; some dynamic boxes then move.
#[derive(Clone, Debug)]
struct Scene {
    proxies: Vec<(Aabb, ProxyKind)>,
    moves: Vec<(usize, DVec3)>,
}

fn scene() -> impl Strategy<Value = Scene> {
    let kind = prop_oneof![1 => Just(ProxyKind::Static), 3 => Just(ProxyKind::Dynamic)];
    (
        prop::collection::vec((small_box(), kind), 1..300),
        prop::collection::vec((any::<usize>(), vec3(2.0)), 0..200),
    )
        .prop_map(|(proxies, moves)| Scene { proxies, moves })
}

/// Builds the scene inserting proxies in `order`; user data is the proxy's index in the scene.
/// Returns the broad phase and the keys by scene index.
fn build(scene: &Scene, order: &[usize]) -> (BroadPhase, Vec<ProxyKey>) {
    let mut bp = BroadPhase::new(0.1);
    let mut keys = vec![None; scene.proxies.len()];
    for &i in order {
        let (aabb, kind) = scene.proxies[i];
        keys[i] = Some(bp.create_proxy(aabb, kind, i as u64));
    }
    let keys: Vec<ProxyKey> = keys.into_iter().map(Option::unwrap).collect();
    let updates: Vec<ProxyUpdate> = scene
        .moves
        .iter()
        .map(|&(i, delta)| {
            let i = i % scene.proxies.len();
            let (aabb, _) = scene.proxies[i];
            ProxyUpdate {
                key: keys[i],
                aabb: Aabb::new(aabb.min + delta, aabb.max + delta),
                displacement: delta,
            }
        })
        .collect();
    bp.update(&updates);
    (bp, keys)
}

fn brute_force_pairs(bp: &BroadPhase, keys: &[ProxyKey]) -> Vec<(ProxyKey, ProxyKey)> {
    let mut pairs = Vec::new();
    for (i, &a) in keys.iter().enumerate() {
        for &b in &keys[i + 1..] {
            let both_static = a.kind() == ProxyKind::Static && b.kind() == ProxyKind::Static;
            if !both_static && bp.fat_aabb(a).overlaps(&bp.fat_aabb(b)) {
                pairs.push((a.min(b), a.max(b)));
            }
        }
    }
    pairs.sort();
    pairs
}

/// Pairs named by user data (scene indices), which do not depend on the order of insertion.
fn by_user(bp: &BroadPhase, pairs: &[(ProxyKey, ProxyKey)]) -> Vec<(u64, u64)> {
    let mut named: Vec<(u64, u64)> = pairs
        .iter()
        .map(|&(a, b)| {
            let (ua, ub) = (bp.user_data(a), bp.user_data(b));
            (ua.min(ub), ua.max(ub))
        })
        .collect();
    named.sort();
    named
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn find_pairs_equals_brute_force(scene in scene()) {
        let order: Vec<usize> = (0..scene.proxies.len()).collect();
        let (bp, keys) = build(&scene, &order);
        bp.tree(ProxyKind::Static).validate().unwrap();
        bp.tree(ProxyKind::Dynamic).validate().unwrap();
        let pairs = bp.find_pairs();
        prop_assert!(pairs.windows(2).all(|w| w[0] < w[1]), "sorted, each pair once");
        prop_assert!(pairs.iter().all(|(a, b)| a < b), "lower key first");
        prop_assert_eq!(pairs, brute_force_pairs(&bp, &keys));
    }

    #[test]
    fn find_pairs_is_independent_of_insertion_order(scene in scene(), seed in any::<u64>()) {
        let forward: Vec<usize> = (0..scene.proxies.len()).collect();
        let mut shuffled = forward.clone();
        // Fisher–Yates with a small LCG so the permutation comes from the proptest seed.
        let mut s = seed | 1;
        for i in (1..shuffled.len()).rev() {
            s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            shuffled.swap(i, (s >> 33) as usize % (i + 1));
        }
        let (bp1, _) = build(&scene, &forward);
        let (bp2, _) = build(&scene, &shuffled);
        prop_assert_eq!(by_user(&bp1, &bp1.find_pairs()), by_user(&bp2, &bp2.find_pairs()));
        // Same history, same keys: the raw pair lists are identical too.
        let (bp3, _) = build(&scene, &forward);
        prop_assert_eq!(bp1.find_pairs(), bp3.find_pairs());
    }

    #[test]
    fn new_pairs_are_the_pairs_of_moved_proxies(scene in scene()) {
        let order: Vec<usize> = (0..scene.proxies.len()).collect();
        let (mut bp, keys) = build(&scene, &order);
        let all = bp.find_pairs();
        // Everything was just created, so every pair is new.
        prop_assert_eq!(bp.find_new_pairs(), all.clone());
        // Move a few dynamic proxies far enough to be re-inserted.
        let mut moved = Vec::new();
        for (i, &key) in keys.iter().enumerate().step_by(7) {
            if key.kind() == ProxyKind::Dynamic {
                let fat = bp.fat_aabb(key);
                let delta = DVec3::new(1.0 + (i % 3) as f64, 0.0, 0.0);
                let tight = Aabb::new(fat.min + DVec3::splat(0.1) + delta, fat.max - DVec3::splat(0.1) + delta);
                prop_assert!(bp.move_proxy(key, tight, DVec3::ZERO));
                moved.push(key);
            }
        }
        let all = bp.find_pairs();
        let expected: Vec<_> =
            all.iter().copied().filter(|(a, b)| moved.contains(a) || moved.contains(b)).collect();
        prop_assert_eq!(bp.find_new_pairs(), expected);
    }

    #[test]
    fn ray_cast_finds_the_nearest_fat_box(scene in scene(), origin in vec3(30.0), dir in vec3(1.0)) {
        prop_assume!(dir.length() > 1e-3);
        let order: Vec<usize> = (0..scene.proxies.len()).collect();
        let (bp, keys) = build(&scene, &order);
        let ray = Ray::new(origin, dir, 80.0);
        let entry = |key: ProxyKey, r: &Ray| {
            bp.fat_aabb(key).ray_interval(r.origin, r.direction, r.max_distance).map(|(t, _)| t)
        };
        let mut best = f64::INFINITY;
        bp.ray_cast(&ray, |r, key| {
            let t = entry(key, r).expect("callback only for boxes the clipped ray reaches");
            best = best.min(t);
            if t == 0.0 { 0.0 } else { t }
        });
        let brute = keys.iter().filter_map(|&k| entry(k, &ray)).fold(f64::INFINITY, f64::min);
        prop_assert_eq!(best, brute);
    }
}

#[test]
fn area_ratio_and_height_of_a_grid_are_reasonable() {
    let mut tree = DynamicTree::new(0.0);
    for i in 0..20 {
        for j in 0..20 {
            for k in 0..5 {
                let c = DVec3::new(i as f64, j as f64, k as f64) * 1.5;
                tree.create_proxy(Aabb::from_center_half_extents(c, DVec3::splat(0.5)), 0);
            }
        }
    }
    tree.validate().unwrap();
    assert!(tree.height() <= 16, "height {}", tree.height());
    // An ideal split of n boxes filling a volume halves the volume per level, so level k adds
    // about 2^(k/3) root areas: Σ_{k<=log2 n} 2^(k/3) ≈ 50 for n = 2000. Allow 20% over that.
    assert!(tree.area_ratio() < 60.0, "area ratio {}", tree.area_ratio());
}
