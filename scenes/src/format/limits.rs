//! Bounds on what a scene may ask for, checked before anything is allocated.
//!
//! - **Steps.** `stepping.steps`, `stepping.frames` and `output.every` are at most
//!   [`MAX_STEPS`].
//! - **Memory.** The run's peak memory is estimated from the scene alone ([`Footprint`]):
//!   vertices and tets from the generator's formula (or a mesh file's header counts), nodes
//!   and unknowns from the element and method, bytes from a model fitted to measured peaks,
//!   plus the per-step records. A scene whose estimate exceeds half of the machine's memory
//!   is refused, naming the key that drives the estimate. All size arithmetic is in `f64`,
//!   which cannot wrap.

use super::mesh::MeshSpec;
use super::names::{LinearName, ZoneKind};
use super::scene::Scene;
use super::stepping::SteppingSpec;
use crate::error::SceneError;
use isochor_mesh::element::TetElement;
use isochor_solvers::{Method, AUTO_DIRECT_UNKNOWNS};
use std::io::{BufRead, BufReader, Read};
use std::path::Path;

/// Largest number of quasi-static steps or dynamic frames. A run keeps a record of every
/// step (about [`BYTES_PER_STEP`]) for its outputs and writes a line per step and iteration
/// to its logs; a million steps is a load increment of `1e-6`, or e.g. 10 s at `dt = 1e-5`,
/// beyond what any scene of this program needs.
pub const MAX_STEPS: usize = 1_000_000;

/// Memory assumed when `/proc/meminfo` cannot be read.
const FALLBACK_MEMORY: f64 = 8.0 * GIB;

/// Fraction of the machine's memory a run may be estimated to use.
const BUDGET_FRACTION: f64 = 0.5;

const GIB: f64 = 1024.0 * 1024.0 * 1024.0;

/// Memory of the process before the mesh: code, tables, output buffers.
const BASE_BYTES: f64 = 16.0 * 1024.0 * 1024.0;

/// Bytes per unknown that do not grow with the mesh: mesh, element data, assembled matrix, vectors.
/// With [`FILL_BYTES_PER_UNKNOWN`], least squares on the peaks of the scale study of
/// docs/performance.md (`standard`, 8k to 182k unknowns, default ordering; `mixed-p1` agrees within
/// 10% with its density).
const BYTES_PER_UNKNOWN: f64 = 5.2e3;

/// Bytes per unknown of the sparse factor, times `n^(1/3)`: nested-dissection fill of a 3D
/// mesh grows as `n^(4/3)`.
const FILL_BYTES_PER_UNKNOWN: f64 = 185.0;

/// Bytes kept per step: its record and report (residuals of about 10 iterations).
pub const BYTES_PER_STEP: f64 = 2048.0;

/// How a scene's estimate was arrived at.
#[derive(Debug, Clone, PartialEq)]
pub struct Footprint {
    /// Element corners.
    pub vertices: f64,
    /// Elements.
    pub tets: f64,
    /// Unknowns of the linear systems (displacements and pressures).
    pub unknowns: f64,
    /// Bytes of the mesh, systems and factor.
    pub mesh_bytes: f64,
    /// Bytes of the per-step records.
    pub step_bytes: f64,
}

impl Footprint {
    /// The estimate for `scene`, or `None` when its mesh size is not known before reading
    /// (a mesh file whose header cannot be read: the reader reports why).
    pub fn of(scene: &Scene) -> Option<Footprint> {
        let (vertices, tets, file_nodes) = scene_counts(scene)?;
        let nodes = match (scene.element(), file_nodes) {
            // Every edge gets a node; a tet mesh has about `V + T` edges.
            (TetElement::Tet10, _) => file_nodes.unwrap_or(vertices) + vertices + tets,
            (TetElement::Tet4, Some(n)) => n,
            (TetElement::Tet4, None) => vertices,
        };
        let method = scene.method();
        let pressures = match method {
            Method::MixedP1 | Method::MixedP1Log => vertices,
            Method::MixedP0 | Method::MixedP0Log => tets,
            Method::Zonal => match scene.zones.as_ref().map(|z| z.kind) {
                Some(ZoneKind::KRing) => vertices,
                _ => scene.zones.as_ref().map_or(1.0, |z| z.paint.len() as f64),
            },
            Method::Standard | Method::Condensed | Method::Dual => 0.0,
        };
        let unknowns = 3.0 * nodes + pressures;
        let iterative = match scene.solver.linear_choice() {
            LinearName::Iterative => true,
            LinearName::Auto => unknowns > AUTO_DIRECT_UNKNOWNS as f64,
            LinearName::Direct => false,
        };
        let fill = if iterative {
            0.0
        } else {
            FILL_BYTES_PER_UNKNOWN * unknowns.cbrt()
        };
        let mesh_bytes = BASE_BYTES + density(method) * unknowns * (BYTES_PER_UNKNOWN + fill);
        Some(Footprint {
            vertices,
            tets,
            unknowns,
            mesh_bytes,
            step_bytes: BYTES_PER_STEP * scene.num_steps() as f64,
        })
    }

    /// The whole estimate in bytes.
    pub fn bytes(&self) -> f64 {
        self.mesh_bytes + self.step_bytes
    }
}

/// Peak memory per unknown relative to `standard`, measured on a cube at 14k-75k unknowns:
/// the pressure rows, the denser stiffness of the condensed and augmented terms, the zonal
/// Schur complement.
fn density(method: Method) -> f64 {
    match method {
        Method::Standard => 1.0,
        Method::MixedP0 | Method::MixedP0Log => 1.3,
        Method::MixedP1 | Method::MixedP1Log | Method::Zonal => 1.5,
        Method::Condensed | Method::Dual => 4.0,
    }
}

/// Every body's mesh with the prefix of its keys (`""` for `[mesh]`, `bodies.N.` else).
fn mesh_prefixes(scene: &Scene) -> impl Iterator<Item = (String, &MeshSpec)> {
    let own = scene.mesh.iter().map(|m| (String::new(), m));
    let bodies = scene.bodies.iter().enumerate();
    own.chain(bodies.map(|(i, b)| (format!("bodies.{i}."), &b.mesh)))
}

/// Vertices, tets and (for files) nodes of every body's mesh together.
fn scene_counts(scene: &Scene) -> Option<(f64, f64, Option<f64>)> {
    let mut total = (0.0, 0.0, None);
    for spec in scene.meshes() {
        let (vertices, tets, nodes) = mesh_counts(spec)?;
        total.0 += vertices;
        total.1 += tets;
        total.2 = match (total.2, nodes) {
            (None, None) => None,
            (a, b) => Some(a.unwrap_or(0.0) + b.unwrap_or(vertices)),
        };
    }
    Some(total)
}

/// Vertices, tets and (for a file) nodes of a mesh, from its generator's counts
/// ([`MeshSpec::counts`]) or a file's header.
fn mesh_counts(spec: &MeshSpec) -> Option<(f64, f64, Option<f64>)> {
    let (vertices, tets) = match spec {
        MeshSpec::File { path } => {
            let (nodes, elements) = file_counts(path)?;
            return Some((nodes, elements, Some(nodes)));
        }
        generator => generator.counts()?,
    };
    // Invalid parameters (a negative radius, ...) give NaN here: the generator says why.
    (vertices.is_finite() && tets.is_finite()).then_some((vertices, tets, None))
}

/// Node and element counts declared by a mesh file's headers, read without storing the file:
/// Gmsh `$Nodes`/`$Elements` (all elements, an upper bound on the tets), TetGen's `.node`
/// and `.ele` first lines, VTU's `<Piece>` attributes.
fn file_counts(path: &Path) -> Option<(f64, f64)> {
    let ext = path.extension()?.to_str()?.to_ascii_lowercase();
    match ext.as_str() {
        "msh" => gmsh_counts(BufReader::new(std::fs::File::open(path).ok()?)),
        "node" | "ele" => {
            let first = |ext: &str| {
                let file = std::fs::File::open(path.with_extension(ext)).ok()?;
                let line = BufReader::new(file)
                    .lines()
                    .map_while(Result::ok)
                    .map(|l| l.split('#').next().unwrap_or("").trim().to_string())
                    .find(|l| !l.is_empty())?;
                line.split_whitespace().next()?.parse::<f64>().ok()
            };
            Some((first("node")?, first("ele")?))
        }
        "vtu" => vtu_counts(std::fs::File::open(path).ok()?),
        _ => None,
    }
}

/// The longest line the Gmsh header scan reads (a node line is under 100 bytes): a longer
/// one ends the scan, so a file without newlines is never read into memory whole.
const MAX_SCANNED_LINE: u64 = 1 << 16;

/// The lines of `reader` while each is at most [`MAX_SCANNED_LINE`] bytes long.
fn bounded_lines(mut reader: impl BufRead) -> impl Iterator<Item = Vec<u8>> {
    std::iter::from_fn(move || {
        let mut line = Vec::new();
        let read = (&mut reader)
            .take(MAX_SCANNED_LINE + 1)
            .read_until(b'\n', &mut line)
            .ok()?;
        (read > 0 && read as u64 <= MAX_SCANNED_LINE).then_some(line)
    })
}

/// The counts after `$Nodes` and `$Elements` (format 2: the only number; 4.1: the second).
fn gmsh_counts(reader: impl BufRead) -> Option<(f64, f64)> {
    let mut lines = bounded_lines(reader);
    let mut counts = [None, None];
    while let Some(line) = lines.next() {
        let slot = match line.trim_ascii() {
            b"$Nodes" => 0,
            b"$Elements" => 1,
            _ => continue,
        };
        let header = lines.next()?;
        let fields: Vec<f64> = std::str::from_utf8(&header)
            .ok()?
            .split_whitespace()
            .map_while(|f| f.parse().ok())
            .collect();
        counts[slot] = match fields.as_slice() {
            [n] => Some(*n),
            [_, n, ..] => Some(*n),
            [] => None,
        };
        if let [Some(nodes), Some(elements)] = counts {
            return Some((nodes, elements));
        }
    }
    None
}

/// `NumberOfPoints` and `NumberOfCells` of the first `<Piece` within the first megabyte.
fn vtu_counts(file: impl Read) -> Option<(f64, f64)> {
    let mut head = Vec::new();
    file.take(1 << 20).read_to_end(&mut head).ok()?;
    let text = String::from_utf8_lossy(&head);
    let piece = &text[text.find("<Piece")?..];
    let piece = &piece[..piece.find('>')?];
    let attribute = |key: &str| -> Option<f64> {
        let rest = &piece[piece.find(&format!("{key}="))? + key.len() + 1..];
        let quote = rest.chars().next()?;
        rest[1..].split(quote).next()?.trim().parse().ok()
    };
    Some((attribute("NumberOfPoints")?, attribute("NumberOfCells")?))
}

/// The machine's memory in bytes (`MemTotal` of `/proc/meminfo`, else 8 GiB).
pub fn machine_memory() -> f64 {
    std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|info| {
            let line = info.lines().find(|l| l.starts_with("MemTotal:"))?;
            let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
            Some(kib * 1024.0)
        })
        .filter(|b| *b > 0.0)
        .unwrap_or(FALLBACK_MEMORY)
}

/// Checks the step counts against [`MAX_STEPS`].
pub fn check_steps(scene: &Scene, origin: &str) -> Result<(), SceneError> {
    let (key, count) = match scene.stepping {
        SteppingSpec::QuasiStatic { steps, .. } => ("stepping.steps", steps),
        SteppingSpec::Dynamic { frames, .. } => ("stepping.frames", frames),
    };
    for (key, value) in [(key, count), ("output.every", scene.output.every)] {
        if value > MAX_STEPS {
            return Err(SceneError::Invalid {
                origin: origin.to_string(),
                key: key.to_string(),
                message: format!(
                    "{value} is more than the limit of {MAX_STEPS} (a run keeps a record of every step)"
                ),
            });
        }
    }
    Ok(())
}

/// Refuses a scene whose estimated memory exceeds half of the machine's, naming the key
/// that drives the estimate.
pub fn check_memory(scene: &Scene, origin: &str) -> Result<(), SceneError> {
    let Some(footprint) = Footprint::of(scene) else {
        return Ok(());
    };
    let memory = machine_memory();
    let budget = BUDGET_FRACTION * memory;
    if footprint.bytes() <= budget {
        return Ok(());
    }
    let (key, what) = if footprint.step_bytes > footprint.mesh_bytes {
        let (key, name) = if scene.is_dynamic() {
            ("stepping.frames", "frames")
        } else {
            ("stepping.steps", "steps")
        };
        (
            key.to_string(),
            format!(
                "{name} = {} would keep ~{} of step records",
                scene.num_steps(),
                size(footprint.step_bytes)
            ),
        )
    } else {
        // The largest body's mesh is the one to shrink.
        let tets = |spec: &MeshSpec| mesh_counts(spec).map_or(0.0, |c| c.1);
        let (key, value) = mesh_prefixes(scene)
            .max_by(|a, b| tets(a.1).total_cmp(&tets(b.1)))
            .map(|(prefix, largest)| {
                let (key, value) = mesh_key(largest);
                (format!("{prefix}{key}"), value)
            })
            .unwrap_or_else(|| ("mesh".into(), "the scene's meshes".into()));
        (
            key,
            format!(
                "{value} would need ~{:.1e} tets and ~{:.1e} unknowns ({} {}), ~{} in all",
                footprint.tets,
                footprint.unknowns,
                scene.element().name(),
                scene.method().name(),
                size(footprint.bytes())
            ),
        )
    };
    Err(SceneError::Invalid {
        origin: origin.to_string(),
        key,
        message: format!(
            "{what} (estimate); this machine has {} of memory and a run may use half ({})",
            size(memory),
            size(budget)
        ),
    })
}

/// The key that sets a mesh's size, and its value as text.
fn mesh_key(spec: &MeshSpec) -> (&'static str, String) {
    match spec {
        MeshSpec::Box { res, cells, .. } if cells.iter().any(|&c| c > *res) => (
            "mesh.cells",
            format!("cells = {cells:?} (with res = {res})"),
        ),
        MeshSpec::Box { res, .. }
        | MeshSpec::Cylinder { res, .. }
        | MeshSpec::Puck { res, .. }
        | MeshSpec::Tube { res, .. }
        | MeshSpec::Ball { res, .. }
        | MeshSpec::Spine { res }
        | MeshSpec::Cushion { res }
        | MeshSpec::Bubble { res }
        | MeshSpec::Finger { res }
        | MeshSpec::Torso { res }
        | MeshSpec::Creature { res }
        | MeshSpec::Band { res, .. } => ("mesh.res", format!("res = {res}")),
        MeshSpec::Explicit { .. } => ("mesh.tets", "the explicit mesh".to_string()),
        MeshSpec::File { path } => ("mesh.path", format!("the mesh file {}", path.display())),
    }
}

/// Bytes for people: GiB below a TiB, else in powers of ten.
fn size(bytes: f64) -> String {
    if bytes < 1024.0 * GIB {
        format!("{:.1} GiB", bytes / GIB)
    } else {
        format!("{bytes:.1e} bytes")
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_gmsh_scan_stops_at_an_overlong_line() {
        let header = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n12\n";
        let elements = "$EndNodes\n$Elements\n34\n";
        let counts = |text: String| gmsh_counts(std::io::Cursor::new(text.into_bytes()));
        assert_eq!(counts(format!("{header}{elements}")), Some((12.0, 34.0)));
        let long = "1".repeat(MAX_SCANNED_LINE as usize + 1);
        assert_eq!(counts(format!("{header}{long}\n{elements}")), None);
    }

    use super::*;

    fn scene(sets: &[&str]) -> Scene {
        let overrides: Vec<_> = sets
            .iter()
            .map(|s| crate::format::Override::parse(s).unwrap())
            .collect();
        crate::format::load_scene("cantilever", None, &overrides).unwrap()
    }

    #[test]
    fn estimates_follow_the_generator_formulas() {
        // The cantilever: 8 x 2 x 2 cells at res 2.
        let f = Footprint::of(&scene(&[])).unwrap();
        assert_eq!((f.vertices, f.tets), (81.0, 192.0));
        assert_eq!(
            f.unknowns,
            3.0 * 81.0 + 81.0,
            "mixed-p1: one pressure per vertex"
        );
        assert!(f.bytes() < 64e6, "{f:?}");
        let f = Footprint::of(&scene(&["element=tet10", "method=standard"])).unwrap();
        assert_eq!(f.unknowns, 3.0 * (81.0 + 81.0 + 192.0));
        // A huge resolution is a finite estimate, not an overflow.
        let mut huge = scene(&[]);
        if let Some(MeshSpec::Box { res, .. }) = &mut huge.mesh {
            *res = usize::MAX;
        }
        let f = Footprint::of(&huge).unwrap();
        assert!(f.tets.is_finite() && f.tets > 1e57, "{f:?}");
        assert!(check_memory(&huge, "t").is_err());
    }

    /// The creature's counts are exact: they match its generated mesh.
    #[test]
    fn creature_counts_are_exact() {
        for res in [1, 2] {
            let (mesh, _) = isochor_mesh::generate::creature(res).unwrap();
            let counts = mesh_counts(&MeshSpec::Creature { res }).unwrap();
            let generated = (mesh.num_vertices() as f64, mesh.num_tets() as f64, None);
            assert_eq!(counts, generated);
        }
    }

    #[test]
    fn file_headers_are_counted_without_reading_the_mesh() {
        let gmsh2 =
            "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n5\n1 0 0 0\n$EndNodes\n$Elements\n7\n";
        assert_eq!(gmsh_counts(gmsh2.as_bytes()), Some((5.0, 7.0)));
        let gmsh4 = "$Nodes\n2 40 1 40\n$EndNodes\n$Elements\n3 90 1 90\n";
        assert_eq!(gmsh_counts(gmsh4.as_bytes()), Some((40.0, 90.0)));
        assert_eq!(gmsh_counts("garbage".as_bytes()), None);
        let vtu = r#"<VTKFile type="UnstructuredGrid"><UnstructuredGrid><Piece NumberOfPoints="12" NumberOfCells='3'>"#;
        assert_eq!(vtu_counts(vtu.as_bytes()), Some((12.0, 3.0)));
    }

    #[test]
    fn sizes_read_for_people() {
        assert_eq!(size(1.5 * GIB), "1.5 GiB");
        assert_eq!(size(2.5e20), "2.5e20 bytes");
        assert_eq!(size(3.5e14), "3.5e14 bytes");
        assert!(machine_memory() > 0.0);
    }
}
