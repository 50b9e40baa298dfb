//! The needle: its base pose, its shape behind one type, and the friction force distribution
//! along its shaft (the paper's Fig. 2b).
//!
//! The base pose is $(x_b, y_b, \theta)$; the shaft leaves the base along $t = (\cos\theta, \sin\theta)$,
//! with lateral direction $n = (-\sin\theta, \cos\theta)$. A point of the shaft is named by its arc
//! length $s$ from the base; the tip is at $s = L$.
//!
//! Friction per unit length at distance $\ell = s_{tip} - s$ behind the tip:
//! $$q(\ell) = q_0\Big(1 + h\,\tfrac12\big(1 + \cos(\pi \ell / w)\big)\,[\ell < w]\Big),$$
//! a uniform level $q_0$ with a raised-cosine peak of relative height $h$ (≈ 0.3) and width $w$ just
//! behind the tip. A needle node receives the integral of $q$ over its tributary segment.
//!
//! Rate-dependent friction (issue 19): the kinetic friction per unit length grows with the
//! slip speed $v$ as in the modified Karnopp model that Okamura, Simone and O'Leary fitted to
//! needle insertions into bovine liver ("Force modeling for needle insertion into soft tissue",
//! IEEE TBME 51(10), 2004: Coulomb plus viscous friction, $F = C\,\mathrm{sgn}(v) + b\,v$ with
//! $v$ the needle's velocity), distributed along the shaft:
//! $$q(\ell, v) = q_0\Big(1 + h\,\tfrac12\big(1 + \cos(\pi \ell / w)\big)\,[\ell < w]\Big) + b_v\,|v|,$$
//! with $b_v$ (N·s/m², [`RegionNeedleParams::friction_damping_n_s_per_m2`]) the viscous
//! friction per unit length and unit speed; a node of tributary length $\lambda$ gets
//! $\int q_0(\ldots) + b_v |v| \lambda$ (a stuck node's static threshold scales with it). As in
//! Okamura et al., $v$ is the needle's axial speed (over the last tick): the tissue is taken at
//! rest. The tissue points' own speed is not used because the quasi-static stick/slip
//! alternates at the tick level (a contact slides one tick, holds the next), so a per-contact
//! speed is noise at the tick rate rather than a velocity. $b_v = 0$ is the paper's law. By
//! hand, for uniform friction: a shaft length $\ell$ sliding at the insertion speed $V$
//! carries $(q_0 + b_v V)\,\ell$.

/// The commanded or current pose of the needle base.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BasePose {
    pub x_m: f64,
    pub y_m: f64,
    pub theta_rad: f64,
}

impl BasePose {
    /// A pose.
    pub fn new(x_m: f64, y_m: f64, theta_rad: f64) -> Self {
        Self { x_m, y_m, theta_rad }
    }
    /// Whether all three components are finite.
    pub fn is_finite(&self) -> bool {
        self.x_m.is_finite() && self.y_m.is_finite() && self.theta_rad.is_finite()
    }
    /// The base position.
    pub fn position_m(&self) -> [f64; 2] {
        [self.x_m, self.y_m]
    }
    /// The axial direction $t$.
    pub fn axis(&self) -> [f64; 2] {
        let (s, c) = self.theta_rad.sin_cos();
        [c, s]
    }
    /// The lateral direction $n$.
    pub fn normal(&self) -> [f64; 2] {
        let (s, c) = self.theta_rad.sin_cos();
        [-s, c]
    }
}

/// A straight, rigid needle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidNeedle {
    /// Shaft length from base to tip.
    pub length_m: f64,
}

/// A flexible needle: an elastic beam clamped at the base pose (see [`crate::beam`]), optionally
/// with a bevel tip.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlexibleNeedle {
    /// Shaft length from base to tip.
    pub length_m: f64,
    /// Flexural rigidity $EI$, N·m².
    pub flexural_rigidity_nm2: f64,
    /// Number of rigid links of the discrete beam (its resolution).
    pub n_links: usize,
    /// Bevel tip: lateral over axial force of the tissue on the tip, $\beta$ (0: symmetric tip).
    /// The tissue at the tip receives $-s_b \beta f_t\, n$ and the needle $+s_b \beta f_t\, n$,
    /// with $f_t$ the axial force of the tip on the tissue and $s_b = \pm 1$ the bevel side.
    pub bevel_force_ratio: f64,
    /// Initial bevel side $s_b$: +1 towards the needle's $+n$, −1 towards $-n$.
    pub bevel_side: f64,
}

impl FlexibleNeedle {
    /// Second moment of area of a tube, $I = \pi (D^4 - d^4)/64$, m⁴.
    pub fn tube_second_moment_m4(outer_diameter_m: f64, inner_diameter_m: f64) -> f64 {
        std::f64::consts::PI * (outer_diameter_m.powi(4) - inner_diameter_m.powi(4)) / 64.0
    }
    /// $EI$ of a 17-gauge (1.473 mm outer, 1.067 mm inner diameter, regular wall) stainless
    /// steel (E = 193 GPa) needle: ≈ 0.0318 N·m².
    pub fn gauge17_steel_rigidity_nm2() -> f64 {
        193e9 * Self::tube_second_moment_m4(1.473e-3, 1.067e-3)
    }
    /// A 17-gauge stainless steel needle of the given length with a symmetric tip, 2 mm links
    /// (at least 16; the beam's discretisation error, $O(h^2)$, is then below 1e-3 of its
    /// deflection).
    pub fn gauge17_steel(length_m: f64) -> Self {
        Self {
            length_m,
            flexural_rigidity_nm2: Self::gauge17_steel_rigidity_nm2(),
            n_links: ((length_m / 2e-3).round() as usize).clamp(16, 400),
            bevel_force_ratio: 0.0,
            bevel_side: 1.0,
        }
    }
}

/// The needle's shape parameters. The simulation asks this type for the undeformed geometry and
/// keeps the deformed shape of a flexible needle itself ([`crate::beam::NeedleCurve`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NeedleShape {
    Rigid(RigidNeedle),
    Flexible(FlexibleNeedle),
}

impl NeedleShape {
    /// The arc length of the tip, $L$.
    pub fn tip_s_m(&self) -> f64 {
        match self {
            NeedleShape::Rigid(r) => r.length_m,
            NeedleShape::Flexible(f) => f.length_m,
        }
    }
    /// The flexible needle's parameters, if it is one.
    pub fn flexible(&self) -> Option<&FlexibleNeedle> {
        match self {
            NeedleShape::Rigid(_) => None,
            NeedleShape::Flexible(f) => Some(f),
        }
    }
    /// The point of the undeformed (straight) shaft at arc length `s_m`.
    pub fn point_at(&self, base: &BasePose, s_m: f64) -> [f64; 2] {
        let t = base.axis();
        [base.x_m + s_m * t[0], base.y_m + s_m * t[1]]
    }
    /// The frame angle (direction of the tangent) at arc length `s_m`.
    pub fn frame_angle_at(&self, base: &BasePose, _s_m: f64) -> f64 {
        base.theta_rad
    }
    /// The tip position.
    pub fn tip_m(&self, base: &BasePose) -> [f64; 2] {
        self.point_at(base, self.tip_s_m())
    }
    /// Projects a point onto the shaft's line: `(s, lateral)` with $s = t\cdot(p-b)$ and
    /// lateral offset $n\cdot(p-b)$.
    pub fn project(&self, base: &BasePose, p_m: [f64; 2]) -> (f64, f64) {
        let (t, n) = (base.axis(), base.normal());
        let d = [p_m[0] - base.x_m, p_m[1] - base.y_m];
        (t[0] * d[0] + t[1] * d[1], n[0] * d[0] + n[1] * d[1])
    }
    /// Checks the shape's parameters.
    pub fn validate(&self) -> Result<(), String> {
        let length_m = self.tip_s_m();
        let max_len = crate::sim::param_limits::MAX_LENGTH_M;
        if !(length_m.is_finite() && length_m > 0.0 && length_m <= max_len) {
            return Err(format!("needle length {} m must be finite, > 0 and ≤ {} m", crate::num::num(length_m), crate::num::num(max_len)));
        }
        if let NeedleShape::Flexible(f) = self {
            let ei = f.flexural_rigidity_nm2;
            if !(ei.is_finite() && ei > 0.0) {
                return Err(format!("needle flexural_rigidity_nm2 = {} must be finite and > 0", crate::num::num(ei)));
            }
            if !(2..=4096).contains(&f.n_links) {
                return Err(format!("needle n_links = {} must be in 2..=4096", f.n_links));
            }
            if !(f.bevel_force_ratio.is_finite() && f.bevel_force_ratio >= 0.0 && f.bevel_force_ratio <= 10.0) {
                return Err(format!("needle bevel_force_ratio = {} must be finite and in [0, 10]", crate::num::num(f.bevel_force_ratio)));
            }
            if f.bevel_side != 1.0 && f.bevel_side != -1.0 {
                return Err(format!("needle bevel_side = {} must be +1 or -1", crate::num::num(f.bevel_side)));
            }
        }
        Ok(())
    }
}

/// Needle–tissue interaction parameters of one tissue region.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RegionNeedleParams {
    /// Kinetic friction per unit needle length, $q_0$, N/m.
    pub friction_n_per_m: f64,
    /// Static over kinetic friction (≥ 1): a stuck node slips when its axial force exceeds
    /// this ratio times its kinetic friction share.
    pub static_friction_ratio: f64,
    /// Relative height $h$ of the friction peak behind the tip (≈ 0.3 in the paper). With
    /// energy-based cutting ([`Self::toughness_cutting_force_n`]) it acts only while the tip cuts.
    pub tip_peak_ratio: f64,
    /// Width $w$ of the friction peak behind the tip, m.
    pub tip_peak_width_m: f64,
    /// Axial force at which the tip punctures a surface node (or a node of a region the tip
    /// enters), N.
    pub puncture_force_n: f64,
    /// Axial force at which the tip cuts past an interior node of the same region, N.
    pub cutting_force_n: f64,
    /// Viscous friction $b_v$ per unit length and unit slip speed, N·s/m² (module docs): a node
    /// slipping at $v$ gets $b_v |v|$ per metre of its tributary segment on top of $q$. 0: the
    /// paper's rate-independent friction.
    pub friction_damping_n_s_per_m2: f64,
    /// Energy-based cutting (issue 19; Mahvash & Hayward, IEEE TBME 2010), with material-point
    /// contact only: `Some(F_c)`, the cutting force $F_c = G_c\,w$ of a fracture toughness
    /// $G_c$ (J/m²) and the needle's width $w$ (m). Advancing the tip by $\delta$ creates a
    /// crack of area $w\,\delta$ and costs the work $G_c\,w\,\delta$, so the tissue at the tip
    /// resists with the constant force $F_c$ while the tip cuts, and with nothing while it rests
    /// or withdraws. It is applied to the most distal contact on top of its friction share
    /// (`sim/active_set.rs`); interior points are then taken as slipping contacts, not carried
    /// by the tip ($F_c$ replaces [`Self::cutting_force_n`], so no sawtooth). `None`: the
    /// threshold model (a carried contact cut at `cutting_force_n`).
    pub toughness_cutting_force_n: Option<f64>,
}

impl Default for RegionNeedleParams {
    /// PVC-like phantom values for a 17-gauge needle in a 1 cm thick slice.
    fn default() -> Self {
        Self {
            friction_n_per_m: 10.0,
            static_friction_ratio: 1.3,
            tip_peak_ratio: 0.3,
            tip_peak_width_m: 0.005,
            puncture_force_n: 0.3,
            cutting_force_n: 0.05,
            friction_damping_n_s_per_m2: 0.0,
            toughness_cutting_force_n: None,
        }
    }
}

impl RegionNeedleParams {
    /// Checks the values; `region` names the region in the message.
    pub fn validate(&self, region: &str) -> Result<(), String> {
        let fc = self.toughness_cutting_force_n.unwrap_or(0.0);
        let checks: [(&str, f64, bool); 8] = [
            ("friction_n_per_m", self.friction_n_per_m, self.friction_n_per_m >= 0.0),
            ("static_friction_ratio", self.static_friction_ratio, self.static_friction_ratio >= 1.0),
            ("tip_peak_ratio", self.tip_peak_ratio, self.tip_peak_ratio >= 0.0),
            ("tip_peak_width_m", self.tip_peak_width_m, self.tip_peak_width_m > 0.0),
            ("puncture_force_n", self.puncture_force_n, self.puncture_force_n >= 0.0),
            ("cutting_force_n", self.cutting_force_n, self.cutting_force_n >= 0.0),
            ("friction_damping_n_s_per_m2", self.friction_damping_n_s_per_m2, self.friction_damping_n_s_per_m2 >= 0.0),
            ("toughness_cutting_force_n", fc, fc >= 0.0),
        ];
        use crate::sim::param_limits::{MAX_LENGTH_M, MAX_REGION_VALUE};
        for (name, v, ok) in checks {
            let max = if name == "tip_peak_width_m" { MAX_LENGTH_M } else { MAX_REGION_VALUE };
            if !(v.is_finite() && ok && v <= max) {
                let rule = match name {
                    "static_friction_ratio" => "finite and ≥ 1",
                    "tip_peak_width_m" => "finite and > 0",
                    _ => "finite and ≥ 0",
                };
                let bound = if name == "tip_peak_width_m" { format!("{} m", crate::num::num(max)) } else { format!("{max:e}") };
                return Err(format!("region {region}: {name} = {} must be {rule}, at most {bound}", crate::num::num(v)));
            }
        }
        Ok(())
    }

    /// $\int_{\ell_1}^{\ell_2} q(\ell)\,d\ell$ for $0 \le \ell_1 \le \ell_2$ (distances behind the tip).
    pub fn friction_integral_n(&self, l1_m: f64, l2_m: f64) -> f64 {
        self.friction_integral_with_peak_n(l1_m, l2_m, true)
    }

    /// [`Self::friction_integral_n`] with the peak behind the tip (`peak`) or without it
    /// ($h = 0$: the plain $q_0$). With energy-based cutting the peak, which the paper
    /// attributes to cutting, is applied only while the tip cuts (issue 19).
    pub fn friction_integral_with_peak_n(&self, l1_m: f64, l2_m: f64, peak: bool) -> f64 {
        let (q0, w) = (self.friction_n_per_m, self.tip_peak_width_m);
        let h = if peak { self.tip_peak_ratio } else { 0.0 };
        let (l1, l2) = (l1_m.max(0.0), l2_m.max(0.0));
        if l2 <= l1 {
            return 0.0;
        }
        let (p1, p2) = (l1.min(w), l2.min(w));
        let pi = std::f64::consts::PI;
        let peak = 0.5 * h * ((p2 - p1) + (w / pi) * ((pi * p2 / w).sin() - (pi * p1 / w).sin()));
        q0 * ((l2 - l1) + peak)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn friction_integral_matches_quadrature() {
        let p = RegionNeedleParams { friction_n_per_m: 12.0, tip_peak_ratio: 0.3, tip_peak_width_m: 0.004, ..Default::default() };
        let q = |l: f64| {
            let bump = if l < 0.004 { 0.5 * (1.0 + (std::f64::consts::PI * l / 0.004).cos()) } else { 0.0 };
            12.0 * (1.0 + 0.3 * bump)
        };
        for (a, b) in [(0.0, 0.001), (0.002, 0.009), (0.0, 0.02), (0.005, 0.006)] {
            let n = 20000;
            let h = (b - a) / n as f64;
            let num: f64 = (0..n).map(|i| q(a + (i as f64 + 0.5) * h) * h).sum();
            assert!((p.friction_integral_n(a, b) - num).abs() < 1e-7 * num, "[{a}, {b}]");
        }
        // The peak right behind the tip is 30 % above the level.
        assert!((p.friction_integral_n(0.0, 1e-7) / 1e-7 - 12.0 * 1.3).abs() < 1e-6);
    }

    #[test]
    fn projection_and_points_agree() {
        let base = BasePose::new(0.01, -0.02, 0.7);
        let shape = NeedleShape::Rigid(RigidNeedle { length_m: 0.08 });
        let p = shape.point_at(&base, 0.05);
        let (s, lat) = shape.project(&base, p);
        assert!((s - 0.05).abs() < 1e-15 && lat.abs() < 1e-15);
        assert!(RegionNeedleParams { static_friction_ratio: 0.9, ..Default::default() }.validate("skin").unwrap_err().contains("skin"));
    }
}
