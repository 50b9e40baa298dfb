//! The seqlock slot: one single-writer slot of words (the pose's, the force's), its write and
//! its bounded-retry read, and what a reader remembers between reads (see the module docs of
//! [`super`] for the ordering argument).

use std::sync::atomic::{AtomicU64, Ordering, fence};

use super::READ_RETRIES;
use super::values::{ReadStatus, Sample};

#[repr(C, align(128))]
pub(super) struct Slot<const N: usize> {
    pub(super) seq: AtomicU64,
    pub(super) generation: AtomicU64,
    pub(super) words: [AtomicU64; N],
}

pub(super) enum RawRead {
    /// A consistent snapshot: (sequence, writer generation).
    Ok(u64, u64),
    Contended,
}

impl<const N: usize> Slot<N> {
    pub(super) fn reset(&self) {
        self.seq.store(0, Ordering::Relaxed);
        self.generation.store(0, Ordering::Relaxed);
        for w in &self.words {
            w.store(0, Ordering::Relaxed);
        }
    }

    /// The single writer's seqlock write (see the module docs for the ordering argument).
    pub(super) fn write(&self, generation: u64, data: &[u64; N]) {
        let s = self.seq.load(Ordering::Relaxed);
        let open = s | 1; // a writer that died mid-write left it odd: continue from there
        self.seq.store(open, Ordering::Relaxed);
        fence(Ordering::Release);
        self.generation.store(generation, Ordering::Relaxed);
        for (w, &v) in self.words.iter().zip(data) {
            w.store(v, Ordering::Relaxed);
        }
        self.seq.store(open.wrapping_add(1), Ordering::Release);
    }

    pub(super) fn read(&self, out: &mut [u64; N]) -> RawRead {
        for _ in 0..READ_RETRIES {
            let s1 = self.seq.load(Ordering::Acquire);
            if s1 & 1 == 1 {
                std::hint::spin_loop();
                continue;
            }
            let g = self.generation.load(Ordering::Relaxed);
            for (o, w) in out.iter_mut().zip(&self.words) {
                *o = w.load(Ordering::Relaxed);
            }
            fence(Ordering::Acquire);
            let s2 = self.seq.load(Ordering::Relaxed);
            if s1 == s2 {
                return RawRead::Ok(s1, g);
            }
            std::hint::spin_loop();
        }
        RawRead::Contended
    }
}

#[derive(Default)]
pub(super) struct ReaderState<T> {
    pub(super) last_seq: u64,
    pub(super) last: Option<T>,
    pub(super) reads_since_fresh: u64,
}

impl<T: Copy> ReaderState<T> {
    /// The sample of a read that did not happen: the channel is broken.
    pub(super) fn broken(&mut self) -> Sample<T> {
        self.reads_since_fresh = self.reads_since_fresh.saturating_add(1);
        Sample { value: self.last, status: ReadStatus::Broken, reads_since_fresh: self.reads_since_fresh }
    }
}

pub(super) fn read_slot<T: Copy, const N: usize>(
    slot: &Slot<N>,
    generation: u64,
    st: &mut ReaderState<T>,
    decode: fn(&[u64; N]) -> T,
) -> Sample<T> {
    let mut buf = [0u64; N];
    let status = match slot.read(&mut buf) {
        RawRead::Ok(seq, g) if seq != 0 && seq != st.last_seq && g == generation => {
            st.last_seq = seq;
            st.last = Some(decode(&buf));
            ReadStatus::Fresh
        }
        RawRead::Ok(..) => ReadStatus::Unchanged,
        RawRead::Contended => ReadStatus::Contended,
    };
    if status == ReadStatus::Fresh {
        st.reads_since_fresh = 0;
    } else {
        st.reads_since_fresh = st.reads_since_fresh.saturating_add(1);
    }
    Sample { value: st.last, status, reads_since_fresh: st.reads_since_fresh }
}
