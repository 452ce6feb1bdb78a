//! Every buffer length for `n` primitives, from one `const fn`.
//!
//! The core never allocates, so each builder, layout and check takes its
//! storage from the caller, and each has its own sizing function
//! ([`max_nodes`](crate::max_nodes), [`TopDown::index_capacity`](crate::TopDown::index_capacity),
//! [`BottomUp::scratch_len`](crate::builders::BottomUp::scratch_len), ...).
//! [`Capacity::for_primitives`] gathers them: one value, computed at
//! compile time, whose fields size `static` arrays. It is also where the
//! formulas live: the builders' and layouts' own sizing functions read it,
//! and it does not depend on which of them the crate's features compile.

use crate::Bvh;

/// Buffer lengths (entries, not bytes, except where a name says bytes) for
/// trees over `n` primitives, each the worst case of its builder or layout.
///
/// ```
/// use bvhkit::layout::{Wide, WideNode};
/// use bvhkit::{Aabb, Capacity, Node, TopDown, Triangle};
/// const N: usize = 64;
/// const CAP: Capacity = Capacity::for_primitives(N);
/// // Fields are constants: they size `static` arrays (zero bits, `.bss`)...
/// static NODES: [Node<Aabb>; CAP.nodes] = [Node::ZERO; CAP.nodes];
/// assert_eq!(NODES.len(), 127);
/// // ... and any other storage.
/// let mut nodes = [Node::<Aabb>::ZERO; CAP.nodes];
/// let mut indices = [0u32; CAP.indices];
/// let mut wide = [WideNode::ZERO; CAP.wide_records];
/// let tris: [Triangle; N] = core::array::from_fn(|i| {
///     let o = glam::Vec3::new(i as f32, 0.0, 0.0);
///     Triangle::new(o, o + glam::Vec3::X, o + glam::Vec3::Y)
/// });
/// let tree = TopDown::sah().build(&tris, &mut nodes, &mut indices)?;
/// let four = Wide::from_bvh(&tree, &mut wide)?;
/// assert!(four.records().len() <= CAP.wide_records);
/// # Ok::<(), bvhkit::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Capacity {
    /// Primitives the lengths are for.
    pub primitives: usize,
    /// Nodes of a binary tree from any builder (`2n - 1`): also the
    /// records of a [`Preorder`](crate::layout::Preorder) layout.
    pub nodes: usize,
    /// Index entries of every builder but one (`n`).
    pub indices: usize,
    /// Index entries of the top-down builder with
    /// [`SplitPoint::Sweep`](crate::SplitPoint::Sweep), which keeps scratch
    /// in a second half (`2n`).
    pub sweep_indices: usize,
    /// Kept leaf bounds ([`Bvh::with_leaf_bounds`](crate::Bvh::with_leaf_bounds)): one per primitive.
    pub leaf_bounds: usize,
    /// Bottom-up scratch ([`BottomUpScratch`](crate::builders::BottomUpScratch)):
    /// clusters (`2n - 1`), work words (`2n`), keys (`2n`).
    pub bottom_up: (usize, usize, usize),
    /// Insertion-builder scratch ([`Insertion`](crate::builders::Insertion)):
    /// dynamic nodes (`2n - 1`) and order words (`n`).
    pub insertion: (usize, usize),
    /// Nodes of a [`DynamicTree`](crate::builders::DynamicTree) holding `n` objects.
    pub dynamic_nodes: usize,
    /// Records of the 4-wide layout ([`Wide`](crate::layout::Wide)): every
    /// record's child absorbs at least two inner nodes, so from three
    /// primitives on `n - 1` suffice; two primitives in two leaves need two
    /// (a header and the root's record), one primitive one.
    pub wide_records: usize,
    /// Records of the quantized 4-wide layout
    /// ([`QuantizedWide`](crate::layout::QuantizedWide)): as many.
    pub quantized_records: usize,
    /// Scratch words of [`Bvh::validate`](crate::Bvh::validate),
    /// [`Bvh::from_parts`](crate::Bvh::from_parts) and
    /// [`Bvh::from_baked`](crate::Bvh::from_baked).
    pub validate_words: usize,
    /// Bytes of a [baked](crate::baked) tree with one node per slot of
    /// `nodes`, without kept leaf bounds.
    pub baked_bytes: usize,
    /// The same, with kept leaf bounds.
    pub baked_bytes_with_bounds: usize,
}

impl Capacity {
    /// Every length for `n` primitives. A `const fn`: its fields size
    /// `static` arrays, and a firmware's RAM budget can be checked when it
    /// compiles.
    pub const fn for_primitives(n: usize) -> Capacity {
        let nodes = crate::max_nodes(n);
        let four_wide = if n > 2 {
            n - 1
        } else if n == 2 {
            2
        } else {
            1
        };
        Capacity {
            primitives: n,
            nodes,
            indices: n,
            sweep_indices: n.saturating_mul(2),
            leaf_bounds: n,
            bottom_up: (nodes, n.saturating_mul(2), n.saturating_mul(2)),
            insertion: (nodes, n),
            dynamic_nodes: nodes,
            wide_records: four_wide,
            quantized_records: four_wide,
            validate_words: Bvh::<crate::Aabb>::seen_words(nodes, n),
            baked_bytes: crate::baked::baked_len(nodes, n, false),
            baked_bytes_with_bounds: crate::baked::baked_len(nodes, n, true),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Sizes past memory saturate instead of overflowing: no `n` makes a
    /// sizing function panic (an allocation of `usize::MAX` then fails
    /// where it is asked for, with its own error).
    #[test]
    fn huge_counts_saturate() {
        for n in [usize::MAX, usize::MAX / 2 + 1, usize::MAX / 32] {
            let c = Capacity::for_primitives(n);
            assert!(c.nodes >= n.min(usize::MAX / 2));
            assert_eq!(c.sweep_indices, n.saturating_mul(2));
            assert_eq!(c.baked_bytes_with_bounds, usize::MAX);
            assert!(crate::max_nodes_for_leaves(n) >= n.min(usize::MAX / 2));
        }
    }

    /// Each sizing function of a builder or layout reads its field, and
    /// the fields are the documented formulas.
    #[test]
    fn the_sizing_functions_read_their_fields() {
        for n in [0usize, 1, 2, 3, 4, 63, 64, 1000] {
            let c = Capacity::for_primitives(n);
            assert_eq!(c.nodes, crate::max_nodes(n));
            assert_eq!(c.nodes, if n == 0 { 0 } else { 2 * n - 1 });
            assert_eq!((c.indices, c.sweep_indices, c.leaf_bounds), (n, 2 * n, n));
            #[cfg(feature = "bottom-up")]
            assert_eq!(crate::builders::BottomUp::scratch_len(n), c.bottom_up);
            #[cfg(feature = "insertion")]
            assert_eq!(crate::builders::Insertion::scratch_len(n), c.insertion);
            #[cfg(feature = "layouts")]
            {
                assert_eq!(crate::layout::Wide::max_records(n), c.wide_records);
                assert_eq!(
                    crate::layout::QuantizedWide::max_records(n),
                    c.quantized_records
                );
            }
            assert_eq!(
                c.wide_records,
                [1, 1, 2].get(n).copied().unwrap_or(n.saturating_sub(1))
            );
            assert_eq!(c.validate_words, c.nodes.max(n).div_ceil(32));
            assert_eq!(c.baked_bytes, 32 + 32 * c.nodes + 4 * n);
            assert_eq!(c.baked_bytes_with_bounds, c.baked_bytes + 24 * n);
        }
    }
}
