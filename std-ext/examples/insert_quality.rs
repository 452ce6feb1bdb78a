//! SAH cost of insertion builds per search, rotation setting and order.
use bvhkit::builders::{Collapse, DynamicConfig, InsertOrder, Insertion, Rotations, SiblingSearch};
use bvhkit::Aabb;
use bvhkit_std::{scene, OwnedBvh};
fn main() {
    let rock = scene::rock(5, 1);
    for search in [SiblingSearch::Descent, SiblingSearch::BranchAndBound] {
        for rotations in [
            Rotations::Off,
            Rotations::Always,
            Rotations::AboveHeight(24),
            Rotations::Area,
        ] {
            for order in [
                InsertOrder::Shuffled(1),
                InsertOrder::Given,
                InsertOrder::Sorted,
            ] {
                let b = Insertion {
                    config: DynamicConfig {
                        search,
                        rotations,
                        margin: 0.0,
                    },
                    order,
                    // The trees as insertion makes them, one per leaf.
                    collapse: Collapse::None,
                };
                let t = std::time::Instant::now();
                match OwnedBvh::<Aabb>::build_by_insertion(&b, &rock) {
                    Ok(tree) => println!(
                        "{search:?} {rotations:?} {order:?}: SAH {:.2} depth {} {:.0} ms",
                        tree.view().stats().sah_cost,
                        tree.view().depth(),
                        t.elapsed().as_secs_f64() * 1e3
                    ),
                    Err(e) => println!("{search:?} {rotations:?} {order:?}: {e}"),
                }
            }
        }
    }
}
