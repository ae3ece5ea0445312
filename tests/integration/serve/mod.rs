//! `snell serve` over HTTP, as a browser and as an attacker would talk to it: every route,
//! the security rules (paths, Host, Origin, bodies), following saves of the scene and its
//! files (in place, renamed over, deleted and recreated, broken and fixed), cancelling a
//! long render, many pages at once, and Ctrl-C. browser.rs drives a real Chromium.

mod browser;
mod routes;
mod watching;

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// A running `snell serve`, stopped when dropped.
pub struct Server {
    pub child: Child,
    pub port: u16,
    pub dir: PathBuf,
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// The seed scene and its texture copied into a scratch folder, as `scenes/seed.toml` and
/// `assets/earth.jpg`, so that a test can edit them.
pub fn seed_copy(name: &str) -> PathBuf {
    let dir = super::scratch(name);
    std::fs::create_dir_all(dir.join("scenes")).unwrap();
    std::fs::create_dir_all(dir.join("assets")).unwrap();
    std::fs::copy(
        super::repo("scenes/seed.toml"),
        dir.join("scenes/seed.toml"),
    )
    .unwrap();
    std::fs::copy(
        super::repo("assets/earth.jpg"),
        dir.join("assets/earth.jpg"),
    )
    .unwrap();
    dir
}

/// A scratch directory `name` holding the repository's `scenes/SCENE` (one that needs no
/// assets), for `start(&dir, "scenes/SCENE", ...)`.
pub fn scene_copy(name: &str, scene: &str) -> PathBuf {
    let dir = super::scratch(name);
    std::fs::create_dir_all(dir.join("scenes")).unwrap();
    let rel = format!("scenes/{scene}");
    std::fs::copy(super::repo(&rel), dir.join(&rel)).unwrap();
    dir
}

/// Starts `snell serve SCENE --port 0` (plus `args`) in `dir`, and waits for its address.
pub fn start(dir: &Path, scene: &str, args: &[&str]) -> Server {
    let mut child = Command::new(env!("CARGO_BIN_EXE_snell"))
        .args(["serve", scene, "--port", "0"])
        .args(args)
        .current_dir(dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut line = String::new();
    BufReader::new(child.stdout.as_mut().unwrap())
        .read_line(&mut line)
        .unwrap();
    let port = line
        .split("http://127.0.0.1:")
        .nth(1)
        .and_then(|rest| rest.split('/').next())
        .and_then(|p| p.parse().ok())
        .unwrap_or_else(|| panic!("no address in {line:?}"));
    Server {
        child,
        port,
        dir: dir.to_path_buf(),
    }
}

/// A response: status, headers (lower-case names) and body.
pub struct Reply {
    pub status: u16,
    pub headers: Vec<(String, String)>,
    pub body: Vec<u8>,
}

impl Reply {
    pub fn header(&self, name: &str) -> Option<&str> {
        self.headers
            .iter()
            .find(|(k, _)| k == name)
            .map(|(_, v)| v.as_str())
    }

    pub fn text(&self) -> String {
        String::from_utf8_lossy(&self.body).into_owned()
    }

    pub fn json(&self) -> serde_json::Value {
        serde_json::from_slice(&self.body)
            .unwrap_or_else(|e| panic!("not JSON ({e}): {}", self.text()))
    }
}

/// Sends `head` (request line and headers, without the blank line) and `body`, reads the
/// whole answer (the connection is closed after it).
pub fn raw(port: u16, head: &str, body: &[u8]) -> Reply {
    let mut s = TcpStream::connect(("127.0.0.1", port)).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(60))).unwrap();
    let mut req = head.replace('\n', "\r\n").into_bytes();
    req.extend_from_slice(b"\r\n\r\n");
    req.extend_from_slice(body);
    s.write_all(&req).unwrap();
    let mut all = vec![];
    s.read_to_end(&mut all).unwrap();
    parse(&all)
}

fn parse(all: &[u8]) -> Reply {
    let end = all
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .unwrap_or_else(|| panic!("no header end in {:?}", String::from_utf8_lossy(all)));
    let head = String::from_utf8_lossy(&all[..end]).into_owned();
    let mut lines = head.split("\r\n");
    let status = lines
        .next()
        .and_then(|l| l.split(' ').nth(1))
        .and_then(|s| s.parse().ok())
        .unwrap();
    let headers: Vec<(String, String)> = lines
        .filter_map(|l| l.split_once(':'))
        .map(|(k, v)| (k.trim().to_ascii_lowercase(), v.trim().to_string()))
        .collect();
    let mut body = all[end + 4..].to_vec();
    if headers
        .iter()
        .any(|(k, v)| k == "transfer-encoding" && v.contains("chunked"))
    {
        body = unchunk(&body);
    }
    Reply {
        status,
        headers,
        body,
    }
}

fn unchunk(mut b: &[u8]) -> Vec<u8> {
    let mut out = vec![];
    loop {
        let Some(eol) = b.windows(2).position(|w| w == b"\r\n") else {
            return out;
        };
        let n = usize::from_str_radix(String::from_utf8_lossy(&b[..eol]).trim(), 16).unwrap_or(0);
        if n == 0 {
            return out;
        }
        out.extend_from_slice(&b[eol + 2..eol + 2 + n]);
        b = &b[eol + 2 + n + 2..];
    }
}

/// GET `path` with this server's own Host.
pub fn get(port: u16, path: &str) -> Reply {
    raw(
        port,
        &format!("GET {path} HTTP/1.1\nHost: 127.0.0.1:{port}\nConnection: close"),
        b"",
    )
}

/// POST `body` to `path` with this server's own Host and Origin.
pub fn post(port: u16, path: &str, body: &str) -> Reply {
    raw(
        port,
        &format!(
            "POST {path} HTTP/1.1\nHost: 127.0.0.1:{port}\nOrigin: http://127.0.0.1:{port}\nContent-Type: application/json\nContent-Length: {}\nConnection: close",
            body.len()
        ),
        body.as_bytes(),
    )
}

/// The server's status.
pub fn status(port: u16) -> serde_json::Value {
    get(port, "/status").json()
}

/// Waits (up to `secs`) until the status satisfies `ok`, and returns it.
pub fn wait_for(
    port: u16,
    secs: u64,
    what: &str,
    ok: impl Fn(&serde_json::Value) -> bool,
) -> serde_json::Value {
    let start = Instant::now();
    loop {
        let s = status(port);
        if ok(&s) {
            return s;
        }
        assert!(
            start.elapsed() < Duration::from_secs(secs),
            "waited {secs} s for {what}; the status is {s}"
        );
        std::thread::sleep(Duration::from_millis(10));
    }
}

/// Whether the newest frame is of the newest render, with `spp` samples at least.
pub fn current_frame(s: &serde_json::Value) -> bool {
    s["frame"]["generation"] == s["generation"] && s["generation"].as_u64().unwrap_or(0) > 0
}
