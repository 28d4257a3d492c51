//! Dynamics: constraint rows and the solvers that find their impulses.

pub mod lcp;
