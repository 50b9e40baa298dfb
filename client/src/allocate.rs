//! `needlesim allocate` and `needlesim sessions create --allocate`: a game server from the Agones
//! allocator service (issue 22), then — for `--allocate` — the session created on it.
//!
//! **The API.** The `agones-allocator` service's REST gateway (agones.dev, "Allocator Service";
//! `proto/allocation/allocation.proto` and its swagger, grpc-gateway's protojson mapping):
//! `POST /gameserverallocation` with an `AllocationRequest` body over HTTPS with a client
//! certificate (mTLS; plain HTTP only when the service runs with TLS disabled). The request this
//! client sends, for label sets $L_1, \dots, L_k$ (one per `--selector`, tried in order):
//!
//! ```json
//! {"namespace": "default",
//!  "gameServerSelectors": [
//!    {"matchLabels": L1, "gameServerState": "ALLOCATED", "counters": {"sessions": {"minAvailable": "1"}}},
//!    {"matchLabels": L1, "gameServerState": "READY",     "counters": {"sessions": {"minAvailable": "1"}}},
//!    … the same two for L2 … Lk],
//!  "scheduling": "Packed",
//!  "counters": {"sessions": {"action": "Increment", "amount": "1"}},
//!  "priorities": [{"type": "Counter", "key": "sessions", "order": "Ascending"}]}
//! ```
//!
//! — deploy/k8s/allocation.yaml's policy: a server already Allocated with a free session place
//! first (many trainees per pod), else a Ready one, reserving the place at once with the Counter's
//! `Increment` (the server then sets the count to its sessions). `--no-counter` sends the labels
//! alone (`{"matchLabels": L}` per selector), for an Agones without the `CountsAndLists` feature.
//! int64 fields are JSON strings, as protojson writes them. The answer
//! (`AllocationResponse`): `gameServerName`, `address`, `addresses`, `nodeName`,
//! `ports: [{"name", "port"}]`; the session goes to `address` and the port named `--port-name`
//! (the Fleet's `grpc`).
//!
//! **Errors.** The allocator maps a failed allocation to a gRPC status, which grpc-gateway turns
//! into an HTTP status and a body `{"code", "message"}`: no matching server with room
//! (`UnAllocated`) is ResourceExhausted (code 8, HTTP 429, "there is no available GameServer to
//! allocate"), contention is Aborted (code 10, HTTP 409), a malformed request InvalidArgument
//! (code 3, HTTP 400). A client certificate the allocator does not accept ends the TLS handshake
//! with an alert (with TLS 1.3 the client learns it on its first read); a server certificate not
//! signed by `--ca-cert` fails the handshake on this side. Each is an [`AllocateError`] naming
//! the file or flag to fix.
//!
//! **Why hand-written.** One call: hyper's HTTP/1 client over rustls (`tokio-rustls`, ring), both
//! already in the tree through tonic, so the CLI gains no crate; the allocator's gRPC API would
//! need allocation.proto, which imports `google/api` annotations that protox does not bundle.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Duration;

use clap::Args;
use http_body_util::{BodyExt, Full, Limited};
use hyper::body::Bytes;
use hyper::{Method, Request, StatusCode, Uri};
use hyper_util::rt::TokioIo;
use rustls_pki_types::pem::PemObject;
use rustls_pki_types::{CertificateDer, PrivateKeyDer, ServerName};
use serde_json::{Value, json};
use tokio::io::{AsyncRead, AsyncWrite};
use tokio::net::TcpStream;

use crate::{Cli, Command, SessionsCmd};

/// The Counter the needlesim servers publish (sessions in use against `--max-sessions`).
pub const SESSIONS_COUNTER: &str = "sessions";
/// Connecting to the allocator (TCP, and TLS) may take this long.
const CONNECT_TIMEOUT: Duration = Duration::from_secs(5);
/// The whole exchange may take this long (the allocator batches allocations, 500 ms by default,
/// and retries contention itself).
const CALL_TIMEOUT: Duration = Duration::from_secs(30);
/// The largest answer read (a real one is well under 4 KiB).
const MAX_ANSWER_BYTES: usize = 1 << 20;
/// Where the system's CA bundle is looked for when `--ca-cert` is not given (Debian/Ubuntu,
/// Fedora/RHEL, Alpine), after `SSL_CERT_FILE`.
const SYSTEM_CA_FILES: [&str; 3] = ["/etc/ssl/certs/ca-certificates.crt", "/etc/pki/tls/certs/ca-bundle.crt", "/etc/ssl/cert.pem"];

/// How to reach the allocator and what to ask it for (shared by `allocate` and `sessions create --allocate`).
#[derive(Debug, Args, Clone, Default)]
pub struct AllocatorArgs {
    /// The Agones allocator service: https://HOST[:PORT] (mTLS, the default set-up) or
    /// http://HOST:PORT (an allocator with TLS disabled).
    #[arg(long, env = "NEEDLESIM_ALLOCATOR", value_name = "URL")]
    pub allocator: Option<String>,
    /// Labels the game server must carry, KEY=VALUE[,KEY=VALUE…] (all of them); repeat the flag
    /// for fallbacks, tried in order (e.g. agones.dev/fleet=needlesim,agones.dev/sdk-scene=none).
    #[arg(long = "selector", value_name = "KEY=VALUE[,…]")]
    pub selectors: Vec<String>,
    /// The Kubernetes namespace of the fleet.
    #[arg(long, default_value = "default", value_name = "NS")]
    pub namespace: String,
    /// The client certificate (PEM) the allocator accepts (Helm: the secret
    /// allocator-client.default, tls.crt).
    #[arg(long, value_name = "PEM", requires = "client_key")]
    pub client_cert: Option<PathBuf>,
    /// The client certificate's private key (PEM; allocator-client.default, tls.key).
    #[arg(long, value_name = "PEM", requires = "client_cert")]
    pub client_key: Option<PathBuf>,
    /// The CA certificate (PEM) that signed the allocator's certificate (Helm: the secret
    /// allocator-tls-ca in agones-system, tls-ca.crt); default: the system's CA bundle.
    #[arg(long, value_name = "PEM")]
    pub ca_cert: Option<PathBuf>,
    /// The game server port to connect to: the Fleet's port name.
    #[arg(long, default_value = "grpc", value_name = "NAME")]
    pub port_name: String,
    /// Select on labels only: no `sessions` Counter filter and no place reserved (an Agones
    /// without the CountsAndLists feature, or a fleet without the Counter).
    #[arg(long)]
    pub no_counter: bool,
}

/// `needlesim allocate`.
#[derive(Debug, Args)]
pub struct AllocateArgs {
    #[command(flatten)]
    pub allocator: AllocatorArgs,
    /// Print the allocation as one JSON object (address, port, server URL, game server, node).
    #[arg(long)]
    pub json: bool,
}

/// `sessions create`'s allocation options.
#[derive(Debug, Args, Clone, Default)]
pub struct CreateAllocation {
    /// Ask the Agones allocator for a server first, then create the session there (instead of
    /// --server); the server's URL is printed on standard error ("server" with --json).
    #[arg(long)]
    pub allocate: bool,
    #[command(flatten)]
    pub allocator: AllocatorArgs,
}

/// What goes wrong asking the allocator for a server.
#[derive(Debug, thiserror::Error)]
pub enum AllocateError {
    /// `--allocate` (or `allocate`) without an allocator URL.
    #[error("no allocator: pass --allocator https://HOST[:PORT] or set NEEDLESIM_ALLOCATOR")]
    NoAllocator,
    /// The allocator URL is not an http(s)://HOST[:PORT] URL.
    #[error("--allocator {url}: {why}")]
    BadUrl { url: String, why: String },
    /// A `--selector` is not KEY=VALUE[,KEY=VALUE…] with Kubernetes label syntax.
    #[error("--selector {selector:?}: {why}")]
    BadSelector { selector: String, why: String },
    /// Client certificates or a CA given for a plain-HTTP allocator.
    #[error("--{flag} needs an https:// allocator URL, got {url}")]
    TlsNeedsHttps { flag: &'static str, url: String },
    /// A certificate or key file cannot be read or holds no PEM item of the expected kind.
    #[error("--{flag} {}: {why}", path.display())]
    BadPem { flag: &'static str, path: PathBuf, why: String },
    /// No `--ca-cert` and no system CA bundle to verify the allocator with.
    #[error(
        "no CA to verify the allocator's certificate: pass --ca-cert CA.pem (Helm: kubectl get secret allocator-tls-ca -n agones-system -o jsonpath='{{.data.tls-ca\\.crt}}' | base64 -d)"
    )]
    NoCa,
    /// The TCP connection failed (refused, no route, name not resolved) or timed out.
    #[error(
        "cannot reach the Agones allocator at {url}: {detail}; is the agones-allocator service's address right (kubectl get service agones-allocator -n agones-system)?"
    )]
    Unreachable { url: String, detail: String },
    /// The allocator's certificate is not signed by the CA given (or the system's), or does not
    /// name the host of the URL.
    #[error(
        "the allocator at {url} presented a certificate this client does not trust: {detail}; pass the allocator's CA with --ca-cert (allocator-tls-ca) and use the address its certificate names"
    )]
    ServerCertUntrusted { url: String, detail: String },
    /// The allocator refused the client certificate (missing, expired, or not in its
    /// allocator-client-ca list).
    #[error(
        "the allocator at {url} refused {what}: {detail}; pass an allow-listed client certificate with --client-cert and --client-key (Helm: the secret allocator-client.default)"
    )]
    ClientCertRefused { url: String, what: &'static str, detail: String },
    /// Any other TLS or HTTP failure (connection reset, malformed answer).
    #[error("talking to the Agones allocator at {url}: {detail}")]
    Http { url: String, detail: String },
    /// No answer within the call timeout.
    #[error("the Agones allocator at {url} did not answer within {secs} s")]
    Timeout { url: String, secs: u64 },
    /// No game server matches the selectors with a free place (`UnAllocated`: HTTP 429,
    /// ResourceExhausted).
    #[error(
        "no needlesim server available in namespace '{namespace}' for {selectors}: the allocator answered {status}: {message}. Every matching server is full or none carries these labels: retry once the fleet has scaled up, or check the labels (kubectl get gameservers -n {namespace} --show-labels)"
    )]
    NoServer { namespace: String, selectors: String, status: u16, message: String },
    /// Too many concurrent allocations (HTTP 409, Aborted): retry.
    #[error("the allocator is overwhelmed by concurrent allocations ({status}: {message}); retry")]
    Contention { status: u16, message: String },
    /// Any other refusal (400 for a malformed request, 403, 500, …), with the allocator's message.
    #[error("the Agones allocator at {url} answered {status}: {message}")]
    Refused { url: String, status: u16, message: String },
    /// A 200 answer that is not an AllocationResponse this client can use.
    #[error("the Agones allocator's answer is not usable: {why} (answer: {body})")]
    BadAnswer { why: String, body: String },
    /// The allocated game server has no port of the wanted name (and more than one port).
    #[error("the allocated game server {game_server} has no port named '{port_name}' (its ports: {ports}); pass --port-name")]
    NoSuchPort { game_server: String, port_name: String, ports: String },
}

/// An allocated game server.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Allocation {
    /// The GameServer's name.
    pub game_server: String,
    /// The node it runs on.
    pub node_name: String,
    /// Where it is reached (the node's address).
    pub address: String,
    /// The chosen port (named `--port-name`).
    pub port: u16,
    /// Every port of the answer, (name, port).
    pub ports: Vec<(String, u16)>,
}

impl Allocation {
    /// `address:port` (an IPv6 address in brackets).
    pub fn target(&self) -> String {
        if self.address.contains(':') && !self.address.starts_with('[') {
            format!("[{}]:{}", self.address, self.port)
        } else {
            format!("{}:{}", self.address, self.port)
        }
    }

    /// The server URL to give `--server` (https when the needlesim servers use TLS).
    pub fn server_url(&self, tls: bool) -> String {
        format!("{}://{}", if tls { "https" } else { "http" }, self.target())
    }
}

/// The allocator's location, from its URL.
#[derive(Debug, Clone, PartialEq, Eq)]
struct Endpoint {
    https: bool,
    host: String,
    port: u16,
    /// The request path: the URL's path (if any, e.g. behind a proxy) + `/gameserverallocation`.
    path: String,
    /// The URL as given, for messages.
    url: String,
}

fn parse_endpoint(url: &str) -> Result<Endpoint, AllocateError> {
    let bad = |why: &str| AllocateError::BadUrl { url: url.to_owned(), why: why.to_owned() };
    let uri: Uri = url.trim().parse().map_err(|e| bad(&format!("not a URL ({e})")))?;
    let https = match uri.scheme_str() {
        Some("https") => true,
        Some("http") => false,
        Some(s) => return Err(bad(&format!("scheme '{s}': use https:// (or http:// for an allocator with TLS disabled)"))),
        None => return Err(bad("no scheme: write https://HOST[:PORT]")),
    };
    let host = uri.host().filter(|h| !h.is_empty()).ok_or_else(|| bad("no host"))?;
    let host = host.trim_start_matches('[').trim_end_matches(']').to_owned();
    let port = uri.port_u16().unwrap_or(if https { 443 } else { 80 });
    if uri.query().is_some() {
        return Err(bad("a query string is not expected"));
    }
    let base = uri.path().trim_end_matches('/');
    let path = if base.ends_with("/gameserverallocation") { base.to_owned() } else { format!("{base}/gameserverallocation") };
    Ok(Endpoint { https, host, port, path, url: url.trim().to_owned() })
}

/// A Kubernetes label key: an optional DNS-subdomain prefix and `/`, then a name of at most 63
/// characters (alphanumerics, `-`, `_`, `.`, alphanumeric at both ends).
fn label_name_ok(s: &str) -> bool {
    let b = s.as_bytes();
    !b.is_empty()
        && b.len() <= 63
        && b[0].is_ascii_alphanumeric()
        && b[b.len() - 1].is_ascii_alphanumeric()
        && b.iter().all(|c| c.is_ascii_alphanumeric() || matches!(c, b'-' | b'_' | b'.'))
}

fn label_key_ok(key: &str) -> bool {
    match key.split_once('/') {
        Some((prefix, name)) => {
            prefix.len() <= 253
                && !prefix.is_empty()
                && prefix.split('.').all(|p| {
                    let b = p.as_bytes();
                    !b.is_empty()
                        && b[0].is_ascii_alphanumeric()
                        && b[b.len() - 1].is_ascii_alphanumeric()
                        && b.iter().all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || *c == b'-')
                })
                && label_name_ok(name)
        }
        None => label_name_ok(key),
    }
}

/// One `--selector`: KEY=VALUE[,KEY=VALUE…] as a label map.
fn parse_selector(s: &str) -> Result<BTreeMap<String, String>, AllocateError> {
    let bad = |why: String| AllocateError::BadSelector { selector: s.to_owned(), why };
    let mut labels = BTreeMap::new();
    for part in s.split(',') {
        let part = part.trim();
        let Some((k, v)) = part.split_once('=') else {
            return Err(bad(format!("'{part}' is not KEY=VALUE")));
        };
        let (k, v) = (k.trim(), v.trim());
        if !label_key_ok(k) {
            return Err(bad(format!(
                "'{k}' is not a Kubernetes label key ([prefix/]name, name ≤ 63 characters: letters, digits, -, _, .)"
            )));
        }
        if !(v.is_empty() || label_name_ok(v)) {
            return Err(bad(format!(
                "'{v}' is not a Kubernetes label value (≤ 63 characters: letters, digits, -, _, ., alphanumeric at both ends)"
            )));
        }
        if labels.insert(k.to_owned(), v.to_owned()).is_some() {
            return Err(bad(format!("'{k}' is given twice")));
        }
    }
    Ok(labels)
}

/// The selectors as given, for messages: `[a=b,c=d] then [a=e]`, or "any server".
fn describe_selectors(selectors: &[BTreeMap<String, String>]) -> String {
    if selectors.is_empty() {
        return "any game server (no --selector)".to_owned();
    }
    let one = |m: &BTreeMap<String, String>| format!("[{}]", m.iter().map(|(k, v)| format!("{k}={v}")).collect::<Vec<_>>().join(","));
    format!("the selector{} {}", if selectors.len() > 1 { "s" } else { "" }, selectors.iter().map(one).collect::<Vec<_>>().join(" then "))
}

/// The AllocationRequest body (see the module docs).
fn request_body(namespace: &str, selectors: &[BTreeMap<String, String>], counter: bool) -> Value {
    let sets: Vec<BTreeMap<String, String>> = if selectors.is_empty() { vec![BTreeMap::new()] } else { selectors.to_vec() };
    if !counter {
        let list: Vec<Value> = sets.iter().map(|l| json!({ "matchLabels": l })).collect();
        return json!({ "namespace": namespace, "gameServerSelectors": list });
    }
    let free = json!({ SESSIONS_COUNTER: { "minAvailable": "1" } });
    let list: Vec<Value> = sets
        .iter()
        .flat_map(|l| {
            [
                json!({ "matchLabels": l, "gameServerState": "ALLOCATED", "counters": free }),
                json!({ "matchLabels": l, "gameServerState": "READY", "counters": free }),
            ]
        })
        .collect();
    json!({
        "namespace": namespace,
        "gameServerSelectors": list,
        "scheduling": "Packed",
        "counters": { SESSIONS_COUNTER: { "action": "Increment", "amount": "1" } },
        "priorities": [{ "type": "Counter", "key": SESSIONS_COUNTER, "order": "Ascending" }],
    })
}

/// A PEM file by the one rule for local files (a regular file, not a link, at most 1 MiB); the
/// error says why, without the path (the caller names it).
fn read_pem(path: &Path) -> Result<Vec<u8>, String> {
    needlesim_localfile::read_local_bytes(path, needlesim_localfile::MAX_CERTIFICATE_BYTES).map_err(|e| match e {
        needlesim_localfile::LocalFileError::Io { source, .. } => format!("cannot read it: {source}"),
        e => e.reason(),
    })
}

fn read_certs(flag: &'static str, path: &Path) -> Result<Vec<CertificateDer<'static>>, AllocateError> {
    let bad = |why: String| AllocateError::BadPem { flag, path: path.to_owned(), why };
    let bytes = read_pem(path).map_err(bad)?;
    let certs: Vec<CertificateDer<'static>> =
        CertificateDer::pem_slice_iter(&bytes).collect::<Result<_, _>>().map_err(|e| bad(format!("not PEM: {e}")))?;
    if certs.is_empty() {
        return Err(bad("no CERTIFICATE in it".to_owned()));
    }
    Ok(certs)
}

fn read_key(path: &Path) -> Result<PrivateKeyDer<'static>, AllocateError> {
    let bad = |why: String| AllocateError::BadPem { flag: "client-key", path: path.to_owned(), why };
    let bytes = read_pem(path).map_err(bad)?;
    PrivateKeyDer::from_pem_slice(&bytes).map_err(|e| match e {
        rustls_pki_types::pem::Error::NoItemsFound => bad("no PRIVATE KEY in it (PKCS#8, PKCS#1 or SEC1 PEM)".to_owned()),
        e => bad(format!("not PEM: {e}")),
    })
}

/// The TLS configuration: the allocator verified against `--ca-cert` (or the system bundle), the
/// client certificate offered when given.
fn tls_config(a: &AllocatorArgs) -> Result<rustls::ClientConfig, AllocateError> {
    let mut roots = rustls::RootCertStore::empty();
    let (flag, ca_path) = match &a.ca_cert {
        Some(p) => ("ca-cert", p.clone()),
        None => {
            let from_env = std::env::var_os("SSL_CERT_FILE").map(PathBuf::from);
            let found = from_env.into_iter().chain(SYSTEM_CA_FILES.iter().map(PathBuf::from)).find(|p| p.is_file());
            ("ca-cert (the system bundle)", found.ok_or(AllocateError::NoCa)?)
        }
    };
    for cert in read_certs(if a.ca_cert.is_some() { "ca-cert" } else { flag }, &ca_path)? {
        roots.add(cert).map_err(|e| AllocateError::BadPem {
            flag: "ca-cert",
            path: ca_path.clone(),
            why: format!("not a usable CA certificate: {e}"),
        })?;
    }
    let provider = Arc::new(rustls::crypto::ring::default_provider());
    let builder = rustls::ClientConfig::builder_with_provider(provider)
        .with_safe_default_protocol_versions()
        .map_err(|e| AllocateError::Http { url: String::new(), detail: format!("TLS set-up: {e}") })?
        .with_root_certificates(roots);
    match (&a.client_cert, &a.client_key) {
        (Some(cert), Some(key)) => {
            let chain = read_certs("client-cert", cert)?;
            let key_der = read_key(key)?;
            builder.with_client_auth_cert(chain, key_der).map_err(|e| AllocateError::BadPem {
                flag: "client-key",
                path: key.clone(),
                why: format!("does not go with --client-cert {}: {e}", cert.display()),
            })
        }
        _ => Ok(builder.with_no_client_auth()),
    }
}

/// The rustls error behind an error, if any (io errors wrap it; hyper wraps io errors).
fn rustls_error<'a>(e: &'a (dyn std::error::Error + 'static)) -> Option<&'a rustls::Error> {
    let mut cur: Option<&(dyn std::error::Error + 'static)> = Some(e);
    while let Some(c) = cur {
        if let Some(r) = c.downcast_ref::<rustls::Error>() {
            return Some(r);
        }
        if let Some(io) = c.downcast_ref::<std::io::Error>()
            && let Some(inner) = io.get_ref()
            && let Some(r) = inner.downcast_ref::<rustls::Error>()
        {
            return Some(r);
        }
        cur = c.source();
    }
    None
}

/// A TLS failure as the error that says what to fix.
fn tls_failure(ep: &Endpoint, a: &AllocatorArgs, e: &(dyn std::error::Error + 'static)) -> Option<AllocateError> {
    use rustls::AlertDescription as A;
    let r = rustls_error(e)?;
    let detail = r.to_string();
    let url = ep.url.clone();
    Some(match r {
        rustls::Error::InvalidCertificate(_) => AllocateError::ServerCertUntrusted { url, detail },
        rustls::Error::AlertReceived(
            A::BadCertificate | A::UnknownCA | A::CertificateRequired | A::CertificateUnknown | A::CertificateExpired | A::AccessDenied,
        ) => AllocateError::ClientCertRefused {
            url,
            what: if a.client_cert.is_some() {
                "the client certificate"
            } else {
                "the connection: it requires a client certificate, none was given"
            },
            detail,
        },
        _ => AllocateError::Http { url, detail: format!("TLS: {detail}") },
    })
}

/// Every error and its sources, joined.
fn chain(e: &(dyn std::error::Error + 'static)) -> String {
    crate::rpc::chain(e)
}

/// Sends the request on an established stream and returns (status, body).
async fn exchange<S>(stream: S, ep: &Endpoint, body: Vec<u8>) -> Result<(StatusCode, Bytes), hyper::Error>
where
    S: AsyncRead + AsyncWrite + Unpin + Send + 'static,
{
    let (mut sender, conn) = hyper::client::conn::http1::handshake(TokioIo::new(stream)).await?;
    // The connection's own error (e.g. the TLS alert of a refused client certificate) ends the
    // driver; the request then only sees "canceled", so the driver's error is the one reported.
    let driver = tokio::spawn(conn);
    let failed = |e: hyper::Error, driver: tokio::task::JoinHandle<Result<(), hyper::Error>>| async move {
        match driver.await {
            Ok(Err(conn_err)) => conn_err,
            _ => e,
        }
    };
    let host = if ep.host.contains(':') { format!("[{}]:{}", ep.host, ep.port) } else { format!("{}:{}", ep.host, ep.port) };
    let req = Request::builder()
        .method(Method::POST)
        .uri(ep.path.as_str())
        .header(hyper::header::HOST, host)
        .header(hyper::header::CONTENT_TYPE, "application/json")
        .header(hyper::header::ACCEPT, "application/json")
        .header(hyper::header::USER_AGENT, concat!("needlesim/", env!("CARGO_PKG_VERSION")))
        .body(Full::new(Bytes::from(body)))
        .expect("a request built from a checked URL");
    let resp = match sender.send_request(req).await {
        Ok(r) => r,
        Err(e) => return Err(failed(e, driver).await),
    };
    let status = resp.status();
    let bytes = match Limited::new(resp.into_body(), MAX_ANSWER_BYTES).collect().await {
        Ok(b) => b.to_bytes(),
        Err(e) => match e.downcast::<hyper::Error>() {
            Ok(h) => return Err(failed(*h, driver).await),
            // Over the limit: keep what the status says, the body is reported as too long.
            Err(_) => Bytes::from_static(b"{\"message\": \"(answer over 1 MiB)\"}"),
        },
    };
    driver.abort();
    Ok((status, bytes))
}

/// The `message` of a grpc-gateway error body (`{"code", "message", "details"}`), else the body.
fn error_message(body: &[u8]) -> (Option<i64>, String) {
    match serde_json::from_slice::<Value>(body) {
        Ok(v) => {
            let code = v.get("code").and_then(Value::as_i64);
            let msg = v.get("message").and_then(Value::as_str).map(str::to_owned);
            (code, msg.unwrap_or_else(|| clip(&String::from_utf8_lossy(body))))
        }
        Err(_) => (None, clip(String::from_utf8_lossy(body).trim())),
    }
}

fn clip(s: &str) -> String {
    let s = s.trim();
    if s.chars().count() > 300 { format!("{}…", s.chars().take(300).collect::<String>()) } else { s.to_owned() }
}

/// Reads an AllocationResponse.
fn parse_answer(body: &[u8], port_name: &str) -> Result<Allocation, AllocateError> {
    let bad = |why: &str| AllocateError::BadAnswer { why: why.to_owned(), body: clip(&String::from_utf8_lossy(body)) };
    let v: Value = serde_json::from_slice(body).map_err(|e| bad(&format!("not JSON ({e})")))?;
    let text = |k: &str| v.get(k).and_then(Value::as_str).unwrap_or_default().to_owned();
    let game_server = text("gameServerName");
    let address = text("address");
    if address.is_empty() {
        return Err(bad("no address"));
    }
    let mut ports = Vec::new();
    for p in v.get("ports").and_then(Value::as_array).into_iter().flatten() {
        let name = p.get("name").and_then(Value::as_str).unwrap_or_default().to_owned();
        // int32 in protojson: a number (a string is accepted too).
        let port = p.get("port").and_then(|x| x.as_u64().or_else(|| x.as_str().and_then(|s| s.parse().ok())));
        let port = port
            .and_then(|n| u16::try_from(n).ok())
            .filter(|n| *n > 0)
            .ok_or_else(|| bad(&format!("port '{name}' is not a port number")))?;
        ports.push((name, port));
    }
    if ports.is_empty() {
        return Err(bad("no ports"));
    }
    let port = match ports.iter().find(|(n, _)| n == port_name) {
        Some((_, p)) => *p,
        None if ports.len() == 1 => ports[0].1,
        None => {
            return Err(AllocateError::NoSuchPort {
                game_server,
                port_name: port_name.to_owned(),
                ports: ports.iter().map(|(n, p)| format!("{n}={p}")).collect::<Vec<_>>().join(", "),
            });
        }
    };
    Ok(Allocation { game_server, node_name: text("nodeName"), address, port, ports })
}

/// Asks the allocator for a game server (see the module docs).
pub async fn allocate(a: &AllocatorArgs) -> Result<Allocation, AllocateError> {
    let url = a.allocator.as_deref().filter(|u| !u.trim().is_empty()).ok_or(AllocateError::NoAllocator)?;
    let ep = parse_endpoint(url)?;
    let selectors: Vec<BTreeMap<String, String>> = a.selectors.iter().map(|s| parse_selector(s)).collect::<Result<_, _>>()?;
    if a.namespace.trim().is_empty() {
        return Err(AllocateError::BadSelector { selector: String::new(), why: "--namespace is empty".to_owned() });
    }
    if !ep.https {
        for (flag, given) in [("client-cert", a.client_cert.is_some()), ("ca-cert", a.ca_cert.is_some())] {
            if given {
                return Err(AllocateError::TlsNeedsHttps { flag, url: ep.url.clone() });
            }
        }
    }
    let tls = if ep.https { Some(tls_config(a)?) } else { None };
    let body = serde_json::to_vec(&request_body(a.namespace.trim(), &selectors, !a.no_counter)).expect("JSON of strings");

    let unreachable = |detail: String| AllocateError::Unreachable { url: ep.url.clone(), detail };
    let tcp = match tokio::time::timeout(CONNECT_TIMEOUT, TcpStream::connect((ep.host.as_str(), ep.port))).await {
        Ok(Ok(s)) => s,
        Ok(Err(e)) => return Err(unreachable(e.to_string())),
        Err(_) => return Err(unreachable(format!("no connection within {} s", CONNECT_TIMEOUT.as_secs()))),
    };
    let _ = tcp.set_nodelay(true);
    let call = async {
        match tls {
            Some(cfg) => {
                let name = ServerName::try_from(ep.host.clone())
                    .map_err(|e| AllocateError::BadUrl { url: ep.url.clone(), why: format!("host '{}': {e}", ep.host) })?;
                let connector = tokio_rustls::TlsConnector::from(Arc::new(cfg));
                let stream = match tokio::time::timeout(CONNECT_TIMEOUT, connector.connect(name, tcp)).await {
                    Ok(Ok(s)) => s,
                    Ok(Err(e)) => {
                        return Err(tls_failure(&ep, a, &e).unwrap_or_else(|| AllocateError::Http {
                            url: ep.url.clone(),
                            detail: format!("TLS handshake: {}", chain(&e)),
                        }));
                    }
                    Err(_) => return Err(AllocateError::Timeout { url: ep.url.clone(), secs: CONNECT_TIMEOUT.as_secs() }),
                };
                exchange(stream, &ep, body)
                    .await
                    .map_err(|e| tls_failure(&ep, a, &e).unwrap_or_else(|| AllocateError::Http { url: ep.url.clone(), detail: chain(&e) }))
            }
            None => exchange(tcp, &ep, body).await.map_err(|e| AllocateError::Http {
                url: ep.url.clone(),
                detail: format!("{} (the allocator serves HTTPS unless installed with TLS disabled: use https://)", chain(&e)),
            }),
        }
    };
    let (status, answer) = match tokio::time::timeout(CALL_TIMEOUT, call).await {
        Ok(r) => r?,
        Err(_) => return Err(AllocateError::Timeout { url: ep.url.clone(), secs: CALL_TIMEOUT.as_secs() }),
    };
    if status == StatusCode::OK {
        return parse_answer(&answer, &a.port_name);
    }
    let (code, message) = error_message(&answer);
    let s = status.as_u16();
    // grpc-gateway: ResourceExhausted (8) → 429, Aborted (10) → 409.
    match (s, code) {
        (429, _) | (_, Some(8)) => Err(AllocateError::NoServer {
            namespace: a.namespace.trim().to_owned(),
            selectors: describe_selectors(&selectors),
            status: s,
            message,
        }),
        (409, _) | (_, Some(10)) => Err(AllocateError::Contention { status: s, message }),
        (401 | 403, _) => {
            Err(AllocateError::ClientCertRefused { url: ep.url.clone(), what: "the client certificate", detail: format!("{s}: {message}") })
        }
        _ => Err(AllocateError::Refused { url: ep.url.clone(), status: s, message }),
    }
}

/// `needlesim allocate`: prints `address:port` (or the JSON object).
async fn allocate_command(a: &AllocateArgs, tls: bool) -> anyhow::Result<()> {
    let got = allocate(&a.allocator).await?;
    let line = if a.json {
        serde_json::to_string_pretty(&json!({
            "address": got.address,
            "port": got.port,
            "target": got.target(),
            "server": got.server_url(tls),
            "game_server": got.game_server,
            "node_name": got.node_name,
            "ports": got.ports.iter().map(|(n, p)| json!({"name": n, "port": p})).collect::<Vec<_>>(),
        }))?
    } else {
        got.target()
    };
    use std::io::Write as _;
    writeln!(std::io::stdout().lock(), "{line}")?;
    Ok(())
}

/// Runs before the commands: `allocate` is handled here (None: nothing left to do); `sessions
/// create --allocate` allocates and points `--server` at the allocated server.
pub async fn before_command(mut cli: Cli) -> anyhow::Result<Option<Cli>> {
    let tls = cli.tls_ca.is_some();
    match &cli.command {
        Command::Allocate(a) => {
            allocate_command(a, tls).await?;
            Ok(None)
        }
        Command::Sessions(SessionsCmd::Create(c)) if c.alloc.allocate => {
            let got = allocate(&c.alloc.allocator).await?;
            let url = got.server_url(tls);
            eprintln!("allocated game server {} on node {}: {url}", got.game_server, got.node_name);
            cli.server = url;
            Ok(Some(cli))
        }
        Command::Sessions(SessionsCmd::Create(c)) if !c.alloc.allocator.selectors.is_empty() => {
            anyhow::bail!("--selector selects the server to allocate: add --allocate")
        }
        _ => Ok(Some(cli)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn urls_parse_with_default_ports_and_paths() {
        let e = parse_endpoint("https://34.82.195.204").unwrap();
        assert_eq!((e.https, e.host.as_str(), e.port, e.path.as_str()), (true, "34.82.195.204", 443, "/gameserverallocation"));
        let e = parse_endpoint("http://localhost:8000/").unwrap();
        assert_eq!((e.https, e.port, e.path.as_str()), (false, 8000, "/gameserverallocation"));
        let e = parse_endpoint("https://gw.example/agones/gameserverallocation").unwrap();
        assert_eq!(e.path, "/agones/gameserverallocation");
        let e = parse_endpoint("https://[::1]:9443").unwrap();
        assert_eq!((e.host.as_str(), e.port), ("::1", 9443));
        for (bad, why) in [("ftp://h", "scheme"), ("h:443", "scheme"), ("https://h/?x=1", "query"), ("not a url", "URL")] {
            let err = parse_endpoint(bad).unwrap_err().to_string();
            assert!(err.contains(why), "{bad}: {err}");
        }
    }

    #[test]
    fn selectors_follow_the_label_syntax() {
        let m = parse_selector("agones.dev/fleet=needlesim, agones.dev/sdk-scene=none").unwrap();
        assert_eq!(m.len(), 2);
        assert_eq!(m["agones.dev/fleet"], "needlesim");
        assert!(parse_selector("tier=").unwrap()["tier"].is_empty());
        for (bad, why) in [
            ("fleet", "not KEY=VALUE"),
            ("=x", "label key"),
            ("Agones.Dev/fleet=x", "label key"),
            ("fleet=-x", "label value"),
            ("a=1,a=2", "twice"),
            (&format!("k={}", "v".repeat(64)), "label value"),
        ] {
            let err = parse_selector(bad).unwrap_err().to_string();
            assert!(err.contains(why), "{bad}: {err}");
        }
    }

    #[test]
    fn the_request_prefers_allocated_servers_with_room_and_reserves_a_place() {
        let sel = vec![parse_selector("agones.dev/fleet=needlesim").unwrap(), parse_selector("agones.dev/fleet=spare").unwrap()];
        let b = request_body("trainees", &sel, true);
        assert_eq!(b["namespace"], "trainees");
        let list = b["gameServerSelectors"].as_array().unwrap();
        let order: Vec<(String, String)> = list
            .iter()
            .map(|s| (s["matchLabels"]["agones.dev/fleet"].as_str().unwrap().to_owned(), s["gameServerState"].as_str().unwrap().to_owned()))
            .collect();
        let want = [("needlesim", "ALLOCATED"), ("needlesim", "READY"), ("spare", "ALLOCATED"), ("spare", "READY")];
        assert_eq!(order, want.map(|(a, b)| (a.to_owned(), b.to_owned())));
        assert!(list.iter().all(|s| s["counters"]["sessions"]["minAvailable"] == "1"));
        assert_eq!(b["counters"]["sessions"], json!({"action": "Increment", "amount": "1"}));
        assert_eq!(b["priorities"][0]["key"], "sessions");
        // Labels only: one selector per set, nothing about Counters.
        let b = request_body("default", &sel, false);
        assert_eq!(
            b,
            json!({"namespace": "default", "gameServerSelectors": [
            {"matchLabels": {"agones.dev/fleet": "needlesim"}}, {"matchLabels": {"agones.dev/fleet": "spare"}}]})
        );
    }

    #[test]
    fn answers_give_the_named_port() {
        let body = br#"{"gameServerName":"needlesim-x","ports":[{"name":"metrics","port":7001},{"name":"grpc","port":7463}],"address":"10.0.0.5","nodeName":"n1"}"#;
        let a = parse_answer(body, "grpc").unwrap();
        assert_eq!((a.target().as_str(), a.game_server.as_str(), a.node_name.as_str()), ("10.0.0.5:7463", "needlesim-x", "n1"));
        assert_eq!(a.server_url(false), "http://10.0.0.5:7463");
        let err = parse_answer(body, "web").unwrap_err().to_string();
        assert!(err.contains("no port named 'web'") && err.contains("grpc=7463"), "{err}");
        // A single port is taken whatever its name; IPv6 goes in brackets.
        let a = parse_answer(br#"{"ports":[{"name":"default","port":7000}],"address":"fd00::5"}"#, "grpc").unwrap();
        assert_eq!(a.target(), "[fd00::5]:7000");
        for (bad, why) in [(&b"{}"[..], "no address"), (&br#"{"address":"a"}"#[..], "no ports"), (&b"<html>"[..], "not JSON")] {
            let err = parse_answer(bad, "grpc").unwrap_err().to_string();
            assert!(err.contains(why), "{err}");
        }
    }

    #[test]
    fn gateway_errors_carry_their_message() {
        let (code, msg) = error_message(br#"{"code":8,"message":"there is no available GameServer to allocate","details":[]}"#);
        assert_eq!((code, msg.as_str()), (Some(8), "there is no available GameServer to allocate"));
        assert_eq!(error_message(b"upstream connect error").1, "upstream connect error");
    }
}
