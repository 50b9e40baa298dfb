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
