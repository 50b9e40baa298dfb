//! Typed indices of the solver: a mesh node ([`NodeIdx`]), a working-set slot ([`Slot`]) and a
//! component of a needle-frame vector ([`Axis`]), so that they cannot be swapped for one another.
//! They serve 2D and 3D: a slot of a solver in dimension $D$ owns the local DOFs
//! $Dk, \dots, Dk + D - 1$ ([`Slot::local_dof`]); [`Axis`] names the local components $t$, $n$
//! and, in 3D only, $b$.
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
    /// The local DOF of this slot along `axis` in the hybrid system of a **2D** solver: $2k + a$
    /// (the 2D shorthand of [`Slot::local_dof`]`::<2>`).
    #[inline]
    pub fn dof(self, axis: Axis) -> usize {
        self.local_dof::<2>(axis)
    }
    /// The local DOF of this slot along `axis` in the hybrid system of a solver in dimension `D`:
    /// $Dk + a$. `axis` must be one of the first `D` axes (checked in debug builds).
    #[inline]
    pub fn local_dof<const D: usize>(self, axis: Axis) -> usize {
        debug_assert!(axis.index() < D, "axis {axis} in dimension {D}");
        D * self.index() + axis.index()
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

/// A component of a vector in a needle contact's frame: along the shaft ($t$, the axial
/// component, index 0), across it ($n$, the lateral component, index 1) and, in 3D, across it
/// the other way ($b = t \times n$, the binormal component, index 2). The frame's rows are
/// $[t, n]$ in 2D and $[t, n, b]$ in 3D ([`crate::mixed`]). Local arrays `[f64; 2]` and
/// `[f64; 3]` are indexed by it: `f[Axis::Axial]`.
///
/// One enum for both dimensions (rather than a bare component index) keeps the names in the
/// sim's code and in errors; [`Axis::Binormal`] on a 2D solver is a programming error.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Axis {
    /// Along the shaft: in 2D $t = (\cos\theta, \sin\theta)$: $u_t$, $f_t$.
    Axial = 0,
    /// Across the shaft: in 2D $n = (-\sin\theta, \cos\theta)$: $u_n$, $f_n$.
    Lateral = 1,
    /// 3D only: across the shaft, $b = t \times n$: $u_b$, $f_b$.
    Binormal = 2,
}

impl Axis {
    /// Both 2D axes, axial first (the order of a local array).
    pub const BOTH: [Axis; 2] = [Axis::Axial, Axis::Lateral];
    /// The three 3D axes, in the order of a local array.
    pub const ALL3: [Axis; 3] = [Axis::Axial, Axis::Lateral, Axis::Binormal];
    /// The index into a local array: 0 for axial, 1 for lateral, 2 for binormal.
    #[inline]
    pub fn index(self) -> usize {
        self as usize
    }
    /// The axis of a **2D** hybrid-system DOF `k` (`k % 2`); see [`Axis::of_local_dof`].
    #[inline]
    pub fn of_index(k: usize) -> Axis {
        Self::of_local_dof::<2>(k)
    }
    /// The axis of hybrid-system DOF `k` of a solver in dimension `D` (`k % D`).
    #[inline]
    pub fn of_local_dof<const D: usize>(k: usize) -> Axis {
        Self::of_component(k % D)
    }
    /// The axis of local component `c` (0, 1 or 2). Panics only on a programming error (`c > 2`).
    #[inline]
    pub fn of_component(c: usize) -> Axis {
        match c {
            0 => Axis::Axial,
            1 => Axis::Lateral,
            2 => Axis::Binormal,
            _ => panic!("local component {c} does not exist"),
        }
    }
    /// The first `D` axes, in the order of a local array.
    #[inline]
    pub fn all<const D: usize>() -> [Axis; D] {
        std::array::from_fn(Axis::of_component)
    }
    /// The name, as in messages: "axial (t)", "lateral (n)" or "binormal (b)".
    pub fn as_str(self) -> &'static str {
        match self {
            Axis::Axial => "axial (t)",
            Axis::Lateral => "lateral (n)",
            Axis::Binormal => "binormal (b)",
        }
    }
}

impl std::fmt::Display for Axis {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

impl<T, const D: usize> std::ops::Index<Axis> for [T; D] {
    type Output = T;
    #[inline]
    fn index(&self, axis: Axis) -> &T {
        &self[axis.index()]
    }
}

impl<T, const D: usize> std::ops::IndexMut<Axis> for [T; D] {
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
        // 3D: three local DOFs per slot.
        assert_eq!(Slot::new(3).local_dof::<3>(Axis::Binormal), 11);
        assert_eq!(Axis::of_local_dof::<3>(11), Axis::Binormal);
        assert_eq!(Axis::of_index(7), Axis::Lateral);
        assert_eq!(Axis::all::<3>(), Axis::ALL3);
        let g = [1.0, 2.0, 3.0];
        assert_eq!(g[Axis::Binormal], 3.0);
    }
}
