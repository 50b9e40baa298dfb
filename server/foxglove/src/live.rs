//! The live Foxglove endpoint: the Foxglove SDK's WebSocket server on its own port (the Foxglove
//! app connects to `ws://host:port`), with a scene and a force channel per session. Logging to a
//! channel nobody subscribed to costs a flag read; the SDK's server drops messages for a slow
//! client rather than queueing without bound (`message_backlog_size`).
//!
//! No access control: Foxglove's WebSocket protocol carries no tokens, so the endpoint binds to
//! the loopback interface unless the operator says otherwise (the server's `--foxglove-addr`).
use std::sync::Arc;

use foxglove::messages::SceneUpdate;
use foxglove::{Channel, Context, RawChannel, Schema, WebSocketServer, WebSocketServerHandle};

use crate::scene::{FORCE_SCHEMA_JSON, FORCE_SCHEMA_NAME, ForceSample};
use crate::{force_topic, scene_topic};

/// Messages kept per client before the oldest are dropped (about 2 s of scenes at 30 Hz and
/// forces at 100 Hz).
pub const CLIENT_BACKLOG: usize = 256;

/// What goes wrong starting the endpoint or opening a session's channels.
#[derive(Debug, thiserror::Error)]
pub enum LiveError {
    /// When the WebSocket server cannot start (the port is taken, the address is not local).
    #[error("the Foxglove endpoint could not start on {addr}: {source}")]
    Start { addr: String, source: foxglove::FoxgloveError },
    /// When the SDK refuses a session's channel (it checks only that a message encoding is set).
    #[error("the Foxglove channel {topic} could not be opened: {source}")]
    Channel { topic: String, source: foxglove::FoxgloveError },
}

/// The endpoint: one SDK context (so channels never mix with another endpoint's) and its server.
pub struct FoxgloveLive {
    ctx: Arc<Context>,
    handle: Option<WebSocketServerHandle>,
}

impl std::fmt::Debug for FoxgloveLive {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FoxgloveLive").field("port", &self.port()).finish()
    }
}

impl FoxgloveLive {
    /// Starts the WebSocket server on `host:port` (port 0: any free port) on the caller's tokio
    /// runtime.
    pub async fn start(host: &str, port: u16, name: &str) -> Result<Self, LiveError> {
        let ctx = Context::new();
        let handle = WebSocketServer::new()
            .name(name)
            .bind(host, port)
            .context(&ctx)
            .message_backlog_size(CLIENT_BACKLOG)
            .start()
            .await
            .map_err(|source| LiveError::Start { addr: format!("{host}:{port}"), source })?;
        Ok(Self { ctx, handle: Some(handle) })
    }

    /// The port the endpoint listens on.
    pub fn port(&self) -> u16 {
        self.handle.as_ref().map_or(0, WebSocketServerHandle::port)
    }

    /// Opens the channels of a session (closed when the returned value is dropped). Session ids
    /// are unique, so their topics are too.
    ///
    /// Errors: [`LiveError::Channel`] if the SDK refuses the channel.
    pub fn open_session(&self, session: &str) -> Result<SessionChannels, LiveError> {
        let scene: Channel<SceneUpdate> = self.ctx.channel_builder(scene_topic(session)).build();
        let force = self
            .ctx
            .channel_builder(force_topic(session))
            .message_encoding("json")
            .schema(Schema::new(FORCE_SCHEMA_NAME, "jsonschema", FORCE_SCHEMA_JSON.as_bytes().to_vec()))
            .build_raw();
        let force = force.map_err(|source| LiveError::Channel { topic: force_topic(session), source })?;
        Ok(SessionChannels { scene, force })
    }
}

impl Drop for FoxgloveLive {
    fn drop(&mut self) {
        if let Some(h) = self.handle.take() {
            // Stops accepting and closes the clients; the returned handle only waits for that.
            drop(h.stop());
        }
    }
}

/// A session's two channels on the endpoint.
pub struct SessionChannels {
    scene: Channel<SceneUpdate>,
    force: Arc<RawChannel>,
}

impl SessionChannels {
    /// Whether a client subscribed to the scene (build the update only then).
    pub fn wants_scene(&self) -> bool {
        self.scene.has_sinks()
    }

    /// Whether a client subscribed to the force.
    pub fn wants_force(&self) -> bool {
        self.force.has_sinks()
    }

    pub fn log_scene(&self, time_ns: u64, update: &SceneUpdate) {
        self.scene.log_with_time(update, time_ns);
    }

    pub fn log_force(&self, time_ns: u64, sample: &ForceSample) {
        self.force.log_with_meta(&sample.to_json(), foxglove::PartialMetadata { log_time: Some(time_ns) });
    }
}

impl Drop for SessionChannels {
    fn drop(&mut self) {
        self.scene.close();
        self.force.close();
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
        let live = FoxgloveLive::start("127.0.0.1", 0, "needlesim-test").await.unwrap();
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
