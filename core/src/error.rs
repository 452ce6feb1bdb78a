//! The one error type of the crate.
//!
//! Every fallible operation returns [`Error`]; nothing in the core panics on bad
//! input. Each variant names what was wrong and, where it helps, which primitive.

use core::fmt;

/// Everything that can go wrong when building or querying a hierarchy.
///
/// Three ways to print one, from the cheapest on a microcontroller:
/// [`Error::as_str`] (a fixed sentence, no formatting code at all),
/// `defmt::Format` with the `defmt` feature (formatting on the host), and
/// `Display` (the sentence with its numbers; integers only, so no float
/// formatting is linked).
///
/// ```
/// let e = bvhkit::Error::NodeCapacity { needed: 9, available: 4 };
/// assert_eq!(e.as_str(), "node buffer too small");
/// assert_eq!(e.to_string(), "node buffer too small: need up to 9 nodes, have 4");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Error {
    /// Primitive `primitive` has a NaN or infinite coordinate. One such value in a
    /// min/max fold would poison every box above it, so it is rejected up front.
    NonFiniteCoordinate {
        /// Index of the offending primitive in the caller's slice.
        primitive: usize,
    },
    /// Primitive `primitive` has a coordinate larger in magnitude than
    /// [`MAX_COORDINATE`](crate::MAX_COORDINATE).
    CoordinateOutOfRange {
        /// Index of the offending primitive in the caller's slice.
        primitive: usize,
    },
    /// More primitives than a `u32` index can name.
    IndexOverflow {
        /// How many primitives were given.
        count: usize,
    },
    /// The node buffer is too small; `needed` is an upper bound for this input.
    NodeCapacity {
        /// Nodes the build may need.
        needed: usize,
        /// Nodes the caller provided.
        available: usize,
    },
    /// The primitive-index buffer is too small.
    IndexCapacity {
        /// Entries needed.
        needed: usize,
        /// Entries the caller provided.
        available: usize,
    },
    /// A result buffer filled up; `found` results exist in total.
    ResultCapacity {
        /// Total results the query produced.
        found: usize,
        /// Capacity of the buffer.
        capacity: usize,
    },
    /// A traversal needs a deeper stack than the fixed one it owns.
    StackOverflow {
        /// Depth of the tree that was queried.
        depth: usize,
        /// Depth the traversal stack supports.
        capacity: usize,
    },
    /// A breadth-first queue given by the caller is too small for the tree.
    QueueCapacity {
        /// Entries the tree may need ([`Bvh::breadth_first_queue`](crate::Bvh::breadth_first_queue)).
        needed: usize,
        /// Entries the caller provided.
        available: usize,
    },
    /// The primitive slice passed to a query is not the one the tree was built over.
    PrimitiveCountMismatch {
        /// Primitive count the tree was built with.
        tree: usize,
        /// Length of the slice given to the query.
        given: usize,
    },
    /// A value does not fit the field a compact layout stores it in (a 16-bit
    /// offset, an 8-bit leaf size): the tree is refused, never wrapped around.
    FieldOverflow {
        /// Which field.
        field: &'static str,
        /// The value that had to be stored.
        value: usize,
        /// The largest value the field holds.
        max: usize,
    },
    /// The far-link table given to a 16-bit
    /// [`Preorder`](crate::layout::Preorder) is too small: the tree has
    /// `needed` links that do not fit 16 bits
    /// ([`Preorder::far_links_needed`](crate::layout::Preorder::far_links_needed)).
    FarLinkCapacity {
        /// Far links the tree needs.
        needed: usize,
        /// Entries the caller provided.
        available: usize,
    },
    /// A tree is too unbalanced for the implicit array layout: it would need
    /// `slots` array entries for `nodes` nodes.
    SparseTree {
        /// Array entries a complete tree of this depth needs.
        slots: usize,
        /// Nodes the tree really has.
        nodes: usize,
    },
    /// A triangle of a mesh given by indices (the convex hull of the
    /// [`Obb::pca_hull`](crate::Obb::pca_hull) and
    /// [`Obb::face_flush`](crate::Obb::face_flush) fits) names a vertex past
    /// the end of the vertex slice.
    VertexIndexOutOfRange {
        /// Index of the first such triangle.
        triangle: usize,
        /// Number of vertices given.
        vertices: usize,
    },
    /// A scratch buffer given by the caller is too small for the input
    /// (see [`Obb::face_flush_scratch_len`](crate::Obb::face_flush_scratch_len)).
    ScratchCapacity {
        /// Entries needed.
        needed: usize,
        /// Entries the caller provided.
        available: usize,
    },
    /// A [`LeafHandle`](crate::builders::LeafHandle) that names no live leaf
    /// of the tree: its object was removed (the node may hold another object
    /// now, in a later generation), or it came from another tree.
    StaleHandle {
        /// The node the handle names.
        index: u32,
        /// The generation it was made in.
        generation: u32,
    },
    /// A builder option is out of its documented range.
    InvalidConfig(&'static str),
    /// A query's own input is unusable: a region, ray or point with a NaN or
    /// infinite coordinate, an inverted box, a negative radius. Refused
    /// rather than answered with nothing, which would look like a real miss.
    InvalidQuery(&'static str),
    /// A tree failed a structural check (see [`Bvh::validate`](crate::Bvh::validate)).
    InvalidTree(&'static str),
    /// Bytes given as a baked tree ([`Bvh::from_baked`](crate::Bvh::from_baked))
    /// are not one: `what` says which field or check failed, `offset` is the
    /// byte where the problem was found.
    BadBake {
        /// Byte offset into the given bytes.
        offset: usize,
        /// What was expected there.
        what: &'static str,
    },
}

impl Error {
    /// What went wrong, as a fixed sentence without the numbers: printing it
    /// links no formatting code (the book's embedded chapter measures what
    /// `{}` and `{:?}` add to a Cortex-M4 firmware).
    pub const fn as_str(&self) -> &'static str {
        match self {
            Error::NonFiniteCoordinate { .. } => "a primitive has a NaN or infinite coordinate",
            Error::CoordinateOutOfRange { .. } => "a primitive has a coordinate beyond +/-1e32",
            Error::IndexOverflow { .. } => "too many primitives for 32-bit indices",
            Error::NodeCapacity { .. } => "node buffer too small",
            Error::IndexCapacity { .. } => "index buffer too small",
            Error::ResultCapacity { .. } => "result buffer too small",
            Error::StackOverflow { .. } => "tree deeper than the traversal stack",
            Error::QueueCapacity { .. } => "breadth-first queue too small",
            Error::PrimitiveCountMismatch { .. } => {
                "the primitives given are not the ones the tree was built over"
            }
            Error::FieldOverflow { .. } => "a value does not fit the layout's field",
            Error::FarLinkCapacity { .. } => "far-link table too small",
            Error::SparseTree { .. } => "tree too unbalanced for the implicit array",
            Error::VertexIndexOutOfRange { .. } => "a triangle names a vertex that does not exist",
            Error::ScratchCapacity { .. } => "scratch buffer too small",
            Error::StaleHandle { .. } => "the handle names no live leaf of this tree",
            Error::InvalidConfig(what)
            | Error::InvalidQuery(what)
            | Error::InvalidTree(what)
            | Error::BadBake { what, .. } => what,
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Error::NonFiniteCoordinate { primitive } => {
                write!(f, "primitive {primitive} has a NaN or infinite coordinate")
            }
            // The bound written out, not formatted from the f32: float
            // formatting alone would add kilobytes to a firmware.
            Error::CoordinateOutOfRange { primitive } => {
                write!(f, "primitive {primitive} has a coordinate beyond +/-1e32")
            }
            Error::IndexOverflow { count } => {
                write!(f, "{count} primitives do not fit 32-bit indices")
            }
            Error::NodeCapacity { needed, available } => write!(
                f,
                "node buffer too small: need up to {needed} nodes, have {available}"
            ),
            Error::IndexCapacity { needed, available } => write!(
                f,
                "index buffer too small: need {needed} entries, have {available}"
            ),
            Error::ResultCapacity { found, capacity } => write!(
                f,
                "result buffer too small: {found} results, capacity {capacity}"
            ),
            Error::StackOverflow { depth, capacity } => write!(
                f,
                "tree depth {depth} exceeds the traversal stack capacity {capacity}"
            ),
            Error::QueueCapacity { needed, available } => write!(
                f,
                "the breadth-first queue needs {needed} entries but {available} were given"
            ),
            Error::PrimitiveCountMismatch { tree, given } => {
                write!(f, "the tree needs {tree} primitives but {given} were given")
            }
            Error::FieldOverflow { field, value, max } => write!(
                f,
                "{field} is {value}, more than the layout's field holds ({max})"
            ),
            Error::FarLinkCapacity { needed, available } => write!(
                f,
                "far-link table too small: need {needed} entries, have {available}"
            ),
            Error::SparseTree { slots, nodes } => write!(
                f,
                "the implicit array would need {slots} slots for {nodes} nodes; \
                 the tree is too unbalanced for it"
            ),
            Error::VertexIndexOutOfRange { triangle, vertices } => write!(
                f,
                "triangle {triangle} names a vertex past the {vertices} given"
            ),
            Error::ScratchCapacity { needed, available } => write!(
                f,
                "scratch buffer too small: need {needed} entries, have {available}"
            ),
            Error::StaleHandle { index, generation } => write!(
                f,
                "handle (node {index}, generation {generation}) names no live leaf of this tree"
            ),
            Error::InvalidConfig(what) => write!(f, "invalid configuration: {what}"),
            Error::InvalidQuery(what) => write!(f, "invalid query: {what}"),
            Error::InvalidTree(what) => write!(f, "invalid tree: {what}"),
            Error::BadBake { offset, what } => {
                write!(f, "not a baked tree: {what} (at byte {offset})")
            }
        }
    }
}

impl core::error::Error for Error {}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bound the messages write out is the one the builders check.
    #[test]
    fn messages_name_the_real_coordinate_bound() {
        assert_eq!(crate::MAX_COORDINATE, 1e32);
        let e = Error::CoordinateOutOfRange { primitive: 3 };
        assert!(e.as_str().ends_with("1e32"));
        let mut buf = [0u8; 64];
        let mut w = Buf(&mut buf, 0);
        fmt::write(&mut w, format_args!("{e}")).unwrap();
        assert_eq!(w.text(), "primitive 3 has a coordinate beyond +/-1e32");
    }

    /// Every variant has a short sentence of its own (the two carrying a
    /// message pass it through).
    #[test]
    fn every_variant_has_its_own_sentence() {
        let all = [
            Error::NonFiniteCoordinate { primitive: 0 },
            Error::CoordinateOutOfRange { primitive: 0 },
            Error::IndexOverflow { count: 0 },
            Error::NodeCapacity {
                needed: 0,
                available: 0,
            },
            Error::IndexCapacity {
                needed: 0,
                available: 0,
            },
            Error::ResultCapacity {
                found: 0,
                capacity: 0,
            },
            Error::StackOverflow {
                depth: 0,
                capacity: 0,
            },
            Error::QueueCapacity {
                needed: 0,
                available: 0,
            },
            Error::PrimitiveCountMismatch { tree: 0, given: 0 },
            Error::FieldOverflow {
                field: "f",
                value: 0,
                max: 0,
            },
            Error::FarLinkCapacity {
                needed: 0,
                available: 0,
            },
            Error::SparseTree { slots: 0, nodes: 0 },
            Error::VertexIndexOutOfRange {
                triangle: 0,
                vertices: 0,
            },
            Error::ScratchCapacity {
                needed: 0,
                available: 0,
            },
            Error::StaleHandle {
                index: 0,
                generation: 0,
            },
            Error::InvalidConfig("bad config"),
            Error::InvalidQuery("bad query"),
            Error::InvalidTree("bad tree"),
            Error::BadBake {
                offset: 0,
                what: "bad bake",
            },
        ];
        for (i, a) in all.iter().enumerate() {
            assert!(a.as_str().len() > 5, "{a:?}");
            for b in &all[i + 1..] {
                assert_ne!(a.as_str(), b.as_str(), "{a:?} and {b:?}");
            }
        }
    }

    /// A fixed buffer to format into (no allocation in core's tests).
    struct Buf<'a>(&'a mut [u8], usize);
    impl Buf<'_> {
        fn text(&self) -> &str {
            core::str::from_utf8(&self.0[..self.1]).unwrap()
        }
    }
    impl fmt::Write for Buf<'_> {
        fn write_str(&mut self, s: &str) -> fmt::Result {
            let end = self.1 + s.len();
            self.0
                .get_mut(self.1..end)
                .ok_or(fmt::Error)?
                .copy_from_slice(s.as_bytes());
            self.1 = end;
            Ok(())
        }
    }
}
