//! Exercise 29: oriented boxes fitted with given axes. The checks, and the plausible wrong answers they must reject.

use super::common::*;

/// The checks of exercise 29.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 29,
            name: "OBB fit: every point inside in exact arithmetic, also far from the origin; the axes given",
            points: 4,
            run: |e| {
                let mut r = Rng(2929);
                obb_cases(&mut r).iter().all(|(what, pts, axes)| {
                    let b = e.fit_obb(pts, *axes);
                    let call = format!("fit_obb({what}, axes {})", show_axes(axes));
                    if b.axes != *axes {
                        return fail(format!(
                            "{call} returned axes {}, expected the axes given",
                            show_axes(&b.axes)
                        ));
                    }
                    pts.iter().all(|p| {
                        let v = p.as_dvec3() - b.center.as_dvec3();
                        (0..3).all(|k| {
                            let t = b.axes[k].as_dvec3().dot(v).abs();
                            t <= b.half_extents[k] as f64
                                || fail(format!(
                                    "{call} returned centre {} and half extents {}: point {} \
                                     is outside it, {t} from the centre along axis {k} (in f64)",
                                    show_point(b.center),
                                    show_point(b.half_extents),
                                    show_point(*p)
                                ))
                        })
                    })
                })
            },
        },
        Check {
            exercise: 29,
            name: "OBB fit: tight along the given axes (not the AABB, not around the mean)",
            points: 4,
            run: |e| {
                let mut r = Rng(2930);
                obb_cases(&mut r).iter().all(|(what, pts, axes)| {
                    let b = e.fit_obb(pts, *axes);
                    let want = exact_half_extents(pts, axes);
                    // What rounding may add far from the origin: the centre
                    // rounded to f32, and f32 axes that are orthonormal only
                    // to about 1e-7, over a centre 1e6 away.
                    let moved = b.center.abs().max_element() as f64 * 2f64.powi(-20);
                    (0..3).all(|k| {
                        let h = b.half_extents[k] as f64;
                        let most = want[k] * (1.0 + 1e-5) + moved + 1e-30;
                        (h <= most && h >= want[k] * (1.0 - 1e-5))
                            || fail(format!(
                                "fit_obb({what}, axes {}) returned half extent {h} on axis {k}; \
                                 half the points' projection range is {}, so at most {most} \
                                 (and no less than that)",
                                show_axes(axes),
                                want[k]
                            ))
                    })
                })
            },
        },
        Check {
            exercise: 29,
            name: "OBB fit: no points give Obb::EMPTY",
            points: 2,
            run: |e| {
                let mut r = Rng(2931);
                let axes = rotated_axes(&mut r);
                same(
                    format!("fit_obb([], axes {})", show_axes(&axes)),
                    Obb::EMPTY,
                    e.fit_obb(&[], axes),
                )
            },
        },
    ]
}

fn show_axes(axes: &[Vec3; 3]) -> String {
    format!(
        "[{}, {}, {}]",
        show_point(axes[0]),
        show_point(axes[1]),
        show_point(axes[2])
    )
}

/// Orthonormal axes turned by a random rotation.
fn rotated_axes(r: &mut Rng) -> [Vec3; 3] {
    let q = bvhkit::glam::Quat::from_euler(
        bvhkit::glam::EulerRot::XYZ,
        r.next() * 6.0,
        r.next() * 6.0,
        r.next() * 6.0,
    );
    [q * Vec3::X, q * Vec3::Y, q * Vec3::Z]
}

/// Point sets for exercise 29 with axes to fit them in: one point, a
/// stick along an axis, clouds near the origin and a million units away
/// (where f32 rounding of the centre decides containment), squashed along
/// one axis.
fn obb_cases(r: &mut Rng) -> Vec<(String, Vec<Vec3>, [Vec3; 3])> {
    let mut out = Vec::new();
    let axes = rotated_axes(r);
    out.push((
        "[(3, -2, 7.5)]".to_string(),
        vec![Vec3::new(3.0, -2.0, 7.5)],
        axes,
    ));
    out.push((
        "5 points on a stick along the first axis, near (1000, 1000, 1000)".to_string(),
        (0..5)
            .map(|i| axes[0] * i as f32 + Vec3::splat(1e3))
            .collect(),
        axes,
    ));
    out.push((
        "[(1, 2, 3), (-4, 5, 0.5), (2, -1, 1)], with the axes x, y, z".to_string(),
        vec![
            Vec3::new(1.0, 2.0, 3.0),
            Vec3::new(-4.0, 5.0, 0.5),
            Vec3::new(2.0, -1.0, 1.0),
        ],
        [Vec3::X, Vec3::Y, Vec3::Z],
    ));
    for k in 0..60 {
        let axes = rotated_axes(r);
        let offset = if k % 2 == 0 { 0.0 } else { 1e6 };
        let base = r.point(offset, Vec3::ZERO);
        let squash = Vec3::new(1.0, 0.3, 0.01 + r.next());
        let n = 1 + (r.next() * 40.0) as usize;
        let pts = (0..n)
            .map(|_| {
                let p = r.point(5.0, Vec3::ZERO) * squash;
                base + axes[0] * p.x + axes[1] * p.y + axes[2] * p.z
            })
            .collect();
        let place = if k % 2 == 0 {
            "near the origin"
        } else {
            "a million units from the origin"
        };
        out.push((
            format!("{n} points squashed along the third axis, {place}"),
            pts,
            axes,
        ));
    }
    out
}

/// Half the projection range of the points on each axis, in f64.
fn exact_half_extents(pts: &[Vec3], axes: &[Vec3; 3]) -> [f64; 3] {
    let mut out = [0.0; 3];
    for (k, a) in axes.iter().enumerate() {
        let (lo, hi) = pts
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| {
                let t = a.as_dvec3().dot(p.as_dvec3());
                (l.min(t), h.max(t))
            });
        out[k] = (hi - lo) / 2.0;
    }
    out
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 8;

    pub fn fit_obb(which: u32, points: &[Vec3], axes: [Vec3; 3]) -> Obb {
        if points.is_empty() {
            // No special case: a box of size 0 at the origin.
            if which == 5 {
                return Obb {
                    center: Vec3::ZERO,
                    axes,
                    half_extents: Vec3::ZERO,
                };
            }
            return Obb::EMPTY;
        }
        let ax = axes.map(|a| a.as_dvec3());
        let proj = |p: &Vec3| {
            let p = p.as_dvec3();
            bvhkit::glam::DVec3::new(ax[0].dot(p), ax[1].dot(p), ax[2].dot(p))
        };
        let (lo, hi) = points.iter().fold(
            (
                bvhkit::glam::DVec3::INFINITY,
                bvhkit::glam::DVec3::NEG_INFINITY,
            ),
            |(l, h), p| (l.min(proj(p)), h.max(proj(p))),
        );
        let mid = (lo + hi) * 0.5;
        let from_mid = |m: bvhkit::glam::DVec3| (ax[0] * m.x + ax[1] * m.y + ax[2] * m.z).as_vec3();
        match which {
            // Half the range, rounded to nearest: the rounded centre
            // leaves far points just outside.
            1 => Obb {
                center: from_mid(mid),
                axes,
                half_extents: ((hi - lo) * 0.5).as_vec3(),
            },
            // The points' AABB: right when the axes are x, y, z, loose
            // otherwise.
            2 => {
                let mut b = Aabb::EMPTY;
                for p in points {
                    b.grow(*p);
                }
                let h = (b.max - b.min) * 0.5;
                let r = h.x.abs() + h.y.abs() + h.z.abs();
                Obb {
                    center: b.center(),
                    axes,
                    half_extents: Vec3::splat(r),
                }
            }
            // Centred on the mean of the points, not the middle of the
            // range: contains them only with extents past the tight ones.
            3 => {
                let mean = points
                    .iter()
                    .map(|p| p.as_dvec3())
                    .sum::<bvhkit::glam::DVec3>()
                    / points.len() as f64;
                let c = mean.as_vec3();
                let h = reach(points, &ax, c);
                Obb {
                    center: c,
                    axes,
                    half_extents: h.as_vec3() * 1.0001,
                }
            }
            // All in f32: projections of far points lose their last digits.
            4 => {
                let (lo, hi) =
                    points
                        .iter()
                        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(l, h), p| {
                            let t = Vec3::new(axes[0].dot(*p), axes[1].dot(*p), axes[2].dot(*p));
                            (l.min(t), h.max(t))
                        });
                let m = (lo + hi) * 0.5;
                Obb {
                    center: axes[0] * m.x + axes[1] * m.y + axes[2] * m.z,
                    axes,
                    half_extents: (hi - lo) * 0.5,
                }
            }
            // Rounds the half extents up, but measures them from the exact
            // centre, not the rounded one it returns.
            6 => {
                let h = (hi - lo) * 0.5;
                Obb {
                    center: from_mid(mid),
                    axes,
                    half_extents: round_up(h),
                }
            }
            // The centre in the axes' frame (the middle projections), not in the world.
            7 => {
                let h = (hi - lo) * 0.5;
                Obb {
                    center: mid.as_vec3(),
                    axes,
                    half_extents: round_up(h),
                }
            }
            // The whole projection range as the half extent: contains, twice too big.
            8 => {
                let c = from_mid(mid);
                let h = reach(points, &ax, c);
                Obb {
                    center: c,
                    axes,
                    half_extents: (h * 2.0).as_vec3() + 1e-3,
                }
            }
            _ => Reference.fit_obb(points, axes),
        }
    }

    /// The farthest projection of `points` from `c` along each axis, in f64.
    fn reach(points: &[Vec3], ax: &[bvhkit::glam::DVec3; 3], c: Vec3) -> bvhkit::glam::DVec3 {
        points.iter().fold(bvhkit::glam::DVec3::ZERO, |h, p| {
            let v = p.as_dvec3() - c.as_dvec3();
            h.max(bvhkit::glam::DVec3::new(
                ax[0].dot(v).abs(),
                ax[1].dot(v).abs(),
                ax[2].dot(v).abs(),
            ))
        })
    }

    /// Each component rounded up to an `f32` at or above it.
    fn round_up(h: bvhkit::glam::DVec3) -> Vec3 {
        Vec3::new(
            bvhkit::round::up(h.x),
            bvhkit::round::up(h.y),
            bvhkit::round::up(h.z),
        )
    }
}
