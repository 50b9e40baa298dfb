//! Why a tick's output is not converged: one classification for the 2D and 3D steps, which every
//! driver's convergence policy (offline runs stop, live sessions fault) reads.

/// Why a step's output is the solver's last iterate rather than a converged answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unconverged {
    /// The stick/slip iteration stopped at `max_active_set_iterations` passes with contact
    /// conditions still changing.
    ActiveSetCap,
    /// The stick/slip iteration stopped at the tick's update budget
    /// ([`super::param_limits::MAX_UPDATES_PER_TICK`], 2D).
    UpdateBudget,
    /// Flexible needle: the shape passes stopped at their cap with the settled shape still off
    /// the shape the tissue was solved on.
    ShapePassCap,
}

impl Unconverged {
    /// A stable code (1..=3) for records that carry plain numbers (a live session's fault).
    pub fn code(self) -> u8 {
        match self {
            Unconverged::ActiveSetCap => 1,
            Unconverged::UpdateBudget => 2,
            Unconverged::ShapePassCap => 3,
        }
    }

    /// The reason of [`Self::code`], `None` for any other number.
    pub fn from_code(code: u8) -> Option<Self> {
        match code {
            1 => Some(Unconverged::ActiveSetCap),
            2 => Some(Unconverged::UpdateBudget),
            3 => Some(Unconverged::ShapePassCap),
            _ => None,
        }
    }
}

impl std::fmt::Display for Unconverged {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Unconverged::ActiveSetCap => {
                "the stick/slip iteration stopped at its cap (limits.max_active_set_iterations) with contacts still changing"
            }
            Unconverged::UpdateBudget => "the stick/slip iteration stopped at the tick's update budget",
            Unconverged::ShapePassCap => "the flexible needle's shape passes stopped at their cap with the shape still changing",
        })
    }
}

impl super::StepOutput {
    /// Why this output is not converged (`None`: converged): the shape-pass cap first, then the
    /// stick/slip cap, then the update budget.
    pub fn unconverged(&self) -> Option<Unconverged> {
        if self.shape_passes_capped {
            Some(Unconverged::ShapePassCap)
        } else if self.active_set_capped {
            Some(Unconverged::ActiveSetCap)
        } else if !self.converged {
            Some(Unconverged::UpdateBudget)
        } else {
            None
        }
    }
}

impl crate::sim3::StepOutput3 {
    /// Why this output is not converged (`None`: converged): the shape-pass cap, then the
    /// stick/slip cap.
    pub fn unconverged(&self) -> Option<Unconverged> {
        if self.shape_passes_capped {
            Some(Unconverged::ShapePassCap)
        } else if !self.converged {
            Some(Unconverged::ActiveSetCap)
        } else {
            None
        }
    }
}
