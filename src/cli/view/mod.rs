//! `lumiere view`: a live viewer for the classroom. The mouse orbits and zooms the
//! camera, keys move a light, number keys switch the method, a split screen shows
//! two methods and their difference, another key cycles the intermediate buffers;
//! each method's frame time and paper are on screen. While the view moves it draws
//! at half resolution, and refines when it stops; radiosity is solved in the
//! background and the picture follows it.
//!
//! The window is winit's and its pixels softbuffer's: both well-kept, both pure
//! software (no GPU, no OpenGL), which is what a software renderer wants to show
//! its own pixels; this build draws through X11 (XWayland under Wayland).

mod hud;
mod orbit;
mod progressive;
mod session;

use anyhow::{Context, Result, bail};
use glam::DVec3;
use lumiere::settings::ShadowMethod;
use session::{Frame, Session};
use std::num::NonZeroU32;
use std::rc::Rc;
use std::time::{Duration, Instant};
use winit::application::ApplicationHandler;
use winit::event::{ElementState, KeyEvent, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::keyboard::{Key, NamedKey};
use winit::window::{Window, WindowId};

/// Open a window on a catalogue entry or a scene file and explore it live.
///
/// Mouse: drag to orbit, wheel to zoom. Keys: 1-9 the method (shadow method, or
/// radiosity solver); s split screen with the next method, d its difference; b
/// cycle the intermediate buffers; f the texture filter; tab the light, arrows
/// and page up/down move it; p pause the radiosity solve, . one step while
/// paused; h hide the overlay;
/// q or escape quit.
#[derive(clap::Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct Args {
    /// A catalogue id (see `lumiere list`) or the path of a .toml scene file.
    scene: String,
    #[command(flatten)]
    size: super::ImageSize,
    /// The shadow method shown first.
    #[arg(long, value_enum)]
    shadows: Option<ShadowMethod>,
    /// Override any scene key (as for `render`). Repeatable.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    sets: Vec<String>,
    /// No window: orbit the camera through N full-resolution frames with each
    /// method and print the frames per second.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    benchmark: Option<u32>,
}

/// After the last move, the view refines this much later.
const SETTLE: Duration = Duration::from_millis(120);

pub fn run(args: Args) -> Result<()> {
    let mut sets = args.sets.clone();
    sets.extend(args.size.sets());
    if let Some(method) = args.shadows {
        sets.push(format!("shadows.method=\"{}\"", method.name()));
    }
    if let Some(frames) = args.benchmark {
        let mut session = Session::new(&args.scene, sets)?;
        return benchmark(&mut session, &args.scene, frames.max(1));
    }
    if std::env::var_os("DISPLAY").is_none_or(|d| d.is_empty()) {
        if std::env::var_os("WAYLAND_DISPLAY").is_some_and(|d| !d.is_empty()) {
            bail!(
                "lumiere view draws through X11: this Wayland session has no DISPLAY (start XWayland)"
            );
        }
        bail!("lumiere view needs a display: neither DISPLAY nor WAYLAND_DISPLAY is set");
    }
    let session = Session::new(&args.scene, sets)?;
    let event_loop = EventLoop::new().map_err(|e| {
        // The windowing library's message carries its own source file and line:
        // of no use to a user, left out.
        let said = e.to_string();
        let cause: Vec<&str> = said
            .split(": ")
            .filter(|part| !part.contains(".rs:") && !part.starts_with("os error at"))
            .collect();
        anyhow::anyhow!(
            "cannot open the display {}: {} (is an X server running there?)",
            std::env::var("DISPLAY").unwrap_or_default(),
            cause.join(": ")
        )
    })?;
    let mut viewer = Viewer {
        title: args.scene.clone(),
        session,
        window: None,
        surface: None,
        error: None,
        hud: true,
        dragging: None,
        cursor: (0.0, 0.0),
        moved: None,
        refined: false,
        frame: None,
    };
    event_loop
        .run_app(&mut viewer)
        .context("the window's event loop failed")?;
    match viewer.error {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

struct Viewer {
    title: String,
    session: Session,
    window: Option<Rc<Window>>,
    surface: Option<softbuffer::Surface<Rc<Window>, Rc<Window>>>,
    error: Option<anyhow::Error>,
    hud: bool,
    /// The cursor where the drag last was.
    dragging: Option<(f64, f64)>,
    cursor: (f64, f64),
    /// When the view last moved.
    moved: Option<Instant>,
    /// Whether the frame on screen is at full resolution and up to date.
    refined: bool,
    frame: Option<Frame>,
}

impl ApplicationHandler for Viewer {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.window.is_some() {
            return;
        }
        let result = (|| -> Result<()> {
            let size = winit::dpi::PhysicalSize::new(self.session.width, self.session.height);
            let attributes = Window::default_attributes()
                .with_title(format!("lumiere: {}", self.title))
                .with_inner_size(size)
                .with_resizable(false);
            let window = Rc::new(event_loop.create_window(attributes)?);
            let context = softbuffer::Context::new(window.clone())
                .map_err(|e| anyhow::anyhow!("cannot draw in the window: {e}"))?;
            let surface = softbuffer::Surface::new(&context, window.clone())
                .map_err(|e| anyhow::anyhow!("cannot draw in the window: {e}"))?;
            self.window = Some(window);
            self.surface = Some(surface);
            Ok(())
        })();
        if let Err(e) = result {
            self.fail(event_loop, e);
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        let result = match event {
            WindowEvent::CloseRequested => {
                event_loop.exit();
                Ok(())
            }
            WindowEvent::RedrawRequested => self.draw(),
            WindowEvent::KeyboardInput {
                event:
                    KeyEvent {
                        logical_key,
                        state: ElementState::Pressed,
                        ..
                    },
                ..
            } => self.key(event_loop, logical_key),
            WindowEvent::MouseInput {
                state,
                button: MouseButton::Left,
                ..
            } => {
                self.dragging = (state == ElementState::Pressed).then_some(self.cursor);
                Ok(())
            }
            WindowEvent::CursorMoved { position, .. } => {
                self.cursor = (position.x, position.y);
                if let Some((x, y)) = self.dragging {
                    let turn = std::f64::consts::PI / self.session.width.max(1) as f64;
                    self.session
                        .orbit
                        .turn(-(position.x - x) * turn, (position.y - y) * turn);
                    self.dragging = Some(self.cursor);
                    self.changed(true);
                }
                Ok(())
            }
            WindowEvent::MouseWheel { delta, .. } => {
                let lines = match delta {
                    MouseScrollDelta::LineDelta(_, y) => y as f64,
                    MouseScrollDelta::PixelDelta(p) => p.y / 40.0,
                };
                self.session.orbit.zoom(0.9f64.powf(lines));
                self.changed(true);
                Ok(())
            }
            _ => Ok(()),
        };
        if let Err(e) = result {
            self.fail(event_loop, e);
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        match self.session.poll_radiosity() {
            Ok(true) => self.changed(false),
            Ok(false) => {}
            Err(e) => return self.fail(event_loop, e),
        }
        let settling = self.moved.is_some_and(|t| t.elapsed() < SETTLE);
        if !settling && !self.refined {
            self.request_redraw();
        }
        let wake = if settling || self.session.solving() {
            Instant::now() + Duration::from_millis(40)
        } else {
            Instant::now() + Duration::from_millis(500)
        };
        event_loop.set_control_flow(ControlFlow::WaitUntil(wake));
    }
}

impl Viewer {
    fn fail(&mut self, event_loop: &ActiveEventLoop, error: anyhow::Error) {
        self.error.get_or_insert(error);
        event_loop.exit();
    }

    fn request_redraw(&self) {
        if let Some(w) = &self.window {
            w.request_redraw();
        }
    }

    /// The view changed: drawn again, coarse first when it moves.
    fn changed(&mut self, moving: bool) {
        if moving {
            self.moved = Some(Instant::now());
        }
        self.refined = false;
        self.request_redraw();
    }

    fn key(&mut self, event_loop: &ActiveEventLoop, key: Key) -> Result<()> {
        let session = &mut self.session;
        match key.as_ref() {
            Key::Named(NamedKey::Escape) | Key::Character("q") => {
                event_loop.exit();
                return Ok(());
            }
            Key::Character(c) if c.len() == 1 && c.as_bytes()[0].is_ascii_digit() => {
                let n = (c.as_bytes()[0] - b'0') as usize;
                if n >= 1 && n <= session.modes.len() {
                    session.mode = n - 1;
                    session.buffer = None;
                }
            }
            Key::Character("s") => {
                session.split = match session.split {
                    Some(_) => None,
                    None if session.modes.len() > 1 => {
                        Some((session.mode + 1) % session.modes.len())
                    }
                    None => None,
                };
                session.show_difference = false;
            }
            Key::Character("d") => session.show_difference = !session.show_difference,
            Key::Character("b") => session.cycle_buffer()?,
            Key::Character("f") if session.textured() => {
                session.cycle_filter();
                session.forget_renderers();
            }
            Key::Character("p") => session.toggle_pause(),
            Key::Character(".") => session.step(),
            Key::Character("h") => self.hud = !self.hud,
            Key::Named(NamedKey::Tab) => {
                session.light = (session.light + 1) % session.scene.lights.len().max(1);
            }
            Key::Named(named) => {
                let by = match named {
                    NamedKey::ArrowLeft => DVec3::NEG_X,
                    NamedKey::ArrowRight => DVec3::X,
                    NamedKey::ArrowUp => DVec3::NEG_Z,
                    NamedKey::ArrowDown => DVec3::Z,
                    NamedKey::PageUp => DVec3::Y,
                    NamedKey::PageDown => DVec3::NEG_Y,
                    _ => return Ok(()),
                };
                if session.move_light(by) {
                    self.changed(true);
                }
                return Ok(());
            }
            _ => return Ok(()),
        }
        self.changed(false);
        Ok(())
    }

    fn draw(&mut self) -> Result<()> {
        let settling = self.moved.is_some_and(|t| t.elapsed() < SETTLE);
        let scale = if settling { 2 } else { 1 };
        if let Some(frame) = self.session.frame(scale)? {
            self.frame = Some(frame);
            self.refined = scale == 1;
        }
        let Some(size) = self.window.as_ref().map(|w| w.inner_size()) else {
            return Ok(());
        };
        let overlay = self.overlay(size.width as usize);
        let (Some(window), Some(surface)) = (&self.window, &mut self.surface) else {
            return Ok(());
        };
        let (Some(w), Some(h)) = (NonZeroU32::new(size.width), NonZeroU32::new(size.height)) else {
            return Ok(());
        };
        surface
            .resize(w, h)
            .map_err(|e| anyhow::anyhow!("cannot draw in the window: {e}"))?;
        let mut buffer = surface
            .buffer_mut()
            .map_err(|e| anyhow::anyhow!("cannot draw in the window: {e}"))?;
        let (w, h) = (size.width as usize, size.height as usize);
        match &self.frame {
            // The frame scaled to the window, nearest sample.
            Some(f) => {
                for y in 0..h {
                    let fy = y * f.height as usize / h;
                    for x in 0..w {
                        let fx = x * f.width as usize / w;
                        buffer[y * w + x] = f.pixels[fy * f.width as usize + fx];
                    }
                }
            }
            None => buffer.fill(0),
        }
        if self.hud {
            hud::draw(&mut buffer, w, h, &overlay);
        }
        window.pre_present_notify();
        buffer
            .present()
            .map_err(|e| anyhow::anyhow!("cannot draw in the window: {e}"))?;
        Ok(())
    }

    /// The overlay's lines, no longer than the window's width allows.
    fn overlay(&self, width: usize) -> Vec<String> {
        let s = &self.session;
        let time = |m: usize| match s.times[m] {
            Some(t) => format!("{:.0} ms", t.as_secs_f64() * 1000.0),
            None => "-".into(),
        };
        let mode = &s.modes[s.mode];
        let mut lines = vec![format!(
            "[{}] {} ({}) {}",
            s.mode + 1,
            mode.name,
            mode.paper,
            time(s.mode)
        )];
        if let Some(other) = s.split {
            let o = &s.modes[other];
            let measured = match s.difference {
                Some((rmse, share)) => {
                    format!("RMSE {rmse:.4}, {:.2}% of pixels differ", 100.0 * share)
                }
                None => String::new(),
            };
            lines.push(format!(
                "right: [{}] {} ({}) {} {measured}",
                other + 1,
                o.name,
                o.paper,
                time(other)
            ));
        }
        if let Some(b) = s.buffer_label() {
            lines.push(format!("buffer: {b}"));
        }
        if !s.scene.lights.is_empty() {
            lines.push(format!("moving {}", s.light_label()));
        }
        if s.textured() {
            lines.push(format!("texture filter: {}", s.filter_label()));
        }
        if !s.status.is_empty() {
            lines.push(s.status.clone());
        }
        let modes: Vec<String> = (0..s.modes.len())
            .map(|m| format!("{} {} {}", m + 1, s.modes[m].name, time(m)))
            .collect();
        lines.extend(wrap(&modes, " | ", hud::columns(width)));
        lines.push(
            "drag orbit, wheel zoom, s split, d difference, b buffers, f filter, tab/arrows light, p pause . step, h hide, q quit"
                .into(),
        );
        lines
            .into_iter()
            .flat_map(|l| {
                let words: Vec<String> = l.split(' ').map(String::from).collect();
                wrap(&words, " ", hud::columns(width))
            })
            .collect()
    }
}

/// `items` joined by `separator` into lines of at most `columns` characters.
fn wrap(items: &[String], separator: &str, columns: usize) -> Vec<String> {
    let mut lines = Vec::new();
    let mut line = String::new();
    for item in items {
        if !line.is_empty() && line.len() + separator.len() + item.len() > columns {
            lines.push(std::mem::take(&mut line));
        }
        if !line.is_empty() {
            line.push_str(separator);
        }
        line.push_str(item);
    }
    if !line.is_empty() {
        lines.push(line);
    }
    lines
}

/// Frames per second of every mode, orbiting the camera through `frames`
/// full-resolution frames (after one that builds the mode's pre-passes).
fn benchmark(session: &mut Session, scene: &str, frames: u32) -> Result<()> {
    outln!(
        "{scene}, {} x {}, {frames} frames orbiting the camera, per method:",
        session.width,
        session.height
    )?;
    outln!("| method | first frame (pre-passes) | median frame | frames per second |")?;
    outln!("|---|---|---|---|")?;
    for mode in 0..session.modes.len() {
        session.mode = mode;
        let start = Instant::now();
        while session.frame(1)?.is_none() {
            session.poll_radiosity()?;
            std::thread::sleep(Duration::from_millis(10));
        }
        let first = start.elapsed();
        let mut times = Vec::new();
        for _ in 0..frames {
            session
                .orbit
                .turn(2.0 * std::f64::consts::PI / frames as f64, 0.0);
            let start = Instant::now();
            session.frame(1)?;
            times.push(start.elapsed());
        }
        times.sort();
        let median = times[times.len() / 2];
        outln!(
            "| {} | {:.1} ms | {:.1} ms | {:.0} |",
            session.modes[mode].name,
            first.as_secs_f64() * 1000.0,
            median.as_secs_f64() * 1000.0,
            1.0 / median.as_secs_f64()
        )?;
    }
    Ok(())
}
