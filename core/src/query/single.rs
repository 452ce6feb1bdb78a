//! Single-tree queries: which primitives does a region touch?

use super::stack::Stack;
use super::{CastTarget, Hit, Nearest, PointDistance, Ray, RayOrder, RayTarget, ShapeCast, Tally};
#[cfg(feature = "kdop")]
use crate::bv::Kdop;
#[cfg(feature = "sphere")]
use crate::bv::Sphere;
use crate::bv::{Aabb, BoundingVolume};
use crate::primitive::Primitive;
use crate::tree::hierarchy::{check_query, DFS_STACK};
use crate::tree::{Bvh, Content, Hierarchy, Kids};
use crate::Error;
use glam::Vec3;

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

    /// Refuses a region no query can answer meaningfully (every query calls
    /// it first): a NaN, or bounds that are inverted (an empty set, whose
    /// answer "nothing" would look like a real miss). Infinite bounds are
    /// fine: a box from `-inf` to `+inf` asks for everything. An `Err` is
    /// [`Error::InvalidQuery`].
    fn check(&self) -> Result<(), Error>;
}

impl Region for Aabb {
    fn check(&self) -> Result<(), Error> {
        if self.min.is_nan() || self.max.is_nan() {
            return Err(Error::InvalidQuery("the query box has a NaN coordinate"));
        }
        if self.min.cmpgt(self.max).any() {
            return Err(Error::InvalidQuery(
                "the query box is inverted (min > max on an axis)",
            ));
        }
        Ok(())
    }

    /// An AABB region's leaf test is exact, so any conservative node test is
    /// enough; the node volume's own test is the tightest available.
    #[inline]
    fn may_overlap<B: BoundingVolume>(&self, bv: &B) -> bool {
        bv.overlaps_aabb(self)
    }
}

#[cfg(feature = "sphere")]
impl Region for Sphere {
    fn check(&self) -> Result<(), Error> {
        // An infinite radius (everything) is fine.
        if !self.center.is_finite() || self.radius.is_nan() || self.radius < 0.0 {
            return Err(Error::InvalidQuery(
                "the query sphere needs a finite centre and a radius >= 0",
            ));
        }
        Ok(())
    }
}

#[cfg(feature = "kdop")]
impl<const K: usize> Region for Kdop<K> {
    fn check(&self) -> Result<(), Error> {
        if self.min.iter().chain(&self.max).any(|x| x.is_nan()) {
            return Err(Error::InvalidQuery("the query k-DOP has a NaN bound"));
        }
        if self.min.iter().zip(&self.max).any(|(lo, hi)| lo > hi) {
            return Err(Error::InvalidQuery(
                "the query k-DOP is inverted (min > max on a direction)",
            ));
        }
        Ok(())
    }
}

/// Traversal order of a single-tree query.
///
/// Lecture: *hierarchy traversal*. Depth-first needs a stack as deep as the
/// tree (a fixed stack sized from [`MAX_DEPTH`](crate::MAX_DEPTH)); breadth-first needs a queue as
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

/// Calls `f` with each primitive of leaf `n` (ids `here`) whose bounds
/// overlap `region`; returns how many. Reads the tree's kept bounds when it
/// has them ([`Hierarchy::leaf_bounds`]), else the primitives.
#[inline(always)]
fn leaf_overlapping<H: Hierarchy + ?Sized, P: Primitive, R: Region>(
    h: &H,
    n: u32,
    here: &[u32],
    prims: &[P],
    region: &R,
    f: &mut impl FnMut(u32),
) -> u32 {
    let mut found = 0;
    let mut visit = |p: u32, b: &Aabb| {
        if region.overlaps_aabb(b) {
            f(p);
            found += 1;
        }
    };
    match h.leaf_bounds(n) {
        // One box per id, as the trait promises; anything else reads the
        // primitives rather than drop one.
        Some(kept) if kept.len() == here.len() => {
            here.iter().zip(kept).for_each(|(&p, b)| visit(p, b))
        }
        _ => here
            .iter()
            .for_each(|&p| visit(p, &prims[p as usize].bounds())),
    }
    found
}

/// The single-tree queries, for every [`Hierarchy`] (the canonical [`Bvh`]
/// and every [layout](crate::layout)). `Bvh` has the same methods inherently,
/// so it needs no import.
///
/// ```
/// use bvhkit::glam::Vec3;
/// use bvhkit::layout::{Wide, WideNode};
/// use bvhkit::{Aabb, Node, Query, TopDown};
/// let points: Vec<Vec3> = (0..32).map(|i| Vec3::new(i as f32, 0.0, 0.0)).collect();
/// let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(32)];
/// let mut indices = vec![0; 32];
/// let tree = TopDown::default().build(&points, &mut nodes, &mut indices)?;
/// let mut records = vec![WideNode::EMPTY; Wide::records_needed(&tree)?];
/// let wide = Wide::from_bvh(&tree, &mut records)?;
/// // The same question, the same answer, on either representation.
/// let region = Aabb::new(Vec3::new(9.5, -1.0, -1.0), Vec3::new(12.5, 1.0, 1.0));
/// assert_eq!(Query::overlapping(&wide, &points, &region, |_| {})?, 3);
/// assert_eq!(tree.overlapping(&points, &region, |_| {})?, 3);
/// # Ok::<(), bvhkit::Error>(())
/// ```
pub trait Query: Hierarchy {
    /// Calls `f` with every primitive whose bounds overlap `region` (an
    /// [`Aabb`], [`Sphere`] or [`Kdop`]); returns the count. Depth-first with
    /// a fixed stack; children are tested before they are pushed. The answer
    /// equals [`brute_force::overlapping`](crate::brute_force::overlapping).
    fn overlapping<P: Primitive, R: Region>(
        &self,
        prims: &[P],
        region: &R,
        mut f: impl FnMut(u32),
    ) -> Result<usize, Error> {
        check_query(self, prims.len())?;
        region.check()?;
        if self.is_empty() {
            return Ok(0);
        }
        let mut found = 0;
        let root = self.root();
        if !region.may_overlap(&self.bv(root)) {
            return Ok(0);
        }
        let mut stack = Stack::<u32, DFS_STACK>::with(root, self.depth());
        while let Some(n) = stack.pop() {
            match self.content(n) {
                Content::Leaf(here) => {
                    found += leaf_overlapping(self, n, here, prims, region, &mut f) as usize;
                }
                Content::Inner(kids) => {
                    for &c in kids.as_slice().iter().rev() {
                        if region.may_overlap(&self.bv(c)) {
                            stack.push(c)?;
                        }
                    }
                }
            }
        }
        Ok(found)
    }

    /// The same query with a choice of traversal [`Order`] and a [`Tally`]
    /// (`Nv` = node tests, `Np` = primitive tests). Every order returns the
    /// same primitives; the order in which `f` sees them differs.
    fn search<P: Primitive, R: Region>(
        &self,
        prims: &[P],
        region: &R,
        order: Order<'_>,
        mut tally: impl Tally,
        mut f: impl FnMut(u32),
    ) -> Result<usize, Error> {
        check_query(self, prims.len())?;
        region.check()?;
        if self.is_empty() {
            return Ok(0);
        }
        let mut found = 0;
        // Tests leaf `n`'s primitives; returns how many were tested.
        let mut visit_leaf = |n: u32, here: &[u32]| {
            found += leaf_overlapping(self, n, here, prims, region, &mut f) as usize;
            here.len() as u32
        };
        match order {
            Order::DepthFirst => {
                let mut stack = Stack::<u32, DFS_STACK>::with(self.root(), self.depth());
                while let Some(n) = stack.pop() {
                    tally.bv_tests(1);
                    if !region.may_overlap(&self.bv(n)) {
                        continue;
                    }
                    match self.content(n) {
                        Content::Leaf(here) => tally.prim_tests(visit_leaf(n, here)),
                        Content::Inner(kids) => {
                            for &c in kids.as_slice().iter().rev() {
                                stack.push(c)?;
                            }
                        }
                    }
                }
            }
            Order::Recursive => {
                fn walk<H: Hierarchy + ?Sized, R: Region>(
                    h: &H,
                    n: u32,
                    region: &R,
                    tally: &mut impl Tally,
                    leaf: &mut impl FnMut(u32, &[u32]) -> u32,
                ) {
                    tally.bv_tests(1);
                    if !region.may_overlap(&h.bv(n)) {
                        return;
                    }
                    match h.content(n) {
                        Content::Leaf(here) => tally.prim_tests(leaf(n, here)),
                        Content::Inner(kids) => {
                            for &c in kids.as_slice() {
                                walk(h, c, region, tally, leaf);
                            }
                        }
                    }
                }
                walk(self, self.root(), region, &mut tally, &mut visit_leaf);
            }
            Order::BreadthFirst(queue) => {
                let needed = self.breadth_first_queue();
                if queue.len() < needed {
                    return Err(Error::QueueCapacity {
                        needed,
                        available: queue.len(),
                    });
                }
                bfs(self, queue, |n| {
                    tally.bv_tests(1);
                    if !region.may_overlap(&self.bv(n)) {
                        return None;
                    }
                    match self.content(n) {
                        Content::Leaf(here) => {
                            tally.prim_tests(visit_leaf(n, here));
                            None
                        }
                        Content::Inner(kids) => Some(kids),
                    }
                })?;
            }
        }
        Ok(found)
    }

    /// The closest primitive the ray hits (see [`Bvh::cast_ray`]).
    fn cast_ray<P: RayTarget>(
        &self,
        prims: &[P],
        ray: &Ray,
        order: RayOrder,
        tally: impl Tally,
    ) -> Result<Option<Hit>, Error> {
        super::ray::cast_ray(self, prims, ray, order, tally)
    }

    /// Some primitive the ray hits, stopping at the first (see [`Bvh::ray_hits_any`]).
    fn ray_hits_any<P: RayTarget>(
        &self,
        prims: &[P],
        ray: &Ray,
        tally: impl Tally,
    ) -> Result<Option<Hit>, Error> {
        super::ray::ray_hits_any(self, prims, ray, tally)
    }

    /// The first primitive a moving sphere or box touches (see
    /// [`Bvh::cast_shape`]).
    fn cast_shape<P: CastTarget>(
        &self,
        prims: &[P],
        cast: &ShapeCast,
        order: RayOrder,
        tally: impl Tally,
    ) -> Result<Option<Hit>, Error> {
        super::cast::cast_shape(self, prims, cast, order, tally)
    }

    /// Some primitive a moving shape touches, stopping at the first (see
    /// [`Bvh::shape_hits_any`]).
    fn shape_hits_any<P: CastTarget>(
        &self,
        prims: &[P],
        cast: &ShapeCast,
        tally: impl Tally,
    ) -> Result<Option<Hit>, Error> {
        super::cast::shape_hits_any(self, prims, cast, tally)
    }

    /// The primitive nearest to `point`, best-first (see [`Bvh::nearest`]).
    fn nearest<P: PointDistance>(
        &self,
        prims: &[P],
        point: Vec3,
        tally: impl Tally,
    ) -> Result<Option<Nearest>, Error> {
        super::nearest::nearest(self, prims, point, tally)
    }

    /// Queue entries [`Order::BreadthFirst`] needs for this tree: its leaf
    /// count bounds the number of nodes waiting at once (none of them
    /// contains another), and a tree has fewer leaves than nodes.
    fn breadth_first_queue(&self) -> usize {
        if Self::ARITY == 2 {
            self.node_count().div_ceil(2)
        } else {
            self.node_count()
        }
    }
}

impl<H: Hierarchy + ?Sized> Query for H {}

/// Breadth-first over `h` with `queue` as a ring buffer of node ids; `open`
/// tests a node and returns the children to enqueue.
fn bfs<H: Hierarchy + ?Sized>(
    h: &H,
    queue: &mut [u32],
    mut open: impl FnMut(u32) -> Option<Kids>,
) -> Result<(), Error> {
    let cap = queue.len();
    if cap == 0 {
        return Err(Error::QueueCapacity {
            needed: 1,
            available: 0,
        });
    }
    let (mut head, mut len) = (0usize, 1usize);
    queue[0] = h.root();
    while len > 0 {
        let n = queue[head];
        head = (head + 1) % cap;
        len -= 1;
        if let Some(kids) = open(n) {
            for &c in kids.as_slice() {
                if len == cap {
                    return Err(Error::QueueCapacity {
                        needed: cap + 1,
                        available: cap,
                    });
                }
                queue[(head + len) % cap] = c;
                len += 1;
            }
        }
    }
    Ok(())
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
        f: impl FnMut(u32),
    ) -> Result<usize, Error> {
        Query::overlapping(self, prims, region, f)
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
        tally: impl Tally,
        f: impl FnMut(u32),
    ) -> Result<usize, Error> {
        Query::search(self, prims, region, order, tally, f)
    }

    /// Queue entries [`Order::BreadthFirst`] needs for this tree: its leaf count.
    pub fn breadth_first_queue(&self) -> usize {
        Query::breadth_first_queue(self)
    }
}
