//! The incremental broad phase (`collision::PairTracker`): after any
//! sequence of arrivals, moves and departures, each step's pair list equals
//! brute force over the objects present, and its events are exactly the
//! difference from the previous list.

use bvhkit::builders::DynamicConfig;
use bvhkit::collision::{PairEvent, PairTracker};
use bvhkit::glam::Vec3;
use bvhkit::{brute_force, Aabb, Error, Hierarchy, Query};
use bvhkit_tests::*;
use proptest::prelude::*;
use std::collections::BTreeSet;

#[derive(Clone, Debug)]
enum Op {
    Insert(u32, Vec3, f32),
    Remove(u32),
    Nudge(u32, Vec3),
    Jump(u32, Vec3),
    /// Every object present jumps (most of them out of their fat leaves):
    /// the step rebuilds the tree instead of reinserting one by one.
    Scatter(u32),
    /// Every absent id arrives at once (100 objects: enough for the churn
    /// rule to rebuild the tree over them at the next step).
    Crowd(u32),
    Step,
}

/// Object ids: `0..N`.
const N: u32 = 100;

fn op() -> impl Strategy<Value = Op> {
    let v = |r: f32| (-r..r, -r..r, -r..r).prop_map(|(x, y, z)| Vec3::new(x, y, z));
    prop_oneof![
        4 => (0..N, v(6.0), 0.2f32..2.0).prop_map(|(i, o, s)| Op::Insert(i, o, s)),
        2 => (0..N).prop_map(Op::Remove),
        4 => (0..N, v(0.05)).prop_map(|(i, d)| Op::Nudge(i, d)),
        2 => (0..N, v(6.0)).prop_map(|(i, o)| Op::Jump(i, o)),
        1 => any::<u32>().prop_map(Op::Scatter),
        1 => any::<u32>().prop_map(Op::Crowd),
        3 => Just(Op::Step),
    ]
}

/// A spot in `[-6, 6)^3` from a seed and an id.
fn spot(seed: u32, i: usize) -> Vec3 {
    let h = (seed as u64 ^ (i as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15))
        .wrapping_mul(0xbf58_476d_1ce4_e5b9);
    let at = |k: u32| ((h >> (k * 16)) & 0xffff) as f32 / 65536.0 * 12.0 - 6.0;
    Vec3::new(at(0), at(1), at(2))
}

/// The pairs brute force finds among the objects present (`present[i]`
/// holds object `i`'s box).
fn reference(present: &[Option<Aabb>]) -> Vec<(u32, u32)> {
    let boxes: Vec<Aabb> = present
        .iter()
        .map(|b| b.unwrap_or(Aabb::new(Vec3::splat(1e30), Vec3::splat(1e30))))
        .collect();
    let mut want = Vec::new();
    brute_force::self_pairs(&boxes, |i, j| {
        if present[i as usize].is_some() && present[j as usize].is_some() {
            want.push((i, j));
        }
    });
    want
}

/// Runs `ops` with every position offset by `origin` (far from the origin,
/// `f32` spacing reaches 1/16 at 1e6: nudges round, boxes touch exactly).
fn run(ops: &[Op], margin: f32, pair_room: usize, origin: Vec3) -> Result<(), TestCaseError> {
    let n = N as usize;
    let mut storage = bvhkit_std::TrackerBuffers::new(n, pair_room);
    let config = DynamicConfig {
        margin,
        ..DynamicConfig::default()
    };
    let mut world = PairTracker::new(storage.storage(), config).unwrap();
    let mut present: Vec<Option<Aabb>> = vec![None; n];
    let mut before: BTreeSet<(u32, u32)> = BTreeSet::new();
    for op in ops {
        match *op {
            Op::Insert(i, o, s) => {
                let o = o + origin;
                let b = Aabb::new(o, o + s);
                let r = world.insert(i, &b);
                prop_assert_eq!(r.is_ok(), present[i as usize].is_none(), "{:?}", r);
                present[i as usize].get_or_insert(b);
            }
            Op::Remove(i) => {
                let r = world.remove(i);
                prop_assert_eq!(r.is_ok(), present[i as usize].is_some());
                present[i as usize] = None;
            }
            Op::Nudge(i, d) | Op::Jump(i, d) => {
                let Some(b) = present[i as usize] else {
                    prop_assert!(world.set_bounds(i, &Aabb::EMPTY).is_err());
                    continue;
                };
                let moved = match op {
                    Op::Nudge(..) => Aabb::new(b.min + d, b.max + d),
                    _ => Aabb::new(d + origin, d + origin + b.extent()),
                };
                world.set_bounds(i, &moved).unwrap();
                present[i as usize] = Some(moved);
            }
            Op::Scatter(seed) => {
                for (i, slot) in present.iter_mut().enumerate() {
                    let Some(b) = *slot else { continue };
                    let o = spot(seed, i) + origin;
                    let moved = Aabb::new(o, o + b.extent());
                    world.set_bounds(i as u32, &moved).unwrap();
                    *slot = Some(moved);
                }
            }
            Op::Crowd(seed) => {
                for (i, slot) in present.iter_mut().enumerate() {
                    if slot.is_none() {
                        let o = spot(seed, i) + origin;
                        let b = Aabb::new(o, o + 1.0);
                        world.insert(i as u32, &b).unwrap();
                        *slot = Some(b);
                    }
                }
            }
            Op::Step => {
                let want = reference(&present);
                let mut events = Vec::new();
                match world.step(|e| events.push(e)) {
                    Err(Error::ResultCapacity { found, capacity }) => {
                        // Too many pairs for the buffers: refused, and the
                        // old list stays.
                        prop_assert!(found > capacity && want.len() > capacity);
                        prop_assert_eq!(
                            world.pairs().iter().copied().collect::<BTreeSet<_>>(),
                            before.clone()
                        );
                        prop_assert!(events.is_empty());
                        continue;
                    }
                    Err(e) => return Err(TestCaseError::fail(format!("step: {e}"))),
                    Ok(report) => {
                        prop_assert_eq!(world.pairs(), &want[..], "pairs after a step");
                        let now: BTreeSet<_> = want.iter().copied().collect();
                        let mut ends: Vec<_> = before
                            .difference(&now)
                            .map(|&(a, b)| PairEvent::End(a, b))
                            .collect();
                        let begins: Vec<_> = now
                            .difference(&before)
                            .map(|&(a, b)| PairEvent::Begin(a, b))
                            .collect();
                        ends.extend(begins);
                        prop_assert_eq!(&events, &ends, "events are the difference, ends first");
                        prop_assert_eq!(
                            (report.begun + report.ended, report.pairs),
                            (events.len(), want.len())
                        );
                        before = now;
                    }
                }
                world
                    .tree()
                    .validate()
                    .map_err(|e| TestCaseError::fail(format!("{e}")))?;
                prop_assert_eq!(world.len(), present.iter().flatten().count());
                // The tree answers other queries in place, with the boxes.
                let region = Aabb::new(origin - 2.0, origin + 2.0);
                let mut got = Vec::new();
                world
                    .tree()
                    .overlapping(world.boxes(), &region, |i| got.push(i))
                    .unwrap();
                got.sort_unstable();
                let want_region: Vec<u32> = (0..n as u32)
                    .filter(|&i| present[i as usize].is_some_and(|b| b.overlaps(&region)))
                    .collect();
                prop_assert_eq!(got, want_region);
                prop_assert!(world.tree().depth() <= bvhkit::MAX_DEPTH);
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(proptest_config(64))]

    #[test]
    fn steps_report_exactly_the_brute_force_pairs_and_their_changes(
        ops in prop::collection::vec(op(), 1..160),
        margin in prop_oneof![Just(0.0f32), 0.0f32..0.5],
        tight in any::<bool>(),
        origin in prop_oneof![
            3 => Just(Vec3::ZERO),
            1 => Just(Vec3::new(1e4, -3e4, 2e4)),
            1 => Just(Vec3::splat(1e6)),
        ],
    ) {
        // Room for every pair of the objects, or for only a few (then some
        // steps are refused and must change nothing).
        run(&ops, margin, if tight { 12 } else { (N * (N - 1) / 2) as usize }, origin)?;
    }
}

/// A box that leaves its fat leaf along one axis alone is still taken
/// into the tree: each axis is checked (a test that skipped one would leave
/// the leaf's old fat box in the tree, and the self walk would miss the pair).
#[test]
fn a_box_leaving_its_fat_leaf_along_one_axis_is_taken_in() {
    for axis in 0..3 {
        let mut s = bvhkit_std::TrackerBuffers::new(2, 4);
        let mut world = PairTracker::new(s.storage(), DynamicConfig::default()).unwrap();
        let unit_at = |offset: f32| {
            let mut o = Vec3::ZERO;
            o[axis] = offset;
            Aabb::new(o, o + 1.0)
        };
        world.insert(0, &unit_at(0.0)).unwrap();
        world.insert(1, &unit_at(3.0)).unwrap();
        world.step(|_| {}).unwrap();
        assert!(world.pairs().is_empty());
        // Both move (so the step walks the whole tree): object 0 within its
        // fat leaf, object 1 out of its own and onto object 0.
        world.set_bounds(0, &unit_at(0.01)).unwrap();
        world.set_bounds(1, &unit_at(0.5)).unwrap();
        let mut events = Vec::new();
        world.step(|e| events.push(e)).unwrap();
        assert_eq!(events, [PairEvent::Begin(0, 1)], "axis {axis}");
    }
}

#[test]
fn bad_ids_boxes_and_storage_are_errors() {
    let mut s = bvhkit_std::TrackerBuffers::new(4, 6);
    let mut world = PairTracker::new(s.storage(), DynamicConfig::default()).unwrap();
    let unit = Aabb::new(Vec3::ZERO, Vec3::ONE);
    assert!(world.insert(4, &unit).is_err()); // past the slots
    world.insert(1, &unit).unwrap();
    assert!(world.insert(1, &unit).is_err()); // already present
    let nan = Aabb::new(Vec3::splat(f32::NAN), Vec3::ONE);
    assert!(matches!(
        world.insert(2, &nan),
        Err(Error::NonFiniteCoordinate { .. })
    ));
    assert!(matches!(
        world.set_bounds(1, &nan),
        Err(Error::NonFiniteCoordinate { .. })
    ));
    // Each bad box gets its own error, arriving or moving, whichever one
    // axis (alone) is bad.
    for axis in 0..3 {
        let on_axis = |min: f32, max: f32| {
            let mut b = unit;
            (b.min[axis], b.max[axis]) = (min, max);
            b
        };
        let far = 2.0 * bvhkit::MAX_COORDINATE;
        let non_finite = |primitive| Error::NonFiniteCoordinate { primitive };
        let out_of_range = |primitive| Error::CoordinateOutOfRange { primitive };
        for (bad, error) in [
            (on_axis(1.0, 0.0), non_finite as fn(usize) -> Error),
            (on_axis(0.0, f32::INFINITY), non_finite),
            (on_axis(f32::NEG_INFINITY, 1.0), non_finite),
            (on_axis(f32::NAN, 1.0), non_finite),
            (on_axis(0.0, f32::NAN), non_finite),
            (on_axis(0.0, far), out_of_range),
            (on_axis(-far, 0.0), out_of_range),
        ] {
            assert_eq!(world.insert(2, &bad), Err(error(2)), "axis {axis}: {bad:?}");
            assert_eq!(
                world.set_bounds(1, &bad),
                Err(error(1)),
                "axis {axis}: {bad:?}"
            );
        }
    }
    assert!(world.set_bounds(3, &unit).is_err()); // not present
    assert!(world.remove(0).is_err());
    // Nothing was lost: object 1 is still there, with its box.
    assert_eq!(world.len(), 1);
    assert_eq!(world.boxes()[1], unit);
    world.insert(2, &unit).unwrap();
    let mut events = Vec::new();
    world.step(|e| events.push(e)).unwrap();
    assert_eq!(events, [PairEvent::Begin(1, 2)]);
    // Storage too small for the slots.
    let mut s = bvhkit_std::TrackerBuffers::new(4, 6);
    let mut short = s.storage();
    short.moved = &mut std::mem::take(&mut short.moved)[..3];
    assert!(PairTracker::new(short, DynamicConfig::default()).is_err());
    let mut short = s.storage();
    short.next = &mut std::mem::take(&mut short.next)[..2];
    assert!(PairTracker::new(short, DynamicConfig::default()).is_err());
    // An empty world steps to nothing.
    let mut s = bvhkit_std::TrackerBuffers::new(1, 0);
    let mut empty = PairTracker::new(s.storage(), DynamicConfig::default()).unwrap();
    assert_eq!(empty.step(|_| panic!("no events")).unwrap().pairs, 0);
}
