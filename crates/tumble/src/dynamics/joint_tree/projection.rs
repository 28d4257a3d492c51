//! The joint trees' position projection: after each substep's position stage, Newton steps on
//! the trees' position errors move their bodies back onto their joints (post-stabilisation,
//! Cline & Pai 2003), tree by tree, and free figures get back the angular momentum the move
//! took (`docs/joint-tree.md`, "Holding the positions").

use super::{JointTrees, Node, NodeKind, Target, CHORD_TURN, MAX_HALVINGS};
use crate::body::Body;
use crate::dynamics::joint::Joint;
use crate::dynamics::solver_body::SolverBody;
use crate::id::{Slot, SlotPool};
use crate::math::{DMat3, DVec3};
use std::ops::Range;

impl JointTrees {
    /// Moves the trees' bodies until every tree row's position error is at most `tolerance`, by
    /// at most `max_iterations` Newton steps: each the smallest mass-weighted displacement
    /// `Δx = M⁻¹Jᵀλ` with `J Δx = −C` (post-stabilisation, Cline & Pai 2003). Velocities are left
    /// as they are. Run after each substep's position stage, it takes out the drift the substep
    /// made instead of feeding it back through the velocities over the next substeps
    /// (`docs/joint-tree.md`, "Holding the positions").
    ///
    /// While every tree body turned by less than [`CHORD_TURN`] in the substep (`h |ω|`), the
    /// first step reuses the factors of the substep's velocity solve, whose Jacobians are off by
    /// that turn: a chord step, which takes out all but about `h |ω|` of the drift without
    /// refactoring, and is not counted. A step that leaves the largest error larger than it was
    /// is halved (up to [`MAX_HALVINGS`] times): far from the constraint surface a full step can
    /// overshoot, and a projection that makes things worse feeds a diverging loop.
    ///
    /// Moving bodies without touching their velocities changes a figure's angular momentum by
    /// `Σ m Δx × v` and the turn of its inertias: the drift the projection takes out is mostly
    /// centripetal (the anchors of a spinning figure fly outward along straight lines), and a
    /// free six-link chain spinning in zero gravity lost 0.36% of its angular momentum in ten
    /// seconds. So each free figure (one not hung from the ground) gets back the angular momentum
    /// it had before, as a rigid spin of the whole figure about its centre of mass, which leaves
    /// its joints' rows as they were (`restore_angular_momentum`).
    pub fn project_positions(
        &mut self,
        joints: &[Slot<Joint>],
        bodies: &mut [SolverBody],
        world_bodies: &SlotPool<Body>,
        tolerance: f64,
        max_iterations: u32,
        h: f64,
    ) {
        if self.nodes.is_empty() {
            return;
        }
        let mut momenta = std::mem::take(&mut self.momenta);
        momenta.clear();
        for figure in &self.free_figures {
            let centre = self.figure_centre(figure.clone(), bodies, world_bodies);
            momenta.push((centre, self.figure_momentum(figure.clone(), centre, bodies, world_bodies)));
        }
        self.project(joints, bodies, tolerance, max_iterations, h);
        for (figure, &(centre, before)) in self.free_figures.iter().zip(&momenta) {
            self.restore_angular_momentum(figure.clone(), centre, before, bodies, world_bodies);
        }
        self.momenta = momenta;
    }

    /// The body nodes of a figure: (slot, position now).
    fn figure_bodies<'a>(
        &'a self,
        figure: Range<usize>,
        bodies: &'a [SolverBody],
        world_bodies: &'a SlotPool<Body>,
    ) -> impl Iterator<Item = (usize, DVec3)> + 'a {
        self.nodes[figure].iter().filter_map(move |node| match node.kind {
            NodeKind::Body { slot } => {
                let start = world_bodies.iter_slot(slot as usize).expect("tree bodies are live").com_world();
                Some((slot as usize, start + bodies[slot as usize].dp))
            }
            NodeKind::Joint { .. } => None,
        })
    }

    /// A figure's centre of mass now (which the projection keeps: `Σ m Δx = 0`).
    fn figure_centre(
        &self,
        figure: Range<usize>,
        bodies: &[SolverBody],
        world_bodies: &SlotPool<Body>,
    ) -> DVec3 {
        let (weighted, mass) =
            self.figure_bodies(figure, bodies, world_bodies).fold((DVec3::ZERO, 0.0), |(w, m), (slot, x)| {
                let mass = 1.0 / bodies[slot].inv_mass;
                (w + mass * x, m + mass)
            });
        weighted / mass
    }

    /// A figure's angular momentum about `centre`.
    fn figure_momentum(
        &self,
        figure: Range<usize>,
        centre: DVec3,
        bodies: &[SolverBody],
        world_bodies: &SlotPool<Body>,
    ) -> DVec3 {
        self.figure_bodies(figure, bodies, world_bodies)
            .map(|(slot, x)| {
                let body = &bodies[slot];
                let (mass, inertia) = body.mass_matrix().expect("tree bodies have a mass matrix");
                mass * (x - centre).cross(body.v) + inertia * body.w
            })
            .sum()
    }

    /// Gives a free figure back the angular momentum `before` (about its centre of mass `centre`)
    /// by spinning it as one rigid body by `δω = I⁻¹ (L_before − L_now)`, `I` the figure's inertia
    /// about its centre: every body gets `δω × r` and `δω`. A rigid spin keeps the figure's
    /// momentum and changes no joint's relative velocity (up to `δω × C`, `C` the joint's
    /// remaining error, within the projection's tolerance).
    fn restore_angular_momentum(
        &self,
        figure: Range<usize>,
        centre: DVec3,
        before: DVec3,
        bodies: &mut [SolverBody],
        world_bodies: &SlotPool<Body>,
    ) {
        let lost = before - self.figure_momentum(figure.clone(), centre, bodies, world_bodies);
        if lost == DVec3::ZERO {
            return;
        }
        let mut inertia = DMat3::ZERO;
        for (slot, x) in self.figure_bodies(figure.clone(), bodies, world_bodies) {
            let (mass, own) = bodies[slot].mass_matrix().expect("tree bodies have a mass matrix");
            let r = x - centre;
            inertia += own + mass * (DMat3::from_diagonal(DVec3::splat(r.length_squared())) - outer(r, r));
        }
        let spin = inertia.inverse() * lost;
        if !spin.is_finite() {
            return;
        }
        for node in &self.nodes[figure] {
            if let NodeKind::Body { slot } = node.kind {
                let start = world_bodies.iter_slot(slot as usize).expect("tree bodies are live").com_world();
                let body = &mut bodies[slot as usize];
                body.v += spin.cross(start + body.dp - centre);
                body.w += spin;
            }
        }
    }

    /// The projection itself (see `project_positions`), tree by tree: each takes the Newton
    /// steps it needs (a figure still settling its limits takes more than one hanging still).
    fn project(
        &mut self,
        joints: &[Slot<Joint>],
        bodies: &mut [SolverBody],
        tolerance: f64,
        max_iterations: u32,
        h: f64,
    ) {
        let factored = self.factored;
        for t in 0..self.trees.len() {
            let tree = self.trees[t].clone();
            let turned = |node: &Node| match node.kind {
                NodeKind::Body { slot } => h * bodies[slot as usize].w.length(),
                NodeKind::Joint { .. } => 0.0,
            };
            let chord = factored && self.nodes[tree.clone()].iter().all(|node| turned(node) < CHORD_TURN);
            self.project_tree(tree, joints, bodies, tolerance, max_iterations, chord);
        }
    }

    /// One tree's projection; `chord`: its first step may reuse the velocity solve's factors.
    fn project_tree(
        &mut self,
        tree: Range<usize>,
        joints: &[Slot<Joint>],
        bodies: &mut [SolverBody],
        tolerance: f64,
        max_iterations: u32,
        mut chord: bool,
    ) {
        let mut budget = max_iterations;
        let (mut before, mut halvings) = (f64::INFINITY, 0);
        loop {
            // The chord step keeps the velocity solve's limit rows, whose factors it reuses (rows
            // before their limits held where they are); any other step takes in the rows past
            // their limits.
            let assembled = self.assemble(tree.clone(), joints, bodies, Target::Position, false, !chord);
            let error = assembled.largest_error;
            if error > before && halvings < MAX_HALVINGS {
                halvings += 1;
                self.take_step(tree.clone(), bodies, -0.5);
                continue;
            }
            if error <= tolerance {
                return;
            }
            if !std::mem::take(&mut chord) {
                if budget == 0 {
                    return;
                }
                budget -= 1;
                self.assemble(tree.clone(), joints, bodies, Target::Position, true, true);
                self.factor(tree.clone());
            }
            self.solve_factored(tree.clone());
            for node in &mut self.nodes[tree.clone()] {
                let [x, y, z, ax, ay, az, ..] = node.x;
                node.step = [x, y, z, ax, ay, az];
            }
            self.take_step(tree.clone(), bodies, 1.0);
            (before, halvings) = (error, 0);
        }
    }

    /// Moves every body of `tree` by `fraction` of its node's `step`, and scales the steps by
    /// `|fraction|` (so that −½ takes back half of the step just taken and leaves the other half
    /// as the step).
    fn take_step(&mut self, tree: Range<usize>, bodies: &mut [SolverBody], fraction: f64) {
        for node in &mut self.nodes[tree] {
            if let NodeKind::Body { slot } = node.kind {
                let [x, y, z, ax, ay, az] = node.step;
                bodies[slot as usize]
                    .displace(fraction * DVec3::new(x, y, z), fraction * DVec3::new(ax, ay, az));
                if fraction != 1.0 {
                    node.step = node.step.map(|v| v * fraction.abs());
                }
            }
        }
    }
}

/// `u vᵀ`.
fn outer(u: DVec3, v: DVec3) -> DMat3 {
    DMat3::from_cols(u * v.x, u * v.y, u * v.z)
}
