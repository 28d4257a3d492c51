//! A scene's quality result: a few named numbers, printed on one line.

use std::fmt;

/// One quality number.
#[derive(Clone, Debug, PartialEq)]
pub enum Metric {
    /// A length, m.
    Length(&'static str, f64),
    /// A relative error (dimensionless).
    Relative(&'static str, f64),
    /// A count of things.
    Count(&'static str, usize),
    /// A yes/no answer.
    Flag(&'static str, bool),
}

impl Metric {
    pub fn name(&self) -> &'static str {
        match self {
            Metric::Length(n, _) | Metric::Relative(n, _) | Metric::Count(n, _) | Metric::Flag(n, _) => n,
        }
    }

    /// The value as a number (flags as 0 or 1), for tables and JSON.
    pub fn value(&self) -> f64 {
        match *self {
            Metric::Length(_, v) | Metric::Relative(_, v) => v,
            Metric::Count(_, n) => n as f64,
            Metric::Flag(_, b) => f64::from(u8::from(b)),
        }
    }
}

impl fmt::Display for Metric {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Metric::Length(n, v) if v.abs() < 0.1 => write!(f, "{n} {:.2} cm", v * 100.0),
            Metric::Length(n, v) => write!(f, "{n} {v:.3} m"),
            Metric::Relative(n, v) => write!(f, "{n} {v:.2e}"),
            Metric::Count(n, c) => write!(f, "{n} {c}"),
            Metric::Flag(n, b) => write!(f, "{n} {}", if *b { "yes" } else { "no" }),
        }
    }
}

/// The quality result of a scene.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Quality {
    pub metrics: Vec<Metric>,
}

impl fmt::Display for Quality {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, m) in self.metrics.iter().enumerate() {
            if i > 0 {
                write!(f, ", ")?;
            }
            write!(f, "{m}")?;
        }
        Ok(())
    }
}

/// The largest overlap among the touching contacts (0 when none overlap), m.
pub(crate) fn max_penetration(world: &crate::world::World) -> f64 {
    world.contacts().iter().flat_map(|c| c.points.iter()).map(|p| -p.separation).fold(0.0, f64::max)
}

/// The largest distance between the two anchors of any joint now, m.
pub(crate) fn max_joint_separation(world: &crate::world::World) -> f64 {
    world
        .joints()
        .filter_map(|(_, j)| {
            let (a, b) = (world.body(j.body_a()).ok()?, world.body(j.body_b()).ok()?);
            Some(j.separation(a, b).length())
        })
        .fold(0.0, f64::max)
}
