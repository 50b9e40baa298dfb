//! The live ultrasound slice of an exercise session (issue 20): one renderer thread per session,
//! started by the first watcher and stopped when the last one leaves, renders the latest tick
//! record with needlesim-training's `ultrasound` at the highest rate any watcher asked for and
//! publishes the image on a latest-value channel every watcher reads — so the cost does not grow
//! with the number of observers, and nothing of it runs on the real-time thread (the renderer
//! reads the session's latest record and, in 2D, the displacement field the fan-out computes for
//! field subscribers, which it is while it runs).
//!
//! 2D: the slice is the tissue plane, the probe a window in it (by default the mesh's bounding
//! box, depth pointing −y). 3D: a plane through the tissue (by default through the initial needle
//! base, spanned by the needle's horizontal direction and −z, so the needle lies in it), drawn
//! deformed: the session computes no interior displacement field (see the module docs of
//! `needlesim_session::surface`), so the renderer solves for it itself, once per image, from the
//! record's contact points (reference position $X_i$, force $f_i$ of the needle on the tissue;
//! at most `MAX_RECORD_CONTACTS3` of them):
//! $$u = K_{ff}^{-1} \sum_i \sum_a N_a(X_i)\, e_{k_a} \otimes f_i$$
//! with the tissue model's factorisation (`needlesim_training::ultrasound::DeformedTissue3`: one
//! sparse solve, $O(\mathrm{nnz}(L))$, whatever the number of contacts). The model is immutable
//! and shared (`Arc`): the solve takes no lock, so the real-time thread never waits on it.
//! Cost per image on the cube-phantom-3d tissue (48,000 tetrahedra, $\mathrm{nnz}(L)$ = 16.6 M):
//! the solve, memory-bound (it reads $L$ twice): 22–40 ms at load 3.5–5, 52 ms p50 at load 6.6,
//! plus the rasterisation, 15 ms — BENCHMARKS.md, "3D ultrasound slice of the deformed tissue"
//! (`slice_cost` in needlesim-training measures both). The solve is
//! therefore rationed: none when the contacts (positions and forces) are those of the field
//! solved last (a held needle, a moved probe), and at most [`SOLVE_DUTY_MAX`] of the thread's time
//! (after a solve of $T$, the next waits until $T/$`SOLVE_DUTY_MAX` after it began); an image in
//! between draws the record's needle over the last solved tissue, and the renderer comes back
//! for the record's field even when no new record arrives. The renderer thread runs at a lowered
//! priority (nice [`RENDER_THREAD_NICE`], like the surface field's thread): the picture may lag,
//! the compliance worker a capture waits for must not. Whatever the mesh, the renderer takes at
//! most [`RENDER_DUTY_MAX`] of a core (after an image that took $T$ the next waits until
//! $T/$`RENDER_DUTY_MAX` after it began): a 2D slice keeps up to 30 Hz, a large 3D one slows to
//! what that share allows. Measured quiet on 2 cores, biopsy-3d with 10 observers for 20 s: at
//! ~21 Hz without the bound the slice cost 41 missed ticks against 9 without observers; with it
//! (6.7 Hz) 15 against 11.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use needlesim_session::{Session, SessionTissue, TickRecord};
use needlesim_training::ultrasound::{
    DeformedTissue3, Probe, Probe3, SliceScene, SliceScene3, UltrasoundScratch, render_slice, render_slice_3d,
};
use tokio::sync::watch;

/// Largest image side, pixels.
pub const MAX_PROBE_PIXELS: u32 = 512;
/// Smallest image side, pixels.
pub const MIN_PROBE_PIXELS: u32 = 8;
/// The renderer's rate when no watcher asked for one, and the bounds of a request, Hz.
pub const DEFAULT_RATE_HZ: f64 = 10.0;
pub const MAX_RATE_HZ: f64 = 30.0;
/// The largest share of a core the renderer thread takes: after an image that took $T$, the next
/// starts no sooner than $T /$ `RENDER_DUTY_MAX` after it began. A 2D slice (≈ 7 ms) keeps the
/// asked-for rate up to 30 Hz; a 3D slice of a large mesh (15–70 ms with its solve) drops to
/// about 5–10 Hz instead of taking the core the real-time thread's neighbours need.
pub const RENDER_DUTY_MAX: f64 = 0.4;

/// The renderer thread's nice value (the session's worker and fan-out keep 0).
pub const RENDER_THREAD_NICE: i32 = 10;

/// Echogenicity by region index (cycled).
const REGION_GAIN: [f64; 6] = [0.6, 0.9, 0.45, 0.75, 0.55, 0.85];
/// Speckle lattice cell, m.
const SPECKLE_M: f64 = 3e-4;
const SEED: u64 = 20;

/// The probe of a session, of its dimension.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ProbeSpec {
    Two(Probe),
    Three(Probe3),
}

/// One rendered slice.
#[derive(Debug, Clone)]
pub struct SliceImage {
    pub tick: u64,
    pub width: usize,
    pub height: usize,
    pub gray8: Vec<u8>,
    pub probe: ProbeSpec,
    /// The image's cost on the renderer thread, µs: in 3D the displacement solve (when the tick is
    /// new) and the rasterisation.
    pub render_us: f64,
}

/// A probe refused, naming the field.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("probe.{field}: {message}")]
pub struct ProbeError {
    pub field: &'static str,
    pub message: String,
}

/// The renderer state shared by the watchers of one session.
pub struct UltrasoundHub {
    probe: Mutex<ProbeSpec>,
    /// Targets drawn (reference centre, radius), world, m (z = 0 in 2D).
    targets: Vec<([f64; 3], f64)>,
    watchers: AtomicUsize,
    /// The highest rate asked for by a current watcher (bits of an f64), and whether the
    /// renderer thread runs — under one lock, so that no watcher is left without a renderer.
    run: Mutex<(bool, f64)>,
    tx: watch::Sender<Option<Arc<SliceImage>>>,
    /// Images rendered since the session started.
    pub renders: std::sync::atomic::AtomicU64,
}

/// The largest share of the renderer thread's time the 3D displacement solves may take: after a
/// solve that took $T$, the next one starts no sooner than $T / $ `SOLVE_DUTY_MAX` after it began
/// (images in between draw the latest needle over the last solved tissue).
pub const SOLVE_DUTY_MAX: f64 = 0.25;

/// A contact as the solve sees it: reference position (m), force on the tissue (N).
type SolveContact = ([f64; 3], [f64; 3]);

/// What the renderer does with a record's contacts in 3D.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum SolveDecision {
    /// The same contacts (positions and forces, bit for bit) as the field solved last: no solve.
    Same,
    /// New contacts, but the last solve's duty cycle has not elapsed: keep the last field for now.
    Wait,
    /// Solve.
    Solve,
}

/// When the 3D renderer solves (module docs): not for unchanged contacts, and within
/// [`SOLVE_DUTY_MAX`] of the thread's time.
#[derive(Debug, Default)]
struct SolveGate {
    /// The contacts of the field solved last.
    contacts: Vec<SolveContact>,
    /// When the last solve began, and how long it took.
    last: Option<(Instant, Duration)>,
}

impl SolveGate {
    fn decide(&self, contacts: &[SolveContact], now: Instant) -> SolveDecision {
        if self.last.is_some() && self.contacts == contacts {
            return SolveDecision::Same;
        }
        match self.last {
            Some((began, took)) if now < began + took.div_f64(SOLVE_DUTY_MAX) => SolveDecision::Wait,
            _ => SolveDecision::Solve,
        }
    }

    fn solved(&mut self, contacts: &[SolveContact], began: Instant, took: Duration) {
        self.contacts.clear();
        self.contacts.extend_from_slice(contacts);
        self.last = Some((began, took));
    }
}

/// The renderer thread's buffers, reused image after image.
#[derive(Default)]
struct RenderBuffers {
    scratch: UltrasoundScratch,
    u2: Vec<[f64; 2]>,
    /// 3D: the displacement solver (made at the first 3D image), the record's contacts, and when
    /// to solve.
    deformed: Option<DeformedTissue3>,
    contacts: Vec<SolveContact>,
    gate: SolveGate,
    /// 3D: the image drew an older field than its record's (the solve waits): render again.
    field_behind: bool,
    /// 3D: solves that failed (logged at counts 1, 2, 4, …; the slice is then drawn undeformed).
    solve_errors: u64,
}

/// A watcher's registration: leaving drops it.
pub struct Watching {
    hub: Arc<UltrasoundHub>,
}

impl Drop for Watching {
    fn drop(&mut self) {
        self.hub.watchers.fetch_sub(1, Ordering::AcqRel);
    }
}

fn unit3(v: [f64; 3]) -> [f64; 3] {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if n > 0.0 { [v[0] / n, v[1] / n, v[2] / n] } else { v }
}
fn dot3(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The default 2D probe: the mesh's bounding box, 200 pixels wide, depth along −y.
pub fn default_probe_2d(bbox: ([f64; 2], [f64; 2])) -> Probe {
    let ([x0, y0], [x1, y1]) = bbox;
    let width = 200usize;
    let pixel_m = ((x1 - x0) / width as f64).max(1e-6);
    let height = (((y1 - y0) / pixel_m).ceil() as usize).clamp(MIN_PROBE_PIXELS as usize, MAX_PROBE_PIXELS as usize);
    Probe { origin_m: [x0, y1], e_u: [1.0, 0.0], e_v: [0.0, -1.0], pixel_m, width, height }
}

/// The default 3D probe: the plane through `base_m` spanned by the horizontal part of `axis`
/// (x when the needle is vertical) and −z, covering the nodes' extent in it, 200 pixels wide.
pub fn default_probe_3d(nodes_m: &[[f64; 3]], base_m: [f64; 3], axis: [f64; 3]) -> Probe3 {
    let h = [axis[0], axis[1], 0.0];
    let e_u = if (h[0] * h[0] + h[1] * h[1]).sqrt() > 1e-6 { unit3(h) } else { [1.0, 0.0, 0.0] };
    let e_v = [0.0, 0.0, -1.0];
    let (mut u0, mut u1, mut v0, mut v1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for &p in nodes_m {
        let d = [p[0] - base_m[0], p[1] - base_m[1], p[2] - base_m[2]];
        let (u, v) = (dot3(d, e_u), dot3(d, e_v));
        u0 = u0.min(u);
        u1 = u1.max(u);
        v0 = v0.min(v);
        v1 = v1.max(v);
    }
    if !u0.is_finite() {
        (u0, u1, v0, v1) = (-0.05, 0.05, -0.05, 0.05);
    }
    // The tissue and the needle base above it.
    v0 = v0.min(0.0);
    let width = 200usize;
    let pixel_m = ((u1 - u0) / width as f64).max(1e-6);
    let height = (((v1 - v0) / pixel_m).ceil() as usize).clamp(MIN_PROBE_PIXELS as usize, MAX_PROBE_PIXELS as usize);
    let origin_m = [base_m[0] + u0 * e_u[0] + v0 * e_v[0], base_m[1] + u0 * e_u[1] + v0 * e_v[1], base_m[2] + u0 * e_u[2] + v0 * e_v[2]];
    Probe3 { origin_m, e_u, e_v, pixel_m, width, height, thickness_m: 2e-3 }
}

/// Checks a probe from a client (module docs of `training.proto`): finite, `pixel_m` in
/// (1 µm, 1 cm], sides in [`MIN_PROBE_PIXELS`]..=[`MAX_PROBE_PIXELS`], `e_u` and `e_v` unit
/// (±1e-3) and orthogonal (±1e-3) — then made exactly orthonormal —, in 2D in the plane.
#[allow(clippy::too_many_arguments)]
pub fn checked_probe(
    dim: u8,
    origin_m: [f64; 3],
    e_u: [f64; 3],
    e_v: [f64; 3],
    pixel_m: f64,
    width: u32,
    height: u32,
    thickness_m: f64,
) -> Result<ProbeSpec, ProbeError> {
    let bad = |field: &'static str, message: String| Err(ProbeError { field, message });
    if let Some(x) = origin_m.iter().find(|x| !x.is_finite() || x.abs() > 1e3) {
        return bad("origin_m", format!("{} must be finite and within ±1e3 m", needlesim_core::num::num(*x)));
    }
    if !(pixel_m.is_finite() && pixel_m > 1e-6 && pixel_m <= 1e-2) {
        return bad("pixel_m", format!("{} must be in (1e-6, 1e-2] m", needlesim_core::num::num(pixel_m)));
    }
    for (field, v) in [("width", width), ("height", height)] {
        if !(MIN_PROBE_PIXELS..=MAX_PROBE_PIXELS).contains(&v) {
            return bad(field, format!("{v} must be in {MIN_PROBE_PIXELS}..={MAX_PROBE_PIXELS} pixels"));
        }
    }
    let mut e_u = e_u;
    let mut e_v = e_v;
    if dim == 2 {
        e_u[2] = 0.0;
        e_v[2] = 0.0;
    }
    for (field, v) in [("e_u", e_u), ("e_v", e_v)] {
        let n = dot3(v, v).sqrt();
        if !n.is_finite() || (n - 1.0).abs() > 1e-3 {
            return bad(
                field,
                format!("length {}: must be a unit vector{}", needlesim_core::num::num(n), if dim == 2 { " in the x–y plane" } else { "" }),
            );
        }
    }
    if dot3(e_u, e_v).abs() > 1e-3 {
        return bad("e_v", format!("e_u · e_v = {}: must be orthogonal to e_u", needlesim_core::num::num(dot3(e_u, e_v))));
    }
    e_u = unit3(e_u);
    let c = dot3(e_u, e_v);
    e_v = unit3([e_v[0] - c * e_u[0], e_v[1] - c * e_u[1], e_v[2] - c * e_u[2]]);
    let (width, height) = (width as usize, height as usize);
    if dim == 2 {
        return Ok(ProbeSpec::Two(Probe {
            origin_m: [origin_m[0], origin_m[1]],
            e_u: [e_u[0], e_u[1]],
            e_v: [e_v[0], e_v[1]],
            pixel_m,
            width,
            height,
        }));
    }
    if !(thickness_m.is_finite() && thickness_m > 0.0 && thickness_m <= 0.05) {
        return bad("thickness_m", format!("{} must be in (0, 0.05] m", needlesim_core::num::num(thickness_m)));
    }
    Ok(ProbeSpec::Three(Probe3 { origin_m, e_u, e_v, pixel_m, width, height, thickness_m }))
}

impl UltrasoundHub {
    pub fn new(probe: ProbeSpec, targets: Vec<([f64; 3], f64)>) -> Arc<Self> {
        Arc::new(Self {
            probe: Mutex::new(probe),
            targets,
            watchers: AtomicUsize::new(0),
            run: Mutex::new((false, DEFAULT_RATE_HZ)),
            tx: watch::channel(None).0,
            renders: Default::default(),
        })
    }

    pub fn probe(&self) -> ProbeSpec {
        *self.probe.lock().expect("probe lock")
    }

    /// Moves the probe (the next image uses it).
    pub fn set_probe(&self, p: ProbeSpec) {
        *self.probe.lock().expect("probe lock") = p;
    }

    /// Registers a watcher at `rate_hz` (clamped to 1..[`MAX_RATE_HZ`]) and starts the renderer if
    /// it is not running; `closed` tells the renderer the session closed.
    pub fn watch(
        self: &Arc<Self>,
        session: Arc<Session>,
        closed: Arc<dyn Fn() -> bool + Send + Sync>,
        rate_hz: f64,
    ) -> std::io::Result<(watch::Receiver<Option<Arc<SliceImage>>>, Watching)> {
        let rate = rate_hz.clamp(1.0, MAX_RATE_HZ);
        self.watchers.fetch_add(1, Ordering::AcqRel);
        let w = Watching { hub: self.clone() };
        let rx = self.tx.subscribe();
        let mut run = self.run.lock().expect("renderer lock");
        if !run.0 {
            run.1 = rate;
            let hub = self.clone();
            std::thread::Builder::new().name(format!("us-{}", session.id)).spawn(move || hub.render_loop(session, closed))?;
            run.0 = true;
        } else {
            run.1 = run.1.max(rate);
        }
        Ok((rx, w))
    }

    fn render_loop(self: Arc<Self>, s: Arc<Session>, closed: Arc<dyn Fn() -> bool + Send + Sync>) {
        let two = matches!(s.tissue, SessionTissue::Two(_));
        if two {
            s.field_subscribers.fetch_add(1, Ordering::AcqRel);
        }
        // A refusal (not Linux, or the OS says no) only costs that preference.
        let _ = needlesim_channel::rt::lower_thread_priority(RENDER_THREAD_NICE);
        let mut buffers = RenderBuffers::default();
        let mut last: Option<(u64, ProbeSpec)> = None;
        let mut next = Instant::now();
        // No image before this instant (RENDER_DUTY_MAX).
        let mut earliest = Instant::now();
        loop {
            let period = {
                let mut run = self.run.lock().expect("renderer lock");
                if self.watchers.load(Ordering::Acquire) == 0 || closed() || s.is_closed() {
                    *run = (false, DEFAULT_RATE_HZ);
                    break;
                }
                Duration::from_secs_f64(1.0 / run.1)
            };
            let rec = s.latest_record();
            let probe = self.probe();
            if last != Some((rec.tick, probe)) {
                last = Some((rec.tick, probe));
                let t0 = Instant::now();
                let img = self.render(&s, &rec, probe, &mut buffers);
                let took = t0.elapsed();
                earliest = t0 + took.div_f64(RENDER_DUTY_MAX);
                let render_us = took.as_secs_f64() * 1e6;
                if let Some((width, height, gray8)) = img {
                    self.renders.fetch_add(1, Ordering::Relaxed);
                    self.tx.send_replace(Some(Arc::new(SliceImage { tick: rec.tick, width, height, gray8, probe, render_us })));
                }
                if buffers.field_behind {
                    // The record's field is still to come (a held needle brings no new record).
                    last = None;
                }
            }
            next = (next + period).max(earliest);
            let now = Instant::now();
            if next > now {
                std::thread::sleep(next - now);
            } else {
                next = now;
            }
        }
        if two {
            s.field_subscribers.fetch_sub(1, Ordering::AcqRel);
        }
    }

    /// Renders `rec` through `probe`; `None` when the probe's dimension is not the session's.
    fn render(&self, s: &Session, rec: &TickRecord, probe: ProbeSpec, buf: &mut RenderBuffers) -> Option<(usize, usize, Vec<u8>)> {
        let RenderBuffers { scratch, u2, deformed, contacts, gate, field_behind, solve_errors } = buf;
        match (&s.tissue, probe) {
            (SessionTissue::Two(t), ProbeSpec::Two(p)) => {
                let mesh = t.mesh();
                let n = mesh.n_nodes();
                let field = s.field.borrow().clone();
                u2.clear();
                if field.displacement_m.len() == 2 * n {
                    u2.extend(field.displacement_m.chunks_exact(2).map(|c| [c[0], c[1]]));
                } else {
                    u2.resize(n, [0.0; 2]);
                }
                let targets: Vec<([f64; 2], f64)> = self.targets.iter().map(|(c, r)| ([c[0], c[1]], *r)).collect();
                let gains: Vec<f64> = (0..mesh.region_names().len().max(1)).map(|i| REGION_GAIN[i % REGION_GAIN.len()]).collect();
                let inside = rec.n_stuck + rec.n_slipping + rec.n_tip > 0;
                let needle = inside.then_some(([rec.base.x_m, rec.base.y_m], rec.tip_m));
                let scene = SliceScene {
                    region_gain: &gains,
                    targets: &targets,
                    needle_m: needle,
                    needle_halfwidth_px: 1.5,
                    speckle_m: SPECKLE_M,
                    seed: SEED,
                };
                let img = render_slice(mesh.nodes_m(), u2, mesh.triangles(), mesh.region_of_tri(), &scene, &p, scratch);
                Some((img.width, img.height, img.pixels))
            }
            (SessionTissue::Three { model, .. }, ProbeSpec::Three(p)) => {
                let mesh = model.mesh();
                let d = &rec.d3;
                let deformed = deformed.get_or_insert_with(|| DeformedTissue3::new(model));
                contacts.clear();
                contacts.extend(d.contacts().iter().map(|c| (c.x_ref_m, c.force_n)));
                let now = Instant::now();
                let decision = gate.decide(contacts, now);
                *field_behind = decision == SolveDecision::Wait;
                if decision == SolveDecision::Solve {
                    let solved = deformed.solve(model, contacts.iter().copied()).map(|_| ());
                    gate.solved(contacts, now, now.elapsed());
                    if let Err(e) = solved {
                        *solve_errors += 1;
                        if solve_errors.is_power_of_two() {
                            tracing::warn!(session = %s.id, errors = *solve_errors, "ultrasound: the tissue's displacement at tick {}: {e}; drawn undeformed", rec.tick);
                        }
                    }
                }
                let gains: Vec<f64> = (0..mesh.region_names().len().max(1)).map(|i| REGION_GAIN[i % REGION_GAIN.len()]).collect();
                let needle = (d.n_contacts > 0).then_some((d.position_m, d.tip_m));
                let scene = SliceScene3 {
                    region_gain: &gains,
                    targets: &self.targets,
                    needle_m: needle,
                    needle_halfwidth_px: 1.5,
                    speckle_m: SPECKLE_M,
                    seed: SEED,
                };
                let img =
                    render_slice_3d(mesh.nodes_m(), deformed.displacement_m(), mesh.tets(), mesh.region_of_tet(), &scene, &p, scratch);
                Some((img.width, img.height, img.pixels))
            }
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn probes_are_checked_field_by_field_and_made_orthonormal() {
        let ok = checked_probe(3, [0.0; 3], [1.0, 0.0, 0.0], [0.0, 0.0005, -1.0], 1e-4, 64, 64, 2e-3).unwrap();
        let ProbeSpec::Three(p) = ok else { panic!("a 3D probe") };
        assert!(dot3(p.e_u, p.e_v).abs() < 1e-15 && (dot3(p.e_v, p.e_v) - 1.0).abs() < 1e-15);
        let e = checked_probe(2, [0.0; 3], [1.0, 0.0, 0.0], [0.0, -1.0, 0.0], 0.0, 64, 64, 0.0).unwrap_err();
        assert_eq!(e.field, "pixel_m");
        let e = checked_probe(2, [0.0; 3], [1.0, 0.0, 0.0], [0.0, -1.0, 0.0], 1e-4, 4, 64, 0.0).unwrap_err();
        assert_eq!(e.field, "width");
        let e = checked_probe(2, [0.0; 3], [1.0, 0.0, 0.0], [1.0, 0.0, 0.0], 1e-4, 64, 64, 0.0).unwrap_err();
        assert_eq!(e.field, "e_v");
        // In 2D the z parts are dropped: a vector along z alone has no length in the plane.
        let e = checked_probe(2, [0.0; 3], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0], 1e-4, 64, 64, 0.0).unwrap_err();
        assert_eq!(e.field, "e_u");
        let e = checked_probe(3, [f64::NAN, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0], 1e-4, 64, 64, 2e-3).unwrap_err();
        assert_eq!(e.field, "origin_m");
        let e = checked_probe(3, [0.0; 3], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0], 1e-4, 64, 64, 0.0).unwrap_err();
        assert_eq!(e.field, "thickness_m");
    }

    /// The solve is skipped for unchanged contacts, waits out its duty cycle for new ones, and
    /// runs once it has elapsed (or at the first image).
    #[test]
    fn the_3d_solve_is_rationed_by_unchanged_contacts_and_its_duty_cycle() {
        let t0 = Instant::now();
        let a: Vec<SolveContact> = vec![([0.05, 0.05, 0.09], [0.0, 0.0, -0.02]), ([0.05, 0.05, 0.08], [0.001, 0.0, -0.3])];
        let mut b = a.clone();
        b[1].1[2] = -0.31;
        let mut gate = SolveGate::default();
        assert_eq!(gate.decide(&a, t0), SolveDecision::Solve, "the first image solves");
        assert_eq!(gate.decide(&[], t0), SolveDecision::Solve, "no contacts yet: solve (to zero, without a solve)");
        let took = Duration::from_millis(30);
        gate.solved(&a, t0, took);
        let next = t0 + took.div_f64(SOLVE_DUTY_MAX);
        assert_eq!(gate.decide(&a, t0 + Duration::from_secs(5)), SolveDecision::Same, "unchanged contacts never solve again");
        assert_eq!(gate.decide(&b, t0 + took), SolveDecision::Wait);
        assert_eq!(gate.decide(&b, next - Duration::from_micros(1)), SolveDecision::Wait);
        assert_eq!(gate.decide(&b, next), SolveDecision::Solve);
        assert_eq!(gate.decide(&a[..1], next), SolveDecision::Solve, "a contact less is a change");
        gate.solved(&b, next, took);
        assert_eq!(gate.decide(&b, next), SolveDecision::Same);
        assert_eq!(gate.decide(&a, next + took), SolveDecision::Wait);
    }

    /// A live 3D session (a 9³-node box at 1 kHz, its surface field on) with the needle held 35 mm
    /// deep: the displacement the renderer solves from the latest record's contacts
    /// ([`DeformedTissue3`], one solve) equals, at the boundary surface's nodes, the field the
    /// session's fan-out computes from the compliance columns of the same contacts.
    #[test]
    fn the_solved_field_is_the_sessions_surface_field_at_the_surface() {
        use needlesim_core::fixtures::{box_phantom3, box_phantom3_params};
        use needlesim_core::sim3::BasePose3;
        use needlesim_session::{BoundarySurface, PoseCommand3};
        let model = box_phantom3(9);
        let params = box_phantom3_params([0.0513, 0.0487, 0.1], 0.005);
        let start = params.initial_pose;
        let s = Session::start3("box", model.clone(), params, vec![], None).unwrap();
        s.field_subscribers.fetch_add(1, Ordering::AcqRel);
        let t0 = Instant::now();
        for seq in 1.. {
            let t = t0.elapsed().as_secs_f64();
            let p = start.position_m;
            let pose = BasePose3::from_rotation([p[0], p[1], p[2] - 0.04 * (t / 1.5).min(1.0)], start.orientation);
            s.write_pose3_from_io(PoseCommand3 { pose, seq, client_time_ns: 0 }).unwrap();
            if t > 1.6 {
                break;
            }
            std::thread::sleep(Duration::from_millis(2));
        }
        // Held: wait until the contacts stop changing and two fields computed after that agree
        // (the fan-out adds at most 8 nodes' columns per field).
        let surface = BoundarySurface::of(model.mesh());
        let deadline = Instant::now() + Duration::from_secs(30);
        let (rec, field) = loop {
            assert!(Instant::now() < deadline, "the held needle's contacts and surface field did not settle");
            let a = s.latest_record();
            std::thread::sleep(Duration::from_millis(100));
            let f1 = s.field.borrow().clone();
            std::thread::sleep(Duration::from_millis(100));
            let (b, f2) = (s.latest_record(), s.field.borrow().clone());
            if a.d3.contacts() == b.d3.contacts() && f1.tick > a.tick && f2.tick > f1.tick && f1.displacement_m == f2.displacement_m {
                break (b, f2);
            }
        };
        s.close();
        assert!(rec.d3.n_contacts >= 2, "the needle holds points: {}", rec.d3.n_contacts);
        let mut d = DeformedTissue3::new(&model);
        let u = d.solve(&model, rec.d3.contacts().iter().map(|c| (c.x_ref_m, c.force_n))).unwrap();
        assert_eq!(field.displacement_m.len(), 3 * surface.nodes.len());
        let scale = field.displacement_m.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
        assert!(scale > 1e-5, "the surface moved: {scale} m");
        for (k, &v) in surface.nodes.iter().enumerate() {
            for (c, &got) in u[v as usize].iter().enumerate() {
                let want = field.displacement_m[3 * k + c];
                assert!((got - want).abs() <= 1e-9 * scale, "surface node {v} axis {c}: solved {got} m, surface field {want} m");
            }
        }
    }

    #[test]
    fn the_default_3d_probe_holds_the_needle_and_covers_the_nodes() {
        let nodes = [[0.0, 0.0, 0.0], [0.1, 0.0, 0.0], [0.0, 0.1, 0.0], [0.1, 0.1, 0.1]];
        let base = [0.02, 0.05, 0.12];
        let axis = unit3([1.0, 0.0, -1.0]);
        let p = default_probe_3d(&nodes, base, axis);
        let n = [
            p.e_u[1] * p.e_v[2] - p.e_u[2] * p.e_v[1],
            p.e_u[2] * p.e_v[0] - p.e_u[0] * p.e_v[2],
            p.e_u[0] * p.e_v[1] - p.e_u[1] * p.e_v[0],
        ];
        // The base and the needle's direction lie in the plane.
        let d = [base[0] - p.origin_m[0], base[1] - p.origin_m[1], base[2] - p.origin_m[2]];
        assert!(dot3(d, n).abs() < 1e-12 && dot3(axis, n).abs() < 1e-12);
        // Every node's projection falls in the image.
        for q in nodes {
            let d = [q[0] - p.origin_m[0], q[1] - p.origin_m[1], q[2] - p.origin_m[2]];
            let (u, v) = (dot3(d, p.e_u) / p.pixel_m, dot3(d, p.e_v) / p.pixel_m);
            assert!(u >= -1e-9 && u <= p.width as f64 + 1e-9 && v >= -1e-9 && v <= p.height as f64 + 1e-9, "{q:?}: ({u}, {v})");
        }
    }
}
