//! Tree statistics: the *desired characteristics* of the lectures, measured.
//!
//! The SAH cost is the expected cost of a random query under the surface area
//! heuristic, with one unit per node visit (`C_t = 1`) and one per primitive
//! test (`C_i = 1`): `sum(A(n) / A(root))` over internal nodes plus
//! `sum(A(l) / A(root) * count(l))` over leaves. Lower is better; it is
//! comparable between trees over the same primitives.

use crate::bv::{Aabb, BoundingVolume};
use crate::tree::{Bvh, MAX_DEPTH};

/// Measurements of one tree.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct TreeStats {
    /// Nodes in use.
    pub nodes: usize,
    /// Leaves.
    pub leaves: usize,
    /// Depth of the deepest leaf (root = 0).
    pub max_depth: usize,
    /// Mean depth of the leaves.
    pub mean_leaf_depth: f64,
    /// Largest number of primitives in one leaf.
    pub max_leaf_size: usize,
    /// SAH cost with `C_t = C_i = 1`, using the tree's own volume areas.
    pub sah_cost: f64,
    /// Sum of all node volumes divided by the root volume.
    pub volume_sum: f64,
    /// Sum over sibling pairs of the area of their boxes' intersection, divided
    /// by the root area (0 when siblings never overlap).
    pub sibling_overlap: f64,
    /// Bytes of node and index storage.
    pub bytes: usize,
}

impl<B: BoundingVolume> Bvh<'_, B> {
    /// Measures the tree. The empty tree measures zero everywhere.
    ///
    /// ```
    /// use bvhkit::{Aabb, Node, TopDown};
    /// use glam::Vec3;
    /// let pts: Vec<Vec3> = (0..64).map(|i| Vec3::new(i as f32, 0.0, 0.0)).collect();
    /// let mut nodes = vec![Node::<Aabb>::EMPTY; 127];
    /// let mut idx = vec![0; 64];
    /// let s = TopDown::median().with_max_leaf_size(1).build(&pts, &mut nodes, &mut idx)?.stats();
    /// assert_eq!((s.leaves, s.max_depth), (64, 6));
    /// assert_eq!(s.mean_leaf_depth, 6.0);
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn stats(&self) -> TreeStats {
        let nodes = self.nodes();
        let Some(root) = nodes.first().map(|n| &n.bv) else {
            return TreeStats::default();
        };
        // Areas and volumes in the root's own unit: a tree 1e30 wide would
        // overflow f32 areas (1e60); the ratios do not depend on the unit.
        let scale = 1.0 / root.aabb().extent().max_element();
        let scale = if scale > 0.0 && scale.is_finite() {
            scale
        } else {
            1.0
        };
        let root_area = (root.surface_area_scaled(scale) as f64).max(f64::MIN_POSITIVE);
        let root_vol = (root.volume_scaled(scale) as f64).max(f64::MIN_POSITIVE);
        let root_box_area = (root.aabb().surface_area_f64()).max(f64::MIN_POSITIVE);
        let mut s = TreeStats {
            nodes: nodes.len(),
            bytes: self.bytes(),
            ..TreeStats::default()
        };
        let mut depth_sum = 0usize;
        let mut stack = [(0u32, 0usize); MAX_DEPTH + 2];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let (i, d) = stack[top];
            let node = &nodes[i as usize];
            let area = node.bv.surface_area_scaled(scale) as f64 / root_area;
            s.volume_sum += node.bv.volume_scaled(scale) as f64 / root_vol;
            match node.children() {
                None => {
                    s.leaves += 1;
                    s.max_depth = s.max_depth.max(d);
                    s.max_leaf_size = s.max_leaf_size.max(node.count as usize);
                    depth_sum += d;
                    s.sah_cost += area * node.count as f64;
                }
                Some((l, r)) => {
                    s.sah_cost += area;
                    let (lb, rb) = (nodes[l as usize].bv.aabb(), nodes[r as usize].bv.aabb());
                    if let Some(x) = lb.intersection(&rb) {
                        s.sibling_overlap += x.surface_area_f64() / root_box_area;
                    }
                    if top + 2 <= stack.len() {
                        stack[top] = (l, d + 1);
                        stack[top + 1] = (r, d + 1);
                        top += 2;
                    }
                }
            }
        }
        s.mean_leaf_depth = depth_sum as f64 / s.leaves.max(1) as f64;
        s
    }
}

impl Aabb {
    /// Surface area in `f64` (no overflow for huge boxes).
    pub fn surface_area_f64(&self) -> f64 {
        let e = (self.max.as_dvec3() - self.min.as_dvec3()).max(glam::DVec3::ZERO);
        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tree::Node;
    use glam::Vec3;

    #[test]
    fn f64_box_area_is_exact_and_does_not_overflow() {
        let b = Aabb::new(Vec3::ZERO, Vec3::new(1.0, 2.0, 3.0));
        assert_eq!(b.surface_area_f64(), 22.0); // 2 * (2 + 6 + 3)
        let huge = Aabb::new(Vec3::ZERO, Vec3::new(1e30, 2e30, 3e30));
        assert!((huge.surface_area_f64() / 22e60 - 1.0).abs() < 1e-6);
        assert_eq!(Aabb::EMPTY.surface_area_f64(), 0.0);
    }

    /// Sibling overlap: the intersection's area over the root's, summed over
    /// sibling pairs; 0 for siblings that only touch.
    #[test]
    fn sibling_overlap_is_the_intersection_over_the_root() {
        let boxes = [
            Aabb::new(Vec3::ZERO, Vec3::new(2.0, 1.0, 1.0)),
            Aabb::new(Vec3::new(1.0, 0.0, 0.0), Vec3::new(3.0, 1.0, 1.0)),
        ];
        let mut nodes = [Node::<Aabb>::EMPTY; 3];
        let mut idx = [0u32; 2];
        let t = crate::TopDown::default()
            .with_max_leaf_size(1)
            .build(&boxes, &mut nodes, &mut idx)
            .unwrap();
        // Intersection 1x1x1 (area 6) over the 3x1x1 root (area 14).
        assert!((t.stats().sibling_overlap - 6.0 / 14.0).abs() < 1e-12);
    }
}
