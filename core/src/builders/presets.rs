//! Named top-down configurations: one per strategy of the lectures, so tables,
//! tests and students can refer to them by name.

use super::strategy::{AxisChoice, Partition, SplitPoint};
use super::TopDown;

/// A named builder configuration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Preset {
    /// Short name used on the command line and in tables.
    pub name: &'static str,
    /// One line saying what it does.
    pub summary: &'static str,
    /// The configuration.
    pub builder: TopDown,
}

const fn with(partition: Partition, axis: AxisChoice, split: SplitPoint) -> TopDown {
    TopDown {
        partition,
        axis,
        split,
        ..TopDown::sah()
    }
}

/// Every top-down strategy of the lectures, by name.
///
/// ```
/// let p = bvhkit::builders::PRESETS.iter().find(|p| p.name == "median").unwrap();
/// assert_eq!(p.builder, bvhkit::TopDown::median());
/// ```
pub const PRESETS: [Preset; 15] = [
    Preset {
        name: "sah",
        summary: "surface area heuristic, 16 bins on x/y/z (default)",
        builder: TopDown::sah(),
    },
    Preset {
        name: "sah-sweep",
        summary: "surface area heuristic at every centroid (exact sweep)",
        builder: TopDown::sah_sweep(),
    },
    Preset {
        name: "sah-8bins",
        summary: "surface area heuristic, 8 bins on x/y/z",
        builder: with(
            Partition::SurfaceArea,
            AxisChoice::BestOfXyz,
            SplitPoint::Bins(8),
        ),
    },
    Preset {
        name: "sah-longest",
        summary: "surface area heuristic, 16 bins on the longest axis only (fastest SAH)",
        builder: with(
            Partition::SurfaceArea,
            AxisChoice::Longest,
            SplitPoint::Bins(16),
        ),
    },
    Preset {
        name: "median",
        summary: "median cut: equal halves along the longest axis",
        builder: TopDown::median(),
    },
    Preset {
        name: "spatial-median",
        summary: "middle of the longest axis",
        builder: with(
            Partition::Balance,
            AxisChoice::Longest,
            SplitPoint::SpatialMedian,
        ),
    },
    Preset {
        name: "mean-variance",
        summary: "centroid mean along the direction of greatest variance",
        builder: with(
            Partition::Balance,
            AxisChoice::Variance,
            SplitPoint::ObjectMean,
        ),
    },
    Preset {
        name: "distant-points",
        summary: "median along the line through the two most distant centroids",
        builder: with(
            Partition::Balance,
            AxisChoice::DistantPoints,
            SplitPoint::ObjectMedian,
        ),
    },
    Preset {
        name: "min-volume",
        summary: "minimise the sum of child volumes, 16 bins on x/y/z",
        builder: with(
            Partition::Volume,
            AxisChoice::BestOfXyz,
            SplitPoint::Bins(16),
        ),
    },
    Preset {
        name: "min-larger",
        summary: "minimise the larger child volume, 16 bins on x/y/z",
        builder: with(
            Partition::LargerChild,
            AxisChoice::BestOfXyz,
            SplitPoint::Bins(16),
        ),
    },
    Preset {
        name: "min-overlap",
        summary: "minimise the children's overlap, 16 bins on x/y/z",
        builder: with(
            Partition::Overlap,
            AxisChoice::BestOfXyz,
            SplitPoint::Bins(16),
        ),
    },
    Preset {
        name: "max-separation",
        summary: "maximise the gap between children, 16 bins on x/y/z",
        builder: with(
            Partition::Separation,
            AxisChoice::BestOfXyz,
            SplitPoint::Bins(16),
        ),
    },
    Preset {
        name: "weighted",
        summary: "SAH + overlap + balance, weighted",
        builder: with(
            Partition::Weighted {
                surface_area: 1.0,
                volume: 0.0,
                overlap: 1.0,
                balance: 0.1,
            },
            AxisChoice::BestOfXyz,
            SplitPoint::Bins(16),
        ),
    },
    Preset {
        name: "random-centroids",
        summary: "SAH at 16 seeded random centroids on x/y/z",
        builder: with(
            Partition::SurfaceArea,
            AxisChoice::BestOfXyz,
            SplitPoint::RandomCentroids {
                count: 16,
                seed: 42,
            },
        ),
    },
    Preset {
        name: "parent-axes",
        summary: "SAH, 16 bins along the node volume's own axes",
        builder: with(
            Partition::SurfaceArea,
            AxisChoice::ParentVolume,
            SplitPoint::Bins(16),
        ),
    },
];
