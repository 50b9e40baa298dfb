//! The connection to the server and the translation of gRPC failures into one-line messages.

use std::time::Duration;

use anyhow::{Result, anyhow, bail};
use tonic::metadata::MetadataValue;
use tonic::transport::{Certificate, Channel, ClientTlsConfig, Endpoint};
use tonic::{Code, Request, Status};

/// What a call needs the token for, to say which token was refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// Driving, recording or closing a session: the controller token.
    Controller,
    /// Watching a session: its observer or controller token.
    Observer,
    /// No token involved.
    None,
}

/// A connected channel to one server, with the token to send.
pub struct Conn {
    pub channel: Channel,
    pub url: String,
    pub token: Option<String>,
}

/// `host:port` becomes `http://host:port`.
fn normalise_url(url: &str) -> String {
    if url.contains("://") { url.to_owned() } else { format!("http://{url}") }
}

/// The error and its sources, joined by `: ` (tonic's transport errors hide the cause in them).
pub fn chain(e: &(dyn std::error::Error + 'static)) -> String {
    let mut s = e.to_string();
    let mut cur = e.source();
    while let Some(c) = cur {
        let t = c.to_string();
        if !s.contains(&t) {
            s.push_str(": ");
            s.push_str(&t);
        }
        cur = c.source();
    }
    s
}

fn unreachable(url: &str, detail: &str) -> anyhow::Error {
    anyhow!("cannot reach the needlesim server at {url}: {detail}; is it running? (needlesim-server serve)")
}

impl Conn {
    /// Connects (eagerly, so that an unreachable server is reported before anything else).
    pub async fn connect(url: &str, token: Option<String>, tls_ca: Option<&std::path::Path>) -> Result<Self> {
        let url = normalise_url(url);
        let mut ep = Endpoint::from_shared(url.clone())
            .map_err(|e| anyhow!("--server {url} is not a valid URL: {}", chain(&e)))?
            .connect_timeout(Duration::from_secs(5))
            .tcp_nodelay(true);
        let https = url.starts_with("https://");
        match (tls_ca, https) {
            (Some(ca), true) => {
                let pem = needlesim_localfile::read_local_bytes(ca, needlesim_localfile::MAX_CERTIFICATE_BYTES)
                    .map_err(|e| anyhow!("--tls-ca: {}", e.named("CA certificate")))?;
                let tls = ClientTlsConfig::new().ca_certificate(Certificate::from_pem(pem));
                ep = ep.tls_config(tls).map_err(|e| anyhow!("--tls-ca {}: {}", ca.display(), chain(&e)))?;
            }
            (Some(_), false) => bail!("--tls-ca needs an https:// server URL, got {url}"),
            (None, true) => {
                ep = ep.tls_config(ClientTlsConfig::new()).map_err(|e| anyhow!("TLS: {}", chain(&e)))?;
            }
            (None, false) => {}
        }
        let channel = match ep.connect().await {
            Ok(c) => c,
            Err(e) => {
                let mut detail = chain(&e);
                if https && tls_ca.is_none() {
                    detail.push_str(" (for a server with its own CA pass --tls-ca CA.pem)");
                }
                return Err(unreachable(&url, &detail));
            }
        };
        Ok(Self { channel, url, token: token.filter(|t| !t.trim().is_empty()) })
    }

    /// A request carrying the token (when there is one) as `authorization: Bearer <token>`.
    pub fn request<T>(&self, msg: T) -> Result<Request<T>> {
        let mut r = Request::new(msg);
        if let Some(t) = &self.token {
            let v = MetadataValue::try_from(format!("Bearer {}", t.trim()))
                .map_err(|_| anyhow!("the token contains characters that cannot be sent in a header"))?;
            r.metadata_mut().insert("authorization", v);
        }
        Ok(r)
    }

    /// A one-line error for a failed call. `what` names the call ("closing session X"), `session`
    /// the session it was about (for NOT_FOUND).
    pub fn status_error(&self, what: &str, role: Role, session: Option<&str>, s: &Status) -> anyhow::Error {
        let msg = s.message().trim();
        let given = if self.token.is_some() { "" } else { " (no token was given)" };
        match s.code() {
            Code::PermissionDenied => {
                let need = match role {
                    Role::Observer => "watching a session needs its observer or controller token",
                    _ => "driving a session needs its controller token",
                };
                anyhow!(
                    "the token was refused{given}: {need}; pass it with --token TOKEN or NEEDLESIM_TOKEN (`needlesim sessions create` prints both tokens) [{what}: {msg}]"
                )
            }
            Code::NotFound => match session {
                Some(id) => anyhow!("no session '{id}' on {} (`needlesim sessions list` shows the open ones) [{what}: {msg}]", self.url),
                None => anyhow!("{what}: not found: {msg}"),
            },
            Code::Unavailable => unreachable(&self.url, &format!("{what}: {msg}")),
            Code::DeadlineExceeded => anyhow!("{what}: the server at {} did not answer in time: {msg}", self.url),
            Code::InvalidArgument => anyhow!("{what}: the server rejected the request: {msg}"),
            Code::ResourceExhausted => anyhow!("{what}: over a server limit: {msg}"),
            Code::FailedPrecondition => anyhow!("{what}: {msg}"),
            c => anyhow!("{what} failed ({c:?}): {msg}"),
        }
    }
}
