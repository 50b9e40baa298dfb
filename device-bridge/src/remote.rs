//! The remote link: the device loop talks to a session over the gRPC `ControlService.Control`
//! stream instead of the shared-memory channel (a bridge on another machine).
//!
//! The device loop never blocks and never touches async code: [`RemoteLink::send_pose`] puts the
//! pose in a bounded queue (`try_send`; when full the pose is dropped — the next period sends a
//! newer one), and [`RemoteLink::latest`] reads a latest-value slot (`try_lock`; a contended slot
//! reads as "nothing new", the value is there the next period). A tokio runtime owned by the link
//! (one worker thread) streams the poses out and fills the slot from the responses.
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

use crate::render::ServerSample;
use needlesim_channel::shm::monotonic_ns;

/// A pose on its way out.
#[derive(Debug, Clone, Copy)]
struct PoseOut {
    pose: [f64; 3],
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
}

/// Poses that may wait in the queue to the network task (the task drains it into its delay line at once).
const POSE_QUEUE: usize = 8;

impl RemoteLink {
    /// Connects the channel (blocking, before the device loop starts; 5 s timeout) and starts the
    /// streaming task. The control stream itself opens with the first pose.
    pub fn connect(cfg: RemoteConfig) -> Result<Self> {
        let runtime = tokio::runtime::Builder::new_multi_thread()
            .worker_threads(1)
            .thread_name("bridge-remote")
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
        let shared = Arc::new(Shared::default());
        let (tx, rx) = mpsc::channel(POSE_QUEUE);
        let sh = shared.clone();
        runtime.spawn(async move {
            if let Err(e) = stream_task(channel, auth, cfg, rx, sh.clone()).await {
                sh.fail(format!("{e:#}"));
            }
            sh.ended.store(true, Ordering::Release);
        });
        Ok(Self { poses: Some(tx), shared, seq: 0, last_counter: 0, dropped_poses: 0, pending_flip: false, runtime: Some(runtime) })
    }

    /// Asks for a bevel flip; it goes out with the next pose queued (none is lost to a full queue).
    pub fn request_flip(&mut self) {
        self.pending_flip = true;
    }

    /// Queues a pose (never blocks); returns its `seq`, or `None` if the queue was full or the link is down.
    pub fn send_pose(&mut self, pose: [f64; 3], client_time_ns: u64) -> Option<u64> {
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

/// A response to a sample (a 2D session: the planar wrench, 3×3 stiffness and base embedded in
/// the 6-DOF sample); a response without a (complete) stiffness keeps the previous Jacobian
/// (`∂(Fx, Fy, τ)/∂(x, y, θ)`, row-major).
pub fn sample_from_response(r: &pb::ControlResponse, prev_stiffness: [f64; 9]) -> ServerSample {
    let f = r.force_n.unwrap_or_default();
    let stiffness = planar_stiffness_of(r).unwrap_or(prev_stiffness);
    ServerSample::planar([f.x, f.y, r.torque_nm], &stiffness, pose_of(r.base.as_ref()))
}

/// The response's 3×3 stiffness, if complete and finite.
fn planar_stiffness_of(r: &pb::ControlResponse) -> Option<[f64; 9]> {
    (r.stiffness.len() == 9 && r.stiffness.iter().all(|v| v.is_finite())).then(|| std::array::from_fn(|i| r.stiffness[i]))
}

async fn stream_task(
    channel: tonic::transport::Channel,
    auth: tonic::metadata::MetadataValue<tonic::metadata::Ascii>,
    cfg: RemoteConfig,
    mut poses: mpsc::Receiver<PoseOut>,
    shared: Arc<Shared>,
) -> Result<()> {
    let half = cfg.inject_rtt / 2;
    let (req_tx, req_rx) = mpsc::channel::<pb::ControlRequest>(64);
    // Outgoing delay line: drain the queue at once, release each pose at its arrival + half.
    let session_id = cfg.session_id.clone();
    let out = tokio::spawn(async move {
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
                    let m = pb::ControlRequest {
                        session_id: if first { session_id.clone() } else { String::new() },
                        base: Some(pb::Pose2 { x_m: p.pose[0], y_m: p.pose[1], theta_rad: p.pose[2] }),
                        client_time_ns: p.client_time_ns,
                        seq: p.seq,
                        flip_bevel: p.flip_bevel, take_over: false,
                    };
                    first = false;
                    if req_tx.send(m).await.is_err() {
                        return;
                    }
                }
            }
            if !open && line.is_empty() {
                // Dropping req_tx closes our side of the stream.
                return;
            }
        }
    });
    let mut client = pb::control_service_client::ControlServiceClient::new(channel);
    let mut req = tonic::Request::new(tokio_stream::wrappers::ReceiverStream::new(req_rx));
    req.metadata_mut().insert("authorization", auth);
    let what = format!("--server {} session {}", cfg.url, cfg.session_id);
    let mut responses = client.control(req).await.map_err(|s| anyhow!("{what}: Control: {} ({:?})", s.message(), s.code()))?.into_inner();
    // Incoming delay line: each response is published at its arrival + half.
    let mut line: VecDeque<(Instant, pb::ControlResponse)> = VecDeque::new();
    let mut counter = 0u64;
    let mut stiffness = [0.0; 9];
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
                    counter += 1;
                    let sample = sample_from_response(&r, stiffness);
                    stiffness = planar_stiffness_of(&r).unwrap_or(stiffness);
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
