//! An incremental broad phase: the overlapping pairs of many moving
//! objects, kept from step to step, with begin and end events.
//!
//! Lecture: *collision detection system*, the broad phase, for objects that
//! move. Rebuilding a tree over every object and querying it against itself
//! each step costs the same whether one object moved or all did. Here the
//! objects live in a [`DynamicTree`] with fat leaves (a small move costs
//! nothing), and a step queries only the objects that moved: a pair of two
//! objects that both stayed put cannot have changed. The new pair list is
//! the old one without the movers' pairs, plus the movers' new pairs; the
//! difference is reported as [`PairEvent::Begin`] and [`PairEvent::End`].
//! When more than a quarter of the objects moved, one walk of the whole
//! tree against itself is cheaper than a query per mover, and is used
//! instead (the same answer as [`SelfPairs`](crate::query::SelfPairs), by a
//! walk cut to a box tree with one object per leaf). Boxes that left their
//! fat leaves are taken into the tree at the step, all together: a few are
//! reinserted one by one; when many left theirs (a scene where most things
//! move), each such leaf takes its new fat box where it is and the nodes
//! above it are refitted, and only once the tree has grown loose is it
//! rebuilt, laid out in the order the walk visits it (as it is once
//! insertions and reinsertions since the last rebuild reach half the
//! objects: each took a free node wherever it lay, and a scattered tree
//! makes every walk wait on memory).
//!
//! Measured against parry3d's `Bvh` (refit and incremental optimisation
//! each frame) by `scripts/bench-peers --broad-phase` on drifting boxes:
//! reinserting the leaves that left their fat boxes and rebuilding with a
//! median split made a step 2.5-2.7x parry3d's time when every box moved;
//! refits in place, rebuilds in walk order and the cut-down walk bring it
//! to about parity (medians of five runs: 1.17x on 10,000 boxes, 0.98x on
//! 100,000), and to 0.48x and 0.62x with one box in ten moving.
//!
//! A pair is two objects whose current boxes overlap (touching counts),
//! decided on the boxes given, not on the fat leaves: the same answer as
//! [`brute_force::self_pairs`](crate::brute_force::self_pairs) over the
//! boxes of the objects present.

use crate::builders::{DynNode, DynamicConfig, DynamicTree, LeafHandle, NULL};
use crate::bv::{xyz_all, Aabb};
use crate::query::Query;
use crate::Error;

/// What changed about a pair of objects (`a < b`) since the last step.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum PairEvent {
    /// The two boxes overlap now and did not before.
    Begin(u32, u32),
    /// The two boxes overlapped before and do not now (or one object left).
    End(u32, u32),
}

/// One object's slot of a [`PairTracker`] (caller storage: one per id).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Slot {
    /// Whether the slot holds an object.
    present: bool,
    /// Its leaf in the tree; `None` for an empty slot, and for an object
    /// that arrived since the last step (it joins the tree at the step).
    leaf: Option<LeafHandle>,
    /// Its leaf's fat box, kept here so that a move is checked against it
    /// without a visit to the tree.
    fat: Aabb,
    /// Whether it moved (or arrived) since the last step.
    moved: bool,
    /// Whether its box left its fat leaf since the last step: the tree
    /// learns the new box at the next step.
    stale: bool,
}

impl Slot {
    /// An empty slot, for initialising storage.
    pub const EMPTY: Slot = Slot {
        present: false,
        leaf: None,
        fat: Aabb::EMPTY,
        moved: false,
        stale: false,
    };
}

/// The caller's storage for a [`PairTracker`] of up to `n` objects and `m`
/// pairs: `2n - 1` tree nodes, `n` slots, `n` boxes, `n` entries for the
/// movers, and two pair lists of `m` entries (the current one and the
/// next).
#[derive(Debug)]
pub struct TrackerStorage<'s> {
    /// Nodes of the dynamic tree.
    pub nodes: &'s mut [DynNode<Aabb>],
    /// One slot per object id.
    pub slots: &'s mut [Slot],
    /// One box per object id (the primitives the tree is queried with).
    pub boxes: &'s mut [Aabb],
    /// Ids of the objects that moved since the last step.
    pub moved: &'s mut [u32],
    /// The current pairs.
    pub pairs: &'s mut [(u32, u32)],
    /// Room for the next step's pairs. With room for twice as many pairs
    /// as a step finds (in this buffer and in `pairs`), the step sorts
    /// them by radix in the spare half, which costs about half as much as
    /// sorting by comparison.
    pub next: &'s mut [(u32, u32)],
}

/// The pairs of overlapping boxes among moving objects, updated
/// incrementally. Objects are named by ids below the slot count.
///
/// ```
/// use bvhkit::collision::{PairEvent, PairTracker, Slot, TrackerStorage};
/// use bvhkit::builders::{DynNode, DynamicConfig};
/// use bvhkit::Aabb;
/// use glam::Vec3;
/// let unit = |x: f32| Aabb::new(Vec3::new(x, 0.0, 0.0), Vec3::new(x + 1.0, 1.0, 1.0));
/// let (mut nodes, mut slots) = ([DynNode::EMPTY; 7], [Slot::EMPTY; 4]);
/// let (mut boxes, mut moved) = ([Aabb::EMPTY; 4], [0u32; 4]);
/// let (mut pairs, mut next) = ([(0, 0); 6], [(0, 0); 6]);
/// let storage = TrackerStorage {
///     nodes: &mut nodes, slots: &mut slots, boxes: &mut boxes,
///     moved: &mut moved, pairs: &mut pairs, next: &mut next,
/// };
/// let mut world = PairTracker::new(storage, DynamicConfig { margin: 0.1, ..Default::default() })?;
/// for (id, x) in [0.0, 0.5, 3.0, 9.0].into_iter().enumerate() {
///     world.insert(id as u32, &unit(x))?;
/// }
/// let mut events = Vec::new();
/// world.step(|e| events.push(e))?;
/// assert_eq!(events, [PairEvent::Begin(0, 1)]);
/// // Object 2 slides onto object 1 and away from nothing else.
/// world.set_bounds(2, &unit(1.2))?;
/// events.clear();
/// world.step(|e| events.push(e))?;
/// assert_eq!(events, [PairEvent::Begin(1, 2)]);
/// assert_eq!(world.pairs(), [(0, 1), (1, 2)]);
/// // Object 1 leaves: both its pairs end.
/// world.remove(1)?;
/// events.clear();
/// world.step(|e| events.push(e))?;
/// assert_eq!(events, [PairEvent::End(0, 1), PairEvent::End(1, 2)]);
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Debug)]
pub struct PairTracker<'s> {
    tree: DynamicTree<'s, Aabb>,
    slots: &'s mut [Slot],
    boxes: &'s mut [Aabb],
    moved: &'s mut [u32],
    movers: usize,
    /// Objects that arrived since the last step, not yet in the tree.
    arrivals: usize,
    /// Objects whose box left their fat leaf since the last step.
    stale: usize,
    /// Set when a step rebuilt the tree and cleared the movers before it
    /// could finish: the next step must recheck every pair.
    recheck_all: bool,
    pairs: &'s mut [(u32, u32)],
    count: usize,
    next: &'s mut [(u32, u32)],
    /// The inner nodes' total area after the last rebuild; `None` before
    /// the first.
    settled_area: Option<f64>,
    /// Insertions and reinsertions since the last rebuild.
    churn: usize,
    /// The inner nodes' total area now, as the refits since the last
    /// rebuild moved it (the few leaves reinserted are not counted: they
    /// move it little, and each rebuild measures it afresh).
    area: f64,
}

/// More stale leaves than one object in `BULK` are refitted in place, not
/// reinserted one by one.
const BULK: usize = 32;

/// More stale leaves than one object in `SWEEP` are refitted by one walk
/// over the whole tree, not each up from its leaf.
const SWEEP: usize = 8;

/// A tree whose inner area grew past `LOOSE` times its settled area is
/// rebuilt. Chosen by the whole step's instructions (cachegrind, 10,000
/// drifting boxes, 100 frames): 1.05 took 3% more than 1.1, 1.2 2% fewer,
/// 1.3 as many as 1.1, 1.5 5% more (walks over a looser tree).
const LOOSE: f64 = 1.2;

/// Trees of fewer objects are not rebuilt for their churn (see
/// `take_in_stale`): they fit in cache however they lie.
const CHURN_FROM: usize = 64;

/// What one [`PairTracker::step`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StepReport {
    /// Objects queried (moved, arrived or left since the last step).
    pub queried: usize,
    /// Pairs that began.
    pub begun: usize,
    /// Pairs that ended.
    pub ended: usize,
    /// Pairs now.
    pub pairs: usize,
}

impl<'s> PairTracker<'s> {
    /// An empty broad phase over `storage` (ids `0..storage.slots.len()`).
    /// Errors: a buffer shorter than the slots need, or a bad `config`.
    pub fn new(storage: TrackerStorage<'s>, config: DynamicConfig) -> Result<Self, Error> {
        let n = storage.slots.len();
        let short = |needed: usize, available: usize| Error::ScratchCapacity { needed, available };
        if storage.nodes.len() < (2 * n).saturating_sub(1) {
            return Err(Error::NodeCapacity {
                needed: 2 * n - 1,
                available: storage.nodes.len(),
            });
        }
        if storage.boxes.len() < n {
            return Err(short(n, storage.boxes.len()));
        }
        if storage.moved.len() < n {
            return Err(short(n, storage.moved.len()));
        }
        if storage.next.len() < storage.pairs.len() {
            return Err(short(storage.pairs.len(), storage.next.len()));
        }
        if n >= NULL as usize {
            return Err(Error::IndexOverflow { count: n });
        }
        let tree = DynamicTree::new(storage.nodes, config)?;
        storage.slots.fill(Slot::EMPTY);
        Ok(PairTracker {
            tree,
            slots: storage.slots,
            boxes: storage.boxes,
            moved: storage.moved,
            movers: 0,
            arrivals: 0,
            stale: 0,
            recheck_all: false,
            pairs: storage.pairs,
            count: 0,
            next: storage.next,
            settled_area: None,
            churn: 0,
            area: 0.0,
        })
    }

    /// The dynamic tree over the objects: every query runs on it, with
    /// [`boxes`](Self::boxes) as the primitives. It is the tree of the last
    /// [`step`](Self::step): a box given since then that left its object's
    /// fat leaf is taken in at the next step, so query it after a step.
    pub fn tree(&self) -> &DynamicTree<'s, Aabb> {
        &self.tree
    }

    /// The objects' boxes, by id (empty slots hold an empty box).
    pub fn boxes(&self) -> &[Aabb] {
        self.boxes
    }

    /// The pairs `(a, b)`, `a < b`, as of the last step, sorted.
    pub fn pairs(&self) -> &[(u32, u32)] {
        &self.pairs[..self.count]
    }

    /// Objects present (those that arrived since the last step included).
    pub fn len(&self) -> usize {
        self.tree.len() + self.arrivals
    }

    /// Whether no object is present.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    fn slot(&self, id: u32) -> Result<usize, Error> {
        if (id as usize) < self.slots.len() {
            Ok(id as usize)
        } else {
            Err(Error::InvalidConfig("object id past the tracker's slots"))
        }
    }

    fn mark(&mut self, i: usize) {
        if !self.slots[i].moved {
            self.slots[i].moved = true;
            self.moved[self.movers] = i as u32;
            self.movers += 1;
        }
    }

    /// Adds object `id` with box `bounds`; it joins the tree, and its pairs
    /// begin, at the next step. Arrivals wait for the step because many of
    /// them (a scene's first frame) make the step rebuild the tree over
    /// every object, which costs less than inserting them one by one did
    /// (30 of the 44 ms that 10,000 boxes took to their first pairs).
    /// Errors: an id past the slots or already present, a bad box (the
    /// object is not added then).
    pub fn insert(&mut self, id: u32, bounds: &Aabb) -> Result<(), Error> {
        let i = self.slot(id)?;
        if self.slots[i].present {
            return Err(Error::InvalidConfig("object id already present"));
        }
        let fat = self.tree.fat(id, bounds)?;
        self.churn += 1;
        self.arrivals += 1;
        self.slots[i].present = true;
        self.slots[i].leaf = None;
        self.slots[i].fat = fat;
        self.boxes[i] = *bounds;
        self.mark(i);
        Ok(())
    }

    /// Gives object `id` its new box; the object's pairs are rechecked at
    /// the next step (only if the box changed). No tree work here: a box
    /// inside the object's fat leaf never needs any, and a box that left
    /// it is taken into the tree at the next step, all at once (see
    /// [`step`](Self::step)). Errors: an id not present, a bad box (nothing
    /// changes then).
    #[inline]
    pub fn set_bounds(&mut self, id: u32, bounds: &Aabb) -> Result<(), Error> {
        // Called for every object every frame: lane-wise tests, and the
        // slot read once.
        let i = self.slot(id)?;
        let slot = self.slots[i];
        if !slot.present {
            return Err(Error::InvalidConfig("object id not present"));
        }
        let (lo, hi) = bounds.lanes();
        let (old_lo, old_hi) = self.boxes[i].lanes();
        if xyz_all((lo.cmpeq(old_lo) & hi.cmpeq(old_hi)).bitmask()) {
            return Ok(());
        }
        self.tree.check(id, bounds)?;
        let (fat_lo, fat_hi) = slot.fat.lanes();
        let inside_fat = xyz_all((fat_lo.cmple(lo) & hi.cmple(fat_hi)).bitmask());
        if slot.leaf.is_none() {
            // Not in the tree yet: it joins with this box.
            self.slots[i].fat = self.tree.fattened(bounds); // checked above
        } else if !slot.stale && !inside_fat {
            // It left its fat leaf.
            self.slots[i].stale = true;
            self.stale += 1;
        }
        self.boxes[i] = *bounds;
        if !slot.moved {
            self.slots[i].moved = true;
            self.moved[self.movers] = id;
            self.movers += 1;
        }
        Ok(())
    }

    /// Takes every box that left its fat leaf into the tree, before a step
    /// queries it. A few: a box that drifted just past its margin (it
    /// still overlaps its old fat box) grows its leaf in place and the
    /// nodes above it, as in bulk; one that jumped is reinserted where its
    /// sibling search puts it (grown in place, it would stretch every node
    /// between its old and new places). Growing in place took 10,000
    /// drifting boxes, one in ten moving, from 345M to 310M instructions
    /// over 100 frames (a reinsertion cost about 8,000). Many (more than
    /// one object in [`BULK`]: a scene where most things move): each such
    /// leaf takes its new fat box where it is, and the nodes above it are
    /// refitted, which costs a fraction of a sibling search and leaves the
    /// tree's shape alone. Once that shape has grown loose (the inner
    /// nodes' total area [`LOOSE`] times what it was when last settled),
    /// the tree is rebuilt over every object, laid out in walk order
    /// ([`DynamicTree`]'s `rebuild_in_order`). The tree
    /// is rebuilt too once insertions and reinsertions since the last
    /// rebuild reach half the objects (from [`CHURN_FROM`] objects on):
    /// each new leaf takes a free node wherever it lies in the storage, so
    /// a tree grown or kept up that way scatters, and walks over it wait on
    /// memory (one object in ten moving: 0.95x parry3d's step time on
    /// 100,000 boxes before, 0.62x after). Errors: a
    /// leaf that could not be reinserted (see [`DynamicTree::update`]);
    /// that object leaves the tree, its pairs end at the next step, and the
    /// other boxes are still taken in.
    fn take_in_stale(&mut self) -> Result<(), Error> {
        if self.churn * 2 > self.len() && self.len() >= CHURN_FROM {
            return self.rebuild();
        }
        let arrived = self.attach_arrivals();
        let moved = self.take_in_moved();
        arrived.and(moved)
    }

    /// Inserts the objects that arrived since the last step, one by one
    /// (too few for the churn rule to rebuild). Errors: one that could not
    /// be inserted (it leaves; the others are still inserted).
    fn attach_arrivals(&mut self) -> Result<(), Error> {
        let mut first_error = None;
        for k in 0..self.movers {
            if self.arrivals == 0 {
                break;
            }
            let i = self.moved[k] as usize;
            let slot = self.slots[i];
            if !slot.present || slot.leaf.is_some() {
                continue;
            }
            self.arrivals -= 1;
            match self.tree.insert(i as u32, &self.boxes[i]) {
                Ok(leaf) => self.slots[i].leaf = Some(leaf),
                Err(e) => {
                    self.drop_object(i);
                    first_error.get_or_insert(e);
                }
            }
        }
        first_error.map_or(Ok(()), Err)
    }

    /// Takes the boxes that left their fat leaves into the tree (see
    /// [`take_in_stale`](Self::take_in_stale)).
    fn take_in_moved(&mut self) -> Result<(), Error> {
        if self.stale == 0 {
            return Ok(());
        }
        if self.stale * BULK > self.tree.len() {
            let sweep = self.stale * SWEEP > self.tree.len();
            for &m in &self.moved[..self.movers] {
                let slot = &mut self.slots[m as usize];
                if let (true, Some(leaf)) = (slot.stale, slot.leaf) {
                    // Checked when it was given: cannot fail.
                    if sweep {
                        slot.fat = self.tree.set_leaf_fat(leaf, &self.boxes[m as usize])?;
                    } else {
                        let (fat, grown) = self.tree.refit_leaf(leaf, &self.boxes[m as usize])?;
                        slot.fat = fat;
                        self.area += grown;
                    }
                }
                slot.stale = false;
            }
            if sweep {
                self.area = self.tree.refit_inner();
            }
            self.stale = 0;
            // A bulk step before any rebuild (a tree too small for the churn
            // rule) rebuilds too: its area has nothing to be compared with.
            if self
                .settled_area
                .is_some_and(|settled| self.area <= settled * LOOSE)
            {
                return Ok(());
            }
            return self.rebuild();
        }
        let mut first_error = None;
        for k in 0..self.movers {
            let i = self.moved[k] as usize;
            let slot = self.slots[i];
            let (true, Some(leaf)) = (slot.stale, slot.leaf) else {
                continue;
            };
            self.slots[i].stale = false;
            self.stale -= 1;
            if slot.fat.overlaps(&self.boxes[i]) {
                // Drifted just past its margin: its leaf grows in place.
                // Checked when it was given: cannot fail.
                let (fat, grown) = self.tree.refit_leaf(leaf, &self.boxes[i])?;
                self.slots[i].fat = fat;
                self.area += grown;
                continue;
            }
            let before = self.tree.len();
            let updated = self.tree.update(leaf, &self.boxes[i]);
            self.churn += 1;
            if let Ok(fat) = self.tree.fat_bounds(leaf) {
                self.slots[i].fat = fat;
            }
            if let Err(e) = updated {
                if self.tree.len() < before {
                    // It left the tree: its pairs end at the next step.
                    self.drop_object(i);
                }
                first_error.get_or_insert(e);
            }
        }
        if self
            .settled_area
            .is_some_and(|settled| self.area > settled * LOOSE)
        {
            self.rebuild()?;
        }
        first_error.map_or(Ok(()), Err)
    }

    /// Rebuilds the tree over every object present, in walk order. Its
    /// scratch is the movers' list: every pair is rechecked in this step
    /// anyway (most objects moved), so the list is emptied on the way, and
    /// a flag makes the next step recheck every pair should this one stop
    /// before it finishes.
    fn rebuild(&mut self) -> Result<(), Error> {
        for &m in &self.moved[..self.movers] {
            self.slots[m as usize].moved = false;
        }
        self.movers = 0;
        self.recheck_all = true;
        let mut present = 0;
        for (id, slot) in self.slots.iter().enumerate() {
            if slot.present {
                self.moved[present] = id as u32;
                present += 1;
            }
        }
        let slots = &mut *self.slots;
        self.tree
            .rebuild_in_order(&mut self.moved[..present], self.boxes, |id, leaf, fat| {
                slots[id as usize].leaf = Some(leaf);
                slots[id as usize].fat = *fat;
                // Made afresh around its object's box: no longer stale.
                slots[id as usize].stale = false;
            })?;
        self.stale = 0;
        self.arrivals = 0;
        self.area = self.tree.inner_area_sum();
        self.settled_area = Some(self.area);
        self.churn = 0;
        Ok(())
    }

    fn drop_object(&mut self, i: usize) {
        if self.slots[i].stale {
            self.slots[i].stale = false;
            self.stale -= 1;
        }
        self.slots[i].present = false;
        self.slots[i].leaf = None;
        self.boxes[i] = Aabb::EMPTY;
        self.mark(i);
    }

    /// Removes object `id`; its pairs end at the next step.
    pub fn remove(&mut self, id: u32) -> Result<(), Error> {
        let i = self.slot(id)?;
        if !self.slots[i].present {
            return Err(Error::InvalidConfig("object id not present"));
        }
        match self.slots[i].leaf {
            Some(leaf) => self.tree.remove(leaf)?,
            None => {
                // Never joined the tree.
                self.arrivals -= 1;
                self.churn = self.churn.saturating_sub(1);
            }
        }
        self.drop_object(i);
        Ok(())
    }

    /// Brings the pair list up to date: first takes into the tree every box
    /// that left its fat leaf (see [`set_bounds`](Self::set_bounds)), then
    /// queries the tree with the box of every object that moved, arrived or
    /// left since the last step, calls `f` with each change (ends first,
    /// then begins, each group sorted), and keeps the new list. Errors: the
    /// pair buffers are full (the pair list does not change then, and the
    /// next step rechecks every pair it would have); a leaf that could not
    /// be reinserted (see [`DynamicTree::update`]: that object leaves the
    /// tree and its pairs end at the next step).
    pub fn step(&mut self, mut f: impl FnMut(PairEvent)) -> Result<StepReport, Error> {
        // Movers counted before the boxes are taken in: a rebuild clears them.
        let queried = self.movers;
        self.take_in_stale()?;
        let cap = self.next.len().min(self.pairs.len());
        let movers = self.movers;
        let moved = |slots: &[Slot], id: u32| slots[id as usize].moved;
        if self.recheck_all || movers > self.tree.len() / 4 {
            // Most objects moved: one self query of the whole tree shares
            // the walk from the root that a query per mover would repeat.
            let mut found = 0;
            let next = &mut *self.next;
            self.tree.for_each_box_pair(self.boxes, |a, b| {
                if found < cap {
                    next[found] = (a.min(b), a.max(b));
                }
                found += 1;
            })?;
            if found > cap {
                return Err(Error::ResultCapacity {
                    found,
                    capacity: cap,
                });
            }
            let (found_pairs, scratch) = self.next[..cap].split_at_mut(found);
            sort_pairs(found_pairs, scratch, self.slots.len());
            return Ok(self.finish(queried, found, &mut f));
        }
        // The old pairs with no mover in them stay as they are.
        let old = &self.pairs[..self.count];
        let stays = |&(a, b): &(u32, u32)| !moved(self.slots, a) && !moved(self.slots, b);
        let kept = old.iter().filter(|p| stays(p)).count();
        // Each mover's pairs, found by one region query with its box, go to
        // the end of `next`, last first. A pair of two movers is taken from
        // the smaller id's query only.
        let room = cap - kept.min(cap);
        let mut fresh = 0;
        for &m in &self.moved[..movers] {
            let slot = self.slots[m as usize];
            if slot.leaf.is_none() {
                continue; // left: its pairs simply are not found again
            }
            let slots = &*self.slots;
            let next = &mut *self.next;
            self.tree
                .overlapping(self.boxes, &self.boxes[m as usize], |x| {
                    if x == m || (moved(slots, x) && x < m) {
                        return;
                    }
                    if fresh < room {
                        next[cap - 1 - fresh] = (m.min(x), m.max(x));
                    }
                    fresh += 1;
                })?;
        }
        let found = kept + fresh;
        if found > cap {
            return Err(Error::ResultCapacity {
                found,
                capacity: cap,
            });
        }
        // Sort the new pairs and merge them with the kept ones into the
        // front of `next`: the write position never passes the next new
        // pair to read, as kept + new fits the buffer.
        let tail = cap - fresh;
        // Nothing is kept in the front yet: it is the sort's scratch.
        let (scratch, fresh_pairs) = self.next[..cap].split_at_mut(tail);
        sort_pairs(fresh_pairs, scratch, self.slots.len());
        let (mut w, mut j) = (0, tail);
        for p in old.iter().filter(|p| stays(p)) {
            while j < cap && self.next[j] < *p {
                self.next[w] = self.next[j];
                w += 1;
                j += 1;
            }
            self.next[w] = *p;
            w += 1;
        }
        while j < cap {
            self.next[w] = self.next[j];
            w += 1;
            j += 1;
        }
        Ok(self.finish(queried, found, &mut f))
    }

    /// Reports the difference between the old list and the `found` sorted
    /// pairs in `next` (ends first), makes `next` the list, clears the movers.
    fn finish(
        &mut self,
        queried: usize,
        found: usize,
        f: &mut impl FnMut(PairEvent),
    ) -> StepReport {
        let (old, new) = (&self.pairs[..self.count], &self.next[..found]);
        let mut report = StepReport {
            queried,
            pairs: found,
            ..StepReport::default()
        };
        diff(old, new, |p| {
            f(PairEvent::End(p.0, p.1));
            report.ended += 1;
        });
        diff(new, old, |p| {
            f(PairEvent::Begin(p.0, p.1));
            report.begun += 1;
        });
        core::mem::swap(&mut self.pairs, &mut self.next);
        self.count = found;
        for &m in &self.moved[..self.movers] {
            self.slots[m as usize].moved = false;
        }
        self.movers = 0;
        self.recheck_all = false;
        report
    }
}

/// Fewer pairs than this are sorted by comparison: a radix pass costs a
/// fixed 256 counts whatever the number of pairs.
const RADIX_FROM: usize = 128;

/// Sorts pairs of ids below `ids` as the tuples' order does. With room for
/// a copy in `scratch`, by a least-significant-digit radix sort over the
/// ids' bits, 8 at a time (ids below 10,000: 4 passes, each reading every
/// pair twice and writing it once); otherwise, or for a few pairs, by
/// comparison on one `u64` key. The radix sort took the step's sorting
/// from about 170 instructions a pair to about 80 (10,000 drifting boxes).
fn sort_pairs(pairs: &mut [(u32, u32)], scratch: &mut [(u32, u32)], ids: usize) {
    let n = pairs.len();
    if n < RADIX_FROM || scratch.len() < n {
        pairs.sort_unstable_by_key(|&(a, b)| (u64::from(a) << 32) | u64::from(b));
    } else {
        radix_sort_pairs(pairs, scratch, ids);
    }
}

/// The radix sort of [`sort_pairs`], in a frame of its own: its 1 KB of
/// digit counts is on the stack only while it runs, never for the few
/// pairs of a small scene (a microcontroller's stack budget).
#[inline(never)]
fn radix_sort_pairs(pairs: &mut [(u32, u32)], scratch: &mut [(u32, u32)], ids: usize) {
    let n = pairs.len();
    // The second ids' digits first, then the first ids': each pass keeps
    // the order of the last among equal digits.
    let id_bits = usize::BITS - ids.saturating_sub(1).leading_zeros();
    let digits = (0..id_bits).step_by(8);
    let passes = digits.clone().map(|s| (1, s)).chain(digits.map(|s| (0, s)));
    let (mut src, mut dst) = (&mut *pairs, &mut scratch[..n]);
    let mut in_scratch = false;
    for (first, shift) in passes {
        let digit =
            |&(a, b): &(u32, u32)| (((if first == 0 { a } else { b }) >> shift) & 0xff) as usize;
        let mut start = [0u32; 256];
        for p in src.iter() {
            start[digit(p)] += 1;
        }
        if start.iter().any(|&c| c as usize == n) {
            continue; // one digit for all: the order stands
        }
        let mut sum = 0;
        for c in &mut start {
            (*c, sum) = (sum, sum + *c);
        }
        for p in src.iter() {
            let d = digit(p);
            dst[start[d] as usize] = *p;
            start[d] += 1;
        }
        core::mem::swap(&mut src, &mut dst);
        in_scratch = !in_scratch;
    }
    if in_scratch {
        dst.copy_from_slice(src);
    }
}

/// Calls `f` with every entry of sorted `a` that is not in sorted `b`.
fn diff(a: &[(u32, u32)], b: &[(u32, u32)], mut f: impl FnMut((u32, u32))) {
    let mut j = 0;
    for &p in a {
        while j < b.len() && b[j] < p {
            j += 1;
        }
        if j == b.len() || b[j] != p {
            f(p);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bv::BoundingVolume;
    use crate::tree::{Content, Hierarchy};
    use glam::Vec3;

    const N: usize = 300;
    const ROOM: usize = 3000;

    /// Storage for `N` objects and `ROOM` pairs, on the stack.
    struct Buffers {
        nodes: [DynNode<Aabb>; 2 * N - 1],
        slots: [Slot; N],
        boxes: [Aabb; N],
        moved: [u32; N],
        pairs: [(u32, u32); ROOM],
        next: [(u32, u32); ROOM],
    }

    impl Buffers {
        fn new() -> Self {
            Buffers {
                nodes: [DynNode::EMPTY; 2 * N - 1],
                slots: [Slot::EMPTY; N],
                boxes: [Aabb::EMPTY; N],
                moved: [0; N],
                pairs: [(0, 0); ROOM],
                next: [(0, 0); ROOM],
            }
        }

        fn storage(&mut self) -> TrackerStorage<'_> {
            TrackerStorage {
                nodes: &mut self.nodes,
                slots: &mut self.slots,
                boxes: &mut self.boxes,
                moved: &mut self.moved,
                pairs: &mut self.pairs,
                next: &mut self.next,
            }
        }
    }

    /// Whether every inner node reachable from the root has its left child
    /// in the next storage slot: the depth-first layout of a rebuild.
    fn laid_out_in_walk_order(tree: &DynamicTree<'_, Aabb>) -> bool {
        let mut stack = [NULL; 2 * crate::tree::MAX_DEPTH + 2];
        let (mut top, mut in_order) = (1, tree.root() == 0);
        stack[0] = tree.root();
        while top > 0 {
            top -= 1;
            if let Content::Inner(kids) = tree.content(stack[top]) {
                let kids = kids.of_arity(2);
                in_order &= kids[0] == stack[top] + 1;
                stack[top] = kids[0];
                stack[top + 1] = kids[1];
                top += 2;
            }
        }
        in_order
    }

    /// The tracker's pairs are brute force's over `boxes` (every slot holds
    /// an object).
    fn pairs_are_brute_force(world: &PairTracker<'_>, boxes: &[Aabb]) -> bool {
        let mut k = 0;
        let got = world.pairs();
        for i in 0..boxes.len() {
            for j in i + 1..boxes.len() {
                if boxes[i].overlaps(&boxes[j]) {
                    if got.get(k) != Some(&(i as u32, j as u32)) {
                        return false;
                    }
                    k += 1;
                }
            }
        }
        k == got.len()
    }

    #[test]
    fn arrivals_join_the_tree_at_the_step() {
        let mut buffers = Buffers::new();
        let storage = buffers.storage();
        let mut world = PairTracker::new(storage, DynamicConfig::default()).unwrap();
        let mut current = [Aabb::EMPTY; N];
        for (i, b) in current.iter_mut().enumerate() {
            let o = Vec3::new((i % 17) as f32, (i / 17) as f32, 0.0) * 0.9;
            *b = Aabb::new(o, o + 1.0);
            world.insert(i as u32, b).unwrap();
        }
        // Before the step: counted, not in the tree; one leaves, one moves.
        assert_eq!((world.len(), world.tree().len()), (N, 0));
        world.remove(7).unwrap();
        current[7] = Aabb::new(Vec3::splat(1e6), Vec3::splat(1e6));
        current[8] = Aabb::new(Vec3::splat(-30.0), Vec3::splat(-29.0));
        world.set_bounds(8, &current[8]).unwrap();
        assert!(world.insert(9, &current[9]).is_err(), "already present");
        assert_eq!((world.len(), world.churn), (N - 1, N - 1));
        // So many arrivals: the step builds the tree over them at once.
        world.step(|_| {}).unwrap();
        world.tree().validate().unwrap();
        assert_eq!((world.len(), world.tree().len()), (N - 1, N - 1));
        assert!(laid_out_in_walk_order(world.tree()));
        assert!(pairs_are_brute_force(&world, &current));
        // A few arrivals join one by one.
        current[7] = Aabb::new(Vec3::ZERO, Vec3::splat(2.0));
        world.insert(7, &current[7]).unwrap();
        assert_eq!(world.tree().len(), N - 1);
        world.step(|_| {}).unwrap();
        world.tree().validate().unwrap();
        assert_eq!(world.tree().len(), N);
        assert!(pairs_are_brute_force(&world, &current));
    }

    #[test]
    fn a_few_drifting_boxes_grow_their_leaves_and_jumping_ones_are_reinserted() {
        let mut buffers = Buffers::new();
        let margin = 0.1;
        let config = DynamicConfig {
            margin,
            ..Default::default()
        };
        let mut world = PairTracker::new(buffers.storage(), config).unwrap();
        let mut current = [Aabb::EMPTY; N];
        for (i, b) in current.iter_mut().enumerate() {
            let o = Vec3::new((i % 17) as f32, (i / 17) as f32, 0.0) * 1.5;
            *b = Aabb::new(o, o + 1.0);
            world.insert(i as u32, b).unwrap();
        }
        world.step(|_| {}).unwrap();
        let settled = world.settled_area.unwrap();
        // One box drifts just past its margin: its leaf stays where it is
        // and grows; the nodes above it grow with it.
        let leaf = world.slots[5].leaf.unwrap();
        let drift = Vec3::new(2.0 * margin, 0.0, 0.0);
        current[5] = Aabb::new(current[5].min + drift, current[5].max + drift);
        world.set_bounds(5, &current[5]).unwrap();
        world.step(|_| {}).unwrap();
        world.tree().validate().unwrap();
        assert!(pairs_are_brute_force(&world, &current));
        assert_eq!(world.churn, 0, "refitted, not reinserted");
        assert_eq!(world.slots[5].leaf, Some(leaf));
        assert!(world.slots[5].fat.contains(&current[5]));
        assert_eq!(world.tree().fat_bounds(leaf), Ok(world.slots[5].fat));
        // Another jumps across the scene: reinserted where it landed, not
        // stretching the nodes between its old and new places.
        current[6] = Aabb::new(Vec3::new(20.0, 20.0, 0.0), Vec3::new(21.0, 21.0, 1.0));
        world.set_bounds(6, &current[6]).unwrap();
        world.step(|_| {}).unwrap();
        world.tree().validate().unwrap();
        assert!(pairs_are_brute_force(&world, &current));
        assert_eq!(world.churn, 1, "reinserted");
        // Drifting far enough, a box's grown leaves loosen the tree past
        // `LOOSE` times its settled area: the tree is rebuilt.
        let mut rebuilt = false;
        for _ in 0..400 {
            current[5] = Aabb::new(current[5].min + drift, current[5].max + drift);
            world.set_bounds(5, &current[5]).unwrap();
            world.step(|_| {}).unwrap();
            assert!(pairs_are_brute_force(&world, &current));
            if world.churn == 0 {
                rebuilt = true;
                break;
            }
        }
        assert!(rebuilt, "area {} settled {settled}", world.area);
        assert!(laid_out_in_walk_order(world.tree()));
    }

    #[test]
    fn a_tree_grown_or_kept_up_by_insertions_is_rebuilt_in_walk_order() {
        // At the origin, and far from it (f32 spacing 1/16 at 1e6: moves
        // round, boxes touch exactly).
        for origin in [Vec3::ZERO, Vec3::new(1e6, -1e6, 1e6)] {
            churn_rebuilds_from(origin);
        }
    }

    fn churn_rebuilds_from(origin: Vec3) {
        let mut buffers = Buffers::new();
        let storage = buffers.storage();
        let config = DynamicConfig {
            margin: 0.05,
            ..Default::default()
        };
        let mut world = PairTracker::new(storage, config).unwrap();
        let mut s = 0x9e37_79b9_7f4a_7c15u64;
        let mut next_f = move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 40) as f32 / (1u64 << 24) as f32
        };
        let mut spot = || origin + Vec3::new(next_f(), next_f(), next_f()) * 12.0;
        let mut current = [Aabb::EMPTY; N];
        for (i, b) in current.iter_mut().enumerate() {
            let o = spot();
            *b = Aabb::new(o, o + 1.0);
            world.insert(i as u32, b).unwrap();
        }
        // 300 arrivals: the first step lays the tree out.
        world.step(|_| {}).unwrap();
        assert!(pairs_are_brute_force(&world, &current));
        assert!(laid_out_in_walk_order(world.tree()));
        assert_eq!(world.churn, 0);
        // One object in forty jumps each step: too few to refit in bulk,
        // each is reinserted, until the churn rebuilds the tree.
        let mut rebuilt = 0;
        for step in 0..60 {
            for i in (step % 40..N).step_by(40) {
                let o = spot();
                current[i] = Aabb::new(o, o + 1.0);
                world.set_bounds(i as u32, &current[i]).unwrap();
            }
            let churn = world.churn;
            world.step(|_| {}).unwrap();
            world.tree().validate().unwrap();
            assert!(pairs_are_brute_force(&world, &current), "step {step}");
            // Every box that left its fat leaf was taken in.
            assert_eq!(world.stale, 0, "step {step}");
            assert!(world
                .slots
                .iter()
                .zip(world.boxes.iter())
                .all(|(s, b)| !s.stale && s.fat.contains(b)));
            if world.churn < churn {
                rebuilt += 1;
                assert!(laid_out_in_walk_order(world.tree()));
            }
        }
        assert!(rebuilt >= 2, "{rebuilt} rebuilds");
    }

    #[test]
    fn pairs_sort_as_tuples_with_or_without_scratch() {
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move |below: u32| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed % u64::from(below)) as u32
        };
        // Sizes on both sides of the radix threshold; id ranges from one
        // bit (passes skipped as one digit) to the whole u32 range.
        for n in [0, 1, 5, RADIX_FROM - 1, RADIX_FROM, 1000] {
            for ids in [1usize, 2, 300, 70_000, 1 << 32] {
                let below = u32::try_from(ids).unwrap_or(u32::MAX);
                let mut pairs = [(0, 0); 1000];
                pairs[..n].fill_with(|| (next(below), next(below)));
                let mut expected = pairs;
                expected[..n].sort_unstable();
                for room in [0, n.saturating_sub(1), n, 2 * n + 3] {
                    let mut got = pairs;
                    let mut scratch = [(7, 7); 2003];
                    sort_pairs(&mut got[..n], &mut scratch[..room], ids);
                    assert_eq!(
                        got[..n],
                        expected[..n],
                        "{n} pairs, ids below {ids}, room {room}"
                    );
                }
            }
        }
    }
}
