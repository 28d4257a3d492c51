//! A static bounding volume hierarchy over the triangles of a mesh, built once.
//!
//! Static geometry never moves relative to its own frame, so the tree is built top-down in one
//! pass and never refitted: each node's primitives are split at the median centroid along the
//! widest axis of their centroid bounds, down to leaves of at most [`LEAF_SIZE`] primitives. The
//! nodes live in one array with siblings side by side; queries walk it with a small stack.
//! Everything is in the mesh's local frame.

use super::aabb::Aabb;
use crate::math::DVec3;

/// Most primitives in a leaf.
pub const LEAF_SIZE: usize = 4;

#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
struct Node {
    aabb: Aabb,
    /// Leaf: index of the first primitive in `order`; internal: index of the first child (the
    /// second is `first + 1`).
    first: u32,
    /// Primitives in a leaf; 0 for an internal node.
    count: u32,
}

/// The tree: nodes (root first) and the primitive order its leaves index into.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct MeshBvh {
    nodes: Vec<Node>,
    order: Vec<u32>,
}

impl MeshBvh {
    /// Builds the tree over primitives with the given bounds (primitive `i` has bounds `boxes[i]`).
    pub fn build(boxes: &[Aabb]) -> MeshBvh {
        let mut order: Vec<u32> = (0..boxes.len() as u32).collect();
        let centroids: Vec<DVec3> = boxes.iter().map(Aabb::center).collect();
        let mut nodes = Vec::with_capacity(2 * boxes.len() / LEAF_SIZE + 1);
        if boxes.is_empty() {
            return MeshBvh { nodes, order };
        }
        nodes.push(Node { aabb: Aabb::EMPTY, first: 0, count: boxes.len() as u32 });
        // (node, start, end) still to be processed.
        let mut work = vec![(0usize, 0usize, boxes.len())];
        while let Some((node, start, end)) = work.pop() {
            let slice = &mut order[start..end];
            let aabb = slice.iter().fold(Aabb::EMPTY, |b, &i| b.union(&boxes[i as usize]));
            nodes[node].aabb = aabb;
            if slice.len() <= LEAF_SIZE {
                nodes[node].first = start as u32;
                nodes[node].count = slice.len() as u32;
                continue;
            }
            let cb = Aabb::from_points(slice.iter().map(|&i| centroids[i as usize]));
            let extent = cb.max - cb.min;
            let axis = if extent.x >= extent.y && extent.x >= extent.z {
                0
            } else if extent.y >= extent.z {
                1
            } else {
                2
            };
            let mid = slice.len() / 2;
            // Ties broken by index keep the build deterministic.
            slice.select_nth_unstable_by(mid, |&a, &b| {
                centroids[a as usize][axis].total_cmp(&centroids[b as usize][axis]).then(a.cmp(&b))
            });
            let left = nodes.len();
            nodes.push(Node { aabb: Aabb::EMPTY, first: 0, count: 0 });
            nodes.push(Node { aabb: Aabb::EMPTY, first: 0, count: 0 });
            nodes[node].first = left as u32;
            nodes[node].count = 0;
            work.push((left + 1, start + mid, end));
            work.push((left, start, start + mid));
        }
        MeshBvh { nodes, order }
    }

    /// Bounds of everything in the tree (`Aabb::EMPTY` when empty).
    pub fn root_aabb(&self) -> Aabb {
        self.nodes.first().map_or(Aabb::EMPTY, |n| n.aabb)
    }

    /// Number of nodes (for tests and statistics).
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Calls `visit` with the primitives of every leaf whose box overlaps `aabb`, in a fixed
    /// order: every primitive whose bounds overlap `aabb`, and possibly some leaf-mates of them
    /// (callers test the primitives themselves; the tree keeps no per-primitive boxes).
    pub fn query(&self, aabb: &Aabb, mut visit: impl FnMut(u32)) {
        if self.nodes.is_empty() {
            return;
        }
        let mut stack = [0u32; 64];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let node = &self.nodes[stack[top] as usize];
            if !node.aabb.overlaps(aabb) {
                continue;
            }
            if node.count > 0 {
                let start = node.first as usize;
                for &i in &self.order[start..start + node.count as usize] {
                    visit(i);
                }
            } else {
                // Depth is at most log2(n / LEAF_SIZE) + 1 for a median split, far below 64.
                stack[top] = node.first + 1;
                stack[top + 1] = node.first;
                top += 2;
            }
        }
    }

    /// The closest primitive hit by the ray `origin + t·direction`, `t ∈ [0, max_t]`: `hit(i, t_max)`
    /// tests primitive `i` and returns its hit distance if it is below `t_max`. Returns the
    /// primitive and distance of the closest hit.
    pub fn ray_cast(
        &self,
        origin: DVec3,
        direction: DVec3,
        max_t: f64,
        mut hit: impl FnMut(u32, f64) -> Option<f64>,
    ) -> Option<(u32, f64)> {
        if self.nodes.is_empty() {
            return None;
        }
        let mut best: Option<(u32, f64)> = None;
        let mut t_max = max_t;
        let mut stack = [0u32; 64];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let node = &self.nodes[stack[top] as usize];
            if node.aabb.ray_interval(origin, direction, t_max).is_none() {
                continue;
            }
            if node.count > 0 {
                let start = node.first as usize;
                for &i in &self.order[start..start + node.count as usize] {
                    if let Some(t) = hit(i, t_max) {
                        if t <= t_max {
                            t_max = t;
                            best = Some((i, t));
                        }
                    }
                }
            } else {
                // Visit the nearer child first so the far one is often pruned by the shorter ray.
                let (a, b) = (node.first, node.first + 1);
                let entry = |n: u32| {
                    self.nodes[n as usize]
                        .aabb
                        .ray_interval(origin, direction, t_max)
                        .map_or(f64::INFINITY, |r| r.0)
                };
                let (near, far) = if entry(a) <= entry(b) { (a, b) } else { (b, a) };
                stack[top] = far;
                stack[top + 1] = near;
                top += 2;
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn query_finds_exactly_the_overlapping_boxes() {
        let boxes: Vec<Aabb> = (0..100)
            .map(|i| {
                let c = DVec3::new((i % 10) as f64, (i / 10) as f64, 0.0);
                Aabb::from_center_half_extents(c, DVec3::splat(0.3))
            })
            .collect();
        let bvh = MeshBvh::build(&boxes);
        let q = Aabb::new(DVec3::new(2.5, 3.5, -1.0), DVec3::new(4.5, 4.5, 1.0));
        let mut found = Vec::new();
        bvh.query(&q, |i| found.push(i));
        found.sort_unstable();
        let expected: Vec<u32> = (0..100).filter(|&i| boxes[i as usize].overlaps(&q)).collect();
        assert!(expected.iter().all(|i| found.contains(i)), "{found:?} misses some of {expected:?}");
        // Only leaf-mates come extra: at most a leaf's worth per overlapping leaf.
        assert!(found.len() <= expected.len() * LEAF_SIZE, "{found:?}");
        assert!(bvh.root_aabb().contains(&boxes[57]));
    }
}
