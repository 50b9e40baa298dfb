//! needlesim-training: the training layer's pure half — exercises ([`exercise`]: TOML, shipped
//! examples), metrics and score computed incrementally from tick samples ([`sample`],
//! [`metrics`]: `MetricsTracker::push` per tick with bounded memory, `score()` at any time,
//! `finish()`), structures to spare ([`geometry`]), scripted exercise runs ([`run`]) and the
//! after-action report ([`report`]: self-contained HTML, inline SVG) with an expert's run
//! overlaid ([`expert`]: the tick series CSV a scripted run writes, read back).
//!
//! A live session feeds the same tracker from its non-real-time fan-out side: build a
//! [`sample::Sample`] from each tick's output (one `Copy` struct, no allocation), `push` it,
//! call `place()` when the trainee declares "placed", read `score()` at the observers' rate.

pub mod cli;
pub mod exercise;
pub mod expert;
pub mod geometry;
pub mod metrics;
pub mod report;
pub mod run;
pub mod sample;
pub mod strain;
pub mod ultrasound;

pub use exercise::{EXERCISES, Exercise, ExerciseError, load_exercise, parse_exercise};
pub use metrics::{ExerciseResult, Metrics, MetricsTracker, PlaceError, Score, Trace, TrackerSpec};
pub use run::{ExerciseRun, ExerciseRunError, TimelineMarker, run_exercise};
pub use sample::Sample;
