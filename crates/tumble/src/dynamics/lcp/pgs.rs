//! Projected Gauss–Seidel on the same rows, for tests only: an independent, iterative route to the
//! answer that the exact solver must agree with wherever the answer is unique.

use super::dense::DenseMatrix;
use super::system::RowKind;

/// `iterations` sweeps of projected Gauss–Seidel on `w = A λ + b`: each row in turn takes the
/// impulse that zeroes its own velocity, clamped to its bounds (`λ ≥ 0` for normals,
/// `|λ| ≤ μ λ_n` with the current `λ_n` for friction).
pub(crate) fn projected_gauss_seidel(
    a: &DenseMatrix,
    b: &[f64],
    kinds: &[RowKind],
    iterations: usize,
) -> Vec<f64> {
    let n = b.len();
    let mut lambda = vec![0.0; n];
    for _ in 0..iterations {
        for i in 0..n {
            let diag = a[(i, i)];
            if diag <= 0.0 {
                continue;
            }
            let w = b[i] + a.row(i).iter().zip(&lambda).map(|(x, y)| x * y).sum::<f64>();
            let trial = lambda[i] - w / diag;
            lambda[i] = match kinds[i] {
                RowKind::Equality => trial,
                RowKind::Normal => trial.max(0.0),
                RowKind::Friction { normal_row, mu } => {
                    let h = mu * lambda[normal_row];
                    trial.clamp(-h, h)
                }
            };
        }
    }
    lambda
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::lcp::{
        apply_impulses, ball_joint_rows, contact_rows, point_row, residual, solve_exact, Anchor,
        BodyVelocity, ConstraintSystem, ContactPoint, LcpBody, Row, RowKind as Kind,
    };
    use crate::math::{DMat3, DVec3};

    const G: f64 = 9.81;
    const DT: f64 = 1.0 / 60.0;

    /// A box of mass `m` and half extents `h`, body `index`, resting on `below` (the world or a
    /// box of half height `below_hz`), four corner contacts.
    fn corner_contacts(index: usize, below: Option<(usize, f64)>, h: DVec3, mu: f64, rows: &mut Vec<Row>) {
        for (sx, sy) in [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)] {
            let a = match below {
                None => Anchor::WORLD,
                Some((j, hz)) => Anchor::new(j, DVec3::new(sx * h.x, sy * h.y, hz)),
            };
            let b = Anchor::new(index, DVec3::new(sx * h.x, sy * h.y, -h.z));
            let c = ContactPoint { a, b, normal: DVec3::Z, tangent: DVec3::X, mu, bias: 0.0 };
            let first = rows.len();
            rows.extend(contact_rows(&c, first));
        }
    }

    fn box_body(m: f64, h: DVec3) -> LcpBody {
        let i = m / 3.0 * DVec3::new(h.y * h.y + h.z * h.z, h.x * h.x + h.z * h.z, h.x * h.x + h.y * h.y);
        LcpBody::new(1.0 / m, DMat3::from_diagonal(i.recip()))
    }

    fn compare(
        bodies: &[LcpBody],
        vel: &[BodyVelocity],
        rows: &[Row],
        iterations: usize,
        tol: f64,
    ) -> Vec<f64> {
        let exact = solve_exact(bodies, vel, rows).unwrap();
        let sys = ConstraintSystem::assemble(bodies, vel, rows).unwrap();
        let kinds: Vec<RowKind> = rows.iter().map(|r| r.kind).collect();
        let lambda = projected_gauss_seidel(&sys.a, &sys.b, &kinds, iterations);
        let after = apply_impulses(bodies, vel, rows, &lambda);
        let w: Vec<f64> = rows.iter().map(|r| r.velocity(&after) + r.bias).collect();
        assert!(residual(rows, &lambda, &w) < tol, "PGS residual {}", residual(rows, &lambda, &w));
        for (x, y) in after.iter().zip(&exact.velocities) {
            assert!((x.linear - y.linear).length() < tol, "{x:?} vs {y:?}");
            assert!((x.angular - y.angular).length() < tol, "{x:?} vs {y:?}");
        }
        exact.impulses
    }

    #[test]
    fn pgs_agrees_with_exact_on_a_sliding_box() {
        let h = DVec3::new(0.5, 0.3, 0.2);
        let mut rows = Vec::new();
        corner_contacts(0, None, h, 0.4, &mut rows);
        let v = [BodyVelocity::new(DVec3::new(1.0, 0.3, -G * DT), DVec3::new(0.0, 0.0, 0.5))];
        compare(&[box_body(3.0, h)], &v, &rows, 2000, 1e-10);
    }

    #[test]
    fn pgs_agrees_with_exact_on_a_three_box_stack() {
        let h = DVec3::new(0.5, 0.5, 0.5);
        let mut rows = Vec::new();
        corner_contacts(0, None, h, 0.6, &mut rows);
        corner_contacts(1, Some((0, h.z)), h, 0.6, &mut rows);
        corner_contacts(2, Some((1, h.z)), h, 0.6, &mut rows);
        let bodies = [box_body(1.0, h), box_body(2.0, h), box_body(0.5, h)];
        let v = [BodyVelocity::new(DVec3::new(0.0, 0.0, -G * DT), DVec3::ZERO); 3];
        // Stacks are where Gauss–Seidel is slow (the mass ratio 4:1 does not help): many sweeps.
        compare(&bodies, &v, &rows, 20000, 1e-9);
    }

    #[test]
    fn pgs_agrees_with_exact_on_a_jointed_chain_touching_the_ground() {
        // Two boxes hung from the world by ball joints in a chain, the lower one pressed onto the
        // ground at one corner (frictionless, so the post velocities are unique).
        let h = DVec3::new(0.3, 0.2, 0.1);
        let bodies = [box_body(1.0, h), box_body(2.0, h)];
        let mut rows: Vec<Row> =
            ball_joint_rows(Anchor::WORLD, Anchor::new(0, DVec3::new(-0.3, 0.0, 0.1))).to_vec();
        rows.extend(ball_joint_rows(
            Anchor::new(0, DVec3::new(0.3, 0.0, -0.1)),
            Anchor::new(1, DVec3::new(-0.3, 0.0, 0.1)),
        ));
        rows.push(point_row(
            Anchor::WORLD,
            Anchor::new(1, DVec3::new(0.3, 0.2, -0.1)),
            DVec3::Z,
            Kind::Normal,
        ));
        let v = [
            BodyVelocity::new(DVec3::new(0.2, -0.1, -G * DT), DVec3::new(0.0, 0.5, 0.1)),
            BodyVelocity::new(DVec3::new(0.1, 0.3, -1.0), DVec3::new(-0.4, 0.2, 0.0)),
        ];
        let exact = compare(&bodies, &v, &rows, 20000, 1e-9);
        assert!(exact[6] > 0.1, "the contact should be pressed: {exact:?}");
    }
}
