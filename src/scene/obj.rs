//! Wavefront OBJ + MTL loading through tobj. Every face stays a polygon and keeps the
//! material of its group; faces that are not planar are split into a fan
//! (v0 v1 v2) + (v0 v2 v3) + …, and faces of zero area are dropped with a warning.

use super::Vertex;
use super::resources::Resources;
use super::shapes::Faces;
use crate::error::{Error, Result};
use crate::geometry::polygon::{area, newell_normal, non_planarity};
use glam::{DVec2, DVec3};
use std::cell::RefCell;
use std::io::BufReader;
use std::path::Path;

/// Relative distance from a face's plane above which a face counts as non-planar.
const PLANARITY_TOLERANCE: f64 = 1e-9;
/// Above this a non-planar face is reported: it is visibly bent, not measured data
/// a little off true (the Cornell box's red wall is 0.2% off its plane).
const WARN_NON_PLANAR: f64 = 0.01;

/// One OBJ model: its faces with, per face, the name of its MTL material.
pub struct ObjModel {
    pub faces: Faces,
    pub face_materials: Vec<Option<String>>,
    /// The OBJ object (`o`/`g`) each face belongs to.
    pub face_objects: Vec<String>,
    pub materials: Vec<tobj::Material>,
    pub warnings: Vec<String>,
}

pub fn load(resources: &dyn Resources, path: &Path, smooth: bool) -> Result<ObjModel> {
    let bytes = resources.read(path)?;
    let text = text_only(path, &bytes)?;
    let dir = path.parent().unwrap_or(Path::new("")).to_path_buf();
    let options = tobj::LoadOptions {
        single_index: false,
        triangulate: false,
        ignore_points: true,
        ignore_lines: true,
    };
    // tobj's loader callback can only say "open file failed": keep the real cause.
    let mtl_error = RefCell::new(None);
    let (models, materials) =
        tobj::load_obj_buf(&mut BufReader::new(bytes.as_slice()), &options, |mtl| {
            let data = resources
                .read(&dir.join(mtl))
                .and_then(|data| {
                    text_only(&dir.join(mtl), &data)?;
                    Ok(data)
                })
                .and_then(|data| short_colour(&data).map_or(Ok(data), Err))
                .map_err(|e| {
                    mtl_error.replace(Some(e));
                    tobj::LoadError::OpenFileFailed
                })?;
            tobj::load_mtl_buf(&mut BufReader::new(data.as_slice()))
        })
        .map_err(|e| Error::Model {
            path: path.to_path_buf(),
            message: match first_bad_line(text, &e) {
                Some((number, line)) => format!("{e} at line {number}: `{line}`"),
                None => e.to_string(),
            },
        })?;
    let materials = match (materials, mtl_error.into_inner()) {
        (Ok(m), _) => m,
        (Err(_), Some(cause)) => {
            return Err(cause.within(format!("{}: its MTL file", path.display())));
        }
        (Err(e), None) => {
            return Err(Error::Model {
                path: path.to_path_buf(),
                message: format!("its MTL file: {e}"),
            });
        }
    };

    let mut out = ObjModel {
        faces: Vec::new(),
        face_materials: Vec::new(),
        face_objects: Vec::new(),
        materials,
        warnings: Vec::new(),
    };
    for model in &models {
        let mesh = &model.mesh;
        let material = mesh.material_id.map(|m| out.materials[m].name.clone());
        let arities: Vec<usize> = if mesh.face_arities.is_empty() {
            vec![3; mesh.indices.len() / 3]
        } else {
            mesh.face_arities.iter().map(|&a| a as usize).collect()
        };
        let mut start = 0;
        for arity in arities {
            let face: Vec<Vertex> = (start..start + arity)
                .map(|k| corner(mesh, k, smooth))
                .collect();
            start += arity;
            let positions: Vec<DVec3> = face.iter().map(|v| v.position).collect();
            if positions.iter().any(|p| !p.is_finite()) {
                out.warnings.push(format!(
                    "{}: object {}: a face with a vertex that is not a finite number was dropped",
                    path.display(),
                    model.name
                ));
                continue;
            }
            let bend = non_planarity(&positions);
            if bend > WARN_NON_PLANAR {
                out.warnings.push(format!(
                    "{}: object {}: a face is not planar ({:.1}% of its size off its plane): split into triangles",
                    path.display(),
                    model.name,
                    100.0 * bend
                ));
            }
            for polygon in planar_pieces(face) {
                let positions: Vec<DVec3> = polygon.iter().map(|v| v.position).collect();
                let measure = area(&positions);
                if measure == 0.0 || !measure.is_finite() {
                    out.warnings.push(format!(
                        "{}: object {}: a face of zero area was dropped",
                        path.display(),
                        model.name
                    ));
                    continue;
                }
                out.faces.push(polygon);
                out.face_materials.push(material.clone());
                out.face_objects.push(model.name.clone());
            }
        }
    }
    let short = text
        .lines()
        .filter(|l| l.trim_start().starts_with("f ") && l.split_whitespace().count() < 4)
        .count();
    if short > 0 {
        out.warnings.push(format!(
            "{}: {short} faces of fewer than 3 vertices (points or lines, not polygons) were left out",
            path.display()
        ));
    }
    let has_library = text.lines().any(|l| l.trim_start().starts_with("mtllib "));
    if let Some(name) = text
        .lines()
        .filter(|_| has_library)
        .filter_map(|l| l.trim().strip_prefix("usemtl "))
        .map(str::trim)
        .find(|name| !out.materials.iter().any(|m| m.name == *name))
    {
        let known: Vec<&str> = out.materials.iter().map(|m| m.name.as_str()).collect();
        return Err(Error::Model {
            path: path.to_path_buf(),
            message: format!(
                "usemtl {name}: no such material in its MTL file (defined: {})",
                if known.is_empty() {
                    "none".to_string()
                } else {
                    known.join(", ")
                }
            ),
        });
    }
    if out.faces.is_empty() {
        return Err(Error::Model {
            path: path.to_path_buf(),
            message:
                "no face to draw: an OBJ model needs `f` lines of 3 or more vertices with an area"
                    .into(),
        });
    }
    Ok(out)
}

fn corner(mesh: &tobj::Mesh, k: usize, smooth: bool) -> Vertex {
    let p = mesh.indices[k] as usize * 3;
    let position = DVec3::new(
        mesh.positions[p],
        mesh.positions[p + 1],
        mesh.positions[p + 2],
    );
    let normal = match mesh.normal_indices.get(k) {
        Some(&n) if smooth => {
            let n = n as usize * 3;
            DVec3::new(mesh.normals[n], mesh.normals[n + 1], mesh.normals[n + 2])
                .normalize_or_zero()
        }
        _ => DVec3::ZERO,
    };
    let uv = match mesh.texcoord_indices.get(k) {
        Some(&t) => {
            let t = t as usize * 2;
            DVec2::new(mesh.texcoords[t], mesh.texcoords[t + 1])
        }
        None => DVec2::ZERO,
    };
    Vertex {
        position,
        normal,
        uv,
    }
}

/// The face itself when planar, else its fan triangulation. Vertices without a
/// normal of their own get the piece's face normal.
fn planar_pieces(face: Vec<Vertex>) -> Vec<Vec<Vertex>> {
    let positions: Vec<DVec3> = face.iter().map(|v| v.position).collect();
    let pieces = if face.len() > 3 && non_planarity(&positions) > PLANARITY_TOLERANCE {
        (1..face.len() - 1)
            .map(|i| vec![face[0], face[i], face[i + 1]])
            .collect()
    } else {
        vec![face]
    };
    pieces
        .into_iter()
        .map(|mut piece| {
            let p: Vec<DVec3> = piece.iter().map(|v| v.position).collect();
            let n = newell_normal(&p).normalize_or_zero();
            for v in &mut piece {
                if v.normal == DVec3::ZERO {
                    v.normal = n;
                }
            }
            piece
        })
        .collect()
}

/// A colour line (`Ka`, `Kd`, `Ks`, `Ke`) with fewer than three numbers: tobj's MTL
/// parser panics on one, so it is refused here, by line number.
fn short_colour(mtl: &[u8]) -> Option<Error> {
    let text = String::from_utf8_lossy(mtl);
    text.lines().enumerate().find_map(|(n, line)| {
        let mut words = line.split_whitespace();
        let key = words.next()?;
        let count = words.count();
        (matches!(key, "Ka" | "Kd" | "Ks" | "Ke") && count < 3).then(|| {
            Error::Scene(format!(
                "line {}: `{key}` needs three numbers (r g b), got {count}",
                n + 1
            ))
        })
    })
}

/// The first line (1-based, and its text) an OBJ parse error `error` can be blamed
/// on: tobj reports what went wrong, not where.
/// OBJ and MTL files are text: a byte that is not UTF-8 is named with its line
/// (the reader would say only "read error").
fn text_only<'a>(path: &Path, bytes: &'a [u8]) -> Result<&'a str> {
    let e = match std::str::from_utf8(bytes) {
        Ok(text) => return Ok(text),
        Err(e) => e,
    };
    let at = e.valid_up_to();
    let line = bytes[..at].iter().filter(|&&b| b == b'\n').count() + 1;
    Err(Error::Model {
        path: path.to_path_buf(),
        message: format!(
            "line {line}: byte 0x{:02x} is not UTF-8 text (OBJ and MTL files are text)",
            bytes[at]
        ),
    })
}

fn first_bad_line(text: &str, error: &tobj::LoadError) -> Option<(usize, String)> {
    use tobj::LoadError as E;
    let numbers = |rest: &str, least: usize, most: usize| {
        let fields: Vec<&str> = rest.split_whitespace().collect();
        (least..=most).contains(&fields.len()) && fields.iter().all(|f| f.parse::<f32>().is_ok())
    };
    // Vertex, texture-coordinate and normal counts so far, for face indices.
    let mut counts = [0i64; 3];
    for (index, line) in text.lines().enumerate() {
        let line = line.trim();
        let (keyword, rest) = line.split_once(char::is_whitespace).unwrap_or((line, ""));
        let bad = match keyword {
            "v" => {
                counts[0] += 1;
                matches!(error, E::PositionParseError) && !numbers(rest, 3, 4)
            }
            "vt" => {
                counts[1] += 1;
                matches!(error, E::TexcoordParseError) && !numbers(rest, 1, 3)
            }
            "vn" => {
                counts[2] += 1;
                matches!(error, E::NormalParseError) && !numbers(rest, 3, 3)
            }
            "f" => {
                matches!(
                    error,
                    E::FaceParseError
                        | E::FaceVertexOutOfBounds
                        | E::FaceTexCoordOutOfBounds
                        | E::FaceNormalOutOfBounds
                ) && rest.split_whitespace().any(|corner| {
                    corner.split('/').enumerate().any(|(k, i)| {
                        if i.is_empty() && k > 0 {
                            return false;
                        }
                        match i.parse::<i64>() {
                            Ok(i) => i == 0 || i.unsigned_abs() > counts[k.min(2)] as u64,
                            Err(_) => true,
                        }
                    })
                })
            }
            _ => false,
        };
        if bad {
            return Some((index + 1, line.to_string()));
        }
    }
    None
}
