//! The viewer's messages as bytes (docs/viewer-protocol.md): JSON text, and binary
//! messages made of a little-endian header length, a JSON header and a payload.

use serde::Deserialize;
use serde_json::{Value, json};
use std::collections::HashMap;

/// The largest message read: a scene's files sent whole.
pub const MAX_MESSAGE: usize = 64 << 20;

/// A message from the engine to the page.
#[derive(Clone, Debug, PartialEq)]
pub enum Reply {
    /// One JSON object.
    Text(String),
    /// Header length (u32, little-endian), JSON header, payload.
    Binary(Vec<u8>),
}

impl Reply {
    /// The JSON object of a text reply, or the header of a binary one.
    pub fn header(&self) -> Option<Value> {
        match self {
            Reply::Text(text) => serde_json::from_str(text).ok(),
            Reply::Binary(bytes) => split_binary(bytes).ok().map(|(h, _)| h),
        }
    }

    /// The payload of a binary reply (empty for text).
    pub fn payload(&self) -> &[u8] {
        match self {
            Reply::Text(_) => &[],
            Reply::Binary(bytes) => split_binary(bytes).map(|(_, p)| p).unwrap_or(&[]),
        }
    }
}

/// A request of the page's.
#[derive(Debug, Deserialize)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
pub enum Request {
    Catalogue {
        id: u64,
    },
    Open {
        id: u64,
        scene: String,
        #[serde(default)]
        sets: Vec<String>,
    },
    OpenFiles {
        id: u64,
        main: String,
        files: Vec<FileSize>,
        #[serde(default)]
        sets: Vec<String>,
    },
    Set(Box<Change>),
    Solve {
        id: u64,
        action: SolveAction,
    },
    Export {
        id: u64,
        what: String,
    },
    Quit {
        id: u64,
    },
}

/// A file of an `open-files` message: its name and how many bytes it has.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FileSize {
    pub name: String,
    pub size: usize,
}

/// What a `set` changes; what it leaves out stays.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Change {
    pub id: u64,
    pub orbit: Option<OrbitState>,
    pub choices: Option<HashMap<String, String>>,
    pub lights: Option<Vec<[f64; 3]>>,
    /// An option of the first family, or null for no split.
    #[serde(default, deserialize_with = "present")]
    pub split: Option<Option<String>>,
    pub difference: Option<bool>,
    /// A buffer's name, or null for the image.
    #[serde(default, deserialize_with = "present")]
    pub buffer: Option<Option<String>>,
    pub exposure: Option<f32>,
    pub quality: Option<Quality>,
}

/// A field given as null is `Some(None)`, one left out `None`.
fn present<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Option<Option<String>>, D::Error> {
    Option::<String>::deserialize(d).map(Some)
}

#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OrbitState {
    pub yaw: f64,
    pub pitch: f64,
    pub distance: f64,
}

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Quality {
    /// One sample a pixel, while the view moves.
    Preview,
    /// The scene's N × N samples.
    #[default]
    Full,
}

impl Quality {
    pub fn name(self) -> &'static str {
        match self {
            Quality::Preview => "preview",
            Quality::Full => "full",
        }
    }
}

#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SolveAction {
    Pause,
    Resume,
    Step,
}

/// A message that could not be read: what to say, and the id when one was found.
pub struct Unreadable {
    pub id: Option<u64>,
    pub message: String,
}

/// The request of a text message.
pub fn parse_text(text: &str) -> Result<Request, Unreadable> {
    if text.len() > MAX_MESSAGE {
        return Err(too_large(text.len()));
    }
    let value: Value = serde_json::from_str(text).map_err(|e| Unreadable {
        id: None,
        message: format!("a message that is not JSON: {e}"),
    })?;
    request(value)
}

/// The request of a binary message and its payload.
pub fn parse_binary(bytes: &[u8]) -> Result<(Request, &[u8]), Unreadable> {
    if bytes.len() > MAX_MESSAGE {
        return Err(too_large(bytes.len()));
    }
    let (header, payload) =
        split_binary(bytes).map_err(|message| Unreadable { id: None, message })?;
    Ok((request(header)?, payload))
}

fn too_large(size: usize) -> Unreadable {
    Unreadable {
        id: None,
        message: format!(
            "a message of {size} bytes, more than the {} MiB a message may have",
            MAX_MESSAGE >> 20
        ),
    }
}

fn request(value: Value) -> Result<Request, Unreadable> {
    let id = value.get("id").and_then(Value::as_u64);
    let kind = value
        .get("type")
        .and_then(Value::as_str)
        .unwrap_or("")
        .to_string();
    serde_json::from_value(value).map_err(|e| Unreadable {
        id,
        message: if kind.is_empty() {
            format!("a message with no type: {e}")
        } else {
            format!("a `{kind}` message: {e}")
        },
    })
}

/// A binary message's header and payload.
fn split_binary(bytes: &[u8]) -> Result<(Value, &[u8]), String> {
    let Some((length, rest)) = bytes.split_first_chunk::<4>() else {
        return Err(format!(
            "a binary message of {} bytes, too short for its header's length",
            bytes.len()
        ));
    };
    let length = u32::from_le_bytes(*length) as usize;
    if length > rest.len() {
        return Err(format!(
            "a binary message whose header would have {length} bytes, of {} sent",
            rest.len()
        ));
    }
    let (header, payload) = rest.split_at(length);
    let header = serde_json::from_slice(header)
        .map_err(|e| format!("a binary message whose header is not JSON: {e}"))?;
    Ok((header, payload))
}

/// An `error` reply to message `id`.
pub fn error(id: Option<u64>, message: &str) -> Reply {
    Reply::Text(json!({"type": "error", "id": id, "message": message}).to_string())
}

/// A text reply.
pub fn text(value: &Value) -> Reply {
    Reply::Text(value.to_string())
}

/// A binary message of `header` and `payload`.
pub fn binary(header: &Value, payload: &[u8]) -> Reply {
    let header = header.to_string();
    let mut bytes = Vec::with_capacity(4 + header.len() + payload.len());
    bytes.extend_from_slice(&(header.len() as u32).to_le_bytes());
    bytes.extend_from_slice(header.as_bytes());
    bytes.extend_from_slice(payload);
    Reply::Binary(bytes)
}
