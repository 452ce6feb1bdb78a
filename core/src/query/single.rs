//! Single-tree queries: which primitives does a region touch?

use crate::bv::{Aabb, BoundingVolume};
use crate::primitive::Primitive;
use crate::tree::{Bvh, MAX_DEPTH};
use crate::Error;

impl<B: BoundingVolume> Bvh<'_, B> {
    /// Calls `f` with every primitive whose bounds overlap `region`; returns the
    /// count. Depth-first with a fixed stack; subtrees whose volume misses the
    /// region are skipped.
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
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn overlapping<P: Primitive>(
        &self,
        prims: &[P],
        region: &Aabb,
        mut f: impl FnMut(u32),
    ) -> Result<usize, Error> {
        self.check_query(prims.len())?;
        let nodes = self.nodes();
        let mut stack = [0u32; MAX_DEPTH + 1];
        let mut top = 0;
        let mut found = 0;
        if nodes[0].bv.overlaps_aabb(region) {
            stack[0] = 0;
            top = 1;
        }
        while top > 0 {
            top -= 1;
            let node = &nodes[stack[top] as usize];
            match node.children() {
                None => {
                    for &p in self.leaf_primitives(node) {
                        if prims[p as usize].bounds().overlaps(region) {
                            f(p);
                            found += 1;
                        }
                    }
                }
                Some((l, r)) => {
                    // At most one sibling waits per level: depth + 1 entries suffice.
                    for c in [r, l] {
                        if nodes[c as usize].bv.overlaps_aabb(region) {
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
