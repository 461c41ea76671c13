//! `lumiere view`: the viewer page (web/page/, the same page the static site runs
//! on WebAssembly) served on 127.0.0.1, its frames rendered here on every core by
//! the library's viewer session and streamed over a WebSocket. The page does what
//! docs/viewer.md says: methods, lights, split view, buffers, radiosity step by
//! step.

mod benchmark;
mod page;
mod server;

use anyhow::Result;
use lumiere::settings::ShadowMethod;

/// Serve the viewer page on this machine (127.0.0.1 only) for a catalogue entry or
/// a scene file, and render its frames natively.
///
/// In the page: drag to orbit, wheel or pinch to zoom; 1-9 the method, s split
/// with the next method, d their difference, b cycle the intermediate buffers, f
/// the texture filter, tab the light, arrows and page up/down move it, p pause the
/// radiosity solve, . one step while paused, h hide the overlay, q quit the server.
#[derive(clap::Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct Args {
    /// A catalogue id (see `lumiere list`) or the path of a scene file (.toml,
    /// .gltf, .glb).
    scene: String,
    #[command(flatten)]
    size: super::ImageSize,
    /// The shadow method shown first.
    #[arg(long, value_enum)]
    shadows: Option<ShadowMethod>,
    /// Override any scene key (as for `render`). Repeatable.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    sets: Vec<String>,
    /// The port to listen on (default: a free one).
    #[arg(long)]
    port: Option<u16>,
    /// Print the page's address but open no browser.
    #[arg(long)]
    no_open: bool,
    /// No page: orbit the camera through N full-resolution frames with each method,
    /// through a WebSocket on loopback as the page receives them, and print the
    /// frames per second.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    benchmark: Option<u32>,
}

pub fn run(args: Args) -> Result<()> {
    let mut sets = args.sets.clone();
    sets.extend(args.size.sets());
    if let Some(method) = args.shadows {
        sets.push(format!("shadows.method=\"{}\"", method.name()));
    }
    // A scene that cannot load says so now, in one line, before any server starts.
    lumiere::load_scene(&args.scene, &sets)?;
    let server = server::Server::bind(args.port, args.scene.clone(), sets)?;
    if let Some(frames) = args.benchmark {
        let address = server.address();
        std::thread::spawn(move || server.serve());
        return benchmark::run(address, &args.scene, frames);
    }
    let url = server.page_url();
    outln!("lumiere view: {url} (Ctrl-C stops it)")?;
    if !args.no_open {
        open_browser(&url);
    }
    // Until the page sends `quit` (q in the page), or Ctrl-C ends the process.
    server.serve();
    Ok(())
}

/// Opens `url` in the desktop's browser when there is one; silent when not.
fn open_browser(url: &str) {
    let opener: &[&str] = if cfg!(target_os = "macos") {
        &["open"]
    } else if cfg!(windows) {
        &["cmd", "/c", "start", ""]
    } else {
        &["xdg-open"]
    };
    let _ = std::process::Command::new(opener[0])
        .args(&opener[1..])
        .arg(url)
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn();
}
