//! The viewer: its engine through the page's messages (in this process), the
//! native server of `lumiere view` over a real WebSocket, and the page itself in
//! headless Chromium, served natively and as the static WebAssembly site.

mod page;
mod server;
mod session;
mod web;
