//! Descent rules: which tree to descend when two internal nodes overlap.

use crate::bv::{Aabb, BoundingVolume};

/// Which side(s) of an overlapping node pair to open.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Open {
    /// Test A's two children against B.
    A,
    /// Test A against B's two children.
    B,
    /// Test the four child pairs.
    Both,
}

/// What a rule sees when both nodes are internal: the two volumes (B already
/// in A's frame), their children's volumes when the rule asked for them with
/// [`DescentRule::wants_children`], and the number of descents so far.
#[derive(Clone, Copy, Debug)]
pub struct Decision<'a, B> {
    /// The node of tree A.
    pub a: &'a B,
    /// The node of tree B, in A's frame.
    pub b: &'a B,
    /// A's children (two, or up to four in a wide layout), when asked for.
    pub a_children: Option<&'a [B]>,
    /// B's children in A's frame, when asked for.
    pub b_children: Option<&'a [B]>,
    /// Descents from the root pair to this pair.
    pub depth: u32,
}

/// A descent rule: decides which node to open when two internal nodes
/// overlap. Leaves are never opened; the traversal handles leaf–internal pairs
/// by opening the internal side, so a rule only sees internal–internal pairs.
///
/// Implement it to write your own rule; [`Descent`] holds the lectures' rules
/// and [`DepthSwitch`] combines two.
///
/// ```
/// use bvhkit::{Aabb, BoundingVolume, Decision, DescentRule, Open};
/// /// Descend the node with the larger surface area (instead of volume).
/// #[derive(Clone, Copy, Debug)]
/// struct LargerArea;
/// impl DescentRule for LargerArea {
///     fn choose<B: BoundingVolume>(&self, d: &Decision<'_, B>) -> Open {
///         if d.a.surface_area() >= d.b.surface_area() { Open::A } else { Open::B }
///     }
/// }
/// let (big, small) = (Aabb::new(glam::Vec3::ZERO, glam::Vec3::ONE * 2.0), Aabb::new(glam::Vec3::ZERO, glam::Vec3::ONE));
/// let d = Decision { a: &small, b: &big, a_children: None, b_children: None, depth: 0 };
/// assert_eq!(LargerArea.choose(&d), Open::B);
/// ```
pub trait DescentRule {
    /// Which side to open.
    fn choose<B: BoundingVolume>(&self, d: &Decision<'_, B>) -> Open;

    /// Whether [`choose`](Self::choose) reads the children's volumes. The
    /// traversal fetches them only when asked (for a moved tree B that is two
    /// extra updates per decision).
    fn wants_children(&self) -> bool {
        false
    }

    /// The choice when the rule reads nothing but the depth (A first,
    /// B first, simultaneous, alternate), so that the traversal need not
    /// fetch the two volumes, nor move B's for a moved tree B. `None`
    /// (the default) when the rule reads the volumes; when it is `Some`, it
    /// must equal [`choose`](Self::choose) at that depth.
    ///
    /// ```
    /// use bvhkit::glam::{Quat, Vec3};
    /// use bvhkit::{Aabb, BoundingVolume, Counts, Decision, DescentRule, Node, Open, Pairs, Rigid, TopDown, Triangle};
    /// /// Both sides at every step; the second also says so by depth.
    /// struct Both;
    /// struct BothByDepth;
    /// impl DescentRule for Both {
    ///     fn choose<B: BoundingVolume>(&self, _: &Decision<'_, B>) -> Open { Open::Both }
    /// }
    /// impl DescentRule for BothByDepth {
    ///     fn choose<B: BoundingVolume>(&self, _: &Decision<'_, B>) -> Open { Open::Both }
    ///     fn by_depth(&self, _: u32) -> Option<Open> { Some(Open::Both) }
    /// }
    /// let tris: Vec<Triangle> = (0..64).map(|i| {
    ///     let o = Vec3::new(i as f32 * 0.5, 0.0, 0.0);
    ///     Triangle::new(o, o + Vec3::X, o + Vec3::Y)
    /// }).collect();
    /// let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(64)];
    /// let mut idx = vec![0u32; 64];
    /// let tree = TopDown::default().build(&tris, &mut nodes, &mut idx)?;
    /// let motion = Rigid::new(Quat::from_rotation_z(0.1), Vec3::new(0.2, 0.1, 0.0))?;
    /// let (mut looked, mut blind) = (Counts::default(), Counts::default());
    /// let pairs = || Pairs::new(&tree, &tris, &tree, &tris).in_frame(motion);
    /// let n = pairs().descent(Both).counted(&mut looked).count()?;
    /// assert_eq!(pairs().descent(BothByDepth).counted(&mut blind).count()?, n);
    /// // Same pairs and tests; fewer of B's volumes moved (Nu).
    /// assert_eq!(blind.bv_tests, looked.bv_tests);
    /// assert!(blind.updates < looked.updates);
    /// # Ok::<(), bvhkit::Error>(())
    /// ```
    fn by_depth(&self, depth: u32) -> Option<Open> {
        let _ = depth;
        None
    }
}

/// The descent rules of the lectures. Every rule finds the same pairs; they
/// differ in how many volume tests (`Nv` in the cost function) they spend.
///
/// ```
/// use bvhkit::{overlapping_pairs, Aabb, Descent, Node, TopDown, Triangle};
/// use glam::Vec3;
/// let a: Vec<Triangle> = (0..32).map(|i| {
///     let o = Vec3::new(i as f32, 0.0, 0.0);
///     Triangle::new(o, o + Vec3::new(1.5, 0.0, 0.0), o + Vec3::new(0.0, 1.0, 1.0))
/// }).collect();
/// let mut nodes = [Node::<Aabb>::EMPTY; bvhkit::max_nodes(32)];
/// let mut idx = [0u32; 32];
/// let t = TopDown::default().with_max_leaf_size(1).build(&a, &mut nodes, &mut idx)?;
/// let counts = Descent::ALL.map(|rule| overlapping_pairs(&t, &a, &t, &a, rule, |_, _| {}));
/// assert!(counts.iter().all(|c| *c == counts[0])); // same answer, different work
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Descent {
    /// Descend A to its leaves before touching B. No decision cost, and good
    /// when A is the smaller object; costly when B's root contains all of A,
    /// since every node of A is then tested against B's root.
    AFirst,
    /// The mirror image of [`AFirst`](Self::AFirst): good when B is small.
    BFirst,
    /// Open the node with the larger [`size`](BoundingVolume::size) (on a
    /// tie, as between flat volumes, the larger area). Keeps
    /// the two volumes of similar size, so each test prunes well; one size
    /// comparison per decision. The usual default.
    #[default]
    Larger,
    /// Open both (four child tests per step). No decision cost and fewer
    /// stack steps; prunes less finely when the nodes differ much in size.
    Simultaneous,
    /// Alternate between A and B with depth. No decision cost; wins over
    /// A-first when the trees are alike, loses to "larger" when they are not.
    Alternate,
    /// Descend by degree of overlap: open the side whose children lie least
    /// inside the other node (each child's box volume shared with the other
    /// node's box, as a fraction of the child's box, averaged over the
    /// children). A child mostly inside the other node will not be pruned, so
    /// opening that side buys nothing. Costs four box intersections and two
    /// extra child fetches per decision.
    Overlap,
}

impl Descent {
    /// All rules, for tables and tests.
    pub const ALL: [Descent; 6] = [
        Descent::AFirst,
        Descent::BFirst,
        Descent::Larger,
        Descent::Simultaneous,
        Descent::Alternate,
        Descent::Overlap,
    ];

    /// Short name for tables and the command line.
    pub const fn name(self) -> &'static str {
        match self {
            Descent::AFirst => "a-first",
            Descent::BFirst => "b-first",
            Descent::Larger => "larger",
            Descent::Simultaneous => "simultaneous",
            Descent::Alternate => "alternate",
            Descent::Overlap => "overlap",
        }
    }

    /// The rule with this [`name`](Self::name).
    pub fn from_name(name: &str) -> Option<Descent> {
        Descent::ALL.into_iter().find(|d| d.name() == name)
    }
}

impl DescentRule for Descent {
    #[inline]
    fn choose<B: BoundingVolume>(&self, d: &Decision<'_, B>) -> Open {
        match self.by_depth(d.depth) {
            Some(open) => open,
            None if *self == Descent::Overlap => by_overlap(d),
            None => larger(d),
        }
    }

    #[inline]
    fn wants_children(&self) -> bool {
        *self == Descent::Overlap
    }

    #[inline]
    fn by_depth(&self, depth: u32) -> Option<Open> {
        match self {
            Descent::AFirst => Some(Open::A),
            Descent::BFirst => Some(Open::B),
            Descent::Simultaneous => Some(Open::Both),
            Descent::Alternate if depth % 2 == 0 => Some(Open::A),
            Descent::Alternate => Some(Open::B),
            Descent::Larger | Descent::Overlap => None,
        }
    }
}

/// The overlap rule, kept out of line so that the cheap rules inline.
#[inline(never)]
fn by_overlap<B: BoundingVolume>(d: &Decision<'_, B>) -> Open {
    match (d.a_children, d.b_children) {
        (Some(ac), Some(bc)) => {
            let (a, b) = (d.a.aabb(), d.b.aabb());
            // A small pad keeps flat boxes (coplanar scenes) comparable; the
            // smallest normal number keeps points from dividing 0 by 0.
            let pad = (1e-3 * a.union(&b).extent().max_element()).max(f32::MIN_POSITIVE);
            // Mean over the children, so a wide node compares with a binary one.
            let stays = |cs: &[B], other: &Aabb| {
                cs.iter()
                    .map(|c| inside(&c.aabb(), other, pad))
                    .sum::<f32>()
                    / cs.len().max(1) as f32
            };
            let (a_stays, b_stays) = (stays(ac, &b), stays(bc, &a));
            if a_stays <= b_stays {
                Open::A
            } else {
                Open::B
            }
        }
        _ => larger(d),
    }
}

/// The larger volume; on a tie (flat scenes, where every volume is 0) the
/// larger area, so that a 2-D scene does not fall back to "always A".
#[inline]
fn larger<B: BoundingVolume>(d: &Decision<'_, B>) -> Open {
    let (sa, sb) = (d.a.size(), d.b.size());
    let a_wins = if sa == sb {
        d.a.cost_area_scaled(1.0) >= d.b.cost_area_scaled(1.0)
    } else {
        sa > sb
    };
    if a_wins {
        Open::A
    } else {
        Open::B
    }
}

/// The fraction of `x`'s volume inside `y`, each side padded by `pad`: the
/// product over the axes of the shared extent over `x`'s own. Each factor is
/// in [0, 1], so it neither overflows nor needs `f64` (which a
/// microcontroller without a double-precision unit emulates in software).
fn inside(x: &Aabb, y: &Aabb, pad: f32) -> f32 {
    let own = x.extent() + pad;
    let shared = (x.max.min(y.max) - x.min.max(y.min) + pad).max(glam::Vec3::ZERO);
    let f = (shared / own).min(glam::Vec3::ONE);
    f.x * f.y * f.z
}

/// A combination of two rules: `near` for the first `depth` descents, `far`
/// below. For example "simultaneous near the roots, where both trees are
/// large and alike; larger-first below".
///
/// ```
/// use bvhkit::{DepthSwitch, Descent, PairTraversal, Pairs};
/// let rule = DepthSwitch { depth: 4, near: Descent::Simultaneous, far: Descent::Larger };
/// let traversal = PairTraversal::Stack(rule);
/// # let _ = traversal;
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DepthSwitch<N, F> {
    /// Descents handled by `near`.
    pub depth: u32,
    /// The rule near the roots.
    pub near: N,
    /// The rule below `depth`.
    pub far: F,
}

impl<N: DescentRule, F: DescentRule> DescentRule for DepthSwitch<N, F> {
    #[inline]
    fn choose<B: BoundingVolume>(&self, d: &Decision<'_, B>) -> Open {
        if d.depth < self.depth {
            self.near.choose(d)
        } else {
            self.far.choose(d)
        }
    }

    fn wants_children(&self) -> bool {
        self.near.wants_children() || self.far.wants_children()
    }

    #[inline]
    fn by_depth(&self, depth: u32) -> Option<Open> {
        if depth < self.depth {
            self.near.by_depth(depth)
        } else {
            self.far.by_depth(depth)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Aabb;
    use glam::Vec3;

    /// Flat volumes (a 2-D scene at z = 0) all have volume 0: the larger
    /// rule then compares their areas, instead of always opening A.
    #[test]
    fn larger_compares_areas_when_volumes_tie() {
        let small = Aabb::new(Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0));
        let big = Aabb::new(Vec3::ZERO, Vec3::new(4.0, 3.0, 0.0));
        let d = |a, b| Decision {
            a,
            b,
            a_children: None,
            b_children: None,
            depth: 0,
        };
        assert_eq!(Descent::Larger.choose(&d(&small, &big)), Open::B);
        assert_eq!(Descent::Larger.choose(&d(&big, &small)), Open::A);
        // Volumes decide when they differ, whatever the areas.
        let thin = Aabb::new(Vec3::ZERO, Vec3::new(100.0, 100.0, 0.001));
        let cube = Aabb::new(Vec3::ZERO, Vec3::splat(3.0));
        assert_eq!(Descent::Larger.choose(&d(&thin, &cube)), Open::B);
        // A full tie opens A, as before.
        assert_eq!(Descent::Larger.choose(&d(&big, &big)), Open::A);
    }

    /// A rule that answers by depth alone must answer as `choose` does,
    /// whatever the volumes; rules that read the volumes answer `None`.
    #[test]
    fn by_depth_agrees_with_choose() {
        let mut next = crate::test_floats(7);
        let mut boxes = || {
            let c = Vec3::new(next(), next(), next()) * 10.0;
            let h = Vec3::new(next(), next(), next()).abs() * 3.0;
            Aabb::new(c - h, c + h)
        };
        let switch = DepthSwitch {
            depth: 3,
            near: Descent::Simultaneous,
            far: Descent::Larger,
        };
        for depth in 0..8 {
            for _ in 0..20 {
                let (a, b) = (boxes(), boxes());
                let d = Decision {
                    a: &a,
                    b: &b,
                    a_children: None,
                    b_children: None,
                    depth,
                };
                for rule in Descent::ALL {
                    let reads_volumes = matches!(rule, Descent::Larger | Descent::Overlap);
                    match rule.by_depth(depth) {
                        Some(open) => assert_eq!(open, rule.choose(&d), "{rule:?} at {depth}"),
                        None => assert!(reads_volumes, "{rule:?} at {depth}"),
                    }
                    assert_eq!(rule.by_depth(depth).is_none(), reads_volumes);
                }
                let by_depth = switch.by_depth(depth);
                assert_eq!(by_depth.is_some(), depth < 3);
                if let Some(open) = by_depth {
                    assert_eq!(open, switch.choose(&d));
                }
            }
        }
        assert_eq!(Descent::Alternate.by_depth(4), Some(Open::A));
        assert_eq!(Descent::Alternate.by_depth(5), Some(Open::B));
    }
}
