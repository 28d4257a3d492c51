//! Shared helpers for the exact-solver tests: a small deterministic random generator.
#![allow(dead_code)]

use tumble::dynamics::lcp::DenseMatrix;
use tumble::DVec3;

/// SplitMix64: a tiny deterministic generator, so the random tests are reproducible.
pub struct Rng(pub u64);

impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [-1, 1).
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
    pub fn matrix(&mut self, rows: usize, cols: usize) -> DenseMatrix {
        let data: Vec<Vec<f64>> = (0..rows).map(|_| (0..cols).map(|_| self.uniform()).collect()).collect();
        DenseMatrix::from_rows(&data)
    }
}

pub fn random_vec(rng: &mut Rng, scale: f64) -> DVec3 {
    scale * DVec3::new(rng.uniform(), rng.uniform(), rng.uniform())
}

pub fn random_unit(rng: &mut Rng) -> DVec3 {
    loop {
        let v = DVec3::new(rng.uniform(), rng.uniform(), rng.uniform());
        if v.length_squared() > 0.01 && v.length_squared() <= 1.0 {
            return v.normalize();
        }
    }
}
