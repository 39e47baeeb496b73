//! `isochor check`: a scene validated and described before it runs. The scene is built as
//! `run` builds it (mesh, selections, regions, supports, obstacles, the solver's model), then
//! each selection's size and each region's volume are reported, and optionally a VTU of the
//! rest mesh shows the selections and regions.

use crate::error::SceneError;
use crate::format::Scene;
use crate::resolve::{self, ResolvedScene};
use isochor_mesh::io::{write_vtu_elements, Field, VtuEncoding};
use isochor_solvers::Simulation;
use std::fmt::Write as _;
use std::path::Path;

/// What a named selection selects on the scene's mesh: a count, or why it selects nothing
/// of that kind.
#[derive(Debug, Clone, PartialEq)]
pub struct SelectionSize {
    /// The selection's name.
    pub name: String,
    /// Vertices (a Dirichlet condition or probe holds these).
    pub vertices: Result<usize, String>,
    /// Boundary faces (a traction or pressure acts on these).
    pub faces: Result<usize, String>,
    /// Tets (a region or zone is made of these).
    pub tets: Result<usize, String>,
}

/// A region of the body: its name, elements, rest volume and material.
#[derive(Debug, Clone, PartialEq)]
pub struct RegionSize {
    /// `body` for the elements no region claims, else the region's name.
    pub name: String,
    /// Its elements.
    pub tets: usize,
    /// Its rest volume.
    pub volume: f64,
    /// Young's modulus and Poisson's ratio of its material.
    pub young: f64,
    /// Poisson's ratio.
    pub nu: f64,
}

/// The description of a valid scene.
#[derive(Debug, Clone, PartialEq)]
pub struct CheckReport {
    /// The scene's name.
    pub scene: String,
    /// Nodes of the mesh.
    pub nodes: usize,
    /// Elements of the mesh.
    pub tets: usize,
    /// Rest volume of the mesh.
    pub volume: f64,
    /// Every named selection.
    pub selections: Vec<SelectionSize>,
    /// The body's material and every region.
    pub regions: Vec<RegionSize>,
}

/// Builds `scene` as a run would (every error a run would meet before its first step is
/// returned) and describes it; with `vtu`, writes the rest mesh with one `Int32` point field
/// per selection (1 on its vertices) and the cell fields `region` and `sel_NAME` (1 on the
/// selection's tets).
pub fn check_scene(scene: &Scene, vtu: Option<&Path>) -> Result<CheckReport, SceneError> {
    let ResolvedScene {
        problem,
        settings,
        selections,
        ..
    } = resolve::build(scene)?;
    let mesh = problem.mesh.clone();
    let simulation = Simulation::new(problem, settings)?;
    let volumes = mesh.volumes_at(mesh.nodes());
    let regions = simulation.regions();
    let mut sizes: Vec<RegionSize> = regions
        .names()
        .iter()
        .zip(regions.materials())
        .map(|(name, m)| RegionSize {
            name: name.clone(),
            tets: 0,
            volume: 0.0,
            young: m.young(),
            nu: m.nu,
        })
        .collect();
    for (&r, v) in regions.element_regions().iter().zip(&volumes) {
        sizes[r].tets += 1;
        sizes[r].volume += v;
    }
    let mut report = CheckReport {
        scene: scene.name.clone(),
        nodes: mesh.num_nodes(),
        tets: mesh.num_elements(),
        volume: volumes.iter().sum(),
        selections: Vec::new(),
        regions: sizes,
    };
    let mut points = Vec::new();
    let mut cells = vec![Field::int(
        "region",
        regions
            .element_regions()
            .iter()
            .map(|&r| r as i32)
            .collect(),
    )];
    for name in scene.selections.keys() {
        let vertices = selections.nodes(name);
        let tets = selections.tets(name);
        if let Ok(v) = &vertices {
            let mut flag = vec![0; mesh.num_nodes()];
            v.iter().for_each(|&i| flag[i] = 1);
            points.push(Field::int(format!("sel_{name}"), flag));
        }
        if let Ok(t) = &tets {
            let mut flag = vec![0; mesh.num_elements()];
            t.iter().for_each(|&e| flag[e] = 1);
            cells.push(Field::int(format!("sel_{name}"), flag));
        }
        report.selections.push(SelectionSize {
            name: name.clone(),
            vertices: count(vertices),
            faces: count(selections.faces(name)),
            tets: count(tets),
        });
    }
    if let Some(path) = vtu {
        write_vtu_elements(
            path,
            mesh.nodes(),
            mesh.kind(),
            mesh.connectivity(),
            &points,
            &cells,
            VtuEncoding::Ascii,
        )?;
    }
    Ok(report)
}

/// The length of a selection, or why it is empty.
fn count<T>(selected: Result<&[T], SceneError>) -> Result<usize, String> {
    selected.map(|v| v.len()).map_err(|e| e.to_string())
}

impl CheckReport {
    /// The report for people: the mesh, a table of selections and one of regions.
    pub fn to_text(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "scene {}: valid\nmesh  {} nodes, {} tets, volume {:.6e}",
            self.scene, self.nodes, self.tets, self.volume
        );
        let cell = |r: &Result<usize, String>| match r {
            Ok(n) => n.to_string(),
            Err(_) => "-".to_string(),
        };
        if !self.selections.is_empty() {
            let _ = writeln!(
                s,
                "\n{:<20} {:>9} {:>9} {:>9}",
                "selection", "vertices", "faces", "tets"
            );
            for sel in &self.selections {
                let _ = writeln!(
                    s,
                    "{:<20} {:>9} {:>9} {:>9}",
                    sel.name,
                    cell(&sel.vertices),
                    cell(&sel.faces),
                    cell(&sel.tets)
                );
            }
        }
        let _ = writeln!(
            s,
            "\n{:<20} {:>9} {:>13} {:>11} {:>8}",
            "region", "tets", "volume", "E", "nu"
        );
        for r in &self.regions {
            let _ = writeln!(
                s,
                "{:<20} {:>9} {:>13.6e} {:>11.4e} {:>8}",
                r.name, r.tets, r.volume, r.young, r.nu
            );
        }
        s
    }
}
