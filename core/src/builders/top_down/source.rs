//! Where the builder reads primitive bounds: through the caller's slice, or
//! from cached records that move with the partition.

use crate::bv::{Aabb, BoxSet};
use crate::primitive::Primitive;
use glam::Vec3;

/// A primitive's bounds and its index, cached for [`TopDown::build_cached`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrimitiveRef {
    /// Bounds of the primitive.
    pub bounds: Aabb,
    /// Index of the primitive in the caller's slice.
    pub index: u32,
}

impl PrimitiveRef {
    /// A blank record, for initialising storage.
    pub const EMPTY: PrimitiveRef = PrimitiveRef {
        bounds: Aabb::EMPTY,
        index: 0,
    };
}

/// Where the builder reads bounds from: the caller's primitives through an
/// index ([`Indexed`]), or cached records that move with the partition ([`Cached`]).
/// One skeleton serves both.
pub(super) trait Source {
    type Item: Copy;
    fn bounds(&self, item: Self::Item) -> Aabb;
    /// The primitive's index: breaks ties so every ordering is total, and the
    /// tree does not depend on how an unstable sort treats equal keys.
    fn id(&self, item: Self::Item) -> u32;
}

/// The point builders sort by: the centre of the primitive's bounds.
#[inline(always)]
pub(super) fn centroid<S: Source>(src: &S, item: S::Item) -> Vec3 {
    src.bounds(item).center()
}

pub(super) struct Indexed<'a, P>(pub(super) &'a [P]);

impl<P: Primitive> Source for Indexed<'_, P> {
    type Item = u32;
    #[inline(always)]
    fn bounds(&self, i: u32) -> Aabb {
        self.0[i as usize].bounds()
    }
    #[inline(always)]
    fn id(&self, i: u32) -> u32 {
        i
    }
}

pub(super) struct Cached;

impl Source for Cached {
    type Item = PrimitiveRef;
    #[inline(always)]
    fn bounds(&self, r: PrimitiveRef) -> Aabb {
        r.bounds
    }
    #[inline(always)]
    fn id(&self, r: PrimitiveRef) -> u32 {
        r.index
    }
}

/// The bounds of a range of items, as a [`BoxSet`] for volume fitting.
pub(super) struct SourceBoxes<'a, S: Source> {
    pub(super) src: &'a S,
    pub(super) items: &'a [S::Item],
}

impl<S: Source> BoxSet for SourceBoxes<'_, S> {
    fn len(&self) -> usize {
        self.items.len()
    }
    fn aabb(&self, i: usize) -> Aabb {
        self.src.bounds(self.items[i])
    }
}
