//! VTU frames and their `.pvd` collection, through the mesh crate's writers.
//!
//! The frames' points are the rest positions (ParaView's Warp By Vector on `displacement`
//! shows the deformed body), or with `output.points = "deformed"` the deformed positions.
//!
//! Point data: `displacement`, `velocity` (dynamics), `contact_force` (with obstacles),
//! `pressure` (the nodal pressure unknowns of `mixed-p1`, `mixed-p1-log` and `dual`,
//! compression positive: minus the multipliers `p = kappa (J - 1)` of the papers, linear in
//! each element). Cell data at each element's centroid: `stress` (the Cauchy tensor, 9
//! components, tension positive), `mean_stress` (`tr(sigma)/3`, tension positive: the
//! hydrostatic pressure in the usual sense is `-mean_stress`), `von_mises`, `J`, `region` (0:
//! the body's material, `i`: the scene's `i`-th region), `zone` (zonal method).
//!
//! Each meshed obstacle's placed surface, then each cloth body's deformed surface, is written
//! beside each frame as a `.vtp` of triangles, listed in the `.pvd` as a further part of the
//! frame's time (the cloth's nodes are also points of the `.vtu`, in no cell).

use crate::error::SceneError;
use isochor_mesh::io::{
    write_pvd, write_pvd_parts, write_vtp_triangles, write_vtu_elements, Field, VtuEncoding,
};
use isochor_mesh::{ElementMesh, MeshError, Vec3};
use isochor_solvers::ClothSheet;
use nalgebra::Matrix3;
use std::path::{Path, PathBuf};

/// The fields of one frame; the optional ones are left out of the file when empty.
#[derive(Debug, Clone, Copy)]
pub struct FrameFields<'a> {
    /// Node positions.
    pub positions: &'a [Vec3],
    /// Node velocities (dynamics; empty in quasi-static stepping).
    pub velocities: &'a [Vec3],
    /// Von Mises stress per element (optional).
    pub von_mises: &'a [f64],
    /// Cauchy stress per element (optional).
    pub stress: &'a [Matrix3<f64>],
    /// The P1 multiplier field at every node, tension positive (optional).
    pub nodal_pressures: &'a [f64],
    /// Contact force per node (optional).
    pub contact_forces: &'a [Vec3],
    /// Where each meshed obstacle's vertices stand (empty: no obstacle surface written).
    pub obstacle_positions: &'a [Vec<Vec3>],
}

impl<'a> FrameFields<'a> {
    /// The rest state of `mesh`: its nodes, nothing else.
    pub fn rest(mesh: &'a ElementMesh) -> Self {
        FrameFields {
            positions: mesh.nodes(),
            velocities: &[],
            von_mises: &[],
            stress: &[],
            nodal_pressures: &[],
            contact_forces: &[],
            obstacle_positions: &[],
        }
    }

    /// Node displacements from the rest positions of `mesh`.
    pub fn displacements(&self, mesh: &ElementMesh) -> Vec<Vec3> {
        self.positions
            .iter()
            .zip(mesh.nodes())
            .map(|(x, r)| x - r)
            .collect()
    }

    /// Deformed over rest volume of every element (`J`).
    pub fn volume_ratios(&self, mesh: &ElementMesh) -> Vec<f64> {
        mesh.volumes_at(self.positions)
            .iter()
            .zip(mesh.volumes_at(mesh.nodes()))
            .map(|(v, v0)| v / v0)
            .collect()
    }

    /// The mean stress `tr(sigma)/3` per element (tension positive), zeros if there is no
    /// stress (the rest state).
    pub fn mean_stresses(&self, mesh: &ElementMesh) -> Vec<f64> {
        let mean: Vec<f64> = self.stress.iter().map(|s| s.trace() / 3.0).collect();
        or_zeros(&mean, mesh.num_elements())
    }

    /// The von Mises stress per element, zeros if there is none (the rest state).
    pub fn von_mises_or_zeros(&self, mesh: &ElementMesh) -> Vec<f64> {
        or_zeros(self.von_mises, mesh.num_elements())
    }
}

/// `values` if there is one per element, else zeros.
fn or_zeros(values: &[f64], elements: usize) -> Vec<f64> {
    if values.len() == elements {
        values.to_vec()
    } else {
        vec![0.0; elements]
    }
}

/// Writes every `every`-th frame (and always the last) into a folder.
#[derive(Debug)]
pub struct FrameWriter {
    dir: PathBuf,
    stem: String,
    every: usize,
    encoding: VtuEncoding,
    zone_ids: Option<Vec<i32>>,
    region_ids: Vec<i32>,
    body_ids: Option<Vec<i32>>,
    deformed_points: bool,
    /// The meshed obstacles' names and triangles.
    obstacles: Vec<(String, Vec<[usize; 3]>)>,
    /// The cloths' names, first vertices and triangles over the vertices from there.
    cloths: Vec<(String, std::ops::Range<usize>, Vec<[usize; 3]>)>,
    entries: Vec<(f64, String)>,
}

impl FrameWriter {
    /// A writer into `dir` naming files `STEM_00012.vtu` and `STEM.pvd`, in `encoding`;
    /// `zone_ids` is the first zone of each tet (or `None` without zones), `region_ids` the
    /// region of each tet.
    pub fn new(
        dir: &Path,
        stem: &str,
        every: usize,
        encoding: VtuEncoding,
        zone_ids: Option<Vec<i32>>,
        region_ids: Vec<i32>,
    ) -> Self {
        FrameWriter {
            dir: dir.to_path_buf(),
            stem: stem.to_string(),
            every: every.max(1),
            encoding,
            zone_ids,
            region_ids,
            body_ids: None,
            deformed_points: false,
            obstacles: Vec::new(),
            cloths: Vec::new(),
            entries: Vec::new(),
        }
    }

    /// Writes each meshed obstacle's placed surface (`names[k]`, `triangles[k]`) beside
    /// every frame, as `STEM_00012_NAME.vtp`, listed in the `.pvd` as parts 1, 2, ... of the
    /// frame's time (the body is part 0).
    pub fn with_obstacles(mut self, obstacles: Vec<(String, Vec<[usize; 3]>)>) -> Self {
        self.obstacles = obstacles;
        self
    }

    /// Writes each cloth sheet's deformed surface beside every frame, as
    /// `STEM_00012_NAME.vtp`, listed in the `.pvd` after the meshed obstacles.
    pub fn with_cloths(mut self, sheets: &[ClothSheet]) -> Self {
        self.cloths = sheets
            .iter()
            .map(|sheet| {
                let corners = sheet.triangles.iter().flatten();
                let first = corners.clone().copied().min().unwrap_or(0);
                let end = corners.copied().max().map_or(first, |v| v + 1);
                let local = sheet.triangles.iter().map(|t| t.map(|v| v - first));
                (sheet.name.clone(), first..end, local.collect())
            })
            .collect();
        self
    }

    /// The names of the surfaces written beside each frame: the obstacles', the cloths'.
    fn surface_names(&self) -> impl Iterator<Item = &str> {
        let obstacles = self.obstacles.iter().map(|o| o.0.as_str());
        obstacles.chain(self.cloths.iter().map(|c| c.0.as_str()))
    }

    /// The file of surface `k` ([`FrameWriter::surface_names`]) beside the frame file
    /// `frame`.
    fn surface_file(&self, frame: &str, k: usize) -> String {
        let name: String = self
            .surface_names()
            .nth(k)
            .unwrap_or_default()
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '-' {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        format!("{}_{name}.vtp", frame.trim_end_matches(".vtu"))
    }

    /// Writes the body of each tet as the cell field `body` (a scene of several bodies).
    pub fn with_bodies(mut self, body_ids: Option<Vec<i32>>) -> Self {
        self.body_ids = body_ids;
        self
    }

    /// Writes the deformed positions as the frames' points instead of the rest positions.
    pub fn with_deformed_points(mut self, deformed: bool) -> Self {
        self.deformed_points = deformed;
        self
    }

    /// Whether frame `index` of `total` is written.
    pub fn wants(&self, index: usize, total: usize) -> bool {
        index % self.every == 0 || index == total
    }

    /// Writes frame `index` at time or load `t` (0 is the rest state): the rest (or
    /// deformed) points with the fields of `fields`. 10-node meshes are written as VTK
    /// quadratic tetrahedra, which ParaView draws curved.
    pub fn write(
        &mut self,
        mesh: &ElementMesh,
        index: usize,
        t: f64,
        fields: &FrameFields<'_>,
    ) -> Result<(), SceneError> {
        let FrameFields {
            positions,
            velocities,
            von_mises,
            stress,
            nodal_pressures,
            contact_forces,
            ..
        } = *fields;
        let n = mesh.num_elements();
        let displacement = fields.displacements(mesh);
        let j = fields.volume_ratios(mesh);
        let mut cells = vec![
            Field::scalar("mean_stress", fields.mean_stresses(mesh)),
            Field::scalar("J", j),
        ];
        if stress.len() == n {
            cells.push(Field::tensor("stress", stress.to_vec()));
        }
        if von_mises.len() == n {
            cells.push(Field::scalar("von_mises", von_mises.to_vec()));
        }
        if self.region_ids.len() == n {
            cells.push(Field::int("region", self.region_ids.clone()));
        }
        if let Some(z) = &self.zone_ids {
            cells.push(Field::int("zone", z.clone()));
        }
        if let Some(b) = self.body_ids.as_ref().filter(|b| b.len() == n) {
            cells.push(Field::int("body", b.clone()));
        }
        let mut points = vec![Field::vector("displacement", displacement)];
        if velocities.len() == positions.len() {
            points.push(Field::vector("velocity", velocities.to_vec()));
        }
        if nodal_pressures.len() == positions.len() {
            let pressure = nodal_pressures.iter().map(|p| -p).collect();
            points.push(Field::scalar("pressure", pressure));
        }
        if contact_forces.len() == positions.len() {
            points.push(Field::vector("contact_force", contact_forces.to_vec()));
        }
        let name = format!("{}_{index:05}.vtu", self.stem);
        let points_at = if self.deformed_points {
            positions
        } else {
            mesh.nodes()
        };
        write_vtu_elements(
            self.dir.join(&name),
            points_at,
            mesh.kind(),
            mesh.connectivity(),
            &points,
            &cells,
            self.encoding,
        )
        .map_err(written)?;
        for (k, placed) in fields
            .obstacle_positions
            .iter()
            .enumerate()
            .take(self.obstacles.len())
        {
            let file = self.surface_file(&name, k);
            write_vtp_triangles(self.dir.join(file), placed, &self.obstacles[k].1)
                .map_err(written)?;
        }
        for (k, (_, vertices, triangles)) in self.cloths.iter().enumerate() {
            let file = self.surface_file(&name, self.obstacles.len() + k);
            write_vtp_triangles(self.dir.join(file), &positions[vertices.clone()], triangles)
                .map_err(written)?;
        }
        self.entries.push((t, name));
        Ok(())
    }

    /// The frames written so far: time or load parameter, file name.
    pub fn entries(&self) -> &[(f64, String)] {
        &self.entries
    }

    /// Continues a resumed run whose frames so far are `entries` (later files are rewritten).
    pub fn continue_after(&mut self, entries: Vec<(f64, String)>) {
        self.entries = entries;
    }

    /// Writes the `.pvd` collection of the frames written so far.
    pub fn finish(&self) -> Result<(), SceneError> {
        let path = self.dir.join(format!("{}.pvd", self.stem));
        let surfaces = self.obstacles.len() + self.cloths.len();
        if surfaces == 0 {
            return write_pvd(path, &self.entries).map_err(written);
        }
        let parts: Vec<(f64, usize, String)> = self
            .entries
            .iter()
            .flat_map(|(t, frame)| {
                std::iter::once((*t, 0, frame.clone()))
                    .chain((0..surfaces).map(|k| (*t, k + 1, self.surface_file(frame, k))))
            })
            .collect();
        write_pvd_parts(path, &parts).map_err(written)
    }
}

/// The error of writing an output file: an I/O error (a full disk) as the file's, not the
/// mesh's.
fn written(e: MeshError) -> SceneError {
    match e {
        MeshError::Io { path, source } => SceneError::io(path, source),
        other => SceneError::Mesh(other),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Before: a full disk while writing a frame said "mesh: ...: No space left on device".
    #[test]
    fn a_full_disk_is_the_output_files_error_not_the_meshs() {
        let full = std::io::Error::from(std::io::ErrorKind::StorageFull);
        let e = written(MeshError::io(Path::new("out/frame_00001.vtu"), full)).to_string();
        assert!(e.starts_with("out/frame_00001.vtu: "), "{e}");
        assert!(!e.contains("mesh"), "{e}");
    }
}
