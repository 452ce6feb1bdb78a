//! The one error type of the crate.
//!
//! Every fallible operation returns [`Error`]; nothing in the core panics on bad
//! input. Each variant names what was wrong and, where it helps, which primitive.

use core::fmt;

/// Everything that can go wrong when building or querying a hierarchy.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
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
    /// A tree is too unbalanced for the implicit array layout: it would need
    /// `slots` array entries for `nodes` nodes.
    SparseTree {
        /// Array entries a complete tree of this depth needs.
        slots: usize,
        /// Nodes the tree really has.
        nodes: usize,
    },
    /// A builder option is out of its documented range.
    InvalidConfig(&'static str),
    /// A tree failed a structural check (see [`Bvh::validate`](crate::Bvh::validate)).
    InvalidTree(&'static str),
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Error::NonFiniteCoordinate { primitive } => {
                write!(f, "primitive {primitive} has a NaN or infinite coordinate")
            }
            Error::CoordinateOutOfRange { primitive } => write!(
                f,
                "primitive {primitive} has a coordinate beyond +/-{:e}",
                crate::MAX_COORDINATE
            ),
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
            Error::PrimitiveCountMismatch { tree, given } => write!(
                f,
                "tree was built over {tree} primitives but {given} were given"
            ),
            Error::FieldOverflow { field, value, max } => write!(
                f,
                "{field} is {value}, more than the layout's field holds ({max})"
            ),
            Error::SparseTree { slots, nodes } => write!(
                f,
                "the implicit array would need {slots} slots for {nodes} nodes; \
                 the tree is too unbalanced for it"
            ),
            Error::InvalidConfig(what) => write!(f, "invalid configuration: {what}"),
            Error::InvalidTree(what) => write!(f, "invalid tree: {what}"),
        }
    }
}

impl core::error::Error for Error {}
