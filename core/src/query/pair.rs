//! Two-tree queries: which primitive pairs of A and B overlap (or intersect)?
//!
//! The pipeline of one query is fixed; each stage is a small, swappable type:
//!
//! | stage | type | choices |
//! |---|---|---|
//! | walk the trees | [`PairTraversal`] | recursive, explicit stack, simultaneous, leaf-directed |
//! | pick a side | [`DescentRule`] | [`Descent`] (the lectures' rules), [`DepthSwitch`](super::DepthSwitch), your own |
//! | where B is | [`Frame`] | [`Same`] frame, or a [`Rigid`] motion into A's frame |
//! | decide a primitive pair | [`Answer`] | [`Bounds`] overlap, [`Exact`] intersection, a closure |
//! | what to return | method | [`Pairs::for_each`], [`Pairs::first`], [`Pairs::count`] |
//! | count the work | [`Tally`] | `()` (free), [`Counts`](super::Counts) |

use super::stack::Stack;
use super::{Decision, Descent, DescentRule, Open, Tally};
use crate::bv::{Aabb, BoundingVolume};
use crate::narrow::Intersects;
use crate::primitive::Primitive;
use crate::transform::{Rigid, Transform};
use crate::tree::hierarchy::{check_query, DFS_STACK};
use crate::tree::{Boxes4, Content, Hierarchy, Kids, MAX_CHILDREN, MAX_DEPTH};
use crate::Error;
use core::ops::ControlFlow;

/// Stack entries for a pair traversal. Each descent step leaves at most one
/// pair waiting when one side opens and three when both open; a path has at
/// most `2 * MAX_DEPTH` one-sided or `MAX_DEPTH` two-sided steps.
pub const PAIR_STACK: usize = 4 * MAX_DEPTH + 4;

/// One pair waiting on the explicit pair stack: A's node, B's node and the
/// step's depth.
pub(super) type PairEntry = (u32, u32, u32);

/// Spare entries the explicit pair stack keeps past its capacity, so that a
/// step can write all its child pairs before knowing which it keeps.
pub(super) const SLACK: usize = MAX_CHILDREN * MAX_CHILDREN;

/// Stack entries for a pair traversal when either tree is 4-wide: a
/// two-sided step leaves up to 15 pairs waiting. Used only for wide layouts,
/// so binary queries keep the smaller stack frame.
pub const WIDE_PAIR_STACK: usize = 15 * MAX_DEPTH + 4;

/// Stack entries for a pair traversal of two binary trees whose
/// [`pair_stack_bound`] fits (both at most 22 deep, for instance). Such
/// queries run on this smaller stack: 1,008 bytes
/// instead of 3,312 (both with their spare entries), which matters on a
/// microcontroller.
pub const SMALL_PAIR_STACK: usize = 4 * 16 + 4;

/// Most pairs waiting on the stack of a pair traversal of trees with these
/// (arity, depth): `s` two-sided steps (at most the smaller depth) leave
/// `ka * kb - 1` pairs each, the remaining one-sided steps `k - 1` each. The
/// count is linear in `s`, so its maximum is at an end of the range.
///
/// For two binary trees this is `da + db + min(da, db) + 1`:
///
/// ```
/// assert_eq!(bvhkit::query::pair_stack_bound((2, 7), (2, 9)), 7 + 9 + 7 + 1);
/// ```
pub const fn pair_stack_bound((ka, da): (usize, usize), (kb, db): (usize, usize)) -> usize {
    let m = if da < db { da } else { db };
    let none = da * (ka - 1) + db * (kb - 1);
    let all = m * (ka * kb - 1) + (da - m) * (ka - 1) + (db - m) * (kb - 1);
    (if none > all { none } else { all }) + 1
}

/// How a two-tree query walks the trees. The answer is the same for every
/// choice; the work differs.
///
/// ```
/// use bvhkit::glam::Vec3;
/// use bvhkit::{Aabb, Descent, Node, PairTraversal, Pairs, TopDown};
/// // Boxes 1.2 wide at 0, 1, 2, ..., points half-way between them.
/// let a: Vec<Aabb> = (0..20).map(|i| Aabb::new(Vec3::new(i as f32 - 0.6, 0.0, 0.0), Vec3::new(i as f32 + 0.6, 0.0, 0.0))).collect();
/// let b: Vec<Vec3> = (0..20).map(|i| Vec3::new(i as f32 + 0.5, 0.0, 0.0)).collect();
/// let (mut na, mut nb) = (vec![Node::<Aabb>::EMPTY; 39], vec![Node::<Aabb>::EMPTY; 39]);
/// let (mut ia, mut ib) = (vec![0; 20], vec![0; 20]);
/// let ta = TopDown::default().build(&a, &mut na, &mut ia)?;
/// let tb = TopDown::default().build(&b, &mut nb, &mut ib)?;
/// let default = Pairs::new(&ta, &a, &tb, &b).count()?;
/// let recursive = Pairs::new(&ta, &a, &tb, &b)
///     .traversal(PairTraversal::Recursive(Descent::Larger))
///     .count()?;
/// assert_eq!((default, recursive), (39, 39)); // each point in two boxes, the last in one
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PairTraversal<D = Descent> {
    /// The lectures' generic informed depth-first traversal, written as a
    /// recursive function: test the pair on entry, collide two leaves,
    /// otherwise let the rule pick a side and recurse on its children. Uses
    /// the call stack (at most `2 * MAX_DEPTH + 1` frames).
    Recursive(D),
    /// The same traversal without recursion: an explicit fixed stack of
    /// [`PAIR_STACK`] pairs, child pairs tested before they are pushed.
    /// Usually the fastest; the default with [`Descent::Simultaneous`].
    Stack(D),
    /// The textbook's simultaneous depth-first traversal: both trees descend
    /// in lock step (four child pairs per step) on the explicit stack. The
    /// same walk as `Stack(Descent::Simultaneous)`.
    Simultaneous,
    /// Leaf-directed depth-first traversal: walk A alone (pruned against B's
    /// root) and, at each leaf of A, run a single-tree query of that leaf's
    /// volume down B. Tight inner loop; good when A's leaves are few or small
    /// against B, wasteful when B's top levels get re-tested per leaf of A.
    LeafDirected,
}

/// The stack walk with the simultaneous rule: it makes no decision per
/// step, and on the peer benchmark's meshes (a mesh against a moved copy)
/// it ran in 0.70-0.75x the time of [`Descent::Larger`], with small objects
/// against large ones no slower.
impl Default for PairTraversal {
    fn default() -> Self {
        PairTraversal::Stack(Descent::Simultaneous)
    }
}

impl PairTraversal {
    /// [`PairTraversal::Simultaneous`] with the rule type fixed, so that it
    /// needs no type annotation.
    pub const SIMULTANEOUS: PairTraversal = PairTraversal::Simultaneous;
    /// [`PairTraversal::LeafDirected`] with the rule type fixed, so that it
    /// needs no type annotation.
    pub const LEAF_DIRECTED: PairTraversal = PairTraversal::LeafDirected;

    /// The four traversal kinds with the given rule where they take one.
    pub const fn all(rule: Descent) -> [PairTraversal; 4] {
        [
            PairTraversal::Recursive(rule),
            PairTraversal::Stack(rule),
            PairTraversal::Simultaneous,
            PairTraversal::LeafDirected,
        ]
    }

    /// Short name of the traversal kind.
    pub const fn name(&self) -> &'static str {
        match self {
            PairTraversal::Recursive(_) => "recursive",
            PairTraversal::Stack(_) => "stack",
            PairTraversal::Simultaneous => "simultaneous",
            PairTraversal::LeafDirected => "leaf-directed",
        }
    }
}

/// Where tree B sits relative to tree A.
pub trait Frame {
    /// Whether volumes of B are moved (each move counts as an update, `Nu`).
    const MOVES: bool;
    /// A volume of B, in A's frame: contains every moved point of `bv`.
    fn bv<B: BoundingVolume>(&self, bv: &B) -> B;
    /// A volume of B, in A's frame, that also contains the new bounding box
    /// of anything inside (see [`BoundingVolume::transformed_with_boxes`]).
    fn bv_with_boxes<B: BoundingVolume>(&self, bv: &B) -> B {
        self.bv(bv)
    }
}

/// Places a primitive of B in A's frame.
pub trait Place<Q> {
    /// The primitive in A's frame.
    fn place(&self, q: &Q) -> Q;
}

/// B is in A's frame already (no updates).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Same;

impl Frame for Same {
    const MOVES: bool = false;
    #[inline(always)]
    fn bv<B: BoundingVolume>(&self, bv: &B) -> B {
        *bv
    }
}

impl<Q: Clone> Place<Q> for Same {
    #[inline(always)]
    fn place(&self, q: &Q) -> Q {
        q.clone()
    }
}

/// B is moved into A's frame by this motion (B's model frame to A's).
impl Frame for Rigid {
    const MOVES: bool = true;
    #[inline]
    fn bv<B: BoundingVolume>(&self, bv: &B) -> B {
        bv.transformed(self)
    }
    #[inline]
    fn bv_with_boxes<B: BoundingVolume>(&self, bv: &B) -> B {
        bv.transformed_with_boxes(self)
    }
}

impl<Q: Transform> Place<Q> for Rigid {
    #[inline]
    fn place(&self, q: &Q) -> Q {
        q.transformed(self)
    }
}

/// Decides whether a primitive pair (B's already in A's frame) is an answer.
pub trait Answer<P, Q> {
    /// Whether every accepted pair shares a point of the two primitives
    /// themselves (an exact test). Then a moved tree B only needs volumes
    /// containing its moved primitives. Answers that compare *boxes* (the
    /// default, `false`) need B's moved volumes to contain the primitives'
    /// new boxes too, which for spheres is looser.
    const POINTWISE: bool = false;
    /// `true` to report the pair. Queries ask only about pairs whose bounds
    /// ([`Primitive::bounds`]) overlap: no two primitives touch otherwise,
    /// so an answer never sees a pair it would have to reject on that alone.
    fn accept(&mut self, p: &P, q: &Q) -> bool;
    /// [`accept`](Self::accept) for a pair whose bounds are known to overlap
    /// (the query tested them, four at a time): an answer may skip that test
    /// here. The default asks `accept`.
    #[inline(always)]
    fn accept_overlapping(&mut self, p: &P, q: &Q) -> bool {
        self.accept(p, q)
    }
}

/// Report pairs whose primitive bounds overlap: the *candidate* pairs.
/// Exact for boxes; for other primitives a superset of the touching pairs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Bounds;

impl<P: Primitive, Q: Primitive> Answer<P, Q> for Bounds {
    #[inline]
    fn accept(&mut self, p: &P, q: &Q) -> bool {
        p.bounds().overlaps(&q.bounds())
    }
    #[inline(always)]
    fn accept_overlapping(&mut self, _: &P, _: &Q) -> bool {
        true
    }
}

/// Report pairs that really touch ([`Intersects`]): bounds first (cheap
/// reject), then the exact test. [`Pairs::exact`] chooses it.
///
/// ```
/// use bvhkit::glam::Vec3;
/// use bvhkit::{Aabb, Node, Pairs, TopDown, Triangle};
/// // Two triangles whose boxes overlap but which do not touch.
/// let a = [Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y)];
/// let b = [Triangle::new(Vec3::new(0.9, 0.9, -1.0), Vec3::new(0.9, 0.9, 1.0), Vec3::new(1.0, 1.0, 0.0))];
/// let (mut na, mut nb) = ([Node::<Aabb>::EMPTY; 1], [Node::<Aabb>::EMPTY; 1]);
/// let (mut ia, mut ib) = ([0u32; 1], [0u32; 1]);
/// let ta = TopDown::default().build(&a, &mut na, &mut ia)?;
/// let tb = TopDown::default().build(&b, &mut nb, &mut ib)?;
/// assert_eq!(Pairs::new(&ta, &a, &tb, &b).count()?, 1); // bounds overlap
/// assert_eq!(Pairs::new(&ta, &a, &tb, &b).exact().count()?, 0); // no contact
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Exact;

impl<P: Primitive + Intersects<Q>, Q: Primitive> Answer<P, Q> for Exact {
    const POINTWISE: bool = true;
    #[inline]
    fn accept(&mut self, p: &P, q: &Q) -> bool {
        p.bounds().overlaps(&q.bounds()) && p.intersects(q)
    }
    #[inline(always)]
    fn accept_overlapping(&mut self, p: &P, q: &Q) -> bool {
        p.intersects(q)
    }
}

/// Any closure can decide, e.g. to count candidates on the way to an exact answer.
impl<P, Q, G: FnMut(&P, &Q) -> bool> Answer<P, Q> for G {
    #[inline]
    fn accept(&mut self, p: &P, q: &Q) -> bool {
        self(p, q)
    }
}

/// A two-tree query, configured step by step, then run in one of three
/// result modes.
///
/// ```
/// use bvhkit::{Aabb, Counts, Descent, Node, PairTraversal, Pairs, Rigid, TopDown, Triangle};
/// use glam::{Quat, Vec3};
/// let tris: Vec<Triangle> = (0..16).map(|i| {
///     let o = Vec3::new(i as f32, 0.0, 0.0);
///     Triangle::new(o, o + Vec3::new(1.2, 0.0, 0.0), o + Vec3::new(0.0, 1.0, 0.0))
/// }).collect();
/// let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(16)];
/// let mut idx = vec![0; 16];
/// let tree = TopDown::default().with_max_leaf_size(2).build(&tris, &mut nodes, &mut idx)?;
///
/// // The same mesh, turned a quarter around z and stood on its end.
/// let motion = Rigid::new(Quat::from_rotation_z(1.5708), Vec3::new(8.5, -4.0, 0.0))?;
/// let mut counts = Counts::default();
/// let mut hits = Vec::new();
/// Pairs::new(&tree, &tris, &tree, &tris)
///     .traversal(PairTraversal::Stack(Descent::Larger))
///     .in_frame(motion)
///     .exact()
///     .counted(&mut counts)
///     .for_each(|a, b| hits.push((a, b)))?;
/// assert!(!hits.is_empty());
/// assert!(counts.bv_tests > 0 && counts.updates > 0);
/// // Other modes: stop at the first pair, or only count.
/// let first = Pairs::new(&tree, &tris, &tree, &tris).in_frame(motion).exact().first()?;
/// assert!(first.is_some_and(|p| hits.contains(&p)));
/// assert_eq!(Pairs::new(&tree, &tris, &tree, &tris).in_frame(motion).exact().count()?, hits.len());
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Debug)]
pub struct Pairs<'q, A, H, P, Q, D = Descent, F = Same, X = Bounds, T = ()> {
    a: &'q A,
    pa: &'q [P],
    b: &'q H,
    pb: &'q [Q],
    traversal: PairTraversal<D>,
    frame: F,
    answer: X,
    tally: T,
}

impl<'q, A: Hierarchy, H: Hierarchy<Bv = A::Bv>, P, Q> Pairs<'q, A, H, P, Q> {
    /// Tree A over `pa` against tree B over `pb`: stack traversal,
    /// simultaneous rule, same frame, bounds answer, no counting. A and B may be stored in
    /// different representations ([`Bvh`](crate::Bvh), any [layout](crate::layout)) as
    /// long as their volume type is the same.
    pub fn new(a: &'q A, pa: &'q [P], b: &'q H, pb: &'q [Q]) -> Self {
        Pairs {
            a,
            pa,
            b,
            pb,
            traversal: PairTraversal::default(),
            frame: Same,
            answer: Bounds,
            tally: (),
        }
    }
}

impl<'q, A, H, P, Q, D, F, X, T> Pairs<'q, A, H, P, Q, D, F, X, T> {
    /// Chooses the traversal (and with it the descent rule).
    pub fn traversal<D2>(self, traversal: PairTraversal<D2>) -> Pairs<'q, A, H, P, Q, D2, F, X, T> {
        Pairs {
            a: self.a,
            pa: self.pa,
            b: self.b,
            pb: self.pb,
            traversal,
            frame: self.frame,
            answer: self.answer,
            tally: self.tally,
        }
    }

    /// Shorthand for `traversal(PairTraversal::Stack(rule))`.
    pub fn descent<D2>(self, rule: D2) -> Pairs<'q, A, H, P, Q, D2, F, X, T> {
        self.traversal(PairTraversal::Stack(rule))
    }

    /// Queries B as if moved by `motion` (B's frame to A's), without rebuilding it.
    pub fn in_frame(self, motion: Rigid) -> Pairs<'q, A, H, P, Q, D, Rigid, X, T> {
        self.in_frame_of(motion)
    }

    /// Places B by any [`Frame`] ([`Same`] or a [`Rigid`] motion).
    pub fn in_frame_of<F2>(self, frame: F2) -> Pairs<'q, A, H, P, Q, D, F2, X, T> {
        Pairs {
            a: self.a,
            pa: self.pa,
            b: self.b,
            pb: self.pb,
            traversal: self.traversal,
            frame,
            answer: self.answer,
            tally: self.tally,
        }
    }

    /// Decides primitive pairs with `answer`.
    pub fn answer<X2>(self, answer: X2) -> Pairs<'q, A, H, P, Q, D, F, X2, T> {
        Pairs {
            a: self.a,
            pa: self.pa,
            b: self.b,
            pb: self.pb,
            traversal: self.traversal,
            frame: self.frame,
            answer,
            tally: self.tally,
        }
    }

    /// Reports only pairs that really touch (the narrow phase).
    pub fn exact(self) -> Pairs<'q, A, H, P, Q, D, F, Exact, T> {
        self.answer(Exact)
    }

    /// Counts `Nv`, `Np` and `Nu` into `tally`.
    pub fn counted<T2: Tally>(self, tally: T2) -> Pairs<'q, A, H, P, Q, D, F, X, T2> {
        Pairs {
            a: self.a,
            pa: self.pa,
            b: self.b,
            pb: self.pb,
            traversal: self.traversal,
            frame: self.frame,
            answer: self.answer,
            tally,
        }
    }
}

impl<A, H, P, Q, D, F, X, T> Pairs<'_, A, H, P, Q, D, F, X, T>
where
    A: Hierarchy,
    H: Hierarchy<Bv = A::Bv>,
    P: Primitive,
    Q: Primitive,
    D: DescentRule,
    F: Frame + Place<Q>,
    X: Answer<P, Q>,
    T: Tally,
{
    /// Calls `f(a, b)` for every answer pair; returns how many there were.
    pub fn for_each(self, mut f: impl FnMut(u32, u32)) -> Result<usize, Error> {
        let mut found = 0;
        self.run(|p, q| {
            f(p, q);
            found += 1;
            ControlFlow::Continue(())
        })?;
        Ok(found)
    }

    /// The first answer pair found (early out), or `None` when there is none.
    /// Which pair comes first depends on the traversal; that one exists does not.
    pub fn first(self) -> Result<Option<(u32, u32)>, Error> {
        let mut first = None;
        self.run(|p, q| {
            first = Some((p, q));
            ControlFlow::Break(())
        })?;
        Ok(first)
    }

    /// Only the number of answer pairs.
    pub fn count(self) -> Result<usize, Error> {
        self.for_each(|_, _| {})
    }

    fn run(self, mut sink: impl FnMut(u32, u32) -> ControlFlow<()>) -> Result<(), Error> {
        check_query(self.a, self.pa.len())?;
        check_query(self.b, self.pb.len())?;
        if self.a.is_empty() || self.b.is_empty() {
            return Ok(()); // nothing can overlap an empty tree
        }
        // The explicit stack is fixed; refuse up front (no partial answer)
        // when the trees could outgrow it.
        let binary = A::ARITY == 2 && H::ARITY == 2;
        let capacity = if binary { PAIR_STACK } else { WIDE_PAIR_STACK };
        let needed = pair_stack_bound((A::ARITY, self.a.depth()), (H::ARITY, self.b.depth()));
        let small = binary && needed <= SMALL_PAIR_STACK;
        if needed > capacity {
            return Err(Error::StackOverflow {
                depth: self.a.depth() + self.b.depth(),
                capacity,
            });
        }
        let mut walk = Walk {
            a: self.a,
            b: self.b,
            frame: &self.frame,
            with_boxes: !X::POINTWISE,
            tally: self.tally,
            leaf: PrimitivePairs {
                pa: self.pa,
                pb: self.pb,
                frame: &self.frame,
                answer: self.answer,
                sink: &mut sink,
            },
        };
        match &self.traversal {
            PairTraversal::Recursive(rule) => {
                let (ra, rb) = (self.a.root(), self.b.root());
                let yb = walk.b_bv(rb);
                let _ = walk.recurse(rule, ra, rb, &yb, 0);
                Ok(())
            }
            PairTraversal::Stack(rule) if small => walk
                .stack::<_, { SMALL_PAIR_STACK + SLACK }>(rule)
                .map(drop),
            PairTraversal::Stack(rule) if binary => {
                walk.stack::<_, { PAIR_STACK + SLACK }>(rule).map(drop)
            }
            PairTraversal::Stack(rule) => {
                walk.stack::<_, { WIDE_PAIR_STACK + SLACK }>(rule).map(drop)
            }
            PairTraversal::Simultaneous if small => walk
                .stack::<_, { SMALL_PAIR_STACK + SLACK }>(&Descent::Simultaneous)
                .map(drop),
            PairTraversal::Simultaneous if binary => walk
                .stack::<_, { PAIR_STACK + SLACK }>(&Descent::Simultaneous)
                .map(drop),
            PairTraversal::Simultaneous => walk
                .stack::<_, { WIDE_PAIR_STACK + SLACK }>(&Descent::Simultaneous)
                .map(drop),
            PairTraversal::LeafDirected => walk.leaf_directed().map(drop),
        }
    }
}

/// Calls `f(a, b)` for every pair of primitives, one from each tree, whose
/// bounds overlap; returns the count. Shorthand for
/// `Pairs::new(a, prims_a, b, prims_b).descent(rule).for_each(f)`.
///
/// The root pair and every child pair are tested before they are pushed, so
/// even trees of one or two leaves are pruned correctly.
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
pub fn overlapping_pairs<A, H, P, Q>(
    a: &A,
    prims_a: &[P],
    b: &H,
    prims_b: &[Q],
    rule: Descent,
    f: impl FnMut(u32, u32),
) -> Result<usize, Error>
where
    A: Hierarchy,
    H: Hierarchy<Bv = A::Bv>,
    P: Primitive,
    Q: Primitive + Clone,
{
    Pairs::new(a, prims_a, b, prims_b).descent(rule).for_each(f)
}

/// The leaf-pair step of every traversal. For each run of up to four
/// primitives of A, their bounds go side by side ([`Boxes4`]) once; each
/// primitive of B is placed in A's frame once (not copied at all in the same
/// frame) and tested against the four at once; the answer decides only the
/// pairs whose bounds overlap. A struct with an always-inlined method rather
/// than a closure, so that it is inlined into the traversal loop.
struct PrimitivePairs<'q, P, Q, F, X, S> {
    pa: &'q [P],
    pb: &'q [Q],
    frame: &'q F,
    answer: X,
    sink: S,
}

/// A leaf as the leaf-pair step sees it: its primitive ids and, if the
/// tree keeps them ([`Hierarchy::leaf_bounds`]), their bounds side by side.
#[derive(Clone, Copy)]
pub(super) struct Leaf<'a> {
    pub(super) ids: &'a [u32],
    pub(super) bounds: Option<&'a [Aabb]>,
}

/// Decides every primitive pair of two leaves.
pub(super) trait PairStep {
    /// Every pair of `la` (A's primitives) and `lb` (B's); each pair counts
    /// as one primitive test (`Np`) whether the box prefilter or the answer
    /// settled it, so the counts do not depend on how the test is vectorised.
    fn leaf_pair<T: Tally>(&mut self, la: Leaf<'_>, lb: Leaf<'_>, tally: &mut T) -> Flow;
}

impl<P, Q, F, X, S> PairStep for PrimitivePairs<'_, P, Q, F, X, S>
where
    P: Primitive,
    Q: Primitive,
    F: Frame + Place<Q>,
    X: Answer<P, Q>,
    S: FnMut(u32, u32) -> Flow,
{
    #[inline(always)]
    fn leaf_pair<T: Tally>(&mut self, la: Leaf<'_>, lb: Leaf<'_>, tally: &mut T) -> Flow {
        let (ids_a, ids_b) = (la.ids, lb.ids);
        tally.prim_tests((ids_a.len() * ids_b.len()).min(u32::MAX as usize) as u32);
        // B's kept bounds are in B's frame: a moved B places each primitive.
        // (Holding a moved leaf's placed primitives between leaf pairs saved
        // 0-7% of a moved triangle query, and cost 480 bytes of stack in
        // every pair query on the Cortex-M4, moved or not: not kept.)
        let kept_b = if F::MOVES { None } else { lb.bounds };
        for (r, run) in ids_a.chunks(MAX_CHILDREN).enumerate() {
            let mut four = Boxes4::EMPTY;
            match la.bounds {
                Some(bounds) => {
                    let kept = bounds.iter().skip(r * MAX_CHILDREN);
                    for (k, b) in kept.take(run.len()).enumerate() {
                        four.set(k, b);
                    }
                }
                None => {
                    for (k, &p) in run.iter().enumerate() {
                        four.set(k, &self.pa[p as usize].bounds());
                    }
                }
            }
            let live = (1u32 << run.len()) - 1;
            for (m, &q) in ids_b.iter().enumerate() {
                let given = &self.pb[q as usize];
                let moved;
                let placed = if F::MOVES {
                    moved = self.frame.place(given);
                    &moved
                } else {
                    given
                };
                let bounds = match kept_b.and_then(|b| b.get(m)) {
                    Some(b) => *b,
                    None => placed.bounds(),
                };
                let mut mask = four.overlapping(&bounds) & live;
                while mask != 0 {
                    let p = run[mask.trailing_zeros() as usize];
                    mask &= mask - 1;
                    if self.answer.accept_overlapping(&self.pa[p as usize], placed) {
                        (self.sink)(p, q)?;
                    }
                }
            }
        }
        ControlFlow::Continue(())
    }
}

/// The machinery shared by every traversal: node access across frames,
/// counted tests, and the leaf-pair callback.
pub(super) struct Walk<'q, A, H, F, T, L> {
    pub(super) a: &'q A,
    pub(super) b: &'q H,
    pub(super) frame: &'q F,
    /// Move B's volumes so that they contain their primitives' new boxes
    /// (for box-comparing answers).
    pub(super) with_boxes: bool,
    pub(super) tally: T,
    pub(super) leaf: L,
}

pub(super) type Flow = ControlFlow<()>;

/// Volumes of up to [`MAX_CHILDREN`] children, fetched once per decision.
type ChildVolumes<B> = ([u32; MAX_CHILDREN], [B; MAX_CHILDREN], usize);

impl<A, H, F, T, L> Walk<'_, A, H, F, T, L>
where
    A: Hierarchy,
    H: Hierarchy<Bv = A::Bv>,
    F: Frame,
    T: Tally,
    L: PairStep,
{
    /// B's node volume in A's frame.
    #[inline(always)]
    pub(super) fn b_bv(&mut self, j: u32) -> A::Bv {
        let bv = self.b.bv(j);
        if !F::MOVES {
            return self.frame.bv(&bv);
        }
        self.tally.updates(1);
        if self.with_boxes {
            self.frame.bv_with_boxes(&bv)
        } else {
            self.frame.bv(&bv)
        }
    }

    #[inline(always)]
    pub(super) fn test(&mut self, x: &A::Bv, y: &A::Bv) -> bool {
        self.tally.bv_tests(1);
        x.overlaps(y)
    }

    /// A's children and their volumes.
    #[inline(always)]
    fn a_children(&self, kids: &Kids) -> ChildVolumes<A::Bv> {
        let mut out = ([0; MAX_CHILDREN], [A::Bv::EMPTY; MAX_CHILDREN], 0);
        for &c in kids.of_arity(A::ARITY) {
            out.0[out.2] = c;
            out.1[out.2] = self.a.bv(c);
            out.2 += 1;
        }
        out
    }

    /// B's children and their volumes in A's frame.
    #[inline(always)]
    fn b_children(&mut self, kids: &Kids) -> ChildVolumes<A::Bv> {
        let mut out = ([0; MAX_CHILDREN], [A::Bv::EMPTY; MAX_CHILDREN], 0);
        for &c in kids.of_arity(H::ARITY) {
            out.0[out.2] = c;
            out.1[out.2] = self.b_bv(c);
            out.2 += 1;
        }
        out
    }

    /// Every primitive pair of two leaves: A's node `i` holding `la`, B's
    /// node `j` holding `lb`.
    #[inline(always)]
    fn leaves(&mut self, (i, la): (u32, &[u32]), (j, lb): (u32, &[u32])) -> Flow {
        // One box per id, as the trait promises; anything else reads the
        // primitives rather than drop a pair.
        let la = Leaf {
            ids: la,
            bounds: self.a.leaf_bounds(i).filter(|b| b.len() == la.len()),
        };
        let lb = Leaf {
            ids: lb,
            bounds: self.b.leaf_bounds(j).filter(|b| b.len() == lb.len()),
        };
        self.leaf.leaf_pair(la, lb, &mut self.tally)
    }

    /// Both nodes internal: the rule's choice, and B's children in A's frame
    /// if the rule needed them.
    #[inline(always)]
    fn decide<D: DescentRule>(
        &mut self,
        rule: &D,
        (xa, ka): (&A::Bv, &Kids),
        (yb, kb): (&A::Bv, &Kids),
        depth: u32,
    ) -> (Open, Option<ChildVolumes<A::Bv>>) {
        if !rule.wants_children() {
            let d = Decision {
                a: xa,
                b: yb,
                a_children: None,
                b_children: None,
                depth,
            };
            return (rule.choose(&d), None);
        }
        let ac = self.a_children(ka);
        let bc = self.b_children(kb);
        let d = Decision {
            a: xa,
            b: yb,
            a_children: Some(&ac.1[..ac.2]),
            b_children: Some(&bc.1[..bc.2]),
            depth,
        };
        (rule.choose(&d), Some(bc))
    }

    /// The generic informed depth-first traversal, recursive. `yb` is B's
    /// node `j` already in A's frame.
    pub(super) fn recurse<D: DescentRule>(
        &mut self,
        rule: &D,
        i: u32,
        j: u32,
        yb: &A::Bv,
        depth: u32,
    ) -> Flow {
        let xa = self.a.bv(i);
        if !self.test(&xa, yb) {
            return ControlFlow::Continue(());
        }
        let (a, b) = (self.a, self.b);
        let (a_leaf, b_leaf) = (a.is_leaf(i), b.is_leaf(j));
        let kids = |c: Content<'_>| match c {
            Content::Inner(k) => k,
            Content::Leaf(_) => Kids::two(0, 0),
        };
        let (open, known) = match (a_leaf, b_leaf) {
            (true, true) => {
                return match (a.content(i), b.content(j)) {
                    (Content::Leaf(la), Content::Leaf(lb)) => self.leaves((i, la), (j, lb)),
                    _ => ControlFlow::Continue(()),
                };
            }
            (false, true) => ((Open::A, kids(a.content(i)), None), None),
            (true, false) => ((Open::B, kids(b.content(j)), None), None),
            (false, false) => {
                let (ka, kb) = (kids(a.content(i)), kids(b.content(j)));
                let (open, known) = self.decide(rule, (&xa, &ka), (yb, &kb), depth);
                ((open, ka, Some(kb)), known)
            }
        };
        let (open, first, second) = open;
        let b_kids = |w: &mut Self, kb: &Kids| match known {
            Some(c) => c,
            None => w.b_children(kb),
        };
        match open {
            Open::A => {
                for &c in first.of_arity(A::ARITY) {
                    self.recurse(rule, c, j, yb, depth + 1)?;
                }
                ControlFlow::Continue(())
            }
            Open::B => {
                let kb = second.unwrap_or(first);
                let (ids, vols, n) = b_kids(self, &kb);
                for k in 0..n {
                    self.recurse(rule, i, ids[k], &vols[k], depth + 1)?;
                }
                ControlFlow::Continue(())
            }
            Open::Both => {
                let kb = second.unwrap_or(first);
                let (ids, vols, n) = b_kids(self, &kb);
                for &u in first.of_arity(A::ARITY) {
                    for k in 0..n {
                        self.recurse(rule, u, ids[k], &vols[k], depth + 1)?;
                    }
                }
                ControlFlow::Continue(())
            }
        }
    }

    /// The same traversal with an explicit stack of `N` entries; pairs are
    /// tested before they are pushed. `Ok(Break)` when the sink stopped
    /// early. Not inlined, so only the stack array in use occupies the
    /// caller's stack.
    #[inline(never)]
    fn stack<D: DescentRule, const N: usize>(&mut self, rule: &D) -> Result<Flow, Error> {
        let mut stack = [(0u32, 0u32, 0u32); N];
        self.stack_in(rule, self.a.root(), self.b.root(), &mut stack)
    }

    /// The explicit-stack walk from A's node `ra` against B's node `rb` on
    /// the caller's `stack` (at least [`SLACK`] entries; the last `SLACK`
    /// are spare). One copy for every stack size (the sizes differ in the
    /// array their callers hold, not in code: 2.7 KB of flash on a
    /// Cortex-M4 per size), and a self query walking one sibling pair after
    /// another reuses one array instead of clearing a new one each time.
    #[inline(never)]
    pub(super) fn stack_in<D: DescentRule>(
        &mut self,
        rule: &D,
        ra: u32,
        rb: u32,
        stack: &mut [PairEntry],
    ) -> Result<Flow, Error> {
        // The last `SLACK` entries are spare: they let a
        // step write every child pair unconditionally and keep it by
        // advancing `top` by the test's outcome (no branch on an
        // unpredictable test); the capacity is checked once after the step.
        // Hence an array, not `heapless::Vec` (which pushes behind a test):
        // pushes behind tests took the armadillo query from 4.1-4.3 to
        // 4.9-5.0 ms (the book's traversal chapter has the measurement).
        let capacity = stack.len().saturating_sub(SLACK);
        let mut top = 0;
        let overflow = Error::StackOverflow {
            depth: self.a.depth() + self.b.depth(),
            capacity,
        };
        macro_rules! push {
            ($i:expr, $j:expr, $d:expr) => {{
                if top == capacity {
                    return Err(overflow);
                }
                stack[top] = ($i, $j, $d);
                top += 1;
            }};
        }
        // Pushes the pairs whose bit is set in `mask`, last child first.
        macro_rules! push_masked {
            ($mask:expr, $kids:expr, |$c:ident| $pair:expr) => {{
                let mask = $mask;
                for (k, &$c) in $kids.iter().enumerate().rev() {
                    stack[top] = $pair;
                    top += ((mask >> k) & 1) as usize;
                }
                if top > capacity {
                    return Err(overflow);
                }
            }};
        }
        let (a, b) = (self.a, self.b);
        let (xa, yb) = (a.bv(ra), self.b_bv(rb));
        if self.test(&xa, &yb) {
            push!(ra, rb, 0);
        }
        let none = Kids::two(0, 0);
        // B's node last moved for an A-side step, with its moved volume.
        let mut last_moved: Option<(u32, A::Bv)> = None;
        while top > 0 {
            top -= 1;
            let (i, j, depth) = stack[top];
            // Leaf tests first: cheap, and most pops are not leaf pairs.
            let (a_leaf, b_leaf) = (a.is_leaf(i), b.is_leaf(j));
            if a_leaf && b_leaf {
                if let (Content::Leaf(la), Content::Leaf(lb)) = (a.content(i), b.content(j)) {
                    if self.leaves((i, la), (j, lb)).is_break() {
                        return Ok(ControlFlow::Break(()));
                    }
                }
                continue;
            }
            let kids = |c: Content<'_>| match c {
                Content::Inner(k) => k,
                Content::Leaf(_) => none,
            };
            let ka = &if a_leaf { none } else { kids(a.content(i)) };
            let kb = &if b_leaf { none } else { kids(b.content(j)) };
            // B's node in A's frame, when the step needs it.
            let mut yb = None;
            let open = match (a_leaf, b_leaf) {
                (false, true) => Open::A,
                (true, false) => Open::B,
                _ if rule.wants_children() => {
                    // The informed rules see the children's volumes; fetch
                    // them once and use them for the pushes too.
                    let y = self.b_bv(j);
                    let x = a.bv(i);
                    let (open, known) = self.decide(rule, (&x, ka), (&y, kb), depth);
                    let (ids, vols, n) = known.unwrap_or(([0; MAX_CHILDREN], [y; MAX_CHILDREN], 0));
                    match open {
                        Open::A => {
                            for &c in ka.of_arity(A::ARITY).iter().rev() {
                                let xc = a.bv(c);
                                if self.test(&xc, &y) {
                                    push!(c, j, depth + 1);
                                }
                            }
                        }
                        Open::B => {
                            for k in (0..n).rev() {
                                if self.test(&x, &vols[k]) {
                                    push!(i, ids[k], depth + 1);
                                }
                            }
                        }
                        Open::Both => {
                            for &u in ka.of_arity(A::ARITY).iter().rev() {
                                let xu = a.bv(u);
                                for k in (0..n).rev() {
                                    if self.test(&xu, &vols[k]) {
                                        push!(u, ids[k], depth + 1);
                                    }
                                }
                            }
                        }
                    }
                    continue;
                }
                _ => match rule.by_depth(depth) {
                    Some(open) => open,
                    None => {
                        let y = self.b_bv(j);
                        let x = a.bv(i);
                        yb = Some(y);
                        self.decide(rule, (&x, ka), (&y, kb), depth).0
                    }
                },
            };
            match open {
                Open::A => {
                    let y = match yb {
                        Some(y) => y,
                        // A moved B's node stays put while A opens below
                        // it, so the same node comes back pop after pop:
                        // move it once.
                        None if F::MOVES => match last_moved {
                            Some((k, y)) if k == j => y,
                            _ => {
                                let y = self.b_bv(j);
                                last_moved = Some((j, y));
                                y
                            }
                        },
                        None => self.b_bv(j),
                    };
                    let kids = ka.of_arity(A::ARITY);
                    self.tally.bv_tests(kids.len() as u32);
                    push_masked!(a.children_overlapping(ka, &y), kids, |c| (c, j, depth + 1));
                }
                Open::B if !F::MOVES => {
                    let x = a.bv(i);
                    let kids = kb.of_arity(H::ARITY);
                    self.tally.bv_tests(kids.len() as u32);
                    push_masked!(b.children_overlapping(kb, &x), kids, |c| (i, c, depth + 1));
                }
                Open::B => {
                    let x = a.bv(i);
                    let (ids, vols, n) = self.b_children(kb);
                    self.tally.bv_tests(n as u32);
                    let mut mask = 0;
                    for (k, v) in vols[..n].iter().enumerate() {
                        mask |= (x.overlaps(v) as u32) << k;
                    }
                    push_masked!(mask, &ids[..n], |v| (i, v, depth + 1));
                }
                Open::Both if F::MOVES || b.children_boxes(kb).is_none() => {
                    // B's children fetched (and moved) once per step, not
                    // once per child of A.
                    let (ids, vols, n) = self.b_children(kb);
                    let kids = &ids[..n];
                    for &u in ka.of_arity(A::ARITY).iter().rev() {
                        let xu = a.bv(u);
                        self.tally.bv_tests(n as u32);
                        let mut mask = 0;
                        for (k, v) in vols[..n].iter().enumerate() {
                            mask |= (xu.overlaps(v) as u32) << k;
                        }
                        push_masked!(mask, kids, |v| (u, v, depth + 1));
                    }
                }
                Open::Both => {
                    let kids = kb.of_arity(H::ARITY);
                    for &u in ka.of_arity(A::ARITY).iter().rev() {
                        let xu = a.bv(u);
                        self.tally.bv_tests(kids.len() as u32);
                        push_masked!(b.children_overlapping(kb, &xu), kids, |v| (u, v, depth + 1));
                    }
                }
            }
        }
        Ok(ControlFlow::Continue(()))
    }

    /// Leaf-directed: depth-first over A pruned by B's root; at each leaf of
    /// A, a single-tree descent of B with that leaf's volume.
    fn leaf_directed(&mut self) -> Result<Flow, Error> {
        self.leaf_directed_from(self.a.root(), self.b.root())
    }

    /// [`leaf_directed`](Self::leaf_directed) over A's subtree `ra` and
    /// B's subtree `sub_b`.
    pub(super) fn leaf_directed_from(&mut self, ra: u32, sub_b: u32) -> Result<Flow, Error> {
        let (a, b) = (self.a, self.b);
        let depth = a.depth().max(b.depth());
        let rb = self.b_bv(sub_b);
        let xa = a.bv(ra);
        if !self.test(&xa, &rb) {
            return Ok(ControlFlow::Continue(()));
        }
        let mut sa = Stack::<u32, DFS_STACK>::with(ra, depth);
        let mut sb = Stack::<u32, DFS_STACK>::with(sub_b, depth);
        while let Some(i) = sa.pop() {
            let la = match a.content(i) {
                Content::Inner(kids) => {
                    for &c in kids.as_slice().iter().rev() {
                        let cb = a.bv(c);
                        if self.test(&cb, &rb) {
                            sa.push(c)?;
                        }
                    }
                    continue;
                }
                Content::Leaf(la) => la,
            };
            // A leaf of A that overlaps B's root: descend B with its volume.
            let xb = a.bv(i);
            sb.reset(sub_b);
            while let Some(j) = sb.pop() {
                match b.content(j) {
                    Content::Leaf(lb) => {
                        if self.leaves((i, la), (j, lb)).is_break() {
                            return Ok(ControlFlow::Break(()));
                        }
                    }
                    Content::Inner(kids) => {
                        for &c in kids.as_slice().iter().rev() {
                            let cb = self.b_bv(c);
                            if self.test(&xb, &cb) {
                                sb.push(c)?;
                            }
                        }
                    }
                }
            }
        }
        Ok(ControlFlow::Continue(()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::query::brute_force;
    use crate::tree::Node;
    use crate::{TopDown, Triangle};
    use glam::{Quat, Vec3};

    const N: usize = 48;

    fn triangles(seed: u64) -> [Triangle; N] {
        let mut next = crate::test_floats(seed);
        core::array::from_fn(|_| {
            let o = Vec3::new(next(), next(), next()) * 1.5;
            let mut corner = || o + Vec3::new(next(), next(), next()) * 0.8;
            Triangle::new(corner(), corner(), corner())
        })
    }

    fn sorted(pairs: &mut [(u32, u32)]) -> &[(u32, u32)] {
        pairs.sort_unstable();
        pairs
    }

    /// A moved B's leaves of every size (up to and past four primitives),
    /// under four traversals and both answers, match brute force over the
    /// placed primitives.
    #[test]
    fn moved_leaves_of_every_size_answer_as_placed() {
        let (a, b) = (triangles(3), triangles(11));
        let motion = Rigid::new(
            Quat::from_axis_angle(Vec3::new(1.0, 2.0, 0.5).normalize(), 0.4),
            Vec3::new(0.3, -0.2, 0.1),
        )
        .unwrap();
        let mut want_exact = [(0u32, 0u32); N * N];
        let mut want_bounds = [(0u32, 0u32); N * N];
        let (mut we, mut wb) = (0, 0);
        brute_force::pairs_placed(&a, &b, &motion, Exact, |i, j| {
            want_exact[we] = (i, j);
            we += 1;
        });
        brute_force::pairs_placed(&a, &b, &motion, Bounds, |i, j| {
            want_bounds[wb] = (i, j);
            wb += 1;
        });
        assert!(
            we > 10 && wb > we,
            "a scene with work: {we} exact, {wb} bounds"
        );
        let want_exact = sorted(&mut want_exact[..we]);
        let want_bounds = sorted(&mut want_bounds[..wb]);
        for leaf in [1, 3, 4, MAX_CHILDREN as u32 + 2] {
            let build = TopDown::default().with_max_leaf_size(leaf);
            let (mut na, mut nb) = ([Node::<Aabb>::EMPTY; 2 * N], [Node::<Aabb>::EMPTY; 2 * N]);
            let (mut ia, mut ib) = ([0u32; N], [0u32; N]);
            let ta = build.build(&a, &mut na, &mut ia).unwrap();
            let tb = build.build(&b, &mut nb, &mut ib).unwrap();
            for traversal in [
                PairTraversal::Stack(Descent::Simultaneous),
                PairTraversal::Stack(Descent::Larger),
                PairTraversal::Recursive(Descent::Larger),
                PairTraversal::LeafDirected,
            ] {
                let pairs = || {
                    Pairs::new(&ta, &a, &tb, &b)
                        .traversal(traversal)
                        .in_frame(motion)
                };
                let mut got = [(0u32, 0u32); N * N];
                let mut g = 0;
                pairs()
                    .exact()
                    .for_each(|i, j| {
                        got[g] = (i, j);
                        g += 1;
                    })
                    .unwrap();
                assert_eq!(
                    sorted(&mut got[..g]),
                    want_exact,
                    "exact, leaves of {leaf}, {traversal:?}"
                );
                g = 0;
                pairs()
                    .for_each(|i, j| {
                        got[g] = (i, j);
                        g += 1;
                    })
                    .unwrap();
                assert_eq!(
                    sorted(&mut got[..g]),
                    want_bounds,
                    "bounds, leaves of {leaf}, {traversal:?}"
                );
            }
        }
    }
}
