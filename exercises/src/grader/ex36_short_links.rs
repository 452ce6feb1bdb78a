//! Exercise 36: 16-bit links with an escape to a far table. The checks, and the plausible wrong answers they must reject.

use super::common::*;
use super::ex27_tree_measures::each_tree;
use bvhkit::layout::{FarLink, PreNode, Preorder};

/// The checks of exercise 36.
pub fn checks() -> Vec<Check> {
    vec![
        Check {
            exercise: 36,
            name: "offsets from the record, as the 16-bit Preorder layout stores them (nothing escapes)",
            points: 3,
            run: |e| on_trees(|what, tree| compare(e, what, tree, crate::ESCAPE - 1)),
        },
        Check {
            exercise: 36,
            name: "an offset above the reach escapes, with (record, right child) in the far table sorted by record; an offset equal to the reach does not",
            points: 3,
            run: |e| {
                on_trees(|what, tree| {
                    reaches(tree)
                        .into_iter()
                        .all(|reach| compare(e, what, tree, reach))
                })
            },
        },
        Check {
            exercise: 36,
            name: "decoding: the right child of every internal record, through escapes too",
            points: 3,
            run: |e| {
                on_trees(|what, tree| {
                    reaches(tree).into_iter().all(|reach| {
                        let Some((pre_links, pre_far, rights)) = library(tree, reach) else {
                            return fail(format!("the grader could not lay out {what}"));
                        };
                        // A long far table is summarised, not printed.
                        let table = match pre_far.len() {
                            0..=16 => format!("far table {pre_far:?}"),
                            n => format!("a far table of {n} entries"),
                        };
                        rights.iter().enumerate().all(|(i, right)| {
                            let Some(right) = right else { return true };
                            same(
                                format!(
                                    "decode_right(the links of {what} with reach {reach}, \
                                     {table}, record {i})"
                                ),
                                *right,
                                e.decode_right(&pre_links, &pre_far, i),
                            )
                        })
                    })
                })
            },
        },
        Check {
            exercise: 36,
            name: "no internal node: an empty tree has no entries, a tree of one leaf the entry 0",
            points: 1,
            run: |e| {
                let empty = Bvh::<Aabb>::from_raw_parts(&[], &[], 0);
                let leaf = [node([0.0; 3], [1.0; 3], true)];
                let one = Bvh::from_raw_parts(&leaf, &[0], 0);
                same(
                    "short_links(an empty tree, reach 10)",
                    (vec![], vec![]),
                    e.short_links(&empty, 10),
                ) && same(
                    "short_links(a tree that is one leaf, reach 10)",
                    (vec![0], vec![]),
                    e.short_links(&one, 10),
                )
            },
        },
    ]
}

/// The trees of exercise 27 (see [`each_tree`]) and one whose root and
/// root's left child both escape at a small reach (a far table found out
/// of record order).
fn on_trees(check: impl Fn(&str, &Bvh<Aabb>) -> bool) -> bool {
    let pts: Vec<Vec3> = (0..16).map(|i| Vec3::new(i as f32, 0.0, 0.0)).collect();
    let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(pts.len())];
    let mut idx = vec![0u32; pts.len()];
    each_tree(&check)
        && match TopDown::median()
            .with_max_leaf_size(1)
            .build(&pts, &mut nodes, &mut idx)
        {
            Ok(tree) => check(
                "a median tree over 16 points on a line, leaves of one",
                &tree,
            ),
            Err(err) => fail(format!("the grader could not build a median tree: {err}")),
        }
}

/// Reaches that make some links of `tree` escape: 1 (every link), 2 (a
/// left child that is a leaf stays), and the largest offset less one and
/// exactly (the root's, or another node's, escapes or not).
fn reaches(tree: &Bvh<Aabb>) -> Vec<u16> {
    let largest = library(tree, crate::ESCAPE - 1)
        .map(|(links, _, _)| links.into_iter().max().unwrap_or(0))
        .unwrap_or(0);
    let mut r = vec![1, 2, 3, largest.saturating_sub(1).max(1), largest.max(1)];
    r.dedup();
    r
}

/// The library's 16-bit preorder of `tree` at `reach`, in the exercise's
/// form (leaves 0, the far links of internal records only), and every
/// record's right child.
type Library = (Vec<u16>, Vec<(u32, u32)>, Vec<Option<usize>>);

fn library(tree: &Bvh<Aabb>, reach: u16) -> Option<Library> {
    let reach = reach as usize;
    let needed = Preorder::<Aabb, u16>::far_links_needed_reaching(tree, reach).ok()?;
    let mut recs = vec![PreNode::<Aabb, u16>::EMPTY; tree.node_count()];
    let mut far = vec![FarLink::EMPTY; needed];
    let pre = Preorder::from_bvh_reaching(tree, &mut recs, &mut far, reach).ok()?;
    let inner = |i: usize| pre.records()[i].has_left_child();
    let links = (pre.records().iter())
        .map(|r| if r.has_left_child() { r.link() } else { 0 })
        .collect();
    let far = (pre.far_links().iter())
        .filter(|f| inner(f.record as usize))
        .map(|f| (f.record, f.link))
        .collect();
    let rights = (0..pre.records().len()).map(|i| pre.right(i)).collect();
    Some((links, far, rights))
}

/// `e.short_links(tree, reach)` against the library's layout.
fn compare(e: &dyn Exercises, what: &str, tree: &Bvh<Aabb>, reach: u16) -> bool {
    let Some((links, far, _)) = library(tree, reach) else {
        return fail(format!("the grader could not lay out {what}"));
    };
    let (got_links, got_far) = e.short_links(tree, reach);
    same_list(
        format!("short_links({what}, reach {reach}).0"),
        &links,
        &got_links,
        |v| v.to_string(),
    ) && same_list(
        format!("short_links({what}, reach {reach}).1 (the far table)"),
        &far,
        &got_far,
        |f| format!("{f:?}"),
    )
}

/// Plausible wrong answers, numbered from 1; each loses points here.
#[cfg(test)]
pub mod wrong {
    use super::*;
    use crate::ESCAPE;

    /// How many wrong answers this exercise keeps.
    pub const COUNT: u32 = 8;

    /// The preorder walk with a rule for storing a right link: `store(i, j,
    /// reach)` gives the entry and, if the link escapes, the far entry.
    fn walk(
        tree: &Bvh<Aabb>,
        reach: u16,
        store: impl Fn(usize, usize, u16) -> (u16, Option<(u32, u32)>),
        sort: bool,
    ) -> (Vec<u16>, Vec<(u32, u32)>) {
        let nodes = tree.nodes();
        let (mut links, mut far) = (Vec::new(), Vec::new());
        let mut stack = if nodes.is_empty() {
            vec![]
        } else {
            vec![(0u32, None::<usize>)]
        };
        while let Some((n, parent)) = stack.pop() {
            let record = links.len();
            if let Some(p) = parent {
                let (entry, escaped) = store(p, record, reach);
                links[p] = entry;
                far.extend(escaped);
            }
            links.push(0);
            if let Some((l, r)) = nodes[n as usize].children() {
                stack.push((r, Some(record)));
                stack.push((l, None));
            }
        }
        if sort {
            far.sort_unstable();
        }
        (links, far)
    }

    pub fn short_links(which: u32, tree: &Bvh<Aabb>, reach: u16) -> (Vec<u16>, Vec<(u32, u32)>) {
        let escape = |i: usize, j: usize| (ESCAPE, Some((i as u32, j as u32)));
        match which {
            // The offset counted from the next record (the left child).
            1 => walk(
                tree,
                reach,
                |i, j, reach| match j - i - 1 {
                    d if d <= reach as usize => (d as u16, None),
                    _ => escape(i, j),
                },
                true,
            ),
            // An offset equal to the reach escapes too.
            2 => walk(
                tree,
                reach,
                |i, j, reach| match j - i {
                    d if d < reach as usize => (d as u16, None),
                    _ => escape(i, j),
                },
                true,
            ),
            // The far table in the order the links were found, unsorted.
            3 => walk(
                tree,
                reach,
                |i, j, reach| match j - i {
                    d if d <= reach as usize => (d as u16, None),
                    _ => escape(i, j),
                },
                false,
            ),
            // The far table keeps the offset, not the right child's record.
            4 => walk(
                tree,
                reach,
                |i, j, reach| match j - i {
                    d if d <= reach as usize => (d as u16, None),
                    d => (ESCAPE, Some((i as u32, d as u32))),
                },
                true,
            ),
            // The reach compared with the right child's record, not the offset.
            5 => walk(
                tree,
                reach,
                |i, j, reach| match j - i {
                    d if j <= reach as usize => (d as u16, None),
                    _ => escape(i, j),
                },
                true,
            ),
            // A tree of one leaf (no internal node) gives no entries.
            8 if tree.nodes().iter().all(|n| n.is_leaf()) => (vec![], vec![]),
            _ => Reference.short_links(tree, reach),
        }
    }

    pub fn decode_right(which: u32, links: &[u16], far: &[(u32, u32)], record: usize) -> usize {
        match which {
            // The entry taken as the right child's record itself.
            6 if links[record] != ESCAPE => links[record] as usize,
            // The offset counted from the next record.
            7 if links[record] != ESCAPE => record + 1 + links[record] as usize,
            _ => Reference.decode_right(links, far, record),
        }
    }
}
