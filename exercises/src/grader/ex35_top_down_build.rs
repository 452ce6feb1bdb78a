//! Exercise 35: a whole top-down build with the object median, into the
//! caller's arrays. The checks, and the plausible wrong answers they must
//! reject. The student's tree is not compared with the reference's array
//! (children may be numbered in any order): it is walked and every rule of
//! the statement is checked node by node.

use super::common::*;

/// The checks of exercise 35.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 35,
            name: "no boxes: 0 nodes; one box: one leaf",
            points: 1,
            run: |e| {
                let one = vec![b([1.0, 2.0, 3.0], [4.0, 5.0, 6.0])];
                build_is_valid(e, &[], 4, "no boxes")
                    && build_is_valid(e, &one, 4, "one box")
                    && build_is_valid(e, &one, 1, "one box, leaves of 1")
            },
        },
        Check {
            exercise: 35,
            name:
                "every primitive in exactly one leaf of at most max_leaf, every node reached once",
            points: 2,
            run: |e| {
                [1, 2, 4, 7].iter().all(|&k| {
                    build_is_valid(
                        e,
                        &boxes(300, 11, Vec3::ZERO),
                        k,
                        "300 boxes on a jittered grid",
                    )
                })
            },
        },
        Check {
            exercise: 35,
            name: "each node's box is exactly its primitives' union (also far from the origin)",
            points: 2,
            run: |e| {
                let far = boxes(200, 12, Vec3::new(1.0e6, -3.0e5, 7.0e4));
                build_is_valid(e, &far, 2, "200 boxes a million units from the origin")
                    && build_is_valid(e, &uneven_boxes(), 1, "boxes of very different sizes")
            },
        },
        Check {
            exercise: 35,
            name: "each split is the object median along the longest axis of the node's centroids",
            points: 3,
            run: |e| {
                build_is_valid(
                    e,
                    &boxes(300, 13, Vec3::ZERO),
                    3,
                    "300 boxes on a jittered grid",
                ) && build_is_valid(
                    e,
                    &long_in_x(),
                    1,
                    "64 boxes 100 long in x whose centres lie along y",
                ) && build_is_valid(e, &vec![unit_at(0.0); 100], 4, "100 identical boxes")
            },
        },
        Check {
            exercise: 35,
            name: "a node of exactly max_leaf primitives is a leaf; one more is split",
            points: 1,
            run: |e| {
                let row = |n: usize| (0..n).map(|i| unit_at(2.0 * i as f32)).collect::<Vec<_>>();
                build_is_valid(e, &row(8), 8, "8 cubes in a row, max_leaf 8")
                    && build_is_valid(e, &row(9), 8, "9 cubes in a row, max_leaf 8")
                    && build_is_valid(e, &row(17), 4, "17 cubes in a row, max_leaf 4")
            },
        },
        Check {
            exercise: 35,
            name: "too little storage: None, without panicking; exactly enough: a tree",
            points: 2,
            run: |e| {
                let scene = boxes(50, 14, Vec3::ZERO);
                let n = scene.len();
                for (nodes, idx) in [(2 * n - 2, n), (2 * n - 1, n - 1), (0, 0)] {
                    let (got, _, _) = run(e, &scene, 1, nodes, idx);
                    if got.is_some() {
                        return fail(format!(
                            "top_down_build(50 boxes, max_leaf 1, {nodes} nodes, {idx} indices) \
                             returned {got:?}, expected None (a tree needs {} nodes and {n} indices)",
                            2 * n - 1
                        ));
                    }
                }
                build_is_valid(e, &scene, 1, "50 boxes, max_leaf 1, exactly 2n - 1 nodes")
            },
        },
        Check {
            exercise: 35,
            name: "arrays that held a bigger tree before are written in full",
            points: 1,
            run: |e| {
                let (big, small) = (boxes(300, 15, Vec3::ZERO), boxes(40, 16, Vec3::ONE));
                let mut nodes = vec![garbage(); 2 * big.len()];
                let mut idx = vec![u32::MAX; big.len()];
                let _ = e.top_down_build(&big, 2, &mut nodes, &mut idx);
                let got = e.top_down_build(&small, 2, &mut nodes, &mut idx);
                validate(&small, 2, got, &nodes, &idx)
                    .map_err(|why| {
                        fail(format!(
                            "40 boxes built after 300 in the same arrays: {why}"
                        ))
                    })
                    .is_ok()
            },
        },
    ]
}

/// A node that is no node: what the arrays hold before a build.
fn garbage() -> Node<Aabb> {
    Node {
        bv: b([-7.0; 3], [9.0; 3]),
        first: 999_999,
        count: 3,
    }
}

/// The student's build of `scene` into arrays of the given lengths, filled
/// with garbage first.
fn run(
    e: &dyn Exercises,
    scene: &[Aabb],
    max_leaf: u32,
    nodes_len: usize,
    idx_len: usize,
) -> (Option<usize>, Vec<Node<Aabb>>, Vec<u32>) {
    let mut nodes = vec![garbage(); nodes_len];
    let mut idx = vec![u32::MAX; idx_len];
    let got = e.top_down_build(scene, max_leaf, &mut nodes, &mut idx);
    (got, nodes, idx)
}

/// Builds `scene` into arrays of exactly the needed lengths and checks the
/// tree, explaining the first rule it breaks.
fn build_is_valid(e: &dyn Exercises, scene: &[Aabb], max_leaf: u32, what: &str) -> bool {
    let n = scene.len();
    let (got, nodes, idx) = run(e, scene, max_leaf, (2 * n).saturating_sub(1), n);
    match validate(scene, max_leaf, got, &nodes, &idx) {
        Ok(()) => true,
        Err(why) => fail(format!("{what}, max_leaf {max_leaf}: {why}")),
    }
}

/// Every rule of the statement, or the first one broken.
fn validate(
    scene: &[Aabb],
    max_leaf: u32,
    got: Option<usize>,
    nodes: &[Node<Aabb>],
    idx: &[u32],
) -> Result<(), String> {
    let n = scene.len();
    let used = got.ok_or("returned None with enough storage")?;
    if n == 0 {
        return if used == 0 {
            Ok(())
        } else {
            Err(format!("returned {used} nodes, expected 0"))
        };
    }
    if used == 0 || used > 2 * n - 1 || used > nodes.len() {
        return Err(format!(
            "returned {used} nodes, expected 1 to {}",
            2 * n - 1
        ));
    }
    let mut reached = vec![false; used];
    let mut seen = vec![false; n];
    walk(
        scene,
        max_leaf,
        nodes,
        idx,
        used,
        0,
        &mut reached,
        &mut seen,
    )?;
    if let Some(k) = reached.iter().position(|r| !r) {
        return Err(format!(
            "returned {used} nodes, but node {k} is not in the tree (the count must be the \
             nodes written)"
        ));
    }
    if let Some(p) = seen.iter().position(|s| !s) {
        return Err(format!("primitive {p} is in no leaf"));
    }
    Ok(())
}

/// Checks the subtree at `node` and returns its primitives.
#[allow(clippy::too_many_arguments)]
fn walk(
    scene: &[Aabb],
    max_leaf: u32,
    nodes: &[Node<Aabb>],
    idx: &[u32],
    used: usize,
    node: usize,
    reached: &mut [bool],
    seen: &mut [bool],
) -> Result<Vec<u32>, String> {
    if node >= used {
        return Err(format!(
            "a child index {node} is past the {used} nodes returned"
        ));
    }
    if std::mem::replace(&mut reached[node], true) {
        return Err(format!("node {node} is reached twice"));
    }
    let nd = nodes[node];
    let prims = if nd.count > 0 {
        let (first, count) = (nd.first as usize, nd.count as usize);
        if first + count > scene.len() {
            return Err(format!(
                "leaf {node} holds indices[{first}..{}], past the {} primitives",
                first + count,
                scene.len()
            ));
        }
        let prims = idx[first..first + count].to_vec();
        for &p in &prims {
            let p = p as usize;
            if p >= scene.len() {
                return Err(format!(
                    "leaf {node} holds primitive {p}, which does not exist"
                ));
            }
            if std::mem::replace(&mut seen[p], true) {
                return Err(format!("primitive {p} is in two leaves (or twice in one)"));
            }
        }
        if count > max_leaf as usize {
            return Err(format!(
                "leaf {node} holds {count} primitives, more than {max_leaf}"
            ));
        }
        prims
    } else {
        let first = nd.first as usize;
        let left = walk(scene, max_leaf, nodes, idx, used, first, reached, seen)?;
        let right = walk(scene, max_leaf, nodes, idx, used, first + 1, reached, seen)?;
        median_rule(scene, max_leaf, node, &left, &right)?;
        [left, right].concat()
    };
    let want = prims
        .iter()
        .fold(Aabb::EMPTY, |u, &p| u.union(&scene[p as usize]));
    if nd.bv != want {
        return Err(format!(
            "node {node} has box {}, but its {} primitives' union is {}",
            show_box(&nd.bv),
            prims.len(),
            show_box(&want)
        ));
    }
    Ok(prims)
}

/// The split of an internal node over `left` and `right`.
fn median_rule(
    scene: &[Aabb],
    max_leaf: u32,
    node: usize,
    left: &[u32],
    right: &[u32],
) -> Result<(), String> {
    let m = left.len() + right.len();
    if m <= max_leaf as usize {
        return Err(format!(
            "node {node} is split, but its {m} primitives fit in one leaf (max_leaf {max_leaf})"
        ));
    }
    if left.len() != m / 2 {
        return Err(format!(
            "node {node} puts {} of its {m} primitives on the left, expected {} (the object \
             median: half of them)",
            left.len(),
            m / 2
        ));
    }
    let c = |p: &u32| scene[*p as usize].center();
    let cb = left
        .iter()
        .chain(right)
        .fold(Aabb::EMPTY, |u, p| u.union(&Aabb::from_point(c(p))));
    let axis = cb.longest_axis();
    let lmax = left
        .iter()
        .map(|p| c(p)[axis])
        .fold(f32::NEG_INFINITY, f32::max);
    let rmin = right
        .iter()
        .map(|p| c(p)[axis])
        .fold(f32::INFINITY, f32::min);
    if lmax > rmin {
        return Err(format!(
            "node {node}: along {} (the longest axis of its centroids' box), a centroid on the \
             left is at {lmax}, one on the right at {rmin}: the left must hold the smallest",
            ["x", "y", "z"][axis]
        ));
    }
    Ok(())
}

/// Boxes 100 long in x whose centres lie along y: the boxes' box is longest
/// in x, the centroids' box in y.
fn long_in_x() -> Vec<Aabb> {
    (0..64)
        .map(|i| {
            let c = Vec3::new((i % 3) as f32 * 0.01, i as f32 * 0.5, 0.0);
            Aabb::new(c - Vec3::new(50.0, 0.1, 0.1), c + Vec3::new(50.0, 0.1, 0.1))
        })
        .collect()
}

/// Boxes from tiny to huge, so that a box grown from the wrong ones shows.
fn uneven_boxes() -> Vec<Aabb> {
    (0..40)
        .map(|i| {
            let c = Vec3::new(i as f32 * 3.0, (i % 5) as f32, (i % 7) as f32 * 0.5);
            let h = Vec3::splat(0.001 * 1.5f32.powi(i % 20));
            Aabb::new(c - h, c + h)
        })
        .collect()
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 8;

    pub fn top_down_build(
        which: u32,
        boxes: &[Aabb],
        max_leaf: u32,
        nodes: &mut [Node<Aabb>],
        indices: &mut [u32],
    ) -> Option<usize> {
        if which == 0 {
            return Reference.top_down_build(boxes, max_leaf, nodes, indices);
        }
        let n = boxes.len();
        if n == 0 {
            return Some(0);
        }
        // 5: no capacity check (indexes past the arrays).
        if which != 5 && (nodes.len() < 2 * n - 1 || indices.len() < n) {
            return None;
        }
        let centroids: Vec<Vec3> = boxes.iter().map(Aabb::center).collect();
        for (k, i) in indices[..n].iter_mut().enumerate() {
            *i = k as u32;
        }
        let mut used = 1;
        let mut work = vec![(0usize, 0usize, n)];
        while let Some((node, start, end)) = work.pop() {
            let range = &mut indices[start..end];
            let bv = match which {
                // 4: the box of the first primitive only, grown by nothing.
                4 => boxes[range[0] as usize],
                // 8: the box rebuilt from centre and half extent in f32.
                8 => range.iter().fold(Aabb::EMPTY, |u, &i| {
                    let (c, h) = (boxes[i as usize].center(), boxes[i as usize].extent() * 0.5);
                    u.union(&Aabb::new(c - h, c + h))
                }),
                _ => range
                    .iter()
                    .fold(Aabb::EMPTY, |u, &i| u.union(&boxes[i as usize])),
            };
            let m = end - start;
            // 2: a leaf only below max_leaf (`<` for `<=`).
            let leaf = if which == 2 {
                m < max_leaf as usize || m == 1
            } else {
                m <= max_leaf as usize
            };
            let cb = range.iter().fold(Aabb::EMPTY, |u, &i| {
                u.union(&Aabb::from_point(centroids[i as usize]))
            });
            // 6: coinciding centroids are not split.
            if leaf || (which == 6 && cb.extent() == Vec3::ZERO) {
                nodes[node] = Node {
                    bv,
                    first: start as u32,
                    count: m as u32,
                };
                continue;
            }
            // 3: the axis of the primitives' boxes, not of their centroids.
            let axis = if which == 3 {
                bv.longest_axis()
            } else {
                cb.longest_axis()
            };
            range.sort_by(|&a, &b| {
                centroids[a as usize][axis].total_cmp(&centroids[b as usize][axis])
            });
            let half = if which == 1 {
                // 1: the spatial median: split at the middle of the box.
                let mid = (cb.min[axis] + cb.max[axis]) * 0.5;
                let k = range
                    .iter()
                    .filter(|&&i| centroids[i as usize][axis] < mid)
                    .count();
                k.clamp(1, m - 1)
            } else {
                m / 2
            };
            nodes[node] = Node {
                bv,
                first: used as u32,
                count: 0,
            };
            work.push((used, start, start + half));
            work.push((used + 1, start + half, end));
            used += 2;
        }
        // 7: the count one short (the last node forgotten).
        Some(if which == 7 { used - 1 } else { used })
    }
}
