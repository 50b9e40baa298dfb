//! The remote link: the device loop talks to a session over the gRPC `ControlService.Control`/`Control3`
//! stream instead of the shared-memory channel (a bridge on another machine).
//!
//! The device loop never blocks and never touches async code: [`RemoteLink::send_pose`] puts the
//! pose in a bounded queue (`try_send`; when full the pose is dropped — the next period sends a
//! newer one), and [`RemoteLink::latest`] reads a latest-value slot (`try_lock`; a contended slot
//! reads as "nothing new", the value is there the next period). A tokio runtime owned by the link
//! (one worker thread) streams the poses out and fills the slot from the responses.
//!
//! # 2D and 3D sessions
//!
//! [`RemoteLink::connect`] asks the session's dimension (`GetSession`) before the device loop
//! starts. A 2D session is driven through `Control`: the device's 6-DOF pose goes out as its planar
//! part `(x, y, θ)` and each response's `(Fx, Fy, τ)`, 3 × 3 stiffness and base come back through
//! the planar embedding ([`sample_from_response`]). A 3D session is driven through `Control3`: the
//! pose goes out whole (`base3`: position, m, and unit quaternion `(w, x, y, z)`, world), and each
//! response's `d3` gives the wrench `(F, τ)` (N, N·m, world, at the base point), the 6 × 6
//! stiffness `K = ∂(F, τ)/∂δ` (row-major; `δ = (δp, δθ)` with `R ← exp(δθ̂)R`, the channel's
//! convention) and the base pose `q_s` it was computed at ([`sample_from_response3`]), so the
//! renderer's local model `w_s + K δ(q_d, q_s)` and coupling work exactly as over shared memory.
//! `Control3` has no bevel flip: a button press in a 3D remote session is ignored (said once).
//!
//! `inject_rtt`: a delay line inside the link holds every outgoing pose for half of it before it
//! is sent and every incoming response for the other half before it is published (FIFO, each
//! item released at its own arrival time + RTT/2), to test latency without a real network.

use std::collections::VecDeque;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use anyhow::{Context, Result, anyhow};
use needlesim_proto::v1 as pb;
use tokio::sync::mpsc;
use tokio::time::Instant;

use crate::render::{Pose6, ServerSample};
use needlesim_channel::shm::{Dimension, monotonic_ns};
use needlesim_channel::spatial;

/// A pose on its way out.
#[derive(Debug, Clone, Copy)]
struct PoseOut {
    pose: Pose6,
    client_time_ns: u64,
    seq: u64,
    flip_bevel: bool,
}

/// The newest response, as the device loop sees it.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RemoteSample {
    /// Increases with every response published (0 = none yet).
    pub counter: u64,
    pub sample: ServerSample,
    pub tick: u64,
    /// `seq` and `client_time_ns` of the newest pose the server's tick had used (echo).
    pub pose_seq: u64,
    pub client_time_ns: u64,
    /// When the response was published to the device loop (after the injected delay), monotonic ns.
    pub t_published_ns: u64,
}

#[derive(Debug, Default)]
struct Shared {
    slot: Mutex<RemoteSample>,
    failed: AtomicBool,
    error: Mutex<Option<String>>,
    ended: AtomicBool,
    /// The device loop closed its side.
    closing: AtomicBool,
}

impl Shared {
    fn fail(&self, msg: String) {
        let mut e = self.error.lock().unwrap_or_else(|p| p.into_inner());
        if e.is_none() {
            *e = Some(msg);
        }
        self.failed.store(true, Ordering::Release);
    }
}

/// Where and how to connect.
#[derive(Debug, Clone)]
pub struct RemoteConfig {
    pub url: String,
    pub session_id: String,
    pub token: String,
    /// Injected round-trip delay (half each way).
    pub inject_rtt: Duration,
    /// SCHED_FIFO priority of the link's network thread (0: normal scheduling). Below the device
    /// loop's: on a loaded machine a normally scheduled network thread waits tens of ms for a core
    /// at each wake-up, and the poses and forces then cross in bursts.
    pub rt_priority: i32,
}

/// The device loop's end of the remote link.
pub struct RemoteLink {
    poses: Option<mpsc::Sender<PoseOut>>,
    shared: Arc<Shared>,
    seq: u64,
    last_counter: u64,
    /// Poses dropped because the queue was full.
    pub dropped_poses: u64,
    /// A bevel flip waiting to go out with the next pose that is queued.
    pending_flip: bool,
    runtime: Option<tokio::runtime::Runtime>,
    /// The session's dimension (`GetSession`), which says the stream (`Control` or `Control3`).
    dimension: Dimension,
}

/// Poses that may wait in the queue to the network task (the task drains it into its delay line at once).
const POSE_QUEUE: usize = 8;

impl RemoteLink {
    /// Connects the channel (blocking, before the device loop starts; 5 s timeout), asks the
    /// session's dimension (`GetSession`: an unknown session fails here, naming it) and starts the
    /// streaming task (`Control` for a 2D session, `Control3` for a 3D one). The control stream
    /// itself opens with the first pose.
    pub fn connect(cfg: RemoteConfig) -> Result<Self> {
        let runtime = tokio::runtime::Builder::new_multi_thread()
            .worker_threads(1)
            .thread_name("bridge-remote")
            .on_thread_start({
                let priority = cfg.rt_priority;
                move || {
                    if priority > 0
                        && let Err(why) = needlesim_channel::rt::request_realtime_priority(priority)
                    {
                        tracing::debug!("the remote link's thread runs without real-time priority ({why})");
                    }
                }
            })
            .enable_all()
            .build()
            .context("starting the remote link's runtime")?;
        let url = cfg.url.clone();
        let channel = runtime
            .block_on(async {
                tonic::transport::Endpoint::from_shared(url.clone())?
                    .connect_timeout(Duration::from_secs(5))
                    .tcp_nodelay(true)
                    .connect()
                    .await
            })
            .map_err(|e| anyhow!("--server {url}: cannot connect: {}", error_chain(&e)))?;
        let auth: tonic::metadata::MetadataValue<tonic::metadata::Ascii> =
            format!("Bearer {}", cfg.token.trim()).parse().map_err(|_| anyhow!("--token: not a valid header value"))?;
        let dimension = runtime.block_on(session_dimension(channel.clone(), auth.clone(), &cfg))?;
        let shared = Arc::new(Shared::default());
        let (tx, rx) = mpsc::channel(POSE_QUEUE);
        let sh = shared.clone();
        runtime.spawn(async move {
            if let Err(e) = stream_task(channel, auth, cfg, dimension, rx, sh.clone()).await {
                sh.fail(format!("{e:#}"));
            }
            sh.ended.store(true, Ordering::Release);
        });
        Ok(Self {
            poses: Some(tx),
            shared,
            seq: 0,
            last_counter: 0,
            dropped_poses: 0,
            pending_flip: false,
            runtime: Some(runtime),
            dimension,
        })
    }

    /// The session's dimension: a 2D session gets the planar part of each pose.
    pub fn dimension(&self) -> Dimension {
        self.dimension
    }

    /// Asks for a bevel flip; it goes out with the next pose queued (none is lost to a full queue).
    /// A 3D session (`Control3`) has no flip: the request is dropped with the next pose.
    pub fn request_flip(&mut self) {
        self.pending_flip = true;
    }

    /// Queues a pose (never blocks); returns its `seq`, or `None` if the queue was full or the link is down.
    pub fn send_pose(&mut self, pose: &Pose6, client_time_ns: u64) -> Option<u64> {
        let pose = *pose;
        let tx = self.poses.as_ref()?;
        let seq = self.seq + 1;
        match tx.try_send(PoseOut { pose, client_time_ns, seq, flip_bevel: self.pending_flip }) {
            Ok(()) => {
                self.seq = seq;
                self.pending_flip = false;
                Some(seq)
            }
            Err(_) => {
                self.dropped_poses += 1;
                None
            }
        }
    }

    /// The newest response if one was published since the previous call (never blocks).
    pub fn latest(&mut self) -> Option<RemoteSample> {
        let s = *self.shared.slot.try_lock().ok()?;
        (s.counter > self.last_counter).then(|| {
            self.last_counter = s.counter;
            s
        })
    }

    /// Responses published so far.
    pub fn responses(&self) -> u64 {
        self.last_counter
    }

    /// The link failed (connection, status, stream ended by the server): the message.
    pub fn failure(&self) -> Option<String> {
        if !self.shared.failed.load(Ordering::Acquire) {
            return None;
        }
        Some(self.shared.error.lock().unwrap_or_else(|p| p.into_inner()).clone().unwrap_or_default())
    }

    /// Closes our side of the stream (the server then ends its side) and waits up to `timeout` for the task.
    pub fn close(&mut self, timeout: Duration) {
        self.shared.closing.store(true, Ordering::Release);
        self.poses = None;
        let t0 = std::time::Instant::now();
        while !self.shared.ended.load(Ordering::Acquire) && t0.elapsed() < timeout {
            std::thread::sleep(Duration::from_millis(1));
        }
        if let Some(rt) = self.runtime.take() {
            rt.shutdown_timeout(Duration::from_millis(100));
        }
    }
}

impl Drop for RemoteLink {
    fn drop(&mut self) {
        self.close(Duration::from_millis(200));
    }
}

fn error_chain(e: &dyn std::error::Error) -> String {
    let mut s = e.to_string();
    let mut src = e.source();
    while let Some(c) = src {
        s.push_str(": ");
        s.push_str(&c.to_string());
        src = c.source();
    }
    s
}

fn pose_of(p: Option<&pb::Pose2>) -> [f64; 3] {
    p.map_or([0.0; 3], |p| [p.x_m, p.y_m, p.theta_rad])
}

/// The session's dimension, from `GetSession` (its `dimension`: 0 from servers before 3D is 2).
async fn session_dimension(
    channel: tonic::transport::Channel,
    auth: tonic::metadata::MetadataValue<tonic::metadata::Ascii>,
    cfg: &RemoteConfig,
) -> Result<Dimension> {
    let mut client = pb::session_service_client::SessionServiceClient::new(channel);
    let mut req = tonic::Request::new(pb::GetSessionRequest { session_id: cfg.session_id.clone() });
    req.metadata_mut().insert("authorization", auth);
    let info = tokio::time::timeout(Duration::from_secs(5), client.get_session(req))
        .await
        .map_err(|_| anyhow!("--server {}: GetSession did not answer within 5 s", cfg.url))?
        .map_err(|s| anyhow!("--server {} session {}: GetSession: {} ({:?})", cfg.url, cfg.session_id, s.message(), s.code()))?
        .into_inner();
    match info.dimension {
        0 | 2 => Ok(Dimension::Two),
        3 => Ok(Dimension::Three),
        d => Err(anyhow!("--server {} session {}: the session's dimension is {d}, neither 2 nor 3", cfg.url, cfg.session_id)),
    }
}

/// A response to a sample (a 2D session: the planar wrench, 3×3 stiffness and base embedded in
/// the 6-DOF sample); a response without a (complete) stiffness keeps the previous Jacobian
/// (`∂(Fx, Fy, τ)/∂(x, y, θ)`, row-major).
pub fn sample_from_response(r: &pb::ControlResponse, prev_stiffness: [f64; 9]) -> ServerSample {
    let f = r.force_n.unwrap_or_default();
    let stiffness = planar_stiffness_of(r).unwrap_or(prev_stiffness);
    ServerSample::planar([f.x, f.y, r.torque_nm], &stiffness, pose_of(r.base.as_ref()))
}

/// A response to a sample for a 3D session (`d3`: wrench `(F, τ)`, 6 × 6 stiffness row-major, the
/// base pose it was computed at, normalised); a response without a (complete, finite) 6 × 6 keeps
/// the previous one. `None` for a response without `d3` (not a 3D session's) or without its
/// force, torque or a valid base pose: such a response is not a sample to render.
pub fn sample_from_response3(r: &pb::ControlResponse, prev_stiffness: &[[f64; 6]; 6]) -> Option<ServerSample> {
    let d = r.d3.as_ref()?;
    let (f, t) = (d.force_n.as_ref()?, d.torque_nm.as_ref()?);
    let wrench = [f.x, f.y, f.z, t.x, t.y, t.z];
    if !wrench.iter().all(|v| v.is_finite()) {
        return None;
    }
    let base = d.base.as_ref()?;
    let p = base.position_m.as_ref()?;
    let q = base.orientation.as_ref()?;
    let position_m = [p.x, p.y, p.z];
    if !position_m.iter().all(|v| v.is_finite()) {
        return None;
    }
    let orientation = spatial::quat_normalize([q.w, q.x, q.y, q.z])?;
    Some(ServerSample { wrench, stiffness: stiffness3_of(r).unwrap_or(*prev_stiffness), base: Pose6 { position_m, orientation } })
}

/// The response's 6 × 6 stiffness (`d3.stiffness`, row-major), if complete and finite.
fn stiffness3_of(r: &pb::ControlResponse) -> Option<[[f64; 6]; 6]> {
    let k = &r.d3.as_ref()?.stiffness;
    (k.len() == 36 && k.iter().all(|v| v.is_finite())).then(|| std::array::from_fn(|i| std::array::from_fn(|j| k[6 * i + j])))
}

/// The response's 3×3 stiffness, if complete and finite.
fn planar_stiffness_of(r: &pb::ControlResponse) -> Option<[f64; 9]> {
    (r.stiffness.len() == 9 && r.stiffness.iter().all(|v| v.is_finite())).then(|| std::array::from_fn(|i| r.stiffness[i]))
}

/// The outgoing delay line: drains the pose queue at once and releases each pose, made into the
/// stream's message by `make(pose, session_id)` (the session id in the first message only), at its
/// arrival + `half`. Returns the message stream and the task (ended when the queue closes and the
/// line is empty: dropping the sender closes our side of the stream).
fn delay_out<M: Send + 'static>(
    session_id: String,
    half: Duration,
    mut poses: mpsc::Receiver<PoseOut>,
    make: fn(&PoseOut, String) -> M,
) -> (mpsc::Receiver<M>, tokio::task::JoinHandle<()>) {
    let (req_tx, req_rx) = mpsc::channel::<M>(64);
    let task = tokio::spawn(async move {
        let mut line: VecDeque<(Instant, PoseOut)> = VecDeque::new();
        let mut first = true;
        let mut open = true;
        loop {
            let next = line.front().map(|(t, _)| *t);
            tokio::select! {
                p = poses.recv(), if open => match p {
                    Some(p) => line.push_back((Instant::now() + half, p)),
                    None => open = false,
                },
                _ = tokio::time::sleep_until(next.unwrap_or_else(Instant::now)), if next.is_some() => {
                    let (_, p) = line.pop_front().expect("front exists");
                    let m = make(&p, if first { session_id.clone() } else { String::new() });
                    first = false;
                    if req_tx.send(m).await.is_err() {
                        return;
                    }
                }
            }
            if !open && line.is_empty() {
                return;
            }
        }
    });
    (req_rx, task)
}

/// A 2D session's message: the pose's planar part.
fn request2(p: &PoseOut, session_id: String) -> pb::ControlRequest {
    let [x_m, y_m, theta_rad] = p.pose.to_planar();
    pb::ControlRequest {
        session_id,
        base: Some(pb::Pose2 { x_m, y_m, theta_rad }),
        client_time_ns: p.client_time_ns,
        seq: p.seq,
        flip_bevel: p.flip_bevel,
        take_over: false,
    }
}

/// A 3D session's message: the whole pose (position, m; unit quaternion w, x, y, z; world).
fn request3(p: &PoseOut, session_id: String) -> pb::ControlRequest3 {
    let ([x, y, z], [qw, qx, qy, qz]) = (p.pose.position_m, p.pose.orientation);
    pb::ControlRequest3 {
        session_id,
        base3: Some(pb::Pose3 { position_m: Some(pb::Vec3 { x, y, z }), orientation: Some(pb::Quaternion { w: qw, x: qx, y: qy, z: qz }) }),
        client_time_ns: p.client_time_ns,
        seq: p.seq,
        take_over: false,
    }
}

/// The stiffness a response leaves for the next one that lacks it, per dimension.
enum LastStiffness {
    Planar([f64; 9]),
    Spatial(Box<[[f64; 6]; 6]>),
}

async fn stream_task(
    channel: tonic::transport::Channel,
    auth: tonic::metadata::MetadataValue<tonic::metadata::Ascii>,
    cfg: RemoteConfig,
    dimension: Dimension,
    poses: mpsc::Receiver<PoseOut>,
    shared: Arc<Shared>,
) -> Result<()> {
    let half = cfg.inject_rtt / 2;
    let what = format!("--server {} session {}", cfg.url, cfg.session_id);
    let mut client = pb::control_service_client::ControlServiceClient::new(channel);
    let (opened, out) = match dimension {
        Dimension::Two => {
            let (rx, out) = delay_out(cfg.session_id.clone(), half, poses, request2);
            let mut req = tonic::Request::new(tokio_stream::wrappers::ReceiverStream::new(rx));
            req.metadata_mut().insert("authorization", auth);
            (client.control(req).await.map_err(|s| anyhow!("{what}: Control: {} ({:?})", s.message(), s.code())), out)
        }
        Dimension::Three => {
            let (rx, out) = delay_out(cfg.session_id.clone(), half, poses, request3);
            let mut req = tonic::Request::new(tokio_stream::wrappers::ReceiverStream::new(rx));
            req.metadata_mut().insert("authorization", auth);
            (client.control3(req).await.map_err(|s| anyhow!("{what}: Control3: {} ({:?})", s.message(), s.code())), out)
        }
    };
    let mut responses = opened?.into_inner();
    // Incoming delay line: each response is published at its arrival + half.
    let mut line: VecDeque<(Instant, pb::ControlResponse)> = VecDeque::new();
    let mut counter = 0u64;
    let mut stiffness = match dimension {
        Dimension::Two => LastStiffness::Planar([0.0; 9]),
        Dimension::Three => LastStiffness::Spatial(Box::new([[0.0; 6]; 6])),
    };
    let mut open = true;
    loop {
        let next = line.front().map(|(t, _)| *t);
        tokio::select! {
            r = responses.message(), if open => match r {
                Ok(Some(r)) => line.push_back((Instant::now() + half, r)),
                Ok(None) => open = false,
                Err(s) => return Err(anyhow!("{what}: the control stream failed: {} ({:?})", s.message(), s.code())),
            },
            _ = tokio::time::sleep_until(next.unwrap_or_else(Instant::now)), if next.is_some() => {
                let now = Instant::now();
                // Publish every response that is due (only the newest is visible to the loop).
                while line.front().is_some_and(|(t, _)| *t <= now) {
                    let (_, r) = line.pop_front().expect("front exists");
                    let sample = match &mut stiffness {
                        LastStiffness::Planar(k) => {
                            let sample = sample_from_response(&r, *k);
                            *k = planar_stiffness_of(&r).unwrap_or(*k);
                            sample
                        }
                        LastStiffness::Spatial(k) => {
                            // A 3D response without a usable d3 is not a sample: the device keeps the last one.
                            let Some(sample) = sample_from_response3(&r, k) else { continue };
                            **k = sample.stiffness;
                            sample
                        }
                    };
                    counter += 1;
                    let v = RemoteSample {
                        counter,
                        sample,
                        tick: r.tick,
                        pose_seq: r.pose_seq,
                        client_time_ns: r.client_time_ns,
                        t_published_ns: monotonic_ns(),
                    };
                    *shared.slot.lock().unwrap_or_else(|p| p.into_inner()) = v;
                }
            }
        }
        if !open && line.is_empty() {
            break;
        }
    }
    if !shared.closing.load(Ordering::Acquire) {
        // The server ended the stream while we were still sending: the session is gone.
        out.abort();
        shared.fail(format!("{what}: the server ended the control stream (session closed?)"));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v3(x: f64, y: f64, z: f64) -> Option<pb::Vec3> {
        Some(pb::Vec3 { x, y, z })
    }

    /// A 3D response with a distinct value in every entry of the wrench, the 6 × 6 and the base.
    fn response3(stiffness: Vec<f64>, q: [f64; 4]) -> pb::ControlResponse {
        pb::ControlResponse {
            tick: 7,
            d3: Some(pb::Tick3 {
                base: Some(pb::Pose3 {
                    position_m: v3(0.05, 0.04, 0.2),
                    orientation: Some(pb::Quaternion { w: q[0], x: q[1], y: q[2], z: q[3] }),
                }),
                force_n: v3(0.1, -0.2, 0.3),
                torque_nm: v3(-0.004, 0.005, -0.006),
                stiffness,
                ..Default::default()
            }),
            ..Default::default()
        }
    }

    #[test]
    fn a_3d_response_gives_the_6dof_wrench_its_row_major_6x6_and_its_base() {
        let k: Vec<f64> = (0..36).map(|i| -(i as f64) - 0.5).collect();
        let q = [std::f64::consts::FRAC_1_SQRT_2, 0.0, std::f64::consts::FRAC_1_SQRT_2, 0.0];
        let s = sample_from_response3(&response3(k.clone(), q), &[[9.0; 6]; 6]).expect("a sample");
        assert_eq!(s.wrench, [0.1, -0.2, 0.3, -0.004, 0.005, -0.006]);
        for (i, row) in s.stiffness.iter().enumerate() {
            for (j, v) in row.iter().enumerate() {
                assert_eq!(*v, k[6 * i + j], "K[{i}][{j}]: row = wrench component, column = perturbation");
            }
        }
        assert_eq!(s.base.position_m, [0.05, 0.04, 0.2]);
        let dq: f64 = s.base.orientation.iter().zip(&q).map(|(a, b)| (a - b).abs()).sum();
        assert!(dq < 1e-15, "{:?}", s.base.orientation);
        // A quaternion off unit norm by rounding is normalised.
        let s = sample_from_response3(&response3(k, q.map(|v| v * (1.0 + 1e-9))), &[[0.0; 6]; 6]).unwrap();
        let n: f64 = s.base.orientation.iter().map(|v| v * v).sum();
        assert!((n - 1.0).abs() < 1e-15, "{n}");
    }

    #[test]
    fn a_3d_response_without_a_complete_6x6_keeps_the_previous_one() {
        let prev: [[f64; 6]; 6] = std::array::from_fn(|i| std::array::from_fn(|j| (10 * i + j) as f64));
        let q = spatial::IDENTITY;
        for k in [vec![], vec![1.0; 9], vec![1.0; 35], { (0..36).map(|i| if i == 20 { f64::NAN } else { 1.0 }).collect() }] {
            let s = sample_from_response3(&response3(k.clone(), q), &prev).expect("the wrench is still a sample");
            assert_eq!(s.stiffness, prev, "stiffness of {} entries", k.len());
        }
    }

    #[test]
    fn a_response_without_a_usable_3d_part_is_no_3d_sample() {
        let prev = [[0.0; 6]; 6];
        let q = spatial::IDENTITY;
        // A 2D session's response (no d3).
        assert!(
            sample_from_response3(&pb::ControlResponse { force_n: Some(pb::Vec2 { x: 1.0, y: 2.0 }), ..Default::default() }, &prev)
                .is_none()
        );
        let broken = |f: fn(&mut pb::Tick3)| {
            let mut r = response3(vec![0.0; 36], q);
            f(r.d3.as_mut().unwrap());
            sample_from_response3(&r, &prev)
        };
        assert!(broken(|d| d.force_n = None).is_none());
        assert!(broken(|d| d.torque_nm = None).is_none());
        assert!(broken(|d| d.base = None).is_none());
        assert!(broken(|d| d.force_n = v3(f64::INFINITY, 0.0, 0.0)).is_none());
        assert!(broken(|d| d.base.as_mut().unwrap().position_m = v3(f64::NAN, 0.0, 0.0)).is_none());
        assert!(broken(|d| d.base.as_mut().unwrap().orientation = Some(pb::Quaternion::default())).is_none());
        assert!(broken(|_| {}).is_some());
    }

    #[test]
    fn poses_go_out_whole_to_a_3d_session_and_planar_to_a_2d_one() {
        let q = spatial::quat_normalize([0.9, 0.1, -0.2, 0.3]).unwrap();
        let p = PoseOut { pose: Pose6 { position_m: [0.01, 0.02, 0.03], orientation: q }, client_time_ns: 42, seq: 5, flip_bevel: true };
        let m = request3(&p, "s1".into());
        assert_eq!((m.session_id.as_str(), m.client_time_ns, m.seq, m.take_over), ("s1", 42, 5, false));
        let b = m.base3.unwrap();
        let (pos, o) = (b.position_m.unwrap(), b.orientation.unwrap());
        assert_eq!([pos.x, pos.y, pos.z], [0.01, 0.02, 0.03]);
        assert_eq!([o.w, o.x, o.y, o.z], q);
        let m = request2(&p, String::new());
        let b = m.base.unwrap();
        assert_eq!([b.x_m, b.y_m, b.theta_rad], spatial::pose_to_planar([0.01, 0.02, 0.03], q));
        assert!(m.flip_bevel && m.session_id.is_empty() && m.seq == 5 && m.client_time_ns == 42);
    }
}
