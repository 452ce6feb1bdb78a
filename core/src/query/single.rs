//! Single-tree queries: which primitives does a region touch?

use crate::bv::{Aabb, BoundingVolume, Kdop, Sphere};
use crate::primitive::Primitive;
use crate::tree::{Bvh, MAX_DEPTH};
use crate::Error;

/// A volume that can be used as a query region.
///
/// The answer of a region query is defined without the tree: the primitives
/// whose bounds pass [`BoundingVolume::overlaps_aabb`]. For the tree to find
/// exactly that set, the test must be *monotone*: if it accepts a box, it
/// accepts every larger box, even with `f32` rounding. Then a node whose box
/// encloses an accepted primitive box is accepted too. That holds for
/// [`Aabb`] (exact comparisons), [`Sphere`] (the clamped distance only shrinks
/// as a box grows) and [`Kdop`] (slabs rounded outward only widen). It is not
/// proven for the OBB's rounded separating-axis test, so [`Obb`](crate::Obb)
/// is not a region.
pub trait Region: BoundingVolume {
    /// Whether a subtree with volume `bv` can hold a primitive this region
    /// accepts. The default tests the region against the volume's enclosing
    /// box, which is monotone by the trait's contract.
    #[inline]
    fn may_overlap<B: BoundingVolume>(&self, bv: &B) -> bool {
        self.overlaps_aabb(&bv.aabb())
    }
}

impl Region for Aabb {
    /// An AABB region's leaf test is exact, so any conservative node test is
    /// enough; the node volume's own test is the tightest available.
    #[inline]
    fn may_overlap<B: BoundingVolume>(&self, bv: &B) -> bool {
        bv.overlaps_aabb(self)
    }
}

impl Region for Sphere {}

impl<const K: usize> Region for Kdop<K> {}

impl<B: BoundingVolume> Bvh<'_, B> {
    /// Calls `f` with every primitive whose bounds overlap `region` (an
    /// [`Aabb`], [`Sphere`] or [`Kdop`]); returns the count. Depth-first with a
    /// fixed stack; subtrees whose volume misses the region are skipped. The
    /// answer equals [`brute_force::overlapping`](crate::brute_force::overlapping).
    ///
    /// ```
    /// use bvhkit::{Aabb, Node, Sphere, TopDown, Triangle};
    /// use glam::Vec3;
    /// let tris: Vec<Triangle> = (0..10).map(|i| {
    ///     let o = Vec3::new(i as f32 * 2.0, 0.0, 0.0);
    ///     Triangle::new(o, o + Vec3::X, o + Vec3::Y)
    /// }).collect();
    /// let mut nodes = vec![Node::<Sphere>::EMPTY; bvhkit::max_nodes(10)];
    /// let mut idx = vec![0; 10];
    /// let bvh = TopDown::default().build(&tris, &mut nodes, &mut idx)?;
    /// let mut hits = Vec::new();
    /// let region = Aabb::new(Vec3::new(3.5, 0.0, 0.0), Vec3::new(6.5, 1.0, 1.0));
    /// bvh.overlapping(&tris, &region, |i| hits.push(i))?;
    /// hits.sort();
    /// assert_eq!(hits, [2, 3]);
    /// // Any region volume works the same way, here a sphere:
    /// let ball = Sphere::new(Vec3::new(4.0, 0.5, 0.0), 0.6);
    /// assert_eq!(bvh.overlapping(&tris, &ball, |_| {})?, 1);
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn overlapping<P: Primitive, R: Region>(
        &self,
        prims: &[P],
        region: &R,
        mut f: impl FnMut(u32),
    ) -> Result<usize, Error> {
        self.check_query(prims.len())?;
        let nodes = self.nodes();
        let mut stack = [0u32; MAX_DEPTH + 1];
        let mut top = 0;
        let mut found = 0;
        if region.may_overlap(&nodes[0].bv) {
            stack[0] = 0;
            top = 1;
        }
        while top > 0 {
            top -= 1;
            let node = &nodes[stack[top] as usize];
            match node.children() {
                None => {
                    for &p in self.leaf_primitives(node) {
                        if region.overlaps_aabb(&prims[p as usize].bounds()) {
                            f(p);
                            found += 1;
                        }
                    }
                }
                Some((l, r)) => {
                    // At most one sibling waits per level: depth + 1 entries suffice.
                    for c in [r, l] {
                        if region.may_overlap(&nodes[c as usize].bv) {
                            stack[top] = c;
                            top += 1;
                        }
                    }
                }
            }
        }
        Ok(found)
    }

    /// Checks that a query can run: the primitive slice matches and the tree fits the stack.
    pub(crate) fn check_query(&self, given: usize) -> Result<(), Error> {
        if given != self.primitive_count() {
            return Err(Error::PrimitiveCountMismatch {
                tree: self.primitive_count(),
                given,
            });
        }
        if self.depth() > MAX_DEPTH {
            return Err(Error::StackOverflow {
                depth: self.depth(),
                capacity: MAX_DEPTH,
            });
        }
        Ok(())
    }
}
