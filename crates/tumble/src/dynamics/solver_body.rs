//! The solver's working copy of each body for one step, and the two integration stages that run
//! inside every substep.
//!
//! Positions are tracked as the *change* of the centre of mass since the step began (`dp`):
//! constraints compare changes, which keeps round-off small far from the origin.

use crate::body::{Body, BodyKind};
use crate::integrate::{free_rotation_flow, free_rotation_flow_steps_lanes, rotate_by_angular_velocity};
use crate::math::{DMat3, DQuat, DVec3};

/// The velocities, which the constraint stages write, come first and share one cache line; the
/// rest, which they only read, lies in other lines. (Threads solving different colours write the
/// same body in turn: only its velocity line then moves between their caches.)
#[derive(Clone, Copy, Debug, serde::Serialize, serde::Deserialize)]
#[repr(C, align(64))]
pub(crate) struct SolverBody {
    pub v: DVec3,
    pub w: DVec3,
    /// Centre-of-mass displacement since the start of the step, world frame.
    pub dp: DVec3,
    pub inv_mass: f64,
    /// The turn since the step began as a rotation vector, world frame (`q = exp(turn) q_start`),
    /// kept while the body has barely turned: its contacts then move their points by `turn × r`,
    /// to first order (contact_solver.rs, `ContactConstraint::solve_normals`).
    pub turn: DVec3,
    // The flags side by side (no padding between 8-byte fields); what the contact rows read
    // (`v`, `w`, `dp`, `inv_mass`, `turn`, `barely_turned`, `inv_inertia`) lies in the first three lines.
    kind: BodyKind,
    /// The body has turned less than [`STILL_TURN`] since the step began: its levers (offsets from
    /// its centre of mass) and world inertia are those of the step start to first order. Whether
    /// a contact between two such bodies may use its step-start rows also depends on how far the
    /// two have moved against each other ([`still_pair`]); how far the body has moved by itself
    /// changes none of them.
    pub barely_turned: bool,
    /// All three principal moments are equal (a sphere, a cube): every axis is principal, the
    /// free flow is a rotation about `ω` at constant `ω`, and the world inertia never changes.
    isotropic: bool,
    /// World inverse inertia for the current `q` (refreshed after every position update).
    pub inv_inertia: DMat3,
    /// `q` as a matrix (body frame to world), refreshed with it: the contacts turn their material
    /// points with it several times a substep, and a matrix does that in half the operations.
    pub rotation: DMat3,
    /// Body-frame orientation now.
    pub q: DQuat,
    /// `q` at the start of the step.
    q_start: DQuat,
    inertia_principal: DVec3,
    principal_rotation_local: DQuat,
    force: DVec3,
    torque: DVec3,
    gravity_scale: f64,
    linear_damping: f64,
    angular_damping: f64,
}

impl SolverBody {
    /// A body that never moves (also stands in for removed slots).
    pub const FIXED: SolverBody = SolverBody {
        v: DVec3::ZERO,
        w: DVec3::ZERO,
        dp: DVec3::ZERO,
        q: DQuat::IDENTITY,
        inv_mass: 0.0,
        inv_inertia: DMat3::ZERO,
        rotation: DMat3::IDENTITY,
        kind: BodyKind::Static,
        barely_turned: true,
        turn: DVec3::ZERO,
        q_start: DQuat::IDENTITY,
        isotropic: true,
        inertia_principal: DVec3::ONE,
        principal_rotation_local: DQuat::IDENTITY,
        force: DVec3::ZERO,
        torque: DVec3::ZERO,
        gravity_scale: 0.0,
        linear_damping: 0.0,
        angular_damping: 0.0,
    };

    #[inline(always)]
    pub fn from_body(body: &Body) -> SolverBody {
        SolverBody {
            v: body.state.linear_velocity,
            w: body.state.angular_velocity,
            dp: DVec3::ZERO,
            q: body.state.rotation,
            inv_mass: body.inverse_mass,
            inv_inertia: body.inverse_inertia_world(),
            rotation: DMat3::from_quat(body.state.rotation),
            kind: body.kind,
            barely_turned: true,
            turn: DVec3::ZERO,
            q_start: body.state.rotation,
            isotropic: body.inertia_principal.x == body.inertia_principal.y
                && body.inertia_principal.y == body.inertia_principal.z,
            inertia_principal: body.inertia_principal,
            principal_rotation_local: body.principal_rotation_local,
            force: body.force_world,
            torque: body.torque_world,
            gravity_scale: body.gravity_scale,
            linear_damping: body.linear_damping,
            angular_damping: body.angular_damping,
        }
    }

    /// Writes the step's result back into the body. Only a dynamic body's velocities are the
    /// solver's to change: a static or kinematic body has infinite mass, so the impulses it takes
    /// are multiplied by zero — which is NaN, not zero, when a diverging neighbour's impulse is
    /// infinite. Writing them back would spread that NaN to the ground.
    pub fn write_back(&self, body: &mut Body) {
        match self.kind {
            BodyKind::Static => {}
            BodyKind::Kinematic => {
                body.state.com_world += self.dp;
                body.state.rotation = self.q;
            }
            BodyKind::Dynamic => {
                body.state.com_world += self.dp;
                body.state.rotation = self.q;
                body.state.linear_velocity = self.v;
                body.state.angular_velocity = self.w;
            }
        }
    }

    /// Whether the body moves under impulses (a dynamic body, awake); the others only take part
    /// as fixed (or kinematically moving) ends of constraints.
    pub fn is_dynamic(&self) -> bool {
        self.kind == BodyKind::Dynamic
    }

    /// Whether the body moves in the position stage (dynamic or kinematic).
    pub fn moves(&self) -> bool {
        self.kind != BodyKind::Static
    }

    /// Whether `mass_matrix` exists (without computing it).
    pub fn has_mass_matrix(&self) -> bool {
        let finite_positive = |x: f64| x.is_finite() && x > 0.0;
        finite_positive(self.inv_mass) && self.inertia_principal.to_array().into_iter().all(finite_positive)
    }

    /// The mass and world inertia tensor, or `None` unless both are finite and positive (a body
    /// that does not move, or one with an infinite moment).
    pub fn mass_matrix(&self) -> Option<(f64, DMat3)> {
        if !self.has_mass_matrix() {
            return None;
        }
        let r = DMat3::from_quat(self.q * self.principal_rotation_local);
        Some((1.0 / self.inv_mass, r * DMat3::from_diagonal(self.inertia_principal) * r.transpose()))
    }

    /// Sets `q` and the `rotation` matrix that goes with it, and whether the body has barely
    /// turned (called after `dp` has moved).
    fn set_orientation(&mut self, q: DQuat) {
        self.q = q;
        self.rotation = DMat3::from_quat(q);
        // |q·q_start| = cos(θ/2) of the turn since the step began.
        self.barely_turned = q.dot(self.q_start).abs() > (0.5 * STILL_TURN).cos();
        if self.barely_turned {
            // `q q_start⁻¹ = (sin(θ/2) u, cos(θ/2))`; below a milliradian `2 sin(θ/2) u` is the
            // rotation vector `θ u` to a relative 4e-8.
            let turn = q * self.q_start.conjugate();
            self.turn = 2.0 * turn.w.signum() * DVec3::new(turn.x, turn.y, turn.z);
        }
    }

    /// A dynamic body at rest at the step start, oriented `q` (for tests of the constraint stages).
    #[cfg(test)]
    pub(crate) fn dynamic_for_test(inv_mass: f64, inv_inertia_local: DVec3, q: DQuat) -> SolverBody {
        let mut body = SolverBody::FIXED;
        body.kind = BodyKind::Dynamic;
        body.inv_mass = inv_mass;
        body.inertia_principal = inv_inertia_local.recip();
        body.q_start = q;
        body.set_orientation(q);
        body.refresh_inverse_inertia();
        body
    }

    /// Moves the body to `dp` from its step-start position, oriented `q` (for tests).
    #[cfg(test)]
    pub(crate) fn move_for_test(&mut self, dp: DVec3, q: DQuat) {
        self.dp = dp;
        self.set_orientation(q);
        self.refresh_inverse_inertia();
    }

    fn refresh_inverse_inertia(&mut self) {
        let r = DMat3::from_quat(self.q * self.principal_rotation_local);
        self.inv_inertia = r * DMat3::from_diagonal(self.inertia_principal.recip()) * r.transpose();
    }

    /// Stage "integrate velocities": gravity and applied forces, the first half of the torque
    /// kick, damping (implicit, so stable for any rate).
    pub fn integrate_velocity(&mut self, gravity: DVec3, h: f64) {
        if self.kind != BodyKind::Dynamic {
            return;
        }
        self.integrate_linear_velocity(gravity, h);
        if self.torque != DVec3::ZERO {
            self.w += self.inv_inertia * (0.5 * h * self.torque);
        }
        self.w /= 1.0 + h * self.angular_damping;
    }

    /// Gravity and applied force, then linear damping (implicit).
    #[inline]
    fn integrate_linear_velocity(&mut self, gravity: DVec3, h: f64) {
        self.v += h * (gravity * self.gravity_scale + self.force * self.inv_mass);
        self.v /= 1.0 + h * self.linear_damping;
    }

    /// Stage "integrate positions": `x += h v`, and the rotation by the exact free-rigid-body flow
    /// (splitting into principal-axis rotations, `docs/free-rotation.md`), which also turns `ω`
    /// the way a free body's does — that is where gyroscopic effects come from. Then the second
    /// half of the torque kick.
    pub fn integrate_position(&mut self, h: f64) {
        match self.kind {
            BodyKind::Static => {}
            BodyKind::Kinematic => {
                self.dp += h * self.v;
                self.set_orientation(rotate_by_angular_velocity(self.q, self.w, h));
            }
            BodyKind::Dynamic if self.isotropic => {
                // The exact free flow: ω stays, the body turns about it by |ω| h (one sine and
                // cosine instead of the splitting's five), and its inertia looks the same.
                self.dp += h * self.v;
                self.set_orientation(rotate_by_angular_velocity(self.q, self.w, h));
                if self.torque != DVec3::ZERO {
                    self.w += self.inv_inertia * (0.5 * h * self.torque);
                }
            }
            BodyKind::Dynamic => {
                self.dp += h * self.v;
                let q_principal = self.q * self.principal_rotation_local;
                let inertia = self.inertia_principal;
                let l_principal = inertia * (q_principal.inverse() * self.w);
                let (q_principal, l_principal) = free_rotation_flow(q_principal, l_principal, inertia, h);
                self.w = q_principal * (l_principal / inertia);
                self.set_orientation((q_principal * self.principal_rotation_local.inverse()).normalize());
                self.refresh_inverse_inertia();
                if self.torque != DVec3::ZERO {
                    self.w += self.inv_inertia * (0.5 * h * self.torque);
                }
            }
        }
    }

    /// Moves the body by `shift` and turns it by the rotation vector `turn` (both world frame),
    /// without touching its velocities: the joint trees' position projection.
    pub fn displace(&mut self, shift: DVec3, turn: DVec3) {
        self.dp += shift;
        self.set_orientation((DQuat::from_scaled_axis(turn) * self.q).normalize());
        if !self.isotropic {
            self.refresh_inverse_inertia();
        }
    }

    /// All `substeps` substeps of bodies no constraint acts on, at once, up to
    /// [`FREE_FLOW_LANES`] side by side:
    /// the velocity and position stages in turn — and when no torque or angular damping acts
    /// between them, the rotation as one merged free flow (`free_rotation_flow_steps_lanes`: the
    /// same map to round-off in 4n + 1 principal rotations instead of 5n, the world inertia and
    /// rotation matrix only once, and the bodies' rotations overlapped). Each body's numbers are
    /// its own, whatever bodies share its group.
    pub fn integrate_unconstrained(
        bodies: &mut [Option<&mut SolverBody>; FREE_FLOW_LANES],
        gravity: DVec3,
        h: f64,
        substeps: u32,
    ) {
        let mut rotations = [DQuat::IDENTITY; FREE_FLOW_LANES];
        let mut momenta = [DVec3::ZERO; FREE_FLOW_LANES];
        let mut inertias = [DVec3::ONE; FREE_FLOW_LANES];
        let mut in_flow = [false; FREE_FLOW_LANES];
        for (lane, body) in bodies.iter_mut().enumerate() {
            let Some(body) = body else { continue };
            let torque_free = body.torque == DVec3::ZERO && body.angular_damping == 0.0;
            if body.kind != BodyKind::Dynamic || !torque_free {
                for _ in 0..substeps {
                    body.integrate_velocity(gravity, h);
                    body.integrate_position(h);
                }
                continue;
            }
            for _ in 0..substeps {
                body.integrate_linear_velocity(gravity, h);
                body.dp += h * body.v;
            }
            let q_principal = body.q * body.principal_rotation_local;
            inertias[lane] = body.inertia_principal;
            momenta[lane] = body.inertia_principal * (q_principal.inverse() * body.w);
            rotations[lane] = q_principal;
            in_flow[lane] = true;
        }
        free_rotation_flow_steps_lanes(&mut rotations, &mut momenta, &inertias, h, substeps);
        for (lane, body) in bodies.iter_mut().enumerate() {
            if let (Some(body), true) = (body, in_flow[lane]) {
                let (q_principal, l_principal) = (rotations[lane], momenta[lane]);
                body.w = q_principal * (l_principal / body.inertia_principal);
                // Only the orientation: no constraint reads this body's rotation matrix or world
                // inertia after its integration (the write-back takes `q`, `dp`, `v` and `ω`).
                body.q = (q_principal * body.principal_rotation_local.inverse()).normalize();
            }
        }
    }
}

/// How far, rad, a body may turn within a step and count as barely turned, and how far, m, two
/// such bodies may move against each other for their contacts to keep their step-start rows: a
/// shared lever of length `r` then differs from the one the exact rows would take by at most
/// r·10⁻³ + 1 mm (`still_pair`).
pub(crate) const STILL_TURN: f64 = 1e-3;
pub(crate) const STILL_DISTANCE: f64 = 1e-3;

/// Whether the contacts between `a` and `b` may use their step-start rows (contact_lanes.rs): both
/// bodies have turned less than [`STILL_TURN`] and they have moved less than [`STILL_DISTANCE`]
/// against each other since the step began.
///
/// Not how far each has moved: a translation common to both changes neither body's levers nor
/// inertia, and the rows' separation and normal velocity take it exactly. What the step-start
/// rows leave out of a translation is the drift of the shared point the impulses act at, which
/// follows the two anchors' relative displacement (`shared_levers`). A pile that sags as a whole
/// moves its boxes by more than a millimetre a step but each against its neighbours by far less:
/// in the first twenty steps of the 100-box-base pyramid, a quarter of the contact solves were of
/// still pairs under a bound on each body's own displacement, and 95% are under this one.
#[inline]
pub(crate) fn still_pair(a: &SolverBody, b: &SolverBody) -> bool {
    a.barely_turned && b.barely_turned && (b.dp - a.dp).length_squared() < STILL_DISTANCE * STILL_DISTANCE
}

/// How many unconstrained bodies integrate side by side: two SIMD vectors of sines and cosines
/// (`sin_cos.rs`). With one, the chain of rotations waited on each vector's result; sixteen were
/// no faster than eight (docs/free-rotation.md).
pub(crate) const FREE_FLOW_LANES: usize = 8;
