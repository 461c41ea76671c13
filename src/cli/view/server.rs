//! The viewer's server: HTTP for the page's files and one WebSocket a page for its
//! messages, on 127.0.0.1 only. Each connection is a thread with a session of its
//! own (`lumiere::viewer::Session`, the engine the WebAssembly worker runs too).
//! The socket is read with a short timeout so that a radiosity solve goes on
//! between messages. A request from another host name than this machine's
//! loopback (a page elsewhere reaching it by DNS rebinding) is refused, and so is
//! a WebSocket opened by a page of another origin.

use super::super::url::percent_encoded;
use super::page;
use anyhow::{Context, Result};
use lumiere::viewer::{MAX_MESSAGE, Reply, Session};
use std::io::{ErrorKind, Read, Write};
use std::net::{Ipv4Addr, SocketAddr, TcpListener, TcpStream};
use std::time::Duration;
use tungstenite::protocol::{Role, WebSocketConfig};
use tungstenite::{Message, WebSocket};

/// The longest request head read (request line and headers).
const MAX_HEAD: usize = 16 << 10;
/// How long the socket waits for a message before the solve goes on.
const POLL: Duration = Duration::from_millis(20);

pub struct Server {
    listener: TcpListener,
    scene: String,
    sets: Vec<String>,
}

impl Server {
    /// Listens on 127.0.0.1, on `port` or a free one.
    pub fn bind(port: Option<u16>, scene: String, sets: Vec<String>) -> Result<Server> {
        let port = port.unwrap_or(0);
        let listener = TcpListener::bind((Ipv4Addr::LOCALHOST, port))
            .with_context(|| format!("--port {port}: cannot listen on 127.0.0.1:{port}"))?;
        Ok(Server {
            listener,
            scene,
            sets,
        })
    }

    pub fn address(&self) -> SocketAddr {
        self.listener.local_addr().expect("a bound listener")
    }

    /// The page's address, opened on the scene.
    pub fn page_url(&self) -> String {
        format!(
            "http://{}/?engine=socket&scene={}",
            self.address(),
            percent_encoded(&self.scene)
        )
    }

    /// Answers connections until the process ends.
    pub fn serve(self) {
        let port = self.address().port();
        for stream in self.listener.incoming().flatten() {
            let (scene, sets) = (self.scene.clone(), self.sets.clone());
            std::thread::spawn(move || {
                if let Err(e) = connection(stream, port, scene, sets) {
                    eprintln!("lumiere view: a connection failed: {e}");
                }
            });
        }
    }
}

/// One connection: a page file, or the WebSocket.
fn connection(mut stream: TcpStream, port: u16, scene: String, sets: Vec<String>) -> Result<()> {
    stream.set_read_timeout(Some(Duration::from_secs(10)))?;
    let Some(head) = read_head(&mut stream)? else {
        return respond(&mut stream, 431, "text/plain", b"request head too large");
    };
    let mut headers = [httparse::EMPTY_HEADER; 64];
    let mut request = httparse::Request::new(&mut headers);
    if !matches!(request.parse(&head), Ok(httparse::Status::Complete(_))) {
        return respond(&mut stream, 400, "text/plain", b"not an HTTP request");
    }
    let header = |name: &str| {
        request
            .headers
            .iter()
            .find(|h| h.name.eq_ignore_ascii_case(name))
            .and_then(|h| std::str::from_utf8(h.value).ok())
    };
    let loopback = [
        format!("127.0.0.1:{port}"),
        format!("localhost:{port}"),
        format!("[::1]:{port}"),
    ];
    if !header("host").is_some_and(|h| loopback.iter().any(|l| l == h)) {
        return respond(&mut stream, 403, "text/plain", b"only this machine's pages");
    }
    let path = request.path.unwrap_or("/");
    let path = path.split(['?', '#']).next().unwrap_or("/");
    if request.method != Some("GET") {
        return respond(&mut stream, 405, "text/plain", b"GET only");
    }
    if path == "/socket" {
        let origin_ok =
            header("origin").is_none_or(|o| loopback.iter().any(|l| o == format!("http://{l}")));
        let key = header("sec-websocket-key");
        let upgrade = header("upgrade").is_some_and(|u| u.eq_ignore_ascii_case("websocket"));
        let (true, Some(key), true) = (origin_ok, key, upgrade) else {
            return respond(
                &mut stream,
                403,
                "text/plain",
                b"a WebSocket from this page only",
            );
        };
        let accept = tungstenite::handshake::derive_accept_key(key.as_bytes());
        write!(
            stream,
            "HTTP/1.1 101 Switching Protocols\r\nUpgrade: websocket\r\nConnection: Upgrade\r\nSec-WebSocket-Accept: {accept}\r\n\r\n"
        )?;
        return socket(stream, Session::allowing(&scene, sets));
    }
    match page::file(path.trim_start_matches('/')) {
        Some((bytes, media)) => respond(&mut stream, 200, media, bytes),
        None => respond(&mut stream, 404, "text/plain", b"no such file"),
    }
}

/// The request head, up to its blank line; `None` when longer than `MAX_HEAD`.
fn read_head(stream: &mut TcpStream) -> Result<Option<Vec<u8>>> {
    let mut head = Vec::new();
    let mut byte = [0u8; 1];
    while !head.ends_with(b"\r\n\r\n") {
        if head.len() >= MAX_HEAD {
            return Ok(None);
        }
        // Byte by byte: nothing past the head is taken from the stream.
        if stream.read(&mut byte)? == 0 {
            anyhow::bail!("the connection closed in the request head");
        }
        head.push(byte[0]);
    }
    Ok(Some(head))
}

fn respond(stream: &mut TcpStream, status: u16, media: &str, body: &[u8]) -> Result<()> {
    let reason = match status {
        200 => "OK",
        400 => "Bad Request",
        403 => "Forbidden",
        404 => "Not Found",
        405 => "Method Not Allowed",
        _ => "Request Header Fields Too Large",
    };
    write!(
        stream,
        "HTTP/1.1 {status} {reason}\r\nContent-Type: {media}\r\nContent-Length: {}\r\nCache-Control: no-cache\r\nConnection: close\r\n\r\n",
        body.len()
    )?;
    stream.write_all(body)?;
    stream.flush()?;
    // What the client still sends (the rest of a refused head) is read and
    // dropped, so that closing does not reset the connection before it reads
    // the answer.
    stream.shutdown(std::net::Shutdown::Write)?;
    stream.set_read_timeout(Some(Duration::from_millis(200)))?;
    let _ = std::io::copy(&mut (&mut *stream).take(1 << 20), &mut std::io::sink());
    Ok(())
}

/// The page's messages, answered until it closes; a radiosity solve goes on
/// while none comes.
fn socket(stream: TcpStream, mut session: Session) -> Result<()> {
    stream.set_read_timeout(Some(POLL))?;
    // Past the session's own limit, so that it answers an oversized message with
    // its error; beyond this the connection ends.
    let config = WebSocketConfig::default()
        .max_message_size(Some(MAX_MESSAGE + (16 << 20)))
        .max_frame_size(Some(MAX_MESSAGE + (16 << 20)));
    let mut socket = WebSocket::from_raw_socket(stream, Role::Server, Some(config));
    loop {
        let replies = match socket.read() {
            Ok(Message::Text(text)) => session.handle_text(&text),
            Ok(Message::Binary(bytes)) => session.handle_binary(&bytes),
            Ok(Message::Close(_)) => {
                let _ = socket.flush();
                return Ok(());
            }
            Ok(_) => continue,
            Err(tungstenite::Error::Io(e))
                if matches!(e.kind(), ErrorKind::WouldBlock | ErrorKind::TimedOut) =>
            {
                session.tick()
            }
            Err(tungstenite::Error::ConnectionClosed | tungstenite::Error::AlreadyClosed) => {
                return Ok(());
            }
            Err(e) => {
                // What the socket cannot read ends this connection, not the server.
                let said = serde_json::json!({"type": "error", "id": null, "message": format!("the connection ends: {e}")});
                let _ = socket.send(Message::text(said.to_string()));
                return Ok(());
            }
        };
        for reply in replies {
            let message = match reply {
                Reply::Text(text) => Message::text(text),
                Reply::Binary(bytes) => Message::binary(bytes),
            };
            socket.send(message)?;
        }
        if session.quit() {
            let _ = socket.close(None);
            let _ = socket.flush();
            eprintln!("lumiere view: the page asked to stop");
            std::process::exit(0);
        }
    }
}
