//! The 2D pieces of the static solve: a node's frame is its angle, and the 2D wording of the
//! errors (quoted by tests and users as it was). A 2D problem takes no material points: the
//! triangle search of the 2D simulation (`sim/setup.rs`, `sim/capture.rs`) is its own and the
//! `solve` command sends 2D points to the reference solver, so [`NoPointLocation`] has no value
//! and locating a 2D point is the error [`NoPointLocationError`].

use crate::dim::{ConditionLabel, Dim2};
use crate::statics::StaticError;

/// The rows $t = (\cos a, \sin a)$, $n = (-\sin a, \cos a)$ of the frame at angle $a$.
#[inline]
pub fn frame_rows(angle_rad: f64) -> [[f64; 2]; 2] {
    let (s, c) = angle_rad.sin_cos();
    [[c, s], [-s, c]]
}

/// An angle is a frame when it is finite; `what` is the condition's label.
pub fn check_angle(angle_rad: f64, what: &str) -> Result<(), StaticError<Dim2>> {
    if !angle_rad.is_finite() {
        return Err(StaticError::NonFinite { what: what.to_owned() });
    }
    Ok(())
}

/// The 2D wording: "a prescribed displacement on node 3", "a local-frame condition on node 3".
pub fn condition_label(label: ConditionLabel, node: usize) -> String {
    match label {
        ConditionLabel::World => format!("a prescribed displacement on node {node}"),
        ConditionLabel::LocalFrame | ConditionLabel::LocalValue => format!("a local-frame condition on node {node}"),
    }
}

/// Where a 2D material point lies in statics: nowhere (no value of this type exists).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NoPointLocation {}

/// A 2D static problem was given a material point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("a 2D static problem takes conditions at nodes only (material points are solved by the reference solver, fem_ref.py)")]
pub struct NoPointLocationError;
