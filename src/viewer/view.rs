//! One scene open in the viewer: where it came from, the families of methods it
//! offers and the options chosen, one renderer per combination of options (each
//! keeps its view-independent work: shadow maps, shadow polygons and volumes, a
//! radiosity solution), the orbit, the lights' moves, the split view and the
//! buffer shown; and the frame of all that.

use super::families::{Family, families};
use super::orbit::Orbit;
use super::picture;
use super::protocol::Quality;
use super::solve::SteppedShooting;
use crate::catalogue::{self, Algorithm};
use crate::error::{Error, Result};
use crate::image_io::Image;
use crate::render::{Frame, Renderer};
use crate::scene::Scene;
use crate::settings::Solver;
use glam::DVec3;
use std::collections::HashMap;
use std::sync::Arc;
use web_time::{Duration, Instant};

/// Renderers kept at once: each holds its pre-passes (a radiosity solve, maps).
const KEPT_RENDERERS: usize = 6;

/// Where a scene came from, to load it again with other options.
#[derive(Clone)]
pub enum Source {
    /// A catalogue id or a scene file's path.
    Spec(String),
    /// Files held in memory and the name of the scene's among them.
    Files {
        main: String,
        files: Arc<HashMap<String, Vec<u8>>>,
    },
}

impl Source {
    pub fn load(&self, sets: &[String]) -> Result<Scene> {
        match self {
            Source::Spec(spec) => crate::load::load_scene(spec, sets),
            Source::Files { main, files } => {
                crate::load::scene_from_files(main, files.as_ref().clone(), sets)
            }
        }
    }

    pub fn title(&self) -> String {
        match self {
            Source::Spec(spec) => spec.clone(),
            Source::Files { main, .. } => main.clone(),
        }
    }
}

/// A renderer of one combination of options, and its radiosity solve.
struct Kept {
    choices: Vec<usize>,
    renderer: Renderer,
    /// A shooting solve under way, its state handed to the renderer as it goes.
    shooting: Option<SteppedShooting>,
    /// The buffers its frames can show, asked once: they follow from the scene's
    /// methods, which a kept renderer never changes (moving a light or the camera
    /// does not).
    buffers: Option<Vec<String>>,
}

/// What a frame showed, for its header.
pub struct Shown {
    pub image: Image,
    /// The exposure it is shown at (1 where it is a picture already).
    pub exposure: f32,
    pub buffer: Option<(String, String)>,
    pub split: Option<(f64, f64)>,
}

pub struct View {
    pub source: Source,
    pub sets: Vec<String>,
    pub scene: Scene,
    pub entry: Option<Algorithm>,
    pub families: Vec<Family>,
    pub choices: Vec<usize>,
    /// The options the scene itself chose: their renderer draws the scene as
    /// loaded, without loading it again.
    initial: Vec<usize>,
    kept: Vec<Kept>,
    pub orbit: Orbit,
    /// Each light's offset from where the scene put it.
    pub offsets: Vec<DVec3>,
    /// The split view's other option of the first family.
    pub split: Option<usize>,
    pub difference: bool,
    pub buffer: Option<String>,
    pub exposure: f32,
    pub quality: Quality,
    /// Each option of the first family's last full frame, in milliseconds.
    pub times: HashMap<String, f64>,
    /// A light's move, 2% of the scene's size.
    pub step: f64,
}

impl View {
    pub fn open(source: Source, sets: Vec<String>) -> Result<View> {
        let scene = source.load(&sets)?;
        let entry = match &source {
            Source::Spec(spec) => catalogue::entry(spec).ok().map(|e| e.algorithm),
            Source::Files { .. } => None,
        };
        let load = |extra: &[String]| {
            let mut all = sets.clone();
            all.extend_from_slice(extra);
            source.load(&all)
        };
        let (families, choices) = families(&scene, &load);
        // A scene no method can render says why now, not at the first frame.
        Renderer::new(scene.clone()).check()?;
        let (low, high) = bounds(&scene);
        Ok(View {
            orbit: Orbit::new(scene.camera.clone()),
            offsets: vec![DVec3::ZERO; scene.lights.len()],
            step: ((high - low).length() * 0.02).max(1e-6),
            exposure: scene.render.exposure,
            source,
            sets,
            entry,
            families,
            initial: choices.clone(),
            choices,
            kept: Vec::new(),
            split: None,
            difference: false,
            buffer: None,
            quality: Quality::Full,
            times: HashMap::new(),
            scene,
        })
    }

    /// The first family's option chosen now (the method the frame shows).
    pub fn method(&self) -> Option<&str> {
        let family = self.families.first()?;
        Some(&family.options[self.choices[0]].name)
    }

    /// The options `choices` with the first family's replaced by `first`.
    fn with_first(&self, first: usize) -> Vec<usize> {
        let mut choices = self.choices.clone();
        if let Some(c) = choices.first_mut() {
            *c = first;
        }
        choices
    }

    /// The renderer of `choices`, made (and its solve started) the first time.
    fn kept(&mut self, choices: &[usize]) -> Result<&mut Kept> {
        if let Some(k) = self.kept.iter().position(|k| k.choices == choices) {
            // Most recently used last.
            let kept = self.kept.remove(k);
            self.kept.push(kept);
        } else {
            let scene = if choices == self.initial {
                self.scene.clone()
            } else {
                let mut sets = self.sets.clone();
                for (family, &c) in self.families.iter().zip(choices) {
                    sets.extend(family.options[c].sets.iter().cloned());
                }
                self.source.load(&sets)?
            };
            let mut renderer = Renderer::new(scene);
            renderer.check()?;
            for (index, offset) in self.offsets.iter().enumerate() {
                if let Some(light) = self.scene.lights[index].moved(*offset) {
                    renderer.set_light(index, light)?;
                }
            }
            let shooting = match renderer.scene().radiosity.clone() {
                Some(settings)
                    if settings.solver == Solver::Shooting && renderer.scene().global.is_none() =>
                {
                    Some(SteppedShooting::start(renderer.scene().clone(), settings)?)
                }
                _ => None,
            };
            if self.kept.len() >= KEPT_RENDERERS {
                self.kept.remove(0);
            }
            self.kept.push(Kept {
                choices: choices.to_vec(),
                renderer,
                shooting,
                buffers: None,
            });
        }
        Ok(self.kept.last_mut().expect("kept above"))
    }

    /// Moves light `index` to `offset` from where the scene put it; false for a
    /// light that does not move (distant, polygon).
    pub fn move_light(&mut self, index: usize, offset: DVec3) -> Result<bool> {
        let Some(light) = self.scene.lights.get(index) else {
            return Err(Error::Light {
                index,
                message: format!("the scene has no light {index}"),
            });
        };
        let Some(light) = light.moved(offset) else {
            return Ok(offset == DVec3::ZERO);
        };
        if self.offsets[index] == offset {
            return Ok(true);
        }
        self.offsets[index] = offset;
        for kept in &mut self.kept {
            kept.renderer.set_light(index, light.clone())?;
            if let Some(s) = &kept.shooting {
                // The solve's lights moved: shoot again from the start.
                let paused = s.paused;
                let mut again = SteppedShooting::start(
                    kept.renderer.scene().clone(),
                    kept.renderer
                        .scene()
                        .radiosity
                        .clone()
                        .expect("a radiosity scene"),
                )?;
                again.paused = paused;
                kept.shooting = Some(again);
            }
        }
        Ok(true)
    }

    /// Whether the shown renderer's solve has steps to shoot.
    pub fn solving(&self) -> bool {
        self.shown_solve().is_some_and(SteppedShooting::has_work)
    }

    /// The solve's progress, or "".
    pub fn status(&self) -> String {
        self.shown_solve()
            .map(|s| s.solution().summary)
            .unwrap_or_default()
    }

    fn shown_solve(&self) -> Option<&SteppedShooting> {
        let kept = self.kept.iter().find(|k| k.choices == self.choices)?;
        kept.shooting.as_ref()
    }

    /// Steers the shown renderer's solve.
    pub fn steer(&mut self, f: impl FnOnce(&mut SteppedShooting)) -> Result<bool> {
        let choices = self.choices.clone();
        let kept = self.kept(&choices)?;
        match kept.shooting.as_mut() {
            Some(s) => {
                f(s);
                Ok(true)
            }
            None => Ok(false),
        }
    }

    /// Shoots the shown renderer's solve for about `budget`.
    pub fn advance(&mut self, budget: Duration) -> Result<()> {
        let choices = self.choices.clone();
        let kept = self.kept(&choices)?;
        if let Some(s) = kept.shooting.as_mut() {
            let solution = s.advance(budget);
            kept.renderer.set_radiosity_solution(Arc::new(solution));
        }
        Ok(())
    }

    /// The linear image of `choices` from the orbit's camera, and its time.
    fn image(&mut self, choices: &[usize], buffers: &[String]) -> Result<(Frame, f64)> {
        let (width, height) = (self.scene.camera.width, self.scene.camera.height);
        let camera = self.orbit.camera(width, height);
        let supersample = match self.quality {
            Quality::Preview => 1,
            Quality::Full => self.scene.render.supersample,
        };
        let kept = self.kept(choices)?;
        if let Some(s) = kept.shooting.as_mut()
            && !kept.renderer.has_radiosity_solution()
        {
            // The first state: the emitters' first shots.
            let first = s.advance(Duration::ZERO);
            kept.renderer.set_radiosity_solution(Arc::new(first));
        }
        kept.renderer.set_camera(camera);
        kept.renderer.set_supersample(supersample);
        let start = Instant::now();
        let frame = kept.renderer.render_with_buffers(buffers)?;
        Ok((frame, start.elapsed().as_secs_f64() * 1e3))
    }

    /// The frame as it stands: the image (or a buffer, or two methods split), at
    /// the quality asked.
    pub fn frame(&mut self) -> Result<Shown> {
        let choices = self.choices.clone();
        if let Some(name) = self.buffer.clone() {
            let (frame, _) = self.image(&choices, std::slice::from_ref(&name))?;
            let buffer = frame.buffer(&name).ok_or_else(|| {
                Error::invalid("buffer", format!("the frame made no buffer `{name}`"))
            })?;
            let (image, legend) = picture::buffer_picture(buffer, self.exposure);
            return Ok(Shown {
                image,
                exposure: 1.0,
                buffer: Some((name, legend)),
                split: None,
            });
        }
        let (frame, time) = self.image(&choices, &[])?;
        self.record(choices.first().copied(), time);
        let Some(other) = self.split.filter(|&o| Some(o) != choices.first().copied()) else {
            return Ok(Shown {
                image: frame.image,
                exposure: self.exposure,
                buffer: None,
                split: None,
            });
        };
        let (second, time) = self.image(&self.with_first(other), &[])?;
        self.record(Some(other), time);
        let (first, second) = (frame.image, second.image);
        let c = crate::image_io::compare(&first, &second, self.exposure)?;
        let (image, exposure) = if self.difference {
            (
                crate::image_io::difference_image(&first, &second, self.exposure, 4.0),
                1.0,
            )
        } else {
            // Left half one method, right half the other, a white line between.
            let mut image = first;
            let (w, h) = (image.width as usize, image.height as usize);
            for y in 0..h {
                for x in w / 2..w {
                    image.pixels[y * w + x] = second.pixels[y * w + x];
                }
                image.pixels[y * w + w / 2] = glam::Vec3::splat(1.0 / self.exposure.max(1e-6));
            }
            (image, self.exposure)
        };
        Ok(Shown {
            image,
            exposure,
            buffer: None,
            split: Some((c.rmse, c.differing_share)),
        })
    }

    fn record(&mut self, first: Option<usize>, time: f64) {
        if self.quality != Quality::Full {
            return;
        }
        if let (Some(family), Some(c)) = (self.families.first(), first) {
            self.times.insert(family.options[c].name.clone(), time);
        }
    }

    /// The buffers the shown renderer's frames can give.
    pub fn buffers(&mut self) -> Result<Vec<String>> {
        let choices = self.choices.clone();
        let kept = self.kept(&choices)?;
        if kept.buffers.is_none() {
            let available = kept.renderer.available_buffers()?;
            kept.buffers = Some(available.into_iter().map(|b| b.name).collect());
        }
        Ok(kept.buffers.clone().unwrap_or_default())
    }

    /// The linear values of the image or of buffer `what`, unrounded, at full
    /// quality: channels a pixel, and the values.
    pub fn export(&mut self, what: &str) -> Result<(u32, u32, usize, Vec<f32>)> {
        let choices = self.choices.clone();
        let quality = std::mem::replace(&mut self.quality, Quality::Full);
        let buffers = if what == "image" {
            Vec::new()
        } else {
            vec![what.to_string()]
        };
        let result = self.image(&choices, &buffers);
        self.quality = quality;
        let (frame, _) = result?;
        if what == "image" {
            let image = frame.image;
            let values = image.pixels.iter().flat_map(|p| p.to_array()).collect();
            return Ok((image.width, image.height, 3, values));
        }
        let buffer = frame
            .buffer(what)
            .ok_or_else(|| Error::invalid("what", format!("the frame made no buffer `{what}`")))?;
        let (channels, values) = picture::buffer_values(buffer);
        Ok((buffer.width, buffer.height, channels, values))
    }

    /// Each light's label and whether it moves.
    pub fn lights(&self) -> Vec<(String, bool)> {
        self.scene
            .lights
            .iter()
            .enumerate()
            .map(|(i, l)| (l.label(i), l.moved(DVec3::ZERO).is_some()))
            .collect()
    }
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
