//! Exercise 39: moving subtrees built on their own into the whole tree (the
//! parallel build's second pass). The checks, and the plausible wrong
//! answers they must reject. The pieces are cut from real sequential trees,
//! so the expected answer is what the sequential builder wrote.

use super::common::*;
use bvhkit::Primitive;

/// The checks of exercise 39.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 39,
            name: "pieces cut from built trees go back where the sequential build put them",
            points: 5,
            run: |e| {
                each_piece(|what, piece, start, base, want| {
                    same(
                        format!("relocate_piece({what}, start {start}, base {base})"),
                        want.to_vec(),
                        e.relocate_piece(piece, start, base),
                    )
                })
            },
        },
        Check {
            exercise: 39,
            name: "a piece that is one leaf: only its range moves",
            points: 2,
            run: |e| {
                let leaf = Node {
                    bv: b([0.0; 3], [1.0; 3]),
                    first: 2,
                    count: 3,
                };
                let want = vec![Node { first: 12, ..leaf }];
                same(
                    "relocate_piece([a leaf over the piece's primitives 2..5], start 10, base 40)",
                    want,
                    e.relocate_piece(&[leaf], 10, 40),
                )
            },
        },
        Check {
            exercise: 39,
            name: "the half with fewer primitives first, the left one on a tie",
            points: 5,
            run: |e| {
                // (pair, left (primitives, nodes), right, expected bases)
                type Case = (u32, (u32, u32), (u32, u32), (u32, u32));
                let cases: [Case; 5] = [
                    // Left smaller: its nodes follow the pair.
                    (1, (3, 5), (9, 13), (3, 7)),
                    // Right smaller: its nodes come first.
                    (7, (9, 13), (3, 5), (13, 9)),
                    // A tie in primitives: left first.
                    (20, (6, 9), (6, 7), (22, 30)),
                    // Fewer nodes on the left but more primitives: right first.
                    (4, (4, 1), (3, 5), (10, 6)),
                    // One-node halves (leaves): nothing below either.
                    (5, (2, 1), (1, 1), (7, 7)),
                ];
                cases.iter().all(|&(pair, l, r, want)| {
                    same(
                        format!(
                            "piece_bases(pair {pair}, left {} primitives / {} nodes, right {} / {})",
                            l.0, l.1, r.0, r.1
                        ),
                        want,
                        e.piece_bases(pair, l, r),
                    )
                })
            },
        },
    ]
}

/// Calls `check(what, piece, start, base, want)` for pieces cut from
/// sequential trees: every internal node of a few trees (rocks, leaves of 1
/// and 4, and a row of boxes) taken as the root of a piece, its subtree
/// rewritten with links of its own as the forked build makes it.
fn each_piece(check: impl Fn(&str, &[Node<Aabb>], u32, u32, &[Node<Aabb>]) -> bool) -> bool {
    let rock = bvhkit_std::scene::rock(2, 3);
    let row: Vec<Aabb> = (0..37)
        .map(|i| b([i as f32, 0.0, 0.0], [i as f32 + 0.5, 1.0, 1.0]))
        .collect();
    let trees: [(&str, Vec<Aabb>, u32); 3] = [
        (
            "a rock of 320 triangles, leaves of 4",
            rock.iter().map(|t| t.bounds()).collect(),
            4,
        ),
        (
            "the same rock, leaves of 1",
            rock.iter().map(|t| t.bounds()).collect(),
            1,
        ),
        ("37 boxes in a row, leaves of 2", row, 2),
    ];
    trees.iter().all(|(name, boxes, leaf)| {
        let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(boxes.len())];
        let mut idx = vec![0u32; boxes.len()];
        let Ok(tree) = TopDown::sah()
            .with_max_leaf_size(*leaf)
            .build(boxes, &mut nodes, &mut idx)
        else {
            return fail(format!("the grader could not build {name}"));
        };
        let nodes = tree.nodes();
        (0..nodes.len()).filter(|&x| !nodes[x].is_leaf()).all(|x| {
            let (piece, start, base) = cut(nodes, x);
            let mut want = vec![nodes[x]];
            want.extend_from_slice(&nodes[base as usize..base as usize + piece.len() - 1]);
            let what = format!("the subtree of node {x} of {name}, {} nodes", piece.len());
            check(&what, &piece, start, base, &want)
        })
    })
}

/// The subtree of node `x` as a piece built on its own: its root first, its
/// other nodes (which the sequential build keeps together, from `x`'s
/// children on) after it, links counted from the piece's start, leaf ranges
/// from its first primitive. Returns (piece, start, base).
pub(crate) fn cut(nodes: &[Node<Aabb>], x: usize) -> (Vec<Node<Aabb>>, u32, u32) {
    let (mut size, mut start, mut stack) = (1usize, u32::MAX, vec![x]);
    while let Some(i) = stack.pop() {
        match nodes[i].children() {
            Some((l, r)) => {
                size += 2;
                stack.extend([l as usize, r as usize]);
            }
            None => start = start.min(nodes[i].first),
        }
    }
    let base = nodes[x].children().map_or(0, |(l, _)| l);
    let local = |n: &Node<Aabb>| match n.children() {
        Some((l, _)) => Node {
            first: l - base + 1,
            ..*n
        },
        None => Node {
            first: n.first - start,
            ..*n
        },
    };
    let mut piece = vec![local(&nodes[x])];
    piece.extend(
        nodes[base as usize..base as usize + size - 1]
            .iter()
            .map(local),
    );
    (piece, start, base)
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 8;

    pub fn relocate_piece(
        which: u32,
        piece: &[Node<Aabb>],
        start: u32,
        base: u32,
    ) -> Vec<Node<Aabb>> {
        let moved = |n: &Node<Aabb>, inner: &dyn Fn(u32) -> u32, leaf: &dyn Fn(u32) -> u32| Node {
            first: if n.is_leaf() {
                leaf(n.first)
            } else {
                inner(n.first)
            },
            ..*n
        };
        let all = |inner: &dyn Fn(u32) -> u32, leaf: &dyn Fn(u32) -> u32| {
            piece.iter().map(|n| moved(n, inner, leaf)).collect()
        };
        match which {
            // Links moved by `base`, forgetting that the root is not in the block.
            1 => all(&|f| base + f, &|f| f + start),
            // Leaf ranges moved by the node block's start instead of the primitives'.
            2 => all(&|f| base + f - 1, &|f| f + base),
            // Leaf ranges left as they were.
            3 => all(&|f| base + f - 1, &|f| f),
            // Internal links moved by the primitives' start.
            4 => all(&|f| f + start, &|f| f + start),
            // The root left out: only the nodes of the block.
            5 => {
                let v: Vec<_> = all(&|f| base + f - 1, &|f| f + start);
                v[1..].to_vec()
            }
            _ => Reference.relocate_piece(piece, start, base),
        }
    }

    pub fn piece_bases(which: u32, pair: u32, left: (u32, u32), right: (u32, u32)) -> (u32, u32) {
        let order = |left_first: bool| {
            if left_first {
                (pair + 2, pair + 1 + left.1)
            } else {
                (pair + 1 + right.1, pair + 2)
            }
        };
        match which {
            // The larger half first.
            6 => order(left.0 > right.0),
            // A tie goes to the right.
            7 => order(left.0 < right.0),
            // The half with fewer nodes first.
            8 => order(left.1 <= right.1),
            _ => Reference.piece_bases(pair, left, right),
        }
    }
}
