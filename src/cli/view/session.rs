//! What the viewer shows, without the window: the scene, the modes the number
//! keys choose between (shadow methods, or radiosity solvers), one renderer per
//! mode kept between frames (each keeps its view-independent work: shadow maps,
//! shadow polygons, volumes, radiosity), the camera's orbit, the lights' moves,
//! the texture filter, the split screen and the buffer shown.

use super::orbit::Orbit;
use super::progressive::Progressive;
use anyhow::Result;
use glam::DVec3;
use lumiere::internals::image_io;
use lumiere::settings::{Filter, Solver};
use lumiere::{Image, Light, Renderer, Scene};
use lumiere::{catalogue, load_scene};
use std::collections::HashMap;
use std::time::{Duration, Instant};

/// One choice of the number keys.
pub struct Mode {
    pub name: String,
    /// The paper it follows, for the overlay.
    pub paper: String,
    sets: Vec<String>,
}

const FILTERS: [Filter; 5] = [
    Filter::Nearest,
    Filter::Bilinear,
    Filter::MipNearest,
    Filter::Trilinear,
    Filter::SummedArea,
];

/// A picture to show, in 0RGB words, and how long its frame took.
pub struct Frame {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<u32>,
}

pub struct Session {
    spec: String,
    sets: Vec<String>,
    pub scene: Scene,
    pub modes: Vec<Mode>,
    pub mode: usize,
    /// The split screen's other mode.
    pub split: Option<usize>,
    pub show_difference: bool,
    /// The texture filter forced on every texture (index in FILTERS).
    pub filter: Option<usize>,
    renderers: HashMap<(usize, Option<usize>), Renderer>,
    /// Background radiosity solves, per renderer.
    solves: HashMap<(usize, Option<usize>), Progressive>,
    pub orbit: Orbit,
    pub width: u32,
    pub height: u32,
    /// The light the keys move, and each light's offset from where the scene put it.
    pub light: usize,
    offsets: Vec<DVec3>,
    /// The buffer shown instead of the image (index in the current mode's list).
    pub buffer: Option<usize>,
    pub buffer_names: Vec<String>,
    /// The last full-resolution frame time of each mode.
    pub times: Vec<Option<Duration>>,
    /// What the split screen measured: RMSE and share of differing pixels.
    pub difference: Option<(f64, f64)>,
    /// Radiosity progress to show.
    pub status: String,
    /// A scale for the step the keys move a light by: the scene's size.
    pub step: f64,
}

impl Session {
    pub fn new(spec: &str, sets: Vec<String>) -> Result<Session> {
        let scene = load_scene(spec, &sets)?;
        let modes = modes(&scene)?;
        if modes.is_empty() {
            // No method can render it: the scene's own refusal says why.
            Renderer::new(scene.clone()).check()?;
            anyhow::bail!("no method of lumiere can render {spec}");
        }
        let mode = modes
            .iter()
            .position(|m| {
                m.sets.iter().any(|s| {
                    s == &format!("shadows.method=\"{}\"", scene.shadows.method.name())
                        || scene.radiosity.as_ref().is_some_and(|r| {
                            s == &format!("radiosity.solver=\"{}\"", solver_name(r.solver))
                        })
                })
            })
            .unwrap_or(0);
        let (low, high) = bounds(&scene);
        Ok(Session {
            spec: spec.to_string(),
            sets,
            orbit: Orbit::new(scene.camera.clone()),
            width: scene.camera.width,
            height: scene.camera.height,
            light: 0,
            offsets: vec![DVec3::ZERO; scene.lights.len()],
            times: modes.iter().map(|_| None).collect(),
            step: ((high - low).length() * 0.02).max(1e-6),
            modes,
            mode,
            split: None,
            show_difference: false,
            filter: None,
            renderers: HashMap::new(),
            solves: HashMap::new(),
            buffer: None,
            buffer_names: Vec::new(),
            difference: None,
            status: String::new(),
            scene,
        })
    }

    /// Whether a texture filter can be chosen.
    pub fn textured(&self) -> bool {
        !self.scene.textures.is_empty()
    }

    pub fn filter_label(&self) -> String {
        match self.filter {
            None => "the scene's".into(),
            Some(f) => Filter::name(FILTERS[f]).into(),
        }
    }

    pub fn cycle_filter(&mut self) {
        if self.textured() {
            self.filter = match self.filter {
                None => Some(0),
                Some(f) if f + 1 < FILTERS.len() => Some(f + 1),
                Some(_) => None,
            };
        }
    }

    /// Moves the selected light (point, spot and sphere lights move; the others
    /// stay).
    pub fn move_light(&mut self, by: DVec3) -> bool {
        let Some(light) = self.scene.lights.get(self.light) else {
            return false;
        };
        if moved(light, DVec3::ZERO).is_none() {
            return false;
        }
        self.offsets[self.light] += by * self.step;
        for renderer in self.renderers.values_mut() {
            let light = moved(&self.scene.lights[self.light], self.offsets[self.light])
                .expect("a light that moves");
            // The renderers' scenes hold the same lights as the session's.
            let _ = renderer.set_light(self.light, light);
        }
        true
    }

    pub fn light_label(&self) -> String {
        match self.scene.lights.get(self.light) {
            None => "no light".into(),
            Some(l) => l.label(self.light),
        }
    }

    /// The renderer of mode `mode` under the current filter, made the first time.
    fn renderer(&mut self, mode: usize) -> Result<&mut Renderer> {
        let key = (mode, self.filter);
        if !self.renderers.contains_key(&key) {
            let mut sets = self.sets.clone();
            sets.extend(self.modes[mode].sets.iter().cloned());
            if let Some(f) = self.filter {
                for t in &self.scene.textures {
                    sets.push(format!(
                        "textures.{}.filter=\"{}\"",
                        t.name,
                        Filter::name(FILTERS[f])
                    ));
                }
            }
            let scene = load_scene(&self.spec, &sets)?;
            let mut renderer = Renderer::new(scene);
            renderer.check()?;
            for (index, offset) in self.offsets.iter().enumerate() {
                if let Some(light) = moved(&self.scene.lights[index], *offset) {
                    renderer.set_light(index, light)?;
                }
            }
            if let Some(settings) = renderer.scene().radiosity.clone() {
                self.solves
                    .insert(key, Progressive::start(renderer.scene().clone(), settings));
            }
            self.renderers.insert(key, renderer);
        }
        Ok(self.renderers.get_mut(&key).expect("made above"))
    }

    /// Hands each renderer the newest state of its background solve; whether any
    /// changed.
    /// A failed solve's error ends the viewer.
    pub fn poll_radiosity(&mut self) -> Result<bool> {
        let mut changed = false;
        for (key, solve) in &mut self.solves {
            solve.failure()?;
            if let Some(solution) = solve.newest() {
                if *key == (self.mode, self.filter) {
                    self.status = solution.summary.clone();
                }
                if let Some(r) = self.renderers.get_mut(key) {
                    r.set_radiosity_solution(std::sync::Arc::new(solution));
                    changed = true;
                }
            }
        }
        Ok(changed)
    }

    pub fn solving(&self) -> bool {
        self.solves.values().any(|s| !s.finished())
    }

    pub fn step(&mut self) {
        if let Some(s) = self.solves.get(&(self.mode, self.filter)) {
            s.step();
        }
    }

    pub fn toggle_pause(&mut self) {
        if let Some(s) = self.solves.get(&(self.mode, self.filter)) {
            s.toggle_pause();
        }
    }

    /// The radiance image of `mode` at `width` × `height`, and the time it took;
    /// `None` while its radiosity has no state to show yet.
    fn image(&mut self, mode: usize, width: u32, height: u32) -> Result<Option<(Image, Duration)>> {
        let camera = self.orbit.camera(width, height);
        let has_radiosity = self.scene.radiosity.is_some();
        let renderer = self.renderer(mode)?;
        renderer.set_camera(camera);
        if has_radiosity && !self.solves[&(mode, self.filter)].started() {
            return Ok(None);
        }
        let renderer = &self.renderers[&(mode, self.filter)];
        let start = Instant::now();
        let image = renderer.render()?;
        Ok(Some((image, start.elapsed())))
    }

    /// The frame to show at `scale` (1: full resolution, 2: half…).
    pub fn frame(&mut self, scale: u32) -> Result<Option<Frame>> {
        let (width, height) = ((self.width / scale).max(1), (self.height / scale).max(1));
        let exposure = self.scene.render.exposure;
        if let Some(b) = self.buffer {
            return self.buffer_frame(b, width, height);
        }
        let Some((image, time)) = self.image(self.mode, width, height)? else {
            return Ok(None);
        };
        if scale == 1 {
            self.times[self.mode] = Some(time);
        }
        let Some(other) = self.split.filter(|&o| o != self.mode) else {
            self.difference = None;
            return Ok(Some(to_frame(&image, exposure)));
        };
        let Some((second, time)) = self.image(other, width, height)? else {
            return Ok(Some(to_frame(&image, exposure)));
        };
        if scale == 1 {
            self.times[other] = Some(time);
        }
        let c = lumiere::compare_images(&image, &second, exposure)?;
        self.difference = Some((c.rmse, c.differing_share));
        if self.show_difference {
            let d = lumiere::difference_image(&image, &second, exposure, 4.0);
            return Ok(Some(to_frame(&d, 1.0)));
        }
        // Left half one mode, right half the other.
        let mut frame = to_frame(&image, exposure);
        let right = to_frame(&second, exposure);
        for y in 0..height as usize {
            for x in width as usize / 2..width as usize {
                let i = y * width as usize + x;
                frame.pixels[i] = right.pixels[i];
            }
            frame.pixels[y * width as usize + width as usize / 2] = 0xffffff;
        }
        Ok(Some(frame))
    }

    /// Cycles through the current mode's buffers, then back to the image.
    pub fn cycle_buffer(&mut self) -> Result<()> {
        let mode = self.mode;
        self.renderer(mode)?;
        // Until the background solve hands over a state, the buffers would solve
        // the radiosity again on this thread.
        if self
            .solves
            .get(&(mode, self.filter))
            .is_some_and(|s| !s.started())
        {
            return Ok(());
        }
        let renderer = &self.renderers[&(mode, self.filter)];
        let names: Vec<String> = renderer
            .available_buffers()?
            .into_iter()
            .map(|b| b.name)
            .collect();
        self.buffer_names = names;
        self.buffer = match self.buffer {
            None if !self.buffer_names.is_empty() => Some(0),
            Some(b) if b + 1 < self.buffer_names.len() => Some(b + 1),
            _ => None,
        };
        Ok(())
    }

    pub fn buffer_label(&self) -> Option<&str> {
        self.buffer
            .and_then(|b| self.buffer_names.get(b))
            .map(String::as_str)
    }

    fn buffer_frame(&mut self, b: usize, width: u32, height: u32) -> Result<Option<Frame>> {
        let camera = self.orbit.camera(width, height);
        let exposure = self.scene.render.exposure;
        let mode = self.mode;
        let renderer = self.renderer(mode)?;
        renderer.set_camera(camera);
        let Some(name) = self.buffer_names.get(b).cloned() else {
            return Ok(None);
        };
        let rendered = self.renderers[&(mode, self.filter)].render_with_buffers(&[name])?;
        let picture = super::super::buffer_picture::displayed(&rendered.buffers[0], exposure);
        Ok(Some(to_frame(&picture, 1.0)))
    }

    /// Drops every renderer (after a filter change, their scenes differ).
    pub fn forget_renderers(&mut self) {
        self.renderers.clear();
        self.solves.clear();
        self.buffer = None;
    }
}

/// The modes of `scene`: its radiosity solvers, or every shadow method that can
/// shadow its lights.
fn modes(scene: &Scene) -> Result<Vec<Mode>> {
    let paper = |id: &str| {
        catalogue::entry(id)
            .map(|e| e.algorithm.authors)
            .unwrap_or_default()
    };
    if scene.radiosity.is_some() {
        return Ok(vec![
            Mode {
                name: "gathering".into(),
                paper: paper("radiosity-gathering"),
                sets: vec!["radiosity.solver=\"gathering\"".into()],
            },
            Mode {
                name: "shooting".into(),
                paper: paper("radiosity-shooting"),
                sets: vec!["radiosity.solver=\"shooting\"".into()],
            },
        ]);
    }
    let mut modes = Vec::new();
    for method in lumiere::internals::shadow::METHODS {
        let mut candidate = scene.clone();
        candidate.shadows.method = method;
        if Renderer::new(candidate).check().is_ok() {
            modes.push(Mode {
                name: method.name().into(),
                paper: match lumiere::internals::shadow::method(method).entry {
                    Some(entry) => paper(entry),
                    None => "no shadows".into(),
                },
                sets: vec![format!("shadows.method=\"{}\"", method.name())],
            });
        }
    }
    Ok(modes)
}

fn solver_name(solver: Solver) -> &'static str {
    match solver {
        Solver::Gathering => "gathering",
        Solver::Shooting => "shooting",
    }
}

/// `light` moved by `offset`, for the lights that sit at a point.
fn moved(light: &Light, offset: DVec3) -> Option<Light> {
    let mut light = light.clone();
    match &mut light {
        Light::Point(l) => l.position += offset,
        Light::Spot(l) => l.position += offset,
        Light::Sphere(l) => l.centre += offset,
        Light::Distant(_) | Light::Polygon(_) => return None,
    }
    Some(light)
}

/// The scene's bounding box.
fn bounds(scene: &Scene) -> (DVec3, DVec3) {
    let mut low = DVec3::splat(f64::INFINITY);
    let mut high = DVec3::splat(f64::NEG_INFINITY);
    for p in &scene.polygons {
        for v in p.positions() {
            low = low.min(v);
            high = high.max(v);
        }
    }
    if low.x > high.x {
        (DVec3::ZERO, DVec3::ONE)
    } else {
        (low, high)
    }
}

/// An image as 0RGB words, sRGB after `exposure`, as PNG output encodes it.
fn to_frame(image: &Image, exposure: f32) -> Frame {
    let pixels = image
        .pixels
        .iter()
        .map(|&p| {
            let [r, g, b] = image_io::to_srgb8(p, exposure);
            (r as u32) << 16 | (g as u32) << 8 | b as u32
        })
        .collect();
    Frame {
        width: image.width,
        height: image.height,
        pixels,
    }
}
