//! Counting the work of a query: the terms of the cost function.
//!
//! Lecture: *cost function* `T = Nv*Cv + Np*Cp + Nu*Cu + Co`. A query counts
//! `Nv` (volume-pair tests), `Np` (primitive-pair tests) and `Nu` (volumes
//! updated, here: carried into another frame by a [`Rigid`](crate::Rigid)
//! motion) through a [`Tally`]. The unit type `()` is a tally that counts
//! nothing; because queries are generic over the tally, the counting code is
//! compiled away when `()` is used, so counting costs nothing unless asked for.

/// Receives the counts of a query as it runs.
pub trait Tally {
    /// `n` bounding-volume overlap tests were made.
    fn bv_tests(&mut self, n: u32);
    /// `n` primitive tests were made.
    fn prim_tests(&mut self, n: u32);
    /// `n` volumes were updated (moved into another frame).
    fn updates(&mut self, n: u32);
}

/// The tally that counts nothing (compiled away).
impl Tally for () {
    #[inline(always)]
    fn bv_tests(&mut self, _: u32) {}
    #[inline(always)]
    fn prim_tests(&mut self, _: u32) {}
    #[inline(always)]
    fn updates(&mut self, _: u32) {}
}

impl<T: Tally + ?Sized> Tally for &mut T {
    #[inline(always)]
    fn bv_tests(&mut self, n: u32) {
        (**self).bv_tests(n)
    }
    #[inline(always)]
    fn prim_tests(&mut self, n: u32) {
        (**self).prim_tests(n)
    }
    #[inline(always)]
    fn updates(&mut self, n: u32) {
        (**self).updates(n)
    }
}

/// The three counters of the cost function.
///
/// ```
/// use bvhkit::{Counts, CostModel};
/// let counts = Counts { bv_tests: 1000, prim_tests: 50, updates: 0 };
/// let model = CostModel { cv: 2.0, cp: 30.0, cu: 10.0, co: 500.0 }; // nanoseconds
/// assert_eq!(model.predict(&counts), 1000.0 * 2.0 + 50.0 * 30.0 + 500.0);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counts {
    /// `Nv`: bounding-volume pair tests.
    pub bv_tests: u64,
    /// `Np`: primitive pair tests.
    pub prim_tests: u64,
    /// `Nu`: volumes updated.
    pub updates: u64,
}

impl Tally for Counts {
    #[inline(always)]
    fn bv_tests(&mut self, n: u32) {
        self.bv_tests += n as u64;
    }
    #[inline(always)]
    fn prim_tests(&mut self, n: u32) {
        self.prim_tests += n as u64;
    }
    #[inline(always)]
    fn updates(&mut self, n: u32) {
        self.updates += n as u64;
    }
}

/// The cost function `T = Nv*Cv + Np*Cp + Nu*Cu + Co`, with unit costs in
/// whatever time unit the caller measured them in.
///
/// `bvhkit-std` calibrates the unit costs on the running machine and compares
/// the prediction with measured query times.
///
/// ```
/// use bvhkit::{CostModel, Counts};
/// // Unit costs in nanoseconds; counts from a query's tally.
/// let model = CostModel { cv: 2.0, cp: 10.0, cu: 0.0, co: 50.0 };
/// let counts = Counts { bv_tests: 100, prim_tests: 20, updates: 0 };
/// assert_eq!(model.predict(&counts), 100.0 * 2.0 + 20.0 * 10.0 + 50.0);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CostModel {
    /// Cost of one bounding-volume pair test.
    pub cv: f64,
    /// Cost of one primitive pair test.
    pub cp: f64,
    /// Cost of updating one volume.
    pub cu: f64,
    /// One-off cost per query (set-up, transforms of the roots).
    pub co: f64,
}

impl CostModel {
    /// The predicted time of a query that made `counts`.
    pub fn predict(&self, counts: &Counts) -> f64 {
        counts.bv_tests as f64 * self.cv
            + counts.prim_tests as f64 * self.cp
            + counts.updates as f64 * self.cu
            + self.co
    }
}
