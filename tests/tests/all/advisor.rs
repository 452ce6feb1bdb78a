//! The advisor: its advice reacts to the workload and the statistics, every
//! combination of its grid answers like brute force, and its pick is always
//! one of the measured combinations. (How fast the pick is lives in
//! `bvhkit bench`, not here: timings do not belong in tests.)

use bvhkit::{Descent, PairTraversal, RayOrder};
use bvhkit_std::advisor::{
    advise, judge, measure_grid, workload_ms, BuilderChoice, Case, LayoutChoice, Motion, QueryKind,
    SceneStats, VolumeChoice, Walk, Workload, VOLUME_FILLING,
};
use bvhkit_std::scene;

fn stats(occupancy: f64, size_ratio: f64) -> SceneStats {
    SceneStats {
        primitives: 10_000,
        other_primitives: 10_000,
        occupancy,
        size_spread: 1.5,
        thinness: 1.3,
        size_ratio,
    }
}

#[test]
fn advice_follows_the_workload() {
    let s = stats(0.05, 1.0);
    let rays = advise(&s, &Workload::new(QueryKind::Rays, Motion::Static)).choice;
    assert_eq!(rays.builder, BuilderChoice::Sah);
    assert_eq!(rays.layout, LayoutChoice::Wide);
    assert_eq!(rays.walk, Walk::Rays(RayOrder::DepthFirst));
    let deforming = advise(&s, &Workload::new(QueryKind::Pairs, Motion::Deforming)).choice;
    assert_eq!(deforming.builder, BuilderChoice::Sah8);
    let small = SceneStats {
        primitives: 1_000,
        ..s
    };
    let rebuilt = advise(&small, &Workload::new(QueryKind::Rays, Motion::Deforming)).choice;
    assert_eq!(
        rebuilt.builder,
        BuilderChoice::Sah8,
        "small scenes too: measured"
    );
    assert_eq!(
        rebuilt.layout,
        LayoutChoice::Canonical,
        "rays rebuilt: no conversion per frame"
    );
    assert_eq!(
        deforming.layout,
        LayoutChoice::Canonical,
        "no conversion per frame"
    );
    let static_pairs = advise(&s, &Workload::new(QueryKind::Pairs, Motion::Static)).choice;
    assert_eq!(static_pairs.layout, LayoutChoice::Wide);
    assert_eq!(static_pairs.builder, BuilderChoice::Sah);
    assert_eq!(
        static_pairs.walk,
        Walk::Pairs(PairTraversal::Stack(Descent::Simultaneous))
    );
    for w in Workload::ALL {
        let a = advise(&s, &w);
        assert_eq!(a.choice.volume, VolumeChoice::Aabb);
        assert_eq!(
            a.reasons.len(),
            4,
            "one reason per decision: {:?}",
            a.reasons
        );
    }
}

#[test]
fn advice_follows_the_statistics() {
    let rigid = Workload::new(QueryKind::Pairs, Motion::Rigid);
    let walk = |s: SceneStats| advise(&s, &rigid).choice.walk;
    let stack = |d| Walk::Pairs(PairTraversal::Stack(d));
    assert_eq!(walk(stats(0.05, 1.0)), stack(Descent::Simultaneous));
    assert_eq!(
        walk(stats(VOLUME_FILLING + 0.1, 1.0)),
        stack(Descent::BFirst)
    );
    // Objects of different sizes: open the larger, whatever the filling.
    assert_eq!(walk(stats(0.05, 5.0)), stack(Descent::Larger));
    assert_eq!(walk(stats(0.9, 0.1)), stack(Descent::Larger));
}

#[test]
fn statistics_tell_scenes_apart() {
    // Occupancy separates surfaces from soups once there are a few thousand
    // primitives (a surface's share of the cells shrinks as n grows).
    let n = 5_120;
    let of = |t: &[bvhkit::Triangle]| SceneStats::of(t, None);
    let (soup, clustered, slivers, rock) = (
        of(&scene::soup(n, 1)),
        of(&scene::clustered(n, 1)),
        of(&scene::slivers(n, 1)),
        of(&scene::rock(4, 1)),
    );
    assert!(soup.occupancy > VOLUME_FILLING, "{soup:?}");
    assert!(rock.occupancy < VOLUME_FILLING, "{rock:?}");
    assert!(clustered.occupancy < rock.occupancy, "{clustered:?}");
    assert!(clustered.size_spread > 3.0 * rock.size_spread);
    assert!(slivers.thinness > 10.0 * rock.thinness, "{slivers:?}");
    assert_eq!(soup.size_ratio, 1.0);
    let pair = SceneStats::of(&scene::rock(2, 1), Some(&scene::soup(100, 2)));
    assert_eq!(pair.other_primitives, 100);
    // Empty input: no panic, no NaN in what the rules read.
    let empty = SceneStats::of(&[], None);
    assert_eq!(empty.primitives, 0);
    assert!(empty.occupancy == 0.0 && empty.size_ratio == 1.0);
    let _ = advise(&empty, &Workload::new(QueryKind::Pairs, Motion::Static));
}

#[test]
fn workload_time_counts_builds_and_queries() {
    assert_eq!(workload_ms(10.0, 2.0, Motion::Static, 60), 130.0);
    assert_eq!(workload_ms(10.0, 2.0, Motion::Rigid, 60), 130.0);
    assert_eq!(workload_ms(10.0, 2.0, Motion::Deforming, 60), 720.0);
    assert_eq!(workload_ms(10.0, 2.0, Motion::Static, 0), 10.0);
}

/// Every combination of the grid on tiny scenes equals brute force, and the
/// judge finds the advised and the default combination among them.
#[test]
fn every_grid_combination_is_verified_and_the_advice_is_in_it() {
    let mut cases = Case::generated(1).unwrap(); // 80 triangles per object
    let bunny_like = scene::rock(1, 9);
    cases.push(Case::from_mesh("mesh", &bunny_like).unwrap());
    for case in &cases {
        let grid = measure_grid(case, 50, 1, |_| {}).unwrap();
        let bad: Vec<String> = grid
            .iter()
            .filter(|m| !m.verified)
            .map(|m| format!("{} moved={}", m.choice, m.moved))
            .collect();
        assert!(bad.is_empty(), "{}: {bad:?}", case.name);
        // Boxes in all 6 layouts, the other 3 volumes in the canonical one
        // (an implicit array may refuse a sparse tree): per builder, 7 pair
        // walks twice (in A's frame and moved) and 2 ray orders.
        let per_layout = 7 * 2 + 2;
        let most = BuilderChoice::ALL.len() * (6 + 3) * per_layout;
        let least = BuilderChoice::ALL.len() * (5 + 3) * per_layout;
        assert!(
            (least..=most).contains(&grid.len()),
            "{}: {}",
            case.name,
            grid.len()
        );
        let rows = judge(case, &grid, &Workload::ALL);
        assert_eq!(rows.len(), Workload::ALL.len(), "{}", case.name);
        for r in &rows {
            assert!(r.all_verified);
            assert!(r.ratio >= 1.0 && r.default_ratio >= 1.0, "{r:?}");
            assert!(r.rank >= 1 && r.rank <= r.candidates);
        }
    }
}
