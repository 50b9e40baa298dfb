//! The measurement side of the paper (issue 9): marker tracking in phantom images, identification
//! of Young's modulus and Poisson's ratio from a probing experiment, the needle force
//! distribution from an insertion experiment, and a synthetic experiment generator for the tests.
//!
//! Data flow: images (PNG) → [`track`] → marker tracks ([`tracks::MarkerTracks`], CSV) →
//! [`probe`] (E, ν) or [`needle_fit`] (friction per length and tip peak) → a scene file.
//! [`experiment`] and [`render`] make the synthetic inputs from the simulator itself.

pub mod cli;
pub mod experiment;
pub mod needle_fit;
pub mod probe;
pub mod render;
pub mod track;
pub mod tracks;
