//! `lumiere view --benchmark N`: frames per second as the page receives them. A
//! WebSocket client on loopback opens the scene, and for each method of its first
//! family orbits the camera through N full-resolution frames, each asked for and
//! received whole (rendering, encoding and transfer included).

use anyhow::{Context, Result, bail};
use serde_json::{Value, json};
use std::net::{SocketAddr, TcpStream};
use std::time::Instant;
use tungstenite::{Message, WebSocket};

pub fn run(address: SocketAddr, scene: &str, frames: u32) -> Result<()> {
    let stream = TcpStream::connect(address).context("connecting to the viewer's server")?;
    let url = format!("ws://{address}/socket");
    let (mut socket, _) =
        tungstenite::client(url.as_str(), stream).context("opening the viewer's WebSocket")?;
    let mut id = 0;
    let mut ask = |socket: &mut WebSocket<TcpStream>, message: Value| -> Result<Value> {
        id += 1;
        let mut message = message;
        message["id"] = json!(id);
        socket.send(Message::text(message.to_string()))?;
        frame_or_scene(socket, message["type"] == "open")
    };
    let opened = ask(&mut socket, json!({"type": "open", "scene": scene}))?;
    let (width, height) = (opened["width"].clone(), opened["height"].clone());
    let orbit = opened["orbit"].clone();
    let family = opened["families"].get(0).cloned();
    let options: Vec<String> = match &family {
        Some(f) => f["options"]
            .as_array()
            .into_iter()
            .flatten()
            .filter_map(|o| o["name"].as_str().map(String::from))
            .collect(),
        None => vec![String::new()],
    };
    outln!(
        "{scene}, {width} x {height}, {frames} frames orbiting the camera, per method (through the page's WebSocket):"
    )?;
    outln!("| method | first frame (pre-passes) | median frame | frames per second |")?;
    outln!("|---|---|---|---|")?;
    for option in options {
        let mut change = json!({"type": "set", "quality": "full"});
        if let Some(f) = &family {
            change["choices"] = json!({ f["name"].as_str().unwrap_or_default(): option });
        }
        let start = Instant::now();
        ask(&mut socket, change)?;
        let first = start.elapsed();
        let mut times = Vec::new();
        for k in 1..=frames {
            let yaw = 2.0 * std::f64::consts::PI * k as f64 / frames as f64;
            let turned =
                json!({"yaw": yaw, "pitch": orbit["pitch"], "distance": orbit["distance"]});
            let start = Instant::now();
            ask(&mut socket, json!({"type": "set", "orbit": turned}))?;
            times.push(start.elapsed());
        }
        times.sort();
        let median = times[times.len() / 2];
        outln!(
            "| {} | {:.1} ms | {:.1} ms | {:.0} |",
            if option.is_empty() {
                "the scene's"
            } else {
                &option
            },
            first.as_secs_f64() * 1000.0,
            median.as_secs_f64() * 1000.0,
            1.0 / median.as_secs_f64()
        )?;
    }
    Ok(())
}

/// Reads replies up to the frame (after the scene, when `opening`); the scene's
/// header when opening, else the frame's. An error reply fails the benchmark.
fn frame_or_scene(socket: &mut WebSocket<TcpStream>, opening: bool) -> Result<Value> {
    let mut scene = Value::Null;
    loop {
        let header: Value = match socket.read()? {
            Message::Text(text) => serde_json::from_str(&text)?,
            Message::Binary(bytes) => {
                let length = u32::from_le_bytes(bytes[..4].try_into()?) as usize;
                serde_json::from_slice(&bytes[4..4 + length])?
            }
            _ => continue,
        };
        match header["type"].as_str() {
            Some("error") => bail!("{}", header["message"].as_str().unwrap_or_default()),
            Some("scene") => scene = header,
            Some("frame") => return Ok(if opening { scene } else { header }),
            _ => {}
        }
    }
}
