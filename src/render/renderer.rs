//! The renderer: one scene, and the view-independent work of its frames kept between
//! them. The occluders' hierarchy, each light's shadow pre-pass (shadow maps, shadow
//! polygons, shadow volumes' quads, Bouknight & Kelley's projections) and the
//! integrator's own state (a radiosity solution, a second pass: `integrators::Kept`)
//! are built the first time a frame needs them and reused after (texture pyramids
//! and summed-area tables are built once, with the scene), and so are environment
//! maps captured from the scene.
//! Moving the camera invalidates none of it; moving a light, that light's
//! shadows and a radiosity solution (which holds the lights that are not
//! polygons); changing the shadow settings, every light's shadows.

use super::accumulation::render_rotated_grid;
use super::buffers::available;
use super::capture::{face_cameras, without_objects};
use super::frame::render_frame;
use super::integrators::{
    Declaration, Integrator, Kept, Lighting, Role, ScanLine, check_keys, declaration,
};
use super::output::{BufferInfo, Frame};
use super::plan::{EnvironmentMaps, FramePlan};
use crate::error::{Error, Result};
use crate::image_io::Image;
use crate::radiosity::Solution;
use crate::scene::{Camera, EnvironmentSource, Light, Scene};
use crate::settings::{Filter, MediumMethod, SamplePattern, ShadowSettings};
use crate::shadow::{self, LightShadows, SceneOccluders, SharedWork};
use crate::texture::Texels;
use crate::texture::environment::EnvironmentMap;
use glam::DVec3;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

/// How many view-independent pre-passes a renderer has built.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Prepasses {
    /// The occluders' bounding volume hierarchy.
    pub occluders: usize,
    /// Lights' shadow pre-passes.
    pub light_shadows: usize,
    /// Radiosity solutions.
    pub radiosity: usize,
    /// Environment maps rendered from the scene (captures).
    pub captures: usize,
}

/// A scene and the view-independent work of its frames, kept between them.
pub struct Renderer {
    scene: Scene,
    occluders: Mutex<Option<Arc<SceneOccluders>>>,
    lights: Vec<Mutex<Option<Arc<dyn LightShadows>>>>,
    /// What the scene's integrator declares, and its view-independent state.
    declared: &'static Declaration,
    kept: Box<dyn Kept>,
    environments: Mutex<Option<EnvironmentMaps>>,
    /// Whether captured environments are made (not inside a capture).
    captures: bool,
    built_occluders: AtomicUsize,
    built_light_shadows: AtomicUsize,
    built_captures: AtomicUsize,
    hemicube_element: usize,
    progress: Option<super::plan::Progress>,
    stop: Option<Arc<std::sync::atomic::AtomicBool>>,
}

impl Renderer {
    /// A renderer of `scene`; nothing is built until a frame needs it.
    pub fn new(scene: Scene) -> Renderer {
        let declared = declaration(Integrator::of(&scene));
        Renderer {
            lights: scene.lights.iter().map(|_| Mutex::new(None)).collect(),
            scene,
            occluders: Mutex::new(None),
            declared,
            kept: (declared.kept)(),
            environments: Mutex::new(None),
            captures: true,
            built_occluders: AtomicUsize::new(0),
            built_light_shadows: AtomicUsize::new(0),
            built_captures: AtomicUsize::new(0),
            hemicube_element: 0,
            progress: None,
            stop: None,
        }
    }

    /// A renderer whose frames show no captured environment (the renderer a capture
    /// itself uses).
    pub fn without_captures(scene: Scene) -> Renderer {
        Renderer {
            captures: false,
            ..Renderer::new(scene)
        }
    }

    /// The scene's environment maps, captures rendered the first time they are
    /// needed (`None` inside a capture).
    fn environment_maps(&self) -> Result<EnvironmentMaps> {
        let mut slot = self.environments.lock().expect("no poisoned lock");
        if let Some(maps) = slot.as_ref() {
            return Ok(maps.clone());
        }
        let mut maps = Vec::with_capacity(self.scene.environments.len());
        for e in &self.scene.environments {
            maps.push(match &e.source {
                _ if !self.scene.render.environments => None,
                EnvironmentSource::Map(map) => Some(map.clone()),
                EnvironmentSource::Capture(c) if self.captures => {
                    let map = capture_cube(&self.scene, c.at, c.resolution, &c.hide, c.filter)?;
                    self.built_captures.fetch_add(1, Ordering::Relaxed);
                    Some(Arc::new(map))
                }
                EnvironmentSource::Capture(_) => None,
            });
        }
        let maps: EnvironmentMaps = maps.into();
        *slot = Some(maps.clone());
        Ok(maps)
    }

    /// Captured environments depend on the lights and shadows: made again.
    fn forget_captures(&self) {
        *self.environments.lock().expect("no poisoned lock") = None;
    }

    /// The scene as the renderer draws it (its camera, lights and settings as changed).
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The pre-passes built so far.
    pub fn prepasses(&self) -> Prepasses {
        Prepasses {
            occluders: self.built_occluders.load(Ordering::Relaxed),
            light_shadows: self.built_light_shadows.load(Ordering::Relaxed),
            radiosity: self.kept.solution().map_or(0, |s| s.solved()),
            captures: self.built_captures.load(Ordering::Relaxed),
        }
    }

    /// The radiosity element whose hemi-cube item buffers the `hemicube-*` buffers
    /// show (0 unless chosen).
    pub fn hemicube_element(&self) -> usize {
        self.hemicube_element
    }

    /// Chooses the element the `hemicube-*` buffers show.
    /// Has `progress` told the fraction of each scan-line frame done, band by band
    /// (a command line's progress bar).
    pub fn set_progress(&mut self, progress: impl Fn(f64) + Send + Sync + 'static) {
        self.progress = Some(Arc::new(progress));
    }

    /// A switch another thread may set to stop the scan-line frame being rendered:
    /// it ends after its current band of rows with `Error::Stopped`, and the
    /// pre-passes already built are kept. (Whitted's ray-traced frames and a
    /// radiosity solve run to their end.)
    pub fn set_stop(&mut self, stop: Arc<std::sync::atomic::AtomicBool>) {
        self.stop = Some(stop);
    }

    pub fn set_hemicube_element(&mut self, element: usize) {
        self.hemicube_element = element;
    }

    /// A new camera: nothing view-independent changes.
    pub fn set_camera(&mut self, camera: Camera) {
        self.scene.camera = camera;
    }

    /// Moves or changes light `index`: its shadows are redone, and a radiosity
    /// solution, which holds every light but the polygon lights, is solved again. A
    /// polygon light is a polygon of the scene (geometry), which a renderer does not
    /// change.
    pub fn set_light(&mut self, index: usize, light: Light) -> Result<()> {
        let Some(old) = self.scene.lights.get(index) else {
            return Err(Error::Light {
                index,
                message: format!("the scene has no light {index}"),
            });
        };
        if matches!(old, Light::Polygon(_)) || matches!(light, Light::Polygon(_)) {
            return Err(Error::Light {
                index,
                message: format!(
                    "{} is a polygon of the scene: change the scene, not the light",
                    old.label(index)
                ),
            });
        }
        self.scene.lights[index] = light;
        *self.lights[index].lock().expect("no poisoned lock") = None;
        if let Some(reader) = self.kept.solution() {
            reader.forget();
        }
        self.forget_captures();
        Ok(())
    }

    /// Samples per pixel along each axis (`render.supersample`): a frame setting,
    /// nothing view-independent changes (the viewer previews at one sample a
    /// pixel while the view moves). An irradiance cache, swept per view and
    /// sampling, is swept again.
    pub fn set_supersample(&mut self, samples: u32) {
        self.scene.render.supersample = samples.max(1);
    }

    /// Whether a radiosity solution is kept (solved, or handed over).
    pub fn has_radiosity_solution(&self) -> bool {
        self.kept.solution().is_some_and(|s| s.has_solution())
    }

    /// The integrator that lights this renderer's frames.
    pub fn integrator(&self) -> Integrator {
        self.declared.integrator
    }

    /// New shadow settings: every light's shadows are redone.
    pub fn set_shadows(&mut self, settings: ShadowSettings) {
        self.scene.shadows = settings;
        for slot in &self.lights {
            *slot.lock().expect("no poisoned lock") = None;
        }
        self.forget_captures();
    }

    /// Hands the renderer a radiosity solution of its scene (solved elsewhere, with
    /// progress shown, say), so that it is not solved again; an integrator that
    /// reads no solution (direct light, ray tracing) has no use for it.
    pub fn set_radiosity_solution(&mut self, solution: Arc<Solution>) {
        if let Some(reader) = self.kept.solution() {
            reader.hand_over(&self.scene, solution);
        }
    }

    /// Refuses, before any work, what the integrator cannot render (a key it would
    /// ignore, materials the two-pass methods' first pass cannot carry), a shadow
    /// method that cannot shadow one of the lights the frame shadows, and a ray
    /// march over its step budget.
    pub fn check(&self) -> Result<()> {
        self.check_integrator()?;
        if self.declared.role == Role::ScanLine {
            let method = shadow::method(self.scene.shadows.method);
            let direct = (self.declared.direct_lights)(&self.scene);
            for (index, _) in direct.iter().enumerate().filter(|(_, d)| **d) {
                shadow::check(&self.scene, index, method.method)?;
            }
            (method.budget)(&self.scene).map_err(Error::OverBudget)?;
        }
        Ok(())
    }

    /// What every frame checks first: the march's budget, the integrator's keys
    /// and its own check.
    fn check_integrator(&self) -> Result<()> {
        super::medium::check_march(&self.scene)?;
        check_keys(&self.scene, self.declared)?;
        (self.declared.check)(&self.scene)
    }

    /// Whether a polygon lies in front of the camera, within its field of view and
    /// beyond `camera.near`: a frame where none does shows the background only.
    pub fn sees_a_polygon(&self) -> bool {
        let view = crate::raster::sample_view(&self.scene);
        !crate::raster::screen_polygons(&self.scene, &view).is_empty()
    }

    /// What a user should know of this scene as this renderer draws it: the scene's
    /// own warnings, then its shadow method's (one line each, a line said many times
    /// said once with its count).
    pub fn warnings(&self) -> Vec<String> {
        let method = shadow::method(self.scene.shadows.method);
        let mut warnings = self.scene.warnings.clone();
        if self.declared.role == Role::ScanLine {
            warnings.extend((method.warnings)(&self.scene));
        }
        said_once(warnings)
    }

    /// The frame's linear radiance image.
    pub fn render(&self) -> Result<Image> {
        Ok(self.render_with_buffers(&[])?.image)
    }

    /// The frame, and the buffers named in `buffers` (see `available_buffers`):
    /// made by an integrator that makes its own (Whitted's rays through the
    /// pixels), or the scan-line frame.
    pub fn render_with_buffers(&self, buffers: &[String]) -> Result<Frame> {
        match self.lighting()? {
            Lighting::OwnFrame(integrator) => {
                integrator.render(&self.scene, &self.environment_maps()?, buffers)
            }
            Lighting::ScanLine(integrator) => {
                let plan = self.plan(integrator)?;
                if self.scene.render.sample_pattern == SamplePattern::RotatedGrid
                    && self.scene.render.supersample > 1
                {
                    if let Some(name) = buffers.first() {
                        return Err(Error::invalid(
                            "render.sample_pattern",
                            format!(
                                "render.sample_pattern: the buffer `{name}` is made on the regular grid's samples; the rotated grid averages {} frames and gives the image alone (use sample_pattern = \"regular\" for buffers)",
                                self.scene.render.supersample.pow(2)
                            ),
                        ));
                    }
                    return render_rotated_grid(&self.scene, &plan);
                }
                render_frame(&self.scene, &plan, buffers)
            }
        }
    }

    /// The buffers this renderer's frames can give.
    pub fn available_buffers(&self) -> Result<Vec<BufferInfo>> {
        match self.lighting()? {
            Lighting::OwnFrame(integrator) => Ok(integrator.buffers()),
            Lighting::ScanLine(integrator) => Ok(available(&self.scene, &self.plan(integrator)?)),
        }
    }

    /// What the next frame needs of the integrator, checked first.
    fn lighting(&self) -> Result<Lighting> {
        self.check_integrator()?;
        self.kept.lighting(&self.scene)
    }

    /// Everything the next scan-line frame needs but the scene.
    fn plan(&self, integrator: Arc<dyn ScanLine>) -> Result<FramePlan> {
        let direct = (self.declared.direct_lights)(&self.scene);
        let shadows = self.shadows_of(&direct)?;
        let environments = self.environment_maps()?;
        let marched = self
            .scene
            .medium
            .as_ref()
            .is_some_and(|m| m.extinction > 0.0 && m.method == MediumMethod::RayMarching);
        let occluders = marched.then(|| self.occluders());
        Ok(FramePlan {
            integrator,
            declared: self.declared,
            direct,
            shadows,
            environments,
            occluders,
            hemicube_element: self.hemicube_element,
            progress: self.progress.clone(),
            stop: self.stop.clone(),
        })
    }

    /// How many times an irradiance cache was swept (a view-dependent pass: again
    /// for each new camera).
    pub fn irradiance_caches_swept(&self) -> usize {
        self.kept.caches_swept()
    }

    /// The shadow pre-passes of the lights `direct` selects (`None` for the others
    /// and for unshadowed lights).
    fn shadows_of(&self, direct: &[bool]) -> Result<Vec<Option<Arc<dyn LightShadows>>>> {
        direct
            .iter()
            .enumerate()
            .map(|(index, &lit)| {
                if lit {
                    self.light_shadows(index)
                } else {
                    Ok(None)
                }
            })
            .collect()
    }

    /// Light `index`'s shadow pre-pass (`None`: unshadowed).
    fn light_shadows(&self, index: usize) -> Result<Option<Arc<dyn LightShadows>>> {
        let mut slot = self.lights[index].lock().expect("no poisoned lock");
        if let Some(shadows) = slot.as_ref() {
            return Ok(Some(shadows.clone()));
        }
        let built = shadow::prepare(&self.scene, index, &self.scene.shadows, self)?;
        if let Some(shadows) = &built {
            self.built_light_shadows.fetch_add(1, Ordering::Relaxed);
            *slot = Some(shadows.clone());
        }
        Ok(built)
    }
}

impl SharedWork for Renderer {
    fn occluders(&self) -> Arc<SceneOccluders> {
        let mut slot = self.occluders.lock().expect("no poisoned lock");
        slot.get_or_insert_with(|| {
            self.built_occluders.fetch_add(1, Ordering::Relaxed);
            Arc::new(SceneOccluders::owned(self.scene.polygons.clone()))
        })
        .clone()
    }
}

/// The cube map of `scene` seen from `at`, `size` texels a side: six frames rendered
/// by a renderer that captures nothing itself, without the `hidden` objects.
pub fn capture_cube(
    scene: &Scene,
    at: DVec3,
    size: u32,
    hidden: &[usize],
    filter: Filter,
) -> Result<EnvironmentMap> {
    let seen = without_objects(scene, hidden);
    let mut renderer = Renderer::without_captures(seen);
    let mut faces = Vec::with_capacity(6);
    for camera in face_cameras(at, size, scene.camera.near) {
        renderer.set_camera(camera);
        let image = renderer.render()?;
        faces.push(Texels {
            width: image.width,
            height: image.height,
            texels: image.pixels,
        });
    }
    Ok(EnvironmentMap::cube(faces, filter))
}

/// Each distinct line once, where it first appeared, with how many times it was
/// said when more than once.
fn said_once(lines: Vec<String>) -> Vec<String> {
    let mut counts: std::collections::HashMap<&str, usize> = std::collections::HashMap::new();
    for line in &lines {
        *counts.entry(line.as_str()).or_default() += 1;
    }
    let mut seen = std::collections::HashSet::new();
    lines
        .iter()
        .filter(|line| seen.insert(line.as_str()))
        .map(|line| match counts[line.as_str()] {
            1 => line.clone(),
            n => format!("{line} ({n} times)"),
        })
        .collect()
}
