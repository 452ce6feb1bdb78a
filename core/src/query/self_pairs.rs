//! One tree against itself: which pairs of its own primitives overlap?
//!
//! Lecture: *collision between two hierarchies*, with both hierarchies the
//! same. Self-collision (cloth folding onto itself, a deforming body, the
//! broad phase over the objects of a scene) asks for every pair `i < j` of
//! one set. Running the two-tree query on `(tree, tree)` finds each pair
//! twice, `(i, j)` and `(j, i)`, plus every primitive with itself, and
//! throws half its work away. The self query finds each pair once:
//!
//! - two primitives in the same leaf are paired inside that leaf;
//! - two primitives in different leaves meet at the lowest node above both,
//!   in two different children; so for every inner node, each pair of its
//!   children is walked *once* with the two-tree traversal (any
//!   [`PairTraversal`] and descent rule), and nothing else is.
//!
//! In a mesh, neighbouring triangles share a vertex and so always touch;
//! a self query skips them by default ([`SkipAdjacent`]), through a rule the
//! caller can replace ([`SelfPairs::keep_adjacent`], [`SelfPairs::skip`]).

use super::pair::{Flow, Leaf, PairEntry, PairStep, Walk, SLACK};
use super::stack::Stack;
use super::{pair_stack_bound, Answer, Bounds, Descent, DescentRule, Exact, PairTraversal, Same};
use super::{Tally, PAIR_STACK, SMALL_PAIR_STACK, WIDE_PAIR_STACK};
use crate::bv::Aabb;
use crate::primitive::{Primitive, Triangle};
use crate::tree::hierarchy::{check_query, BINARY_DFS_STACK, DFS_STACK};
use crate::tree::{Boxes4, Content, Hierarchy, MAX_CHILDREN};
use crate::Error;
use core::ops::ControlFlow;
use glam::Vec3;

/// Whether two primitives of one set are neighbours that touch by
/// construction, so a self query should not report them: triangles of a
/// mesh that share a corner. Corners are compared by position (bit-equal
/// after `-0.0 == 0.0`), which for a welded mesh is the same as sharing a
/// vertex index. Primitives without corners (points, boxes, spheres) have
/// no neighbours.
pub trait Adjacent {
    /// `true` when `self` and `other` are neighbours.
    fn adjacent(&self, other: &Self) -> bool;
}

fn share_corner(a: &[Vec3; 3], b: &[Vec3; 3]) -> bool {
    a.iter().any(|p| b.contains(p))
}

impl Adjacent for Triangle {
    #[inline]
    fn adjacent(&self, other: &Self) -> bool {
        share_corner(&self.v, &other.v)
    }
}

impl Adjacent for [Vec3; 3] {
    #[inline]
    fn adjacent(&self, other: &Self) -> bool {
        share_corner(self, other)
    }
}

macro_rules! no_neighbours {
    ($($t:ty),*) => {$(
        impl Adjacent for $t {
            #[inline(always)]
            fn adjacent(&self, _: &Self) -> bool {
                false
            }
        }
    )*};
}
no_neighbours!(Vec3, Aabb);
#[cfg(feature = "sphere")]
no_neighbours!(crate::bv::Sphere);

impl<P: Adjacent> Adjacent for &P {
    #[inline(always)]
    fn adjacent(&self, other: &Self) -> bool {
        (**self).adjacent(*other)
    }
}

/// Which pairs a self query leaves out before deciding them (ids `i`, `j`
/// of the primitives `p`, `q`). Runs only on pairs whose bounds overlap,
/// before the [`Answer`]: an exact test on neighbours, which always touch,
/// would be the slowest test of all and wasted.
pub trait SelfFilter<P> {
    /// `true` to leave the pair out.
    fn skip(&mut self, i: u32, j: u32, p: &P, q: &P) -> bool;
}

/// Skips [`Adjacent`] pairs (the default of [`SelfPairs`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SkipAdjacent;

impl<P: Adjacent> SelfFilter<P> for SkipAdjacent {
    #[inline(always)]
    fn skip(&mut self, _: u32, _: u32, p: &P, q: &P) -> bool {
        p.adjacent(q)
    }
}

/// Skips nothing ([`SelfPairs::keep_adjacent`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct KeepAll;

impl<P> SelfFilter<P> for KeepAll {
    #[inline(always)]
    fn skip(&mut self, _: u32, _: u32, _: &P, _: &P) -> bool {
        false
    }
}

/// A rule on ids ([`SelfPairs::skip`]): for instance "shares a vertex
/// index" with the mesh's index triples.
#[derive(Clone, Copy, Debug)]
pub struct SkipIds<G>(pub G);

impl<P, G: FnMut(u32, u32) -> bool> SelfFilter<P> for SkipIds<G> {
    #[inline(always)]
    fn skip(&mut self, i: u32, j: u32, _: &P, _: &P) -> bool {
        (self.0)(i, j)
    }
}

/// The pairs `i < j` of one tree's primitives, each once, configured step
/// by step like [`Pairs`](super::Pairs), then run in one of three result
/// modes. The answer equals [`brute_force::self_pairs`](super::brute_force::self_pairs).
///
/// ```
/// use bvhkit::query::{SelfPairs, brute_force};
/// use bvhkit::{Aabb, Node, TopDown, Triangle};
/// use glam::Vec3;
/// // A strip of triangles, each sharing corners with the next, and one
/// // triangle folded back across the strip.
/// let mut tris: Vec<Triangle> = (0..8).map(|i| {
///     let x = i as f32;
///     Triangle::new(Vec3::new(x, 0.0, 0.0), Vec3::new(x + 1.0, 0.0, 0.0), Vec3::new(x, 1.0, 0.0))
/// }).collect();
/// tris.push(Triangle::new(Vec3::new(2.2, 0.2, -1.0), Vec3::new(2.2, 0.2, 1.0), Vec3::new(5.2, 0.3, 0.0)));
/// let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(tris.len())];
/// let mut idx = vec![0; tris.len()];
/// let tree = TopDown::default().with_max_leaf_size(2).build(&tris, &mut nodes, &mut idx)?;
///
/// // Touching pairs, neighbours (shared corners) skipped: the fold only.
/// let mut hits = Vec::new();
/// SelfPairs::new(&tree, &tris).exact().for_each(|i, j| hits.push((i, j)))?;
/// hits.sort();
/// assert!(hits.iter().all(|&(i, j)| i < j && j == 8));
/// assert!(!hits.is_empty());
/// // Every pair whose boxes overlap, neighbours included, once each.
/// let all = SelfPairs::new(&tree, &tris).keep_adjacent().count()?;
/// assert_eq!(all, brute_force::self_pairs(&tris, |_, _| {}));
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Debug)]
pub struct SelfPairs<'q, H, P, D = Descent, X = Bounds, S = SkipAdjacent, T = ()> {
    tree: &'q H,
    prims: &'q [P],
    traversal: PairTraversal<D>,
    answer: X,
    filter: S,
    tally: T,
}

impl<'q, H: Hierarchy, P> SelfPairs<'q, H, P> {
    /// `tree` over `prims` against itself: stack traversal, simultaneous
    /// rule, bounds answer, neighbours skipped, no counting.
    pub fn new(tree: &'q H, prims: &'q [P]) -> Self {
        SelfPairs {
            tree,
            prims,
            traversal: PairTraversal::default(),
            answer: Bounds,
            filter: SkipAdjacent,
            tally: (),
        }
    }
}

impl<'q, H, P, D, X, S, T> SelfPairs<'q, H, P, D, X, S, T> {
    /// Chooses how each pair of sibling subtrees is walked (and the rule).
    pub fn traversal<D2>(self, traversal: PairTraversal<D2>) -> SelfPairs<'q, H, P, D2, X, S, T> {
        SelfPairs {
            tree: self.tree,
            prims: self.prims,
            traversal,
            answer: self.answer,
            filter: self.filter,
            tally: self.tally,
        }
    }

    /// Shorthand for `traversal(PairTraversal::Stack(rule))`.
    pub fn descent<D2>(self, rule: D2) -> SelfPairs<'q, H, P, D2, X, S, T> {
        self.traversal(PairTraversal::Stack(rule))
    }

    /// Decides primitive pairs with `answer`.
    pub fn answer<X2>(self, answer: X2) -> SelfPairs<'q, H, P, D, X2, S, T> {
        SelfPairs {
            tree: self.tree,
            prims: self.prims,
            traversal: self.traversal,
            answer,
            filter: self.filter,
            tally: self.tally,
        }
    }

    /// Reports only pairs that really touch (the narrow phase).
    pub fn exact(self) -> SelfPairs<'q, H, P, D, Exact, S, T> {
        self.answer(Exact)
    }

    /// Leaves out the pairs any [`SelfFilter`] names, instead of neighbours.
    pub fn filter<S2>(self, filter: S2) -> SelfPairs<'q, H, P, D, X, S2, T> {
        SelfPairs {
            tree: self.tree,
            prims: self.prims,
            traversal: self.traversal,
            answer: self.answer,
            filter,
            tally: self.tally,
        }
    }

    /// Reports neighbours too: every pair is decided by the answer alone.
    pub fn keep_adjacent(self) -> SelfPairs<'q, H, P, D, X, KeepAll, T> {
        self.filter(KeepAll)
    }

    /// Leaves out the pairs for which `skip(i, j)` is `true` instead of
    /// neighbours (for instance triangles sharing a vertex *index*).
    pub fn skip<G: FnMut(u32, u32) -> bool>(
        self,
        skip: G,
    ) -> SelfPairs<'q, H, P, D, X, SkipIds<G>, T> {
        self.filter(SkipIds(skip))
    }

    /// Counts `Nv` and `Np` into `tally`.
    pub fn counted<T2: Tally>(self, tally: T2) -> SelfPairs<'q, H, P, D, X, S, T2> {
        SelfPairs {
            tree: self.tree,
            prims: self.prims,
            traversal: self.traversal,
            answer: self.answer,
            filter: self.filter,
            tally,
        }
    }
}

/// The leaf-pair step of a self query: as the two-tree step (four of A's
/// bounds side by side against each of B's), plus the filter, and each pair
/// reported as `(smaller id, larger id)`.
struct SelfLeafPairs<'q, P, X, S, K> {
    prims: &'q [P],
    answer: X,
    filter: S,
    sink: K,
}

impl<P, X, S, K> SelfLeafPairs<'_, P, X, S, K>
where
    P: Primitive,
    X: Answer<P, P>,
    S: SelfFilter<P>,
    K: FnMut(u32, u32) -> Flow,
{
    /// Decides `p` and `q`, whose bounds overlap.
    #[inline(always)]
    fn decide(&mut self, p: u32, q: u32) -> Flow {
        let (i, j) = if p < q { (p, q) } else { (q, p) };
        if i == j {
            return ControlFlow::Continue(()); // one id named twice: not a pair
        }
        let (pi, pj) = (&self.prims[i as usize], &self.prims[j as usize]);
        if self.filter.skip(i, j, pi, pj) || !self.answer.accept_overlapping(pi, pj) {
            return ControlFlow::Continue(());
        }
        (self.sink)(i, j)
    }

    /// Every pair inside one leaf.
    fn within<T: Tally>(&mut self, leaf: Leaf<'_>, tally: &mut T) -> Flow {
        let ids = leaf.ids;
        let k = ids.len();
        tally.prim_tests((k * k.saturating_sub(1) / 2).min(u32::MAX as usize) as u32);
        let bound = |m: usize| match leaf.bounds {
            Some(b) => b[m],
            None => self.prims[ids[m] as usize].bounds(),
        };
        for m in 0..k {
            let bm = bound(m);
            for l in m + 1..k {
                if bm.overlaps(&bound(l)) {
                    self.decide(ids[m], ids[l])?;
                }
            }
        }
        ControlFlow::Continue(())
    }
}

impl<P, X, S, K> PairStep for SelfLeafPairs<'_, P, X, S, K>
where
    P: Primitive,
    X: Answer<P, P>,
    S: SelfFilter<P>,
    K: FnMut(u32, u32) -> Flow,
{
    #[inline(always)]
    fn leaf_pair<T: Tally>(&mut self, la: Leaf<'_>, lb: Leaf<'_>, tally: &mut T) -> Flow {
        let (ids_a, ids_b) = (la.ids, lb.ids);
        tally.prim_tests((ids_a.len() * ids_b.len()).min(u32::MAX as usize) as u32);
        for (r, run) in ids_a.chunks(MAX_CHILDREN).enumerate() {
            let mut four = Boxes4::EMPTY;
            for (k, &p) in run.iter().enumerate() {
                let b = match la.bounds {
                    Some(bounds) => bounds[r * MAX_CHILDREN + k],
                    None => self.prims[p as usize].bounds(),
                };
                four.set(k, &b);
            }
            let live = (1u32 << run.len()) - 1;
            for (m, &q) in ids_b.iter().enumerate() {
                let bq = match lb.bounds {
                    Some(bounds) => bounds[m],
                    None => self.prims[q as usize].bounds(),
                };
                let mut mask = four.overlapping(&bq) & live;
                while mask != 0 {
                    let p = run[mask.trailing_zeros() as usize];
                    mask &= mask - 1;
                    self.decide(p, q)?;
                }
            }
        }
        ControlFlow::Continue(())
    }
}

impl<H, P, D, X, S, T> SelfPairs<'_, H, P, D, X, S, T>
where
    H: Hierarchy,
    P: Primitive,
    D: DescentRule,
    X: Answer<P, P>,
    S: SelfFilter<P>,
    T: Tally,
{
    /// Calls `f(i, j)`, `i < j`, for every answer pair; returns how many.
    pub fn for_each(self, mut f: impl FnMut(u32, u32)) -> Result<usize, Error> {
        let mut found = 0;
        self.run(|i, j| {
            f(i, j);
            found += 1;
            ControlFlow::Continue(())
        })?;
        Ok(found)
    }

    /// The first answer pair found (early out), or `None` when there is none.
    pub fn first(self) -> Result<Option<(u32, u32)>, Error> {
        let mut first = None;
        self.run(|i, j| {
            first = Some((i, j));
            ControlFlow::Break(())
        })?;
        Ok(first)
    }

    /// Only the number of answer pairs.
    pub fn count(self) -> Result<usize, Error> {
        self.for_each(|_, _| {})
    }

    fn run(self, sink: impl FnMut(u32, u32) -> Flow) -> Result<(), Error> {
        let tree = self.tree;
        check_query(tree, self.prims.len())?;
        if tree.is_empty() {
            return Ok(());
        }
        let binary = H::ARITY == 2;
        let capacity = if binary { PAIR_STACK } else { WIDE_PAIR_STACK };
        let needed = pair_stack_bound((H::ARITY, tree.depth()), (H::ARITY, tree.depth()));
        if needed > capacity {
            return Err(Error::StackOverflow {
                depth: 2 * tree.depth(),
                capacity,
            });
        }
        let small = binary && needed <= SMALL_PAIR_STACK;
        let mut walk = Walk {
            a: tree,
            b: tree,
            frame: &Same,
            with_boxes: !X::POINTWISE,
            tally: self.tally,
            leaf: SelfLeafPairs {
                prims: self.prims,
                answer: self.answer,
                filter: self.filter,
                sink,
            },
        };
        // The node walk's stack holds `(arity - 1) * depth + 1` entries:
        // a binary tree's (65 entries) is a third of a 4-wide tree's; the
        // pair walk's, the smallest that holds the tree.
        let traversal = &self.traversal;
        if !binary {
            nodes::<_, _, _, _, _, _, _, DFS_STACK, { WIDE_PAIR_STACK + SLACK }>(
                &mut walk, traversal,
            )
        } else if small {
            nodes::<_, _, _, _, _, _, _, BINARY_DFS_STACK, { SMALL_PAIR_STACK + SLACK }>(
                &mut walk, traversal,
            )
        } else {
            nodes::<_, _, _, _, _, _, _, BINARY_DFS_STACK, { PAIR_STACK + SLACK }>(
                &mut walk, traversal,
            )
        }
    }
}

/// Every node of the tree once, depth first: a leaf's own pairs, and each
/// pair of an inner node's children walked against each other on one pair
/// stack of `M` entries, cleared once for the whole query, not once per
/// sibling pair. Out of line, one small copy per pair of stack sizes, so
/// that only the arrays in use are on the caller's stack (inlined together,
/// a binary tree's small and large pair stacks took 4.3 KiB on a
/// Cortex-M4); the walk itself is one copy for every size.
#[inline(never)]
fn nodes<H, T, P, X, S, K, D, const N: usize, const M: usize>(
    walk: &mut Walk<'_, H, H, Same, T, SelfLeafPairs<'_, P, X, S, K>>,
    traversal: &PairTraversal<D>,
) -> Result<(), Error>
where
    H: Hierarchy,
    T: Tally,
    P: Primitive,
    X: Answer<P, P>,
    S: SelfFilter<P>,
    K: FnMut(u32, u32) -> Flow,
    D: DescentRule,
{
    let tree = walk.a;
    let mut nodes = Stack::<u32, N>::with(tree.root(), tree.depth());
    let stack = &mut [(0u32, 0u32, 0u32); M];
    while let Some(n) = nodes.pop() {
        match tree.content(n) {
            Content::Leaf(ids) => {
                let leaf = Leaf {
                    ids,
                    bounds: tree.leaf_bounds(n).filter(|b| b.len() == ids.len()),
                };
                if walk.leaf.within(leaf, &mut walk.tally).is_break() {
                    return Ok(());
                }
            }
            Content::Inner(kids) => {
                let kids = kids.of_arity(H::ARITY);
                for (k, &u) in kids.iter().enumerate() {
                    for &v in &kids[k + 1..] {
                        if cross(walk, traversal, u, v, stack)?.is_break() {
                            return Ok(());
                        }
                    }
                }
                for &c in kids.iter().rev() {
                    nodes.push(c)?;
                }
            }
        }
    }
    Ok(())
}

/// Walks sibling subtrees `u` and `v` against each other with `traversal`.
fn cross<H, T, L, D>(
    walk: &mut Walk<'_, H, H, Same, T, L>,
    traversal: &PairTraversal<D>,
    u: u32,
    v: u32,
    stack: &mut [PairEntry],
) -> Result<Flow, Error>
where
    H: Hierarchy,
    T: Tally,
    L: PairStep,
    D: DescentRule,
{
    match traversal {
        PairTraversal::Recursive(rule) => {
            let yv = walk.b_bv(v);
            Ok(walk.recurse(rule, u, v, &yv, 0))
        }
        PairTraversal::Stack(rule) => walk.stack_in(rule, u, v, stack),
        PairTraversal::Simultaneous => walk.stack_in(&Descent::Simultaneous, u, v, stack),
        PairTraversal::LeafDirected => walk.leaf_directed_from(u, v),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::query::brute_force;
    use crate::tree::Node;
    use crate::TopDown;

    /// Boxes on a jittered grid, some overlapping their neighbours.
    fn boxes(n: usize) -> [Aabb; 64] {
        let mut out = [Aabb::EMPTY; 64];
        for (i, b) in out.iter_mut().enumerate().take(n) {
            let o = Vec3::new((i % 4) as f32, ((i / 4) % 4) as f32, (i / 16) as f32);
            let grow = 0.3 + 0.5 * ((i * 7 % 5) as f32 / 5.0);
            *b = Aabb::new(o, o + Vec3::splat(0.5 + grow));
        }
        out
    }

    #[test]
    fn each_overlapping_pair_once_in_every_traversal() {
        for (n, leaf) in [(64, 1), (64, 3), (37, 4), (2, 4), (1, 1)] {
            let prims = &boxes(n)[..n];
            let mut nodes = [Node::<Aabb>::EMPTY; 127];
            let mut idx = [0u32; 64];
            let tree = TopDown::default()
                .with_max_leaf_size(leaf)
                .build(prims, &mut nodes, &mut idx[..n])
                .unwrap();
            let mut want = [(0u32, 0u32); 2016];
            let mut w = 0;
            brute_force::self_pairs(prims, |i, j| {
                want[w] = (i, j);
                w += 1;
            });
            for traversal in [
                PairTraversal::Stack(Descent::Simultaneous),
                PairTraversal::Stack(Descent::Larger),
                PairTraversal::Recursive(Descent::Larger),
                PairTraversal::Simultaneous,
                PairTraversal::LeafDirected,
            ] {
                let mut got = [(0u32, 0u32); 2016];
                let mut g = 0;
                let count = SelfPairs::new(&tree, prims)
                    .traversal(traversal)
                    .for_each(|i, j| {
                        got[g] = (i, j);
                        g += 1;
                    })
                    .unwrap();
                assert_eq!(count, w, "{n} boxes, leaves of {leaf}, {traversal:?}");
                got[..g].sort_unstable();
                assert_eq!(
                    got[..g],
                    want[..w],
                    "{n} boxes, leaves of {leaf}, {traversal:?}"
                );
            }
        }
    }

    /// A tree too deep for the small pair stack (the boxes double in size,
    /// so the binned SAH peels a few off at a time) walks on the large one,
    /// one array for every sibling pair, and still finds every pair.
    #[test]
    fn a_deep_tree_walks_on_the_large_stack_and_finds_every_pair() {
        const N: usize = 100;
        let mut prims = [Aabb::EMPTY; N];
        let mut x = 1.0f32;
        for b in prims.iter_mut() {
            // Each box reaches a little into the next one.
            *b = Aabb::new(Vec3::new(x, 0.0, 0.0), Vec3::new(2.1 * x, 1.0, 1.0));
            x *= 2.0;
        }
        let mut nodes = [Node::<Aabb>::EMPTY; 2 * N - 1];
        let mut idx = [0u32; N];
        let tree = TopDown::sah()
            .with_max_leaf_size(1)
            .build(&prims, &mut nodes, &mut idx)
            .unwrap();
        let depth = tree.depth();
        assert!(
            pair_stack_bound((2, depth), (2, depth)) > SMALL_PAIR_STACK,
            "depth {depth} fits the small stack: the test misses the large one"
        );
        for traversal in [
            PairTraversal::Stack(Descent::Larger),
            PairTraversal::Simultaneous,
            PairTraversal::Recursive(Descent::Larger),
            PairTraversal::LeafDirected,
        ] {
            let mut got = [(0u32, 0u32); N];
            let mut g = 0;
            SelfPairs::new(&tree, &prims)
                .traversal(traversal)
                .for_each(|i, j| {
                    got[g] = (i.min(j), i.max(j));
                    g += 1;
                })
                .unwrap();
            got[..g].sort_unstable();
            let want: [(u32, u32); N - 1] = core::array::from_fn(|i| (i as u32, i as u32 + 1));
            assert_eq!(&got[..g], &want[..], "{traversal:?}");
        }
    }

    #[test]
    fn neighbours_are_skipped_by_default_and_kept_on_request() {
        // Two triangles sharing an edge (touching) and one crossing both.
        let tris = [
            Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y),
            Triangle::new(Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y),
            Triangle::new(
                Vec3::new(0.5, 0.4, -1.0),
                Vec3::new(0.5, 0.4, 1.0),
                Vec3::new(0.6, 0.6, 0.0),
            ),
        ];
        let mut nodes = [Node::<Aabb>::EMPTY; 5];
        let mut idx = [0u32; 3];
        let tree = TopDown::default()
            .with_max_leaf_size(1)
            .build(&tris, &mut nodes, &mut idx)
            .unwrap();
        type Run<'a> = &'a mut dyn FnMut(&mut dyn FnMut(u32, u32));
        let collect = |q: Run<'_>| {
            let mut v = [(9, 9); 3];
            let mut k = 0;
            q(&mut |i, j| {
                v[k] = (i, j);
                k += 1;
            });
            v[..k].sort_unstable();
            (v, k)
        };
        let (v, k) = collect(&mut |f| {
            SelfPairs::new(&tree, &tris).exact().for_each(f).unwrap();
        });
        assert_eq!(&v[..k], &[(0, 2), (1, 2)]);
        let (v, k) = collect(&mut |f| {
            SelfPairs::new(&tree, &tris)
                .keep_adjacent()
                .exact()
                .for_each(f)
                .unwrap();
        });
        assert_eq!(&v[..k], &[(0, 1), (0, 2), (1, 2)]);
        let (v, k) = collect(&mut |f| {
            SelfPairs::new(&tree, &tris)
                .skip(|i, j| i == 0 && j == 2)
                .exact()
                .for_each(f)
                .unwrap();
        });
        assert_eq!(&v[..k], &[(0, 1), (1, 2)]);
        assert!(SelfPairs::new(&tree, &tris)
            .exact()
            .first()
            .unwrap()
            .is_some());
    }
}
