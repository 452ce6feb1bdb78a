//! Descent rules: which tree to descend when two internal nodes overlap.

use crate::bv::BoundingVolume;
use crate::tree::Node;

/// The rule a two-tree traversal uses to pick which node to open next.
/// Every rule finds the same pairs; they differ in how many volume tests
/// (`Nv` in the cost function) they spend getting there.
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
    /// Descend A to its leaves before touching B. Cheap decisions, but costly
    /// when B's root contains all of A: every A node is tested against B's root.
    AFirst,
    /// The mirror image of [`AFirst`](Self::AFirst).
    BFirst,
    /// Open the node with the larger [`size`](BoundingVolume::size): keeps the
    /// two volumes similar in size, so each test prunes well. The usual default.
    #[default]
    Larger,
    /// Open both at once (four child pairs): no decision cost, prunes less finely.
    Simultaneous,
    /// Alternate between A and B with depth.
    Alternate,
}

impl Descent {
    /// All rules, for tables and tests.
    pub const ALL: [Descent; 5] = [
        Descent::AFirst,
        Descent::BFirst,
        Descent::Larger,
        Descent::Simultaneous,
        Descent::Alternate,
    ];

    /// Short name for tables.
    pub const fn name(self) -> &'static str {
        match self {
            Descent::AFirst => "a-first",
            Descent::BFirst => "b-first",
            Descent::Larger => "larger",
            Descent::Simultaneous => "simultaneous",
            Descent::Alternate => "alternate",
        }
    }

    /// Which sides to open for a pair where at least one node is internal:
    /// `(open_a, open_b)`. A leaf is never opened.
    #[inline]
    pub(crate) fn choose<B: BoundingVolume>(
        self,
        a: &Node<B>,
        b: &Node<B>,
        depth: u32,
    ) -> (bool, bool) {
        let (la, lb) = (a.is_leaf(), b.is_leaf());
        if la {
            return (false, true);
        }
        if lb {
            return (true, false);
        }
        match self {
            Descent::AFirst => (true, false),
            Descent::BFirst => (false, true),
            Descent::Larger => {
                let a_larger = a.bv.size() >= b.bv.size();
                (a_larger, !a_larger)
            }
            Descent::Simultaneous => (true, true),
            Descent::Alternate => (depth % 2 == 0, depth % 2 == 1),
        }
    }
}
