//! The collision system (broad phase + exact narrow phase over posed objects)
//! against the brute-force contact list.

use bvhkit::collision::{collide, object_pairs, BroadPhase, Contact, Object};
use bvhkit::glam::{EulerRot, Quat, Vec3};
use bvhkit::{
    brute_force, max_nodes, Aabb, Descent, Node, PairTraversal, Rigid, Sphere, TopDown, Triangle,
};
use bvhkit_tests::*;
use proptest::prelude::*;
use proptest::strategy::ValueTree;

fn pose() -> impl Strategy<Value = Rigid> {
    prop_oneof![
        1 => Just(Rigid::IDENTITY),
        4 => ((-3.2f32..3.2, -3.2f32..3.2, -3.2f32..3.2), (-2.0f32..2.0, -2.0f32..2.0, -2.0f32..2.0)).prop_map(|(r, t)| {
            Rigid::new(Quat::from_euler(EulerRot::XYZ, r.0, r.1, r.2), Vec3::new(t.0, t.1, t.2)).unwrap()
        }),
    ]
}

/// Objects modelled far apart (offsets up to 50) whose poses bring them back
/// near the world origin, turned: the model boxes are disjoint, the world
/// boxes overlap, so only a correct broad phase finds the contacts. Some
/// objects use the generators' stress frames (huge or far coordinates).
fn objects() -> impl Strategy<Value = Vec<(Vec<Triangle>, Rigid)>> {
    let near = prop::collection::vec(
        (
            (-2.0f32..2.0, -2.0f32..2.0, -2.0f32..2.0),
            (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0),
            (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0),
        )
            .prop_map(|(a, b, c)| {
                let a = Vec3::new(a.0, a.1, a.2);
                Triangle::new(
                    a,
                    a + Vec3::new(b.0, b.1, b.2),
                    a + Vec3::new(c.0, c.1, c.2),
                )
            }),
        1..20,
    );
    let object = (
        prop_oneof![4 => near, 1 => scene(20)],
        (-50.0f32..50.0, -50.0f32..50.0, -50.0f32..50.0),
        pose(),
    )
        .prop_map(|(tris, o, pose)| {
            let offset = Vec3::new(o.0, o.1, o.2);
            let model: Vec<Triangle> = tris.iter().map(|t| t.translated(offset)).collect();
            (model, pose.after(&Rigid::translation(-offset).unwrap()))
        });
    prop::collection::vec(object, 1..6).prop_filter("two or more objects", |v| v.len() >= 2)
}

/// Checks one scene; returns its number of contacts.
fn run<B: bvhkit::BoundingVolume>(
    scene: &[(Vec<Triangle>, Rigid)],
    traversal: PairTraversal,
) -> Result<usize, TestCaseError> {
    let cfg = TopDown::default().with_max_leaf_size(2);
    let built: Vec<Built<B>> = scene
        .iter()
        .map(|(t, _)| build::<B, _>(&cfg, t).unwrap())
        .collect();
    let trees: Vec<_> = built
        .iter()
        .zip(scene)
        .map(|((n, i, _), (t, _))| open(n, i, t))
        .collect();
    let objects: Vec<Object<B, Triangle>> = trees
        .iter()
        .zip(scene)
        .map(|(tree, (prims, pose))| Object {
            tree,
            prims,
            pose: *pose,
        })
        .collect();
    let n = objects.len();
    let (mut boxes, mut nodes, mut idx) = (
        vec![Aabb::EMPTY; n],
        vec![Node::EMPTY; max_nodes(n)],
        vec![0u32; n],
    );
    let mut scratch = BroadPhase {
        boxes: &mut boxes,
        nodes: &mut nodes,
        indices: &mut idx,
    };
    let mut got: Vec<Contact> = Vec::new();
    let count = collide(&objects, &mut scratch, traversal, |c| got.push(c)).unwrap();
    got.sort_unstable();
    let mut want = Vec::new();
    brute_force::contacts(&objects, |c| want.push(c));
    want.sort_unstable();
    prop_assert_eq!(count, got.len());
    prop_assert_eq!(&got, &want, "{} objects, {:?}", n, traversal);

    // The broad phase lists every object pair that has a contact.
    let mut listed = Vec::new();
    object_pairs(&objects, &mut scratch, |a, b| listed.push((a, b))).unwrap();
    for c in &want {
        prop_assert!(
            listed.contains(&c.objects),
            "pair {:?} missing from the broad phase",
            c.objects
        );
    }
    Ok(want.len())
}

proptest! {
    #![proptest_config(proptest_config(48))]

    #[test]
    fn collide_matches_brute_force(scene in objects(), k in 0..4usize) {
        let traversal = PairTraversal::all(Descent::ALL[k])[k];
        run::<Aabb>(&scene, traversal)?;
        run::<Sphere>(&scene, traversal)?;
    }

    /// Copies of one mesh at nearly the same pose: dense touching and coplanar contacts.
    #[test]
    fn stacked_copies_match(prims in scene(30), jitter in 0.0f32..1e-3) {
        let poses = [Rigid::IDENTITY, Rigid::translation(Vec3::splat(jitter)).unwrap(), Rigid::new(Quat::from_rotation_y(jitter), Vec3::ZERO).unwrap()];
        let scene: Vec<_> = poses.iter().map(|p| (prims.clone(), *p)).collect();
        run::<Aabb>(&scene, PairTraversal::default())?;
    }
}

#[test]
fn generated_scenes_have_contacts() {
    let mut runner = proptest::test_runner::TestRunner::deterministic();
    let (mut contacts, mut with_contacts) = (0, 0);
    for _ in 0..40 {
        let scene = objects().new_tree(&mut runner).unwrap().current();
        let n = run::<Aabb>(&scene, PairTraversal::default()).unwrap();
        contacts += n;
        with_contacts += (n > 0) as usize;
    }
    eprintln!("{contacts} contacts in {with_contacts} of 40 scenes");
    assert!(
        with_contacts >= 12,
        "the generator makes too few contacts: {with_contacts} of 40 scenes"
    );
}

#[test]
fn small_scratch_is_an_error_not_a_panic() {
    let tri = [Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y)];
    let (nodes, idx, _) = build::<Aabb, _>(&TopDown::default(), &tri).unwrap();
    let tree = open(&nodes, &idx, &tri);
    let objects = [Object {
        tree: &tree,
        prims: &tri[..],
        pose: Rigid::IDENTITY,
    }; 3];
    let (mut boxes, mut bn, mut bi) = ([Aabb::EMPTY; 2], [Node::EMPTY; 5], [0u32; 3]);
    let mut scratch = BroadPhase {
        boxes: &mut boxes,
        nodes: &mut bn,
        indices: &mut bi,
    };
    assert!(collide(&objects, &mut scratch, PairTraversal::default(), |_| {}).is_err());
    // Six objects apart need more than one node (leaves hold at most four).
    let apart: Vec<Object<Aabb, Triangle>> = (0..6)
        .map(|i| Object {
            tree: &tree,
            prims: &tri[..],
            pose: Rigid::translation(Vec3::X * 5.0 * i as f32).unwrap(),
        })
        .collect();
    let (mut boxes, mut bn, mut bi) = ([Aabb::EMPTY; 6], [Node::EMPTY; 1], [0u32; 6]);
    let mut scratch = BroadPhase {
        boxes: &mut boxes,
        nodes: &mut bn,
        indices: &mut bi,
    };
    assert!(collide(&apart, &mut scratch, PairTraversal::default(), |_| {}).is_err());
    let (mut boxes, mut bn, mut bi) = ([Aabb::EMPTY; 3], [Node::EMPTY; 5], [0u32; 3]);
    let mut scratch = BroadPhase {
        boxes: &mut boxes,
        nodes: &mut bn,
        indices: &mut bi,
    };
    // Three identical triangles at one place: every pair touches.
    assert_eq!(
        collide(&objects, &mut scratch, PairTraversal::default(), |_| {}).unwrap(),
        3
    );
}
