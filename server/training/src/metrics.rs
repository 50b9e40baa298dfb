//! Metrics and score of an exercise from tick samples, computed incrementally
//! ([`MetricsTracker::push`], O(targets + structures) per sample, memory fixed at construction),
//! with the score available at any time ([`MetricsTracker::score`]) and a final result
//! ([`MetricsTracker::finish`]).
//!
//! Notation: samples $k = 0 \dots K$ at times $t_k$, tip $x_k$, axis $a_k$, contacts $n_k$,
//! axial force $F_k$ ([`Sample`]). The needle is *in the tissue* at $k$ when it holds a
//! contact: $\mathrm{in}_k \Leftrightarrow n_k > 0$, $\mathrm{in}_{-1} = $ false. An insertion
//! starts at the first sample $k_0$ in the tissue; its entry point is $E = x_{k_0}$ and the
//! depth is $d_k = (x_k - E)\cdot a_k$ (along the needle; the simulation's inserted length lags
//! it with node capture, so it is not used).
//!
//! - **Time** $T = t_K - t_0$.
//! - **Insertions** $N_{ins} = \#\{k : \mathrm{in}_k \wedge \neg\mathrm{in}_{k-1}\}$ (the tip
//!   enters the tissue); reinsertions $N_{ins} - 1$ (none before the first).
//! - **Redirections** (within one insertion; $w$ = `redirect_threshold_m`, 5 mm by default):
//!   with the depth $d_k$ above: advancing, the peak is $P = \max d$ since the last
//!   re-advance; when $d_k < P - w$ the needle is withdrawing, with trough $V = \min d$ since;
//!   when then $d_k > V + w$ one redirection is counted and it advances again with $P = d_k$.
//!   So a redirection is a withdrawal by more than $w$ followed by a re-advance by more than
//!   $w$, without leaving the tissue (leaving and re-entering is a reinsertion instead).
//! - **Path length in tissue** $L = \sum_{k \ge 1,\ \mathrm{in}_k \wedge \mathrm{in}_{k-1}} |x_k - x_{k-1}|$.
//! - **Peak axial force** $F_{peak} = \max_k |F_k|$; **mean axial force**
//!   $\bar F = \frac{1}{|I|}\sum_{k\in I} |F_k|$ over $I = \{k : \mathrm{in}_k\}$ (0 if empty).
//! - **Targeting error.** When "placed" is declared at sample $k$ ([`MetricsTracker::place`]),
//!   the not yet placed target whose displaced centre $c_{i,k}$ is nearest the tip is placed,
//!   with error $e_i = |x_k - c_{i,k}|$ and depth $d_k$; it is *on target* when
//!   $e_i \le \tau_i$ (its tolerance).
//! - **Structures touched.** Structure $j$'s clearance at $k$ is the minimum signed distance
//!   over the inserted shaft, $c_{j,k} = \min_{0\le s\le \max(d_k, 0)} \phi_j(x_k - s a_k)$
//!   ([`crate::geometry`]); over the run $c_j = \min_{k\in I} c_{j,k}$ ($+\infty$ if $I$ is
//!   empty), the intrusion depth $\delta_j = \max(0, -c_j)$, touched when $c_j \le 0$, and the
//!   number of samples touching it.
//! - **Tissue strain above a damage threshold** (2D; [`crate::strain`] for the per-triangle
//!   equivalent strain $\varepsilon_{eq,e}$ and the damaged area $A_d$ above the exercise's
//!   `damage_strain` $\varepsilon_d$): at strain samples $j$ (every
//!   [`crate::run::STRAIN_INTERVAL_S`] of exercise time in a scripted run, from the displacement
//!   field $u = \sum_w C_{:,w} f_w$ of the working contacts, $O(n\,d)$ each), the peak strain
//!   $\varepsilon_{max} = \max_j \max_e \varepsilon_{eq,e,j}$ and its time, the largest damaged
//!   area $\max_j A_{d,j}$, and the number of strain samples with $A_{d,j} > 0$ (i.e.
//!   $\max_e \varepsilon_{eq,e,j} > \varepsilon_d$) — "samples above". A live 2D session takes
//!   the samples on its fan-out side from the field it computes for observers (the server's
//!   training_live.rs). Not scored. Not computed in 3D (the strain sample count is 0).
//!
//! **Score.** Sub-scores in $[0, 1]$:
//! accuracy $s_{acc} = \frac1n\sum_i a_i$ with $a_i = 1$ if $e_i \le \tau_i$,
//! $\max(0, 1 - \frac{e_i - \tau_i}{2\tau_i})$ otherwise (0 from $3\tau_i$), 0 if not placed;
//! efficiency $s_{eff} = 1 / (1 + \max(0, N_{ins} - 1) + N_{redir})$;
//! path $s_{path} = \min(1, D / L)$ with $D$ the deepest placement's depth (0 with no
//! placement or $L = 0$);
//! force $s_F = \mathrm{clamp}(1 - \bar F / F_{lim}, 0, 1)$;
//! safety $s_{safe} = \min_j \mathrm{clamp}(c_j / m_j, 0, 1)$ (1 without structures; $m_j$ the
//! structure's margin);
//! time $s_T = \mathrm{clamp}(2(1 - T / T_{lim}), 0, 1)$.
//! Total $S = \mathrm{clamp}\big(100\,\frac{\sum_m w_m s_m}{\sum_m w_m} - p\,(\mathbb 1[T > T_{lim}]
//! \;{+}\; \mathbb 1[N_{ins} - 1 > R_{lim}] \;{+}\; \mathbb 1[F_{peak} > F_{lim}]), 0, 100\big)$,
//! $p$ the limits' `penalty`. Before the end it is the score so far (unplaced targets count 0).

use serde::Serialize;

use crate::exercise::{Limits, Structure, Weights};
use crate::sample::{Sample, dist3};

/// A target as the tracker sees it.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackedTarget {
    pub name: String,
    /// Its index among the sample's targets ([`Sample::targets`]).
    pub sample_idx: usize,
    pub tolerance_m: f64,
}

/// What the tracker is built from (an exercise resolved against its scene: [`crate::run`]).
#[derive(Debug, Clone, PartialEq)]
pub struct TrackerSpec {
    /// 2 or 3 (structures' distances in 2D ignore z).
    pub dims: usize,
    pub targets: Vec<TrackedTarget>,
    pub structures: Vec<Structure>,
    pub limits: Limits,
    pub weights: Weights,
    pub redirect_threshold_m: f64,
}

/// Why "placed" was refused.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PlaceError {
    /// Declared before the first sample.
    #[error("\"placed\" declared before the first tick")]
    NoSample,
    /// Every target is placed already.
    #[error("every target is placed already ({0})")]
    AllPlaced(usize),
    /// The sample lacks the target the tracker expects (a spec that does not match the simulation).
    #[error("the tick carries {have} targets, target '{name}' is number {idx}")]
    MissingTarget { name: String, idx: usize, have: usize },
}

/// A placement.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Placement {
    pub t_s: f64,
    /// $e_i$, m.
    pub error_m: f64,
    pub on_target: bool,
    /// Depth $d_k$ at the placement, m.
    pub depth_m: f64,
    pub tip_m: [f64; 3],
    /// The displaced target centre, m.
    pub centre_m: [f64; 3],
}

/// A target's result.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TargetResult {
    pub name: String,
    pub tolerance_m: f64,
    pub placement: Option<Placement>,
    /// The closest approach of the tip to the displaced centre over the run, m.
    pub closest_m: f64,
    /// Its sub-score $a_i$.
    pub score: f64,
}

/// The tissue strain metrics (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Default)]
pub struct StrainResult {
    /// Strain samples taken (0: not computed: 3D, or a live session).
    pub strain_samples: u64,
    /// $\varepsilon_{max}$, the largest equivalent strain over the tissue and the samples.
    pub peak_strain: f64,
    /// When it peaked, s.
    pub peak_strain_t_s: f64,
    /// $\max_j A_{d,j}$, m².
    pub damaged_area_m2: f64,
    /// When the damaged area peaked, s.
    pub damaged_area_t_s: f64,
    /// Strain samples above the threshold.
    pub samples_above: u64,
    /// The threshold $\varepsilon_d$.
    pub damage_strain: f64,
}

/// A structure's result.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StructureResult {
    pub name: String,
    /// $c_j$, m (`null` in JSON when the needle never entered the tissue).
    pub min_clearance_m: Option<f64>,
    /// $\delta_j$, m.
    pub intrusion_depth_m: f64,
    pub touched: bool,
    pub touching_samples: u64,
    pub margin_m: f64,
}

/// The sub-scores, each in [0, 1].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SubScores {
    pub accuracy: f64,
    pub efficiency: f64,
    pub path: f64,
    pub force: f64,
    pub safety: f64,
    pub time: f64,
}

/// The score at a moment: sub-scores, the limits exceeded, the total (module docs).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Score {
    pub sub: SubScores,
    pub time_exceeded: bool,
    pub reinsertions_exceeded: bool,
    pub peak_force_exceeded: bool,
    pub penalty: f64,
    /// $S \in [0, 100]$.
    pub total: f64,
}

/// Every metric (module docs).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Metrics {
    pub samples: u64,
    pub time_s: f64,
    pub insertions: u32,
    pub reinsertions: u32,
    pub redirections: u32,
    pub path_length_m: f64,
    pub peak_axial_force_n: f64,
    pub mean_axial_force_n: f64,
    pub max_depth_m: f64,
    pub targets: Vec<TargetResult>,
    pub structures: Vec<StructureResult>,
    /// Tissue strain (module docs); `strain_samples == 0`: not computed.
    pub strain: StrainResult,
    /// Declarations of "placed" refused because every target was placed.
    pub extra_placements: u32,
}

/// The final result of an exercise.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ExerciseResult {
    pub metrics: Metrics,
    pub score: Score,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Phase {
    Out,
    Advancing { peak_m: f64 },
    Withdrawing { trough_m: f64 },
}

#[derive(Debug, Clone, Copy)]
struct StructState {
    min_clearance_m: f64,
    touching: u64,
}

/// The incremental metrics (module docs). `push` allocates nothing.
#[derive(Debug, Clone)]
pub struct MetricsTracker {
    spec: TrackerSpec,
    samples: u64,
    t_first_s: f64,
    last: Option<Sample>,
    phase: Phase,
    entry_m: [f64; 3],
    depth_m: f64,
    insertions: u32,
    redirections: u32,
    path_m: f64,
    peak_force_n: f64,
    sum_force_n: f64,
    in_tissue_samples: u64,
    max_depth_m: f64,
    structs: Vec<StructState>,
    placements: Vec<Option<Placement>>,
    closest_m: Vec<f64>,
    extra_placements: u32,
    strain: StrainResult,
}

impl MetricsTracker {
    pub fn new(spec: TrackerSpec) -> Self {
        let n = spec.targets.len();
        Self {
            structs: vec![StructState { min_clearance_m: f64::INFINITY, touching: 0 }; spec.structures.len()],
            placements: vec![None; n],
            closest_m: vec![f64::INFINITY; n],
            spec,
            samples: 0,
            t_first_s: 0.0,
            last: None,
            phase: Phase::Out,
            entry_m: [0.0; 3],
            depth_m: 0.0,
            insertions: 0,
            redirections: 0,
            path_m: 0.0,
            peak_force_n: 0.0,
            sum_force_n: 0.0,
            in_tissue_samples: 0,
            max_depth_m: 0.0,
            extra_placements: 0,
            strain: StrainResult::default(),
        }
    }

    pub fn spec(&self) -> &TrackerSpec {
        &self.spec
    }

    /// The depth $d_k$ of the last sample (0 outside the tissue), m.
    pub fn depth_m(&self) -> f64 {
        self.depth_m
    }

    /// Whether the last sample was in the tissue.
    pub fn in_tissue(&self) -> bool {
        self.phase != Phase::Out
    }

    /// Takes one tick's sample (module docs for what each metric does with it).
    pub fn push(&mut self, s: &Sample) {
        if self.samples == 0 {
            self.t_first_s = s.t_s;
        }
        self.samples += 1;
        let inside = s.contacts > 0;
        let was_inside = self.phase != Phase::Out;
        let w = self.spec.redirect_threshold_m;
        if inside && !was_inside {
            self.entry_m = s.tip_m;
        }
        let e = self.entry_m;
        let d = if inside { (0..3).map(|i| (s.tip_m[i] - e[i]) * s.axis[i]).sum::<f64>() } else { 0.0 };
        self.depth_m = d;
        self.phase = match (inside, self.phase) {
            (false, _) => Phase::Out,
            (true, Phase::Out) => {
                self.insertions += 1;
                Phase::Advancing { peak_m: d }
            }
            (true, Phase::Advancing { peak_m }) => {
                if d < peak_m - w {
                    Phase::Withdrawing { trough_m: d }
                } else {
                    Phase::Advancing { peak_m: peak_m.max(d) }
                }
            }
            (true, Phase::Withdrawing { trough_m }) => {
                if d > trough_m + w {
                    self.redirections += 1;
                    Phase::Advancing { peak_m: d }
                } else {
                    Phase::Withdrawing { trough_m: trough_m.min(d) }
                }
            }
        };
        if inside {
            if was_inside && let Some(p) = &self.last {
                self.path_m += dist3(s.tip_m, p.tip_m);
            }
            self.in_tissue_samples += 1;
            self.sum_force_n += s.axial_force_n.abs();
            self.max_depth_m = self.max_depth_m.max(d);
            for (st, structure) in self.structs.iter_mut().zip(&self.spec.structures) {
                let (c, _) = structure.shape.segment_clearance(s.tip_m, s.axis, d.max(0.0), self.spec.dims);
                st.min_clearance_m = st.min_clearance_m.min(c);
                if c <= 0.0 {
                    st.touching += 1;
                }
            }
        }
        self.peak_force_n = self.peak_force_n.max(s.axial_force_n.abs());
        for (c, t) in self.closest_m.iter_mut().zip(&self.spec.targets) {
            if let Some(st) = s.targets().get(t.sample_idx) {
                *c = c.min(st.distance_m);
            }
        }
        self.last = Some(*s);
    }

    /// Takes a strain sample at time `t_s` ([`crate::strain::StrainField::evaluate`]).
    pub fn push_strain(&mut self, t_s: f64, s: &crate::strain::StrainSummary) {
        let r = &mut self.strain;
        if r.strain_samples == 0 || s.max_strain > r.peak_strain {
            r.peak_strain = s.max_strain;
            r.peak_strain_t_s = t_s;
        }
        if r.strain_samples == 0 || s.area_above_m2 > r.damaged_area_m2 {
            r.damaged_area_m2 = s.area_above_m2;
            r.damaged_area_t_s = t_s;
        }
        r.strain_samples += 1;
        r.samples_above += (s.area_above_m2 > 0.0) as u64;
        r.damage_strain = s.damage_strain;
    }

    /// Declares "placed" at the last sample: the nearest target not yet placed is placed
    /// (module docs). Returns its index in the spec's targets and the placement.
    pub fn place(&mut self) -> Result<(usize, Placement), PlaceError> {
        let s = self.last.ok_or(PlaceError::NoSample)?;
        let mut best: Option<(usize, f64, [f64; 3])> = None;
        for (i, t) in self.spec.targets.iter().enumerate() {
            if self.placements[i].is_some() {
                continue;
            }
            let st = s.targets().get(t.sample_idx).ok_or_else(|| PlaceError::MissingTarget {
                name: t.name.clone(),
                idx: t.sample_idx,
                have: s.targets().len(),
            })?;
            let e = dist3(s.tip_m, st.centre_m);
            if best.is_none_or(|b| e < b.1) {
                best = Some((i, e, st.centre_m));
            }
        }
        let Some((i, e, c)) = best else {
            self.extra_placements += 1;
            return Err(PlaceError::AllPlaced(self.spec.targets.len()));
        };
        let p = Placement {
            t_s: s.t_s,
            error_m: e,
            on_target: e <= self.spec.targets[i].tolerance_m,
            depth_m: self.depth_m,
            tip_m: s.tip_m,
            centre_m: c,
        };
        self.placements[i] = Some(p);
        Ok((i, p))
    }

    fn time_s(&self) -> f64 {
        self.last.map_or(0.0, |l| l.t_s - self.t_first_s)
    }

    fn target_score(&self, i: usize) -> f64 {
        let tol = self.spec.targets[i].tolerance_m;
        match self.placements[i] {
            None => 0.0,
            Some(p) if p.error_m <= tol => 1.0,
            Some(p) => (1.0 - (p.error_m - tol) / (2.0 * tol)).max(0.0),
        }
    }

    /// The score so far (module docs).
    pub fn score(&self) -> Score {
        let n = self.spec.targets.len();
        let accuracy = if n == 0 { 1.0 } else { (0..n).map(|i| self.target_score(i)).sum::<f64>() / n as f64 };
        let reinsertions = self.insertions.saturating_sub(1);
        let efficiency = 1.0 / (1.0 + reinsertions as f64 + self.redirections as f64);
        let deepest = self.placements.iter().flatten().map(|p| p.depth_m).fold(0.0, f64::max);
        let path = if self.path_m > 0.0 { (deepest / self.path_m).min(1.0) } else { 0.0 };
        let l = &self.spec.limits;
        let mean = self.mean_force_n();
        let force = (1.0 - mean / l.peak_force_n).clamp(0.0, 1.0);
        let safety = self
            .structs
            .iter()
            .zip(&self.spec.structures)
            .map(|(st, s)| (st.min_clearance_m / s.margin_m).clamp(0.0, 1.0))
            .fold(1.0, f64::min);
        let t = self.time_s();
        let time = (2.0 * (1.0 - t / l.time_s)).clamp(0.0, 1.0);
        let sub = SubScores { accuracy, efficiency, path, force, safety, time };
        let w = &self.spec.weights;
        let wsum = w.accuracy + w.efficiency + w.path + w.force + w.safety + w.time;
        let weighted =
            (w.accuracy * accuracy + w.efficiency * efficiency + w.path * path + w.force * force + w.safety * safety + w.time * time)
                / wsum;
        let time_exceeded = t > l.time_s;
        let reinsertions_exceeded = reinsertions > l.reinsertions;
        let peak_force_exceeded = self.peak_force_n > l.peak_force_n;
        let penalty = l.penalty * (time_exceeded as u8 + reinsertions_exceeded as u8 + peak_force_exceeded as u8) as f64;
        Score {
            sub,
            time_exceeded,
            reinsertions_exceeded,
            peak_force_exceeded,
            penalty,
            total: (100.0 * weighted - penalty).clamp(0.0, 100.0),
        }
    }

    fn mean_force_n(&self) -> f64 {
        if self.in_tissue_samples == 0 { 0.0 } else { self.sum_force_n / self.in_tissue_samples as f64 }
    }

    /// Every metric so far.
    pub fn metrics(&self) -> Metrics {
        Metrics {
            samples: self.samples,
            time_s: self.time_s(),
            insertions: self.insertions,
            reinsertions: self.insertions.saturating_sub(1),
            redirections: self.redirections,
            path_length_m: self.path_m,
            peak_axial_force_n: self.peak_force_n,
            mean_axial_force_n: self.mean_force_n(),
            max_depth_m: self.max_depth_m,
            targets: self
                .spec
                .targets
                .iter()
                .enumerate()
                .map(|(i, t)| TargetResult {
                    name: t.name.clone(),
                    tolerance_m: t.tolerance_m,
                    placement: self.placements[i],
                    closest_m: self.closest_m[i],
                    score: self.target_score(i),
                })
                .collect(),
            structures: self
                .structs
                .iter()
                .zip(&self.spec.structures)
                .map(|(st, s)| StructureResult {
                    name: s.name.clone(),
                    min_clearance_m: st.min_clearance_m.is_finite().then_some(st.min_clearance_m),
                    intrusion_depth_m: (-st.min_clearance_m).max(0.0),
                    touched: st.min_clearance_m <= 0.0,
                    touching_samples: st.touching,
                    margin_m: s.margin_m,
                })
                .collect(),
            extra_placements: self.extra_placements,
            strain: self.strain,
        }
    }

    /// The final result.
    pub fn finish(self) -> ExerciseResult {
        ExerciseResult { metrics: self.metrics(), score: self.score() }
    }
}

/// One point of a [`Trace`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TracePoint {
    pub t_s: f64,
    pub depth_m: f64,
    pub axial_force_n: f64,
    pub tip_m: [f64; 3],
}

/// The curves of the after-action report in bounded memory: every `stride`-th sample, at most
/// `capacity` points; when full, every other point is dropped and the stride doubles (so the
/// kept points stay evenly spaced in ticks). The last sample is always kept apart.
#[derive(Debug, Clone)]
pub struct Trace {
    capacity: usize,
    stride: u64,
    seen: u64,
    points: Vec<TracePoint>,
    last: Option<TracePoint>,
}

impl Trace {
    /// `capacity` ≥ 2.
    pub fn new(capacity: usize) -> Self {
        let capacity = capacity.max(2);
        Self { capacity, stride: 1, seen: 0, points: Vec::with_capacity(capacity), last: None }
    }

    /// Takes a sample with its depth (the tracker's [`MetricsTracker::depth_m`], 0 outside).
    pub fn push(&mut self, s: &Sample, depth_m: f64) {
        let p = TracePoint { t_s: s.t_s, depth_m, axial_force_n: s.axial_force_n, tip_m: s.tip_m };
        if self.seen.is_multiple_of(self.stride) {
            if self.points.len() == self.capacity {
                let mut k = 0;
                self.points.retain(|_| {
                    k += 1;
                    (k - 1) % 2 == 0
                });
                self.stride *= 2;
            }
            if self.seen.is_multiple_of(self.stride) {
                self.points.push(p);
            }
        }
        self.seen += 1;
        self.last = Some(p);
    }

    /// The kept points, and the last sample if it was not kept.
    pub fn points(&self) -> Vec<TracePoint> {
        let mut v = self.points.clone();
        if let Some(l) = self.last
            && v.last() != Some(&l)
        {
            v.push(l);
        }
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exercise::Weights;
    use crate::geometry::Shape;

    fn spec(structures: Vec<Structure>) -> TrackerSpec {
        TrackerSpec {
            dims: 3,
            targets: vec![
                TrackedTarget { name: "a".into(), sample_idx: 0, tolerance_m: 0.002 },
                TrackedTarget { name: "b".into(), sample_idx: 1, tolerance_m: 0.002 },
            ],
            structures,
            limits: Limits { time_s: 10.0, reinsertions: 0, peak_force_n: 2.0, penalty: 10.0 },
            weights: Weights { accuracy: 1.0, efficiency: 1.0, path: 1.0, force: 1.0, safety: 1.0, time: 1.0 },
            redirect_threshold_m: 0.005,
        }
    }

    /// A needle along +x entering the tissue at x = 0: depth d, tip at (d, 0, 0).
    fn sample(t: f64, d: f64, f: f64) -> Sample {
        let mut s = Sample::new(t, [d, 0.0, 0.0], [1.0, 0.0, 0.0], d.max(0.0), (d >= 0.0) as u32, f);
        s.push_target([0.03, 0.001, 0.0]);
        s.push_target([0.05, 0.0, 0.0]);
        s
    }

    #[test]
    fn counts_insertions_redirections_path_and_forces_by_the_definitions() {
        let sphere =
            Structure { name: "v".into(), shape: Shape::Sphere { centre_m: [0.02, 0.004, 0.0], radius_m: 0.003 }, margin_m: 0.002 };
        let mut m = MetricsTracker::new(spec(vec![sphere]));
        // depths (mm): out, in to 20, back to 14 (6 mm withdrawal: withdrawing), forward to 20
        // (6 mm re-advance: one redirection), back 4 mm and forward (no), out, in again to 10.
        let depths_mm = [-1.0, 0.0, 5.0, 10.0, 20.0, 14.0, 17.0, 20.0, 16.0, 20.0, 0.0, -2.0, 3.0, 10.0];
        let forces = [0.0, 0.0, 0.5, 1.0, 1.5, -0.5, 0.5, 2.5, -0.2, 0.4, 0.0, 0.0, 0.3, 0.6];
        for (k, (&d, &f)) in depths_mm.iter().zip(&forces).enumerate() {
            m.push(&sample(k as f64 * 0.5, d * 1e-3, f));
        }
        let r = m.metrics();
        assert_eq!((r.insertions, r.reinsertions, r.redirections), (2, 1, 1));
        // In tissue (d >= 0): 0,5,10,20,14,17,20,16,20,0 (entry at 0), then 3,10 (entry at 3).
        // Path: 5+5+10+6+3+3+4+4+20 = 60 mm, then 7 mm.
        assert!((r.path_length_m - 0.067).abs() < 1e-15, "{}", r.path_length_m);
        assert!((r.max_depth_m - 0.020).abs() < 1e-15);
        assert_eq!(r.peak_axial_force_n, 2.5);
        let mean = (0.5 + 1.0 + 1.5 + 0.5 + 0.5 + 2.5 + 0.2 + 0.4 + 0.3 + 0.6) / 12.0;
        assert!((r.mean_axial_force_n - mean).abs() < 1e-15);
        assert_eq!(r.time_s, 6.5);
        // The sphere (centre (20, 4) mm, r 3 mm): the shaft along y = 0 passes 4 mm from the centre: clearance 1 mm.
        let s = &r.structures[0];
        assert!((s.min_clearance_m.unwrap() - 0.001).abs() < 1e-15 && !s.touched && s.intrusion_depth_m == 0.0);
        let sc = m.score();
        assert!(sc.reinsertions_exceeded && sc.peak_force_exceeded && !sc.time_exceeded);
        assert_eq!(sc.penalty, 20.0);
        assert!((sc.sub.safety - 0.5).abs() < 1e-12 && (sc.sub.efficiency - 1.0 / 3.0).abs() < 1e-15 && sc.sub.accuracy == 0.0);
    }

    #[test]
    fn placement_takes_the_nearest_unplaced_target_and_scores_it() {
        let mut m = MetricsTracker::new(spec(vec![]));
        assert_eq!(m.place().unwrap_err(), PlaceError::NoSample);
        for k in 0..=31 {
            m.push(&sample(k as f64 * 0.1, k as f64 * 1e-3, 0.5));
        }
        // Tip at 31 mm: target a at (30, 1) mm is 1.414 mm away (on target, tolerance 2 mm).
        let (i, p) = m.place().unwrap();
        assert_eq!(i, 0);
        assert!((p.error_m - 2f64.sqrt() * 1e-3).abs() < 1e-15 && p.on_target);
        for k in 32..=55 {
            m.push(&sample(k as f64 * 0.1, k as f64 * 1e-3, 0.5));
        }
        // Tip at 55 mm: b at 50 mm is 5 mm away: a = 1 - (5 - 2)/4 = 0.25.
        let (i, p) = m.place().unwrap();
        assert_eq!(i, 1);
        assert!(!p.on_target);
        assert_eq!(m.place().unwrap_err(), PlaceError::AllPlaced(2));
        let r = m.finish();
        assert!((r.score.sub.accuracy - (1.0 + 0.25) / 2.0).abs() < 1e-12);
        // Path 55 mm, deepest placement 55 mm.
        assert!((r.score.sub.path - 1.0).abs() < 1e-12);
        assert_eq!(r.metrics.extra_placements, 1);
    }

    #[test]
    fn the_trace_is_bounded_and_evenly_strided() {
        let mut t = Trace::new(8);
        for k in 0..100 {
            t.push(&sample(k as f64, 0.0, 0.0), 0.0);
        }
        let p = t.points();
        assert!(p.len() <= 9);
        let times: Vec<f64> = p.iter().map(|p| p.t_s).collect();
        let step = times[1] - times[0];
        assert!(times.windows(2).take(p.len() - 2).all(|w| w[1] - w[0] == step), "{times:?}");
        assert_eq!(*times.last().unwrap(), 99.0);
    }
}
