//! Typed indices of the solver: a mesh node ([`NodeIdx`]), a working-set slot ([`Slot`]) and a
//! component of a needle-frame vector ([`Axis`]), so that they cannot be swapped for one another.
//!
//! All three are `Copy` and as small as the integer they wrap; `Option<Slot>` is the same size as
//! `Slot` (a niche), which replaces the old `usize::MAX` "no slot" marker.

use std::num::NonZeroU32;

/// A node of the tissue mesh: its index into the mesh's node list (DOFs $2i$, $2i+1$ in world
/// $x$, $y$).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[repr(transparent)]
pub struct NodeIdx(pub usize);

impl NodeIdx {
    /// The index into the mesh's node list.
    #[inline]
    pub fn index(self) -> usize {
        self.0
    }
    /// The world DOF of this node along $x$ (`0`) or $y$ (`1`): $2i + c$.
    #[inline]
    pub fn dof(self, world_component: usize) -> usize {
        2 * self.0 + world_component
    }
}

impl std::fmt::Display for NodeIdx {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.0.fmt(f)
    }
}

/// A slot of the working set (the nodes the needle touches): its row block in the hybrid matrix.
/// Slots are dense, `0..n_nodes`; removing one moves the last slot into its place.
///
/// Stored as `index + 1` in a `NonZeroU32`, so that `Option<Slot>` costs no more than `Slot`.
/// A working set never exceeds [`crate::sim::param_limits::MAX_NEEDLE_NODES`] (4096) slots.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[repr(transparent)]
pub struct Slot(NonZeroU32);

impl Slot {
    /// The slot with index `index`. Panics only on a programming error (an index ≥ 2³² − 1,
    /// far past any capacity a solver accepts).
    #[inline]
    pub fn new(index: usize) -> Self {
        let v = u32::try_from(index + 1).ok().and_then(NonZeroU32::new).expect("slot index fits in u32");
        Slot(v)
    }
    /// The slot's index, `0..n_nodes`.
    #[inline]
    pub fn index(self) -> usize {
        (self.0.get() - 1) as usize
    }
    /// The local DOF of this slot along `axis` in the hybrid system: $2k + a$.
    #[inline]
    pub fn dof(self, axis: Axis) -> usize {
        2 * self.index() + axis.index()
    }
    /// The slots `0..n`, in order.
    #[inline]
    pub fn all(n: usize) -> impl DoubleEndedIterator<Item = Slot> + ExactSizeIterator {
        (0..n).map(Slot::new)
    }
}

impl std::fmt::Debug for Slot {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Slot({})", self.index())
    }
}

impl std::fmt::Display for Slot {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.index().fmt(f)
    }
}

/// A component of a vector in a needle node's frame $(t, n)$: along the shaft ($t$, the axial
/// component, index 0) or across it ($n$, the lateral component, index 1). Local arrays
/// `[f64; 2]` are indexed by it: `f[Axis::Axial]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Axis {
    /// Along the shaft, $t = (\cos\theta, \sin\theta)$: $u_t$, $f_t$.
    Axial = 0,
    /// Across the shaft, $n = (-\sin\theta, \cos\theta)$: $u_n$, $f_n$.
    Lateral = 1,
}

impl Axis {
    /// Both axes, axial first (the order of a local array).
    pub const BOTH: [Axis; 2] = [Axis::Axial, Axis::Lateral];
    /// The index into a local array: 0 for axial, 1 for lateral.
    #[inline]
    pub fn index(self) -> usize {
        self as usize
    }
    /// The axis of a local index (`k % 2` of a hybrid-system DOF).
    #[inline]
    pub fn of_index(k: usize) -> Axis {
        if k.is_multiple_of(2) { Axis::Axial } else { Axis::Lateral }
    }
    /// The name, as in messages: "axial (t)" or "lateral (n)".
    pub fn as_str(self) -> &'static str {
        match self {
            Axis::Axial => "axial (t)",
            Axis::Lateral => "lateral (n)",
        }
    }
}

impl std::fmt::Display for Axis {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

impl<T> std::ops::Index<Axis> for [T; 2] {
    type Output = T;
    #[inline]
    fn index(&self, axis: Axis) -> &T {
        &self[axis.index()]
    }
}

impl<T> std::ops::IndexMut<Axis> for [T; 2] {
    #[inline]
    fn index_mut(&mut self, axis: Axis) -> &mut T {
        &mut self[axis.index()]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slot_round_trips_and_option_has_a_niche() {
        for k in [0usize, 1, 7, 4095] {
            assert_eq!(Slot::new(k).index(), k);
        }
        assert_eq!(std::mem::size_of::<Option<Slot>>(), std::mem::size_of::<Slot>());
        assert_eq!(Slot::new(3).dof(Axis::Lateral), 7);
        let f = [1.0, 2.0];
        assert_eq!((f[Axis::Axial], f[Axis::Lateral]), (1.0, 2.0));
    }
}
