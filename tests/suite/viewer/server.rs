//! `lumiere view` as a user's browser meets it: the page's files over HTTP and its
//! messages over a real WebSocket on 127.0.0.1. Malformed, oversized and
//! out-of-order messages each get an error and the server stays up; other hosts
//! and other origins are refused; the socket is bound to loopback alone.

use serde_json::{Value, json};
use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::time::Duration;
use tungstenite::{Message, WebSocket};

/// A `lumiere view --no-open` process, killed when dropped.
pub struct Server {
    pub child: Child,
    pub port: u16,
    pub url: String,
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

impl Server {
    pub fn start(args: &[&str]) -> Server {
        let mut child = Command::new(env!("CARGO_BIN_EXE_lumiere"))
            .arg("view")
            .args(args)
            .arg("--no-open")
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("the binary runs");
        let mut line = String::new();
        BufReader::new(child.stdout.take().unwrap())
            .read_line(&mut line)
            .unwrap();
        let url = line
            .split_whitespace()
            .find(|w| w.starts_with("http://"))
            .unwrap_or_else(|| panic!("no address in {line:?}"))
            .to_string();
        let port = url["http://127.0.0.1:".len()..]
            .split('/')
            .next()
            .unwrap()
            .parse()
            .unwrap();
        Server { child, port, url }
    }

    /// A raw HTTP/1.1 exchange: the status line's code and the body.
    pub fn request(&self, head: &str) -> (u16, Vec<u8>) {
        let mut stream = TcpStream::connect(("127.0.0.1", self.port)).unwrap();
        stream.write_all(head.as_bytes()).unwrap();
        // A refusal closes the connection; an answer that keeps it open (an
        // upgrade let through) is read for as long as the timeout.
        stream
            .set_read_timeout(Some(Duration::from_secs(10)))
            .unwrap();
        let mut answer = Vec::new();
        if let Err(e) = stream.read_to_end(&mut answer) {
            assert!(!answer.is_empty(), "no answer to {head:.60}: {e}");
        }
        let text = String::from_utf8_lossy(&answer);
        let code = text.split(' ').nth(1).unwrap().parse().unwrap();
        let body = match answer.windows(4).position(|w| w == b"\r\n\r\n") {
            Some(at) => answer[at + 4..].to_vec(),
            None => Vec::new(),
        };
        (code, body)
    }

    pub fn socket(&self) -> WebSocket<TcpStream> {
        let stream = TcpStream::connect(("127.0.0.1", self.port)).unwrap();
        stream
            .set_read_timeout(Some(Duration::from_secs(120)))
            .unwrap();
        let url = format!("ws://127.0.0.1:{}/socket", self.port);
        tungstenite::client(url.as_str(), stream)
            .expect("the socket opens")
            .0
    }
}

/// The headers of the replies to one message, up to its frame or error.
fn exchange(socket: &mut WebSocket<TcpStream>, message: Message) -> Vec<Value> {
    socket.send(message).unwrap();
    let mut headers = Vec::new();
    loop {
        let header: Value = match socket.read().expect("the server answers") {
            Message::Text(text) => serde_json::from_str(&text).unwrap(),
            Message::Binary(bytes) => {
                let length = u32::from_le_bytes(bytes[..4].try_into().unwrap()) as usize;
                serde_json::from_slice(&bytes[4..4 + length]).unwrap()
            }
            _ => continue,
        };
        let end = matches!(header["type"].as_str(), Some("frame" | "error" | "export"));
        headers.push(header);
        if end {
            return headers;
        }
    }
}

fn error_of(headers: &[Value]) -> String {
    let last = headers.last().unwrap();
    assert_eq!(last["type"], "error", "{headers:?}");
    last["message"].as_str().unwrap().to_string()
}

const SIZE: [&str; 4] = ["--width", "48", "--height", "40"];

#[test]
fn bad_messages_get_an_error_and_the_server_stays_up() {
    let server = Server::start(&["cornell-box-point", SIZE[0], SIZE[1], SIZE[2], SIZE[3]]);
    let mut socket = server.socket();
    // Out of order: a change before any scene is open.
    let said = error_of(&exchange(
        &mut socket,
        Message::text(json!({"type": "set", "id": 1}).to_string()),
    ));
    assert!(said.contains("no scene is open"), "{said}");
    // Malformed: not JSON, a binary message too short for its header.
    let said = error_of(&exchange(&mut socket, Message::text("{not json")));
    assert!(said.contains("not JSON"), "{said}");
    let said = error_of(&exchange(&mut socket, Message::binary(vec![9u8, 0])));
    assert!(said.contains("binary message"), "{said}");
    // Oversized: more than the 64 MiB a message may have.
    let big = vec![b' '; lumiere::viewer::MAX_MESSAGE + 1];
    let said = error_of(&exchange(&mut socket, Message::binary(big)));
    assert!(said.contains("MiB"), "{said}");
    // The scene the command line named opens, with its overrides.
    let opened = exchange(
        &mut socket,
        Message::text(json!({"type": "open", "id": 2, "scene": "cornell-box-point"}).to_string()),
    );
    assert_eq!(opened[0]["type"], "scene");
    assert_eq!(
        (opened[1]["width"].as_u64(), opened[1]["height"].as_u64()),
        (Some(48), Some(40))
    );
    // No file of the machine opens through the page: only the catalogue and the
    // command line's scene.
    let said = error_of(&exchange(
        &mut socket,
        Message::text(json!({"type": "open", "id": 3, "scene": "Cargo.toml"}).to_string()),
    ));
    assert!(said.contains("not a catalogue entry"), "{said}");
    let frame = exchange(
        &mut socket,
        Message::text(
            json!({"type": "set", "id": 4, "choices": {"shadows": "shadow-volumes"}}).to_string(),
        ),
    );
    assert_eq!(frame[0]["method"], "shadow-volumes");
    // A page that goes away without closing leaves the server answering others.
    drop(socket);
    let mut again = server.socket();
    let frame = exchange(
        &mut again,
        Message::text(json!({"type": "open", "id": 1, "scene": "shadow-map"}).to_string()),
    );
    assert_eq!(frame.last().unwrap()["type"], "frame");
    // The page's `quit` ends the server, status 0.
    again
        .send(Message::text(json!({"type": "quit", "id": 9}).to_string()))
        .unwrap();
    let mut server = server;
    let status = server.child.wait().unwrap();
    assert!(status.success(), "{status}");
}

#[test]
fn the_server_is_on_loopback_alone_and_refuses_other_hosts_and_origins() {
    let server = Server::start(&["cornell-box-point", SIZE[0], SIZE[1], SIZE[2], SIZE[3]]);
    assert!(
        server.url.starts_with("http://127.0.0.1:"),
        "{}",
        server.url
    );
    // The kernel's table of listening sockets: this port, bound to 127.0.0.1 only.
    let table = std::fs::read_to_string("/proc/net/tcp").unwrap()
        + &std::fs::read_to_string("/proc/net/tcp6").unwrap_or_default();
    let port = format!(":{:04X} ", server.port);
    let listening: Vec<&str> = table
        .lines()
        .filter(|l| {
            l.split_whitespace()
                .nth(1)
                .is_some_and(|a| format!("{a} ").ends_with(&port))
        })
        .filter(|l| l.split_whitespace().nth(3) == Some("0A"))
        .map(|l| l.split_whitespace().nth(1).unwrap())
        .collect();
    assert_eq!(
        listening,
        [format!("0100007F{}", port.trim_end())],
        "{listening:?}"
    );
    let host = format!("127.0.0.1:{}", server.port);
    let (code, body) = server.request(&format!("GET / HTTP/1.1\r\nHost: {host}\r\n\r\n"));
    assert_eq!(code, 200);
    assert!(
        String::from_utf8_lossy(&body).contains("<canvas"),
        "the page"
    );
    let (code, _) = server.request(&format!("GET /viewer.js HTTP/1.1\r\nHost: {host}\r\n\r\n"));
    assert_eq!(code, 200);
    let (code, _) = server.request(&format!(
        "GET /../Cargo.toml HTTP/1.1\r\nHost: {host}\r\n\r\n"
    ));
    assert_eq!(code, 404);
    // A name that resolves elsewhere to this port (DNS rebinding): refused.
    let (code, _) = server.request(&format!(
        "GET / HTTP/1.1\r\nHost: example.com:{}\r\n\r\n",
        server.port
    ));
    assert_eq!(code, 403);
    // A WebSocket opened by a page of another origin: refused.
    let upgrade = |origin: &str| {
        format!(
            "GET /socket HTTP/1.1\r\nHost: {host}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\nSec-WebSocket-Version: 13\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nOrigin: {origin}\r\n\r\n"
        )
    };
    let (code, _) = server.request(&upgrade("http://example.com"));
    assert_eq!(code, 403);
    let mut stream = TcpStream::connect(("127.0.0.1", server.port)).unwrap();
    stream
        .write_all(upgrade(&format!("http://{host}")).as_bytes())
        .unwrap();
    let mut line = String::new();
    BufReader::new(stream).read_line(&mut line).unwrap();
    assert!(line.starts_with("HTTP/1.1 101"), "{line}");
    // A head without end, larger than any request: refused, the server goes on.
    let (code, _) = server.request(&format!(
        "GET / HTTP/1.1\r\nHost: {host}\r\nX: {}\r\n\r\n",
        "a".repeat(20_000)
    ));
    assert_eq!(code, 431);
    let (code, _) = server.request(&format!("GET / HTTP/1.1\r\nHost: {host}\r\n\r\n"));
    assert_eq!(code, 200);
}

#[test]
fn a_scene_that_cannot_load_is_one_line_before_any_server() {
    let out = Command::new(env!("CARGO_BIN_EXE_lumiere"))
        .args(["view", "no-such-entry", "--no-open"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("no-such-entry"), "{stderr}");
}

#[test]
fn ctrl_c_ends_the_server_and_frees_its_port() {
    let mut server = Server::start(&["cornell-box-point", SIZE[0], SIZE[1], SIZE[2], SIZE[3]]);
    let mut socket = server.socket();
    exchange(
        &mut socket,
        Message::text(json!({"type": "open", "id": 1, "scene": "cornell-box-point"}).to_string()),
    );
    let kill = Command::new("kill")
        .args(["-INT", &server.child.id().to_string()])
        .status()
        .unwrap();
    assert!(kill.success());
    // Interrupted, as any lumiere command: 128 + SIGINT, nothing left behind.
    assert_eq!(server.child.wait().unwrap().code(), Some(130));
    assert!(
        TcpStream::connect(("127.0.0.1", server.port)).is_err(),
        "the port is free"
    );
}
