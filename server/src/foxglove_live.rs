//! Live sessions in the Foxglove app (`serve --foxglove-addr`): the Foxglove SDK's WebSocket
//! endpoint (needlesim-foxglove) with a scene and a force channel per session, fed by one task per
//! session that reads the session's latest tick record and displacement field like a rendering
//! observer — never the real-time thread — and builds messages only while a Foxglove client
//! subscribes. Sessions are picked up by a watcher that looks at the session list twice a second,
//! so no session-creation path needs to know about Foxglove.
//!
//! No tokens: Foxglove's protocol has none, so the endpoint exposes every live session to whoever
//! reaches its port. It binds where the operator says (loopback in the guide's examples, docs/guide/viewer.md).
use std::collections::HashSet;
use std::net::SocketAddr;
use std::sync::atomic::Ordering;
use std::sync::{Arc, OnceLock};
use std::time::Duration;

use anyhow::{Context as _, Result};
use needlesim_foxglove::{
    ForceSample, FoxgloveLive, LiveOptions, LiveStats, PointState, SceneFrame, ScenePoint, SceneTarget, SessionChannels, Surface,
    scene_update,
};
use needlesim_session::{Session, SessionTissue, TickRecord};

use crate::serve::SharedState;

/// The force channel's rate (Hz); the scene goes out every [`SCENE_EVERY`]-th of its periods.
pub const FORCE_HZ: f64 = 100.0;
/// Scenes at `FORCE_HZ / SCENE_EVERY` ≈ 33 Hz.
pub const SCENE_EVERY: u32 = 3;

/// The endpoint of this process, once started (for `/metrics`).
static ENDPOINT: OnceLock<Arc<FoxgloveLive>> = OnceLock::new();

/// The endpoint's counters, if it was started.
pub fn stats() -> Option<LiveStats> {
    ENDPOINT.get().map(|l| l.stats())
}

/// Starts the endpoint on `addr` (at most `max_clients` connections at once) and the watcher that
/// gives every session its channels.
pub async fn start(addr: SocketAddr, max_clients: usize, state: SharedState) -> Result<u16> {
    anyhow::ensure!(max_clients > 0, "--foxglove-max-clients must be at least 1");
    let opts = LiveOptions { max_clients, ..LiveOptions::default() };
    let live = FoxgloveLive::start(&addr.ip().to_string(), addr.port(), "needlesim", opts)
        .await
        .with_context(|| format!("--foxglove-addr {addr}"))?;
    let port = live.port();
    let live = Arc::new(live);
    let _ = ENDPOINT.set(live.clone());
    tokio::spawn(async move {
        let mut known: HashSet<String> = HashSet::new();
        let mut every = tokio::time::interval(Duration::from_millis(500));
        loop {
            every.tick().await;
            let sessions: Vec<Arc<Session>> = state.sessions.read().expect("sessions lock").values().cloned().collect();
            known.retain(|id| sessions.iter().any(|s| &s.id == id));
            for s in sessions {
                if known.insert(s.id.clone()) {
                    match live.open_session(&s.id) {
                        Ok(ch) => {
                            tokio::spawn(publish(s, ch));
                        }
                        Err(e) => tracing::warn!(session = %s.id, error = %e, "no Foxglove channels for this session"),
                    }
                }
            }
        }
    });
    Ok(port)
}

/// The surface Foxglove draws: a 3D session's boundary, a 2D session's mesh at z = 0.
pub(crate) fn surface_of(s: &Session) -> Surface {
    match &s.tissue {
        SessionTissue::Three { model, surface } => {
            let x = model.mesh().nodes_m();
            Surface { positions_m: surface.nodes.iter().map(|&n| x[n as usize]).collect(), triangles: surface.triangles.clone() }
        }
        SessionTissue::Two(model) => {
            let m = model.mesh();
            Surface {
                positions_m: m.nodes_m().iter().map(|&[x, y]| [x, y, 0.0]).collect(),
                triangles: m.triangles().iter().map(|t| t.map(|n| n as u32)).collect(),
            }
        }
    }
}

fn point_state(code: u8) -> PointState {
    match code {
        0 => PointState::Stuck,
        1 => PointState::Slipping,
        2 => PointState::Tip,
        _ => PointState::Other,
    }
}

/// A tick record's needle, contacts and targets (world, m), into the caller's buffers.
fn scene_parts(r: &TickRecord, needle: &mut Vec<[f64; 3]>, points: &mut Vec<ScenePoint>, targets: &mut Vec<SceneTarget>) {
    needle.clear();
    points.clear();
    targets.clear();
    if r.dimension == 3 {
        let d = &r.d3;
        needle.extend([d.position_m, d.tip_m]);
        points.extend(d.contacts().iter().map(|c| ScenePoint { position_m: c.x_m, state: point_state(c.state) }));
        targets.extend(d.targets().iter().map(|t| SceneTarget { centre_m: t.centre_m, radius_m: t.radius_m, hit: t.hit }));
    } else {
        needle.extend(r.shape().iter().map(|&[x, y]| [x, y, 0.0]));
        if needle.len() < 2 {
            needle.clear();
            needle.extend([[r.base.x_m, r.base.y_m, 0.0], [r.tip_m[0], r.tip_m[1], 0.0]]);
        }
        // A 2D record carries no target radius: a 2 mm marker at the displaced centre.
        targets.extend(r.targets().iter().map(|t| SceneTarget {
            centre_m: [t.position_m[0], t.position_m[1], 0.0],
            radius_m: 1e-3,
            hit: t.hit,
        }));
    }
}

/// A tick record's force sample (2D embedded in the plane z = 0, the torque about z).
pub(crate) fn force_of(r: &TickRecord) -> ForceSample {
    let (force_n, torque_nm) =
        if r.dimension == 3 { (r.d3.force_n, r.d3.torque_nm) } else { ([r.force_n[0], r.force_n[1], 0.0], [0.0, 0.0, r.torque_nm]) };
    ForceSample { time_s: r.time_s, depth_m: r.inserted_length_m, force_n: force_n.into(), torque_nm: torque_nm.into() }
}

/// Buffers for a record's scene (reused from one scene to the next).
#[derive(Default)]
pub(crate) struct SceneParts {
    needle: Vec<[f64; 3]>,
    points: Vec<ScenePoint>,
    targets: Vec<SceneTarget>,
}

impl SceneParts {
    /// The scene of `rec` without displacements (the surface undeformed), with the surface
    /// entity when `surface` is given.
    pub(crate) fn scene_update(
        &mut self,
        rec: &TickRecord,
        surface: Option<&Surface>,
    ) -> needlesim_foxglove::foxglove::messages::SceneUpdate {
        scene_parts(rec, &mut self.needle, &mut self.points, &mut self.targets);
        let frame = SceneFrame {
            time_ns: (rec.time_s * 1e9) as u64,
            surface_displacement_m: None,
            needle_m: &self.needle,
            points: &self.points,
            targets: &self.targets,
        };
        scene_update(surface, &frame, 0.0)
    }
}

/// Holds one displacement-field subscription of a session while a Foxglove client watches its
/// scene (the fan-out computes the field only for subscribers).
struct FieldInterest<'a> {
    session: &'a Session,
    on: bool,
}

impl FieldInterest<'_> {
    fn set(&mut self, on: bool) {
        if on != self.on {
            if on {
                self.session.field_subscribers.fetch_add(1, Ordering::Relaxed);
            } else {
                self.session.field_subscribers.fetch_sub(1, Ordering::Relaxed);
            }
            self.on = on;
        }
    }
}

impl Drop for FieldInterest<'_> {
    fn drop(&mut self) {
        self.set(false);
    }
}

/// One session's publisher: until the session closes (its channels are then removed).
async fn publish(s: Arc<Session>, ch: SessionChannels) {
    let surface = surface_of(&s);
    let dims = if matches!(s.tissue, SessionTissue::Three { .. }) { 3 } else { 2 };
    let mut latest = s.latest.clone();
    let mut field = s.field.clone();
    let mut interest = FieldInterest { session: &s, on: false };
    let (mut needle, mut points, mut targets, mut u3) = (Vec::new(), Vec::new(), Vec::new(), Vec::<[f64; 3]>::new());
    let mut every = tokio::time::interval(Duration::from_secs_f64(1.0 / FORCE_HZ));
    every.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Skip);
    let (mut last_tick, mut period) = (u64::MAX, 0u32);
    let closed = s.closed();
    tokio::pin!(closed);
    loop {
        tokio::select! {
            // The session closed: its channels go (unadvertised) and so does this task's hold on it.
            () = &mut closed => return,
            _ = every.tick() => {}
        }
        match latest.has_changed() {
            Err(_) => return,
            Ok(false) => continue,
            Ok(true) => {}
        }
        let rec = latest.borrow_and_update().clone();
        if rec.tick == last_tick {
            continue;
        }
        last_tick = rec.tick;
        let time_ns = (rec.time_s * 1e9) as u64;
        if ch.wants_force() {
            ch.log_force(time_ns, &force_of(&rec));
        }
        interest.set(ch.wants_scene());
        period = period.wrapping_add(1);
        if !ch.wants_scene() || period % SCENE_EVERY != 0 {
            continue;
        }
        scene_parts(&rec, &mut needle, &mut points, &mut targets);
        let f = field.borrow_and_update().clone();
        u3.clear();
        if f.displacement_m.len() == dims * surface.positions_m.len() {
            u3.extend(f.displacement_m.chunks_exact(dims).map(|c| if dims == 3 { [c[0], c[1], c[2]] } else { [c[0], c[1], 0.0] }));
        }
        let frame = SceneFrame {
            time_ns,
            surface_displacement_m: (!u3.is_empty()).then_some(u3.as_slice()),
            needle_m: &needle,
            points: &points,
            targets: &targets,
        };
        ch.log_scene(time_ns, &scene_update(Some(&surface), &frame, 0.0));
    }
}
