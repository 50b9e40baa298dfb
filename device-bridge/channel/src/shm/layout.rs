//! The memory layout of the channel file: the versioned header, the two slots' places, and
//! how a pose and a force are encoded as the words of their slot.

use std::mem::{offset_of, size_of};
use std::sync::atomic::{AtomicU32, AtomicU64};

use super::seqlock::Slot;
use super::values::{DevicePose, ServerForce};

#[repr(C, align(128))]
pub(super) struct Header {
    pub(super) magic: AtomicU64,
    pub(super) version: AtomicU32,
    pub(super) owner_lock: AtomicU32,
    pub(super) total_size: AtomicU64,
    pub(super) generation: AtomicU64,
    pub(super) creator_pid: AtomicU32,
    pub(super) attacher_pid: AtomicU32,
    pub(super) closed: AtomicU32,
    pub(super) dimension: AtomicU32,
    pub(super) tick_origin_ns: AtomicU64,
    pub(super) tick_period_ns: AtomicU64,
}

pub(super) const POSE_WORDS: usize = 10;
pub(super) const FORCE_WORDS: usize = 53;

#[repr(C)]
pub(super) struct Layout {
    pub(super) header: Header,
    pub(super) pose: Slot<POSE_WORDS>,
    pub(super) force: Slot<FORCE_WORDS>,
}

const _: () = {
    assert!(size_of::<Layout>() == 768);
    assert!(offset_of!(Layout, header) == 0);
    assert!(offset_of!(Header, version) == 8);
    assert!(offset_of!(Header, owner_lock) == 12);
    assert!(offset_of!(Header, total_size) == 16);
    assert!(offset_of!(Header, generation) == 24);
    assert!(offset_of!(Header, creator_pid) == 32);
    assert!(offset_of!(Header, attacher_pid) == 36);
    assert!(offset_of!(Header, closed) == 40);
    assert!(offset_of!(Header, dimension) == 44);
    assert!(offset_of!(Header, tick_origin_ns) == 48);
    assert!(offset_of!(Header, tick_period_ns) == 56);
    assert!(offset_of!(Layout, pose) == 128);
    assert!(offset_of!(Layout, force) == 256);
    assert!(offset_of!(Slot<FORCE_WORDS>, words) == 16);
};

impl DevicePose {
    /// Words: `t_ns`, `position_m[3]`, `orientation[4]`, `buttons`, `counter`.
    pub(super) fn encode(&self, counter: u64) -> [u64; POSE_WORDS] {
        let mut w = [0u64; POSE_WORDS];
        w[0] = self.t_ns;
        for (d, s) in w[1..4].iter_mut().zip(&self.position_m) {
            *d = s.to_bits();
        }
        for (d, s) in w[4..8].iter_mut().zip(&self.orientation) {
            *d = s.to_bits();
        }
        w[8] = self.buttons as u64;
        w[9] = counter;
        w
    }
    pub(super) fn decode(w: &[u64; POSE_WORDS]) -> Self {
        let f = |i: usize| f64::from_bits(w[i]);
        Self { t_ns: w[0], position_m: [f(1), f(2), f(3)], orientation: [f(4), f(5), f(6), f(7)], buttons: w[8] as u32, counter: w[9] }
    }
}

/// The pose slot's word holding the counter.
pub(super) const POSE_COUNTER_WORD: usize = 9;

impl ServerForce {
    /// Words: `t_ns`, `tick`, `force_n[3]`, `torque_nm[3]`, `stiffness[36]` (row-major),
    /// `base_position_m[3]`, `base_orientation[4]`, `state`, `pose_counter`.
    pub(super) fn encode(&self) -> [u64; FORCE_WORDS] {
        let mut w = [0u64; FORCE_WORDS];
        w[0] = self.t_ns;
        w[1] = self.tick;
        let floats = self
            .force_n
            .iter()
            .chain(&self.torque_nm)
            .chain(self.stiffness.iter().flatten())
            .chain(&self.base_position_m)
            .chain(&self.base_orientation);
        for (d, s) in w[2..51].iter_mut().zip(floats) {
            *d = s.to_bits();
        }
        w[51] = self.state as u64;
        w[52] = self.pose_counter;
        w
    }
    pub(super) fn decode(w: &[u64; FORCE_WORDS]) -> Self {
        let f = |i: usize| f64::from_bits(w[i]);
        Self {
            t_ns: w[0],
            tick: w[1],
            force_n: [f(2), f(3), f(4)],
            torque_nm: [f(5), f(6), f(7)],
            stiffness: std::array::from_fn(|r| std::array::from_fn(|c| f(8 + 6 * r + c))),
            base_position_m: [f(44), f(45), f(46)],
            base_orientation: [f(47), f(48), f(49), f(50)],
            state: w[51] as u32,
            pose_counter: w[52],
        }
    }
}
