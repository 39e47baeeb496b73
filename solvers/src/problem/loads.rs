//! What drives the body: prescribed motions of Dirichlet conditions, and external loads with
//! their schedules.

use super::schedule::Curve;
use isochor_mesh::Vec3;

/// How a Dirichlet-constrained vertex moves with its parameter `t`: the load parameter in
/// `[0, 1]` (quasi-static) or `time / duration` (dynamics), or the value of the condition's
/// [`Curve`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Motion {
    /// Held at the rest position.
    Fixed,
    /// Translated by `t * offset`.
    Translate(Vec3),
    /// Rotated by `t * angle` (radians) about `axis` through `center` (twisting).
    Rotate {
        /// A point on the axis.
        center: Vec3,
        /// The axis' direction (any length but zero).
        axis: Vec3,
        /// The angle at `t = 1`, in radians.
        angle: f64,
    },
    /// Scaled about `center` by `1 + t (factors - 1)` per axis (stretching).
    Scale {
        /// The fixed point of the scaling.
        center: Vec3,
        /// The scale factors along x, y and z at `t = 1`.
        factors: Vec3,
    },
}

impl Motion {
    /// Prescribed position at load parameter `t` of the vertex with rest position `rest`.
    pub fn position(&self, rest: &Vec3, t: f64) -> Vec3 {
        match *self {
            Motion::Fixed => *rest,
            Motion::Translate(offset) => rest + t * offset,
            Motion::Rotate {
                center,
                axis,
                angle,
            } => {
                let rotation = nalgebra::Rotation3::from_axis_angle(
                    &nalgebra::Unit::new_normalize(axis),
                    t * angle,
                );
                center + rotation * (rest - center)
            }
            Motion::Scale { center, factors } => {
                let s = Vec3::repeat(1.0) + t * (factors - Vec3::repeat(1.0));
                center + (rest - center).component_mul(&s)
            }
        }
    }
}

/// A Dirichlet condition: the listed components of the listed nodes follow `motion`.
#[derive(Debug, Clone, PartialEq)]
pub struct Dirichlet {
    /// Node indices (on a 10-node mesh, include the mid-edge nodes of the held region).
    pub nodes: Vec<usize>,
    /// Which components (x, y, z) are prescribed.
    pub axes: [bool; 3],
    /// How they move.
    pub motion: Motion,
    /// The motion's parameter as a function of the load parameter or time (`None`: the
    /// fraction of the run).
    pub curve: Option<Curve>,
}

/// An external load at full scale; a [`ScheduledLoad`] says how it is scaled over the run.
#[derive(Debug, Clone, PartialEq)]
pub enum Load {
    /// Body force `rho g` per unit rest volume, as consistent nodal forces.
    Gravity(Vec3),
    /// Dead traction (force per unit rest area) on boundary faces, given by their corner
    /// triangles (on a 10-node mesh, the 6-node faces over them are loaded).
    Traction {
        /// The loaded boundary faces, by their corner vertices.
        faces: Vec<[usize; 3]>,
        /// Force per unit rest area.
        traction: Vec3,
    },
    /// Follower pressure on boundary faces, oriented with the body's outward normal: a
    /// positive pressure pushes the faces into the body, so listing the faces that line a
    /// chamber inflates it.
    Pressure {
        /// The loaded boundary faces, by their corner vertices; they must close a surface or
        /// have their rim held by Dirichlet conditions.
        faces: Vec<[usize; 3]>,
        /// Pressure, force per unit deformed area.
        pressure: f64,
        /// The point the enclosed volume is measured about (its potential is the cone volume
        /// of the faces about it, see [`crate::terms::EnclosedVolume`]): any point for a
        /// closed surface, a point on the symmetry planes of a cut one.
        origin: Vec3,
        /// Whether each boundary loop of the faces (a chamber's opening) is capped by the fan
        /// from its centroid ([`crate::terms::Openings`]).
        cap_openings: bool,
    },
    /// A cavity held at a volume: the faces of a [`Load::Pressure`], its enclosed volume
    /// about `origin` held at `1 + (volume_ratio - 1) s` times the rest volume (`s` the load
    /// scale), the pressure the unknown multiplier of that constraint (positive inflates).
    Cavity {
        /// The faces lining the cavity, by their corner vertices, with the body's outward
        /// orientation; closed, or closed by symmetry planes through `origin`.
        faces: Vec<[usize; 3]>,
        /// The cavity's volume over its rest volume at full load.
        volume_ratio: f64,
        /// The point the enclosed volume is measured about.
        origin: Vec3,
        /// Whether each boundary loop of the faces is capped by the fan from its centroid.
        cap_openings: bool,
    },
}

/// A load and its scale over the run.
#[derive(Debug, Clone, PartialEq)]
pub struct ScheduledLoad {
    /// The load at scale 1.
    pub load: Load,
    /// Its scale as a function of the load parameter or time (`None`: ramped with the load
    /// parameter in quasi-static stepping, constant in dynamics).
    pub curve: Option<Curve>,
}

impl From<Load> for ScheduledLoad {
    fn from(load: Load) -> Self {
        ScheduledLoad { load, curve: None }
    }
}
