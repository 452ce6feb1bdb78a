//! What every crate in the comparison shares: the scene (the same f32
//! triangles and boxes for all), the timing rule, the SAH formula, the pair
//! checksum and the triangle test behind every crate's ray callback.
//!
//! Each peer module (`ours`, `parry`, `obvhs_peer`, `bvh_peer`) turns a
//! [`Scene`] into a list of [`Measured`] trees; `main` checks every answer
//! against one ground truth and prints the tables.

use bvhkit::glam::Vec3;
use bvhkit::{Aabb, Primitive, Ray, RayTarget, Triangle};
use std::time::Instant;

/// One benchmark scene: a mesh `a`, a moved copy `b` (already in `a`'s frame,
/// so every crate sees the same boxes), and the rays.
#[derive(Debug)]
pub struct Scene {
    /// Name shown in the tables (the mesh file's stem, or `armadillo-x20`).
    pub name: String,
    /// The mesh.
    pub a: Vec<Triangle>,
    /// The mesh moved by a small rotation and translation.
    pub b: Vec<Triangle>,
    /// `a[i].bounds()`, computed once: the input every builder gets.
    pub boxes_a: Vec<Aabb>,
    /// `b[i].bounds()`.
    pub boxes_b: Vec<Aabb>,
    /// Random rays (unit direction, `t_max = INFINITY`) aimed into `a`'s box.
    pub rays: Vec<Ray>,
}

/// How many times to repeat each measurement.
#[derive(Clone, Copy, Debug)]
pub struct Runs {
    /// Counted builds (one more, uncounted, warms the allocator first).
    pub build: usize,
    /// Counted pair queries.
    pub pairs: usize,
    /// Counted passes over all rays.
    pub rays: usize,
}

/// Median and minimum of the counted runs, in milliseconds.
#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub struct Timing {
    /// Median.
    pub median_ms: f64,
    /// Minimum.
    pub min_ms: f64,
}

/// Runs `f` once uncounted (warm caches and allocator), then `runs` times
/// counted; returns the timing and the last result.
pub fn time<R>(runs: usize, mut f: impl FnMut() -> R) -> (Timing, R) {
    time_setup(runs, || (), |()| f())
}

/// Surface area of a box, in f64.
pub fn area(b: &Aabb) -> f64 {
    let e = (b.max - b.min).as_dvec3().max(bvhkit::glam::DVec3::ZERO);
    2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
}

/// The SAH cost every crate's tree is scored with (the same formula as
/// bvhkit's `TreeStats::sah_cost`):
///
/// `SAH = (C_t * sum over internal nodes A(n) + C_i * sum over leaves A(l) * |l|) / A(root)`
///
/// with `C_t = C_i = 1` and `A` the surface area of the node's box. The root
/// counts as an internal node (term 1). A tree whose root is not one node (a
/// wide root, parry's root pair) passes the enclosing box as `root` and
/// lists that virtual root among `nodes` as internal.
///
/// `nodes` yields `(box, primitive count)`, count 0 for an internal node.
pub fn sah(root: &Aabb, nodes: impl IntoIterator<Item = (Aabb, u32)>) -> f64 {
    let root_area = area(root).max(f64::MIN_POSITIVE);
    nodes
        .into_iter()
        .map(|(b, count)| area(&b) / root_area * f64::from(count.max(1)))
        .sum()
}

/// The answer of a pair query: how many pairs, and an order-independent
/// checksum of them (a wrapping sum of a 64-bit mix of `(i, j)`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct PairSum {
    /// Number of pairs reported.
    pub count: u64,
    /// Wrapping sum of `mix(i, j)` over the pairs.
    pub checksum: u64,
}

impl PairSum {
    /// Adds the pair (triangle `i` of `a`, triangle `j` of `b`).
    #[inline(always)]
    pub fn add(&mut self, i: u32, j: u32) {
        self.count += 1;
        self.checksum = self
            .checksum
            .wrapping_add(mix((u64::from(i) << 32) | u64::from(j)));
    }
}

/// SplitMix64's finaliser: a pair reported twice, or a wrong pair, changes
/// the sum with overwhelming probability.
#[inline(always)]
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The box test every crate's pair answer is defined by: closed intervals
/// (touching boxes overlap), as `bvhkit::Aabb::overlaps`.
#[inline(always)]
pub fn boxes_overlap(p: &Aabb, q: &Aabb) -> bool {
    p.min.x <= q.max.x
        && q.min.x <= p.max.x
        && p.min.y <= q.max.y
        && q.min.y <= p.max.y
        && p.min.z <= q.max.z
        && q.min.z <= p.max.z
}

/// The triangle test behind every crate's ray callback: bvhkit's f64
/// Möller–Trumbore (`Triangle::ray_hit`), limited to `t <= t_max`.
#[inline]
pub fn hit_triangle(tris: &[Triangle], prim: u32, ray: &Ray, t_max: f32) -> Option<f32> {
    let r = ray.with_t_max(t_max).expect("t_max from a hit is >= 0");
    tris[prim as usize].ray_hit(&r)
}

/// One crate's answer for one ray: the primitive hit and its distance.
pub type RayHit = Option<(u32, f32)>;

/// The measurements of one tree: one row of the tables and the JSON.
#[derive(Debug)]
pub struct Measured {
    /// The crate (`bvhkit`, `parry3d`, `obvhs`, `bvh`).
    pub krate: &'static str,
    /// Builder (and layout after a `/` where the tree was converted).
    pub builder: String,
    /// Build time from the triangles' boxes (conversion included for a
    /// converted layout).
    pub build: Timing,
    /// Leaves of the tree.
    pub leaves: usize,
    /// SAH cost by [`sah`], where the tree is binary (`None` for wide ones).
    pub sah: Option<f64>,
    /// Bytes of nodes plus primitive indices.
    pub bytes: usize,
    /// The pair query (A against B, every triangle pair whose boxes
    /// overlap), where this tree runs it.
    pub pairs: Option<(Timing, PairSum)>,
    /// Closest hits of every ray in `Scene::rays`, where this tree runs them.
    pub rays: Option<(Timing, Vec<RayHit>)>,
    /// What was chosen for this crate, for the notes under the table.
    pub note: &'static str,
}

/// Random rays into `bounds`: origins in the box grown by half its size on
/// each side, directions towards a random point inside it, normalised.
/// Deterministic for a given `seed`.
pub fn random_rays(bounds: &Aabb, n: usize, seed: u64) -> Vec<Ray> {
    let mut s = seed;
    let mut next = move || {
        s = s.wrapping_add(0x9e37_79b9_7f4a_7c15);
        (mix(s) >> 40) as f32 / (1u64 << 24) as f32
    };
    let (lo, size) = (bounds.min, bounds.max - bounds.min);
    let mut point = |grow: f32| {
        let u = Vec3::new(next(), next(), next()) * (1.0 + 2.0 * grow) - Vec3::splat(grow);
        lo + u * size
    };
    (0..n)
        .filter_map(|_| {
            let origin = point(0.5);
            let dir = (point(0.0) - origin).normalize_or_zero();
            Ray::new(origin, dir, f32::INFINITY).ok()
        })
        .collect()
}

/// The bounding box of a slice of boxes.
pub fn union(boxes: &[Aabb]) -> Aabb {
    boxes.iter().fold(Aabb::EMPTY, |acc, b| {
        Aabb::new(acc.min.min(b.min), acc.max.max(b.max))
    })
}

/// The boxes of triangles.
pub fn bounds_of(tris: &[Triangle]) -> Vec<Aabb> {
    tris.iter().map(Primitive::bounds).collect()
}

/// Counted runs go on past the requested count until they add up to this
/// much time: five builds of a quarter of a millisecond are 1.25 ms, which
/// one burst of a shared machine's noise decides (the fast builders' ratio
/// swung from 0.68x to 1.46x between three quick runs of one day).
pub const MIN_TIMED_MS: f64 = 200.0;
/// At most this many counted runs, however short each is.
pub const MAX_RUNS: usize = 1000;

/// Like [`time`], but `setup` makes a fresh input for every run outside the
/// timed part (for builders that consume or mutate their input). Runs at
/// least `runs` times, and more until [`MIN_TIMED_MS`] are timed (at most
/// [`MAX_RUNS`]).
pub fn time_setup<S, R>(
    runs: usize,
    mut setup: impl FnMut() -> S,
    mut f: impl FnMut(S) -> R,
) -> (Timing, R) {
    std::hint::black_box(f(setup()));
    let mut ms = Vec::with_capacity(runs.max(1));
    let mut last = None;
    let mut total = 0.0;
    while ms.len() < runs.max(1) || (total < MIN_TIMED_MS && ms.len() < MAX_RUNS) {
        let input = setup();
        let t = Instant::now();
        let r = std::hint::black_box(f(input));
        let elapsed = t.elapsed().as_secs_f64() * 1e3;
        ms.push(elapsed);
        total += elapsed;
        last = Some(r);
    }
    ms.sort_by(f64::total_cmp);
    let timing = Timing {
        median_ms: ms[ms.len() / 2],
        min_ms: ms[0],
    };
    (timing, last.expect("at least one run"))
}

/// Times two ways of doing one job, `a` and `b`, alternating: each once
/// uncounted, then rounds of one counted run each, `a` first in even
/// rounds and `b` first in odd ones, for at least `runs` rounds and more
/// until each side has [`MIN_TIMED_MS`] (at most [`MAX_RUNS`]). A shared
/// machine's speed drifts over seconds; timing all of `a`'s runs and then
/// all of `b`'s put each side in a different stretch of that drift (a
/// 100 ms task's ratio swung from 0.79x to 1.10x between two runs of the
/// engine tasks), where alternating puts both sides in the same stretch.
pub fn time_pair<A, B>(
    runs: usize,
    mut a: impl FnMut() -> A,
    mut b: impl FnMut() -> B,
) -> ((Timing, A), (Timing, B)) {
    std::hint::black_box(a());
    std::hint::black_box(b());
    let (mut ms_a, mut ms_b) = (Vec::new(), Vec::new());
    let (mut last_a, mut last_b) = (None, None);
    let (mut total_a, mut total_b) = (0.0, 0.0);
    let mut round = 0;
    while ms_a.len() < runs.max(1)
        || ((total_a < MIN_TIMED_MS || total_b < MIN_TIMED_MS) && ms_a.len() < MAX_RUNS)
    {
        for side in [round % 2, 1 - round % 2] {
            let t = Instant::now();
            if side == 0 {
                last_a = Some(std::hint::black_box(a()));
                let elapsed = t.elapsed().as_secs_f64() * 1e3;
                ms_a.push(elapsed);
                total_a += elapsed;
            } else {
                last_b = Some(std::hint::black_box(b()));
                let elapsed = t.elapsed().as_secs_f64() * 1e3;
                ms_b.push(elapsed);
                total_b += elapsed;
            }
        }
        round += 1;
    }
    let timing = |mut ms: Vec<f64>| {
        ms.sort_by(f64::total_cmp);
        Timing {
            median_ms: ms[ms.len() / 2],
            min_ms: ms[0],
        }
    };
    (
        (timing(ms_a), last_a.expect("at least one run")),
        (timing(ms_b), last_b.expect("at least one run")),
    )
}

impl Scene {
    /// The scene for mesh `a`: `b` is `a` turned by 0.02 rad (about y, and
    /// 0.01 about x) and shifted by 1% of the box size, so most triangles
    /// overlap a few of their moved neighbours; `rays` random rays.
    pub fn new(name: &str, a: Vec<Triangle>, rays: usize) -> Scene {
        let boxes_a = bounds_of(&a);
        let bounds = union(&boxes_a);
        let shift = (bounds.max - bounds.min) * Vec3::new(0.01, 0.007, 0.004);
        let b = bvhkit_std::scene::transformed(&a, 0.02, shift);
        let boxes_b = bounds_of(&b);
        let rays = random_rays(&bounds, rays, 0x5eed_0001);
        Scene {
            name: name.to_string(),
            a,
            b,
            boxes_a,
            boxes_b,
            rays,
        }
    }
}

/// Brute-force references for small scenes (tests only: quadratic).
#[cfg(test)]
pub mod reference {
    use super::*;

    /// A small scene: a generated rock of 1 280 triangles, 300 rays.
    pub fn small_scene() -> Scene {
        Scene::new("rock-1280", bvhkit_std::scene::rock(3, 7), 300)
    }

    /// Every pair `(i, j)` with overlapping boxes, by testing all of them.
    pub fn pairs(scene: &Scene) -> PairSum {
        let mut sum = PairSum::default();
        for (i, p) in scene.boxes_a.iter().enumerate() {
            for (j, q) in scene.boxes_b.iter().enumerate() {
                if boxes_overlap(p, q) {
                    sum.add(i as u32, j as u32);
                }
            }
        }
        sum
    }

    /// The closest hit of each ray, testing every triangle.
    pub fn rays(scene: &Scene) -> Vec<RayHit> {
        (0..scene.rays.len())
            .map(|k| crate::truth::ray(scene, k))
            .collect()
    }

    /// Runs one crate's `run` on [`small_scene`] once and checks every tree
    /// it measured; returns them for further assertions.
    pub fn run_and_check(run: fn(&Scene, Runs) -> Vec<Measured>) -> Vec<Measured> {
        let scene = small_scene();
        let runs = Runs {
            build: 1,
            pairs: 1,
            rays: 1,
        };
        let m = run(&scene, runs);
        check(&scene, &m);
        m
    }

    /// Checks a crate's measured trees against the references: every pair
    /// answer equal, every ray's distance equal (ties between primitives at
    /// the same distance may name either).
    pub fn check(scene: &Scene, measured: &[Measured]) {
        let (want_pairs, want_rays) = (pairs(scene), rays(scene));
        assert!(want_pairs.count > 0 && want_rays.iter().any(Option::is_some));
        assert!(!measured.is_empty());
        for m in measured {
            assert!(m.leaves > 0 && m.bytes > 0, "{}: empty tree", m.builder);
            if let Some((_, got)) = &m.pairs {
                assert_eq!(*got, want_pairs, "{} {}: pairs", m.krate, m.builder);
            }
            if let Some((_, got)) = &m.rays {
                assert_eq!(got.len(), want_rays.len());
                for (k, (g, w)) in got.iter().zip(&want_rays).enumerate() {
                    assert_eq!(
                        g.map(|h| h.1),
                        w.map(|h| h.1),
                        "{} {}: ray {k}",
                        m.krate,
                        m.builder
                    );
                }
            }
            if let Some(s) = m.sah {
                assert!(
                    s.is_finite() && s >= 1.0,
                    "{} {}: sah {s}",
                    m.krate,
                    m.builder
                );
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::RefCell;

    #[test]
    fn paired_timing_alternates_which_side_goes_first() {
        let order = RefCell::new(String::new());
        let ((ta, a), (tb, b)) = time_pair(
            3,
            || {
                order.borrow_mut().push('a');
                1
            },
            || {
                order.borrow_mut().push('b');
                2
            },
        );
        // One uncounted run each, then rounds a-first, b-first, ... until
        // each side has MIN_TIMED_MS (near-instant closures: MAX_RUNS).
        let order = order.into_inner();
        assert!(order.starts_with("ab"), "warm-up runs first");
        assert!(order[2..].starts_with("abbaab"), "{order}");
        assert_eq!(order.len(), 2 + 2 * MAX_RUNS);
        assert_eq!((a, b), (1, 2));
        assert!(ta.min_ms <= ta.median_ms && tb.min_ms <= tb.median_ms);
    }
}
