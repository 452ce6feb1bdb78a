//! Two-tree queries: which primitive pairs of A and B overlap?

use super::Descent;
use crate::bv::BoundingVolume;
use crate::primitive::Primitive;
use crate::tree::{Bvh, MAX_DEPTH};
use crate::Error;

/// Stack entries for a pair traversal: one-sided rules wait on at most one pair
/// per level (`<= 2 * MAX_DEPTH` levels); simultaneous descent on at most three
/// per level while both sides descend.
const PAIR_STACK: usize = 4 * MAX_DEPTH + 4;

/// Calls `f(a, b)` for every pair of primitives, one from each tree, whose
/// bounds overlap; returns the count.
///
/// This is the lectures' informed depth-first traversal with an explicit stack:
/// a pair of nodes is opened only if their volumes overlap, and `rule` picks
/// which side to open. The root pair and every child pair are tested before
/// they are pushed, so even trees of one or two leaves are pruned correctly.
///
/// ```
/// use bvhkit::{overlapping_pairs, Aabb, Descent, Node, TopDown, Triangle};
/// use glam::Vec3;
/// let a = [Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y + Vec3::Z)];
/// let b = [Triangle::new(Vec3::splat(0.5), Vec3::new(2.0, 0.5, 0.5), Vec3::new(0.5, 2.0, 0.5)),
///          Triangle::new(Vec3::splat(9.0), Vec3::splat(9.5), Vec3::new(9.0, 9.5, 9.0))];
/// let (mut na, mut nb) = ([Node::<Aabb>::EMPTY; 1], [Node::<Aabb>::EMPTY; 3]);
/// let (mut ia, mut ib) = ([0; 1], [0; 2]);
/// let ta = TopDown::default().build(&a, &mut na, &mut ia)?;
/// let tb = TopDown::default().with_max_leaf_size(1).build(&b, &mut nb, &mut ib)?;
/// let mut pairs = Vec::new();
/// overlapping_pairs(&ta, &a, &tb, &b, Descent::Larger, |i, j| pairs.push((i, j)))?;
/// assert_eq!(pairs, [(0, 0)]);
/// # Ok::<(), bvhkit::Error>(())
/// ```
pub fn overlapping_pairs<B: BoundingVolume, P: Primitive, Q: Primitive>(
    a: &Bvh<'_, B>,
    prims_a: &[P],
    b: &Bvh<'_, B>,
    prims_b: &[Q],
    rule: Descent,
    mut f: impl FnMut(u32, u32),
) -> Result<usize, Error> {
    a.check_query(prims_a.len())?;
    b.check_query(prims_b.len())?;
    let (na, nb) = (a.nodes(), b.nodes());
    let mut stack = [(0u32, 0u32, 0u32); PAIR_STACK];
    let mut top = 0;
    let mut found = 0;
    if na[0].bv.overlaps(&nb[0].bv) {
        top = 1;
    }
    while top > 0 {
        top -= 1;
        let (i, j, depth) = stack[top];
        let (x, y) = (&na[i as usize], &nb[j as usize]);
        if x.is_leaf() && y.is_leaf() {
            for &p in a.leaf_primitives(x) {
                let pb = prims_a[p as usize].bounds();
                for &q in b.leaf_primitives(y) {
                    if pb.overlaps(&prims_b[q as usize].bounds()) {
                        f(p, q);
                        found += 1;
                    }
                }
            }
            continue;
        }
        let (open_a, open_b) = rule.choose(x, y, depth);
        let sides = |open: bool, node: &crate::Node<B>, me: u32| match (open, node.children()) {
            (true, Some((l, r))) => ([l, r], 2),
            _ => ([me, me], 1),
        };
        let (ca, ka) = sides(open_a, x, i);
        let (cb, kb) = sides(open_b, y, j);
        for &u in &ca[..ka] {
            for &v in &cb[..kb] {
                if na[u as usize].bv.overlaps(&nb[v as usize].bv) {
                    if top == PAIR_STACK {
                        return Err(Error::StackOverflow {
                            depth: a.depth() + b.depth(),
                            capacity: PAIR_STACK,
                        });
                    }
                    stack[top] = (u, v, depth + 1);
                    top += 1;
                }
            }
        }
    }
    Ok(found)
}
