//! Insertion construction: a tree that grows one object at a time.
//!
//! Lecture: *insertion construction* (Goldsmith and Salmon). An object is
//! inserted next to the node (its *sibling*) where it costs least: the cost
//! of a sibling is the surface area of the new parent that joins them, plus
//! the growth of every ancestor's area caused by the object. Two searches:
//!
//! - [`SiblingSearch::Descent`]: one walk from the root, always into the
//!   cheaper child, stopping when staying is cheaper (`O(log n)` per insert);
//! - [`SiblingSearch::BranchAndBound`]: the best sibling of the whole tree,
//!   exploring a subtree only while its lower bound beats the best found.
//!
//! The same tree supports removal and updates of moving objects with fat
//! (enlarged) leaf volumes: an object that moves but stays inside its fat
//! volume needs no work; one that leaves it is reinserted. Optional rotations
//! (exchanging a node with a grandchild when heights differ by more than one)
//! keep the tree shallow even for sorted input.
//!
//! Storage is the caller's ([`DynNode`] array of `2n - 1` entries for `n`
//! objects); [`DynamicTree::to_bvh`] writes the tree in the layout every query
//! of this crate runs on.

use super::enclose;
use super::{BuildReport, Collapse};
use crate::bv::{xyz_all, xyz_any, Aabb, BoundingVolume};
use crate::primitive::{validate, Primitive};
use crate::tree::{Bvh, Node, MAX_DEPTH};
use crate::Error;
use glam::{Vec3, Vec3A};

/// No node.
pub const NULL: u32 = u32::MAX;

/// One node of a [`DynamicTree`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DynNode<B> {
    /// Volume (for a leaf: the fat volume of its object).
    pub bv: B,
    /// Parent, or [`NULL`] for the root. In the free list: the next free node.
    pub parent: u32,
    /// Children; `left == NULL` for a leaf.
    pub left: u32,
    /// Second child.
    pub right: u32,
    /// The object of a leaf.
    pub item: u32,
    /// Height: 0 for a leaf; `u32::MAX` for a free node.
    pub height: u32,
    /// How many times this node was freed: a [`LeafHandle`] names the
    /// generation its leaf was made in, so one kept past a removal no longer
    /// matches, even once the node holds another object.
    pub generation: u32,
}

impl<B: BoundingVolume> DynNode<B> {
    /// A blank node, for initialising storage.
    pub const EMPTY: Self = DynNode {
        bv: B::EMPTY,
        parent: NULL,
        left: NULL,
        right: NULL,
        item: 0,
        height: u32::MAX,
        generation: 0,
    };

    fn is_leaf(&self) -> bool {
        self.left == NULL
    }

    /// Whether this node is a leaf in the tree (not free, not internal) of
    /// generation `generation`: what a [`LeafHandle`] must find to be live.
    pub const fn is_live_leaf(&self, generation: u32) -> bool {
        self.height == 0 && self.left == NULL && self.generation == generation
    }

    /// This node freed: blank, linked to `next_free` (the free list runs
    /// through `parent`), in the next generation (wrapping), so that no
    /// handle of its old leaf matches it again.
    pub const fn released(&self, next_free: u32) -> Self {
        DynNode {
            parent: next_free,
            generation: self.generation.wrapping_add(1),
            ..Self::EMPTY
        }
    }
}

/// A leaf of a [`DynamicTree`], as [`insert`](DynamicTree::insert) returns
/// it: the leaf's node and that node's generation.
///
/// Removing an object frees its node and moves the node to the next
/// generation, so a handle kept past [`remove`](DynamicTree::remove) is
/// refused ([`Error::StaleHandle`]) by every operation that takes one, even
/// after the node was reused for another object: an old handle can never
/// move or remove the wrong object. (A node's generation is a `u32`; it
/// would take 2^32 removals from one node for a handle to match again.)
///
/// ```
/// use bvhkit::builders::{DynNode, DynamicConfig, DynamicTree};
/// use bvhkit::{Aabb, Error};
/// use glam::Vec3;
/// let mut storage = [DynNode::<Aabb>::EMPTY; 3];
/// let mut tree = DynamicTree::new(&mut storage, DynamicConfig::default())?;
/// let unit = Aabb::new(Vec3::ZERO, Vec3::ONE);
/// let old = tree.insert(7, &unit)?;
/// tree.remove(old)?;
/// let new = tree.insert(8, &unit)?; // the same node, the next generation
/// assert_eq!(new.index(), old.index());
/// assert!(matches!(tree.update(old, &unit), Err(Error::StaleHandle { .. })));
/// assert_eq!(tree.item(new)?, 8);
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct LeafHandle {
    index: u32,
    generation: u32,
}

impl LeafHandle {
    /// A handle from its two numbers, for keeping handles outside Rust (in a
    /// file, across an FFI boundary). It cannot forge access: a tree refuses
    /// it unless node `index` is a live leaf of exactly that generation.
    pub const fn from_parts(index: u32, generation: u32) -> Self {
        LeafHandle { index, generation }
    }

    /// The leaf's node in the tree's storage.
    pub const fn index(self) -> u32 {
        self.index
    }

    /// The generation of that node the leaf belongs to.
    pub const fn generation(self) -> u32 {
        self.generation
    }
}

/// Bins per axis for [`sah_split`].
const SPLIT_BINS: usize = 16;

/// Nodes over this few objects split at the median: binning three axes
/// costs about 0.5 us a node whatever its size, most of a rebuild's time
/// if every node paid it, for splits that differ little this low. Chosen
/// by the broad phase's whole work (rebuilds plus the walks over the trees
/// they make, counted by cachegrind on drifting boxes): 8 took 2% fewer
/// instructions than 16, 4 about as many as 8, 64 5% more.
const MEDIAN_BELOW: usize = 8;

/// Splits `items` between equal-width bins of their boxes' centres, on the
/// axis and at the boundary that minimise the surface-area cost
/// `area(left) * n_left + area(right) * n_right`, partitioning them in
/// place; returns the left count, or `None` when on every axis all centres
/// fall in one bin (then the caller splits at the median).
fn sah_split(items: &mut [u32], boxes: &[Aabb], centres: &Aabb) -> Option<usize> {
    let width = Vec3A::from(centres.extent());
    let scale = Vec3A::select(
        width.cmpgt(Vec3A::ZERO),
        Vec3A::splat(SPLIT_BINS as f32) / width,
        Vec3A::ZERO,
    );
    let (origin, top) = (
        Vec3A::from(centres.min),
        Vec3A::splat((SPLIT_BINS - 1) as f32),
    );
    // The three bins of a box, one per axis, in 4-lane registers (the same
    // arithmetic when binning and when partitioning, so the two agree).
    let bins_of = |b: &Aabb| {
        let (lo, hi) = (Vec3A::from(b.min), Vec3A::from(b.max));
        let t = (((lo + hi) * 0.5 - origin) * scale).clamp(Vec3A::ZERO, top);
        ([t.x as usize, t.y as usize, t.z as usize], lo, hi)
    };
    let mut low = [[Vec3A::INFINITY; SPLIT_BINS]; 3];
    let mut high = [[Vec3A::NEG_INFINITY; SPLIT_BINS]; 3];
    let mut count = [[0u32; SPLIT_BINS]; 3];
    for &i in items.iter() {
        let (bins, lo, hi) = bins_of(&boxes[i as usize]);
        for (axis, k) in bins.into_iter().enumerate() {
            let k = k & (SPLIT_BINS - 1); // at most `top` already
            low[axis][k] = low[axis][k].min(lo);
            high[axis][k] = high[axis][k].max(hi);
            count[axis][k] += 1;
        }
    }
    let half_area = |lo: Vec3A, hi: Vec3A| {
        let e = (hi - lo).max(Vec3A::ZERO);
        f64::from(e.x * e.y + e.y * e.z + e.z * e.x)
    };
    let mut best: Option<(f64, usize, usize)> = None;
    for axis in 0..3 {
        if scale[axis] == 0.0 {
            continue;
        }
        // Right to left: the cost of everything from bin k on.
        let mut right = [0.0f64; SPLIT_BINS];
        let (mut lo, mut hi, mut n) = (Vec3A::INFINITY, Vec3A::NEG_INFINITY, 0);
        for k in (1..SPLIT_BINS).rev() {
            lo = lo.min(low[axis][k]);
            hi = hi.max(high[axis][k]);
            n += count[axis][k];
            right[k] = half_area(lo, hi) * f64::from(n);
        }
        let (mut lo, mut hi, mut n) = (Vec3A::INFINITY, Vec3A::NEG_INFINITY, 0);
        for k in 1..SPLIT_BINS {
            lo = lo.min(low[axis][k - 1]);
            hi = hi.max(high[axis][k - 1]);
            n += count[axis][k - 1];
            if n == 0 || n as usize == items.len() {
                continue;
            }
            let cost = half_area(lo, hi) * f64::from(n) + right[k];
            if best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, axis, k));
            }
        }
    }
    let (_, axis, boundary) = best?;
    let mut left = 0;
    for j in 0..items.len() {
        if bins_of(&boxes[items[j] as usize]).0[axis] < boundary {
            items.swap(left, j);
            left += 1;
        }
    }
    Some(left)
}

/// How an insertion picks the sibling of the new leaf.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SiblingSearch {
    /// One root-to-leaf walk (Goldsmith–Salmon): cheap, good enough.
    Descent,
    /// Branch and bound over the whole tree: the cheapest sibling.
    #[default]
    BranchAndBound,
}

/// When a [`DynamicTree`] rebalances by rotations.
///
/// Rotations by height keep the tree shallow, but they ignore the volumes, so
/// they cost quality: on a shuffled 20 480-triangle rock, branch-and-bound
/// insertion gives SAH cost 39.6 without rotations and 47.1 with rotations at
/// every node. Rotating only where the tree is already tall bounds the depth
/// for adversarial (sorted) input and leaves ordinary trees alone.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rotations {
    /// Never rotate, except where an insertion would otherwise make the tree
    /// deeper than [`MAX_DEPTH`] (sorted input gets there): the tree is then
    /// rebalanced by rotations so every query can still walk it.
    Off,
    /// Rebalance every node whose children's heights differ by more than one.
    Always,
    /// Rebalance only nodes taller than this height.
    AboveHeight(u32),
    /// Rotations chosen by surface area (as Box2D v3 does): at every node on
    /// the path to the root, swap a child with a grandchild on the other side
    /// when that shrinks the area of the child that changes, the swap that
    /// shrinks it most. Heights are not balanced (a height rotation still
    /// steps in where the tree would pass [`MAX_DEPTH`]), so the tree keeps
    /// the quality that height rotations give away.
    Area,
}

/// Options of a [`DynamicTree`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DynamicConfig {
    /// Sibling search.
    pub search: SiblingSearch,
    /// When to rebalance by rotations after inserts and removals.
    pub rotations: Rotations,
    /// How much each leaf volume is enlarged beyond its object's box.
    pub margin: f32,
}

impl Default for DynamicConfig {
    fn default() -> Self {
        DynamicConfig {
            search: SiblingSearch::BranchAndBound,
            rotations: Rotations::AboveHeight(32),
            margin: 0.0,
        }
    }
}

/// A tree built by insertion, with removal and updates, in caller storage.
///
/// ```
/// use bvhkit::builders::{DynNode, DynamicConfig, DynamicTree};
/// use bvhkit::{Aabb, Node};
/// use glam::Vec3;
/// let mut storage = vec![DynNode::<Aabb>::EMPTY; 2 * 100 - 1];
/// let mut tree = DynamicTree::new(&mut storage, DynamicConfig { margin: 0.1, ..Default::default() })?;
/// let mut handles = Vec::new();
/// for i in 0..100 {
///     let lo = Vec3::new(i as f32, 0.0, 0.0);
///     handles.push(tree.insert(i, &Aabb::new(lo, lo + 0.5))?);
/// }
/// assert_eq!(tree.len(), 100);
/// assert!(tree.height() <= 40); // rotations keep sorted input from growing a chain
/// // A small move stays inside the fat leaf: nothing to do.
/// let lo = Vec3::new(3.05, 0.0, 0.0);
/// assert!(!tree.update(handles[3], &Aabb::new(lo, lo + 0.5))?);
/// tree.remove(handles[7])?;
/// assert_eq!(tree.len(), 99);
/// // Export to the layout every query runs on.
/// let mut nodes = vec![Node::<Aabb>::EMPTY; 2 * 99 - 1];
/// let mut idx = vec![0u32; 99];
/// let bvh = tree.to_bvh(&mut nodes, &mut idx)?;
/// assert_eq!(bvh.node_count(), 197);
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Debug)]
pub struct DynamicTree<'s, B> {
    nodes: &'s mut [DynNode<B>],
    root: u32,
    free: u32,
    leaves: u32,
    config: DynamicConfig,
    /// Insertions that had to rotate against the configuration (the
    /// depth limit), reported by [`to_bvh`](Self::to_bvh).
    forced_rebalances: u32,
    /// The largest object id of a live leaf (meaningless when empty): a
    /// query's primitive slice must reach it.
    max_item: u32,
    /// The storage slot where [`optimize`](DynamicTree::optimize) goes on.
    cursor: u32,
}

fn area<B: BoundingVolume>(b: &B) -> f64 {
    b.cost_area_scaled(1.0) as f64
}

/// A power of two that brings `b`'s largest extent into `[1, 2)`: an
/// insertion compares its candidates' areas with lengths in that unit, so a
/// scene 1e30 wide (areas 1e60, past `f32`) or 1e-15 wide (products of
/// extents that fall to subnormals) compares as it would at unit size. A
/// power of two scales every length exactly, so the choices, and the tree,
/// are the same as in raw `f32` wherever that did not overflow.
fn unit_scale(b: &Aabb) -> f32 {
    let m = b.extent().max_element();
    if !(m > 0.0 && m.is_finite()) {
        return 1.0;
    }
    // `m` in [2^(e-127), 2^(e-126)) for its biased exponent `e` (0 for a
    // subnormal, which the clamp treats as the smallest normal).
    let e = ((m.to_bits() >> 23) & 0xff) as i32;
    f32::from_bits(((254 - e.max(1)).clamp(1, 254) as u32) << 23)
}

/// [`area`] with lengths scaled by `scale` (see [`unit_scale`]).
fn area_in<B: BoundingVolume>(b: &B, scale: f32) -> f64 {
    b.cost_area_scaled(scale) as f64
}

/// The Goldsmith–Salmon cost of `sibling` for a new leaf `bv`: the new
/// parent's area plus the growth of every ancestor.
fn cost_in<B: BoundingVolume>(nodes: &[DynNode<B>], sibling: u32, bv: &B) -> f64 {
    let mut cost = area(&nodes[sibling as usize].bv.merge(bv));
    let mut a = nodes[sibling as usize].parent;
    while a != NULL {
        let node = &nodes[a as usize].bv;
        cost += area(&node.merge(bv)) - area(node);
        a = nodes[a as usize].parent;
    }
    cost
}

/// One rotation by area (see [`Rotations::Area`]): the node's child `down`
/// (0 the left, 1 the right) moves into its other child, in place of that
/// child's child `up` (0 its left, 1 its right), which moves up beside
/// the child that stayed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AreaRotation {
    /// Which child of the node moves down.
    pub down: usize,
    /// Which child of the other child moves up.
    pub up: usize,
}

/// The rotation by area of a node with `children`, each with its own two
/// children if it is not a leaf (`grandchildren[k]` belongs to
/// `children[k]`): of the up to four swaps, the one after which the child
/// that received a node has the smallest surface area, if that is smaller
/// than before; `None` when no swap shrinks it. Ties go to the first in the
/// order (down 0, up 0), (0, 1), (1, 0), (1, 1). The node's own volume is
/// the same after any swap, so this area is the whole change in the tree's
/// cost. Areas are compared with lengths scaled by a power of two that brings
/// the node to unit size, so huge and tiny scenes rotate as unit ones do.
///
/// ```
/// use bvhkit::builders::{area_rotation, AreaRotation};
/// use bvhkit::Aabb;
/// use glam::Vec3;
/// let unit = |x: f32| Aabb::new(Vec3::new(x, 0.0, 0.0), Vec3::new(x + 1.0, 1.0, 1.0));
/// // A leaf at 0 beside a node over leaves at 1 and 9: the leaf at 9 should
/// // move up, and the leaf at 0 down beside the leaf at 1.
/// let (a, b, c) = (unit(0.0), unit(1.0), unit(9.0));
/// let r = area_rotation([&a, &b.union(&c)], [None, Some([&b, &c])]);
/// assert_eq!(r, Some(AreaRotation { down: 0, up: 1 }));
/// // Already the best shape: nothing to do.
/// assert_eq!(area_rotation([&c, &a.union(&b)], [None, Some([&a, &b])]), None);
/// ```
pub fn area_rotation<B: BoundingVolume>(
    children: [&B; 2],
    grandchildren: [Option<[&B; 2]>; 2],
) -> Option<AreaRotation> {
    let scale = unit_scale(&enclose(children[0], children[1]).aabb());
    let mut best: Option<(AreaRotation, f64)> = None;
    for down in 0..2 {
        let Some(kids) = grandchildren[1 - down] else {
            continue; // the other child is a leaf: nothing moves into it
        };
        let before = area_in(children[1 - down], scale);
        for up in 0..2 {
            let after = area_in(&enclose(children[down], kids[1 - up]), scale);
            let saved = before - after;
            if saved > 0.0 && best.is_none_or(|(_, b)| saved > b) {
                best = Some((AreaRotation { down, up }, saved));
            }
        }
    }
    best.map(|(r, _)| r)
}

impl<'s, B: BoundingVolume> DynamicTree<'s, B> {
    /// An empty tree over `storage` (room for `(storage.len() + 1) / 2` objects).
    pub fn new(storage: &'s mut [DynNode<B>], config: DynamicConfig) -> Result<Self, Error> {
        if !(config.margin >= 0.0 && config.margin.is_finite()) {
            return Err(Error::InvalidConfig("the margin must be finite and >= 0"));
        }
        if storage.len() >= NULL as usize {
            return Err(Error::IndexOverflow {
                count: storage.len(),
            });
        }
        let n = storage.len();
        for (i, node) in storage.iter_mut().enumerate() {
            // A new generation: handles of an earlier tree in this storage
            // are stale.
            *node = DynNode {
                parent: if i + 1 < n { i as u32 + 1 } else { NULL },
                generation: node.generation.wrapping_add(1),
                ..DynNode::EMPTY
            };
        }
        Ok(DynamicTree {
            nodes: storage,
            root: NULL,
            free: if n > 0 { 0 } else { NULL },
            leaves: 0,
            config,
            forced_rebalances: 0,
            max_item: 0,
            cursor: 0,
        })
    }

    /// Objects in the tree.
    pub fn len(&self) -> usize {
        self.leaves as usize
    }

    /// Whether the tree holds no object.
    pub fn is_empty(&self) -> bool {
        self.leaves == 0
    }

    /// Height of the root (0 for one leaf or an empty tree).
    pub fn height(&self) -> usize {
        if self.root == NULL {
            0
        } else {
            self.nodes[self.root as usize].height as usize
        }
    }

    /// Sum of the surface areas of all nodes (the quantity insertion minimises).
    pub fn area_sum(&self) -> f64 {
        let mut sum = 0.0;
        self.for_each_node(|n| sum += area(&n.bv));
        sum
    }

    fn for_each_node(&self, mut f: impl FnMut(&DynNode<B>)) {
        if self.root == NULL {
            return;
        }
        let mut stack = [NULL; 2 * MAX_DEPTH + 2];
        stack[0] = self.root;
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let n = &self.nodes[stack[top] as usize];
            f(n);
            if !n.is_leaf() && top + 2 <= stack.len() {
                stack[top] = n.left;
                stack[top + 1] = n.right;
                top += 2;
            }
        }
    }

    fn allocate(&mut self) -> Result<u32, Error> {
        if self.free == NULL {
            return Err(Error::NodeCapacity {
                needed: self.nodes.len() + 2,
                available: self.nodes.len(),
            });
        }
        let i = self.free;
        self.free = self.nodes[i as usize].parent;
        self.nodes[i as usize] = DynNode {
            height: 0,
            generation: self.nodes[i as usize].generation,
            ..DynNode::EMPTY
        };
        Ok(i)
    }

    /// Frees node `i`, in the next generation.
    fn release(&mut self, i: u32) {
        self.nodes[i as usize] = self.nodes[i as usize].released(self.free);
        self.free = i;
    }

    /// `bounds` enlarged by the margin, once [`check`](Self::check)ed.
    pub(crate) fn fat(&self, item: u32, bounds: &Aabb) -> Result<B, Error> {
        self.check(item, bounds)?;
        Ok(self.fattened(bounds))
    }

    /// Whether `bounds` may be object `item`'s box: finite, not inverted,
    /// and far enough inside [`MAX_COORDINATE`](crate::MAX_COORDINATE) for
    /// its fat volume to be too. One lane-wise test passes every good box
    /// (a NaN fails each comparison); the error is worked out only for a
    /// bad one (a broad phase checks every box of every frame).
    #[inline]
    pub(crate) fn check(&self, item: u32, bounds: &Aabb) -> Result<(), Error> {
        let (lo, hi) = bounds.lanes();
        let limit = glam::Vec4::splat(crate::MAX_COORDINATE - self.config.margin);
        if xyz_all((lo.abs().cmple(limit) & hi.abs().cmple(limit) & lo.cmple(hi)).bitmask()) {
            return Ok(());
        }
        let primitive = item as usize;
        Err(if !bounds.is_finite() || xyz_any(lo.cmpgt(hi).bitmask()) {
            Error::NonFiniteCoordinate { primitive }
        } else {
            Error::CoordinateOutOfRange { primitive }
        })
    }

    /// `bounds` enlarged by the margin (checked by [`fat`](Self::fat)).
    pub(crate) fn fattened(&self, bounds: &Aabb) -> B {
        let m = Vec3::splat(self.config.margin);
        B::from_aabb(&Aabb::new(bounds.min - m, bounds.max + m))
    }

    /// Inserts object `item` with bounds `bounds`; returns its leaf's
    /// handle, which [`update`](Self::update) and [`remove`](Self::remove)
    /// take. Errors: non-finite bounds or storage full; the object is not
    /// inserted then. Depth is not an error: a tree that would get deeper
    /// than [`MAX_DEPTH`] is rebalanced by rotations whatever [`Rotations`]
    /// says.
    pub fn insert(&mut self, item: u32, bounds: &Aabb) -> Result<LeafHandle, Error> {
        let bv = self.fat(item, bounds)?;
        if self.free == NULL || (self.root != NULL && self.nodes[self.free as usize].parent == NULL)
        {
            // A new object needs a leaf and a parent.
            return Err(Error::NodeCapacity {
                needed: 2 * self.leaves as usize + 1,
                available: self.nodes.len(),
            });
        }
        let leaf = self.allocate()?;
        self.nodes[leaf as usize].bv = bv;
        self.nodes[leaf as usize].item = item;
        if let Err(e) = self.attach(leaf) {
            self.release(leaf);
            return Err(e);
        }
        self.leaves += 1;
        self.max_item = if self.leaves == 1 {
            item
        } else {
            self.max_item.max(item)
        };
        Ok(LeafHandle {
            index: leaf,
            generation: self.nodes[leaf as usize].generation,
        })
    }

    /// Removes the object of `handle`. Errors: a handle that is not a live
    /// leaf of this tree (removed already, or never one); nothing changes.
    pub fn remove(&mut self, handle: LeafHandle) -> Result<(), Error> {
        let leaf = self.check_leaf(handle)?;
        let item = self.nodes[leaf as usize].item;
        self.detach(leaf);
        self.release(leaf);
        self.leaves -= 1;
        self.forget(item);
        Ok(())
    }

    /// After the leaf of `item` left the tree: finds the new largest id if
    /// it was the largest (a scan of the storage, so only when the largest
    /// id leaves: rare for ids spread over the objects).
    fn forget(&mut self, item: u32) {
        if item == self.max_item && self.leaves > 0 {
            self.max_item = self
                .nodes
                .iter()
                .filter(|n| n.height == 0 && n.is_leaf())
                .map(|n| n.item)
                .max()
                .unwrap_or(0);
        }
    }

    /// Tells the tree that the object of `leaf` now has `bounds`. Returns
    /// `false` when the bounds are still inside the leaf's fat volume (nothing
    /// changed), `true` when the leaf was reinserted with a new fat volume.
    /// Bad bounds are an error that leaves the object where it was. (The
    /// reinsertion itself cannot fail: the detach freed the node it needs,
    /// and a tree that would get too deep is rebalanced as in
    /// [`insert`](Self::insert). Should even that fail, the object is
    /// removed and the error says so.)
    pub fn update(&mut self, handle: LeafHandle, bounds: &Aabb) -> Result<bool, Error> {
        let leaf = self.check_leaf(handle)?;
        let item = self.nodes[leaf as usize].item;
        let bv = self.fat(item, bounds)?;
        if self.nodes[leaf as usize].bv.contains_aabb(bounds) {
            return Ok(false);
        }
        self.detach(leaf);
        self.nodes[leaf as usize].bv = bv;
        if let Err(e) = self.attach(leaf) {
            self.release(leaf);
            self.leaves -= 1;
            self.forget(item);
            return Err(e); // the object is no longer in the tree
        }
        Ok(true)
    }

    /// Improves the tree a little: takes up to `budget` nodes out, each with
    /// its subtree, and inserts each again where it now costs least, and
    /// returns how many it reinserted. Nodes are taken in storage order (the
    /// root excepted), each call going on where the last one stopped, so a
    /// few per frame visit the whole tree in turn.
    ///
    /// Why it helps: a tree grown one insertion at a time (or kept up by
    /// updates while objects drift) has nodes that went where they cost
    /// least *then*. Taken out, a node's best sibling is searched in the
    /// tree as it is now. Moving whole subtrees, not only leaves, is what
    /// untangles a bad shape (a chain, say): a leaf moved alone leaves the
    /// chain's inner nodes where they were (the reinsertion search of
    /// Bittner, Hapala and Havran, here in storage order, not by a measure
    /// of how badly each node sits). With [`SiblingSearch::BranchAndBound`]
    /// and a box tree, the old place is one of the candidates, so the total
    /// node area (the cost the search minimises) does not grow, unless
    /// height rotations ([`Rotations::Always`], [`Rotations::AboveHeight`])
    /// trade area for balance afterwards; [`Rotations::Area`] only ever
    /// shrinks it. Handles, items and fat volumes stay as they are. A tree
    /// with fewer than three objects has nothing to gain.
    ///
    /// Errors: only a tree that would pass [`MAX_DEPTH`] even after
    /// rebalancing (not seen in practice); the node then goes back where it
    /// was, and nothing is lost.
    ///
    /// ```
    /// use bvhkit::builders::{DynNode, DynamicConfig, DynamicTree, Rotations};
    /// use bvhkit::Aabb;
    /// use glam::Vec3;
    /// // Sorted input without rotations: every box lands on one long spine.
    /// let config = DynamicConfig { rotations: Rotations::Off, ..Default::default() };
    /// let mut storage = vec![DynNode::<Aabb>::EMPTY; 2 * 40 - 1];
    /// let mut tree = DynamicTree::new(&mut storage, config)?;
    /// for i in 0..40 {
    ///     let lo = Vec3::new(i as f32, 0.0, 0.0);
    ///     tree.insert(i, &Aabb::new(lo, lo + Vec3::splat(0.5)))?;
    /// }
    /// let before = tree.area_sum();
    /// for _ in 0..4 {
    ///     tree.optimize(40)?; // 40 of the 78 nodes below the root a call
    /// }
    /// tree.validate()?;
    /// assert_eq!(tree.len(), 40);
    /// assert!(tree.area_sum() < before);
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn optimize(&mut self, budget: usize) -> Result<usize, Error> {
        let slots = self.nodes.len();
        if self.leaves < 3 {
            return Ok(0);
        }
        let (mut moved, mut scanned) = (0, 0);
        while moved < budget && scanned < slots {
            let slot = self.cursor as usize; // always below `slots`
            self.cursor = ((slot + 1) % slots) as u32;
            scanned += 1;
            let node = self.nodes[slot];
            let n = slot as u32;
            if node.height == u32::MAX || n == self.root {
                continue; // a free slot, or the root (nowhere else to go)
            }
            let p = self.nodes[node.parent as usize];
            let old_sibling = if p.left == n { p.right } else { p.left };
            // Taken out without rotations, the tree is the old one less this
            // subtree, so the old place is still there to be found.
            self.with_rotations(Rotations::Off, |t| t.detach(n));
            if let Err(e) = self.attach(n) {
                // Too deep even rebalanced (not seen in practice): back
                // next to its old sibling, nothing lost.
                let parent = self.splice(n, old_sibling)?;
                self.with_rotations(Rotations::Off, |t| t.fix_upwards(parent));
                return Err(e);
            }
            moved += 1;
        }
        Ok(moved)
    }

    /// Rebuilds every internal node top-down over the leaves as they are:
    /// each object keeps its leaf, its handle and its fat volume; only the
    /// nodes above the leaves are made anew, each splitting its leaves at
    /// the median of their centres along the longest side of the centres'
    /// box. The cure for a tree whose objects all moved: reinserting `n`
    /// leaves one by one costs a sibling search each, where this costs
    /// `O(n log n)` and leaves a balanced tree (height about `log2 n`).
    /// `scratch` holds one entry per object. Errors: `scratch` too short
    /// (nothing changes then).
    ///
    /// ```
    /// use bvhkit::builders::{DynNode, DynamicConfig, DynamicTree};
    /// use bvhkit::{Aabb, Query};
    /// use glam::Vec3;
    /// let mut storage = vec![DynNode::<Aabb>::EMPTY; 2 * 100 - 1];
    /// let mut tree = DynamicTree::new(&mut storage, DynamicConfig::default())?;
    /// let unit = |x: f32| Aabb::new(Vec3::new(x, 0.0, 0.0), Vec3::new(x + 1.0, 1.0, 1.0));
    /// let handles: Vec<_> = (0..100).map(|i| tree.insert(i, &unit(i as f32 * 2.0)).unwrap()).collect();
    /// let mut scratch = vec![0u32; 100];
    /// tree.rebuild(&mut scratch)?;
    /// tree.validate()?;
    /// assert_eq!(tree.height(), 7); // 100 leaves, balanced: ceil(log2 100)
    /// assert_eq!(tree.item(handles[42])?, 42); // every handle still names its object
    /// let boxes: Vec<Aabb> = (0..100).map(|i| unit(i as f32 * 2.0)).collect();
    /// let mut hits = Vec::new();
    /// tree.overlapping(&boxes, &unit(84.5), |i| hits.push(i))?;
    /// assert_eq!(hits, [42]);
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn rebuild(&mut self, scratch: &mut [u32]) -> Result<(), Error> {
        let n = self.leaves as usize;
        if scratch.len() < n {
            return Err(Error::IndexCapacity {
                needed: n,
                available: scratch.len(),
            });
        }
        if self.root == NULL {
            return Ok(());
        }
        // Collect the leaves and free the nodes above them, in one walk.
        let mut stack = [NULL; 2 * MAX_DEPTH + 2];
        stack[0] = self.root;
        let (mut top, mut found) = (1, 0);
        while top > 0 {
            top -= 1;
            let i = stack[top];
            let node = self.nodes[i as usize];
            if node.is_leaf() {
                scratch[found] = i;
                found += 1;
            } else {
                stack[top] = node.left;
                stack[top + 1] = node.right;
                top += 2;
                self.release(i);
            }
        }
        let leaves = &mut scratch[..found];
        self.root = self.build_over(leaves);
        self.nodes[self.root as usize].parent = NULL;
        Ok(())
    }

    /// Rebuilds the whole tree over `items` (each object once: those in
    /// the tree and any others, which join it), laid out anew in depth-first order from storage slot 0, each leaf's
    /// fat volume made afresh from `boxes[item]`; `on_leaf(item, handle,
    /// fat volume)` receives every object's new leaf, and every old handle is stale
    /// afterwards. Splits as [`rebuild`](Self::rebuild) does. Why: a tree
    /// kept up by insertions and updates has its nodes scattered over the
    /// storage, and a walk over all of it (a self query each step) then
    /// waits on memory; laid out in walk order, it streams. Errors: more
    /// items than the storage holds, or an item whose box is bad (nothing
    /// changes then).
    pub(crate) fn rebuild_in_order(
        &mut self,
        items: &mut [u32],
        boxes: &[Aabb],
        mut on_leaf: impl FnMut(u32, LeafHandle, &B),
    ) -> Result<(), Error> {
        let used = (2 * items.len()).saturating_sub(1);
        if used > self.nodes.len() {
            return Err(Error::NodeCapacity {
                needed: used,
                available: self.nodes.len(),
            });
        }
        for &item in items.iter() {
            let bounds = boxes.get(item as usize).ok_or(Error::IndexOverflow {
                count: item as usize,
            })?;
            self.fat(item, bounds)?;
        }
        // Every slot free and in its next generation: no old handle matches.
        for node in self.nodes.iter_mut() {
            *node = node.released(NULL);
        }
        self.leaves = items.len() as u32;
        self.max_item = items.iter().copied().max().unwrap_or(0);
        let mut next = 0;
        self.root = if items.is_empty() {
            NULL
        } else {
            self.place(items, boxes, NULL, &mut next, &mut on_leaf)
        };
        // The slots after the tree, in order, are the free list.
        let slots = self.nodes.len();
        for i in used..slots {
            self.nodes[i].parent = if i + 1 < slots { i as u32 + 1 } else { NULL };
        }
        self.free = if used < slots { used as u32 } else { NULL };
        Ok(())
    }

    /// The subtree of [`rebuild_in_order`](Self::rebuild_in_order) over
    /// `items` (at least one), its root at slot `*next`, its nodes after it.
    fn place(
        &mut self,
        items: &mut [u32],
        boxes: &[Aabb],
        parent: u32,
        next: &mut u32,
        on_leaf: &mut impl FnMut(u32, LeafHandle, &B),
    ) -> u32 {
        let at = *next;
        *next += 1;
        let generation = self.nodes[at as usize].generation;
        if let [item] = *items {
            self.nodes[at as usize] = DynNode {
                bv: self.fattened(&boxes[item as usize]),
                parent,
                left: NULL,
                right: NULL,
                item,
                height: 0,
                generation,
            };
            on_leaf(
                item,
                LeafHandle::from_parts(at, generation),
                &self.nodes[at as usize].bv,
            );
            return at;
        }
        let centre = |i: u32| boxes[i as usize].center();
        let mut box_of_centres = Aabb::EMPTY;
        for &i in items.iter() {
            box_of_centres.grow(centre(i));
        }
        let axis = box_of_centres.extent().max_position();
        let sah = if items.len() > MEDIAN_BELOW {
            sah_split(items, boxes, &box_of_centres)
        } else {
            None
        };
        let mid = match sah {
            Some(mid) => mid,
            None => {
                let mid = items.len() / 2;
                items.select_nth_unstable_by(mid, |&a, &b| {
                    centre(a)[axis].total_cmp(&centre(b)[axis]).then(a.cmp(&b))
                });
                mid
            }
        };
        let (lo, hi) = items.split_at_mut(mid);
        let left = self.place(lo, boxes, at, next, on_leaf);
        let right = self.place(hi, boxes, at, next, on_leaf);
        let (l, r) = (&self.nodes[left as usize], &self.nodes[right as usize]);
        self.nodes[at as usize] = DynNode {
            bv: enclose(&l.bv, &r.bv),
            parent,
            left,
            right,
            item: 0,
            height: 1 + l.height.max(r.height),
            generation,
        };
        at
    }

    /// Calls `f(i, j)` for every pair of objects, `i != j`, whose boxes
    /// `boxes[i]` and `boxes[j]` overlap (touching counts), each pair once
    /// in either order: the answer of [`SelfPairs`](crate::query::SelfPairs)
    /// with the bounds answer. The broad phase's walk over every object, cut
    /// to what a box tree with one object per leaf needs: each pair of
    /// nodes popped tests its children against each other straight from
    /// the nodes, with none of the general walk's dispatch (a third of the
    /// time on 10,000 drifting boxes). Errors: `boxes` shorter than the
    /// largest id needs.
    // Not inlined: inlined into a tracker step, its code moved with every
    // change to the step (up to 4% more instructions on 10,000 boxes).
    #[inline(never)]
    pub(crate) fn for_each_box_pair(
        &self,
        boxes: &[Aabb],
        mut f: impl FnMut(u32, u32),
    ) -> Result<(), Error> {
        crate::tree::hierarchy::check_query(self, boxes.len())?;
        if self.root == NULL {
            return Ok(());
        }
        let nodes = &*self.nodes;
        let mut inner = [NULL; MAX_DEPTH + 1];
        let mut pairs = [(NULL, NULL); crate::query::PAIR_STACK];
        // One pop pushes at most four pairs and goes a level down on both
        // sides, or two and one level down on one side: a height `h` tree
        // against itself keeps at most `3 * h + 1` pairs waiting.
        let height = nodes[self.root as usize].height as usize;
        if 3 * height + 4 > pairs.len() {
            return Err(Error::StackOverflow {
                depth: 2 * height,
                capacity: pairs.len(),
            });
        }
        let (mut top_inner, mut top) = (0, 0);
        let mut visit = self.root;
        loop {
            let n = &nodes[visit as usize];
            if !n.is_leaf() {
                let (l, r) = (&nodes[n.left as usize], &nodes[n.right as usize]);
                pairs[0] = (n.left, n.right);
                top = usize::from(l.bv.overlaps(&r.bv));
                inner[top_inner] = n.right;
                top_inner += 1;
                visit = n.left;
            } else if top_inner > 0 {
                top_inner -= 1;
                visit = inner[top_inner];
            } else {
                break;
            }
            while top > 0 {
                top -= 1;
                let (a, b) = pairs[top];
                let (na, nb) = (&nodes[a as usize], &nodes[b as usize]);
                match (na.is_leaf(), nb.is_leaf()) {
                    (true, true) => {
                        if boxes[na.item as usize].overlaps(&boxes[nb.item as usize]) {
                            f(na.item, nb.item);
                        }
                    }
                    (false, false) => {
                        let (al, ar) = (&nodes[na.left as usize].bv, &nodes[na.right as usize].bv);
                        let (bl, br) = (&nodes[nb.left as usize].bv, &nodes[nb.right as usize].bv);
                        // Written unconditionally, kept by the test's outcome.
                        pairs[top] = (na.left, nb.left);
                        top += usize::from(al.overlaps(bl));
                        pairs[top] = (na.left, nb.right);
                        top += usize::from(al.overlaps(br));
                        pairs[top] = (na.right, nb.left);
                        top += usize::from(ar.overlaps(bl));
                        pairs[top] = (na.right, nb.right);
                        top += usize::from(ar.overlaps(br));
                    }
                    (a_leaf, _) => {
                        let (leaf, node, kids) = if a_leaf { (a, na, nb) } else { (b, nb, na) };
                        let bv = &node.bv;
                        pairs[top] = (leaf, kids.left);
                        top += usize::from(bv.overlaps(&nodes[kids.left as usize].bv));
                        pairs[top] = (leaf, kids.right);
                        top += usize::from(bv.overlaps(&nodes[kids.right as usize].bv));
                    }
                }
            }
        }
        Ok(())
    }

    /// Sum of the surface areas of the inner nodes: how well the tree
    /// groups its leaves (the leaves' own areas do not depend on the shape).
    pub(crate) fn inner_area_sum(&self) -> f64 {
        let mut sum = 0.0;
        self.for_each_node(|n| {
            if !n.is_leaf() {
                sum += area(&n.bv);
            }
        });
        sum
    }

    /// The subtree over `leaves` (at least one), rooted at the returned
    /// node: each node splits its leaves at the median of their centres
    /// along the longest side of the centres' box, so the recursion is
    /// `ceil(log2 n)` deep, far under [`MAX_DEPTH`]. (A binned surface-area
    /// split was tried: on 100,000 drifting boxes it took longer to build
    /// and the self-pair walk over it was no faster.) Every inner node it
    /// needs was freed by [`rebuild`](Self::rebuild): `n` leaves need `n - 1`.
    fn build_over(&mut self, leaves: &mut [u32]) -> u32 {
        if let [one] = leaves {
            return *one;
        }
        let nodes = &*self.nodes;
        let centre = |i: u32| nodes[i as usize].bv.aabb().center();
        let mut box_of_centres = Aabb::EMPTY;
        for &i in leaves.iter() {
            box_of_centres.grow(centre(i));
        }
        let axis = box_of_centres.extent().max_position();
        let mid = leaves.len() / 2;
        leaves.select_nth_unstable_by(mid, |&a, &b| {
            centre(a)[axis].total_cmp(&centre(b)[axis]).then(a.cmp(&b))
        });
        let (lo, hi) = leaves.split_at_mut(mid);
        let left = self.build_over(lo);
        let right = self.build_over(hi);
        // The walk in `rebuild` freed one node per inner node, and a tree
        // over these leaves has one fewer: the free list cannot be empty.
        let parent = self.free;
        self.free = self.nodes[parent as usize].parent;
        let (l, r) = (self.nodes[left as usize], self.nodes[right as usize]);
        self.nodes[parent as usize] = DynNode {
            bv: enclose(&l.bv, &r.bv),
            parent: NULL,
            left,
            right,
            item: 0,
            height: 1 + l.height.max(r.height),
            generation: self.nodes[parent as usize].generation,
        };
        self.nodes[left as usize].parent = parent;
        self.nodes[right as usize].parent = parent;
        parent
    }

    /// Gives the leaf of `handle` the fat volume of `bounds` in place and
    /// refits the nodes above it (heights and shape unchanged), stopping
    /// where a node's volume no longer changes. Returns the leaf's new fat
    /// volume and how much the inner nodes' total area
    /// ([`inner_area_sum`](Self::inner_area_sum)) grew (negative when it
    /// shrank). Errors as [`update`](Self::update); nothing changes then.
    pub(crate) fn refit_leaf(
        &mut self,
        handle: LeafHandle,
        bounds: &Aabb,
    ) -> Result<(B, f64), Error> {
        let leaf = self.check_leaf(handle)?;
        let fat = self.fat(self.nodes[leaf as usize].item, bounds)?;
        self.nodes[leaf as usize].bv = fat;
        let mut grown = 0.0;
        let mut n = self.nodes[leaf as usize].parent;
        while n != NULL {
            let node = self.nodes[n as usize];
            let bv = enclose(
                &self.nodes[node.left as usize].bv,
                &self.nodes[node.right as usize].bv,
            );
            if bv == node.bv {
                break;
            }
            grown += area(&bv) - area(&node.bv);
            self.nodes[n as usize].bv = bv;
            n = node.parent;
        }
        Ok((fat, grown))
    }

    /// Gives `handle`'s leaf the fat volume of `bounds`, and leaves the
    /// nodes above it as they are: after many such leaves, one
    /// [`refit_inner`](Self::refit_inner) brings every inner node up to
    /// date for less than a [`refit_leaf`](Self::refit_leaf) each (whose
    /// walks up the tree share most of their nodes). Errors as
    /// [`update`](Self::update).
    pub(crate) fn set_leaf_fat(&mut self, handle: LeafHandle, bounds: &Aabb) -> Result<B, Error> {
        let leaf = self.check_leaf(handle)?;
        let fat = self.fat(self.nodes[leaf as usize].item, bounds)?;
        self.nodes[leaf as usize].bv = fat;
        Ok(fat)
    }

    /// Makes every inner node's volume enclose its children's, children
    /// first (one walk of the tree), and returns the inner nodes' total
    /// area (see [`inner_area_sum`](Self::inner_area_sum)).
    pub(crate) fn refit_inner(&mut self) -> f64 {
        let mut sum = 0.0;
        if self.root == NULL || self.nodes[self.root as usize].is_leaf() {
            return sum;
        }
        // The path from the root to the node in hand; `from` is the node
        // the walk came up from (its parent's left child or right child).
        let mut path = [NULL; MAX_DEPTH + 1];
        let (mut top, mut n) = (0, self.root);
        loop {
            while !self.nodes[n as usize].is_leaf() && top < path.len() {
                path[top] = n;
                top += 1;
                n = self.nodes[n as usize].left;
            }
            let mut from = n;
            loop {
                if top == 0 {
                    return sum;
                }
                let p = self.nodes[path[top - 1] as usize];
                if from == p.left {
                    n = p.right;
                    break;
                }
                let bv = enclose(
                    &self.nodes[p.left as usize].bv,
                    &self.nodes[p.right as usize].bv,
                );
                sum += area(&bv);
                from = path[top - 1];
                self.nodes[from as usize].bv = bv;
                top -= 1;
            }
        }
    }

    /// The object id of `handle`'s leaf. Errors as [`remove`](Self::remove).
    pub fn item(&self, handle: LeafHandle) -> Result<u32, Error> {
        let leaf = self.check_leaf(handle)?;
        Ok(self.nodes[leaf as usize].item)
    }

    /// The fat volume of `handle`'s leaf: its object's box when it was last
    /// (re)inserted, enlarged by the margin. Errors as [`remove`](Self::remove).
    pub fn fat_bounds(&self, handle: LeafHandle) -> Result<B, Error> {
        let leaf = self.check_leaf(handle)?;
        Ok(self.nodes[leaf as usize].bv)
    }

    /// Whether `handle` names a live leaf of this tree.
    pub fn contains(&self, handle: LeafHandle) -> bool {
        self.check_leaf(handle).is_ok()
    }

    /// `handle`'s node, if it is a live leaf of the handle's generation.
    fn check_leaf(&self, handle: LeafHandle) -> Result<u32, Error> {
        let LeafHandle { index, generation } = handle;
        match self.nodes.get(index as usize) {
            Some(n) if n.is_live_leaf(generation) => Ok(index),
            _ => Err(Error::StaleHandle { index, generation }),
        }
    }

    /// The cost of making `sibling` the sibling of a new leaf with volume
    /// `bv`: the new parent's area plus the growth of every ancestor.
    pub fn insertion_cost(&self, sibling: u32, bv: &B) -> f64 {
        cost_in(self.nodes, sibling, bv)
    }

    /// [`insertion_cost`](Self::insertion_cost) on storage that is not
    /// borrowed by a live tree (for tools and exercises): `sibling` is a node
    /// index of `storage`, `new` the object's box.
    pub fn insertion_cost_of(storage: &[DynNode<B>], sibling: u32, new: &Aabb) -> f64 {
        cost_in(storage, sibling, &B::from_aabb(new))
    }

    fn best_sibling(&self, bv: &B) -> u32 {
        // Lengths in the unit of the tree and the new box together.
        let scale = unit_scale(&self.nodes[self.root as usize].bv.merge(bv).aabb());
        match self.config.search {
            SiblingSearch::Descent => {
                // Goldsmith–Salmon with the weights of Box2D's dynamic tree:
                // staying creates a parent (counted twice: it is new and it
                // is visited), descending pays the growth of this node.
                let mut n = self.root;
                while !self.nodes[n as usize].is_leaf() {
                    let node = &self.nodes[n as usize];
                    let combined = area_in(&node.bv.merge(bv), scale);
                    let here = 2.0 * combined;
                    let inheritance = 2.0 * (combined - area_in(&node.bv, scale));
                    let child_cost = |c: u32| {
                        let cb = &self.nodes[c as usize].bv;
                        let m = area_in(&cb.merge(bv), scale);
                        inheritance
                            + if self.nodes[c as usize].is_leaf() {
                                m
                            } else {
                                m - area_in(cb, scale)
                            }
                    };
                    let (cl, cr) = (child_cost(node.left), child_cost(node.right));
                    if here < cl && here < cr {
                        break;
                    }
                    n = if cl <= cr { node.left } else { node.right };
                }
                n
            }
            SiblingSearch::BranchAndBound => {
                let own = area_in(bv, scale);
                // A bound to prune by from the start: the cheapest sibling
                // on one greedy root-to-leaf path (each step into the child
                // whose subtree can be cheapest). Only subtrees that cannot
                // reach it are skipped, so the search finds the sibling it
                // found without the bound (the same cost, the same tie).
                let seed = {
                    let (mut n, mut inherited, mut cheapest) = (self.root, 0.0f64, f64::INFINITY);
                    loop {
                        let node = &self.nodes[n as usize];
                        let direct = area_in(&node.bv.merge(bv), scale);
                        cheapest = cheapest.min(direct + inherited);
                        if node.is_leaf() {
                            break cheapest;
                        }
                        inherited += direct - area_in(&node.bv, scale);
                        let grows = |c: u32| {
                            let cb = &self.nodes[c as usize].bv;
                            area_in(&cb.merge(bv), scale) - area_in(cb, scale)
                        };
                        n = if grows(node.left) <= grows(node.right) {
                            node.left
                        } else {
                            node.right
                        };
                    }
                };
                let mut best = (f64::INFINITY, self.root);
                let mut stack = [(NULL, 0.0f64); 2 * MAX_DEPTH + 2];
                stack[0] = (self.root, 0.0);
                let mut top = 1;
                while top > 0 {
                    top -= 1;
                    let (n, inherited) = stack[top];
                    let node = &self.nodes[n as usize];
                    let direct = area_in(&node.bv.merge(bv), scale);
                    let cost = direct + inherited;
                    if cost < best.0 {
                        best = (cost, n);
                    }
                    let below = inherited + direct - area_in(&node.bv, scale);
                    // Any sibling below costs at least the new leaf's own area.
                    let bound = own + below;
                    if !node.is_leaf() && bound < best.0 && bound <= seed && top + 2 <= stack.len()
                    {
                        stack[top] = (node.right, below);
                        stack[top + 1] = (node.left, below);
                        top += 2;
                    }
                }
                best.1
            }
        }
    }

    /// Links a detached leaf into the tree.
    fn attach(&mut self, leaf: u32) -> Result<(), Error> {
        if self.root == NULL {
            self.root = leaf;
            self.nodes[leaf as usize].parent = NULL;
            return Ok(());
        }
        let bv = self.nodes[leaf as usize].bv;
        let sibling = self.best_sibling(&bv);
        let parent = self.splice(leaf, sibling)?;
        self.fix_upwards(parent);
        if self.height() > MAX_DEPTH {
            // Too deep for the traversals' fixed stacks (only possible when
            // rotations are off or start high): rotate whatever the
            // configuration says, first along the new leaf's path, then,
            // if that was not enough, along every leaf's path. Depth is
            // never a reason to refuse an object.
            self.forced_rebalances = self.forced_rebalances.saturating_add(1);
            self.with_rotations(Rotations::Always, |t| t.fix_upwards(parent));
            if self.height() > MAX_DEPTH {
                self.with_rotations(Rotations::Always, Self::rebalance_every_path);
            }
        }
        if self.height() > MAX_DEPTH {
            let h = self.height();
            self.detach(leaf);
            return Err(Error::StackOverflow {
                depth: h,
                capacity: MAX_DEPTH,
            });
        }
        Ok(())
    }

    /// Links `node` (a leaf or a subtree, out of the tree) next to `sibling`
    /// under a new parent, which it returns; the caller refits upwards.
    fn splice(&mut self, node: u32, sibling: u32) -> Result<u32, Error> {
        let parent = self.allocate()?;
        let old_parent = self.nodes[sibling as usize].parent;
        let (sb, nb) = (self.nodes[sibling as usize], self.nodes[node as usize]);
        self.nodes[parent as usize] = DynNode {
            bv: enclose(&sb.bv, &nb.bv),
            parent: old_parent,
            left: sibling,
            right: node,
            item: 0,
            height: 1 + sb.height.max(nb.height),
            generation: self.nodes[parent as usize].generation,
        };
        self.nodes[sibling as usize].parent = parent;
        self.nodes[node as usize].parent = parent;
        if old_parent == NULL {
            self.root = parent;
        } else if self.nodes[old_parent as usize].left == sibling {
            self.nodes[old_parent as usize].left = parent;
        } else {
            self.nodes[old_parent as usize].right = parent;
        }
        Ok(parent)
    }

    /// Runs `f` with `rotations`, then restores the configuration.
    fn with_rotations(&mut self, rotations: Rotations, f: impl FnOnce(&mut Self)) {
        let configured = self.config.rotations;
        self.config.rotations = rotations;
        f(self);
        self.config.rotations = configured;
    }

    /// Balances the path from every leaf to the root (O(n * height); only
    /// run when one path's rotations did not bring the tree under
    /// [`MAX_DEPTH`]).
    fn rebalance_every_path(&mut self) {
        for i in 0..self.nodes.len() {
            let node = self.nodes[i];
            if node.height == 0 && node.is_leaf() && node.parent != NULL {
                self.fix_upwards(node.parent);
            }
        }
    }

    /// Unlinks a leaf (not freed); its sibling takes the parent's place.
    fn detach(&mut self, leaf: u32) {
        if leaf == self.root {
            self.root = NULL;
            return;
        }
        let parent = self.nodes[leaf as usize].parent;
        let grand = self.nodes[parent as usize].parent;
        let p = self.nodes[parent as usize];
        let sibling = if p.left == leaf { p.right } else { p.left };
        self.nodes[sibling as usize].parent = grand;
        if grand == NULL {
            self.root = sibling;
        } else {
            if self.nodes[grand as usize].left == parent {
                self.nodes[grand as usize].left = sibling;
            } else {
                self.nodes[grand as usize].right = sibling;
            }
            self.fix_upwards(grand);
        }
        self.release(parent);
        self.nodes[leaf as usize].parent = NULL;
    }

    /// Refits volumes and heights from `n` to the root, rotating if enabled.
    fn fix_upwards(&mut self, mut n: u32) {
        while n != NULL {
            n = self.rotate(n);
            let node = self.nodes[n as usize];
            let (l, r) = (
                &self.nodes[node.left as usize],
                &self.nodes[node.right as usize],
            );
            let height = 1 + l.height.max(r.height);
            let bv = enclose(&l.bv, &r.bv);
            self.nodes[n as usize].height = height;
            self.nodes[n as usize].bv = bv;
            n = node.parent;
        }
    }

    /// If the children's heights differ by more than one, lift the taller
    /// child into `a`'s place, `a` keeping the shorter grandchild (a tree
    /// rotation), then balance the demoted `a` the same way; returns the node
    /// now at `a`'s place.
    fn rotate(&mut self, a: u32) -> u32 {
        let na = self.nodes[a as usize];
        let tall_enough = match self.config.rotations {
            Rotations::Area => {
                self.rotate_by_area(a);
                return a;
            }
            Rotations::Off => false,
            Rotations::Always => true,
            Rotations::AboveHeight(h) => na.height > h,
        };
        if na.is_leaf() || na.height < 2 || !tall_enough {
            return a;
        }
        let (b, c) = (na.left, na.right);
        let balance = self.nodes[c as usize].height as i64 - self.nodes[b as usize].height as i64;
        let (up, keep, up_is_right) = if balance > 1 {
            (c, b, true)
        } else if balance < -1 {
            (b, c, false)
        } else {
            return a;
        };
        let nu = self.nodes[up as usize];
        let (f, g) = (nu.left, nu.right);
        // `up` takes `a`'s place; `a` becomes a child of `up`.
        self.nodes[up as usize].parent = na.parent;
        self.nodes[a as usize].parent = up;
        if na.parent == NULL {
            self.root = up;
        } else if self.nodes[na.parent as usize].left == a {
            self.nodes[na.parent as usize].left = up;
        } else {
            self.nodes[na.parent as usize].right = up;
        }
        // The taller grandchild stays under `up`; the other moves to `a`.
        let (stay, moves) = if self.nodes[f as usize].height > self.nodes[g as usize].height {
            (f, g)
        } else {
            (g, f)
        };
        self.nodes[up as usize].left = a;
        self.nodes[up as usize].right = stay;
        if up_is_right {
            self.nodes[a as usize].right = moves;
        } else {
            self.nodes[a as usize].left = moves;
        }
        self.nodes[moves as usize].parent = a;
        let (kb, mb) = (self.nodes[keep as usize], self.nodes[moves as usize]);
        self.nodes[a as usize].bv = enclose(&kb.bv, &mb.bv);
        self.nodes[a as usize].height = 1 + kb.height.max(mb.height);
        // The demoted node may itself be out of balance now (its new child
        // can be much taller than the one it kept): balance it too. Heights
        // shrink on the way down, so this ends.
        self.rotate(a);
        let (l, r) = (self.nodes[up as usize].left, self.nodes[up as usize].right);
        let (lb, rb) = (self.nodes[l as usize], self.nodes[r as usize]);
        self.nodes[up as usize].bv = enclose(&lb.bv, &rb.bv);
        self.nodes[up as usize].height = 1 + lb.height.max(rb.height);
        up
    }

    /// The area rotation of `a` (see [`Rotations::Area`]): with children `b`
    /// and `c`, moving `b` down into `c` in place of one of `c`'s children
    /// (which moves up to `a`) leaves `c` enclosing `b` and the other child,
    /// so `a`'s cost changes by the area of that new `c` against the old one;
    /// and the same the other way round. The best of the (up to) four swaps
    /// is made if it shrinks that area; `a`'s own volume does not change.
    fn rotate_by_area(&mut self, a: u32) {
        let na = self.nodes[a as usize];
        if na.is_leaf() {
            return;
        }
        let kids = [na.left, na.right];
        let [l, r] = kids.map(|k| self.nodes[k as usize]);
        let grand = |n: &DynNode<B>| {
            (!n.is_leaf()).then(|| {
                [
                    &self.nodes[n.left as usize].bv,
                    &self.nodes[n.right as usize].bv,
                ]
            })
        };
        let Some(AreaRotation { down, up }) = area_rotation([&l.bv, &r.bv], [grand(&l), grand(&r)])
        else {
            return;
        };
        let (down, into) = (kids[down], kids[1 - down]);
        let ni = self.nodes[into as usize];
        let (up, stay) = if up == 0 {
            (ni.left, ni.right)
        } else {
            (ni.right, ni.left)
        };
        // `up` takes `down`'s place under `a`; `down` takes `up`'s under `into`.
        if self.nodes[a as usize].left == down {
            self.nodes[a as usize].left = up;
        } else {
            self.nodes[a as usize].right = up;
        }
        if ni.left == up {
            self.nodes[into as usize].left = down;
        } else {
            self.nodes[into as usize].right = down;
        }
        self.nodes[up as usize].parent = a;
        self.nodes[down as usize].parent = into;
        let (d, st) = (self.nodes[down as usize], self.nodes[stay as usize]);
        self.nodes[into as usize].bv = enclose(&d.bv, &st.bv);
        self.nodes[into as usize].height = 1 + d.height.max(st.height);
    }

    /// Checks the structure: parent and child links agree, heights are exact,
    /// every volume contains its children, the tree holds `len()` leaves and
    /// `2 * len() - 1` nodes, and every other node is on the free list (no
    /// node leaks after removals).
    pub fn validate(&self) -> Result<(), Error> {
        let bad = Error::InvalidTree;
        let mut reached = 0usize;
        let mut leaves = 0usize;
        if self.root != NULL {
            if self.nodes[self.root as usize].parent != NULL {
                return Err(bad("the root has a parent"));
            }
            let mut stack = [NULL; 2 * MAX_DEPTH + 2];
            stack[0] = self.root;
            let mut top = 1;
            while top > 0 {
                top -= 1;
                let i = stack[top];
                let n = &self.nodes[i as usize];
                reached += 1;
                if reached > self.nodes.len() {
                    return Err(bad("a cycle in the child links"));
                }
                if n.is_leaf() {
                    leaves += 1;
                    if n.height != 0 {
                        return Err(bad("a leaf with a non-zero height"));
                    }
                    continue;
                }
                let (l, r) = (&self.nodes[n.left as usize], &self.nodes[n.right as usize]);
                if l.parent != i || r.parent != i {
                    return Err(bad("a child does not point back to its parent"));
                }
                if n.height != 1 + l.height.max(r.height) {
                    return Err(bad("a stale height"));
                }
                if !n.bv.contains(&l.bv) || !n.bv.contains(&r.bv) {
                    return Err(bad("a volume does not contain its children"));
                }
                if top + 2 > stack.len() {
                    return Err(bad("deeper than MAX_DEPTH"));
                }
                stack[top] = n.left;
                stack[top + 1] = n.right;
                top += 2;
            }
        }
        if leaves != self.leaves as usize || reached != (2 * leaves).saturating_sub(1) {
            return Err(bad("leaf or node count differs from the live count"));
        }
        let mut free = 0usize;
        let mut f = self.free;
        while f != NULL {
            free += 1;
            if free > self.nodes.len() {
                return Err(bad("a cycle in the free list"));
            }
            f = self.nodes[f as usize].parent;
        }
        if free + reached != self.nodes.len() {
            return Err(bad("nodes leaked: neither in the tree nor free"));
        }
        Ok(())
    }

    /// Writes the tree in the query layout (children adjacent, one object per
    /// leaf): `nodes` needs `2 * len() - 1` entries, `indices` `len()`. An
    /// empty tree gives the empty `Bvh` (no nodes). Its
    /// [`build_report`](Bvh::build_report) counts, as `depth_limited`, the
    /// insertions since [`new`](Self::new) that rebalanced the tree against
    /// its [`Rotations`] to stay within [`MAX_DEPTH`].
    pub fn to_bvh<'a>(
        &self,
        nodes: &'a mut [Node<B>],
        indices: &'a mut [u32],
    ) -> Result<Bvh<'a, B>, Error> {
        self.to_bvh_with(nodes, indices, Collapse::None)
    }

    /// [`to_bvh`](Self::to_bvh), then `collapse` applied to its leaves: a
    /// snapshot for queries with up to `max_leaf_size` objects per leaf
    /// where the SAH says a leaf is cheaper. Same buffers.
    ///
    /// ```
    /// use bvhkit::builders::{Collapse, DynNode, DynamicConfig, DynamicTree};
    /// use bvhkit::{Aabb, Node};
    /// use glam::Vec3;
    /// let mut storage = vec![DynNode::<Aabb>::EMPTY; 199];
    /// let mut tree = DynamicTree::new(&mut storage, DynamicConfig::default())?;
    /// for i in 0..100u32 {
    ///     let o = Vec3::new((i % 10) as f32, (i / 10) as f32, 0.0);
    ///     tree.insert(i, &Aabb::new(o, o + Vec3::splat(0.9)))?;
    /// }
    /// let (mut nodes, mut idx) = (vec![Node::<Aabb>::ZERO; 199], vec![0u32; 100]);
    /// let bvh = tree.to_bvh_with(&mut nodes, &mut idx, Collapse::default())?;
    /// assert!(bvh.node_count() < 199 && bvh.primitive_count() == 100);
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    pub fn to_bvh_with<'a>(
        &self,
        nodes: &'a mut [Node<B>],
        indices: &'a mut [u32],
        collapse: Collapse,
    ) -> Result<Bvh<'a, B>, Error> {
        if self.root == NULL {
            return Ok(Bvh::from_built(&nodes[..0], &indices[..0], 0));
        }
        let n = self.leaves as usize;
        let needed = 2 * n - 1;
        if nodes.len() < needed {
            return Err(Error::NodeCapacity {
                needed,
                available: nodes.len(),
            });
        }
        if indices.len() < n {
            return Err(Error::IndexCapacity {
                needed: n,
                available: indices.len(),
            });
        }
        let depth = super::emit_layout(self.root, nodes, indices, |d| {
            let node = &self.nodes[d as usize];
            let kind = if node.is_leaf() {
                Err(node.item)
            } else {
                Ok((node.left, node.right))
            };
            (node.bv, kind)
        })?;
        let done = collapse.apply(nodes, needed, depth)?;
        let bound = crate::tree::index_bound_of(&indices[..n]);
        let report = BuildReport {
            depth_limited: self.forced_rebalances,
            max_leaf_size: collapse.max_leaf_size(),
            ..BuildReport::default()
        };
        Ok(
            Bvh::from_built_ids(&nodes[..done.count], &indices[..n], done.depth, bound)
                .with_build_report(report),
        )
    }
}

/// Every query runs on the dynamic tree directly, with no copy into a
/// [`Bvh`]: region, ray, nearest and pair queries (with every traversal and
/// descent rule), and a [`Bvh`] or layout against it.
///
/// Node ids are storage indices; a leaf holds one object, its id the
/// `item` given to [`insert`](DynamicTree::insert). A query takes the
/// objects' primitives as a slice indexed by those ids (long enough for the
/// largest live id; ids need not be dense), and tests them at the leaves:
/// the answer is exact for the primitives given, not for the fat volumes.
/// That needs each primitive's bounds inside its leaf's fat volume, which
/// holds when the slice holds what was last given to `insert` or `update`.
///
/// ```
/// use bvhkit::builders::{DynNode, DynamicConfig, DynamicTree};
/// use bvhkit::{Aabb, Pairs, Query};
/// use glam::Vec3;
/// // Ten moving boxes; the slice of their current bounds is the primitives.
/// let mut boxes: Vec<Aabb> = (0..10)
///     .map(|i| Aabb::new(Vec3::new(i as f32, 0.0, 0.0), Vec3::new(i as f32 + 0.5, 0.5, 0.5)))
///     .collect();
/// let mut storage = vec![DynNode::<Aabb>::EMPTY; 2 * 10 - 1];
/// let config = DynamicConfig { margin: 0.2, ..Default::default() };
/// let mut tree = DynamicTree::new(&mut storage, config)?;
/// let handles: Vec<_> = (0..10).map(|i| tree.insert(i, &boxes[i as usize])).collect::<Result<_, _>>()?;
/// // Box 3 moves onto box 4.
/// boxes[3] = Aabb::new(Vec3::new(3.8, 0.0, 0.0), Vec3::new(4.3, 0.5, 0.5));
/// tree.update(handles[3], &boxes[3])?;
/// // A region query, straight on the tree.
/// let region = Aabb::new(Vec3::new(4.1, 0.0, 0.0), Vec3::new(4.2, 1.0, 1.0));
/// let mut hits = Vec::new();
/// tree.overlapping(&boxes, &region, |i| hits.push(i))?;
/// hits.sort();
/// assert_eq!(hits, [3, 4]);
/// // A pair query of the tree against itself: (3, 4) and (4, 3), and every box with itself.
/// let pairs = Pairs::new(&tree, &boxes, &tree, &boxes).count()?;
/// assert_eq!(pairs, 10 + 2);
/// # Ok::<(), bvhkit::Error>(())
/// ```
impl<B: BoundingVolume> crate::tree::Hierarchy for DynamicTree<'_, B> {
    type Bv = B;
    const ARITY: usize = 2;

    #[inline(always)]
    fn root(&self) -> u32 {
        self.root
    }

    #[inline(always)]
    fn bv(&self, node: u32) -> B {
        self.nodes[node as usize].bv
    }

    #[inline(always)]
    fn content(&self, node: u32) -> crate::tree::Content<'_> {
        let n = &self.nodes[node as usize];
        if n.is_leaf() {
            crate::tree::Content::Leaf(core::slice::from_ref(&n.item))
        } else {
            crate::tree::Content::Inner(crate::tree::Kids::two(n.left, n.right))
        }
    }

    #[inline(always)]
    fn is_leaf(&self, node: u32) -> bool {
        self.nodes[node as usize].is_leaf()
    }

    fn depth(&self) -> usize {
        self.height()
    }

    fn primitive_count(&self) -> usize {
        self.len()
    }

    fn index_bound(&self) -> usize {
        if self.is_empty() {
            0
        } else {
            (self.max_item as usize).saturating_add(1)
        }
    }

    fn dense_ids(&self) -> bool {
        false
    }

    fn node_count(&self) -> usize {
        (2 * self.len()).saturating_sub(1)
    }

    fn bytes(&self) -> usize {
        self.node_count() * core::mem::size_of::<DynNode<B>>()
    }
}

/// The order in which [`Insertion`] inserts the primitives. The lectures
/// note that insertion results depend on it; `bvhkit tour` measures how much.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InsertOrder {
    /// As given.
    Given,
    /// A seeded random permutation (reproducible).
    Shuffled(u64),
    /// Sorted by centre along the longest axis of the centres' box: the
    /// adversarial order (each object lands at the end of a growing row).
    Sorted,
}

/// Insertion construction as a builder: every primitive inserted in turn
/// (in the chosen [`InsertOrder`]), then written in the query layout.
///
/// ```
/// use bvhkit::builders::{DynNode, Insertion};
/// use bvhkit::{Aabb, Node, Triangle};
/// use glam::Vec3;
/// let tris: Vec<Triangle> = (0..50).map(|i| {
///     let o = Vec3::new(i as f32, (i % 7) as f32, 0.0);
///     Triangle::new(o, o + Vec3::X, o + Vec3::Y)
/// }).collect();
/// let mut storage = vec![DynNode::<Aabb>::EMPTY; 99];
/// let mut order = vec![0u32; 50];
/// let mut nodes = vec![Node::<Aabb>::EMPTY; 99];
/// let mut idx = vec![0u32; 50];
/// let bvh = Insertion::default().build(&tris, &mut storage, &mut order, &mut nodes, &mut idx)?;
/// assert_eq!(bvh.primitive_count(), 50);
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Insertion {
    /// Tree options (margin is usually 0 for a static build).
    pub config: DynamicConfig,
    /// Insertion order.
    pub order: InsertOrder,
    /// What becomes of the one-object leaves once every object is in.
    pub collapse: Collapse,
}

impl Default for Insertion {
    fn default() -> Self {
        Insertion {
            config: DynamicConfig::default(),
            order: InsertOrder::Shuffled(0x5eed),
            collapse: Collapse::default(),
        }
    }
}

impl Insertion {
    /// Buffer lengths for `n` primitives: `(storage, order)` = `(2n - 1, n)`
    /// (plus [`max_nodes`](crate::max_nodes)`(n)` nodes and `n` indices for
    /// the output tree). A `const fn`, to size `static` buffers:
    ///
    /// ```
    /// use bvhkit::builders::{DynNode, Insertion};
    /// use bvhkit::Aabb;
    /// const STORAGE: usize = Insertion::scratch_len(64).0;
    /// static STORAGE_NODES: [DynNode<Aabb>; STORAGE] = [DynNode::EMPTY; STORAGE];
    /// assert_eq!((STORAGE, Insertion::scratch_len(64).1), (127, 64));
    /// ```
    pub const fn scratch_len(n: usize) -> (usize, usize) {
        crate::Capacity::for_primitives(n).insertion
    }

    /// Builds: `storage` needs `2n - 1` nodes, `order` `n` words, `nodes`
    /// `2n - 1` and `indices` `n`.
    pub fn build<'a, B: BoundingVolume, P: Primitive>(
        &self,
        prims: &[P],
        storage: &mut [DynNode<B>],
        order: &mut [u32],
        nodes: &'a mut [Node<B>],
        indices: &'a mut [u32],
    ) -> Result<Bvh<'a, B>, Error> {
        validate(prims)?;
        let n = prims.len();
        if n == 0 {
            return Ok(Bvh::from_built(&nodes[..0], &indices[..0], 0));
        }
        if order.len() < n {
            return Err(Error::IndexCapacity {
                needed: n,
                available: order.len(),
            });
        }
        let needed = 2 * n - 1;
        if storage.len() < needed {
            return Err(Error::NodeCapacity {
                needed,
                available: storage.len(),
            });
        }
        let order = &mut order[..n];
        for (i, o) in order.iter_mut().enumerate() {
            *o = i as u32;
        }
        if self.order == InsertOrder::Sorted {
            let mut centres = Aabb::EMPTY;
            for p in prims {
                centres.grow(p.bounds().center());
            }
            let axis = centres.longest_axis();
            order.sort_unstable_by(|&i, &j| {
                let (ci, cj) = (
                    prims[i as usize].bounds().center()[axis],
                    prims[j as usize].bounds().center()[axis],
                );
                ci.total_cmp(&cj).then(i.cmp(&j))
            });
        }
        if let InsertOrder::Shuffled(seed) = self.order {
            // Fisher–Yates with SplitMix64: reproducible for a given seed.
            let mut state = seed;
            for i in (1..n).rev() {
                state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
                let mut z = state;
                z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
                z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
                z ^= z >> 31;
                order.swap(i, (z % (i as u64 + 1)) as usize);
            }
        }
        let mut tree = DynamicTree::new(&mut storage[..needed], self.config)?;
        for &i in order.iter() {
            tree.insert(i, &prims[i as usize].bounds())?;
        }
        tree.to_bvh_with(nodes, indices, self.collapse)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_at(x: f32) -> Aabb {
        Aabb::new(Vec3::new(x, 0.0, 0.0), Vec3::new(x + 1.0, 1.0, 1.0))
    }

    #[test]
    fn area_rotation_picks_the_swap_that_shrinks_the_changed_child_most() {
        let (a, b, c) = (unit_at(0.0), unit_at(1.0), unit_at(9.0));
        let bc = b.union(&c);
        // Left leaf `a`, right node over (b, c): `c` goes up, `a` down.
        assert_eq!(
            area_rotation([&a, &bc], [None, Some([&b, &c])]),
            Some(AreaRotation { down: 0, up: 1 })
        );
        // The same the other way round, and with the grandchildren swapped.
        assert_eq!(
            area_rotation([&bc, &a], [Some([&c, &b]), None]),
            Some(AreaRotation { down: 1, up: 0 })
        );
        // Two leaves, or a node already in its best shape: nothing.
        assert_eq!(area_rotation::<Aabb>([&a, &c], [None, None]), None);
        let ab = a.union(&b);
        assert_eq!(area_rotation([&c, &ab], [None, Some([&a, &b])]), None);
        // Both children inner: of four swaps, the one that saves most. Left
        // over (0, 1), right over (2, 30): the left node moving down beside
        // 2 lifts 30 out of the right one.
        let (l0, l1, r0, r1) = (unit_at(0.0), unit_at(1.0), unit_at(2.0), unit_at(30.0));
        let (l, r) = (l0.union(&l1), r0.union(&r1));
        let got = area_rotation([&l, &r], [Some([&l0, &l1]), Some([&r0, &r1])]);
        assert_eq!(got, Some(AreaRotation { down: 0, up: 1 }));
        let got = area_rotation([&r, &l], [Some([&r1, &r0]), Some([&l1, &l0])]);
        assert_eq!(got, Some(AreaRotation { down: 1, up: 0 }));
        // Two swaps that both save: the larger saving wins even when it
        // comes first (b at -9 moving up leaves the right child 0..6; c
        // moving up would leave -9..1).
        let (b, c) = (unit_at(-9.0), unit_at(5.0));
        let bc = b.union(&c);
        assert_eq!(
            area_rotation([&a, &bc], [None, Some([&b, &c])]),
            Some(AreaRotation { down: 0, up: 0 })
        );
        // Two swaps saving the same: the first in order.
        let (b, c) = (unit_at(-9.0), unit_at(9.0));
        let bc = b.union(&c);
        assert_eq!(
            area_rotation([&a, &bc], [None, Some([&b, &c])]),
            Some(AreaRotation { down: 0, up: 0 })
        );
        // A swap that keeps the area exactly is not made.
        let same = a.union(&a);
        assert_eq!(area_rotation([&a, &same], [None, Some([&a, &a])]), None);
        // Far from unit size, the same choice.
        let s = |x: f32| {
            Aabb::new(
                Vec3::new(x, 0.0, 0.0) * 1e30,
                Vec3::new(x + 1.0, 1.0, 1.0) * 1e30,
            )
        };
        let (a, b, c) = (s(0.0), s(1.0), s(9.0));
        assert_eq!(
            area_rotation([&a, &b.union(&c)], [None, Some([&b, &c])]),
            Some(AreaRotation { down: 0, up: 1 })
        );
    }

    #[test]
    fn area_rotations_keep_a_sorted_line_shallow_and_cheap() {
        let n = 256;
        let mut plain = [DynNode::<Aabb>::EMPTY; 511];
        let mut area = [DynNode::<Aabb>::EMPTY; 511];
        let off = DynamicConfig {
            rotations: Rotations::Off,
            ..Default::default()
        };
        let by_area = DynamicConfig {
            rotations: Rotations::Area,
            ..Default::default()
        };
        let mut t_off = DynamicTree::new(&mut plain, off).unwrap();
        let mut t_area = DynamicTree::new(&mut area, by_area).unwrap();
        for i in 0..n {
            t_off.insert(i, &unit_at(i as f32 * 2.0)).unwrap();
            t_area.insert(i, &unit_at(i as f32 * 2.0)).unwrap();
        }
        t_area.validate().unwrap();
        let (area, off) = (t_area.area_sum(), t_off.area_sum());
        assert!(area < 0.5 * off, "{area} against {off}");
        let (h_area, h_off) = (t_area.height(), t_off.height());
        assert!(h_area < h_off, "{h_area} against {h_off}");
    }

    #[test]
    fn optimize_goes_on_where_it_stopped_and_repairs_a_chain() {
        let mut storage = [DynNode::<Aabb>::EMPTY; 2 * 64 - 1];
        let config = DynamicConfig {
            rotations: Rotations::Off,
            ..Default::default()
        };
        let mut tree = DynamicTree::new(&mut storage, config).unwrap();
        let mut handles = [LeafHandle::from_parts(0, 0); 64];
        for (i, h) in handles.iter_mut().enumerate().take(2) {
            *h = tree.insert(i as u32, &unit_at(i as f32 * 2.0)).unwrap();
        }
        // Two objects: nothing to gain.
        assert_eq!(tree.optimize(10), Ok(0));
        // Three: up to four nodes besides the root, and every leaf (the
        // root's slot can change as nodes move, so one slot may be skipped).
        handles[2] = tree.insert(2, &unit_at(4.0)).unwrap();
        let moved = tree.optimize(10).unwrap();
        assert!((3..=4).contains(&moved), "{moved}");
        for (i, h) in handles.iter_mut().enumerate().skip(3) {
            *h = tree.insert(i as u32, &unit_at(i as f32 * 2.0)).unwrap();
        }
        assert_eq!(tree.optimize(0), Ok(0));
        let (area, height) = (tree.area_sum(), tree.height());
        // 127 nodes, the root stays: a pass is 126 moves, in three calls.
        assert_eq!(tree.optimize(50), Ok(50));
        assert_eq!(tree.optimize(50), Ok(50));
        let rest = tree.optimize(1000).unwrap();
        assert!((20..=126).contains(&rest), "{rest}");
        tree.validate().unwrap();
        assert!(
            tree.area_sum() < 0.6 * area,
            "{} against {area}",
            tree.area_sum()
        );
        assert!(tree.height() < height / 2);
        for (i, &h) in handles.iter().enumerate() {
            assert_eq!(tree.item(h), Ok(i as u32));
        }
    }

    /// The branch-and-bound search as it was before it took a seed bound
    /// from a greedy path: the seeded search must pick the same sibling.
    fn unseeded(tree: &DynamicTree<'_, Aabb>, bv: &Aabb) -> u32 {
        let scale = unit_scale(&tree.nodes[tree.root as usize].bv.merge(bv).aabb());
        let mut best = (f64::INFINITY, tree.root);
        let mut stack = [(NULL, 0.0f64); 2 * MAX_DEPTH + 2];
        stack[0] = (tree.root, 0.0);
        let mut top = 1;
        let own = area_in(bv, scale);
        while top > 0 {
            top -= 1;
            let (n, inherited) = stack[top];
            let node = &tree.nodes[n as usize];
            let direct = area_in(&node.bv.merge(bv), scale);
            if direct + inherited < best.0 {
                best = (direct + inherited, n);
            }
            let below = inherited + direct - area_in(&node.bv, scale);
            if !node.is_leaf() && own + below < best.0 && top + 2 <= stack.len() {
                stack[top] = (node.right, below);
                stack[top + 1] = (node.left, below);
                top += 2;
            }
        }
        best.1
    }

    /// On random boxes and on a grid (where costs tie), in trees grown by
    /// the search itself, every new box gets the sibling the unseeded
    /// search gives it.
    #[test]
    fn the_seeded_search_picks_the_unseeded_sibling() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 40) as f32 / (1u64 << 24) as f32
        };
        for grid in [false, true] {
            let mut storage = [DynNode::<Aabb>::EMPTY; 2 * 300 - 1];
            let mut tree = DynamicTree::new(&mut storage, DynamicConfig::default()).unwrap();
            let mut checked = 0;
            for i in 0..300 {
                let at = if grid {
                    Vec3::new((i % 7) as f32, ((i / 7) % 6) as f32, (i / 42) as f32)
                } else {
                    Vec3::new(next(), next(), next()) * 40.0
                };
                let b = Aabb::new(at, at + Vec3::splat(if grid { 1.0 } else { 0.5 + next() }));
                if tree.root != NULL {
                    let fat = tree.fat(i, &b).unwrap();
                    assert_eq!(tree.best_sibling(&fat), unseeded(&tree, &fat), "box {i}");
                    checked += 1;
                }
                tree.insert(i, &b).unwrap();
            }
            assert_eq!(checked, 299);
        }
    }

    /// The size the embedded chapter quotes for its storage formula.
    /// The largest live id bounds what a query reads, whatever the order
    /// of insertion: ids 5 then 2 need 6 primitives, and 3 is refused
    /// (not read past its end); after 5 leaves, 3 are enough.
    #[test]
    fn the_largest_id_bounds_the_primitives_a_query_needs() {
        use crate::query::Query;
        let boxes: [Aabb; 6] = core::array::from_fn(|i| unit_at(i as f32));
        let mut storage = [DynNode::<Aabb>::EMPTY; 3];
        let mut tree = DynamicTree::new(&mut storage, DynamicConfig::default()).unwrap();
        let five = tree.insert(5, &boxes[5]).unwrap();
        tree.insert(2, &boxes[2]).unwrap();
        let everything = Aabb::new(Vec3::splat(-1.0), Vec3::splat(10.0));
        assert_eq!(tree.overlapping(&boxes, &everything, |_| {}), Ok(2));
        assert!(tree.overlapping(&boxes[..3], &everything, |_| {}).is_err());
        tree.remove(five).unwrap();
        assert_eq!(tree.overlapping(&boxes[..3], &everything, |_| {}), Ok(1));
    }

    #[test]
    fn a_node_of_boxes_is_48_bytes() {
        assert_eq!(core::mem::size_of::<DynNode<Aabb>>(), 48);
    }

    /// Freeing blanks the node (it no longer reads as a leaf of any
    /// generation), links it, and advances its generation, wrapping.
    #[test]
    fn a_released_node_is_blank_linked_and_in_the_next_generation() {
        let leaf = DynNode {
            bv: Aabb::new(Vec3::ZERO, Vec3::ONE),
            parent: 3,
            left: NULL,
            right: NULL,
            item: 9,
            height: 0,
            generation: u32::MAX,
        };
        assert!(leaf.is_live_leaf(u32::MAX) && !leaf.is_live_leaf(0));
        let freed = leaf.released(5);
        assert_eq!(
            freed,
            DynNode {
                parent: 5,
                generation: 0,
                ..DynNode::EMPTY
            }
        );
        assert!(!freed.is_live_leaf(0) && !freed.is_live_leaf(u32::MAX));
    }

    /// Boxes of varied sizes on a small grid (many touch exactly), from a
    /// fixed generator.
    fn grid_boxes(n: usize, seed: u64) -> alloc_free::Boxes {
        let mut s = seed;
        let mut next = move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 40) as u32
        };
        let mut out = alloc_free::Boxes::new();
        for _ in 0..n {
            let lo = Vec3::new(
                (next() % 12) as f32,
                (next() % 12) as f32,
                (next() % 12) as f32,
            ) * 0.5;
            let size = Vec3::new(
                (next() % 4 + 1) as f32,
                (next() % 4 + 1) as f32,
                (next() % 4 + 1) as f32,
            ) * 0.5;
            out.push(Aabb::new(lo, lo + size)).unwrap();
        }
        out
    }

    /// Fixed-size buffers, so the tests need no allocator.
    mod alloc_free {
        pub type Boxes = heapless::Vec<super::Aabb, 200>;
        pub type Pairs = heapless::Vec<(u32, u32), 20_000>;
    }

    fn brute_pairs(boxes: &[Aabb]) -> alloc_free::Pairs {
        let mut want = alloc_free::Pairs::new();
        for i in 0..boxes.len() {
            for j in i + 1..boxes.len() {
                if boxes[i].overlaps(&boxes[j]) {
                    want.push((i as u32, j as u32)).unwrap();
                }
            }
        }
        want
    }

    fn box_pairs(tree: &DynamicTree<'_, Aabb>, boxes: &[Aabb]) -> alloc_free::Pairs {
        let mut got = alloc_free::Pairs::new();
        tree.for_each_box_pair(boxes, |i, j| {
            assert_ne!(i, j);
            got.push((i.min(j), i.max(j))).unwrap();
        })
        .unwrap();
        got.sort_unstable();
        got
    }

    #[test]
    fn the_box_pair_walk_finds_the_brute_force_pairs_once_each() {
        for (n, margin) in [(0, 0.0), (1, 0.0), (2, 0.0), (37, 0.0), (150, 0.25)] {
            let boxes = grid_boxes(n, 0x9e37_79b9 + n as u64);
            let mut storage = [DynNode::<Aabb>::EMPTY; 2 * 150];
            let config = DynamicConfig {
                margin,
                ..DynamicConfig::default()
            };
            let mut tree = DynamicTree::new(&mut storage, config).unwrap();
            for (i, b) in boxes.iter().enumerate() {
                tree.insert(i as u32, b).unwrap();
            }
            let want = brute_pairs(&boxes);
            assert!(n < 37 || want.len() > n, "a scene with many touching pairs");
            assert_eq!(box_pairs(&tree, &boxes), want, "{n} boxes");
            // Too few boxes for the largest id: an error, not a panic.
            if n > 0 {
                assert!(tree.for_each_box_pair(&boxes[..n - 1], |_, _| {}).is_err());
            }
        }
    }

    #[test]
    fn a_rebuild_in_order_lays_the_tree_out_depth_first_with_new_handles() {
        let boxes = grid_boxes(150, 7);
        let mut storage = [DynNode::<Aabb>::EMPTY; 2 * 150 + 5];
        let config = DynamicConfig {
            margin: 0.1,
            ..DynamicConfig::default()
        };
        let mut tree = DynamicTree::new(&mut storage, config).unwrap();
        let mut old = [LeafHandle::from_parts(0, 0); 150];
        for (i, b) in boxes.iter().enumerate() {
            old[i] = tree.insert(i as u32, b).unwrap();
        }
        // Object 3 leaves: 149 objects, ids with a gap.
        tree.remove(old[3]).unwrap();
        let mut items = [0u32; 150];
        let mut k = 0;
        for i in (0..150u32).filter(|&i| i != 3) {
            items[k] = i;
            k += 1;
        }
        // A bad box is refused, and the tree is as it was.
        let mut bad = boxes.clone();
        bad[5].max.y = f32::NAN;
        assert!(tree
            .rebuild_in_order(&mut items[..k], &bad, |_, _, _| {})
            .is_err());
        assert!(tree.contains(old[0]));
        assert_eq!(tree.len(), 149);
        // So are more objects than the storage holds.
        let mut small = [DynNode::<Aabb>::EMPTY; 5];
        let mut small = DynamicTree::new(&mut small, config).unwrap();
        assert!(matches!(
            small.rebuild_in_order(&mut [0, 1, 2, 4], &boxes, |_, _, _| {}),
            Err(Error::NodeCapacity { needed: 7, .. })
        ));
        assert!(small.is_empty());
        let mut new = [None; 150];
        tree.rebuild_in_order(&mut items[..k], &boxes, |item, leaf, fat| {
            assert_eq!(
                *fat,
                Aabb::new(
                    boxes[item as usize].min - 0.1,
                    boxes[item as usize].max + 0.1
                )
            );
            new[item as usize] = Some(leaf);
        })
        .unwrap();
        tree.validate().unwrap();
        assert_eq!(tree.len(), 149);
        for i in 0..150 {
            assert!(!tree.contains(old[i]), "every old handle is stale");
            assert_eq!(new[i].is_some(), i != 3);
            if let Some(leaf) = new[i] {
                assert_eq!(tree.item(leaf).unwrap(), i as u32);
            }
        }
        // Depth first from slot 0: each inner node's left child is the
        // next slot, and the tree fills slots 0..2n-1.
        assert_eq!(tree.root, 0);
        for (at, node) in tree.nodes[..2 * 149 - 1].iter().enumerate() {
            assert_ne!(node.height, u32::MAX, "slot {at} in use");
            if !node.is_leaf() {
                assert_eq!(node.left as usize, at + 1);
            }
        }
        // The pairs are the same, and the free slots take new objects.
        let mut present = [Aabb::new(Vec3::splat(1e6), Vec3::splat(1e6)); 150];
        for i in (0..150).filter(|&i| i != 3) {
            present[i] = boxes[i];
        }
        let want = brute_pairs(&present);
        assert_eq!(box_pairs(&tree, &present), want);
        let again = tree.insert(3, &boxes[3]).unwrap();
        assert!(again.index() >= 2 * 149 - 1);
        tree.validate().unwrap();
        assert_eq!(box_pairs(&tree, &boxes), brute_pairs(&boxes));
    }

    #[test]
    fn a_refit_in_place_keeps_the_shape_and_reports_the_area_change() {
        let boxes = grid_boxes(60, 11);
        let mut storage = [DynNode::<Aabb>::EMPTY; 2 * 60];
        let config = DynamicConfig {
            margin: 0.05,
            ..DynamicConfig::default()
        };
        let mut tree = DynamicTree::new(&mut storage, config).unwrap();
        let mut leaves = [LeafHandle::from_parts(0, 0); 60];
        for (i, b) in boxes.iter().enumerate() {
            leaves[i] = tree.insert(i as u32, b).unwrap();
        }
        let mut moved = boxes.clone();
        let mut area = tree.inner_area_sum();
        for i in (0..60).step_by(3) {
            let d = Vec3::new(3.0, -1.0, 0.5) * (i % 5) as f32;
            moved[i] = Aabb::new(boxes[i].min + d, boxes[i].max + d);
            let height = tree.height();
            let (fat, grown) = tree.refit_leaf(leaves[i], &moved[i]).unwrap();
            assert_eq!(fat, tree.fat_bounds(leaves[i]).unwrap());
            assert!(fat.contains(&moved[i]));
            area += grown;
            let exact = tree.inner_area_sum();
            assert!(
                (area - exact).abs() <= 1e-9 * exact,
                "{area} against {exact}"
            );
            assert_eq!(tree.height(), height, "the shape is unchanged");
        }
        tree.validate().unwrap();
        assert_eq!(box_pairs(&tree, &moved), brute_pairs(&moved));
        // A bad box changes nothing.
        let nan = Aabb::new(Vec3::splat(f32::NAN), Vec3::ONE);
        assert!(tree.refit_leaf(leaves[0], &nan).is_err());
        tree.validate().unwrap();
    }

    #[test]
    fn leaves_given_new_boxes_then_one_refit_of_every_inner_node() {
        // Grown by insertion: nodes lie anywhere in the storage.
        let boxes = grid_boxes(80, 5);
        let mut storage = [DynNode::<Aabb>::EMPTY; 2 * 80];
        let mut tree = DynamicTree::new(&mut storage, DynamicConfig::default()).unwrap();
        let mut leaves = [LeafHandle::from_parts(0, 0); 80];
        for (i, b) in boxes.iter().enumerate() {
            leaves[i] = tree.insert(i as u32, b).unwrap();
        }
        let mut moved = boxes.clone();
        for i in (0..80).step_by(2) {
            let d = Vec3::new(-2.0, 4.0, 1.0) * (i % 7) as f32;
            moved[i] = Aabb::new(boxes[i].min + d, boxes[i].max + d);
            let fat = tree.set_leaf_fat(leaves[i], &moved[i]).unwrap();
            assert_eq!(fat, tree.fat_bounds(leaves[i]).unwrap());
        }
        let area = tree.inner_area_sum(); // before: the old inner boxes
        let sum = tree.refit_inner();
        assert_ne!(sum, area);
        assert_eq!(sum, tree.inner_area_sum());
        // Every inner node is exactly its children's union.
        let mut inner = 0;
        for node in tree.nodes.iter().filter(|n| n.height != u32::MAX) {
            if !node.is_leaf() {
                let (l, r) = (
                    &tree.nodes[node.left as usize],
                    &tree.nodes[node.right as usize],
                );
                assert_eq!(node.bv, l.bv.union(&r.bv));
                inner += 1;
            }
        }
        assert_eq!(inner, 79);
        tree.validate().unwrap();
        assert_eq!(box_pairs(&tree, &moved), brute_pairs(&moved));
        // A bad box is refused and changes nothing.
        let nan = Aabb::new(Vec3::splat(f32::NAN), Vec3::ONE);
        assert!(tree.set_leaf_fat(leaves[1], &nan).is_err());
        assert!(tree.fat_bounds(leaves[1]).unwrap().contains(&moved[1]));
    }
}
