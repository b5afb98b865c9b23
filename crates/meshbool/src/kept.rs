//! What an operand keeps between booleans: structures of its mesh alone that every
//! boolean with it would build again. A boolean of meshes under
//! [`crate::intersect::GRID_FROM`] triangles builds trees over each mesh's triangles near
//! the other, about a tenth of a small boolean. An [`crate::ops::Operand`] met again builds
//! its whole tree once, on its second request, and later booleans take it as it is (a
//! Python loop, a terrain against many pit shells). The first request builds nothing, so a
//! one-off boolean (the command line) pays nothing for it.

use std::sync::atomic::{AtomicBool, Ordering::Relaxed};
use std::sync::OnceLock;

use crate::broad::Slivers;
use crate::bvh::Bvh;

/// One structure kept between calls: built on its second request, then kept.
#[derive(Debug, Default)]
pub struct Kept<T> {
    asked: AtomicBool,
    value: OnceLock<T>,
}

impl<T: Clone> Clone for Kept<T> {
    fn clone(&self) -> Self {
        Kept {
            asked: self.asked.load(Relaxed).into(),
            value: self.value.clone(),
        }
    }
}

impl<T> Kept<T> {
    /// The structure, made by `build` on the second request and kept; `None` on the
    /// first. `build` must make the same structure at every request.
    pub fn get(&self, build: impl FnOnce() -> T) -> Option<&T> {
        if let Some(v) = self.value.get() {
            return Some(v);
        }
        self.asked
            .swap(true, Relaxed)
            .then(|| self.value.get_or_init(build))
    }

    /// Whether the structure has been built.
    #[cfg(test)]
    pub fn is_built(&self) -> bool {
        self.value.get().is_some()
    }
}

/// What one mesh keeps for booleans, of the mesh it is given with: the whole tree of its
/// triangles, built for queries ([`Bvh::new_for_queries`]), and its slivers
/// ([`Slivers`]).
#[derive(Clone, Debug, Default)]
pub struct Keeps {
    /// The tree, taken by the broad phase where the mesh is used whole.
    pub tree: Kept<Bvh>,
    /// Its slivers and the sums the broad phase weighs them against.
    pub slivers: Kept<Slivers>,
}
