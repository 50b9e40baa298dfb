//! The Foxglove WebSocket server behind [`crate::FoxgloveLive`]: the ws-protocol's server side
//! (`serverInfo`, `advertise`, `unadvertise`; the client's `subscribe` and `unsubscribe`; binary
//! `messageData`) on tokio-tungstenite, with every resource a client can hold bounded (issue 35):
//!
//! - **Connections**: at most `max_clients` at once, counted from the TCP accept (a connection
//!   over the bound is closed at once); a connection that has not completed its WebSocket
//!   handshake within `handshake_timeout` is closed.
//! - **Memory per client**: the messages waiting for a client are held per channel, at most the
//!   channel's `keep` (1 for a scene: a newer scene replaces an unsent one; a few for the force
//!   samples); an older one is dropped and counted. Control messages (advertisements) are bounded
//!   too: a client that lets [`MAX_CONTROL_QUEUE`] of them pile up is closed.
//! - **Stalled clients**: a client whose socket accepts no message for `stall_timeout` is closed.
//!
//! One message is encoded once per client (its subscription id is in the frame's header) and the
//! socket is written one message at a time, so a client that never reads costs its queue (about
//! one scene) and the kernel's socket buffers, nothing more.
use std::collections::{BTreeMap, HashMap, VecDeque};
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, RwLock};
use std::time::Duration;

use futures_util::{SinkExt, StreamExt};
use tokio::net::{TcpListener, TcpStream};
use tokio::sync::{Notify, OwnedSemaphorePermit, Semaphore, watch};
use tokio_tungstenite::tungstenite::handshake::server::{ErrorResponse, Request, Response};
use tokio_tungstenite::tungstenite::protocol::WebSocketConfig;
use tokio_tungstenite::tungstenite::{Bytes, Message};

/// The subprotocols the server speaks (the Foxglove SDK's name and the older ws-protocol name;
/// the messages used here are the same in both).
const SUBPROTOCOLS: [&str; 2] = ["foxglove.sdk.v1", "foxglove.websocket.v1"];
/// Control messages (advertisements) waiting for one client before it is closed.
pub const MAX_CONTROL_QUEUE: usize = 64;
/// The largest message a client may send, bytes (subscribe and unsubscribe are small JSON).
const MAX_CLIENT_MESSAGE_BYTES: usize = 64 << 10;
/// Subscriptions one client may hold (a session has two channels).
const MAX_SUBSCRIPTIONS: usize = 4096;

/// The endpoint's bounds.
#[derive(Clone, Copy, Debug)]
pub struct LiveOptions {
    /// Connections at once (with or without a completed handshake); more are closed at once.
    pub max_clients: usize,
    /// A connection's WebSocket handshake must be done within this.
    pub handshake_timeout: Duration,
    /// A client whose socket takes no message for this long is closed.
    pub stall_timeout: Duration,
}

impl Default for LiveOptions {
    fn default() -> Self {
        Self { max_clients: 64, handshake_timeout: Duration::from_secs(5), stall_timeout: Duration::from_secs(20) }
    }
}

/// The endpoint's counters (since start) and its present load.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LiveStats {
    /// Connections open now (with or without a completed handshake).
    pub connections: u64,
    /// Clients that completed the handshake and are connected now.
    pub clients: u64,
    /// Connections closed at once because `max_clients` were open.
    pub refused_connections: u64,
    /// Connections closed without a handshake (too slow, or not a Foxglove WebSocket request).
    pub failed_handshakes: u64,
    /// Messages dropped for slow clients (a newer one of the same channel replaced them).
    pub dropped_messages: u64,
    /// Clients closed because they did not read (stalled socket or too many control messages).
    pub stalled_clients: u64,
    /// The most messages waiting for any one client now.
    pub queued_messages_max: u64,
    /// The bytes waiting for all clients now.
    pub queued_bytes: u64,
}

#[derive(Default)]
struct Counters {
    connections: AtomicU64,
    clients: AtomicU64,
    refused: AtomicU64,
    failed_handshakes: AtomicU64,
    dropped: AtomicU64,
    stalled: AtomicU64,
}

/// An advertised channel.
pub(crate) struct ChannelInfo {
    pub(crate) id: u64,
    topic: String,
    encoding: String,
    schema_name: String,
    schema_encoding: String,
    /// The schema as the protocol carries it (base64 for binary schemas).
    schema: String,
    /// Messages kept per client before the oldest is dropped.
    keep: usize,
    subscribers: AtomicUsize,
}

impl ChannelInfo {
    pub(crate) fn has_subscribers(&self) -> bool {
        self.subscribers.load(Ordering::Relaxed) > 0
    }

    fn advertisement(&self) -> serde_json::Value {
        serde_json::json!({
            "id": self.id, "topic": self.topic, "encoding": self.encoding, "schemaName": self.schema_name,
            "schemaEncoding": self.schema_encoding, "schema": self.schema,
        })
    }
}

/// What waits for one client.
#[derive(Default)]
struct Outbox {
    /// Channel id → the client's subscription id.
    subs: HashMap<u64, u32>,
    control: VecDeque<Message>,
    data: VecDeque<(u64, Message)>,
    /// Messages of each channel in `data`.
    per_channel: HashMap<u64, usize>,
    bytes: usize,
    /// Set when the client must be closed (its control queue overflowed).
    overflowed: bool,
}

impl Outbox {
    fn push_control(&mut self, m: Message) {
        if self.control.len() >= MAX_CONTROL_QUEUE {
            self.overflowed = true;
            return;
        }
        self.bytes += m.len();
        self.control.push_back(m);
    }

    /// Queues `m` of channel `ch`, dropping the oldest of that channel beyond `keep`: the number
    /// dropped.
    fn push_data(&mut self, ch: u64, keep: usize, m: Message) -> u64 {
        let mut dropped = 0;
        let n = self.per_channel.entry(ch).or_default();
        if *n >= keep.max(1)
            && let Some(i) = self.data.iter().position(|(c, _)| *c == ch)
        {
            let (_, old) = self.data.remove(i).expect("a position in the queue");
            self.bytes -= old.len();
            *n -= 1;
            dropped = 1;
        }
        *n += 1;
        self.bytes += m.len();
        self.data.push_back((ch, m));
        dropped
    }

    /// Forgets the subscription to `ch` and its waiting messages: whether there was one.
    fn drop_channel(&mut self, ch: u64) -> bool {
        let had = self.subs.remove(&ch).is_some();
        if self.per_channel.remove(&ch).is_some() {
            let mut freed = 0;
            self.data.retain(|(c, m)| {
                let keep = *c != ch;
                if !keep {
                    freed += m.len();
                }
                keep
            });
            self.bytes -= freed;
        }
        had
    }

    fn pop(&mut self) -> Option<Message> {
        let m = if let Some(m) = self.control.pop_front() {
            m
        } else {
            let (ch, m) = self.data.pop_front()?;
            if let Some(n) = self.per_channel.get_mut(&ch) {
                *n -= 1;
                if *n == 0 {
                    self.per_channel.remove(&ch);
                }
            }
            m
        };
        self.bytes -= m.len();
        Some(m)
    }
}

struct Client {
    id: u64,
    outbox: Mutex<Outbox>,
    wake: Notify,
}

/// The server's state shared by its tasks and the session channels.
pub(crate) struct Hub {
    name: String,
    session_id: String,
    opts: LiveOptions,
    next_channel: AtomicU64,
    next_client: AtomicU64,
    /// Lock order: `clients`, then `channels`, then a client's outbox.
    clients: Mutex<Vec<Arc<Client>>>,
    channels: RwLock<BTreeMap<u64, Arc<ChannelInfo>>>,
    counters: Counters,
}

fn text(v: &serde_json::Value) -> Message {
    Message::Text(v.to_string().into())
}

impl Hub {
    pub(crate) fn new(name: &str, opts: LiveOptions) -> Self {
        let started = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_millis());
        Self {
            name: name.to_owned(),
            session_id: started.to_string(),
            opts,
            next_channel: AtomicU64::new(1),
            next_client: AtomicU64::new(1),
            clients: Mutex::default(),
            channels: RwLock::default(),
            counters: Counters::default(),
        }
    }

    /// Adds a channel and advertises it to every client.
    pub(crate) fn add_channel(
        &self,
        topic: String,
        encoding: &str,
        schema_name: &str,
        schema_encoding: &str,
        schema: &[u8],
        keep: usize,
    ) -> Arc<ChannelInfo> {
        use base64::Engine as _;
        let schema = if matches!(schema_encoding, "protobuf" | "flatbuffer") {
            base64::engine::general_purpose::STANDARD.encode(schema)
        } else {
            String::from_utf8_lossy(schema).into_owned()
        };
        let ch = Arc::new(ChannelInfo {
            id: self.next_channel.fetch_add(1, Ordering::Relaxed),
            topic,
            encoding: encoding.to_owned(),
            schema_name: schema_name.to_owned(),
            schema_encoding: schema_encoding.to_owned(),
            schema,
            keep,
            subscribers: AtomicUsize::new(0),
        });
        let clients = self.clients.lock().expect("clients lock");
        self.channels.write().expect("channels lock").insert(ch.id, ch.clone());
        let adv = text(&serde_json::json!({"op": "advertise", "channels": [ch.advertisement()]}));
        for c in clients.iter() {
            c.outbox.lock().expect("outbox lock").push_control(adv.clone());
            c.wake.notify_one();
        }
        ch
    }

    /// Removes a channel: its subscriptions and waiting messages go, clients are told.
    pub(crate) fn remove_channel(&self, id: u64) {
        let clients = self.clients.lock().expect("clients lock");
        self.channels.write().expect("channels lock").remove(&id);
        let unadv = text(&serde_json::json!({"op": "unadvertise", "channelIds": [id]}));
        for c in clients.iter() {
            let mut o = c.outbox.lock().expect("outbox lock");
            o.drop_channel(id);
            o.push_control(unadv.clone());
            drop(o);
            c.wake.notify_one();
        }
    }

    /// Queues a message of `ch` for each client subscribed to it.
    pub(crate) fn log(&self, ch: &ChannelInfo, time_ns: u64, payload: &[u8]) {
        if !ch.has_subscribers() {
            return;
        }
        let clients = self.clients.lock().expect("clients lock");
        for c in clients.iter() {
            let mut o = c.outbox.lock().expect("outbox lock");
            let Some(&sub) = o.subs.get(&ch.id) else { continue };
            let mut frame = Vec::with_capacity(13 + payload.len());
            frame.push(1u8);
            frame.extend_from_slice(&sub.to_le_bytes());
            frame.extend_from_slice(&time_ns.to_le_bytes());
            frame.extend_from_slice(payload);
            let dropped = o.push_data(ch.id, ch.keep, Message::Binary(Bytes::from(frame)));
            drop(o);
            self.counters.dropped.fetch_add(dropped, Ordering::Relaxed);
            c.wake.notify_one();
        }
    }

    pub(crate) fn stats(&self) -> LiveStats {
        let (mut max_len, mut bytes) = (0, 0);
        for c in self.clients.lock().expect("clients lock").iter() {
            let o = c.outbox.lock().expect("outbox lock");
            max_len = max_len.max((o.control.len() + o.data.len()) as u64);
            bytes += o.bytes as u64;
        }
        let k = &self.counters;
        LiveStats {
            connections: k.connections.load(Ordering::Relaxed),
            clients: k.clients.load(Ordering::Relaxed),
            refused_connections: k.refused.load(Ordering::Relaxed),
            failed_handshakes: k.failed_handshakes.load(Ordering::Relaxed),
            dropped_messages: k.dropped.load(Ordering::Relaxed),
            stalled_clients: k.stalled.load(Ordering::Relaxed),
            queued_messages_max: max_len,
            queued_bytes: bytes,
        }
    }

    /// Registers a client: it gets the server's info and every channel's advertisement first.
    fn register(&self) -> Arc<Client> {
        let client =
            Arc::new(Client { id: self.next_client.fetch_add(1, Ordering::Relaxed), outbox: Mutex::default(), wake: Notify::new() });
        let mut clients = self.clients.lock().expect("clients lock");
        let channels = self.channels.read().expect("channels lock");
        let mut o = client.outbox.lock().expect("outbox lock");
        o.push_control(text(&serde_json::json!({
            "op": "serverInfo", "name": self.name, "capabilities": [], "supportedEncodings": [],
            "metadata": {}, "sessionId": self.session_id,
        })));
        // One advertisement for all channels (a session has two; the control queue is bounded).
        let all: Vec<_> = channels.values().map(|c| c.advertisement()).collect();
        o.push_control(text(&serde_json::json!({"op": "advertise", "channels": all})));
        drop(o);
        clients.push(client.clone());
        client
    }

    fn unregister(&self, client: &Client) {
        let mut clients = self.clients.lock().expect("clients lock");
        clients.retain(|c| c.id != client.id);
        let channels = self.channels.read().expect("channels lock");
        let mut o = client.outbox.lock().expect("outbox lock");
        for ch in o.subs.keys() {
            if let Some(info) = channels.get(ch) {
                info.subscribers.fetch_sub(1, Ordering::Relaxed);
            }
        }
        *o = Outbox::default();
    }

    /// A client's text message: subscribe and unsubscribe are acted on, anything else ignored.
    fn on_client_text(&self, client: &Client, msg: &str) {
        let Ok(v) = serde_json::from_str::<serde_json::Value>(msg) else { return };
        let _clients = self.clients.lock().expect("clients lock");
        let channels = self.channels.read().expect("channels lock");
        let mut o = client.outbox.lock().expect("outbox lock");
        match v["op"].as_str() {
            Some("subscribe") => {
                for s in v["subscriptions"].as_array().into_iter().flatten() {
                    let (Some(sub), Some(ch)) = (s["id"].as_u64(), s["channelId"].as_u64()) else { continue };
                    let (Ok(sub), Some(info)) = (u32::try_from(sub), channels.get(&ch)) else { continue };
                    if o.subs.values().any(|&x| x == sub) || o.subs.len() >= MAX_SUBSCRIPTIONS {
                        continue;
                    }
                    if o.subs.insert(ch, sub).is_none() {
                        info.subscribers.fetch_add(1, Ordering::Relaxed);
                    }
                }
            }
            Some("unsubscribe") => {
                for sub in v["subscriptionIds"].as_array().into_iter().flatten().filter_map(serde_json::Value::as_u64) {
                    let Some((&ch, _)) = o.subs.iter().find(|(_, s)| u64::from(**s) == sub) else { continue };
                    if o.drop_channel(ch)
                        && let Some(info) = channels.get(&ch)
                    {
                        info.subscribers.fetch_sub(1, Ordering::Relaxed);
                    }
                }
            }
            _ => {}
        }
    }
}

/// Accepts connections until `stop` turns true.
pub(crate) async fn serve(hub: Arc<Hub>, listener: TcpListener, mut stop: watch::Receiver<bool>) {
    let slots = Arc::new(Semaphore::new(hub.opts.max_clients));
    let (mut warned_full, mut warned_accept) = (false, false);
    loop {
        let accepted = tokio::select! {
            a = listener.accept() => a,
            _ = stop.changed() => return,
        };
        let stream = match accepted {
            Ok((s, _)) => s,
            Err(e) => {
                // Out of descriptors, most likely: wait for some to be freed.
                if !std::mem::replace(&mut warned_accept, true) {
                    tracing::warn!(error = %e, "the Foxglove endpoint cannot accept connections (logged once)");
                }
                tokio::time::sleep(Duration::from_millis(100)).await;
                continue;
            }
        };
        let Ok(permit) = slots.clone().try_acquire_owned() else {
            hub.counters.refused.fetch_add(1, Ordering::Relaxed);
            if !std::mem::replace(&mut warned_full, true) {
                tracing::warn!(max_clients = hub.opts.max_clients, "Foxglove connection refused: the endpoint is full (logged once)");
            }
            drop(stream);
            continue;
        };
        tokio::spawn(connection(hub.clone(), stream, permit, stop.clone()));
    }
}

/// Picks the subprotocol from a handshake's offered ones.
// The error type is tungstenite's callback's, not ours to box.
#[allow(clippy::result_large_err)]
fn negotiate(req: &Request, mut res: Response) -> Result<Response, ErrorResponse> {
    let offered = req.headers().get_all("sec-websocket-protocol").iter().flat_map(|h| h.to_str().unwrap_or_default().split(','));
    let chosen = offered.map(str::trim).filter(|p| SUBPROTOCOLS.contains(p)).min_by_key(|p| SUBPROTOCOLS.iter().position(|s| s == p));
    let Some(proto) = chosen else {
        let mut e = ErrorResponse::new(Some(format!("the sec-websocket-protocol header must offer {}", SUBPROTOCOLS.join(" or "))));
        *e.status_mut() = tokio_tungstenite::tungstenite::http::StatusCode::BAD_REQUEST;
        return Err(e);
    };
    res.headers_mut().insert("sec-websocket-protocol", proto.parse().expect("a header value"));
    Ok(res)
}

/// One connection: the handshake (bounded in time), then the client until it leaves, stalls or
/// the server stops.
async fn connection(hub: Arc<Hub>, stream: TcpStream, _permit: OwnedSemaphorePermit, mut stop: watch::Receiver<bool>) {
    let k = &hub.counters;
    k.connections.fetch_add(1, Ordering::Relaxed);
    struct Open<'a>(&'a AtomicU64);
    impl Drop for Open<'_> {
        fn drop(&mut self) {
            self.0.fetch_sub(1, Ordering::Relaxed);
        }
    }
    let _open = Open(&k.connections);
    let _ = stream.set_nodelay(true);
    let config = WebSocketConfig::default().max_message_size(Some(MAX_CLIENT_MESSAGE_BYTES)).max_frame_size(Some(MAX_CLIENT_MESSAGE_BYTES));
    let handshake = tokio_tungstenite::accept_hdr_async_with_config(stream, negotiate, Some(config));
    let ws = tokio::select! {
        r = tokio::time::timeout(hub.opts.handshake_timeout, handshake) => r,
        _ = stop.changed() => return,
    };
    let Ok(Ok(ws)) = ws else {
        k.failed_handshakes.fetch_add(1, Ordering::Relaxed);
        return;
    };
    k.clients.fetch_add(1, Ordering::Relaxed);
    let _client_open = Open(&k.clients);
    let client = hub.register();
    let (mut tx, mut rx) = ws.split();
    let send = async {
        loop {
            let next = {
                let mut o = client.outbox.lock().expect("outbox lock");
                if o.overflowed {
                    k.stalled.fetch_add(1, Ordering::Relaxed);
                    return;
                }
                o.pop()
            };
            match next {
                Some(m) => match tokio::time::timeout(hub.opts.stall_timeout, tx.send(m)).await {
                    Ok(Ok(())) => {}
                    Ok(Err(_)) => return,
                    Err(_) => {
                        k.stalled.fetch_add(1, Ordering::Relaxed);
                        return;
                    }
                },
                None => client.wake.notified().await,
            }
        }
    };
    let receive = async {
        while let Some(Ok(m)) = rx.next().await {
            match m {
                Message::Text(t) => hub.on_client_text(&client, t.as_str()),
                Message::Close(_) => return,
                _ => {}
            }
        }
    };
    tokio::select! {
        () = send => {}
        () = receive => {}
        _ = stop.changed() => {}
    }
    hub.unregister(&client);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_channels_unsent_messages_beyond_its_keep_are_dropped_oldest_first() {
        let mut o = Outbox::default();
        let m = |s: &str| Message::Text(s.to_owned().into());
        assert_eq!(o.push_data(1, 1, m("scene a")), 0);
        assert_eq!(o.push_data(2, 2, m("f1")), 0);
        assert_eq!(o.push_data(2, 2, m("f2")), 0);
        assert_eq!(o.push_data(1, 1, m("scene b")), 1, "the unsent scene is replaced");
        assert_eq!(o.push_data(2, 2, m("f3")), 1);
        let mut out = Vec::new();
        while let Some(Message::Text(t)) = o.pop() {
            out.push(t.to_string());
        }
        assert_eq!(out, ["f2", "scene b", "f3"], "in the order logged");
        assert_eq!(o.bytes, 0);
        assert!(o.per_channel.is_empty());
        for i in 0..MAX_CONTROL_QUEUE + 1 {
            o.push_control(m(&i.to_string()));
        }
        assert!(o.overflowed);
        assert_eq!(o.control.len(), MAX_CONTROL_QUEUE);
    }
}
