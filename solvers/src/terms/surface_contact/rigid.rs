//! The meshed obstacles of a surface-contact term: their vertices follow the bodies' nodes in
//! the term's position vector (indices `num_nodes..`), placed at the level of the current
//! attempt; they are positions, not degrees of freedom.

use crate::problem::mesh_obstacle::MeshObstacle;
use crate::problem::schedule::LoadLevel;
use isochor_mesh::Vec3;
use std::borrow::Cow;
use std::sync::RwLock;

/// Where the obstacles stand: at the current attempt's level, and at the last accepted
/// step's (`None` until a step is accepted after a restore).
#[derive(Debug, Clone)]
struct Placement {
    current: Vec<Vec3>,
    accepted: Option<Vec<Vec3>>,
}

/// The meshed obstacles, their vertices numbered after the bodies' `num_nodes` nodes.
#[derive(Debug)]
pub(super) struct RigidSurfaces {
    obstacles: Vec<MeshObstacle>,
    /// The first position index of each obstacle, then the total.
    offsets: Vec<usize>,
    placement: RwLock<Placement>,
}

impl RigidSurfaces {
    /// The obstacles after `num_nodes` body nodes, placed at the start of the run.
    pub fn new(obstacles: Vec<MeshObstacle>, num_nodes: usize) -> Self {
        let mut offsets = vec![num_nodes];
        for o in &obstacles {
            offsets.push(offsets.last().copied().unwrap_or(num_nodes) + o.vertices.len());
        }
        let start = Self::place(&obstacles, &LoadLevel::quasi_static(0.0));
        RigidSurfaces {
            obstacles,
            offsets,
            placement: RwLock::new(Placement {
                current: start.clone(),
                accepted: Some(start),
            }),
        }
    }

    fn place(obstacles: &[MeshObstacle], level: &LoadLevel) -> Vec<Vec3> {
        obstacles.iter().flat_map(|o| o.placed(level)).collect()
    }

    /// Whether there is no obstacle.
    pub fn is_empty(&self) -> bool {
        self.obstacles.is_empty()
    }

    /// The obstacles.
    pub fn obstacles(&self) -> &[MeshObstacle] {
        &self.obstacles
    }

    /// The number of body nodes (the first obstacle vertex's index).
    pub fn num_nodes(&self) -> usize {
        self.offsets[0]
    }

    /// The position indices of obstacle `k`'s vertices.
    pub fn range(&self, k: usize) -> std::ops::Range<usize> {
        self.offsets[k]..self.offsets[k + 1]
    }

    /// Every obstacle triangle, in position indices.
    pub fn triangles(&self) -> Vec<[usize; 3]> {
        self.obstacles
            .iter()
            .zip(&self.offsets)
            .flat_map(|(o, &first)| o.triangles.iter().map(move |t| t.map(|v| v + first)))
            .collect()
    }

    /// The vertices at the start of the run, in order.
    pub fn start(&self) -> Vec<Vec3> {
        self.obstacles
            .iter()
            .flat_map(|o| o.vertices.iter().copied())
            .collect()
    }

    fn read(&self) -> std::sync::RwLockReadGuard<'_, Placement> {
        self.placement.read().unwrap_or_else(|e| e.into_inner())
    }

    fn write(&self) -> std::sync::RwLockWriteGuard<'_, Placement> {
        self.placement.write().unwrap_or_else(|e| e.into_inner())
    }

    /// The body nodes `x` followed by the obstacle vertices where they stand now (`x`
    /// itself without obstacles).
    pub fn extend<'a>(&self, x: &'a [Vec3]) -> Cow<'a, [Vec3]> {
        if self.is_empty() {
            return Cow::Borrowed(x);
        }
        Cow::Owned(x.iter().chain(&self.read().current).copied().collect())
    }

    /// Each obstacle's vertices where they stand now.
    pub fn current(&self) -> Vec<Vec<Vec3>> {
        let placement = self.read();
        let n = self.num_nodes();
        (0..self.obstacles.len())
            .map(|k| {
                let r = self.range(k);
                placement.current[r.start - n..r.end - n].to_vec()
            })
            .collect()
    }

    /// The motion of every vertex from where `level` places it to where it stands now.
    pub fn motion_since(&self, level: &LoadLevel) -> Vec<Vec3> {
        let then = Self::place(&self.obstacles, level);
        self.read()
            .current
            .iter()
            .zip(then)
            .map(|(now, then)| now - then)
            .collect()
    }

    /// Places the obstacles at `level` for an attempt; returns the placement the last
    /// accepted step left (if known) and the new one, for the check that the motion
    /// crosses no body.
    pub fn begin_attempt(&self, level: &LoadLevel) -> (Option<Vec<Vec3>>, Vec<Vec3>) {
        let new = Self::place(&self.obstacles, level);
        let mut placement = self.write();
        placement.current = new.clone();
        (placement.accepted.clone(), new)
    }

    /// Takes the current placement as the accepted step's.
    pub fn accept(&self) {
        let mut placement = self.write();
        placement.accepted = Some(placement.current.clone());
    }

    /// Forgets the accepted placement (a restored checkpoint): the next attempt's motion is
    /// not swept.
    pub fn forget(&self) {
        self.write().accepted = None;
    }
}
