//! The viewer's engine: one [`Session`] answers the viewer page's messages
//! (docs/viewer-protocol.md), whoever carries them: the WebAssembly worker of the
//! static site or the native server of `lumiere view`. The page never knows which
//! engine draws: both are this code.

mod families;
mod orbit;
mod picture;
mod protocol;
mod solve;
mod view;

pub use picture::buffer_picture;
pub use protocol::{MAX_MESSAGE, Reply};

use crate::catalogue;
use crate::error::Error;
use protocol::{Change, Request, SolveAction, error};
use serde_json::{Value, json};
use std::collections::HashMap;
use std::sync::Arc;
use view::{Source, View};
use web_time::Duration;

/// How long one tick shoots a radiosity solve before showing its state.
const TICK: Duration = Duration::from_millis(120);

/// What the viewer shows and the renderers kept to show it.
#[derive(Default)]
pub struct Session {
    /// Scene files besides catalogue ids that `open` may name (the native
    /// server's command-line scene).
    allowed: Vec<String>,
    /// Overrides of the command line, applied when an allowed scene opens.
    allowed_sets: Vec<String>,
    view: Option<View>,
    /// The id of the last `set` (or `open`), which frames sent on their own carry.
    last_id: Option<u64>,
    quit: bool,
}

impl Session {
    /// A session with no scene open, that opens catalogue entries and files sent.
    pub fn new() -> Session {
        Session::default()
    }

    /// A session that may also open `spec` (a scene file's path or a catalogue id),
    /// with `sets` applied when it does: what `lumiere view SCENE --set …` names.
    pub fn allowing(spec: &str, sets: Vec<String>) -> Session {
        Session {
            allowed: vec![spec.to_string()],
            allowed_sets: sets,
            ..Session::default()
        }
    }

    /// Whether a `quit` was received.
    pub fn quit(&self) -> bool {
        self.quit
    }

    /// The replies to a text message (one JSON object).
    pub fn handle_text(&mut self, text: &str) -> Vec<Reply> {
        match protocol::parse_text(text) {
            Ok(request) => self.handle(request, &[]),
            Err(e) => vec![error(e.id, &e.message)],
        }
    }

    /// The replies to a binary message (header length, header, payload).
    pub fn handle_binary(&mut self, bytes: &[u8]) -> Vec<Reply> {
        match protocol::parse_binary(bytes) {
            Ok((request, payload)) => self.handle(request, payload),
            Err(e) => vec![error(e.id, &e.message)],
        }
    }

    /// Work left over after the last message (a radiosity solve going on): the
    /// frame it makes. Empty when there is nothing to do.
    pub fn tick(&mut self) -> Vec<Reply> {
        let id = self.last_id;
        let Some(view) = self.view.as_mut().filter(|v| v.solving()) else {
            return Vec::new();
        };
        match view.advance(TICK) {
            Ok(()) => self.frame(id),
            Err(e) => vec![error(id, &e.line())],
        }
    }

    /// Whether [`Session::tick`] has work to do.
    pub fn busy(&self) -> bool {
        self.view.as_ref().is_some_and(View::solving)
    }

    fn handle(&mut self, request: Request, payload: &[u8]) -> Vec<Reply> {
        let result = match request {
            Request::Catalogue { id } => catalogue_reply(id),
            Request::Open { id, scene, sets } => {
                let (source, sets) = if self.allowed.contains(&scene) {
                    let mut all = self.allowed_sets.clone();
                    all.extend(sets);
                    (Source::Spec(scene), all)
                } else if catalogue::entry(&scene).is_ok() {
                    (Source::Spec(scene), sets)
                } else {
                    return vec![error(
                        Some(id),
                        &format!(
                            "{scene}: not a catalogue entry (`lumiere list` lists them){}",
                            if self.allowed.is_empty() {
                                "; open a scene's files instead"
                            } else {
                                ""
                            }
                        ),
                    )];
                };
                self.open(id, source, sets)
            }
            Request::OpenFiles {
                id,
                main,
                files,
                sets,
            } => match split_files(&files, payload) {
                Ok(files) => self.open(
                    id,
                    Source::Files {
                        main,
                        files: Arc::new(files),
                    },
                    sets,
                ),
                Err(message) => Err((id, message)),
            },
            Request::Set(change) => self.set(*change),
            Request::Solve { id, action } => self.solve(id, action),
            Request::Export { id, what } => self.export(id, &what),
            Request::Quit { id } => {
                self.quit = true;
                Ok(vec![protocol::text(&json!({"type": "quit", "id": id}))])
            }
        };
        result.unwrap_or_else(|(id, message)| vec![error(Some(id), &message)])
    }

    fn open(
        &mut self,
        id: u64,
        source: Source,
        sets: Vec<String>,
    ) -> Result<Vec<Reply>, (u64, String)> {
        let view = View::open(source, sets).map_err(|e| (id, e.line()))?;
        self.view = Some(view);
        self.last_id = Some(id);
        let mut replies = vec![self.scene_reply(id)];
        replies.extend(self.frame(Some(id)));
        Ok(replies)
    }

    fn scene_reply(&self, id: u64) -> Reply {
        let view = self.view.as_ref().expect("a scene is open");
        let families: Vec<Value> = view
            .families
            .iter()
            .zip(&view.choices)
            .map(|(f, &c)| {
                json!({
                    "name": f.name,
                    "label": f.label,
                    "options": f.options.iter().map(|o| json!({"name": o.name, "paper": o.paper})).collect::<Vec<_>>(),
                    "chosen": f.options[c].name,
                })
            })
            .collect();
        let [yaw, pitch, distance] = view.orbit.state();
        let entry = view.entry.as_ref().map(|a| {
            json!({"id": a.id, "title": a.title, "paper": a.authors, "summary": a.summary, "citation": a.citation})
        });
        protocol::text(&json!({
            "type": "scene",
            "id": id,
            "title": view.source.title(),
            "entry": entry,
            "width": view.scene.camera.width,
            "height": view.scene.camera.height,
            "supersample": view.scene.render.supersample,
            "exposure": view.scene.render.exposure,
            "orbit": {"yaw": yaw, "pitch": pitch, "distance": distance},
            "families": families,
            "lights": view.lights().into_iter().map(|(label, movable)| json!({"label": label, "movable": movable})).collect::<Vec<_>>(),
            "step": view.step,
            "warnings": view.scene.warnings,
        }))
    }

    /// The frame of what is shown, as message `id`'s reply.
    fn frame(&mut self, id: Option<u64>) -> Vec<Reply> {
        let Some(view) = self.view.as_mut() else {
            return vec![error(id, "no scene is open: open one first")];
        };
        let shown = match view.frame() {
            Ok(shown) => shown,
            Err(e) => return vec![error(id, &e.line())],
        };
        let buffers = view.buffers().unwrap_or_default();
        let header = json!({
            "type": "frame",
            "id": id,
            "width": shown.image.width,
            "height": shown.image.height,
            "quality": view.quality.name(),
            "method": view.method(),
            "times": view.times,
            "split": shown.split.map(|(rmse, differing)| json!({"rmse": rmse, "differing": differing})),
            "buffer": shown.buffer.as_ref().map(|(name, legend)| json!({"name": name, "legend": legend})),
            "buffers": buffers,
            "status": view.status(),
            "solving": view.solving(),
        });
        let pixels = picture::rgba(&shown.image, shown.exposure);
        vec![protocol::binary(&header, &pixels)]
    }

    fn view(&mut self, id: u64) -> Result<&mut View, (u64, String)> {
        self.view
            .as_mut()
            .ok_or_else(|| (id, "no scene is open: open one first".to_string()))
    }

    fn set(&mut self, change: Change) -> Result<Vec<Reply>, (u64, String)> {
        let id = change.id;
        let failed = |e: Error| (id, e.line());
        let view = self.view(id)?;
        if let Some(choices) = &change.choices {
            let mut chosen = view.choices.clone();
            for (family, option) in choices {
                let Some(f) = view.families.iter().position(|f| f.name == family) else {
                    let names: Vec<&str> = view.families.iter().map(|f| f.name).collect();
                    return Err((
                        id,
                        format!(
                            "choices: the scene offers no family `{family}` (it offers: {})",
                            names.join(", ")
                        ),
                    ));
                };
                chosen[f] = option_index(&view.families[f], option).map_err(|m| (id, m))?;
            }
            view.choices = chosen;
        }
        if let Some(split) = &change.split {
            view.split = match split {
                None => None,
                Some(option) => {
                    let Some(first) = view.families.first() else {
                        return Err((id, "split: the scene offers no methods to compare".into()));
                    };
                    Some(option_index(first, option).map_err(|m| (id, m))?)
                }
            };
        }
        if let Some(difference) = change.difference {
            view.difference = difference;
        }
        if let Some(buffer) = &change.buffer {
            view.buffer = buffer.clone();
        }
        if let Some(exposure) = change.exposure {
            if !(exposure.is_finite() && exposure > 0.0) {
                return Err((
                    id,
                    format!("exposure must be a positive number, got {exposure}"),
                ));
            }
            view.exposure = exposure;
        }
        if let Some(quality) = change.quality {
            view.quality = quality;
        }
        if let Some(o) = change.orbit {
            view.orbit.set(o.yaw, o.pitch, o.distance);
        }
        if let Some(lights) = &change.lights {
            if lights.len() != view.offsets.len() {
                return Err((
                    id,
                    format!(
                        "lights: the scene has {} lights, {} offsets were sent",
                        view.offsets.len(),
                        lights.len()
                    ),
                ));
            }
            for (index, offset) in lights.iter().enumerate() {
                let offset = glam::DVec3::from_array(*offset);
                if !offset.is_finite() {
                    return Err((id, format!("lights: offset {index} is not finite")));
                }
                view.move_light(index, offset).map_err(failed)?;
            }
        }
        self.last_id = Some(id);
        Ok(self.frame(Some(id)))
    }

    fn solve(&mut self, id: u64, action: SolveAction) -> Result<Vec<Reply>, (u64, String)> {
        let view = self.view(id)?;
        let steered = view
            .steer(|s| match action {
                SolveAction::Pause => s.paused = true,
                SolveAction::Resume => s.paused = false,
                SolveAction::Step => s.ask_step(),
            })
            .map_err(|e| (id, e.line()))?;
        if !steered {
            return Err((
                id,
                "solve: what is shown has no shooting solve to steer (choose the shooting solver)"
                    .into(),
            ));
        }
        self.last_id = Some(id);
        if matches!(action, SolveAction::Step) {
            // The step now, and its state.
            return Ok(self.tick());
        }
        Ok(self.frame(Some(id)))
    }

    fn export(&mut self, id: u64, what: &str) -> Result<Vec<Reply>, (u64, String)> {
        let view = self.view(id)?;
        let (width, height, channels, values) = view.export(what).map_err(|e| (id, e.line()))?;
        let header = json!({"type": "export", "id": id, "what": what, "width": width, "height": height, "channels": channels});
        let payload: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        Ok(vec![protocol::binary(&header, &payload)])
    }
}

fn option_index(family: &families::Family, option: &str) -> Result<usize, String> {
    family
        .options
        .iter()
        .position(|o| o.name == option)
        .ok_or_else(|| {
            let names: Vec<&str> = family.options.iter().map(|o| o.name.as_str()).collect();
            format!(
                "{}: no option `{option}` (the scene offers: {})",
                family.name,
                names.join(", ")
            )
        })
}

fn catalogue_reply(id: u64) -> Result<Vec<Reply>, (u64, String)> {
    let entries = catalogue::entries().map_err(|e| (id, e.line()))?;
    let entries: Vec<Value> = entries
        .iter()
        .map(|e| {
            let a = &e.algorithm;
            json!({"id": a.id, "title": a.title, "topic": a.topic, "paper": a.authors, "summary": a.summary})
        })
        .collect();
    Ok(vec![protocol::text(
        &json!({"type": "catalogue", "id": id, "entries": entries}),
    )])
}

/// The files of an `open-files` message, cut from its payload by their sizes.
fn split_files(
    files: &[protocol::FileSize],
    payload: &[u8],
) -> Result<HashMap<String, Vec<u8>>, String> {
    let total = files
        .iter()
        .try_fold(0usize, |sum, f| sum.checked_add(f.size));
    if total != Some(payload.len()) {
        return Err(format!(
            "open-files: the files' sizes add up to {}, but {} bytes came",
            total.map_or("more than can be".into(), |t| t.to_string()),
            payload.len()
        ));
    }
    let mut out = HashMap::new();
    let mut at = 0;
    for f in files {
        out.insert(f.name.clone(), payload[at..at + f.size].to_vec());
        at += f.size;
    }
    Ok(out)
}
