//! `ObserveService`: every tick (or the exact count missed), or the latest frame at the
//! client's rate with the displacement field on request; a slow observer only slows itself.
//! The streams are pulled (issue 35): a frame is made only when the client's connection takes
//! one, so a reader that stops holds no queue of frames — the every-tick stream counts what it
//! missed from the session's shared broadcast, the rate stream skips to the latest record.
//! Both end when the session closes (`streams::of_session`).

use std::time::Duration;

use std::sync::Arc;
use std::sync::atomic::Ordering;

use futures_util::stream;
use needlesim_proto::v1 as pb;
use tonic::{Request, Response, Status};

use needlesim_session::Session;

use super::{Api, BoxStream, Role, StreamPermit, authorize};
use crate::convert;

/// Counts an observer for as long as its stream lives.
struct ObserverGuard {
    session: Arc<Session>,
    wants_field: bool,
    _permit: StreamPermit,
}

impl Drop for ObserverGuard {
    fn drop(&mut self) {
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
                needlesim_core::num::num(r.rate_hz),
                needlesim_core::num::num(s.tick_rate_hz)
            )));
        }
        // Checked and counted in one step: concurrent streams never exceed the limits.
        let permit = self.state.admit_stream(Some(&s), "Observe")?;
        if r.include_displacements {
            s.field_subscribers.fetch_add(1, Ordering::Relaxed);
        }
        let guard = ObserverGuard { session: s.clone(), wants_field: r.include_displacements, _permit: permit };
        let names = s.target_names.clone();
        if r.rate_hz == 0.0 {
            // Every tick, or an exact count of the ticks this stream missed.
            struct EveryTick {
                ticks: tokio::sync::broadcast::Receiver<Arc<needlesim_session::TickRecord>>,
                names: Vec<String>,
                _guard: ObserverGuard,
            }
            let st = EveryTick { ticks: s.all_ticks.subscribe(), names, _guard: guard };
            let frames = stream::unfold(st, |mut st| async move {
                let mut missed = 0u64;
                loop {
                    match st.ticks.recv().await {
                        Ok(rec) => {
                            let frame = convert::frame_from_record(&rec, &st.names, missed);
                            return Some((Ok(frame), st));
                        }
                        Err(tokio::sync::broadcast::error::RecvError::Lagged(n)) => missed += n,
                        Err(tokio::sync::broadcast::error::RecvError::Closed) => return None,
                    }
                }
            });
            return Ok(Response::new(super::streams::of_session(&s, Box::pin(frames))));
        }
        // Rendering: the latest frame at the requested rate; a slow client only slows itself.
        let period = Duration::from_secs_f64(1.0 / r.rate_hz);
        let mut interval = tokio::time::interval(period);
        interval.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Skip);
        struct Latest {
            latest: tokio::sync::watch::Receiver<Arc<needlesim_session::TickRecord>>,
            field: tokio::sync::watch::Receiver<Arc<needlesim_session::Field>>,
            interval: tokio::time::Interval,
            last_tick: u64,
            include_displacements: bool,
            names: Vec<String>,
            _guard: ObserverGuard,
        }
        let st = Latest {
            latest: s.latest.clone(),
            field: s.field.clone(),
            interval,
            last_tick: u64::MAX,
            include_displacements: r.include_displacements,
            names,
            _guard: guard,
        };
        let frames = stream::unfold(st, |mut st| async move {
            loop {
                st.interval.tick().await;
                match st.latest.has_changed() {
                    Err(_) => return None,
                    // Until the session's first tick the slot holds a placeholder record
                    // (tick 0, zero pose), not a state of the session: send nothing yet.
                    Ok(false) if st.last_tick == u64::MAX => continue,
                    Ok(_) => {}
                }
                let rec = st.latest.borrow_and_update().clone();
                if rec.tick == st.last_tick {
                    continue;
                }
                st.last_tick = rec.tick;
                let mut frame = convert::frame_from_record(&rec, &st.names, 0);
                if st.include_displacements {
                    let u = st.field.borrow_and_update().displacement_m.clone();
                    if rec.dimension == 3 {
                        frame.surface_displacement_m = u;
                    } else {
                        frame.node_displacement_m = u;
                    }
                }
                return Some((Ok(frame), st));
            }
        });
        Ok(Response::new(super::streams::of_session(&s, Box::pin(frames))))
    }
}
