//! Duty-cycled spinning of a 3D needle (issue 18; Minhas et al. 2007): while the needle is
//! inserted, it rolls about its own axis one full turn per `period_m` of insertion, over the
//! first fraction $\delta$ (the duty cycle) of each period, and holds its roll over the rest. A
//! bevel tip's lateral force then averages to about $(1 - \delta)$ of its unspun value, so the
//! path's curvature is controlled proportionally; $\delta = 1$ spins continuously (a straight
//! path), $\delta = 0$ stops the spin where it is.
//!
//! **The roll.** With $a$ the insertion accumulated since the command (the base's advance along
//! its own axis, tick by tick, counting only advances: a withdrawal does not unwind it), the
//! roll added to the controller's pose is
//! $$\phi(a) = \phi_0 + 2\pi\left(\lfloor a / p \rfloor + \min\!\left(1, \frac{a/p - \lfloor a/p \rfloor}{\delta}\right)\right),$$
//! $p$ the period and $\phi_0$ the roll the previous command had reached (a new command never
//! jumps the needle). The rolled pose is the controller's turned by $\phi$ about the needle's
//! axis through the base (the orientation's local $+x$): $q' = q \cdot R_x(\phi)$.
//!
//! The IO side writes the command as one atomic word ([`SpinCommand::to_word`]); the real-time
//! thread reads it each tick and keeps the accumulated insertion in [`SpinState`] — no lock, no
//! allocation.

use nalgebra::{UnitQuaternion, Vector3};
use needlesim_core::num::num;
use needlesim_core::sim3::BasePose3;

/// Shortest spin period, m.
pub const MIN_SPIN_PERIOD_M: f64 = 1e-4;
/// Longest spin period, m.
pub const MAX_SPIN_PERIOD_M: f64 = 0.1;
/// The period when a request leaves it at 0, m (Minhas et al.'s order of magnitude).
pub const DEFAULT_SPIN_PERIOD_M: f64 = 1e-3;

/// A spin command: the duty cycle in [0, 1] and the period, m, each held to a millionth (of
/// one) and a nanometre so that the pair fits one atomic word.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpinCommand {
    duty_ppm: u32,
    period_nm: u32,
}

/// A spin command refused, naming the field.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SpinError {
    /// When the duty cycle is not a number in [0, 1].
    #[error("duty_cycle = {}: must be in [0, 1] (0 stops the spin, 1 spins continuously)", num(*.0))]
    DutyCycle(f64),
    /// When the period is not finite or outside [`MIN_SPIN_PERIOD_M`, `MAX_SPIN_PERIOD_M`].
    #[error("period_m = {}: must be in [{MIN_SPIN_PERIOD_M}, {MAX_SPIN_PERIOD_M}] m (0: the default {DEFAULT_SPIN_PERIOD_M} m)", num(*.0))]
    Period(f64),
}

impl SpinCommand {
    /// No spin (a session's start).
    pub const STOPPED: Self = Self { duty_ppm: 0, period_nm: 1_000_000 };

    /// The command for a duty cycle and a period (m; 0 means [`DEFAULT_SPIN_PERIOD_M`]).
    ///
    /// Errors: [`SpinError::DutyCycle`] when `duty_cycle` is not in [0, 1],
    /// [`SpinError::Period`] when `period_m` is neither 0 nor in the bounds.
    pub fn new(duty_cycle: f64, period_m: f64) -> Result<Self, SpinError> {
        if !(0.0..=1.0).contains(&duty_cycle) {
            return Err(SpinError::DutyCycle(duty_cycle));
        }
        let period_m = if period_m == 0.0 { DEFAULT_SPIN_PERIOD_M } else { period_m };
        if !(MIN_SPIN_PERIOD_M..=MAX_SPIN_PERIOD_M).contains(&period_m) {
            return Err(SpinError::Period(period_m));
        }
        Ok(Self { duty_ppm: (duty_cycle * 1e6).round() as u32, period_nm: (period_m * 1e9).round() as u32 })
    }

    pub fn duty_cycle(&self) -> f64 {
        f64::from(self.duty_ppm) * 1e-6
    }

    pub fn period_m(&self) -> f64 {
        f64::from(self.period_nm) * 1e-9
    }

    /// The command as one word: duty (ppm) in the high half, period (nm) in the low half.
    pub fn to_word(self) -> u64 {
        (u64::from(self.duty_ppm) << 32) | u64::from(self.period_nm)
    }

    /// The command of [`SpinCommand::to_word`]'s word; the stopped command for 0 (a session's
    /// initial word).
    pub fn from_word(w: u64) -> Self {
        if w == 0 {
            return Self::STOPPED;
        }
        Self { duty_ppm: (w >> 32) as u32, period_nm: w as u32 }
    }
}

/// What the real-time thread keeps between ticks: the command in force, the insertion
/// accumulated under it and the roll reached before it.
#[derive(Debug, Clone, Copy, Default)]
pub struct SpinState {
    word: u64,
    advance_m: f64,
    roll0_rad: f64,
    last_position_m: Option<[f64; 3]>,
}

impl SpinState {
    /// The roll added so far, rad (module docs).
    pub fn roll_rad(&self) -> f64 {
        let cmd = SpinCommand::from_word(self.word);
        let delta = cmd.duty_cycle();
        if delta == 0.0 {
            return self.roll0_rad;
        }
        let x = self.advance_m / cmd.period_m();
        let k = x.floor();
        self.roll0_rad + std::f64::consts::TAU * (k + ((x - k) / delta).min(1.0))
    }

    /// Turns `pose` (the controller's) by the spin's roll for this tick, given the command word
    /// the IO side wrote; accumulates the base's advance along its axis since the last tick.
    pub fn apply_from_rt(&mut self, word: u64, pose: &mut BasePose3) {
        if word != self.word {
            // A new command: the roll reached so far is its start.
            self.roll0_rad = self.roll_rad();
            self.advance_m = 0.0;
            self.word = word;
        }
        let p = pose.position_m;
        if let Some(q) = self.last_position_m {
            let t = pose.axis();
            let d = (p[0] - q[0]) * t[0] + (p[1] - q[1]) * t[1] + (p[2] - q[2]) * t[2];
            if d > 0.0 {
                self.advance_m += d;
            }
        }
        self.last_position_m = Some(p);
        let roll = self.roll_rad();
        if roll != 0.0 {
            let r = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), roll);
            *pose = BasePose3::from_rotation(p, pose.orientation * r);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{PI, TAU};

    /// The roll about the pose's axis from `a` to `b` (b = a turned about a's axis), rad.
    fn roll_between(a: &BasePose3, b: &BasePose3) -> f64 {
        let rel = a.orientation.inverse() * b.orientation;
        match rel.axis_angle() {
            None => 0.0,
            Some((axis, angle)) => {
                assert!((axis.x.abs() - 1.0).abs() < 1e-9, "a roll is about the local x axis: {axis:?}");
                angle * axis.x.signum()
            }
        }
    }

    fn wrap(a: f64) -> f64 {
        (a + PI).rem_euclid(TAU) - PI
    }

    /// Issue 35 (finding 6a): a client's 1e300 was echoed as 301 digits.
    #[test]
    fn issue35_refused_values_are_printed_short() {
        let e = SpinCommand::new(1e300, 0.0).unwrap_err().to_string();
        assert!(e.starts_with("duty_cycle = 1e300: must be in [0, 1]"), "{e}");
        let e = SpinCommand::new(0.5, -1e-300).unwrap_err().to_string();
        assert!(e.starts_with("period_m = -1e-300: must be in ["), "{e}");
        assert!(SpinCommand::new(0.5, 1e300).unwrap_err().to_string().len() < 120);
    }

    #[test]
    fn commands_are_checked_and_round_trip_through_one_word() {
        assert_eq!(SpinCommand::new(1.5, 0.0), Err(SpinError::DutyCycle(1.5)));
        assert!(matches!(SpinCommand::new(f64::NAN, 0.0), Err(SpinError::DutyCycle(_))));
        assert_eq!(SpinCommand::new(0.5, 1.0), Err(SpinError::Period(1.0)));
        assert!(matches!(SpinCommand::new(0.5, f64::INFINITY), Err(SpinError::Period(_))));
        assert!(SpinCommand::new(0.5, -1e-3).is_err());
        let c = SpinCommand::new(0.25, 0.002).unwrap();
        assert_eq!(SpinCommand::from_word(c.to_word()), c);
        assert_eq!((c.duty_cycle(), c.period_m()), (0.25, 0.002));
        assert_eq!(SpinCommand::new(0.5, 0.0).unwrap().period_m(), DEFAULT_SPIN_PERIOD_M);
        assert_eq!(SpinCommand::from_word(0), SpinCommand::STOPPED);
        assert_eq!(SpinCommand::STOPPED.duty_cycle(), 0.0);
    }

    /// A needle inserted along a tilted axis in uneven steps, withdrawn and inserted again: the
    /// roll is the closed form of the accumulated insertion; a new command starts from the roll
    /// reached; δ = 0 holds it; the position is never changed.
    #[test]
    fn the_roll_follows_the_accumulated_insertion() {
        let start = BasePose3::looking_along([0.01, 0.02, 0.1], [0.3, -0.2, -0.93]);
        let t = start.axis();
        let b = start.position_m;
        let at = |s: f64| BasePose3::from_rotation([b[0] + s * t[0], b[1] + s * t[1], b[2] + s * t[2]], start.orientation);
        let mut st = SpinState::default();
        let half = SpinCommand::new(0.5, 1e-3).unwrap().to_word();
        let mut p = at(0.0);
        st.apply_from_rt(half, &mut p);
        assert_eq!(roll_between(&at(0.0), &p), 0.0);
        // Uneven steps to 2.3 mm: 2 turns and 0.3 / 0.5 of the third.
        let (mut s, mut k) = (0.0, 0);
        while s < 2.3e-3 - 1e-12 {
            s = (s + 1.7e-4 * (1.0 + (k % 3) as f64)).min(2.3e-3);
            k += 1;
            p = at(s);
            st.apply_from_rt(half, &mut p);
        }
        let want = TAU * (2.0 + 0.3 / 0.5);
        assert!(wrap(roll_between(&at(s), &p) - want).abs() < 1e-9, "{} vs {want}", roll_between(&at(s), &p));
        assert!((st.roll_rad() - want).abs() < 1e-9);
        assert!((0..3).all(|i| (p.position_m[i] - at(s).position_m[i]).abs() < 1e-15), "the position is the controller's");
        // Withdrawing 1 mm does not unwind; inserting it again rolls on (1 mm more: one turn).
        for s2 in [1.8e-3, 1.3e-3] {
            let mut q = at(s2);
            st.apply_from_rt(half, &mut q);
            assert!((st.roll_rad() - want).abs() < 1e-9, "{}", st.roll_rad());
        }
        for s2 in [1.8e-3, 2.3e-3] {
            let mut q = at(s2);
            st.apply_from_rt(half, &mut q);
        }
        let want = want + TAU;
        assert!((st.roll_rad() - want).abs() < 1e-9, "{}", st.roll_rad());
        // A new command (δ = 1, 2 mm) starts from the roll reached.
        let full = SpinCommand::new(1.0, 2e-3).unwrap().to_word();
        let mut q = at(2.3e-3);
        st.apply_from_rt(full, &mut q);
        assert!((st.roll_rad() - want).abs() < 1e-12);
        let mut q = at(2.8e-3);
        st.apply_from_rt(full, &mut q);
        assert!((st.roll_rad() - want - TAU * 0.25).abs() < 1e-9);
        // δ = 0 stops where it is, whatever the insertion.
        let stop = SpinCommand::new(0.0, 0.0).unwrap().to_word();
        let held = st.roll_rad();
        for s2 in [3e-3, 5e-3, 9e-3] {
            let mut q = at(s2);
            st.apply_from_rt(stop, &mut q);
            assert!(wrap(roll_between(&at(s2), &q) - held).abs() < 1e-9);
        }
    }
}
