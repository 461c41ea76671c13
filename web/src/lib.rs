//! lumiere's viewer engine for a Web Worker: [`Engine`] carries the page's messages
//! (docs/viewer-protocol.md) to a [`lumiere::viewer::Session`] and hands its replies
//! back, each a JS string (text) or a `Uint8Array` (binary). Built by
//! tools/build-web.sh.

use js_sys::{Array, Uint8Array};
use lumiere::viewer::{Reply, Session};
use wasm_bindgen::prelude::*;

/// Set once: a panic's message (and where) goes to `console.error` before the trap.
#[cfg(target_arch = "wasm32")]
static PANIC_HOOK: std::sync::Once = std::sync::Once::new();

/// One viewer session, driven by the worker's messages.
#[wasm_bindgen]
pub struct Engine {
    session: Session,
}

#[wasm_bindgen]
impl Engine {
    /// A session with no scene open. The first engine also sends panics to
    /// `console.error`, where the worker's console shows them.
    #[wasm_bindgen(constructor)]
    pub fn new() -> Engine {
        #[cfg(target_arch = "wasm32")]
        PANIC_HOOK.call_once(|| {
            std::panic::set_hook(Box::new(|info| console_error(&info.to_string())));
        });
        Engine {
            session: Session::new(),
        }
    }

    /// The replies to a text message (one JSON object).
    pub fn handle_text(&mut self, text: &str) -> Array {
        replies(self.session.handle_text(text))
    }

    /// The replies to a binary message (header length, header, payload).
    pub fn handle_binary(&mut self, bytes: &[u8]) -> Array {
        replies(self.session.handle_binary(bytes))
    }

    /// The frames of work left over after the last message (a solve going on).
    pub fn tick(&mut self) -> Array {
        replies(self.session.tick())
    }

    /// Whether `tick` has work to do.
    pub fn busy(&self) -> bool {
        self.session.busy()
    }
}

impl Default for Engine {
    fn default() -> Engine {
        Engine::new()
    }
}

fn replies(replies: Vec<Reply>) -> Array {
    replies
        .into_iter()
        .map(|reply| -> JsValue {
            match reply {
                Reply::Text(text) => text.into(),
                Reply::Binary(bytes) => Uint8Array::from(bytes.as_slice()).into(),
            }
        })
        .collect()
}

#[cfg(target_arch = "wasm32")]
#[wasm_bindgen]
extern "C" {
    #[wasm_bindgen(js_namespace = console, js_name = error)]
    fn console_error(message: &str);
}
