//! The zones of a scene's `[zones]` on its mesh.

use super::bodies::SceneBodies;
use super::selections::Selections;
use crate::error::SceneError;
use crate::format::{Scene, ZoneKind};
use isochor_mesh::{TetMesh, Zones};

/// Whether a run of `scene` needs its zones: the zonal method constrains them, and a
/// `zone-volume-change` probe measures them whatever the method.
pub fn needed(scene: &Scene) -> bool {
    scene.method() == isochor_solvers::Method::Zonal
        || scene
            .probes
            .values()
            .any(|p| matches!(p, crate::format::ProbeSpec::ZoneVolumeChange { .. }))
}

/// The zones of the scene's `[zones]` on `mesh` (if absent, one global zone per body: each
/// body keeps its own volume).
pub fn zones(
    scene: &Scene,
    mesh: &TetMesh,
    selections: &Selections,
    bodies: &SceneBodies,
) -> Result<Zones, SceneError> {
    let global = || {
        Zones::from_sets(
            bodies
                .parts
                .iter()
                .filter(|p| !p.elements.is_empty())
                .map(|p| p.elements.clone().collect())
                .collect(),
        )
    };
    let Some(spec) = &scene.zones else {
        return Ok(global());
    };
    Ok(match spec.kind {
        ZoneKind::Global => global(),
        ZoneKind::None => Zones::from_sets(Vec::new()),
        ZoneKind::KRing => Zones::k_ring_cover(mesh, spec.k.unwrap_or(1))?,
        ZoneKind::Painted => {
            let mut labels = vec![Vec::new(); mesh.num_vertices()];
            for (zone, name) in spec.paint.iter().enumerate() {
                for &v in selections.vertices(name)? {
                    labels[v].push(zone);
                }
            }
            Zones::painted(mesh, &labels)?
        }
    })
}
