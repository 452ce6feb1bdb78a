//! Every builder of the library by name: the top-down presets, the bottom-up
//! builders and the insertion builders. The command-line tool's `--builder`
//! and the tour take their names from here, so every builder can be tried
//! from the command line.

use crate::OwnedBvh;
use bvhkit::builders::{
    BottomUp, Collapse, DynamicConfig, InsertOrder, Insertion, MergeMetric, Method, SiblingSearch,
    PRESETS,
};
use bvhkit::{BoundingVolume, Primitive, TopDown};

/// A way to build a tree.
#[derive(Clone, Copy, Debug)]
pub enum Builder {
    /// A top-down configuration.
    TopDown(TopDown),
    /// A bottom-up configuration.
    BottomUp(BottomUp),
    /// Insertion, one primitive at a time.
    Insertion(Insertion),
}

impl Builder {
    /// Builds into owned storage.
    pub fn build<B: BoundingVolume>(
        &self,
        prims: &[impl Primitive],
    ) -> Result<OwnedBvh<B>, bvhkit::Error> {
        match self {
            Builder::TopDown(t) => OwnedBvh::build(t, prims),
            Builder::BottomUp(b) => OwnedBvh::build_bottom_up(b, prims),
            Builder::Insertion(i) => OwnedBvh::build_by_insertion(i, prims),
        }
    }

    /// The builder called `name` (one of [`names`]).
    ///
    /// ```
    /// use bvhkit_std::builders::{names, Builder};
    /// assert!(matches!(Builder::by_name("ploc-r16"), Some(Builder::BottomUp(_))));
    /// assert!(names().iter().all(|n| Builder::by_name(n).is_some()));
    /// assert!(Builder::by_name("magic").is_none());
    /// ```
    pub fn by_name(name: &str) -> Option<Builder> {
        catalogue()
            .into_iter()
            .find(|(n, _, _)| *n == name)
            .map(|(_, _, b)| b)
    }
}

/// Every builder: (name, what it is, the builder). The top-down presets
/// first, in [`PRESETS`] order.
pub fn catalogue() -> Vec<(&'static str, &'static str, Builder)> {
    let mut all: Vec<_> = PRESETS
        .iter()
        .map(|p| (p.name, p.summary, Builder::TopDown(p.builder)))
        .collect();
    let ploc = |radius| {
        Builder::BottomUp(BottomUp {
            method: Method::Ploc { radius },
            ..BottomUp::default()
        })
    };
    let insertion = |search, order| {
        Builder::Insertion(Insertion {
            config: DynamicConfig {
                search,
                ..DynamicConfig::default()
            },
            order,
            collapse: Collapse::default(),
        })
    };
    let shuffled = InsertOrder::Shuffled(0x5eed);
    all.extend([
        (
            "ploc-r16",
            "bottom-up, locally-ordered clustering, 16 neighbours each side (BottomUp::default)",
            ploc(16),
        ),
        ("ploc-r4", "bottom-up PLOC, 4 neighbours each side", ploc(4)),
        (
            "ploc-r1",
            "bottom-up PLOC, 1 neighbour each side (fastest)",
            ploc(1),
        ),
        (
            "bottom-up-exhaustive",
            "the textbook bottom-up build: best pair of all, O(n^3), a few hundred primitives",
            Builder::BottomUp(BottomUp::exhaustive(MergeMetric::SurfaceArea)),
        ),
        (
            "insert-bnb",
            "insertion in shuffled order, best sibling by branch and bound",
            insertion(SiblingSearch::BranchAndBound, shuffled),
        ),
        (
            "insert-descent",
            "insertion in shuffled order, sibling by greedy descent",
            insertion(SiblingSearch::Descent, shuffled),
        ),
        (
            "insert-bnb-mesh",
            "insertion in the mesh's order, branch and bound",
            insertion(SiblingSearch::BranchAndBound, InsertOrder::Given),
        ),
        (
            "insert-bnb-sorted",
            "insertion sorted along the longest axis, branch and bound",
            insertion(SiblingSearch::BranchAndBound, InsertOrder::Sorted),
        ),
        (
            "insert-dsc-sorted",
            "insertion sorted along the longest axis, greedy descent",
            insertion(SiblingSearch::Descent, InsertOrder::Sorted),
        ),
    ]);
    all
}

/// The names of [`catalogue`], for a command line's possible values.
pub fn names() -> Vec<&'static str> {
    catalogue().into_iter().map(|(n, _, _)| n).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use bvhkit::{Aabb, Pairs};

    #[test]
    fn every_builder_builds_a_tree_that_answers_like_brute_force() {
        let mesh = crate::scene::rock(1, 3);
        let moved: Vec<_> = mesh
            .iter()
            .map(|t| t.translated(bvhkit::glam::Vec3::X * 0.3))
            .collect();
        let mut want = Vec::new();
        bvhkit::brute_force::pairs(&mesh, &moved, |i, j| want.push((i, j)));
        want.sort_unstable();
        let all = catalogue();
        assert_eq!(all.len(), PRESETS.len() + 9);
        let mut seen = std::collections::HashSet::new();
        for (name, _, builder) in all {
            assert!(seen.insert(name), "{name} twice");
            let (ta, tb) = (
                builder.build::<Aabb>(&mesh).unwrap(),
                builder.build::<Aabb>(&moved).unwrap(),
            );
            let mut got = Vec::new();
            Pairs::new(&ta.view(), &mesh, &tb.view(), &moved)
                .for_each(|i, j| got.push((i, j)))
                .unwrap();
            got.sort_unstable();
            assert_eq!(got, want, "{name}");
        }
    }
}
