//! `[mesh]`: where the mesh comes from (a generator with its parameters, or a file).

use super::common::one;
use super::common::Vector;
use isochor_mesh::io::PhysicalGroups;
use isochor_mesh::{generate, MeshError, TetMesh, Vec3};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::PathBuf;

/// Where the mesh comes from.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(tag = "generator", rename_all = "kebab-case", deny_unknown_fields)]
pub enum MeshSpec {
    /// A box `[min, max]` with `res * cells` hexes per axis, Kuhn-split into 6 tets each.
    Box {
        /// Lower corner.
        min: Vector,
        /// Upper corner.
        max: Vector,
        /// Resolution multiplier.
        res: usize,
        /// Cells per axis per unit of `res` (default `[1, 1, 1]`).
        #[serde(default = "ones")]
        cells: [usize; 3],
        /// `res` must be a multiple of this (so that load patches fall on grid lines).
        #[serde(default = "one")]
        res_multiple_of: usize,
    },
    /// A solid cylinder about the z axis from `z = 0` to `height`.
    Cylinder {
        /// Radius.
        radius: f64,
        /// Height.
        height: f64,
        /// Resolution: cells across the radius.
        res: usize,
    },
    /// A puck (short cylinder with at least `res` layers).
    Puck {
        /// Radius.
        radius: f64,
        /// Height.
        height: f64,
        /// Resolution: cells across the radius (and at least this many layers).
        res: usize,
    },
    /// A thick-walled tube about the z axis from `z = 0` to `height`.
    Tube {
        /// Inner radius.
        inner_radius: f64,
        /// Outer radius.
        outer_radius: f64,
        /// Height.
        height: f64,
        /// Resolution: cells across the wall.
        res: usize,
    },
    /// A ball centred at `center`.
    Ball {
        /// Radius.
        radius: f64,
        /// Resolution: cells across the radius.
        res: usize,
        /// Centre (default the origin).
        #[serde(default)]
        center: Vector,
    },
    /// The spine arm of Francu et al. 2021: a 0.25 x 0.03 x 0.03 m bar along x with five
    /// square through-holes (`isochor_mesh::generate::spine_arm`, `1260 res^3` tets).
    Spine {
        /// Resolution: cells per centimetre.
        res: usize,
    },
    /// The "cushion" of Francu et al. 2021, Fig. 6 (shape ours): a 40 x 40 x 13 mm pad with a
    /// closed 30 x 30 x 4 mm chamber (`isochor_mesh::generate::cushion`, `768 res^3` tets),
    /// groups `base`, `chamber`, `top`.
    Cushion {
        /// Resolution: cells across the thinnest wall.
        res: usize,
    },
    /// The "bubble" of Francu et al. 2021, Fig. 6 (shape ours): a 40 x 40 x 15 mm block with a
    /// closed 30 x 30 x 6 mm chamber under a 3 mm membrane (`isochor_mesh::generate::bubble`,
    /// `552 res^3` tets), groups `base`, `chamber`, `membrane`.
    Bubble {
        /// Resolution: cells across the membrane.
        res: usize,
    },
    /// The "finger" of Francu et al. 2021, Fig. 6 (shape ours): a 64 x 10 x 16 mm PneuNet-style
    /// bender with five chambers joined by a channel above a strain-limiting base
    /// (`isochor_mesh::generate::finger`, `1494 res^3` tets), groups `base`, `chamber`, `tip`.
    Finger {
        /// Resolution: cells across a chamber wall.
        res: usize,
    },
    /// A torso on the tops of two legs (Sheen et al. 2021, Figs. 1 and 4; shape ours): 0.34 m
    /// wide at the hips, 0.45 m tall, the waist at z = 0.34 m, rounded sections
    /// (`isochor_mesh::generate::torso`, `2016 res^3` tets), groups `legs` (the legs' cut
    /// faces, z = 0) and `top` (the cut at the chest).
    Torso {
        /// Resolution: cells about 4 cm wide at 1 (8 res across the hips), 2 cm high at the
        /// waist.
        res: usize,
    },
    /// A creature-like body standing in for the armadillo of Sheen et al. 2021, sec. 8.7
    /// (shape ours): a 160 x 80 x 50 mm torso on four legs, a thin neck and a head, 260 mm
    /// long (`isochor_mesh::generate::creature`, `942 res^3` tets), group `feet`.
    Creature {
        /// Resolution: cells across the neck.
        res: usize,
    },
    /// A band, the mesh of a cloth body only (`kind = "cloth"`): an open cylindrical triangle
    /// surface of `radius` about the z axis from `z = 0` to `z = width`, `res` cells across
    /// its width and about as many per width around (`isochor_mesh::generate::band`); the
    /// body's `place` moves it.
    Band {
        /// Radius (m).
        radius: f64,
        /// Width along the axis (m).
        width: f64,
        /// Resolution: cells across the width.
        res: usize,
    },
    /// Explicit nodes and tets (small test scenes such as Fig. 2 of Sheen et al., and the
    /// arrays of `isochor.Problem` in Python), with named groups of their faces and tets.
    Explicit {
        /// Node positions: every node a tet's, the corners before the mid-edge nodes (the
        /// numbering `vertices` and the groups refer to).
        positions: Vec<Vector>,
        /// Tets, as 4 corner indices each, or 10 (the corners, then the mid-edge nodes in
        /// Gmsh's order), all alike.
        tets: Vec<Vec<usize>>,
        /// Named groups for the selections' `physical` key.
        #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
        groups: BTreeMap<String, GroupSpec>,
    },
    /// A mesh file: Gmsh `.msh`, TetGen `.node`/`.ele` (either name), or `.vtu`. A relative
    /// path is resolved against the scene file's folder (or the working directory).
    File {
        /// The file.
        path: PathBuf,
    },
}

/// A named group of an explicit mesh: boundary triangles (a surface group) or tets (a
/// volume group), exactly one of the two.
#[derive(Debug, Clone, PartialEq, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct GroupSpec {
    /// Triangles, as three corner indices each.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub faces: Vec<[usize; 3]>,
    /// Tet indices.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub tets: Vec<usize>,
}

/// The true surface of a curved generator: the mid-edge node of a boundary edge on a curved
/// wall (see `isochor_mesh::generate::cylinder_surface`).
pub type Surface = Box<dyn Fn(&Vec3, &Vec3) -> Option<Vec3>>;

/// A generated mesh: its tets, the groups the generator names, its true surface if curved.
pub struct Generated {
    /// The 4-node mesh.
    pub mesh: TetMesh,
    /// The named groups of faces, for the generators that name some.
    pub groups: Option<PhysicalGroups>,
    /// The curved surface 10-node tets follow.
    pub surface: Option<Surface>,
}

impl Generated {
    fn plain(mesh: TetMesh) -> Generated {
        Generated {
            mesh,
            groups: None,
            surface: None,
        }
    }

    fn curved(mesh: TetMesh, surface: Surface) -> Generated {
        Generated {
            mesh,
            groups: None,
            surface: Some(surface),
        }
    }

    fn grouped((mesh, groups): (TetMesh, PhysicalGroups)) -> Generated {
        Generated {
            mesh,
            groups: Some(groups),
            surface: None,
        }
    }
}

impl MeshSpec {
    /// The mesh of a generator; a mesh file is read and an explicit mesh taken as it is, not
    /// generated (an error here).
    pub fn generate(&self) -> Result<Generated, MeshError> {
        match self {
            MeshSpec::Box {
                min,
                max,
                res,
                cells,
                ..
            } => generate::box_grid(vec3(*min), vec3(*max), cells.map(|c| c * res))
                .map(Generated::plain),
            MeshSpec::Cylinder {
                radius,
                height,
                res,
            } => generate::cylinder(*radius, *height, *res)
                .map(|m| Generated::curved(m, Box::new(generate::cylinder_surface(*radius)))),
            MeshSpec::Puck {
                radius,
                height,
                res,
            } => generate::puck(*radius, *height, *res)
                .map(|m| Generated::curved(m, Box::new(generate::cylinder_surface(*radius)))),
            MeshSpec::Tube {
                inner_radius,
                outer_radius,
                height,
                res,
            } => generate::tube(*inner_radius, *outer_radius, *height, *res).map(|t| {
                let surface = generate::tube_surface(*inner_radius, *outer_radius);
                Generated::curved(t.mesh, Box::new(surface))
            }),
            MeshSpec::Ball {
                radius,
                res,
                center,
            } => generate::ball(*radius, *res).and_then(|ball| {
                let c = vec3(*center);
                let moved = ball.positions().iter().map(|x| x + c).collect();
                let sphere = generate::ball_surface(*radius);
                Ok(Generated::curved(
                    TetMesh::new(moved, ball.tets().to_vec())?,
                    Box::new(move |a: &Vec3, b: &Vec3| sphere(&(a - c), &(b - c)).map(|p| p + c)),
                ))
            }),
            MeshSpec::Spine { res } => generate::spine_arm(*res).map(Generated::grouped),
            MeshSpec::Cushion { res } => generate::cushion(*res).map(Generated::grouped),
            MeshSpec::Bubble { res } => generate::bubble(*res).map(Generated::grouped),
            MeshSpec::Finger { res } => generate::finger(*res).map(Generated::grouped),
            MeshSpec::Torso { res } => generate::torso(*res).map(Generated::grouped),
            MeshSpec::Creature { res } => generate::creature(*res).map(Generated::grouped),
            MeshSpec::Band { .. } => Err(MeshError::parameter(
                "generator",
                "band",
                "a band is a cloth surface, the mesh of a body of kind = \"cloth\"",
            )),
            MeshSpec::Explicit { .. } => Err(MeshError::parameter(
                "generator",
                "explicit",
                "an explicit mesh is taken as it is, not generated",
            )),
            MeshSpec::File { path } => Err(MeshError::parameter(
                "generator",
                format!("file ({})", path.display()),
                "a mesh file is read, not generated",
            )),
        }
    }

    /// The vertex and tet counts of [`MeshSpec::generate`]'s mesh, from the generator's
    /// formula without generating (NaN for parameters the generator refuses); `None` for a
    /// mesh file.
    pub fn counts(&self) -> Option<(f64, f64)> {
        Some(match self {
            MeshSpec::Box { res, cells, .. } => {
                generate::box_grid_counts(cells.map(|c| c as f64 * *res as f64))
            }
            MeshSpec::Cylinder {
                radius,
                height,
                res,
            } => generate::cylinder_counts(*radius, *height, *res, false),
            MeshSpec::Puck {
                radius,
                height,
                res,
            } => generate::cylinder_counts(*radius, *height, *res, true),
            MeshSpec::Tube {
                inner_radius,
                outer_radius,
                height,
                res,
            } => generate::tube_counts(*inner_radius, *outer_radius, *height, *res),
            MeshSpec::Ball { res, .. } => generate::ball_counts(*res),
            MeshSpec::Spine { res } => generate::spine_arm_counts(*res),
            MeshSpec::Cushion { res } => generate::cushion_counts(*res),
            MeshSpec::Bubble { res } => generate::bubble_counts(*res),
            MeshSpec::Finger { res } => generate::finger_counts(*res),
            MeshSpec::Torso { res } => generate::torso_counts(*res),
            MeshSpec::Creature { res } => generate::creature_counts(*res),
            MeshSpec::Band { radius, width, res } => {
                (generate::band_counts(*radius, *width, *res).0, 0.0)
            }
            MeshSpec::Explicit {
                positions, tets, ..
            } => (positions.len() as f64, tets.len() as f64),
            MeshSpec::File { .. } => return None,
        })
    }
}

fn vec3(a: [f64; 3]) -> Vec3 {
    Vec3::new(a[0], a[1], a[2])
}

fn ones() -> [usize; 3] {
    [1, 1, 1]
}
