//! Bottom-up construction: start from the primitives and merge clusters.
//!
//! Lecture: *bottom-up construction*. Every primitive starts as a cluster;
//! the two clusters whose merged volume is smallest are merged, until one
//! cluster (the root) remains. Two methods:
//!
//! - [`Method::Exhaustive`]: the textbook algorithm, searching all pairs at
//!   every step: `O(n^2)` per merge, `O(n^3)` in all. Meant for teaching and
//!   as a reference; use it for n up to a few hundred.
//! - [`Method::Ploc`]: locally-ordered clustering (Meister and Bittner, 2018):
//!   primitives sorted along a Morton curve, each cluster looks for its best
//!   partner only among `radius` neighbours on each side, and all mutual best
//!   pairs merge at once. About `O(n * radius)` per round and `O(log n)`
//!   rounds; builds trees of the same kind at scale.
//!
//! Both need caller scratch ([`BottomUp::scratch_len`]); nothing allocates.

use super::{BuildReport, Collapse};
use crate::bv::{Aabb, BoundingVolume};
use crate::primitive::{validate_bounds, Primitive};
use crate::tree::{Bvh, Node, MAX_DEPTH};
use crate::Error;

/// What "smallest merged volume" measures.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum MergeMetric {
    /// Surface area of the merged volume (the SAH's measure). The default.
    #[default]
    SurfaceArea,
    /// Volume of the merged volume.
    Volume,
}

/// How pairs are searched.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// All pairs at every step: `O(n^3)`.
    Exhaustive,
    /// Locally-ordered clustering with a search radius (16 is common).
    Ploc {
        /// Neighbours searched on each side along the Morton order (1..=64).
        radius: u32,
    },
}

/// One cluster of the bottom-up scratch: its volume and its two parts
/// (`left == right` marks a single primitive, stored in `left`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cluster<B> {
    /// Volume around the cluster.
    pub bv: B,
    /// First part (cluster id), or the primitive for a single-primitive cluster.
    pub left: u32,
    /// Second part (cluster id); equal to `left` for a single primitive.
    pub right: u32,
}

impl<B: BoundingVolume> Cluster<B> {
    /// A blank cluster, for initialising scratch.
    pub const EMPTY: Self = Cluster {
        bv: B::EMPTY,
        left: 0,
        right: 0,
    };

    /// A cluster of zero bits, for initialising scratch that the builder
    /// overwrites anyway: a `static` array of it goes to `.bss`, and a
    /// vector of it can come from zeroed pages instead of being filled.
    pub const ZERO: Self = Cluster {
        bv: B::ZERO,
        left: 0,
        right: 0,
    };
}

/// Caller-provided scratch for a bottom-up build over `n` primitives; sizes
/// from [`BottomUp::scratch_len`].
#[derive(Debug)]
pub struct BottomUpScratch<'s, B> {
    /// At least `2n - 1` clusters, or none at all where
    /// [`BottomUp::needs_clusters`] says so (PLOC without a collapse): such
    /// a build refuses a tree deeper than [`MAX_DEPTH`](crate::MAX_DEPTH)
    /// instead of rebuilding its deep subtrees balanced here.
    pub clusters: &'s mut [Cluster<B>],
    /// At least `2n` words (active list and neighbour table).
    pub work: &'s mut [u32],
    /// At least `2n` keys (Morton codes and their sort's second buffer;
    /// unused by the exhaustive method).
    pub keys: &'s mut [u64],
}

/// A bottom-up builder.
///
/// ```
/// use bvhkit::builders::{BottomUp, BottomUpScratch, Cluster, Method, MergeMetric};
/// use bvhkit::{Aabb, Node, Triangle};
/// use glam::Vec3;
/// let tris: Vec<Triangle> = (0..100).map(|i| {
///     let o = Vec3::new((i % 10) as f32, (i / 10) as f32, 0.0);
///     Triangle::new(o, o + Vec3::X * 0.8, o + Vec3::Y * 0.8)
/// }).collect();
/// let builder = BottomUp { method: Method::Ploc { radius: 8 }, ..BottomUp::default() };
/// let (nc, nw, nk) = BottomUp::scratch_len(tris.len());
/// let mut clusters = vec![Cluster::<Aabb>::EMPTY; nc];
/// let (mut work, mut keys) = (vec![0u32; nw], vec![0u64; nk]);
/// let mut scratch = BottomUpScratch { clusters: &mut clusters, work: &mut work, keys: &mut keys };
/// let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(tris.len())];
/// let mut idx = vec![0u32; tris.len()];
/// let bvh = builder.build(&tris, &mut nodes, &mut idx, &mut scratch)?;
/// // One triangle per leaf, then up to 4 where the SAH says so.
/// assert!(bvh.node_count() <= 199 && bvh.build_report().max_leaf_size == 4);
/// assert!(bvh.depth() < 20);
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BottomUp {
    /// Pair search.
    pub method: Method,
    /// What a merge minimises.
    pub metric: MergeMetric,
    /// What becomes of the one-primitive leaves once the merges are done.
    pub collapse: Collapse,
}

impl Default for BottomUp {
    fn default() -> Self {
        BottomUp {
            method: Method::Ploc { radius: 16 },
            metric: MergeMetric::SurfaceArea,
            collapse: Collapse::default(),
        }
    }
}

impl BottomUp {
    /// The textbook exhaustive builder (`O(n^3)`), one primitive per leaf
    /// as the lectures describe it ([`Collapse::None`]).
    pub const fn exhaustive(metric: MergeMetric) -> Self {
        BottomUp {
            method: Method::Exhaustive,
            metric,
            collapse: Collapse::None,
        }
    }

    /// Scratch lengths for `n` primitives: `(clusters, work, keys)` =
    /// `(2n - 1, 2n, 2n)`. In bytes: `(2n - 1) * (size_of::<B>() + 8) + 8n + 16n`.
    pub const fn scratch_len(n: usize) -> (usize, usize, usize) {
        crate::Capacity::for_primitives(n).bottom_up
    }

    /// Whether [`build`](Self::build) needs [`BottomUpScratch::clusters`]
    /// in full: PLOC without a collapse builds in `nodes` and reads the
    /// clusters only to limit a tree deeper than
    /// [`MAX_DEPTH`](crate::MAX_DEPTH).
    pub const fn needs_clusters(&self) -> bool {
        !matches!(self.method, Method::Ploc { .. }) || self.collapse.max_leaf_size() > 1
    }

    /// Builds a tree into `nodes` (at least [`max_nodes(n)`](crate::max_nodes))
    /// and `indices` (at least `n`): one primitive per leaf, then the
    /// [`Collapse`] of the configuration.
    ///
    /// Empty input builds the empty tree. Errors: non-finite input, buffers too small, an invalid
    /// radius, or a tree deeper than [`MAX_DEPTH`](crate::MAX_DEPTH) (possible for adversarial
    /// input such as exponentially spaced points; the error says how deep).
    pub fn build<'a, B: BoundingVolume, P: Primitive>(
        &self,
        prims: &[P],
        nodes: &'a mut [Node<B>],
        indices: &'a mut [u32],
        scratch: &mut BottomUpScratch<'_, B>,
    ) -> Result<Bvh<'a, B>, Error> {
        let (scene, centres) = validate_bounds(prims)?;
        let n = prims.len();
        if n == 0 {
            return Ok(Bvh::from_built(&nodes[..0], &indices[..0], 0));
        }
        let (nc, nw, nk) = Self::scratch_len(n);
        if nodes.len() < nc {
            return Err(Error::NodeCapacity {
                needed: nc,
                available: nodes.len(),
            });
        }
        if indices.len() < n {
            return Err(Error::IndexCapacity {
                needed: n,
                available: indices.len(),
            });
        }
        let uses_keys = matches!(self.method, Method::Ploc { .. });
        if (self.needs_clusters() && scratch.clusters.len() < nc)
            || scratch.work.len() < nw
            || (uses_keys && scratch.keys.len() < nk)
        {
            return Err(Error::InvalidConfig(
                "bottom-up scratch too small: see BottomUp::scratch_len",
            ));
        }
        if let Method::Ploc { radius } = self.method {
            if !(1..=64).contains(&radius) {
                return Err(Error::InvalidConfig("PLOC radius must be in 1..=64"));
            }
        }
        let clusters = &mut *scratch.clusters;
        let mut report = BuildReport {
            max_leaf_size: self.collapse.max_leaf_size(),
            ..BuildReport::default()
        };
        let root = match self.method {
            Method::Exhaustive => {
                let active = &mut scratch.work[..n];
                for (i, p) in prims.iter().enumerate() {
                    clusters[i] = Cluster {
                        bv: B::from_aabb(&p.bounds()),
                        left: i as u32,
                        right: i as u32,
                    };
                    active[i] = i as u32;
                }
                exhaustive(clusters, active, n, self.metric, unit_scale(&scene))
            }
            Method::Ploc { radius } => {
                let scale = unit_scale(&scene);
                let depth = ploc(
                    prims,
                    morton_order(prims, &centres, &mut scratch.keys[..2 * n]),
                    nodes,
                    indices,
                    scratch.work,
                    radius as usize,
                    |bv: &B| cost(bv, self.metric, scale),
                );
                if depth as usize <= MAX_DEPTH && self.collapse.max_leaf_size() <= 1 {
                    // Already in the query layout, one primitive per leaf.
                    return Ok(Bvh::from_built(&nodes[..nc], &indices[..n], depth)
                        .with_build_report(report));
                }
                // Too deep, or to be collapsed (which rewrites a depth-first
                // layout in place): the tree goes to the clusters and comes
                // back depth first, as the exhaustive method's does.
                if clusters.len() < nc {
                    return Err(Error::StackOverflow {
                        depth: depth as usize,
                        capacity: MAX_DEPTH,
                    });
                }
                for (s, node) in nodes[..nc].iter().enumerate() {
                    let (left, right) = if node.count > 0 {
                        let prim = indices[node.first as usize];
                        (prim, prim)
                    } else {
                        (node.first, node.first + 1)
                    };
                    clusters[s] = Cluster {
                        bv: node.bv,
                        left,
                        right,
                    };
                }
                0
            }
        };
        let emit = |clusters: &[Cluster<B>], nodes: &mut [Node<B>], indices: &mut [u32]| {
            super::emit_layout(root, nodes, indices, |c| {
                let cl = &clusters[c as usize];
                let kind = if cl.left == cl.right {
                    Err(cl.left)
                } else {
                    Ok((cl.left, cl.right))
                };
                (cl.bv, kind)
            })
        };
        let depth = match emit(clusters, nodes, indices) {
            Err(Error::StackOverflow { .. }) => {
                // Merging the cheapest pairs can make a chain (primitives
                // growing geometrically along a line: each merge is cheapest
                // at the small end). Depth is no reason to refuse: every
                // subtree hanging below depth MAX_DEPTH / 2 is rebuilt
                // balanced over its primitives, in their order along it.
                report.depth_limited = bound_depth(clusters, root, n, scratch.work);
                emit(clusters, nodes, indices)?
            }
            other => other?,
        };
        let done = self.collapse.apply(nodes, nc, depth)?;
        Ok(
            Bvh::from_built(&nodes[..done.count], &indices[..n], done.depth)
                .with_build_report(report),
        )
    }
}

/// The merge cost, with lengths scaled by `scale` (1 / the scene's size).
fn cost<B: BoundingVolume>(bv: &B, metric: MergeMetric, scale: f32) -> f32 {
    match metric {
        MergeMetric::SurfaceArea => bv.cost_area_scaled(scale),
        MergeMetric::Volume => bv.cost_volume_scaled(scale),
    }
}

/// 1 / the size of `scene`: merge costs take the scene's size as the unit
/// of length, so the largest merges cost about 1 whether the scene is 1e-12
/// or 1e30 wide (1 for a point or an overflow).
fn unit_scale(scene: &Aabb) -> f32 {
    let scale = 1.0 / scene.extent().max_element();
    if scale > 0.0 && scale.is_finite() {
        scale
    } else {
        1.0
    }
}

/// Rebuilds, balanced, every subtree of the cluster tree under `root` whose
/// root sits at depth `MAX_DEPTH / 2`: afterwards no leaf is deeper than
/// `MAX_DEPTH / 2 + log2(n)`. `work` (`2n` words) is scratch: the subtree's
/// primitives in order at the front, the walk's stack at the back; the
/// subtree's inner clusters are reused, chained through their `left` field
/// while free. Returns how many subtrees were rebuilt.
fn bound_depth<B: BoundingVolume>(
    clusters: &mut [Cluster<B>],
    root: u32,
    n: usize,
    work: &mut [u32],
) -> u32 {
    const CUT: usize = crate::MAX_DEPTH / 2;
    const NONE: u32 = u32::MAX;
    let is_leaf = |c: &Cluster<B>| c.left == c.right;
    // Post-order down to the cut: subtrees at the cut are rebuilt on the way
    // down, inner clusters above it re-merged on the way up (a rebuilt
    // subtree may merge, say, spheres in another order: its parent must
    // contain the new volume). At most two entries wait per level.
    let mut stack = [(0u32, 0usize, false); 2 * CUT + 4];
    stack[0] = (root, 0, false);
    let mut top = 1;
    let mut rebuilt = 0;
    while top > 0 {
        top -= 1;
        let (c, d, children_done) = stack[top];
        let cl = clusters[c as usize];
        if is_leaf(&cl) {
            continue;
        }
        if children_done {
            let bv = clusters[cl.left as usize]
                .bv
                .merge(&clusters[cl.right as usize].bv);
            clusters[c as usize].bv = bv;
            continue;
        }
        if d < CUT {
            stack[top] = (c, d, true);
            stack[top + 1] = (cl.right, d + 1, false);
            stack[top + 2] = (cl.left, d + 1, false);
            top += 3;
            continue;
        }
        // Collect the leaves below `c` in order; free its inner clusters.
        rebuilt += 1;
        let (leaves, walk) = work.split_at_mut(n);
        let (mut m, mut sp, mut free) = (0usize, 1usize, NONE);
        walk[0] = c;
        while sp > 0 {
            sp -= 1;
            let x = walk[sp];
            let cl = clusters[x as usize];
            if is_leaf(&cl) {
                leaves[m] = x;
                m += 1;
                continue;
            }
            walk[sp] = cl.right;
            walk[sp + 1] = cl.left;
            sp += 2;
            if x != c {
                clusters[x as usize].left = free;
                free = x;
            }
        }
        // Pair neighbours round by round; the last merge reuses `c`.
        let mut len = m;
        while len > 1 {
            let mut w = 0;
            let mut i = 0;
            while i < len {
                if i + 1 < len {
                    let id = if len == 2 {
                        c
                    } else {
                        let id = free;
                        free = clusters[id as usize].left;
                        id
                    };
                    let (l, r) = (leaves[i], leaves[i + 1]);
                    clusters[id as usize] = Cluster {
                        bv: clusters[l as usize].bv.merge(&clusters[r as usize].bv),
                        left: l,
                        right: r,
                    };
                    leaves[w] = id;
                } else {
                    leaves[w] = leaves[i];
                }
                w += 1;
                i += 2;
            }
            len = w;
        }
    }
    rebuilt
}

/// Merges the best pair of all active clusters until one is left; returns the root.
fn exhaustive<B: BoundingVolume>(
    clusters: &mut [Cluster<B>],
    active: &mut [u32],
    n: usize,
    metric: MergeMetric,
    scale: f32,
) -> u32 {
    let mut k = n;
    let mut next = n as u32;
    while k > 1 {
        let (mut best, mut bi, mut bj) = (f32::INFINITY, 0, 1);
        for i in 0..k {
            for j in i + 1..k {
                let m = clusters[active[i] as usize]
                    .bv
                    .merge(&clusters[active[j] as usize].bv);
                let c = cost(&m, metric, scale);
                // `<` keeps the first best pair: deterministic ties.
                if c < best {
                    (best, bi, bj) = (c, i, j);
                }
            }
        }
        let (l, r) = (active[bi], active[bj]);
        clusters[next as usize] = Cluster {
            bv: clusters[l as usize].bv.merge(&clusters[r as usize].bv),
            left: l,
            right: r,
        };
        active[bi] = next;
        active[bj] = active[k - 1];
        k -= 1;
        next += 1;
    }
    active[0]
}

/// Locally-ordered clustering, written straight into the query layout:
/// the active clusters sit at the front of `nodes` in curve order (each a
/// finished node: a leaf, or an inner node whose children are already
/// placed), and every merge moves its two parts to the back, as a pair of
/// adjacent children, so the root ends in slot 0 with every parent before
/// its children and no second pass over the tree. Leaves name their
/// position on the curve (`sorted`: the keys of [`morton_order`]);
/// `indices` maps it to the primitive. `work` (`2n`) holds each active
/// cluster's best partner and its height; `cost` prices a merged volume.
/// Returns the root's height (the tree's depth), which may
/// exceed [`MAX_DEPTH`](crate::MAX_DEPTH): the caller then rebuilds.
fn ploc<B: BoundingVolume, P: Primitive>(
    prims: &[P],
    sorted: &[u64],
    nodes: &mut [Node<B>],
    indices: &mut [u32],
    work: &mut [u32],
    radius: usize,
    cost: impl Fn(&B) -> f32,
) -> u32 {
    let n = prims.len();
    // The leaves in curve order: leaf `k` holds the `k`-th primitive along
    // the curve.
    let (nearest, height) = work.split_at_mut(n);
    for (k, &key) in sorted.iter().enumerate() {
        let prim = key as u32;
        indices[k] = prim;
        nodes[k] = Node {
            bv: B::from_aabb(&prims[prim as usize].bounds()),
            first: k as u32,
            count: 1,
        };
        height[k] = 0;
    }
    let mut k = n;
    // The next pair of child slots is `insert - 2, insert - 1`. The front
    // (`k` clusters) and the back (`2n - 1 - insert` nodes) never overlap
    // an unread cluster: `k + (2n - 1 - insert) = n + merges <= 2n - 1`,
    // and the last merge of a round reads its two parts before it writes.
    let mut insert = 2 * n - 1;
    // Each pair's cost is computed once: row `i` of `ring` holds the costs
    // of `i` with `i + 1 ..= i + radius`, kept until the last of those has
    // read it. Wider windows than the ring recompute both directions.
    let mut ring = [[0.0f32; RING]; RING];
    let pair_cost = |a: &Node<B>, b: &Node<B>| cost(&a.bv.merge(&b.bv));
    while k > 1 {
        // Each cluster's best partner within the window. Ties go to the
        // nearer index on the curve, then to the pair `(2m, 2m + 1)`.
        if radius == 1 {
            // Only the two neighbours: each pair's cost is computed once
            // and compared from both of its ends, without a branch (the
            // comparisons are coin flips to a predictor). The costs are
            // finite (validated input, scaled lengths), so these are the
            // window search's decisions at radius 1: the cheaper side, and
            // on a tie the side that makes the pair `(2m, 2m + 1)`.
            let mut left = f32::INFINITY;
            for i in 0..k - 1 {
                let right = pair_cost(&nodes[i], &nodes[i + 1]);
                let go_left = (left < right) | ((left == right) & (i & 1 == 1));
                nearest[i] = (i + 1 - 2 * usize::from(go_left)) as u32;
                left = right;
            }
            nearest[k - 1] = (k - 2) as u32;
        } else {
            for i in 0..k {
                let (lo, hi) = (i.saturating_sub(radius), (i + radius + 1).min(k));
                let (mut best, mut partner) = (f32::INFINITY, i);
                let cached = radius <= RING;
                for j in lo..hi {
                    if j == i {
                        continue;
                    }
                    let c = if cached && j < i {
                        ring[j % RING][i - j - 1]
                    } else {
                        let c = pair_cost(&nodes[i], &nodes[j]);
                        if cached {
                            ring[i % RING][j - i - 1] = c;
                        }
                        c
                    };
                    if c < best || (c == best && tie_prefers(i, j, partner)) {
                        (best, partner) = (c, j);
                    }
                }
                nearest[i] = partner as u32;
            }
        }
        // Mutual best pairs merge into the slot of the lower index, and the
        // list closes up behind them in the same pass (curve order kept:
        // a slot is written only after it and every slot after it that
        // this round reads, `j > i`, have been read).
        let mut w = 0;
        for i in 0..k {
            let j = nearest[i] as usize;
            if j != i && nearest[j] as usize == i {
                if j < i {
                    continue; // merged at `j`
                }
                let (l, r) = (nodes[i], nodes[j]);
                insert -= 2;
                nodes[insert] = l;
                nodes[insert + 1] = r;
                nodes[w] = Node {
                    bv: l.bv.merge(&r.bv),
                    first: insert as u32,
                    count: 0,
                };
                height[w] = height[i].max(height[j]) + 1;
            } else {
                nodes[w] = nodes[i];
                height[w] = height[i];
            }
            w += 1;
        }
        if w == k {
            // Cannot happen with a strict order of pair costs, but never loop
            // forever: merge the first two clusters.
            let (l, r) = (nodes[0], nodes[1]);
            insert -= 2;
            nodes[insert] = l;
            nodes[insert + 1] = r;
            nodes[0] = Node {
                bv: l.bv.merge(&r.bv),
                first: insert as u32,
                count: 0,
            };
            height[0] = height[0].max(height[1]) + 1;
            nodes.copy_within(2..k, 1);
            height.copy_within(2..k, 1);
            w = k - 1;
        }
        k = w;
    }
    debug_assert_eq!(insert, 1);
    height[0]
}

/// The keys of `prims` sorted along a Morton curve over the box of their
/// centres, ties by index: each key holds its 30-bit code above the
/// primitive's index. A stable radix sort on the code's four bytes (one
/// counting pass for all four, 4 KiB of counters on the stack; a digit that
/// is the same for every key is skipped) ping-pongs between the two halves
/// of `keys` (`2n`); returns the half holding the result. (Three 10-bit
/// digits measured 2% faster with 12 KiB of counters: too much stack for a
/// microcontroller.)
fn morton_order<'k, P: Primitive>(prims: &[P], centres: &Aabb, keys: &'k mut [u64]) -> &'k [u64] {
    const BITS: u32 = 8;
    const DIGITS: usize = 1 << BITS;
    const PASSES: usize = 30usize.div_ceil(BITS as usize);
    let n = prims.len();
    let extent = centres.extent();
    let (keys, spare) = keys.split_at_mut(n);
    let mut count = [[0u32; DIGITS]; PASSES];
    let digit =
        |key: u64, pass: usize| ((key >> (32 + BITS * pass as u32)) as usize) & (DIGITS - 1);
    for (i, p) in prims.iter().enumerate() {
        let c = p.bounds().center();
        let mut q = [0u32; 3];
        for k in 0..3 {
            let t = if extent[k] > 0.0 {
                (c[k] - centres.min[k]) / extent[k]
            } else {
                0.0
            };
            q[k] = (t.clamp(0.0, 1.0) * 1023.0) as u32;
        }
        let key = (u64::from(morton3(q[0], q[1], q[2])) << 32) | i as u64;
        keys[i] = key;
        for (pass, count) in count.iter_mut().enumerate() {
            count[digit(key, pass)] += 1;
        }
    }
    let mut sorted_in_keys = true;
    for (pass, start) in count.iter_mut().enumerate() {
        if start.iter().any(|&c| c as usize == n) {
            continue;
        }
        let (from, to) = if sorted_in_keys {
            (&*keys, &mut *spare)
        } else {
            (&*spare, &mut *keys)
        };
        let mut sum = 0;
        for c in start.iter_mut() {
            (*c, sum) = (sum, sum + *c);
        }
        for &key in from {
            let d = digit(key, pass);
            to[start[d] as usize] = key;
            start[d] += 1;
        }
        sorted_in_keys = !sorted_in_keys;
    }
    if sorted_in_keys {
        keys
    } else {
        spare
    }
}

/// The widest search window whose pair costs are cached (`RING * RING`
/// floats on the stack, 1 KiB).
const RING: usize = 16;

/// Among equal costs, prefer the candidate `j` closer to `i` on the curve;
/// between the two at the same distance, the one that makes the pair
/// `(2m, 2m + 1)`, so that runs of equal costs (identical primitives) pair
/// up and halve, instead of all pointing the same way and merging one pair
/// per round into a chain. `current` is the best so far.
fn tie_prefers(i: usize, j: usize, current: usize) -> bool {
    if current == i {
        return true;
    }
    let (dj, dc) = (i.abs_diff(j), i.abs_diff(current));
    dj < dc || (dj == dc && j == i ^ 1)
}

/// Interleaves the low 10 bits of x, y, z.
fn morton3(x: u32, y: u32, z: u32) -> u32 {
    fn spread(v: u32) -> u32 {
        let mut v = v & 0x3ff;
        v = (v | (v << 16)) & 0x030000ff;
        v = (v | (v << 8)) & 0x0300f00f;
        v = (v | (v << 4)) & 0x030c30c3;
        (v | (v << 2)) & 0x09249249
    }
    spread(x) | (spread(y) << 1) | (spread(z) << 2)
}
