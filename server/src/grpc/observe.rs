//! `ObserveService`: every tick (or the exact count missed), or the latest frame at the
//! client's rate with the displacement field on request; a slow observer only slows itself.

use std::time::Duration;

use std::sync::Arc;
use std::sync::atomic::Ordering;

use needlesim_proto::v1 as pb;
use tokio::sync::mpsc;
use tokio_stream::wrappers::ReceiverStream;
use tonic::{Request, Response, Status};

use needlesim_session::Session;

use super::{Api, BoxStream, Role, authorize};
use crate::convert;

/// Counts an observer for as long as it lives.
struct ObserverGuard {
    session: Arc<Session>,
    wants_field: bool,
}

impl Drop for ObserverGuard {
    fn drop(&mut self) {
        self.session.n_observers.fetch_sub(1, Ordering::Relaxed);
        if self.wants_field {
            self.session.field_subscribers.fetch_sub(1, Ordering::Relaxed);
        }
    }
}

#[tonic::async_trait]
impl pb::observe_service_server::ObserveService for Api {
    type ObserveStream = BoxStream<pb::Frame>;

    async fn observe(&self, req: Request<pb::ObserveRequest>) -> Result<Response<Self::ObserveStream>, Status> {
        let s = self.state.session(&req.get_ref().session_id)?;
        authorize(&req, &s, Role::Observer)?;
        let r = req.into_inner();
        if !(r.rate_hz.is_finite() && r.rate_hz >= 0.0 && r.rate_hz <= s.tick_rate_hz) {
            return Err(Status::invalid_argument(format!(
                "rate_hz = {}: 0 (every tick) or up to the tick rate {} Hz",
                r.rate_hz, s.tick_rate_hz
            )));
        }
        // Checked and counted in one step: concurrent observers never exceed the limit.
        let max = self.state.limits.max_observers_per_session as u64;
        if s.n_observers.fetch_update(Ordering::AcqRel, Ordering::Acquire, |n| (n < max).then_some(n + 1)).is_err() {
            return Err(Status::resource_exhausted(format!(
                "session {} has its limit of {} observers",
                s.id, self.state.limits.max_observers_per_session
            )));
        }
        if r.include_displacements {
            s.field_subscribers.fetch_add(1, Ordering::Relaxed);
        }
        let guard = ObserverGuard { session: s.clone(), wants_field: r.include_displacements };
        let (tx, rx) = mpsc::channel(64);
        if r.rate_hz == 0.0 {
            // Every tick, or an exact count of the ticks this stream missed.
            let mut ticks = s.all_ticks.subscribe();
            tokio::spawn(async move {
                let _guard = guard;
                let names = _guard.session.target_names.clone();
                let mut missed = 0u64;
                loop {
                    match ticks.recv().await {
                        Ok(rec) => {
                            if tx.send(Ok(convert::frame_from_record(&rec, &names, missed))).await.is_err() {
                                return;
                            }
                            missed = 0;
                        }
                        Err(tokio::sync::broadcast::error::RecvError::Lagged(n)) => missed += n,
                        Err(tokio::sync::broadcast::error::RecvError::Closed) => return,
                    }
                }
            });
        } else {
            // Rendering: the latest frame at the requested rate; a slow client only slows itself.
            let period = Duration::from_secs_f64(1.0 / r.rate_hz);
            let mut latest = s.latest.clone();
            let mut field = s.field.clone();
            tokio::spawn(async move {
                let _guard = guard;
                let names = _guard.session.target_names.clone();
                let mut interval = tokio::time::interval(period);
                interval.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Skip);
                let mut last_tick = u64::MAX;
                loop {
                    interval.tick().await;
                    match latest.has_changed() {
                        Err(_) => return,
                        // Until the session's first tick the slot holds a placeholder record
                        // (tick 0, zero pose), not a state of the session: send nothing yet.
                        Ok(false) if last_tick == u64::MAX => continue,
                        Ok(_) => {}
                    }
                    let rec = latest.borrow_and_update().clone();
                    if rec.tick == last_tick {
                        continue;
                    }
                    last_tick = rec.tick;
                    let mut frame = convert::frame_from_record(&rec, &names, 0);
                    if r.include_displacements {
                        let u = field.borrow_and_update().displacement_m.clone();
                        if rec.dimension == 3 {
                            frame.surface_displacement_m = u;
                        } else {
                            frame.node_displacement_m = u;
                        }
                    }
                    if tx.send(Ok(frame)).await.is_err() {
                        return;
                    }
                }
            });
        }
        Ok(Response::new(Box::pin(ReceiverStream::new(rx))))
    }
}
