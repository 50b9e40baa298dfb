//! The live Foxglove endpoint: a Foxglove WebSocket server on its own port (the Foxglove app
//! connects to `ws://host:port`), with a scene and a force channel per session. Logging to a
//! channel nobody subscribed to costs a flag read. The server ([`crate::ws`]) bounds what a client
//! can hold (issue 35): connections, the handshake's time, and the messages waiting for a slow
//! client — the latest scene and the last [`FORCE_KEEP`] force samples; older ones are dropped and
//! counted ([`LiveStats`]).
//!
//! No access control: Foxglove's WebSocket protocol carries no tokens, so the endpoint binds to
//! the loopback interface unless the operator says otherwise (the server's `--foxglove-addr`).
use std::sync::Arc;

use foxglove::Encode;
use foxglove::messages::SceneUpdate;
use tokio::sync::watch;

use crate::scene::{FORCE_SCHEMA_JSON, FORCE_SCHEMA_NAME, ForceSample};
use crate::ws::{ChannelInfo, Hub};
pub use crate::ws::{LiveOptions, LiveStats};
use crate::{force_topic, scene_topic};

/// Scenes kept per slow client: a newer scene replaces an unsent one.
pub const SCENE_KEEP: usize = 1;
/// Force samples kept per slow client before the oldest is dropped (160 ms at 100 Hz).
pub const FORCE_KEEP: usize = 16;

/// What goes wrong starting the endpoint or opening a session's channels.
#[derive(Debug, thiserror::Error)]
pub enum LiveError {
    /// When the WebSocket server cannot start (the port is taken, the address is not local).
    #[error("the Foxglove endpoint could not start on {addr}: {source}")]
    Start { addr: String, source: std::io::Error },
    /// When a message type has no schema to advertise (not expected: Foxglove's messages have).
    #[error("the Foxglove channel {topic} could not be opened: its message type has no schema")]
    Channel { topic: String },
}

/// The endpoint: its server's shared state and the signal that stops its tasks.
pub struct FoxgloveLive {
    hub: Arc<Hub>,
    port: u16,
    stop: watch::Sender<bool>,
}

impl std::fmt::Debug for FoxgloveLive {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FoxgloveLive").field("port", &self.port).finish()
    }
}

impl FoxgloveLive {
    /// Starts the WebSocket server on `host:port` (port 0: any free port) on the caller's tokio
    /// runtime, with the bounds of `opts`.
    pub async fn start(host: &str, port: u16, name: &str, opts: LiveOptions) -> Result<Self, LiveError> {
        let addr = format!("{host}:{port}");
        let listener =
            tokio::net::TcpListener::bind((host, port)).await.map_err(|source| LiveError::Start { addr: addr.clone(), source })?;
        let port = listener.local_addr().map_err(|source| LiveError::Start { addr, source })?.port();
        let hub = Arc::new(Hub::new(name, opts));
        let (stop, stopped) = watch::channel(false);
        tokio::spawn(crate::ws::serve(hub.clone(), listener, stopped));
        Ok(Self { hub, port, stop })
    }

    /// The port the endpoint listens on.
    pub fn port(&self) -> u16 {
        self.port
    }

    /// The endpoint's counters and present load.
    pub fn stats(&self) -> LiveStats {
        self.hub.stats()
    }

    /// Opens the channels of a session (closed when the returned value is dropped). Session ids
    /// are unique, so their topics are too.
    ///
    /// Errors: [`LiveError::Channel`] if a message type has no schema.
    pub fn open_session(&self, session: &str) -> Result<SessionChannels, LiveError> {
        let schema = SceneUpdate::get_schema().ok_or_else(|| LiveError::Channel { topic: scene_topic(session) })?;
        let scene = self.hub.add_channel(
            scene_topic(session),
            &SceneUpdate::get_message_encoding(),
            &schema.name,
            &schema.encoding,
            &schema.data,
            SCENE_KEEP,
        );
        let force =
            self.hub.add_channel(force_topic(session), "json", FORCE_SCHEMA_NAME, "jsonschema", FORCE_SCHEMA_JSON.as_bytes(), FORCE_KEEP);
        Ok(SessionChannels { hub: self.hub.clone(), scene, force })
    }
}

impl Drop for FoxgloveLive {
    fn drop(&mut self) {
        // Stops accepting and closes the clients.
        let _ = self.stop.send(true);
    }
}

/// A session's two channels on the endpoint.
pub struct SessionChannels {
    hub: Arc<Hub>,
    scene: Arc<ChannelInfo>,
    force: Arc<ChannelInfo>,
}

impl SessionChannels {
    /// Whether a client subscribed to the scene (build the update only then).
    pub fn wants_scene(&self) -> bool {
        self.scene.has_subscribers()
    }

    /// Whether a client subscribed to the force.
    pub fn wants_force(&self) -> bool {
        self.force.has_subscribers()
    }

    pub fn log_scene(&self, time_ns: u64, update: &SceneUpdate) {
        if !self.wants_scene() {
            return;
        }
        let mut buf = Vec::with_capacity(update.encoded_len().unwrap_or(1024));
        if update.encode(&mut buf).is_ok() {
            self.hub.log(&self.scene, time_ns, &buf);
        }
    }

    pub fn log_force(&self, time_ns: u64, sample: &ForceSample) {
        self.hub.log(&self.force, time_ns, &sample.to_json());
    }
}

impl Drop for SessionChannels {
    fn drop(&mut self) {
        self.hub.remove_channel(self.scene.id);
        self.hub.remove_channel(self.force.id);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{SceneFrame, scene_update};
    use futures_util::{SinkExt, StreamExt};
    use prost::Message as _;
    use tokio_tungstenite::tungstenite::{Message, client::IntoClientRequest};

    /// A Foxglove WebSocket client (the ws-protocol spec: advertise, subscribe, binary
    /// messageData = opcode 1, subscription id u32, log time u64, payload) sees a session's scene
    /// and force messages.
    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn a_foxglove_client_subscribes_and_receives_the_scene_and_the_force() {
        let live = FoxgloveLive::start("127.0.0.1", 0, "needlesim-test", LiveOptions::default()).await.unwrap();
        let session = live.open_session("abc").unwrap();
        let mut req = format!("ws://127.0.0.1:{}", live.port()).into_client_request().unwrap();
        req.headers_mut().insert("sec-websocket-protocol", "foxglove.sdk.v1".parse().unwrap());
        let (mut ws, _) = tokio_tungstenite::connect_async(req).await.unwrap();
        // Read the advertisement of both channels.
        let mut ids = std::collections::BTreeMap::new();
        while ids.len() < 2 {
            let Some(Ok(Message::Text(t))) = ws.next().await else { continue };
            let v: serde_json::Value = serde_json::from_str(&t).unwrap();
            if v["op"] == "advertise" {
                for c in v["channels"].as_array().unwrap() {
                    ids.insert(c["topic"].as_str().unwrap().to_owned(), (c["id"].as_u64().unwrap(), c["schemaName"].clone()));
                }
            }
        }
        assert_eq!(ids["/needlesim/abc/scene"].1, "foxglove.SceneUpdate");
        assert_eq!(ids["/needlesim/abc/force"].1, FORCE_SCHEMA_NAME);
        let subs = serde_json::json!({"op": "subscribe", "subscriptions": [
            {"id": 1, "channelId": ids["/needlesim/abc/scene"].0}, {"id": 2, "channelId": ids["/needlesim/abc/force"].0}]});
        ws.send(Message::Text(subs.to_string().into())).await.unwrap();
        // Log until the subscriptions are in place and one message of each arrived.
        let needle = [[0.0, 0.0, 0.1], [0.0, 0.0, 0.04]];
        let frame = SceneFrame { time_ns: 5, surface_displacement_m: None, needle_m: &needle, points: &[], targets: &[] };
        let (mut got_scene, mut got_force) = (false, false);
        let deadline = tokio::time::Instant::now() + std::time::Duration::from_secs(20);
        while !(got_scene && got_force) {
            assert!(tokio::time::Instant::now() < deadline, "no messages within 20 s");
            if session.wants_scene() {
                session.log_scene(5, &scene_update(None, &frame, 0.0));
            }
            if session.wants_force() {
                let s = ForceSample { time_s: 5e-9, depth_m: 0.06, force_n: [0.0, 0.0, 0.7].into(), torque_nm: [0.0; 3].into() };
                session.log_force(5, &s);
            }
            let Ok(Some(Ok(msg))) = tokio::time::timeout(std::time::Duration::from_millis(50), ws.next()).await else { continue };
            let Message::Binary(b) = msg else { continue };
            assert_eq!(b[0], 1, "messageData opcode");
            let sub = u32::from_le_bytes(b[1..5].try_into().unwrap());
            assert_eq!(u64::from_le_bytes(b[5..13].try_into().unwrap()), 5, "the log time is the simulation's");
            let payload = &b[13..];
            match sub {
                1 => {
                    let up = SceneUpdate::decode(payload).unwrap();
                    assert_eq!(up.entities[0].lines[0].points[1].z, 0.04);
                    got_scene = true;
                }
                2 => {
                    let v: serde_json::Value = serde_json::from_slice(payload).unwrap();
                    assert_eq!(v["force_n"]["z"], 0.7);
                    got_force = true;
                }
                other => panic!("unknown subscription {other}"),
            }
        }
        drop(session);
    }
}
