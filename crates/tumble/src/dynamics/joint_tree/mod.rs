//! Joint trees: the equality rows of tree-shaped groups of joints (chains, ragdolls, robot arms)
//! solved exactly in each pass, in time linear in the number of joints (Baraff, "Linear-time
//! dynamics using Lagrange multipliers", SIGGRAPH 1996). Derivation: `docs/joint-tree.md`.
//!
//! Row-by-row Gauss–Seidel lets a joint stretch under a load it cannot feel in one sweep: a weight
//! of 100 link masses on a chain of 20 pulls its joints apart by centimetres. Solving all the rows
//! of the figure at once gives the impulses that make every joint's velocity error exactly what
//! is asked for, whatever the mass ratios.
//!
//! For the velocity change `Δv` of the figure's bodies and the impulses `λ` of its joints' rows,
//!
//! ```text
//! [ M  Jᵀ ] [ Δv ]   [ 0 ]
//! [ J  0  ] [ −λ ] = [ r ],    r = −(J v + β C)   (β = 0 in the relax pass)
//! ```
//!
//! The graph of this matrix is the figure itself: a node per body, a node per joint, an edge where
//! a joint touches a body. When that graph is a tree, eliminating every node before its parent
//! (leaves first) creates no fill: each elimination only updates the parent's diagonal block, so
//! the factorisation is a sequence of small dense blocks (`block.rs`) — body blocks stay positive
//! definite, joint blocks negative definite, and `LDLᵀ` needs no pivoting.
//!
//! Bodies that do not move in the solve (static, kinematic, asleep) are one "ground": a joint to
//! the ground has a single body neighbour. A joint leaf would have an empty block, so a figure
//! hung from the ground is rooted at that joint; a second joint to the ground, or any joint that
//! closes a loop, stays with the row-by-row solve, as do distance joints and joints with motors,
//! springs or friction (`Joint::tree_row_count`), and every joint of a figure one of those also
//! acts on (`leave_out_held_figures`). A joint's limit rows join its block while they push (an
//! active set, `solve`), so a ragdoll is a tree too. The rows solved here are rigid at the
//! velocity level; their drift is taken out by the position projection (`projection.rs`), or,
//! with the projection off, fed back at the rate `β` of the joint softness. Warm starting, force
//! reporting and breaking use the same accumulated impulses as the row-by-row parts.

pub(crate) mod block;
mod projection;

use crate::dynamics::joint::equality::EqualityRows;
use crate::dynamics::joint::limit_rows::{LimitRows, MAX_LIMIT_ROWS};
use crate::dynamics::joint::Joint;
use crate::dynamics::solver_body::SolverBody;
use crate::id::{RawId, Slot, SlotPool};
use crate::math::DVec3;
use block::{Block, BlockVector, Ldlt, MAX_DIM};
use std::ops::Range;

const NONE: u32 = u32::MAX;

/// The largest turn of any tree body in a substep, rad, up to which the position projection's
/// first step reuses the velocity solve's factors.
const CHORD_TURN: f64 = 0.1;

/// How many times the position projection halves a step that made the error larger.
const MAX_HALVINGS: u32 = 4;

/// Rounds of the limit rows' active set in one velocity solve that may both take rows in and
/// let them go; after these, rounds only let go of rows pulling (up to [`MAX_ACTIVE_SET_ROUNDS`]).
const CHOOSING_ROUNDS: u32 = 3;

/// Most solves of the trees in one pass while the limit rows' active set changes.
const MAX_ACTIVE_SET_ROUNDS: u32 = 6;

/// How far below its target velocity (rad/s or m/s) a limit row left out may end a round before
/// it is taken in: round-off, not a physical tolerance.
const ACTIVATION_SLACK: f64 = 1e-9;

/// What `assemble` found.
struct Assembled {
    /// The largest position error of any equality row, or of an eligible limit row past its
    /// limit (how far past; in the projection, whether taken in or not).
    largest_error: f64,
    /// Some joint has limit rows.
    limited: bool,
}

/// What a solve makes of the rows: their velocities `−β C` (the equality rows) and at least their
/// targets (the limit rows: `−C/h` before the limit, `−β C` past it), or their position errors
/// zero (the equality rows, and the limit rows past their limits).
#[derive(Clone, Copy, Debug)]
enum Target {
    Velocity { bias_rate: f64, inv_h: f64 },
    Position,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum NodeKind {
    Body { slot: u32 },
    Joint { slot: u32 },
}

/// One node of the elimination, with its blocks for the current pass.
#[derive(Clone, Copy, Debug)]
struct Node {
    kind: NodeKind,
    /// 6 for a body; for a joint, its equality rows and the limit rows taken in this pass.
    dim: usize,
    /// For a joint: the number of its equality rows (its block's first rows).
    equality_dim: usize,
    /// For a joint: its body slots (a, b) as last assembled.
    ends: (u32, u32),
    /// For a joint: its limit rows as last assembled, and which of them are in its block.
    limits: LimitRows,
    active: [bool; MAX_LIMIT_ROWS],
    /// For a joint's limit rows in a velocity solve: `Ċ` before the solve, and its target.
    limit_velocity: [f64; MAX_LIMIT_ROWS],
    limit_target: [f64; MAX_LIMIT_ROWS],
    /// The parent's index in `nodes` (always later), or `NONE` for a root.
    parent: u32,
    /// For a joint: the nodes of its bodies that are its children (`NONE` where unused).
    body_children: [u32; 2],
    /// `H_ip`: the block coupling this node to its parent (`dim × parent.dim`).
    coupling: Block,
    /// The diagonal block, updated by the children's eliminations.
    diagonal: Block,
    /// `D⁻¹ H_ip`, the elimination multiplier.
    multiplier: Block,
    factor: Ldlt,
    /// Right-hand side, then solution.
    x: BlockVector,
    /// For a body: its last displacement in the position projection (shift, turn).
    step: [f64; 6],
}

impl Node {
    fn new(kind: NodeKind, dim: usize) -> Node {
        Node {
            kind,
            dim,
            equality_dim: dim,
            ends: (0, 0),
            limits: LimitRows::default(),
            active: [false; MAX_LIMIT_ROWS],
            limit_velocity: [0.0; MAX_LIMIT_ROWS],
            limit_target: [0.0; MAX_LIMIT_ROWS],
            parent: NONE,
            body_children: [NONE; 2],
            coupling: Block::zero(0, 0),
            diagonal: Block::zero(dim, dim),
            multiplier: Block::zero(0, 0),
            factor: Ldlt::EMPTY,
            x: [0.0; MAX_DIM],
            step: [0.0; 6],
        }
    }
}

/// The joint trees of one step, and the buffers they are built in (kept to reuse their
/// allocations).
#[derive(Clone, Debug, Default)]
pub(crate) struct JointTrees {
    /// All trees' nodes in elimination order: every node before its parent.
    nodes: Vec<Node>,
    /// Union–find over body slots, with one extra element for the ground.
    union_find: Vec<u32>,
    /// Per body slot: its node during the build (`NONE`: not in a tree).
    node_of_body: Vec<u32>,
    /// Joint slots in the trees, in slot order.
    tree_joints: Vec<u32>,
    /// Per body slot: where its joints start in `body_joints` (CSR), and the joints.
    body_joint_start: Vec<u32>,
    body_joints: Vec<u32>,
    /// Breadth-first order of the build: (node, parent position in this list).
    breadth_first: Vec<(NodeKind, u32)>,
    joint_visited: Vec<bool>,
    /// The nodes hold the factors of their blocks as last assembled.
    factored: bool,
    /// What the trees were built from: each tree joint (in slot order) with its row count and
    /// whether its bodies move; and this step's, to compare.
    key: Vec<(RawId, u8, bool, bool)>,
    next_key: Vec<(RawId, u8, bool, bool)>,
    /// Per figure root (a body slot): a joint outside the trees acts on the figure
    /// (`leave_out_held_figures`).
    held: Vec<bool>,
    /// The node ranges of the trees, and of the free figures among them (trees rooted at a
    /// body, not hung from the ground).
    trees: Vec<Range<usize>>,
    free_figures: Vec<Range<usize>>,
    /// Each free figure's centre of mass and angular momentum about it before the projection.
    momenta: Vec<(DVec3, DVec3)>,
}

/// Whether a solver body is one of the figure's moving bodies (finite, positive mass).
fn moves(body: &SolverBody) -> bool {
    body.has_mass_matrix()
}

fn find(parents: &mut [u32], mut i: u32) -> u32 {
    while parents[i as usize] != i {
        let grandparent = parents[parents[i as usize] as usize];
        parents[i as usize] = grandparent;
        i = grandparent;
    }
    i
}

impl JointTrees {
    /// No trees this step: every joint is solved row by row.
    pub fn clear(&mut self, joints: &mut SlotPool<Joint>) {
        self.nodes.clear();
        self.free_figures.clear();
        self.trees.clear();
        self.key.clear();
        for (_, joint) in joints.iter_mut() {
            joint.in_tree = false;
        }
    }

    /// Builds this step's trees from the joints being solved, and marks each joint `in_tree`.
    /// `limits`: joints with limits may be tree joints (`SolverSettings::joint_tree_limits`).
    pub fn build(&mut self, joints: &mut SlotPool<Joint>, bodies: &[SolverBody], limits: bool) {
        self.factored = false;
        self.tree_joints.clear();
        self.next_key.clear();
        let ground = bodies.len() as u32;
        self.union_find.clear();
        self.union_find.extend(0..=ground);

        // Accept joints in slot order while they keep the graph a forest.
        for (_, joint) in joints.iter_mut() {
            joint.in_tree = false;
            if !joint.solving || joint.tree_row_count(limits) == 0 {
                continue;
            }
            let (ia, ib) = (joint.body_a.index(), joint.body_b.index());
            let (moves_a, moves_b) = (moves(&bodies[ia]), moves(&bodies[ib]));
            if !moves_a && !moves_b {
                continue;
            }
            let ra = find(&mut self.union_find, if moves_a { ia as u32 } else { ground });
            let rb = find(&mut self.union_find, if moves_b { ib as u32 } else { ground });
            if ra == rb {
                continue; // closes a loop (through the ground or not)
            }
            self.union_find[ra as usize] = rb;
            joint.in_tree = true;
        }
        self.leave_out_held_figures(joints, bodies);
        for (id, joint) in joints.iter() {
            if joint.in_tree {
                let (moves_a, moves_b) =
                    (moves(&bodies[joint.body_a.index()]), moves(&bodies[joint.body_b.index()]));
                self.tree_joints.push(id.index() as u32);
                self.next_key.push((id, joint.tree_row_count(limits) as u8, moves_a, moves_b));
            }
        }
        // The same joints, rows and moving ends as last step make the same trees: keep them (the
        // nodes' blocks are refilled by every solve). Rebuilding them was a tenth of a chain's
        // step.
        if self.next_key == self.key {
            return;
        }
        std::mem::swap(&mut self.key, &mut self.next_key);
        self.nodes.clear();
        self.free_figures.clear();
        self.trees.clear();
        self.breadth_first.clear();
        if self.tree_joints.is_empty() {
            return;
        }

        // Body → joints adjacency (CSR over body slots).
        self.body_joint_start.clear();
        self.body_joint_start.resize(bodies.len() + 1, 0);
        let ends = |joint: &Joint| [joint.body_a.index(), joint.body_b.index()];
        for &slot in &self.tree_joints {
            let joint = joints.iter_slot(slot as usize).expect("tree joints are live");
            for body in ends(joint) {
                if moves(&bodies[body]) {
                    self.body_joint_start[body + 1] += 1;
                }
            }
        }
        for i in 0..bodies.len() {
            self.body_joint_start[i + 1] += self.body_joint_start[i];
        }
        self.body_joints.clear();
        self.body_joints.resize(self.body_joint_start[bodies.len()] as usize, NONE);
        let mut fill = std::mem::take(&mut self.node_of_body);
        fill.clear();
        fill.extend_from_slice(&self.body_joint_start[..bodies.len()]);
        for (k, &slot) in self.tree_joints.iter().enumerate() {
            let joint = joints.iter_slot(slot as usize).expect("tree joints are live");
            for body in ends(joint) {
                if moves(&bodies[body]) {
                    self.body_joints[fill[body] as usize] = k as u32;
                    fill[body] += 1;
                }
            }
        }
        self.node_of_body = fill;
        self.node_of_body.clear();
        self.node_of_body.resize(bodies.len(), NONE);
        self.joint_visited.clear();
        self.joint_visited.resize(self.tree_joints.len(), false);

        // Breadth-first from the roots: a figure's joint to the ground, else its first body.
        for k in 0..self.tree_joints.len() {
            let joint = joints.iter_slot(self.tree_joints[k] as usize).expect("tree joints are live");
            let grounded = ends(joint).iter().any(|&body| !moves(&bodies[body]));
            if grounded && !self.joint_visited[k] {
                self.breadth_first_from(NodeKind::Joint { slot: k as u32 }, joints, bodies);
            }
        }
        for slot in 0..bodies.len() {
            let has_joints = self.body_joint_start[slot] < self.body_joint_start[slot + 1];
            if has_joints && self.node_of_body[slot] == NONE {
                self.breadth_first_from(NodeKind::Body { slot: slot as u32 }, joints, bodies);
            }
        }

        // Elimination order: the breadth-first order reversed (children before parents).
        let n = self.breadth_first.len() as u32;
        for &(kind, parent) in self.breadth_first.iter().rev() {
            let (kind, dim) = match kind {
                NodeKind::Body { slot } => (NodeKind::Body { slot }, 6),
                NodeKind::Joint { slot: k } => {
                    let slot = self.tree_joints[k as usize];
                    let joint = joints.iter_slot(slot as usize).expect("tree joints are live");
                    (NodeKind::Joint { slot }, joint.tree_row_count(limits))
                }
            };
            let mut node = Node::new(kind, dim);
            node.parent = if parent == NONE { NONE } else { n - 1 - parent };
            self.nodes.push(node);
        }
        for i in 0..self.nodes.len() {
            let parent = self.nodes[i].parent;
            if parent != NONE && matches!(self.nodes[i].kind, NodeKind::Body { .. }) {
                let children = &mut self.nodes[parent as usize].body_children;
                let free = if children[0] == NONE { 0 } else { 1 };
                children[free] = i as u32;
            }
        }
        // A tree's nodes are contiguous, its root last; a root that is a body is a free figure.
        let mut start = 0;
        for (i, node) in self.nodes.iter().enumerate() {
            if node.parent == NONE {
                self.trees.push(start..i + 1);
                if matches!(node.kind, NodeKind::Body { .. }) {
                    self.free_figures.push(start..i + 1);
                }
                start = i + 1;
            }
        }
    }

    /// Takes out of the trees every figure (the moving bodies a tree's joints connect) that a
    /// joint left to the row-by-row solve also acts on: one closing a loop, a distance joint, one
    /// with a motor, spring or friction (or a limit, with `joint_tree_limits` off). Its joints go
    /// row by row too.
    ///
    /// Solved exactly, such a figure fights that joint: the tree makes its rows exact and rigid
    /// after the joint's soft rows have acted, so the joint sees its bodies move by more than its
    /// own effective mass allows for, and pushes back harder at the next pass. At the defaults
    /// (`ωh = π/2`) the exchange grows: a ball joint with a swing limit it never reached, beside
    /// a tree of one ball joint, took three free spheres of 50, 5 and 3.5 kg from 1 J to 10¹⁸ J
    /// in ten seconds, and a third of 300 random passive mechanisms gained energy
    /// (`tests/mechanisms.rs`). Row by row both are stable. (Contacts do not count: a chain lying
    /// on the ground stays a tree.)
    fn leave_out_held_figures(&mut self, joints: &mut SlotPool<Joint>, bodies: &[SolverBody]) {
        // The figures: components of the moving bodies over the tree joints (the ground, which
        // joins every grounded figure in the forest test above, left out).
        let slots = bodies.len();
        self.union_find.clear();
        self.union_find.extend(0..slots as u32);
        let moving_ends = |joint: &Joint| {
            let (ia, ib) = (joint.body_a.index(), joint.body_b.index());
            (moves(&bodies[ia]).then_some(ia as u32), moves(&bodies[ib]).then_some(ib as u32))
        };
        for (_, joint) in joints.iter().filter(|(_, j)| j.in_tree) {
            if let (Some(a), Some(b)) = moving_ends(joint) {
                let (ra, rb) = (find(&mut self.union_find, a), find(&mut self.union_find, b));
                self.union_find[ra as usize] = rb;
            }
        }
        // Figures a joint outside the trees touches.
        self.held.clear();
        self.held.resize(slots, false);
        let mut any = false;
        for (_, joint) in joints.iter().filter(|(_, j)| j.solving && !j.in_tree) {
            let (a, b) = moving_ends(joint);
            for body in [a, b].into_iter().flatten() {
                let root = find(&mut self.union_find, body);
                self.held[root as usize] = true;
                any = true;
            }
        }
        if !any {
            return;
        }
        for (_, joint) in joints.iter_mut().filter(|(_, j)| j.in_tree) {
            let (a, b) = moving_ends(joint);
            let body = a.or(b).expect("a tree joint has a moving body");
            if self.held[find(&mut self.union_find, body) as usize] {
                joint.in_tree = false;
            }
        }
    }

    /// Appends the tree reached from `root` to `breadth_first`. Joint nodes carry their index in
    /// `tree_joints` here (their slot only once the order is final).
    fn breadth_first_from(&mut self, root: NodeKind, joints: &SlotPool<Joint>, bodies: &[SolverBody]) {
        let mut head = self.breadth_first.len();
        self.visit(root, NONE);
        while head < self.breadth_first.len() {
            let (kind, _) = self.breadth_first[head];
            match kind {
                NodeKind::Body { slot } => {
                    let (start, end) = (
                        self.body_joint_start[slot as usize] as usize,
                        self.body_joint_start[slot as usize + 1] as usize,
                    );
                    for i in start..end {
                        let k = self.body_joints[i];
                        if !self.joint_visited[k as usize] {
                            self.visit(NodeKind::Joint { slot: k }, head as u32);
                        }
                    }
                }
                NodeKind::Joint { slot: k } => {
                    let joint = joints
                        .iter_slot(self.tree_joints[k as usize] as usize)
                        .expect("tree joints are live");
                    for body in [joint.body_a.index(), joint.body_b.index()] {
                        if moves(&bodies[body]) && self.node_of_body[body] == NONE {
                            self.visit(NodeKind::Body { slot: body as u32 }, head as u32);
                        }
                    }
                }
            }
            head += 1;
        }
    }

    fn visit(&mut self, kind: NodeKind, parent: u32) {
        match kind {
            NodeKind::Body { slot } => self.node_of_body[slot as usize] = self.breadth_first.len() as u32,
            NodeKind::Joint { slot: k } => self.joint_visited[k as usize] = true,
        }
        self.breadth_first.push((kind, parent));
    }

    /// One exact solve of every tree's rows: makes each equality row's velocity `−β C`
    /// (`bias_rate` β; 0 in the relax pass, and in every pass while the position projection holds
    /// the trees), and each limit row's at least its target, pushing only (below); updates the
    /// bodies' velocities and adds the impulses to the joints' accumulated ones.
    ///
    /// The limit rows are an active set: a row is taken into its joint's block, as one more
    /// equality row with its target velocity (`−C/h` before the limit, speculative as in the
    /// row-by-row solve; `−β C` past it), while it pushes. It starts in the set if it pushed at the
    /// end of the last pass (its accumulated impulse is positive) or its velocity is below its
    /// target now; after each solve, a row whose accumulated impulse would turn negative leaves
    /// (its impulse goes back to zero, an impulse the next solve applies), and one left out whose
    /// velocity would end below its target comes in, and the trees are solved again. After
    /// [`CHOOSING_ROUNDS`] rounds rows only leave, so the rounds end.
    pub fn solve(
        &mut self,
        joints: &mut [Slot<Joint>],
        bodies: &mut [SolverBody],
        bias_rate: f64,
        inv_h: f64,
    ) {
        if self.nodes.is_empty() {
            return;
        }
        let target = Target::Velocity { bias_rate, inv_h };
        // Tree by tree: a tree whose active set changes is solved again alone.
        for t in 0..self.trees.len() {
            let tree = self.trees[t].clone();
            let mut round = 0;
            loop {
                let limited = self.assemble(tree.clone(), joints, bodies, target, true, round == 0).limited;
                self.factor(tree.clone());
                self.solve_factored(tree.clone());
                round += 1;
                if !limited
                    || round == MAX_ACTIVE_SET_ROUNDS
                    || !self.update_active_set(tree.clone(), round > CHOOSING_ROUNDS)
                {
                    break;
                }
            }
        }
        self.factored = true;
        for node in &self.nodes {
            match node.kind {
                NodeKind::Body { slot } => {
                    let body = &mut bodies[slot as usize];
                    body.v += DVec3::new(node.x[0], node.x[1], node.x[2]);
                    body.w += DVec3::new(node.x[3], node.x[4], node.x[5]);
                }
                NodeKind::Joint { slot } => {
                    let joint = joints[slot as usize].value_mut().expect("tree joints are live");
                    let mut lambda = [0.0; MAX_DIM];
                    for (l, x) in lambda.iter_mut().zip(&node.x).take(node.dim) {
                        *l = -x;
                    }
                    joint.add_equality_impulse(&lambda[..node.equality_dim]);
                    let mut m = node.equality_dim;
                    for k in 0..node.limits.len {
                        if node.active[k] {
                            joint.add_limit_impulse(k, lambda[m]);
                            m += 1;
                        } else if node.limits.rows[k].impulse != 0.0 {
                            // Let go of: the impulse the solve applied takes it back to zero.
                            joint.add_limit_impulse(k, -node.limits.rows[k].impulse);
                        }
                    }
                }
            }
        }
    }

    /// After a velocity solve: takes out of the active set every limit row whose accumulated
    /// impulse the solve would make negative, and (unless `leave_only`) takes in every eligible
    /// row left out whose velocity would end below its target. Whether the set changed.
    fn update_active_set(&mut self, tree: Range<usize>, leave_only: bool) -> bool {
        let mut changed = false;
        for i in tree {
            if !matches!(self.nodes[i].kind, NodeKind::Joint { .. }) || self.nodes[i].limits.len == 0 {
                continue;
            }
            let (ia, ib) = self.nodes[i].ends;
            let change = |slot: u32| {
                self.body_node(i, slot).map_or([0.0; 6], |n| {
                    let x = self.nodes[n].x;
                    [x[0], x[1], x[2], x[3], x[4], x[5]]
                })
            };
            let (dva, dvb) = (change(ia), change(ib));
            let node = &mut self.nodes[i];
            let mut m = node.equality_dim;
            for k in 0..node.limits.len {
                let row = &node.limits.rows[k];
                if node.active[k] {
                    if row.impulse - node.x[m] < 0.0 {
                        node.active[k] = false;
                        changed = true;
                    }
                    m += 1;
                } else if !leave_only && row.eligible {
                    let j = &row.jacobian;
                    let dot =
                        |u: DVec3, d: &[f64; 6], at: usize| u.x * d[at] + u.y * d[at + 1] + u.z * d[at + 2];
                    let velocity =
                        node.limit_velocity[k] + dot(j.linear_b, &dvb, 0) + dot(j.angular_b, &dvb, 3)
                            - dot(j.linear_a, &dva, 0)
                            - dot(j.angular_a, &dva, 3);
                    if velocity < node.limit_target[k] - ACTIVATION_SLACK {
                        node.active[k] = true;
                        changed = true;
                    }
                }
            }
        }
        changed
    }

    /// The node of body `slot` among joint node `j`'s neighbours, if that body moves.
    fn body_node(&self, j: usize, slot: u32) -> Option<usize> {
        let body = NodeKind::Body { slot };
        let node = &self.nodes[j];
        let parent = node.parent;
        if parent != NONE && self.nodes[parent as usize].kind == body {
            return Some(parent as usize);
        }
        node.body_children
            .into_iter()
            .find(|&c| c != NONE && self.nodes[c as usize].kind == body)
            .map(|c| c as usize)
    }

    /// Fills every node's right-hand side and, with `matrix`, its diagonal and coupling blocks,
    /// for the bodies' state now; returns the largest position error of any row (of a limit row:
    /// how far past its limit). With `choose`, picks the limit rows to take in: for a velocity
    /// solve those pushing at the end of the last pass or moving below their targets now, for the
    /// projection those past their limits; without, keeps the rows taken in. A velocity solve's
    /// right-hand side also applies the impulses that let go of the rows left out
    /// (`add_let_go_impulses`).
    fn assemble(
        &mut self,
        tree: Range<usize>,
        joints: &[Slot<Joint>],
        bodies: &[SolverBody],
        target: Target,
        matrix: bool,
        choose: bool,
    ) -> Assembled {
        let mut largest_error = 0.0_f64;
        let mut limited = false;
        let mut rows = EqualityRows::default();
        for i in tree.clone() {
            let node = &mut self.nodes[i];
            node.x = [0.0; MAX_DIM];
            match node.kind {
                NodeKind::Body { slot } => {
                    if !matrix {
                        continue;
                    }
                    let (mass, inertia) =
                        bodies[slot as usize].mass_matrix().expect("tree bodies have a mass matrix");
                    // Written row by row in place: a block built on the stack and copied in was
                    // a tenth of the tree's time, in memset and memcpy.
                    let d = &mut node.diagonal;
                    (d.rows, d.cols) = (6, 6);
                    for k in 0..3 {
                        let mut linear = [0.0; MAX_DIM];
                        linear[k] = mass;
                        d.m[k] = linear;
                        let i = inertia.row(k);
                        d.m[3 + k] = [0.0, 0.0, 0.0, i.x, i.y, i.z];
                    }
                }
                NodeKind::Joint { slot } => {
                    let joint = joints[slot as usize].value().expect("tree joints are live");
                    let (ia, ib) = (joint.body_a.index(), joint.body_b.index());
                    let (a, b) = (&bodies[ia], &bodies[ib]);
                    node.ends = (ia as u32, ib as u32);
                    let has_rows = joint.tree_rows_into(a, b, &mut rows, &mut node.limits);
                    debug_assert!(has_rows, "tree joints have equality rows");
                    debug_assert_eq!(rows.len, node.equality_dim);
                    for k in 0..rows.len {
                        largest_error = largest_error.max(rows.error[k].abs());
                        node.x[k] = match target {
                            Target::Velocity { bias_rate, .. } => {
                                let cdot = rows.rows[k].velocity(a, b);
                                -(cdot + bias_rate * rows.error[k])
                            }
                            Target::Position => -rows.error[k],
                        };
                    }
                    limited |= node.limits.len > 0;
                    if let Target::Velocity { inv_h, .. } = target {
                        node.limits.choose_approached_sides(1.0 / inv_h, |j| j.velocity(a, b));
                    }
                    // Without `choose` the rows taken in stay as they are, eligible now or not: the
                    // projection's chord step needs exactly the rows its factors were made with.
                    for k in 0..node.limits.len {
                        let row = node.limits.rows[k];
                        let rhs = match target {
                            Target::Velocity { bias_rate, inv_h } => {
                                let cdot = row.jacobian.velocity(a, b);
                                let goal =
                                    if row.error > 0.0 { -row.error * inv_h } else { -bias_rate * row.error };
                                (node.limit_velocity[k], node.limit_target[k]) = (cdot, goal);
                                if choose {
                                    node.active[k] = row.eligible && (row.impulse > 0.0 || cdot < goal);
                                }
                                goal - cdot
                            }
                            Target::Position => {
                                if row.eligible {
                                    largest_error = largest_error.max(-row.error);
                                }
                                if choose {
                                    node.active[k] = row.eligible && row.error < 0.0;
                                }
                                -row.error.min(0.0)
                            }
                        };
                        if node.active[k] {
                            node.x[rows.len] = rhs;
                            rows.push(row.jacobian, row.error);
                        }
                    }
                    node.dim = rows.len;
                    if matrix {
                        node.diagonal.set_zero(node.dim, node.dim);
                        self.couple(i, ia, &rows, -1.0);
                        self.couple(i, ib, &rows, 1.0);
                    }
                }
            }
        }
        if limited && matches!(target, Target::Velocity { .. }) {
            self.add_let_go_impulses(tree);
        }
        Assembled { largest_error, limited }
    }

    /// Adds to the bodies' right-hand sides the impulses that take each limit row left out of the
    /// solve back to zero: the row's accumulated impulse, applied at the warm start, is taken
    /// back (`−λ_acc`), so that the solve's result includes it (`M Δv = Jᵀλ + f`).
    fn add_let_go_impulses(&mut self, tree: Range<usize>) {
        for i in tree {
            let node = &self.nodes[i];
            if !matches!(node.kind, NodeKind::Joint { .. }) {
                continue;
            }
            let (ia, ib) = node.ends;
            for k in 0..node.limits.len {
                let row = self.nodes[i].limits.rows[k];
                if self.nodes[i].active[k] || row.impulse == 0.0 {
                    continue;
                }
                let p = -row.impulse;
                let j = &row.jacobian;
                for (slot, sign, linear, angular) in
                    [(ia, -p, j.linear_a, j.angular_a), (ib, p, j.linear_b, j.angular_b)]
                {
                    if let Some(n) = self.body_node(i, slot) {
                        let x = &mut self.nodes[n].x;
                        for c in 0..3 {
                            x[c] += sign * linear[c];
                            x[3 + c] += sign * angular[c];
                        }
                    }
                }
            }
        }
    }

    /// Writes the coupling between joint node `j` and the node of body `slot` (if it moves): the
    /// joint's Jacobian block for that body, times `sign` (−1 for body a), stored in whichever of
    /// the two is the child.
    fn couple(&mut self, j: usize, slot: usize, rows: &EqualityRows, sign: f64) {
        let jacobian = |k: usize| {
            let row = &rows.rows[k];
            let (linear, angular) =
                if sign < 0.0 { (-row.linear_a, -row.angular_a) } else { (row.linear_b, row.angular_b) };
            [linear.x, linear.y, linear.z, angular.x, angular.y, angular.z]
        };
        let parent = self.nodes[j].parent;
        if parent != NONE && self.nodes[parent as usize].kind == (NodeKind::Body { slot: slot as u32 }) {
            let coupling = &mut self.nodes[j].coupling;
            (coupling.rows, coupling.cols) = (rows.len, 6);
            for k in 0..rows.len {
                coupling.m[k] = jacobian(k);
            }
            return;
        }
        // Otherwise the body, if it moves, is one of the joint's children.
        let body = NodeKind::Body { slot: slot as u32 };
        let child = self.nodes[j]
            .body_children
            .into_iter()
            .find(|&c| c != NONE && self.nodes[c as usize].kind == body);
        if let Some(c) = child {
            let c = c as usize;
            let coupling = &mut self.nodes[c].coupling;
            // Cleared whole: the joint's rows change with its limit rows, and the products
            // read all six columns (`block.rs`).
            coupling.set_zero(6, rows.len);
            for k in 0..rows.len {
                let column = jacobian(k);
                for (r, value) in column.iter().enumerate() {
                    coupling.m[r][k] = *value;
                }
            }
        }
    }

    /// Block `LDLᵀ`, leaves first: each node's factor and elimination multiplier, and its
    /// parent's diagonal block updated.
    fn factor(&mut self, tree: Range<usize>) {
        for i in tree {
            let parent = self.nodes[i].parent;
            let (done, rest) = self.nodes.split_at_mut(i + 1);
            let node = &mut done[i];
            node.factor.factor_from(&node.diagonal);
            if parent != NONE {
                node.factor.solve_block_into(&node.coupling, &mut node.multiplier);
                rest[parent as usize - i - 1].diagonal.sub_transpose_mul(&node.coupling, &node.multiplier);
            }
        }
    }

    /// Solves for the right-hand sides in the nodes' `x` with the factors: forward substitution
    /// (leaves first), the diagonal blocks, back substitution (roots first).
    fn solve_factored(&mut self, tree: Range<usize>) {
        for i in tree.clone() {
            let parent = self.nodes[i].parent;
            if parent != NONE {
                let (done, rest) = self.nodes.split_at_mut(i + 1);
                let node = &done[i];
                node.multiplier.sub_transpose_mul_vector(&node.x, &mut rest[parent as usize - i - 1].x);
            }
        }
        for node in &mut self.nodes[tree.clone()] {
            let mut x = node.x;
            node.factor.solve_in_place(&mut x);
            node.x = x;
        }
        for i in tree.rev() {
            let parent = self.nodes[i].parent;
            if parent != NONE {
                let (done, rest) = self.nodes.split_at_mut(i + 1);
                let node = &mut done[i];
                let x_parent = rest[parent as usize - i - 1].x;
                node.multiplier.sub_mul_vector(&x_parent, &mut node.x);
            }
        }
    }
}

#[cfg(test)]
mod tests;
