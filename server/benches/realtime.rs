//! Real-time server benchmark: a session at 1 kHz driven through the gRPC control stream on
//! loopback, with 0, 10 and 100 rendering observers (60 Hz) attached. Reports tick compute time
//! and start lateness (p50, p99, p99.9) from the session's histograms, missed deadlines, and the
//! loopback latency from a pose sent to the force computed from it received back. The tick
//! histograms cover the whole case; the latency excludes its first second.
//! Run: `cargo bench -p needlesim-server --bench realtime`.

use std::time::{Duration, Instant};

use needlesim_proto::v1 as pb;
use needlesim_server::grpc::ServerLimits;
use needlesim_server::serve::{ServeConfig, serve};
use tokio_stream::StreamExt;
use tonic::metadata::MetadataValue;

fn with_token<T>(msg: T, token: &str) -> tonic::Request<T> {
    let mut r = tonic::Request::new(msg);
    r.metadata_mut().insert("authorization", MetadataValue::try_from(format!("Bearer {token}")).unwrap());
    r
}

fn pct(v: &mut [f64], q: f64) -> f64 {
    v.sort_by(f64::total_cmp);
    v[((v.len() - 1) as f64 * q).round() as usize]
}

async fn run_case(ch: tonic::transport::Channel, n_observers: usize, secs: f64) -> String {
    let mut sessions = pb::session_service_client::SessionServiceClient::new(ch.clone());
    let created = sessions
        .create_session(pb::CreateSessionRequest {
            scene: Some(pb::SceneSource { source: Some(pb::scene_source::Source::Example("paper-phantom".into())) }),
            tick_rate_hz: 1000.0,
            record: false,
            device_channel: false,
        })
        .await
        .unwrap()
        .into_inner();
    let sid = created.session.unwrap().session_id;
    let (ctl, obs) = (created.controller_token, created.observer_token);
    let mut observers = Vec::new();
    for _ in 0..n_observers {
        let req = with_token(pb::ObserveRequest { session_id: sid.clone(), rate_hz: 60.0, include_displacements: false }, &obs);
        let ch = ch.clone();
        observers.push(tokio::spawn(async move {
            let mut s = pb::observe_service_client::ObserveServiceClient::new(ch).observe(req).await.unwrap().into_inner();
            let mut n = 0u64;
            while let Some(Ok(_)) = s.next().await {
                n += 1;
            }
            n
        }));
    }
    let (tx, rx) = tokio::sync::mpsc::channel::<pb::ControlRequest>(64);
    let epoch = Instant::now();
    let pose = move |t: f64| pb::Pose2 { x_m: 0.05, y_m: 0.205 - 0.04 * (t / secs).min(1.0), theta_rad: -std::f64::consts::FRAC_PI_2 };
    tx.send(pb::ControlRequest {
        session_id: sid.clone(),
        base: Some(pose(0.0)),
        client_time_ns: 1,
        seq: 1,
        flip_bevel: false,
        take_over: false,
    })
    .await
    .unwrap();
    let mut responses = pb::control_service_client::ControlServiceClient::new(ch.clone())
        .control(with_token(tokio_stream::wrappers::ReceiverStream::new(rx), &ctl))
        .await
        .unwrap()
        .into_inner();
    let sender = tokio::spawn(async move {
        let mut interval = tokio::time::interval(Duration::from_millis(1));
        let mut seq = 1;
        while epoch.elapsed().as_secs_f64() < secs {
            interval.tick().await;
            seq += 1;
            let t = epoch.elapsed();
            let m = pb::ControlRequest {
                session_id: String::new(),
                base: Some(pose(t.as_secs_f64())),
                client_time_ns: t.as_nanos() as u64,
                seq,
                flip_bevel: false,
                take_over: false,
            };
            if tx.send(m).await.is_err() {
                break;
            }
        }
    });
    let mut latencies = Vec::new();
    let mut last_seen = 0;
    let warm = Duration::from_secs(1);
    let end = Instant::now() + Duration::from_secs_f64(secs);
    while let Ok(Some(Ok(r))) = tokio::time::timeout_at(end.into(), responses.next()).await {
        if r.client_time_ns != last_seen && r.client_time_ns > 1 {
            last_seen = r.client_time_ns;
            if epoch.elapsed() > warm {
                latencies.push((epoch.elapsed().as_nanos() as u64 - r.client_time_ns) as f64 / 1e3);
            }
        }
    }
    let _ = sender.await;
    let st = sessions.get_stats(with_token(pb::GetSessionRequest { session_id: sid.clone() }, &obs)).await.unwrap().into_inner();
    sessions.close_session(with_token(pb::CloseSessionRequest { session_id: sid }, &ctl)).await.unwrap();
    let mut frames = Vec::new();
    for o in observers {
        frames.push(o.await.unwrap());
    }
    let min_frames = frames.iter().min().copied().unwrap_or(0);
    format!(
        "| {n_observers} | {} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {} | {:.0} | {:.0} | {:.0} | {} |",
        st.ticks,
        st.compute_p50_us,
        st.compute_p99_us,
        st.compute_p999_us,
        st.lateness_p50_us,
        st.lateness_p99_us,
        st.lateness_p999_us,
        st.missed_deadlines,
        pct(&mut latencies, 0.5),
        pct(&mut latencies, 0.99),
        pct(&mut latencies, 0.999),
        if n_observers == 0 { "-".to_owned() } else { min_frames.to_string() }
    )
}

fn main() {
    let secs: f64 = std::env::args().skip(1).find_map(|a| a.parse().ok()).unwrap_or(6.0);
    let port = std::net::TcpListener::bind("127.0.0.1:0").unwrap().local_addr().unwrap().port();
    let data = std::env::temp_dir().join(format!("needlesim-bench-{}", std::process::id()));
    let config = ServeConfig {
        listen: format!("127.0.0.1:{port}").parse().unwrap(),
        data_dir: data.clone(),
        web_dir: data.clone(),
        tls: None,
        limits: ServerLimits::default(),
        max_message_bytes: 4 << 20,
        default_scene: None,
        demo: false,
        admin_token: None,
    };
    let rt = tokio::runtime::Builder::new_multi_thread().enable_all().build().unwrap();
    let (stop_tx, stop_rx) = tokio::sync::oneshot::channel::<()>();
    let server = rt.spawn(serve(config, async move {
        let _ = stop_rx.await;
    }));
    println!(
        "machine: {}; server and clients in one process on loopback; {secs} s per case, first 1 s excluded from latency",
        needlesim_lab::bench::machine()
    );
    println!();
    println!(
        "| observers (60 Hz) | ticks | compute p50 µs | p99 | p99.9 | lateness p50 µs | p99 | p99.9 | missed deadlines | pose→force p50 µs | p99 | p99.9 | min frames/observer |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    rt.block_on(async {
        tokio::time::sleep(Duration::from_millis(300)).await;
        let ch = tonic::transport::Channel::from_shared(format!("http://127.0.0.1:{port}")).unwrap().connect().await.unwrap();
        for n in [0, 10, 100] {
            println!("{}", run_case(ch.clone(), n, secs).await);
        }
    });
    let _ = stop_tx.send(());
    let _ = rt.block_on(server);
    let _ = std::fs::remove_dir_all(data);
}
