//! `preview.png`: a picture of the deformed body, drawn by the program itself (no system
//! libraries), for users without ParaView.
//!
//! The boundary surface of the final state is rasterized with a depth buffer through an
//! orthographic camera at azimuth 30 deg and elevation 20 deg, "up" being against gravity
//! (+z in a scene without gravity), framing the rest and deformed bodies together. 10-node
//! meshes draw each 6-node face as its 4 sub-triangles through the mid-edge nodes, so that
//! bending shows curved. Each triangle has the viridis color of a field ([`PreviewField`],
//! the values of the VTU frames' field of that name) darkened by flat Lambert shading. The
//! rest configuration's outline (its feature edges, where faces meet at more than 30 deg, and
//! its silhouette) is drawn over it in thin grey. `plotters` draws the color bar, its labels
//! and the title, and encodes the PNG. The image is always [`WIDTH`] x [`HEIGHT`]; a body
//! with no extent or no finite position gives a picture that says so.

use super::frames::FrameFields;
use super::plots::{plot_error, register_font};
use crate::error::SceneError;
use crate::format::PreviewField;
use isochor_mesh::{ElementMesh, ElementSurface, Vec3};
use plotters::backend::DrawingBackend;
use plotters::prelude::*;
use plotters::style::colors::colormaps::{ColorMap, ViridisRGB};
use std::path::Path;

/// Width of the picture in pixels.
pub const WIDTH: u32 = 800;
/// Height of the picture in pixels.
pub const HEIGHT: u32 = 600;
/// Camera azimuth about the up axis, from the front, in degrees.
const AZIMUTH_DEG: f64 = 30.0;
/// Camera elevation above the horizontal plane, in degrees.
const ELEVATION_DEG: f64 = 20.0;
/// The body's area: `(left, top, right, bottom)` pixels; the color bar is to its right.
const AREA: (f64, f64, f64, f64) = (10.0, 50.0, 670.0, 590.0);
/// Free space around the framed bodies, as a fraction of their size.
const MARGIN: f64 = 0.06;
/// Rest edges between faces whose normals differ by more than this are outlined.
const FEATURE_ANGLE_DEG: f64 = 30.0;
const BACKGROUND: RGBColor = WHITE;
/// The rest outline's color.
pub const OUTLINE: RGBColor = RGBColor(128, 128, 128);
/// The obstacles' color (before shading).
pub const OBSTACLE: RGBColor = RGBColor(190, 190, 200);
/// The cloths' color (before shading).
pub const CLOTH: RGBColor = RGBColor(205, 70, 60);
/// Color bar: `(left, top, right, bottom)` pixels.
const BAR: (i32, i32, i32, i32) = (690, 80, 712, 560);

/// How to draw the preview.
#[derive(Debug, Clone, Copy)]
pub struct PreviewOptions<'a> {
    /// The field that colors the body.
    pub field: PreviewField,
    /// Outline the rest configuration.
    pub rest_outline: bool,
    /// The gravitational acceleration of the scene, whose opposite is drawn up.
    pub gravity: Option<[f64; 3]>,
    /// The title (scene and method; whether the run failed).
    pub title: &'a str,
    /// The obstacles' triangles where they stand, drawn in grey (the camera frames the body).
    pub obstacles: &'a [[Vec3; 3]],
    /// The cloths' triangles where they stand, drawn in red.
    pub cloths: &'a [[Vec3; 3]],
}

/// Draws the boundary of `mesh` at `fields.positions` and writes it as a PNG to `path`.
pub fn write_preview(
    path: &Path,
    mesh: &ElementMesh,
    fields: &FrameFields<'_>,
    options: &PreviewOptions<'_>,
) -> Result<(), SceneError> {
    let picture = render(mesh, fields, options)?;
    let mut backend = BitMapBackend::new(path, (WIDTH, HEIGHT));
    backend
        .blit_bitmap((0, 0), (WIDTH, HEIGHT), &picture)
        .map_err(|e| plot_error(path, e))?;
    backend.present().map_err(|e| plot_error(path, e))
}

/// Renders the picture into memory: RGB rows, top first.
fn render(
    mesh: &ElementMesh,
    fields: &FrameFields<'_>,
    options: &PreviewOptions<'_>,
) -> Result<Vec<u8>, SceneError> {
    if fields.positions.len() != mesh.num_nodes() {
        return Err(SceneError::Output(format!(
            "preview: {} positions for a mesh of {} nodes",
            fields.positions.len(),
            mesh.num_nodes()
        )));
    }
    let surface = mesh.boundary()?;
    let rest = mesh.nodes();
    let deformed = fields.positions;
    let camera = Camera::framing(up_axis(options.gravity), rest.iter().chain(deformed));
    let mut canvas = Canvas::new();
    let mut range = None;
    if let Some(camera) = &camera {
        let values = FieldValues::new(mesh, fields, options.field);
        let triangles = colored_triangles(&surface, &values, deformed);
        range = value_range(triangles.iter().map(|t| t.1));
        let (lo, hi) = range.unwrap_or((0.0, 0.0));
        for (tri, value) in &triangles {
            let x = tri.map(|i| deformed[i]);
            let color = shade(colormap(value, lo, hi), camera.lambert(&x));
            canvas.fill_triangle(x.map(|p| camera.project(&p)), color);
        }
        let others = (options.obstacles.iter().map(|x| (x, OBSTACLE)))
            .chain(options.cloths.iter().map(|x| (x, CLOTH)));
        for (x, base) in others {
            let color = shade(base, camera.lambert(x).max(0.3));
            canvas.fill_triangle(x.map(|p| camera.project(&p)), color);
        }
        if options.rest_outline {
            for path in rest_outline(&surface, rest, camera) {
                for pair in path.windows(2) {
                    canvas.line(pair[0], pair[1], OUTLINE);
                }
            }
        }
    }
    let mut rgb = canvas.rgb;
    {
        register_font();
        let root = BitMapBackend::with_buffer(&mut rgb, (WIDTH, HEIGHT)).into_drawing_area();
        root.draw(&Text::new(
            options.title.to_string(),
            (10, 12),
            ("sans-serif", 22).into_font(),
        ))
        .map_err(drawing_error)?;
        let note = match &camera {
            None => "nothing to draw: the body has no extent or no finite position".to_string(),
            Some(_) => [
                Some("deformed body"),
                options
                    .rest_outline
                    .then_some("rest shape outlined in grey"),
                (!options.obstacles.is_empty()).then_some("obstacles light grey"),
                (!options.cloths.is_empty()).then_some("cloth red"),
            ]
            .into_iter()
            .flatten()
            .collect::<Vec<_>>()
            .join("; "),
        };
        root.draw(&Text::new(note, (10, 38), ("sans-serif", 14).into_font()))
            .map_err(drawing_error)?;
        if let Some((lo, hi)) = range {
            color_bar(&root, options.field, lo, hi)?;
        }
        root.present().map_err(drawing_error)?;
    }
    Ok(rgb)
}

/// The color bar: viridis from `lo` (bottom) to `hi` (top), with the field's name.
fn color_bar(
    root: &DrawingArea<BitMapBackend<'_>, plotters::coord::Shift>,
    field: PreviewField,
    lo: f64,
    hi: f64,
) -> Result<(), SceneError> {
    let (left, top, right, bottom) = BAR;
    for y in top..bottom {
        let t = f64::from(bottom - 1 - y) / f64::from(bottom - 1 - top);
        let color = colormap(&(lo + t * (hi - lo)), lo, hi);
        root.draw(&Rectangle::new([(left, y), (right, y + 1)], color.filled()))
            .map_err(drawing_error)?;
    }
    root.draw(&Rectangle::new([(left, top), (right, bottom)], BLACK))
        .map_err(drawing_error)?;
    let name = match field {
        PreviewField::Displacement => "|displacement|",
        other => other.name(),
    };
    let font = ("sans-serif", 15).into_font();
    root.draw(&Text::new(name, (left - 20, top - 24), font.clone()))
        .map_err(drawing_error)?;
    root.draw(&Text::new(number(hi), (right + 6, top - 6), font.clone()))
        .map_err(drawing_error)?;
    root.draw(&Text::new(number(lo), (right + 6, bottom - 8), font))
        .map_err(drawing_error)?;
    Ok(())
}

fn drawing_error(e: impl std::fmt::Display) -> SceneError {
    SceneError::Output(format!("preview: {e}"))
}

/// A color bar label: four significant digits.
fn number(v: f64) -> String {
    let magnitude = v.abs().log10().floor();
    if v == 0.0 {
        "0".to_string()
    } else if (-2.0..4.0).contains(&magnitude) {
        let decimals = (3.0 - magnitude) as usize;
        format!("{v:.decimals$}")
    } else {
        format!("{v:.3e}")
    }
}

/// The up direction of the picture: against gravity, else +z.
fn up_axis(gravity: Option<[f64; 3]>) -> Vec3 {
    gravity
        .map(|g| -Vec3::from(g))
        .and_then(|g| g.try_normalize(0.0))
        .filter(|g| g.iter().all(|c| c.is_finite()))
        .unwrap_or_else(Vec3::z)
}

/// An orthographic camera that maps world points to pixels and depth (larger is nearer).
#[derive(Debug, Clone, Copy)]
struct Camera {
    right: Vec3,
    up: Vec3,
    /// From the body toward the viewer.
    toward: Vec3,
    /// World point at the center of the body's area.
    center: Vec3,
    /// Pixels per unit length.
    scale: f64,
}

impl Camera {
    /// The camera looking at the finite ones of `points` from the default view with `up`
    /// pointing up; `None` if they have no extent across the view (or none is finite).
    fn framing<'a>(up: Vec3, points: impl Iterator<Item = &'a Vec3>) -> Option<Camera> {
        // The horizontal reference: the world axis most across `up`.
        let axis = (0..3)
            .map(|k| Vec3::ith(k, 1.0))
            .min_by(|a, b| a.dot(&up).abs().total_cmp(&b.dot(&up).abs()))?;
        let a = (axis - axis.dot(&up) * up).try_normalize(1e-12)?;
        let b = up.cross(&a);
        let (az, el) = (AZIMUTH_DEG.to_radians(), ELEVATION_DEG.to_radians());
        let toward = el.cos() * (az.sin() * a - az.cos() * b) + el.sin() * up;
        let right = up.cross(&toward).normalize();
        let screen_up = toward.cross(&right);
        let (mut lo, mut hi) = (Vec3::repeat(f64::INFINITY), Vec3::repeat(f64::NEG_INFINITY));
        for p in points.filter(|p| p.iter().all(|c| c.is_finite())) {
            lo = lo.inf(p);
            hi = hi.sup(p);
        }
        if lo.x > hi.x {
            return None;
        }
        let center = 0.5 * (lo + hi);
        // Screen extent of the bounding box's corners.
        let (mut width, mut height) = (0.0_f64, 0.0_f64);
        for k in 0..8 {
            let corner = Vec3::new(
                if k & 1 == 0 { lo.x } else { hi.x },
                if k & 2 == 0 { lo.y } else { hi.y },
                if k & 4 == 0 { lo.z } else { hi.z },
            ) - center;
            width = width.max(2.0 * corner.dot(&right).abs());
            height = height.max(2.0 * corner.dot(&screen_up).abs());
        }
        let (left, top, right_px, bottom) = AREA;
        let fits = |extent: f64, pixels: f64| {
            (extent > 0.0).then(|| pixels / (extent * (1.0 + 2.0 * MARGIN)))
        };
        let scale = match (fits(width, right_px - left), fits(height, bottom - top)) {
            (Some(w), Some(h)) => w.min(h),
            (Some(s), None) | (None, Some(s)) => s,
            (None, None) => return None,
        };
        (scale.is_finite() && scale > 0.0).then_some(Camera {
            right,
            up: screen_up,
            toward,
            center,
            scale,
        })
    }

    /// Pixel column, pixel row and depth of `p`.
    fn project(&self, p: &Vec3) -> [f64; 3] {
        let (left, top, right, bottom) = AREA;
        let d = p - self.center;
        [
            0.5 * (left + right) + self.scale * d.dot(&self.right),
            0.5 * (top + bottom) - self.scale * d.dot(&self.up),
            d.dot(&self.toward),
        ]
    }

    /// Brightness of a flat triangle: ambient plus two-sided Lambert for a light from the
    /// upper left of the viewer.
    fn lambert(&self, x: &[Vec3; 3]) -> f64 {
        let light = (self.toward + 0.5 * self.up - 0.3 * self.right).normalize();
        let diffuse = (x[1] - x[0])
            .cross(&(x[2] - x[0]))
            .try_normalize(0.0)
            .map_or(0.0, |n| n.dot(&light).abs());
        0.3 + 0.7 * if diffuse.is_finite() { diffuse } else { 0.0 }
    }
}

/// An RGB image with a depth buffer.
struct Canvas {
    rgb: Vec<u8>,
    depth: Vec<f64>,
}

impl Canvas {
    fn new() -> Self {
        let pixels = (WIDTH * HEIGHT) as usize;
        let RGBColor(r, g, b) = BACKGROUND;
        Canvas {
            rgb: [r, g, b].repeat(pixels),
            depth: vec![f64::NEG_INFINITY; pixels],
        }
    }

    /// Fills the pixels whose centers lie in the triangle of projected corners `p` where it
    /// is nearer than what is there; skips triangles with a non-finite corner or no area.
    fn fill_triangle(&mut self, p: [[f64; 3]; 3], color: RGBColor) {
        if p.iter().flatten().any(|c| !c.is_finite()) {
            return;
        }
        let edge = |a: [f64; 3], b: [f64; 3], x: f64, y: f64| {
            (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0])
        };
        let area = edge(p[0], p[1], p[2][0], p[2][1]);
        if area.abs() < 1e-12 {
            return;
        }
        let clamp = |v: f64, n: u32| v.clamp(0.0, f64::from(n - 1)) as usize;
        let x0 = clamp(
            p.iter().map(|q| q[0]).fold(f64::INFINITY, f64::min).floor(),
            WIDTH,
        );
        let x1 = clamp(
            p.iter()
                .map(|q| q[0])
                .fold(f64::NEG_INFINITY, f64::max)
                .ceil(),
            WIDTH,
        );
        let y0 = clamp(
            p.iter().map(|q| q[1]).fold(f64::INFINITY, f64::min).floor(),
            HEIGHT,
        );
        let y1 = clamp(
            p.iter()
                .map(|q| q[1])
                .fold(f64::NEG_INFINITY, f64::max)
                .ceil(),
            HEIGHT,
        );
        let RGBColor(r, g, b) = color;
        for y in y0..=y1 {
            for x in x0..=x1 {
                let (cx, cy) = (x as f64 + 0.5, y as f64 + 0.5);
                let w = [
                    edge(p[1], p[2], cx, cy) / area,
                    edge(p[2], p[0], cx, cy) / area,
                    edge(p[0], p[1], cx, cy) / area,
                ];
                if w.iter().any(|&w| w < -1e-9) {
                    continue;
                }
                let depth = w[0] * p[0][2] + w[1] * p[1][2] + w[2] * p[2][2];
                let k = y * WIDTH as usize + x;
                if depth > self.depth[k] {
                    self.depth[k] = depth;
                    self.rgb[3 * k..3 * k + 3].copy_from_slice(&[r, g, b]);
                }
            }
        }
    }

    /// Draws the segment between projected points `a` and `b` in `color`, over everything,
    /// one pixel wide, unless an end is not finite.
    fn line(&mut self, a: [f64; 3], b: [f64; 3], color: RGBColor) {
        if a.iter().chain(&b).any(|c| !c.is_finite()) {
            return;
        }
        // The ends lie in the picture, so the steps are bounded by its size.
        let steps = (b[0] - a[0])
            .abs()
            .max((b[1] - a[1]).abs())
            .ceil()
            .min(4096.0) as usize;
        let RGBColor(r, g, bl) = color;
        for k in 0..=steps {
            let t = if steps == 0 {
                0.0
            } else {
                k as f64 / steps as f64
            };
            let (x, y) = (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]));
            if (0.0..f64::from(WIDTH)).contains(&x) && (0.0..f64::from(HEIGHT)).contains(&y) {
                let i = 3 * (y as usize * WIDTH as usize + x as usize);
                self.rgb[i..i + 3].copy_from_slice(&[r, g, bl]);
            }
        }
    }
}

/// The field, per node (displacement length) or per element.
enum FieldValues {
    Nodes(Vec<f64>),
    Elements(Vec<f64>),
}

impl FieldValues {
    fn new(mesh: &ElementMesh, fields: &FrameFields<'_>, field: PreviewField) -> Self {
        match field {
            PreviewField::Displacement => {
                FieldValues::Nodes(fields.displacements(mesh).iter().map(Vec3::norm).collect())
            }
            PreviewField::VonMises => FieldValues::Elements(fields.von_mises_or_zeros(mesh)),
            PreviewField::MeanStress => FieldValues::Elements(fields.mean_stresses(mesh)),
            PreviewField::J => FieldValues::Elements(fields.volume_ratios(mesh)),
        }
    }

    /// The value of the triangle `nodes` of a face of element `owner`.
    fn value(&self, nodes: &[usize; 3], owner: usize) -> f64 {
        match self {
            FieldValues::Nodes(v) => nodes.iter().map(|&i| v[i]).sum::<f64>() / 3.0,
            FieldValues::Elements(v) => v[owner],
        }
    }
}

/// The triangles to draw, with their values: every 3-node face, or the 4 sub-triangles of
/// every 6-node face (corners 0, 1, 2; mid-edge nodes 3, 4, 5 of edges 01, 12, 20). Triangles
/// with a non-finite corner are left out.
fn colored_triangles(
    surface: &ElementSurface,
    values: &FieldValues,
    x: &[Vec3],
) -> Vec<([usize; 3], f64)> {
    let owners = surface.corners().owner_tets();
    let mut triangles = Vec::new();
    for (f, &owner) in owners.iter().enumerate() {
        let n = surface.face(f);
        let pieces: &[[usize; 3]] = if n.len() == 6 {
            &[
                [n[0], n[3], n[5]],
                [n[3], n[1], n[4]],
                [n[5], n[4], n[2]],
                [n[3], n[4], n[5]],
            ]
        } else {
            &[[n[0], n[1], n[2]]]
        };
        triangles.extend(
            pieces
                .iter()
                .filter(|t| t.iter().all(|&i| x[i].iter().all(|c| c.is_finite())))
                .map(|t| (*t, values.value(t, owner))),
        );
    }
    triangles
}

/// `(min, max)` of the finite values, `None` if there is none.
fn value_range(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    values
        .filter(|v| v.is_finite())
        .fold(None, |range, v| match range {
            None => Some((v, v)),
            Some((lo, hi)) => Some((v.min(lo), v.max(hi))),
        })
}

/// The viridis color of `v` in `[lo, hi]` (the middle one when the range is empty or `v` is
/// not finite).
fn colormap(v: &f64, lo: f64, hi: f64) -> RGBColor {
    let t = if hi > lo && v.is_finite() {
        ((v - lo) / (hi - lo)).clamp(0.0, 1.0)
    } else {
        0.5
    };
    ViridisRGB.get_color(t)
}

fn shade(RGBColor(r, g, b): RGBColor, brightness: f64) -> RGBColor {
    let s = |c: u8| (f64::from(c) * brightness.clamp(0.0, 1.0)).round() as u8;
    RGBColor(s(r), s(g), s(b))
}

/// The rest outline as paths of projected points: every boundary edge that is a feature
/// edge, on the silhouette or on only one face, through its mid-edge node on a 10-node mesh.
fn rest_outline(surface: &ElementSurface, rest: &[Vec3], camera: &Camera) -> Vec<Vec<[f64; 3]>> {
    let corners: Vec<[usize; 3]> = (0..surface.len())
        .map(|f| {
            let n = surface.face(f);
            [n[0], n[1], n[2]]
        })
        .collect();
    let normals: Vec<Vec3> = corners
        .iter()
        .map(|t| {
            (rest[t[1]] - rest[t[0]])
                .cross(&(rest[t[2]] - rest[t[0]]))
                .try_normalize(0.0)
                .unwrap_or_else(Vec3::zeros)
        })
        .collect();
    // (sorted corner pair, face, local edge) of every face edge, grouped by edge.
    let mut edges: Vec<([usize; 2], usize, usize)> = Vec::new();
    for (f, t) in corners.iter().enumerate() {
        for i in 0..3 {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            edges.push(([a.min(b), a.max(b)], f, i));
        }
    }
    edges.sort_unstable();
    let cos_feature = FEATURE_ANGLE_DEG.to_radians().cos();
    let pixel = |p: &Vec3| camera.project(p);
    edges
        .chunk_by(|a, b| a.0 == b.0)
        .filter(|group| match group {
            [(_, f, _), (_, g, _)] => {
                let (n, m) = (normals[*f], normals[*g]);
                n.dot(&m) < cos_feature
                    || (n.dot(&camera.toward) > 0.0) != (m.dot(&camera.toward) > 0.0)
            }
            _ => true,
        })
        .map(|group| {
            let ([a, b], f, i) = group[0];
            let face = surface.face(f);
            let mut path = vec![pixel(&rest[a])];
            if face.len() == 6 {
                path.push(pixel(&rest[face[3 + i]]));
            }
            path.push(pixel(&rest[b]));
            path
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use isochor_mesh::generate::box_grid;

    fn options(rest_outline: bool) -> PreviewOptions<'static> {
        PreviewOptions {
            field: PreviewField::Displacement,
            rest_outline,
            gravity: None,
            title: "test",
            obstacles: &[],
            cloths: &[],
        }
    }

    /// Shaded viridis has unequal channels; the background, outline and text are grey.
    fn is_body(p: &[u8]) -> bool {
        p.iter().max().unwrap() - p.iter().min().unwrap() > 10
    }

    /// Body pixels inside the body's area and outside both it and the color bar.
    fn body_pixels(rgb: &[u8]) -> (usize, usize) {
        let (left, top, right, bottom) = AREA;
        let (mut inside, mut outside) = (0, 0);
        for (k, p) in rgb.chunks_exact(3).enumerate() {
            let (x, y) = ((k % WIDTH as usize) as f64, (k / WIDTH as usize) as f64);
            if !is_body(p) {
                continue;
            }
            if (left..right).contains(&x) && (top..bottom).contains(&y) {
                inside += 1;
            } else if !(f64::from(BAR.0)..=f64::from(BAR.2)).contains(&x) {
                outside += 1;
            }
        }
        (inside, outside)
    }

    fn outline_pixels(rgb: &[u8]) -> usize {
        rgb.chunks_exact(3)
            .filter(|p| *p == [OUTLINE.0, OUTLINE.1, OUTLINE.2])
            .count()
    }

    fn cube(cells: usize) -> ElementMesh {
        ElementMesh::linear(box_grid(Vec3::zeros(), Vec3::repeat(1.0), [cells; 3]).unwrap())
    }

    fn draw(mesh: &ElementMesh, positions: &[Vec3], rest_outline: bool) -> Vec<u8> {
        let mut fields = FrameFields::rest(mesh);
        fields.positions = positions;
        render(mesh, &fields, &options(rest_outline)).unwrap()
    }

    #[test]
    fn a_sheared_cube_fills_its_area_and_stays_inside() {
        let mesh = cube(2);
        let sheared: Vec<Vec3> = mesh
            .nodes()
            .iter()
            .map(|p| p + Vec3::new(0.3 * p.z, 0.0, 0.0))
            .collect();
        let picture = draw(&mesh, &sheared, true);
        let (inside, outside) = body_pixels(&picture);
        let area = (AREA.2 - AREA.0) * (AREA.3 - AREA.1);
        assert!(inside as f64 > 0.15 * area, "{inside} body pixels");
        assert_eq!(outside, 0);
        let grey = outline_pixels(&picture);
        assert!(grey > 500, "{grey} outline pixels");
    }

    /// A plate under the cube is drawn in light grey around it, and the body stays on top.
    #[test]
    fn obstacles_are_drawn_in_grey() {
        let mesh = cube(1);
        let plate = [
            [
                Vec3::new(-1.0, -1.0, 0.0),
                Vec3::new(2.0, -1.0, 0.0),
                Vec3::new(2.0, 2.0, 0.0),
            ],
            [
                Vec3::new(-1.0, -1.0, 0.0),
                Vec3::new(2.0, 2.0, 0.0),
                Vec3::new(-1.0, 2.0, 0.0),
            ],
        ];
        let fields = FrameFields::rest(&mesh);
        let bare = render(&mesh, &fields, &options(false)).unwrap();
        let with = render(
            &mesh,
            &fields,
            &PreviewOptions {
                obstacles: &plate,
                ..options(false)
            },
        )
        .unwrap();
        let light = |rgb: &[u8]| {
            rgb.chunks_exact(3)
                .filter(|p| !is_body(p) && p[0] < 250 && p[0] > 40)
                .count()
        };
        assert!(
            light(&with) > light(&bare) + 1000,
            "{} against {}",
            light(&with),
            light(&bare)
        );
        assert_eq!(
            body_pixels(&with).0,
            body_pixels(&bare).0,
            "the body is in front"
        );
    }

    /// Mid-edge nodes pulled inward dent the drawn faces: fewer body pixels than with the
    /// same corners and straight edges (in the same frame: the corners set the bounds).
    #[test]
    fn quadratic_faces_are_drawn_through_their_mid_edge_nodes() {
        let mesh =
            ElementMesh::quadratic(box_grid(Vec3::zeros(), Vec3::repeat(1.0), [1; 3]).unwrap());
        let center = Vec3::repeat(0.5);
        let dented: Vec<Vec3> = mesh
            .nodes()
            .iter()
            .enumerate()
            .map(|(i, p)| {
                if i < mesh.num_vertices() {
                    *p
                } else {
                    p - 0.3 * (p - center)
                }
            })
            .collect();
        let flat = body_pixels(&draw(&mesh, mesh.nodes(), false)).0;
        let curved = body_pixels(&draw(&mesh, &dented, false)).0;
        assert!((curved as f64) < 0.95 * flat as f64, "{curved} vs {flat}");
    }

    /// A state without a finite position, or collapsed to a point, draws no body; points
    /// with no extent or none finite give no camera.
    #[test]
    fn degenerate_states_draw_nothing_and_never_panic() {
        let mesh = cube(1);
        let nan = vec![Vec3::repeat(f64::NAN); mesh.num_nodes()];
        let picture = draw(&mesh, &nan, true);
        assert!(outline_pixels(&picture) > 500, "the rest body is framed");
        assert_eq!(body_pixels(&picture), (0, 0));
        let point = vec![Vec3::new(0.5, 0.5, 0.5); mesh.num_nodes()];
        assert_eq!(body_pixels(&draw(&mesh, &point, true)), (0, 0));
        let up = Vec3::z();
        assert!(Camera::framing(up, point.iter()).is_none());
        assert!(Camera::framing(up, nan.iter()).is_none());
        let line: Vec<Vec3> = (0..5).map(|k| Vec3::new(f64::from(k), 0.0, 0.0)).collect();
        let camera = Camera::framing(up, line.iter()).expect("a segment across the view");
        assert!(line
            .iter()
            .all(|p| camera.project(p).iter().all(|c| c.is_finite())));
        let mut fields = FrameFields::rest(&mesh);
        fields.positions = &line;
        assert!(render(&mesh, &fields, &options(true)).is_err());
    }

    #[test]
    fn up_is_against_gravity_or_z() {
        assert_eq!(up_axis(Some([0.0, -9.8, 0.0])), Vec3::y());
        assert_eq!(up_axis(Some([0.0, 0.0, 0.0])), Vec3::z());
        assert_eq!(up_axis(None), Vec3::z());
    }

    #[test]
    fn labels_are_short() {
        assert_eq!(number(0.0), "0");
        assert_eq!(number(0.5), "0.5000");
        assert_eq!(number(0.0125), "0.01250");
        assert_eq!(number(1234.4), "1234");
        assert_eq!(number(2.5e-5), "2.500e-5");
        assert_eq!(number(-3.0e6), "-3.000e6");
    }
}
