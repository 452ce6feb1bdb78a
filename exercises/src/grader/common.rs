//! What the exercises' checks share: the library's types, a deterministic
//! generator, small constructors and scenes used by more than one exercise.

pub(crate) use super::Check;
pub(crate) use crate::reference::Reference;
pub(crate) use crate::{Exercises, NodeStep};
pub(crate) use bvhkit::glam::Vec3;
pub(crate) use bvhkit::{
    brute_force, Aabb, BoundingVolume, Bvh, CostModel, Counts, Decision, Descent, Dop14, Node, Obb,
    Open, Partition, Sphere, Stop, TopDown, Triangle,
};

/// A small deterministic generator so every run grades the same inputs.
pub(crate) struct Rng(pub(crate) u64);
impl Rng {
    pub(crate) fn next(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }
    pub(crate) fn point(&mut self, scale: f32, offset: Vec3) -> Vec3 {
        Vec3::new(self.next() - 0.5, self.next() - 0.5, self.next() - 0.5) * scale + offset
    }
    pub(crate) fn cloud(&mut self, n: usize, scale: f32, offset: Vec3) -> Vec<Vec3> {
        (0..n).map(|_| self.point(scale, offset)).collect()
    }
}

pub(crate) fn b(min: [f32; 3], max: [f32; 3]) -> Aabb {
    Aabb::new(Vec3::from(min), Vec3::from(max))
}

pub(crate) fn clouds() -> Vec<Vec<Vec3>> {
    let mut r = Rng(0x9e3779b97f4a7c15);
    let mut v = vec![
        vec![Vec3::new(-3.0, -2.0, -1.0), Vec3::new(-1.0, -5.0, -2.0)],
        vec![Vec3::new(7.0, 7.0, 7.0)],
    ];
    for i in 0..20 {
        let off = if i % 2 == 0 {
            Vec3::ZERO
        } else {
            Vec3::new(1.0e5, -3.0e4, 2.0e4)
        };
        v.push(r.cloud(3 + i * 7, 10.0, off));
    }
    // Points on a sphere: Ritter is near its worst here.
    v.push(
        (0..200)
            .map(|i| {
                let (t, p) = (i as f32 * 0.7, i as f32 * 0.31);
                Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos()) * 3.0
            })
            .collect(),
    );
    v
}

/// All checks of all exercises.
/// Builds an SAH tree over each of [`measured_trees`] and asks `check` about
/// it; false if any build fails or any answer is false.
pub(crate) fn on_measured_trees(check: impl Fn(&Bvh<Aabb>) -> bool) -> bool {
    measured_trees().iter().all(|(tris, leaf)| {
        let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(tris.len())];
        let mut idx = vec![0u32; tris.len()];
        TopDown::sah()
            .with_max_leaf_size(*leaf)
            .build(tris, &mut nodes, &mut idx)
            .is_ok_and(|tree| check(&tree))
    })
}

/// Triangles for exercise 27, each with a leaf size: empty, three (one
/// leaf), a row of 40 in leaves of one, 300 scattered, and 50 spread over
/// 1e30 (areas past f32's range).
pub(crate) fn measured_trees() -> Vec<(Vec<Triangle>, u32)> {
    let mut r = Rng(2727);
    let tri = |o: Vec3, s: f32| Triangle::new(o, o + Vec3::X * s, o + Vec3::Y * s);
    let mut out = vec![
        (Vec::new(), 4),
        ((0..3).map(|i| tri(Vec3::splat(i as f32), 0.5)).collect(), 4),
        (
            (0..40)
                .map(|i| tri(Vec3::new(i as f32 * 2.0, 0.0, 0.0), 1.0))
                .collect(),
            1,
        ),
    ];
    out.push((
        (0..300)
            .map(|_| tri(r.point(50.0, Vec3::ZERO), 1.0 + r.next()))
            .collect(),
        4,
    ));
    out.push((
        (0..50)
            .map(|_| tri(r.point(1e30, Vec3::ZERO), 1e28))
            .collect(),
        2,
    ));
    out
}

/// A box with half extents (1, 0.6, 0.3) at `c`, turned by `yaw` about z
/// and `pitch` about x.
pub(crate) fn turned(c: Vec3, yaw: f32, pitch: f32) -> Obb {
    let q = bvhkit::glam::Quat::from_rotation_z(yaw) * bvhkit::glam::Quat::from_rotation_x(pitch);
    Obb {
        center: c,
        axes: [q * Vec3::X, q * Vec3::Y, q * Vec3::Z],
        half_extents: Vec3::new(1.0, 0.6, 0.3),
    }
}

/// Relative closeness for the exercises' `f64` answers.
pub(crate) fn close(x: f64, want: f64) -> bool {
    (x - want).abs() <= 1e-9 * want.abs().max(1.0)
}

/// The unit cube at `x` along the x axis.
pub(crate) fn unit_at(x: f32) -> Aabb {
    Aabb::new(Vec3::new(x, 0.0, 0.0), Vec3::new(x + 1.0, 1.0, 1.0))
}

/// A tree over boxes, with its storage.
pub(crate) struct Tree {
    pub(crate) prims: Vec<Aabb>,
    pub(crate) nodes: Vec<Node<Aabb>>,
    pub(crate) indices: Vec<u32>,
    pub(crate) depth: usize,
}

impl Tree {
    pub(crate) fn new(prims: Vec<Aabb>, leaf: u32) -> Tree {
        let builder = TopDown::default().with_max_leaf_size(leaf);
        let mut nodes = vec![Node::EMPTY; bvhkit::max_nodes(prims.len())];
        let mut indices = vec![0u32; prims.len()];
        let (depth, used) = match builder.build(&prims, &mut nodes, &mut indices) {
            Ok(t) => (t.depth(), t.node_count()),
            Err(e) => panic!("grader tree: {e}"),
        };
        nodes.truncate(used);
        Tree {
            prims,
            nodes,
            indices,
            depth,
        }
    }

    pub(crate) fn bvh(&self) -> Bvh<'_, Aabb> {
        Bvh::from_raw_parts(&self.nodes, &self.indices, self.depth)
    }
}

/// Boxes on a jittered grid, some overlapping their neighbours.
pub(crate) fn boxes(n: usize, seed: u64, offset: Vec3) -> Vec<Aabb> {
    let mut r = Rng(seed);
    (0..n)
        .map(|i| {
            let c = Vec3::new((i % 10) as f32, (i / 10 % 10) as f32, (i / 100) as f32) + offset;
            let lo = c + r.point(0.6, Vec3::ZERO);
            Aabb::new(
                lo,
                lo + Vec3::new(r.next(), r.next(), r.next()) * 0.9 + 0.05,
            )
        })
        .collect()
}

pub(crate) fn reference_pairs(a: &Tree, b: &Tree) -> Vec<(u32, u32)> {
    let mut want = Vec::new();
    brute_force::pairs(&a.prims, &b.prims, |i, j| want.push((i, j)));
    want.sort_unstable();
    want
}

/// Scene pairs for the traversal exercises: overlapping grids with different
/// leaf sizes, and tiny trees (1 to 3 leaves) apart and touching.
pub(crate) fn traversal_cases() -> Vec<(Tree, Tree)> {
    let mut cases = vec![
        (
            Tree::new(boxes(300, 1, Vec3::ZERO), 1),
            Tree::new(boxes(250, 2, Vec3::splat(0.4)), 3),
        ),
        (
            Tree::new(boxes(64, 3, Vec3::ZERO), 4),
            Tree::new(boxes(500, 4, Vec3::new(-2.0, 1.0, 0.0)), 1),
        ),
    ];
    for (na, nb) in [(1, 1), (1, 3), (2, 3), (3, 2)] {
        for gap in [0.0f32, 0.5] {
            let a = (0..na)
                .map(|i| Aabb::new(Vec3::X * (2 * i) as f32, Vec3::X * (2 * i) as f32 + 1.0))
                .collect();
            let b = (0..nb)
                .map(|i| {
                    let lo = Vec3::new(1.0 + gap, 0.0, 0.0) + Vec3::Y * (2 * i) as f32;
                    Aabb::new(lo, lo + 1.0)
                })
                .collect();
            cases.push((Tree::new(a, 1), Tree::new(b, 1)));
        }
    }
    cases
}

pub(crate) fn sorted(mut v: Vec<(u32, u32)>) -> Vec<(u32, u32)> {
    v.sort_unstable();
    v
}

pub(crate) fn node(min: [f32; 3], max: [f32; 3], leaf: bool) -> Node<Aabb> {
    Node {
        bv: b(min, max),
        first: 0,
        count: leaf as u32,
    }
}

thread_local! {
    /// Why the running check failed, in the student's words: the first
    /// explanation a check gave (see [`fail`]).
    static EXPLANATION: std::cell::RefCell<Option<String>> = const { std::cell::RefCell::new(None) };
}

/// Records why a check fails: what went in, what was expected and what came
/// back, in words a student understands. Returns `false`, so that a check
/// can end with `return fail(..)`. The first explanation of a run is kept
/// (later ones are usually consequences of it).
pub(crate) fn fail(why: impl Into<String>) -> bool {
    EXPLANATION.with(|x| {
        let mut x = x.borrow_mut();
        if x.is_none() {
            *x = Some(why.into());
        }
    });
    false
}

/// `want == got`, explained on failure as "CALL returned GOT, expected WANT".
pub(crate) fn same<T: PartialEq + std::fmt::Debug>(
    call: impl std::fmt::Display,
    want: T,
    got: T,
) -> bool {
    want == got || fail(format!("{call} returned {got:?}, expected {want:?}"))
}

/// Takes the explanation recorded on this thread since the last call.
pub(crate) fn take_explanation() -> Option<String> {
    EXPLANATION.with(|x| x.borrow_mut().take())
}

/// A box as a student would write it: `[min (x, y, z), max (x, y, z)]`.
pub(crate) fn show_box(b: &Aabb) -> String {
    format!("[min {}, max {}]", show_point(b.min), show_point(b.max))
}

/// A point as `(x, y, z)`, each coordinate in its shortest exact form.
pub(crate) fn show_point(p: Vec3) -> String {
    format!("({}, {}, {})", p.x, p.y, p.z)
}

/// `want == got` for lists, explained on failure by the first entry that
/// differs (or the one missing or extra), each shown with `show`: for long
/// outputs, where printing everything would bury the mistake.
pub(crate) fn same_list<T: PartialEq>(
    call: impl std::fmt::Display,
    want: &[T],
    got: &[T],
    show: impl Fn(&T) -> String,
) -> bool {
    if want == got {
        return true;
    }
    let (n, m) = (got.len(), want.len());
    let why = match (0..n.min(m)).find(|&k| want[k] != got[k]) {
        Some(k) => format!(
            "{call} returned {n} entries, expected {m}; the first that differs is \
             entry {k}: {}, expected {}",
            show(&got[k]),
            show(&want[k])
        ),
        None if n > m => format!(
            "{call} returned {n} entries, expected {m}: the first {m} are right, \
             then comes {}",
            show(&got[m])
        ),
        None => format!(
            "{call} returned {n} entries, expected {m}: the first {n} are right, \
             then {} is missing",
            show(&want[n])
        ),
    };
    fail(why)
}

/// [`close`], explained on failure as "CALL returned GOT, expected WANT".
pub(crate) fn near(call: impl std::fmt::Display, want: f64, got: f64) -> bool {
    close(got, want) || fail(format!("{call} returned {got}, expected {want}"))
}

/// A tree `depth` levels deep whose left children are internal down to the
/// last level and whose right children are leaves (one primitive each): a
/// depth-first walk with a stack keeps one right child waiting per level.
/// Internal node at level `d` is node `0` for `d = 0`, else `2d - 1`; its
/// children are `2d + 1` and `2d + 2`. The right leaf under level `d` holds
/// the unit cube at `x = d`, the last left leaf the one at `x = depth`.
pub(crate) fn left_deep(depth: usize) -> (Vec<Node<Aabb>>, Vec<u32>) {
    assert!(depth >= 1);
    let mut nodes = vec![Node::<Aabb>::EMPTY; 2 * depth + 1];
    let internal = |d: usize| if d == 0 { 0 } else { 2 * d - 1 };
    for d in 0..depth {
        let i = internal(d);
        nodes[i] = Node {
            bv: Aabb::new(
                Vec3::new(d as f32, 0.0, 0.0),
                Vec3::new(depth as f32 + 1.0, 1.0, 1.0),
            ),
            first: 2 * d as u32 + 1,
            count: 0,
        };
        nodes[2 * d + 2] = Node {
            bv: unit_at(d as f32),
            first: d as u32,
            count: 1,
        };
    }
    nodes[2 * depth - 1] = Node {
        bv: unit_at(depth as f32),
        first: depth as u32,
        count: 1,
    };
    (nodes, (0..=depth as u32).collect())
}
