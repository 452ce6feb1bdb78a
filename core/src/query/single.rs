//! Single-tree queries: which primitives does a region touch?

use super::Tally;
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

/// Traversal order of a single-tree query.
///
/// Lecture: *hierarchy traversal*. Depth-first needs a stack as deep as the
/// tree (fixed, [`MAX_DEPTH`]` + 1` entries); breadth-first needs a queue as
/// wide as the tree (up to its leaf count, given by the caller), which is why
/// collision detection favours depth-first.
#[derive(Debug)]
pub enum Order<'q> {
    /// Depth-first with an explicit fixed stack.
    DepthFirst,
    /// Depth-first as a recursive function (the call stack, depth + 1 frames).
    Recursive,
    /// Breadth-first with a caller-provided queue of at least
    /// [`Bvh::breadth_first_queue`] entries.
    BreadthFirst(&'q mut [u32]),
}

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

    /// The same query with a choice of traversal order and a [`Tally`]
    /// (`Nv` = node tests, `Np` = primitive tests). Every order returns the
    /// same primitives; the order in which `f` sees them differs.
    ///
    /// ```
    /// use bvhkit::{Aabb, Counts, Node, Order, TopDown};
    /// use glam::Vec3;
    /// let pts: Vec<Vec3> = (0..64).map(|i| Vec3::new(i as f32, 0.0, 0.0)).collect();
    /// let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(64)];
    /// let mut idx = vec![0; 64];
    /// let bvh = TopDown::default().build(&pts, &mut nodes, &mut idx)?;
    /// let region = Aabb::new(Vec3::new(9.5, -1.0, -1.0), Vec3::new(20.5, 1.0, 1.0));
    /// let mut queue = vec![0u32; bvh.breadth_first_queue()];
    /// let mut counts = Counts::default();
    /// let n = bvh.search(&pts, &region, Order::BreadthFirst(&mut queue), &mut counts, |_| {})?;
    /// assert_eq!(n, 11);
    /// assert_eq!(bvh.search(&pts, &region, Order::Recursive, (), |_| {})?, 11);
    /// assert!(counts.bv_tests < 64); // pruned
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn search<P: Primitive, R: Region>(
        &self,
        prims: &[P],
        region: &R,
        order: Order<'_>,
        mut tally: impl Tally,
        mut f: impl FnMut(u32),
    ) -> Result<usize, Error> {
        self.check_query(prims.len())?;
        let nodes = self.nodes();
        let mut found = 0;
        // Tests a leaf's primitives; returns how many were tested.
        let mut visit_leaf = |n: u32| {
            let here = self.leaf_primitives(&nodes[n as usize]);
            for &p in here {
                if region.overlaps_aabb(&prims[p as usize].bounds()) {
                    f(p);
                    found += 1;
                }
            }
            here.len() as u32
        };
        match order {
            Order::DepthFirst => {
                let mut stack = [0u32; MAX_DEPTH + 2];
                let mut top = 1;
                while top > 0 {
                    top -= 1;
                    let n = stack[top];
                    tally.bv_tests(1);
                    if !region.may_overlap(&nodes[n as usize].bv) {
                        continue;
                    }
                    match nodes[n as usize].children() {
                        None => tally.prim_tests(visit_leaf(n)),
                        Some((l, r)) => {
                            stack[top] = r;
                            stack[top + 1] = l;
                            top += 2;
                        }
                    }
                }
            }
            Order::Recursive => {
                fn walk<B: BoundingVolume, R: Region>(
                    nodes: &[crate::Node<B>],
                    n: u32,
                    region: &R,
                    tally: &mut impl Tally,
                    leaf: &mut impl FnMut(u32) -> u32,
                ) {
                    tally.bv_tests(1);
                    if !region.may_overlap(&nodes[n as usize].bv) {
                        return;
                    }
                    match nodes[n as usize].children() {
                        None => tally.prim_tests(leaf(n)),
                        Some((l, r)) => {
                            walk(nodes, l, region, tally, leaf);
                            walk(nodes, r, region, tally, leaf);
                        }
                    }
                }
                walk(nodes, 0, region, &mut tally, &mut visit_leaf);
            }
            Order::BreadthFirst(queue) => {
                let needed = self.breadth_first_queue();
                if queue.len() < needed {
                    return Err(Error::QueueCapacity {
                        needed,
                        available: queue.len(),
                    });
                }
                // A ring buffer: the queue never holds more nodes than the
                // tree has leaves (the nodes in it never contain one another).
                let cap = queue.len();
                let (mut head, mut len) = (0usize, 1usize);
                queue[0] = 0;
                while len > 0 {
                    let n = queue[head];
                    head = (head + 1) % cap;
                    len -= 1;
                    tally.bv_tests(1);
                    if !region.may_overlap(&nodes[n as usize].bv) {
                        continue;
                    }
                    match nodes[n as usize].children() {
                        None => tally.prim_tests(visit_leaf(n)),
                        Some((l, r)) => {
                            for c in [l, r] {
                                queue[(head + len) % cap] = c;
                                len += 1;
                            }
                        }
                    }
                }
            }
        }
        Ok(found)
    }

    /// Queue entries [`Order::BreadthFirst`] needs for this tree: its leaf count.
    pub fn breadth_first_queue(&self) -> usize {
        self.node_count().div_ceil(2)
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
