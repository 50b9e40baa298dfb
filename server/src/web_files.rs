//! The web viewer's files on the gRPC port (issue 35): the built page and nothing else —
//! `index.html` (at `/` and `/index.html`) and the files of its build output `dist/` that
//! web/build.sh makes (esbuild's `app.js` and `app.css`: one level, names of ASCII letters,
//! digits, `.`, `_` and `-`, ending `.js`, `.css` or `.map`), the same set the container image
//! copies. Each is opened below `--web-dir` one component at a time without following a symbolic
//! link (`openat` with `O_NOFOLLOW`), as a regular file of at most [`MAX_ASSET_BYTES`]. Every other
//! path is 404: the rest of web/ (README.md, package.json, src/, test/, node_modules/), a link
//! inside web/, and paths that try to leave it (`..`, `%2e%2e`, `//etc/passwd`), which match no
//! name (nothing is decoded).
//!
//! The files are read once, when the server starts ([`WebFiles::load`]), into shared [`Bytes`]:
//! a response holds a reference to them, not a copy (issue 35: 5,000 stalled `GET /dist/app.js` on
//! one connection held 5,000 copies, 4 GB). A rebuilt web/ is served from the next start.

use std::collections::HashMap;
use std::ffi::CString;
use std::io::{self, Read};
use std::os::fd::{AsRawFd, FromRawFd, OwnedFd};
use std::os::unix::ffi::OsStrExt;
use std::path::Path;
use std::sync::Arc;

use axum::http::{HeaderValue, Method, StatusCode, header};
use axum::response::Response;
use bytes::Bytes;

/// The largest file served (the viewer's bundle is under 1 MB).
pub const MAX_ASSET_BYTES: u64 = 32 << 20;
/// The most bytes of all the files together, and the most files of `dist/`, kept in memory; past
/// them the rest are not served (logged at start).
pub const MAX_WEB_BYTES: u64 = 64 << 20;
pub const MAX_WEB_FILES: usize = 256;

/// One of the viewer's files: its directory below `--web-dir` (none, or `dist`), its name and
/// its media type.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Asset {
    dir: Option<&'static str>,
    name: String,
    content_type: &'static str,
}

impl Asset {
    /// Its name below `--web-dir` (`index.html`, `dist/app.js`): the key of [`WebFiles`].
    fn key(&self) -> String {
        match self.dir {
            Some(d) => format!("{d}/{}", self.name),
            None => self.name.clone(),
        }
    }
}

/// Why a file is not served.
#[derive(Debug, thiserror::Error)]
pub enum AssetError {
    #[error("not one of the viewer's files")]
    NotFound,
    #[error("{0} bytes, over the bound of {MAX_ASSET_BYTES}")]
    TooLarge(u64),
    #[error("cannot read the file: {0}")]
    Io(#[from] io::Error),
}

/// The viewer's file a request path names, if any (the path exactly, not decoded).
pub fn asset(path: &str) -> Option<Asset> {
    if path == "/" || path == "/index.html" {
        return Some(Asset { dir: None, name: "index.html".into(), content_type: "text/html; charset=utf-8" });
    }
    let name = path.strip_prefix("/dist/")?;
    let plain = name.bytes().all(|b| b.is_ascii_alphanumeric() || matches!(b, b'.' | b'_' | b'-'));
    if name.is_empty() || name.len() > 128 || name.starts_with('.') || !plain {
        return None;
    }
    let content_type = match name.rsplit_once('.')?.1 {
        "js" => "text/javascript; charset=utf-8",
        "css" => "text/css; charset=utf-8",
        "map" => "application/json",
        _ => return None,
    };
    Some(Asset { dir: Some("dist"), name: name.into(), content_type })
}

/// `openat(dir, name, flags | O_CLOEXEC)`.
fn open_at(dir: Option<&OwnedFd>, name: &[u8], flags: libc::c_int) -> Result<OwnedFd, AssetError> {
    let name = CString::new(name).map_err(|_| AssetError::NotFound)?;
    let at = dir.map_or(libc::AT_FDCWD, |d| d.as_raw_fd());
    // SAFETY: `name` is a NUL-terminated string that outlives the call; `at` is AT_FDCWD or an
    // open descriptor borrowed for the call.
    let fd = unsafe { libc::openat(at, name.as_ptr(), flags | libc::O_CLOEXEC) };
    if fd < 0 {
        let e = io::Error::last_os_error();
        return Err(match e.raw_os_error() {
            // Missing, a symbolic link (O_NOFOLLOW), or not a directory on the way.
            Some(libc::ENOENT | libc::ELOOP | libc::ENOTDIR) => AssetError::NotFound,
            _ => AssetError::Io(e),
        });
    }
    // SAFETY: `fd` was just opened and is owned by nobody else.
    Ok(unsafe { OwnedFd::from_raw_fd(fd) })
}

/// The contents of `asset` below `web_dir` (which itself may be a link, as the operator set it).
pub fn read(web_dir: &Path, asset: &Asset) -> Result<Vec<u8>, AssetError> {
    let mut dir = open_at(None, web_dir.as_os_str().as_bytes(), libc::O_RDONLY | libc::O_DIRECTORY)?;
    if let Some(sub) = asset.dir {
        dir = open_at(Some(&dir), sub.as_bytes(), libc::O_RDONLY | libc::O_DIRECTORY | libc::O_NOFOLLOW)?;
    }
    // O_NONBLOCK: a FIFO put there does not block the open (and is refused below).
    let fd = open_at(Some(&dir), asset.name.as_bytes(), libc::O_RDONLY | libc::O_NOFOLLOW | libc::O_NONBLOCK)?;
    let file = std::fs::File::from(fd);
    let meta = file.metadata()?;
    if !meta.file_type().is_file() {
        return Err(AssetError::NotFound);
    }
    if meta.len() > MAX_ASSET_BYTES {
        return Err(AssetError::TooLarge(meta.len()));
    }
    let mut out = Vec::with_capacity(usize::try_from(meta.len()).unwrap_or(0));
    file.take(MAX_ASSET_BYTES + 1).read_to_end(&mut out)?;
    if out.len() as u64 > MAX_ASSET_BYTES {
        return Err(AssetError::TooLarge(out.len() as u64));
    }
    Ok(out)
}

fn plain(status: StatusCode, text: &'static str) -> Response {
    let mut r = Response::new(axum::body::Body::from(text));
    *r.status_mut() = status;
    r.headers_mut().insert(header::CONTENT_TYPE, HeaderValue::from_static("text/plain; charset=utf-8"));
    r
}

/// The viewer's files, read once at start; cheap to clone (one shared map).
#[derive(Debug, Clone, Default)]
pub struct WebFiles {
    /// By file name below `--web-dir` (`index.html`, `dist/app.js`): contents and media type.
    files: Arc<HashMap<String, (Bytes, &'static str)>>,
}

impl WebFiles {
    /// Reads `index.html` and the files of `dist/` that [`asset`] names, below `web_dir`, within
    /// [`MAX_WEB_FILES`] and [`MAX_WEB_BYTES`]. A file that cannot be read is logged and not
    /// served; a missing `web_dir` serves nothing (404 for every path).
    pub fn load(web_dir: &Path) -> Self {
        let mut names = vec!["/index.html".to_owned()];
        match std::fs::read_dir(web_dir.join("dist")) {
            Ok(entries) => {
                let mut dist: Vec<String> = entries
                    .filter_map(|e| e.ok()?.file_name().into_string().ok())
                    .map(|n| format!("/dist/{n}"))
                    .filter(|p| asset(p).is_some())
                    .collect();
                dist.sort();
                if dist.len() > MAX_WEB_FILES {
                    tracing::warn!(web_dir = %web_dir.display(), files = dist.len(), max = MAX_WEB_FILES, "the web viewer's dist/ has too many files: the first ones by name are served");
                    dist.truncate(MAX_WEB_FILES);
                }
                names.extend(dist);
            }
            Err(e) => {
                tracing::warn!(web_dir = %web_dir.display(), error = %e, "the web viewer's dist/ cannot be listed: its files are not served")
            }
        }
        let mut files = HashMap::new();
        let mut total = 0u64;
        for path in names {
            let Some(a) = asset(&path) else { continue };
            let key = a.key();
            match read(web_dir, &a) {
                Ok(bytes) if total + bytes.len() as u64 <= MAX_WEB_BYTES => {
                    total += bytes.len() as u64;
                    files.insert(key, (Bytes::from(bytes), a.content_type));
                }
                Ok(bytes) => {
                    tracing::warn!(file = %key, bytes = bytes.len(), max = MAX_WEB_BYTES, "the web viewer's files pass their bound together: this one is not served");
                }
                Err(AssetError::NotFound) => {}
                Err(e) => {
                    tracing::warn!(web_dir = %web_dir.display(), file = %key, error = %e, "cannot read a file of the web viewer: it is not served")
                }
            }
        }
        Self { files: Arc::new(files) }
    }

    /// Files held, and their bytes together.
    pub fn size(&self) -> (usize, u64) {
        (self.files.len(), self.files.values().map(|(b, _)| b.len() as u64).sum())
    }

    /// The answer to a request for a static file: the file (GET, HEAD), 405 (another method on
    /// one of the files), 404 (anything else, or a file that was not there at start).
    pub fn respond(&self, method: &Method, path: &str) -> Response {
        let Some(a) = asset(path) else {
            return plain(StatusCode::NOT_FOUND, "not found\n");
        };
        let Some((bytes, content_type)) = self.files.get(&a.key()) else {
            return plain(StatusCode::NOT_FOUND, "not found\n");
        };
        if method != Method::GET && method != Method::HEAD {
            let mut r = plain(StatusCode::METHOD_NOT_ALLOWED, "method not allowed\n");
            r.headers_mut().insert(header::ALLOW, HeaderValue::from_static("GET, HEAD"));
            return r;
        }
        let len = bytes.len();
        // A clone of the shared bytes: a reference count, not a copy.
        let body = if method == Method::HEAD { axum::body::Body::empty() } else { axum::body::Body::from(bytes.clone()) };
        let mut r = Response::new(body);
        let h = r.headers_mut();
        h.insert(header::CONTENT_TYPE, HeaderValue::from_static(content_type));
        h.insert(header::CONTENT_LENGTH, HeaderValue::from(len));
        h.insert(header::CACHE_CONTROL, HeaderValue::from_static("no-cache"));
        h.insert(header::X_CONTENT_TYPE_OPTIONS, HeaderValue::from_static("nosniff"));
        r
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_built_page_is_named() {
        for ok in ["/", "/index.html", "/dist/app.js", "/dist/app.css", "/dist/app.js.map", "/dist/chunk-AB12_c.js"] {
            assert!(asset(ok).is_some(), "{ok}");
        }
        for no in [
            "",
            "/README.md",
            "/package.json",
            "/src/main.ts",
            "/test/history.test.mjs",
            "/dist/",
            "/dist/.hidden.js",
            "/dist/../README.md",
            "/dist/%2e%2e/README.md",
            "/%2e%2e/%2e%2e/etc/passwd",
            "//etc/passwd",
            "/dist//etc/passwd.js",
            "/dist/sub/app.js",
            "/dist/app.ts",
            "/dist/app",
            "/index.html/",
            "/dist/app.js\0.css",
        ] {
            assert!(asset(no).is_none(), "{no:?}");
        }
    }

    #[test]
    fn links_and_non_files_are_not_read() {
        let dir = std::env::temp_dir().join(format!("needlesim-web-files-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(dir.join("dist")).unwrap();
        std::fs::write(dir.join("index.html"), "<html>").unwrap();
        std::fs::write(dir.join("secret.txt"), "secret").unwrap();
        std::fs::write(dir.join("dist/app.js"), "js").unwrap();
        std::os::unix::fs::symlink(dir.join("secret.txt"), dir.join("dist/link.js")).unwrap();
        std::fs::create_dir(dir.join("dist/dir.js")).unwrap();
        assert_eq!(read(&dir, &asset("/").unwrap()).unwrap(), b"<html>");
        assert_eq!(read(&dir, &asset("/dist/app.js").unwrap()).unwrap(), b"js");
        for no in ["/dist/link.js", "/dist/dir.js", "/dist/missing.js"] {
            assert!(matches!(read(&dir, &asset(no).unwrap()), Err(AssetError::NotFound)), "{no}");
        }
        // dist/ itself a link: not followed.
        std::fs::rename(dir.join("dist"), dir.join("real")).unwrap();
        std::os::unix::fs::symlink(dir.join("real"), dir.join("dist")).unwrap();
        assert!(matches!(read(&dir, &asset("/dist/app.js").unwrap()), Err(AssetError::NotFound)));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
