//! needlesim-identify, the measurement side of the paper (issue 9): marker tracking in phantom
//! images, identification of Young's modulus and Poisson's ratio from a probing experiment, and
//! the needle force distribution from an insertion experiment; with the `synthetic` feature, the
//! synthetic experiments and images the tests and `needlesim-lab identify synth|render` make.
//!
//! Data flow: images (PNG, [`frame`]) → [`track`] → marker tracks ([`tracks::MarkerTracks`], CSV)
//! → [`probe`] (E, ν, with a [`logs::ProbeLog`]) or [`needle_fit`] (friction per length and tip
//! peak, with a [`logs::ForceLog`]) → a scene file. `experiment` and `render` (feature
//! `synthetic`) make the synthetic inputs from the simulator itself.

#[cfg(feature = "synthetic")]
pub mod experiment;
pub mod frame;
pub mod logs;
pub mod needle_fit;
pub mod probe;
#[cfg(feature = "synthetic")]
pub mod render;
pub mod track;
pub mod tracks;

use std::ops::ControlFlow;

/// The progress callback of the long calls ([`track::track_png_bytes`], [`track::track_frames`],
/// [`probe::fit_probe`], [`needle_fit::fit_needle`]): called with `(done, total)` after each frame
/// or model evaluation; `Break` stops the call there with [`Cancelled`] (a server whose client
/// went away), as `Simulate`'s per-tick callback does.
pub type Progress<'a> = &'a mut dyn FnMut(usize, usize) -> ControlFlow<()>;

/// A progress callback that only lets the call go on.
pub fn no_progress(_done: usize, _total: usize) -> ControlFlow<()> {
    ControlFlow::Continue(())
}

/// The error of a call whose progress callback said `Break`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Cancelled;

impl std::fmt::Display for Cancelled {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("cancelled by the caller")
    }
}

impl std::error::Error for Cancelled {}

/// Reports `(done, total)`; `Err(Cancelled)` when the callback says `Break`.
pub(crate) fn report(progress: &mut dyn FnMut(usize, usize) -> ControlFlow<()>, done: usize, total: usize) -> anyhow::Result<()> {
    match progress(done, total) {
        ControlFlow::Continue(()) => Ok(()),
        ControlFlow::Break(()) => Err(Cancelled.into()),
    }
}
